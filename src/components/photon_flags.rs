//! Photon caster/receiver flags of a placed instance (mental ray `caustic 0|1|2|3` and
//! `globillum 0|1|2|3` on objects and instances), and a light's photon controls (mental ray
//! `energy`, `caustic photons`, `globillum photons`).

use glam::Vec3;

/// The role of a surface for one photon map: a bit set, `1` casts (photons scatter off it
/// and go on), `2` receives (photons are stored on it). mental ray's values: `0` none,
/// `1` casts, `2` receives, `3` both.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PhotonRole(pub u8);

impl PhotonRole {
    /// Neither casts nor receives (`0`).
    pub const NONE: Self = Self(0);
    /// Casts only (`1`).
    pub const CASTS: Self = Self(1);
    /// Receives only (`2`).
    pub const RECEIVES: Self = Self(2);
    /// Casts and receives (`3`).
    pub const BOTH: Self = Self(3);

    /// Whether photons scatter off the surface and go on.
    pub fn casts(self) -> bool {
        self.0 & 1 != 0
    }

    /// Whether photons are stored on the surface.
    pub fn receives(self) -> bool {
        self.0 & 2 != 0
    }
}

/// The explicit photon flags of a placed instance, resolved along its DAG path (the closest
/// instance that sets a flag wins, then the object's own). `None`: the documented default
/// from the material (see `docs/scene-format.md`, "Photon flags"). Only instances with at
/// least one explicit flag carry this component.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct PhotonFlags {
    /// Role for the caustic map.
    pub caustic: Option<PhotonRole>,
    /// Role for the global-illumination map.
    pub globillum: Option<PhotonRole>,
}

impl PhotonFlags {
    /// Whether neither flag is set.
    pub fn is_default(&self) -> bool {
        self.caustic.is_none() && self.globillum.is_none()
    }

    /// `self`'s flags where set, `outer`'s elsewhere.
    pub fn or(self, outer: Self) -> Self {
        Self {
            caustic: self.caustic.or(outer.caustic),
            globillum: self.globillum.or(outer.globillum),
        }
    }
}

/// A light's photon controls; lights without them emit their physical power, sharing each
/// map's `photons` with the other lights by power. Only lights with a control carry this.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LightPhotons {
    /// Power the light's photons carry, W per channel, instead of its physical power
    /// (mental ray `energy`); zero: the light emits no photons.
    pub energy: Option<Vec3>,
    /// Photons this light emits for the caustic map (mental ray `caustic photons`).
    pub caustic_photons: Option<u32>,
    /// Photons this light emits for the global map (mental ray `globillum photons`).
    pub globillum_photons: Option<u32>,
}

impl LightPhotons {
    /// Whether no control is set.
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mental_ray_values_are_bits_and_the_inner_flag_wins() {
        let roles = [0u8, 1, 2, 3].map(|v| (PhotonRole(v).casts(), PhotonRole(v).receives()));
        assert_eq!(
            roles,
            [(false, false), (true, false), (false, true), (true, true)]
        );
        let inner = PhotonFlags {
            caustic: Some(PhotonRole::NONE),
            globillum: None,
        };
        let outer = PhotonFlags {
            caustic: Some(PhotonRole::BOTH),
            globillum: Some(PhotonRole::RECEIVES),
        };
        let got = inner.or(outer);
        assert_eq!(got.caustic, Some(PhotonRole::NONE));
        assert_eq!(got.globillum, Some(PhotonRole::RECEIVES));
        assert!(PhotonFlags::default().is_default());
    }
}
