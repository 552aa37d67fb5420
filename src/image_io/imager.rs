//! Applying a camera's imager ([`Imager`]: background, exposure gain, tone map, display
//! gamma) to scene-linear radiance on its way into an 8-bit output.

use glam::Vec3;

use super::srgb;
use crate::components::{Imager, ToneMap};

impl Imager {
    /// The display value in [0, 1] of one linear channel `c` (after background compositing).
    pub fn encode(&self, c: f32) -> f32 {
        let mut v = c * self.gain;
        if v.is_nan() || v <= 0.0 {
            return 0.0;
        }
        if self.tone_map == ToneMap::Reinhard {
            v /= 1.0 + v;
        }
        match self.gamma {
            None => srgb::encode(v),
            Some(g) => v.min(1.0).powf(1.0 / g),
        }
    }

    /// Composites the background behind a pixel of coverage `alpha`: colour and new alpha.
    /// `c` is the pixel's surfaces' share: the background replaces the environment, which
    /// camera rays then do not see (`encode_png` leaves any environment share out first).
    pub fn composite(&self, c: Vec3, alpha: f32) -> (Vec3, f32) {
        match self.background {
            Some(b) => (c + b * (1.0 - alpha.clamp(0.0, 1.0)), 1.0),
            None => (c, alpha),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renderman_exposure_is_gain_then_gamma() {
        let i = Imager {
            gain: 2.0,
            gamma: Some(2.2),
            ..Imager::default()
        };
        assert!((i.encode(0.1) - 0.2f32.powf(1.0 / 2.2)).abs() < 1e-6);
        assert_eq!(i.encode(-1.0), 0.0);
        assert_eq!(i.encode(f32::NAN), 0.0);
        assert_eq!(i.encode(10.0), 1.0);
    }

    #[test]
    fn reinhard_compresses_highlights_below_one() {
        let i = Imager {
            tone_map: ToneMap::Reinhard,
            gamma: Some(1.0),
            ..Imager::default()
        };
        assert!((i.encode(1.0) - 0.5).abs() < 1e-6);
        assert!(i.encode(1e6) < 1.0);
    }

    #[test]
    fn background_fills_uncovered_part_and_makes_opaque() {
        let i = Imager {
            background: Some(Vec3::new(1.0, 0.0, 0.0)),
            ..Imager::default()
        };
        let (c, a) = i.composite(Vec3::splat(0.2), 0.25);
        assert_eq!(a, 1.0);
        assert!((c - Vec3::new(0.95, 0.2, 0.2)).length() < 1e-6);
    }
}
