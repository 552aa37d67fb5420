//! The rotation of a camera placed by a matrix, snapped to an exact rotation.
//!
//! A camera matrix must be rigid, but exporters and people print rotations rounded to a few
//! digits (`0.707`, `0.7071`), and mental ray and RenderMan render them. A 3×3 part `R`
//! whose Gram matrix `RᵀR` is within [`RIGID_TOLERANCE`] of the identity (every entry) and
//! whose determinant is positive is taken as the rotation it is nearest to: its polar factor
//! (the orthonormal `Q` of `R = Q·P`, `P` symmetric positive), which does not depend on the
//! order of the axes. Anything further from a rotation — a shear, a non-uniform scale, a
//! mirror — is refused by the caller. The camera's uniform scale ([`uniform_scale`]) is a
//! reader's business (RIB and `.mi` drop it into the camera's `space_scale`).
//!
//! Shared by validation (every format's `Matrix` placement) and the RIB and `.mi` readers
//! (which locate the request or `transform` that made the camera transformation non-rigid).

use glam::{DMat3, DMat4, DVec4};

/// The largest distance of an entry of `RᵀR` from the identity's that is still rounding.
///
/// Rounding every entry of a rotation to 3 decimals (an error of at most 5e-4 each) moves an
/// entry of `RᵀR` by at most `2·√3·5e-4 ≈ 1.8e-3` (`0.707` for `√½`: 3.0e-4), 2 decimals
/// (`0.71`) by 8.2e-3 for `√½`; 1e-2 accepts both. What it refuses changes a length by more
/// than 0.5 % or a right angle by more than about 0.6°: a shear or non-uniform scale meant
/// as one, not a rounding.
pub const RIGID_TOLERANCE: f64 = 1e-2;

/// Newton steps of the polar decomposition at most (each squares the distance from a
/// rotation: a matrix within the tolerance needs 4).
const POLAR_STEPS: usize = 20;

/// The rotation `r` is a rounding of, exactly orthonormal with determinant 1; `None` when
/// `r` is not within [`RIGID_TOLERANCE`] of a rotation (shear, scale, mirror, not finite).
pub fn snapped_rotation(r: DMat3) -> Option<DMat3> {
    if !r.is_finite() || r.determinant() <= 0.0 || !near_orthonormal(r) {
        return None;
    }
    // Newton's iteration for the polar factor: Q ← (Q + Q⁻ᵀ) / 2.
    let mut q = r;
    for _ in 0..POLAR_STEPS {
        let next = (q + q.inverse().transpose()) * 0.5;
        let change = (next - q)
            .to_cols_array()
            .iter()
            .fold(0.0f64, |m, e| m.max(e.abs()));
        q = next;
        if change <= 1e-15 {
            break;
        }
    }
    Some(q)
}

/// The uniform scale of the 3×3 part `l` — the cube root of its determinant's size — or 1
/// when `l` is a rotation or mirror within [`RIGID_TOLERANCE`] (the scale a rounding leaves
/// is no scale), or when it is degenerate.
pub fn uniform_scale(l: DMat3) -> f64 {
    let s = l.determinant().abs().cbrt();
    if !(s > 0.0 && s.is_finite()) || near_orthonormal(l) {
        1.0
    } else {
        s
    }
}

/// The camera transformation `camera_from_world` as a file writes it (RIB's at
/// `WorldBegin`, a `.mi` camera instance's `transform`), its rotation snapped
/// ([`snapped_rotation`]) with its uniform scale, mirror and translation kept: the world
/// origin stays where the file puts it in camera space. Unchanged when it is not a rotation
/// times a uniform scale within the tolerance (validation refuses it) or not affine.
pub fn snapped_camera_from_world(m: DMat4) -> DMat4 {
    let l = DMat3::from_mat4(m);
    let s = uniform_scale(l) * l.determinant().signum();
    let affine = m.row(3) == DVec4::W;
    match snapped_rotation(l * (1.0 / s)) {
        Some(q) if affine => {
            let k = q * s;
            DMat4::from_cols(
                k.x_axis.extend(0.0),
                k.y_axis.extend(0.0),
                k.z_axis.extend(0.0),
                m.w_axis,
            )
        }
        _ => m,
    }
}

/// Whether `l` is a rotation or a mirror times a uniform scale, within the tolerance (a
/// camera transformation the readers can place; a mirror is the reader's to undo or refuse).
pub fn near_similarity(l: DMat3) -> bool {
    let r = l * (1.0 / uniform_scale(l));
    r.is_finite() && near_orthonormal(r)
}

/// Whether every entry of `rᵀr` is within [`RIGID_TOLERANCE`] of the identity's.
fn near_orthonormal(r: DMat3) -> bool {
    let off = (r.transpose() * r - DMat3::IDENTITY).to_cols_array();
    off.iter().all(|e| e.abs() <= RIGID_TOLERANCE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A turn by 45° about y written with `c` for √½.
    fn turn(c: f64) -> DMat3 {
        DMat3::from_cols(
            DVec3::new(c, 0.0, -c),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(c, 0.0, c),
        )
    }

    #[test]
    // The values are 1/√2 as files round it, on purpose.
    #[allow(clippy::approx_constant)]
    fn rounded_rotations_snap_to_the_exact_one() {
        let exact = DMat3::from_rotation_y(std::f64::consts::FRAC_PI_4);
        for c in [0.71, 0.707, 0.7071, 0.70710678] {
            let q = snapped_rotation(turn(c)).unwrap();
            assert!(q.abs_diff_eq(exact, 1e-15), "{c}: {q}");
            assert!((q.determinant() - 1.0).abs() < 1e-15);
        }
        // An exact rotation is kept (to the last bits).
        assert!(snapped_rotation(exact).unwrap().abs_diff_eq(exact, 1e-16));
        assert_eq!(snapped_rotation(DMat3::IDENTITY), Some(DMat3::IDENTITY));
    }

    #[test]
    fn a_camera_transformation_keeps_its_scale_mirror_and_translation() {
        let exact = DMat3::from_rotation_y(std::f64::consts::FRAC_PI_4);
        let t = DVec4::new(1.0, 2.0, -5.0, 1.0);
        for (k, mirror) in [(1.0, 1.0), (0.5, 1.0), (2.0, -1.0)] {
            let rounded = turn(0.707) * k * mirror;
            let m = DMat4::from_cols(
                rounded.x_axis.extend(0.0),
                rounded.y_axis.extend(0.0),
                rounded.z_axis.extend(0.0),
                t,
            );
            let snapped = snapped_camera_from_world(m);
            // The scale is the determinant's cube root, which the rounding moves (by 1e-4 of it).
            let kept = DMat3::from_mat4(snapped);
            let s = kept.determinant().abs().cbrt();
            assert!((s - k).abs() <= 2e-4 * k, "{s}");
            assert!((kept * (mirror / s)).abs_diff_eq(exact, 1e-14), "{kept}");
            assert_eq!(snapped.w_axis, t);
            assert_eq!(snapped.row(3), DVec4::W);
        }
        let shear = DMat4::from_cols(DVec4::X, DVec4::new(0.1, 1.0, 0.0, 0.0), DVec4::Z, t);
        assert_eq!(snapped_camera_from_world(shear), shear);
    }

    #[test]
    fn shear_scale_and_mirrors_are_no_rotation() {
        let shear = DMat3::from_cols(DVec3::X, DVec3::new(0.1, 1.0, 0.0), DVec3::Z);
        let stretch = DMat3::from_diagonal(DVec3::new(1.0, 1.02, 1.0));
        let mirror = DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0));
        for m in [shear, stretch, mirror, DMat3::IDENTITY * 2.0, DMat3::ZERO] {
            assert_eq!(snapped_rotation(m), None, "{m}");
        }
        let nan = DMat3::from_diagonal(DVec3::new(f64::NAN, 1.0, 1.0));
        assert_eq!(snapped_rotation(nan), None);
    }

    #[test]
    fn the_uniform_scale_of_a_rounding_is_one() {
        assert_eq!(uniform_scale(turn(0.707)), 1.0);
        assert_eq!(uniform_scale(DMat3::IDENTITY * 0.5), 0.5);
        assert!((uniform_scale(turn(0.707) * 2.0) - 2.0 * 0.999698f64.cbrt()).abs() < 1e-12);
        assert_eq!(uniform_scale(DMat3::ZERO), 1.0);
        assert!(near_similarity(turn(0.707) * 3.0));
        assert!(near_similarity(DMat3::from_diagonal(DVec3::new(
            2.0, 2.0, -2.0
        ))));
        assert!(!near_similarity(DMat3::from_diagonal(DVec3::new(
            1.0, 2.0, 1.0
        ))));
    }
}
