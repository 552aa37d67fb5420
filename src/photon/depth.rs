//! The photon trace depth along one photon's path (mental ray `photon trace depth r t s`):
//! reflections, transmissions and their sum counted at each scattering, the path ended at
//! the first event past a limit of [`PhotonDepth`].

use crate::settings::PhotonDepth;

/// Scattering events of one photon so far, against the limits.
#[derive(Debug, Clone, Copy)]
pub struct PathDepth {
    limits: PhotonDepth,
    reflections: u32,
    refractions: u32,
}

impl PathDepth {
    /// A photon leaving its light.
    pub fn new(limits: PhotonDepth) -> Self {
        Self {
            limits,
            reflections: 0,
            refractions: 0,
        }
    }

    /// Counts one more scattering (`transmission`: a refraction or pass-through, otherwise a
    /// reflection); `false` when it goes past a limit (the photon must stop there).
    pub fn scatter(&mut self, transmission: bool) -> bool {
        if transmission {
            self.refractions += 1;
        } else {
            self.reflections += 1;
        }
        self.reflections <= self.limits.reflection
            && self.refractions <= self.limits.refraction
            && self.reflections + self.refractions <= self.limits.sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn allowed(limits: PhotonDepth, events: &[bool]) -> usize {
        let mut d = PathDepth::new(limits);
        events.iter().take_while(|&&t| d.scatter(t)).count()
    }

    #[test]
    fn each_limit_stops_the_path_at_the_first_event_past_it() {
        let (r, t) = (false, true);
        let limits = |reflection, refraction, sum| PhotonDepth {
            reflection,
            refraction,
            sum,
        };
        // Two refractions through a glass ball, then a reflection.
        let ball = [t, t, r, r];
        assert_eq!(allowed(limits(4, 1, 8), &ball), 1);
        assert_eq!(allowed(limits(4, 2, 8), &ball), 4);
        assert_eq!(allowed(limits(1, 2, 8), &ball), 3);
        assert_eq!(allowed(limits(4, 4, 2), &ball), 2);
        assert_eq!(allowed(limits(0, 0, 0), &ball), 0);
        assert_eq!(allowed(PhotonDepth::UNLIMITED, &[r; 64]), 64);
    }
}
