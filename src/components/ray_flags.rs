//! Ray visibility flags of a placed instance (mental ray `visible`, `shadow`, `trace` on
//! objects and instances): which kinds of rays see its surfaces.

/// Bit of [`RayFlags::mask`] for camera (primary) rays.
pub const CAMERA_RAYS: u8 = 1;
/// Bit of [`RayFlags::mask`] for shadow rays.
pub const SHADOW_RAYS: u8 = 2;
/// Bit of [`RayFlags::mask`] for secondary rays (reflection, refraction, gathering).
pub const SECONDARY_RAYS: u8 = 4;
/// Every bit: seen by every kind of ray (the default).
pub const ALL_RAYS: u8 = CAMERA_RAYS | SHADOW_RAYS | SECONDARY_RAYS;
/// Bit of a triangle's ray mask (beside the kinds of [`RayFlags::mask`], never in it): no
/// ray sees the triangle's back face (`face: Cull` on a one-sided material), rays go on
/// through it.
pub const FRONT_ONLY: u8 = 8;

/// The explicit ray flags of a placed instance, resolved along its DAG path like the photon
/// flags (the closest instance that sets a flag wins, then the object's own). `None`: on.
/// Only instances with at least one explicit flag carry this component.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct RayFlags {
    /// Seen by camera rays (mental ray `visible`).
    pub visible: Option<bool>,
    /// Casts shadows: blocks shadow rays (mental ray `shadow`).
    pub shadow: Option<bool>,
    /// Seen by secondary rays: reflections, refractions, final gathering (mental ray
    /// `trace`).
    pub trace: Option<bool>,
}

impl RayFlags {
    /// Whether no flag is set.
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// `self`'s flags where set, `outer`'s elsewhere.
    pub fn or(self, outer: Self) -> Self {
        Self {
            visible: self.visible.or(outer.visible),
            shadow: self.shadow.or(outer.shadow),
            trace: self.trace.or(outer.trace),
        }
    }

    /// The ray kinds that see the surface, as [`CAMERA_RAYS`] | [`SHADOW_RAYS`] |
    /// [`SECONDARY_RAYS`] bits (unset flags are on).
    pub fn mask(self) -> u8 {
        let bit = |flag: Option<bool>, bit: u8| if flag.unwrap_or(true) { bit } else { 0 };
        bit(self.visible, CAMERA_RAYS)
            | bit(self.shadow, SHADOW_RAYS)
            | bit(self.trace, SECONDARY_RAYS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unset_flags_are_on_and_the_inner_flag_wins() {
        assert_eq!(RayFlags::default().mask(), ALL_RAYS);
        let inner = RayFlags {
            visible: Some(false),
            ..RayFlags::default()
        };
        let outer = RayFlags {
            visible: Some(true),
            shadow: Some(false),
            trace: None,
        };
        let got = inner.or(outer);
        assert_eq!(got.mask(), SECONDARY_RAYS);
        assert!(!got.is_default() && RayFlags::default().is_default());
    }
}
