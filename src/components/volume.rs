//! Volume shaders: participating media (fog, homogeneous or with a height bound and a
//! noise-modulated density) filling the space around the camera (`Atmosphere`, on the camera
//! entity) or the inside of a closed mesh (`Interior`, on a material entity), and the
//! camera's linear colour fade (`AtmosphereFade`, mental ray's `mib_volume`).

use glam::Vec3;

/// A medium: absorption and scattering coefficients per unit length (1/m, per RGB channel)
/// scaled by a density (1 everywhere unless `height` or `density` say otherwise) and a
/// Henyey–Greenstein phase function.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fog {
    /// Absorption coefficient σa, 1/m.
    pub sigma_a: Vec3,
    /// Scattering coefficient σs, 1/m.
    pub sigma_s: Vec3,
    /// Henyey–Greenstein asymmetry in (−1, 1): 0 isotropic, > 0 forward scattering.
    pub g: f32,
    /// Fog only where world y is below this height (density 0 above); `None`: everywhere.
    pub height: Option<f32>,
    /// Density varied by a 3D noise; `None`: uniform (density 1).
    pub density: Option<DensityNoise>,
}

/// A density `1 + amount·n(p / scale)` with `n` a deterministic gradient noise clamped to
/// [−1, 1] (`shading::medium`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DensityNoise {
    /// How far the density varies about 1, in (0, 1].
    pub amount: f32,
    /// Feature size of the noise, scene units (> 0).
    pub scale: f32,
}

impl Fog {
    /// Whether the density is 1 everywhere (closed-form transmittance `e^(−σt·d)`).
    pub fn is_homogeneous(&self) -> bool {
        self.height.is_none() && self.density.is_none()
    }

    /// Extinction coefficient σt = σa + σs, 1/m.
    pub fn sigma_t(&self) -> Vec3 {
        self.sigma_a + self.sigma_s
    }

    /// Transmittance `e^(−σt·d)` over a distance `d` (metres) of density 1.
    pub fn transmittance(&self, d: f32) -> Vec3 {
        let t = self.sigma_t() * d.max(0.0);
        Vec3::new((-t.x).exp(), (-t.y).exp(), (-t.z).exp())
    }
}

/// The camera's atmosphere: the medium every finite ray segment outside fog-filled objects
/// crosses (mental ray's camera volume shader).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere(pub Fog);

/// The medium inside the closed surfaces of a material (mental ray's material volume
/// shader): it fills every segment that ends on the back face of the material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interior(pub Fog);

/// A colour fade as the camera's atmosphere (mental ray's `mib_volume`, RenderMan's `fog`):
/// every finite camera-side segment of length `d` blends the radiance toward `color` by
/// `f = opacity · min(d / max, 1)` (linear) or `f = opacity · (1 − e^(−d / max))`
/// (exponential), `f = opacity` when `max` is 0: `L' = (1 − f)·L + f·color`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fade {
    /// The colour the radiance fades to.
    pub color: Vec3,
    /// Largest blend weight, in [0, 1] (`color`'s alpha in `.mi`).
    pub opacity: f32,
    /// Distance at which the linear fade is complete, or over which the exponential one
    /// leaves 1/e of the radiance; scene units (≥ 0).
    pub max: f32,
    /// How the weight grows with distance.
    pub falloff: Falloff,
}

/// How a [`Fade`]'s weight grows with distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Falloff {
    /// `min(d / max, 1)`.
    Linear,
    /// `1 − e^(−d / max)`.
    Exponential,
}

impl Fade {
    /// The blend weight toward `color` over a distance `d`.
    pub fn weight(&self, d: f32) -> f32 {
        let ramp = if self.max > 0.0 {
            match self.falloff {
                Falloff::Linear => (d / self.max).clamp(0.0, 1.0),
                Falloff::Exponential => -(-(d / self.max).max(0.0)).exp_m1(),
            }
        } else {
            1.0
        };
        self.opacity * ramp
    }
}

/// The camera's fade atmosphere (instead of a fog [`Atmosphere`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtmosphereFade(pub Fade);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exponential_fade_leaves_half_at_max_ln_2() {
        let fade = |falloff| Fade {
            color: Vec3::ONE,
            opacity: 0.8,
            max: 2.0,
            falloff,
        };
        let half = 2.0 * std::f32::consts::LN_2;
        assert!((fade(Falloff::Exponential).weight(half) - 0.4).abs() < 1e-6);
        assert_eq!(fade(Falloff::Exponential).weight(0.0), 0.0);
        assert!((fade(Falloff::Linear).weight(1.0) - 0.4).abs() < 1e-6);
        assert!((fade(Falloff::Linear).weight(5.0) - 0.8).abs() < 1e-6);
    }
}
