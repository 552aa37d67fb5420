//! Volume shaders: homogeneous participating media (fog) filling the space around the camera
//! (`Atmosphere`, on the camera entity) or the inside of a closed mesh (`Interior`, on a
//! material entity).

use glam::Vec3;

/// A homogeneous medium: absorption and scattering coefficients per unit length (1/m, per
/// RGB channel) and a Henyey–Greenstein phase function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fog {
    /// Absorption coefficient σa, 1/m.
    pub sigma_a: Vec3,
    /// Scattering coefficient σs, 1/m.
    pub sigma_s: Vec3,
    /// Henyey–Greenstein asymmetry in (−1, 1): 0 isotropic, > 0 forward scattering.
    pub g: f32,
}

impl Fog {
    /// Extinction coefficient σt = σa + σs, 1/m.
    pub fn sigma_t(&self) -> Vec3 {
        self.sigma_a + self.sigma_s
    }

    /// Transmittance `e^(−σt·d)` over a distance `d` (metres).
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
