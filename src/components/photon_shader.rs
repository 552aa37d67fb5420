//! A material's photon shader (mental ray's material `photon` shader, in the form AIR's
//! caustic attributes give it): what photons do at a surface instead of what its surface
//! shader implies.

use glam::Vec3;

/// AIR's caustic model of a surface (`Attribute "caustic" "specularcolor"`,
/// `"refractioncolor"`, `"refractionindex"`): a photon is reflected as by a perfect mirror
/// with `specular`, refracted with `refraction` by a smooth interface of index `ior`, and
/// the rest is absorbed. Where the two average intensities add up to less than 1 the surface
/// also stores the photon (when it receives for the map), and a `Local` model reads the stored
/// caustic light as AIR's `caustic` light source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonShader {
    /// Reflected fraction per channel, each in \[0, 1\].
    pub specular: Vec3,
    /// Refracted fraction per channel, each in \[0, 1\].
    pub refraction: Vec3,
    /// Index of refraction behind the surface over the one in front, > 0.
    pub ior: f32,
}

impl PhotonShader {
    /// Average intensity of a colour (AIR's probability of the event it weighs).
    fn average(c: Vec3) -> f32 {
        (c.x + c.y + c.z) / 3.0
    }

    /// Whether a photon arriving here is stored (AIR: the average intensities of
    /// `specular` and `refraction` add up to less than 1).
    pub fn stores(&self) -> bool {
        Self::average(self.specular) + Self::average(self.refraction) < 1.0
    }

    /// Whether photons go on from here (reflected or refracted): the surface casts caustics.
    pub fn scatters(&self) -> bool {
        self.specular.max_element() > 0.0 || self.refraction.max_element() > 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn air_stores_below_a_sum_of_one_and_scatters_with_any_colour() {
        let p = |s: f32, r: f32| PhotonShader {
            specular: Vec3::splat(s),
            refraction: Vec3::splat(r),
            ior: 1.0,
        };
        assert!(p(0.4, 0.0).stores() && p(0.4, 0.0).scatters());
        assert!(p(0.0, 0.0).stores() && !p(0.0, 0.0).scatters());
        assert!(!p(0.5, 0.5).stores() && !p(1.0, 0.0).stores());
        assert!(p(0.0, 0.3).scatters());
    }
}
