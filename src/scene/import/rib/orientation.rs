//! The current orientation (RISpec 3.2, "Orientation and Sides"): `Orientation` and
//! `ReverseOrientation`, and which primitives they turn inside out.
//!
//! RISpec keeps the current orientation (left- or right-handed) as an attribute beside the
//! handedness of the current coordinate system; camera space is left-handed and so is the
//! initial orientation (`"outside"`). The orientation "always flips whenever the orientation
//! of the current coordinate system flips", so a mirroring transformation does not turn a
//! primitive inside out; a primitive is inside out exactly when the two differ. The reader
//! therefore keeps that difference ([`super::state::Attributes::inside_out`]), which no
//! transformation changes: `Orientation "outside"` clears it, `"inside"` sets it, `"lh"` and
//! `"rh"` compare with the handedness of the current coordinate system (relative to camera
//! space), `ReverseOrientation` toggles it. An inside-out primitive becomes an object with
//! `reverse_orientation` (its front is its object-space back); every other keeps the
//! object-space front, which is RenderMan's outside for each primitive the reader makes
//! (quadrics face out, polygons toward a viewer who sees their vertices clockwise in a
//! left-handed frame, patches and subdivision meshes along `∂P/∂u × ∂P/∂v`).

use glam::DMat4;

use super::super::located::{Pos, Problem};

/// Whether the coordinate system that `camera_from_current` maps into (left-handed) camera
/// space is right-handed: the map mirrors.
pub fn right_handed(camera_from_current: DMat4) -> bool {
    camera_from_current.determinant() < 0.0
}

/// Whether primitives are inside out after `Orientation token` (written at `pos`) in a
/// coordinate system that is `right_handed` or not; an unknown token is a located error.
pub fn inside_out(token: &str, right_handed: bool, pos: Pos) -> Result<bool, Problem> {
    match token {
        "outside" => Ok(false),
        "inside" => Ok(true),
        // Left-handed orientation in a right-handed coordinate system, and the reverse.
        "lh" => Ok(right_handed),
        "rh" => Ok(!right_handed),
        other => Err(
            Problem::error(pos, format!("unknown orientation \"{other}\""))
                .with_help("expected \"outside\", \"inside\", \"lh\" or \"rh\""),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn handedness_is_relative_to_camera_space() {
        assert!(!right_handed(DMat4::IDENTITY));
        let mirror = DMat4::from_scale(DVec3::new(1.0, 1.0, -1.0));
        assert!(right_handed(mirror));
        assert!(!right_handed(mirror * mirror));
    }

    #[test]
    fn tokens_compare_with_the_coordinate_system() {
        let p = Pos {
            line: 2,
            column: 13,
        };
        for rh in [false, true] {
            assert!(!inside_out("outside", rh, p).unwrap());
            assert!(inside_out("inside", rh, p).unwrap());
        }
        assert!(!inside_out("lh", false, p).unwrap());
        assert!(inside_out("lh", true, p).unwrap());
        assert!(inside_out("rh", false, p).unwrap());
        assert!(!inside_out("rh", true, p).unwrap());
        let e = inside_out("Outside", false, p).unwrap_err();
        assert_eq!(e.message, "unknown orientation \"Outside\"");
        assert_eq!(
            e.help.as_deref(),
            Some("expected \"outside\", \"inside\", \"lh\" or \"rh\"")
        );
    }
}
