//! Tangent-space normal maps (glTF's `normalTexture`, `bump: (normal_map: …)`): the shading
//! normal read from a texel in the frame (tangent, bitangent, normal) of the surface.
//!
//! **Tangents** of a mesh that has them (glTF `TANGENT`) are used as written: `T` the
//! interpolated tangent made orthogonal to `N`, `B = w · N × T` ([`frame_from_tangent`]).
//! Otherwise they are generated: the tangent `T` is the triangle's
//! `∂P/∂u` (from its positions and uvs, [`super::bump::tangents`]) made orthogonal to the
//! interpolated normal `N`, and the bitangent `B = ±N × T`, the sign chosen so that `B`
//! points along `∂P/∂v` (`v` upwards in the image, stagelight's convention). For a uv layout
//! that is not mirrored this is the glTF sample viewer's frame (`T = ∂P/∂u`, `B = N × T`
//! with glTF's `v` flipped), so the image's green channel tilts the normal toward the top
//! of the image, glTF's "+Y up" (the OpenGL convention); a mirrored layout flips `B` like
//! MikkTSpace's handedness sign does. Tangents are per triangle (constant across it), not
//! MikkTSpace's per-vertex averages: on curved, smoothly unwrapped meshes the two differ
//! slightly where a map was baked against MikkTSpace tangents.

use glam::Vec3;

/// The normal `(2c − 1)·(scale, scale, 1)` of the texel `c`, in the frame `t`, `b`, `n`
/// (unit vectors), normalised; `n` itself when the result is degenerate or lies below the
/// surface (a texel that tilts the normal past the tangent plane).
pub fn perturb(n: Vec3, t: Vec3, b: Vec3, texel: Vec3, scale: f32) -> Vec3 {
    let c = texel * 2.0 - Vec3::ONE;
    let m = (t * (c.x * scale) + b * (c.y * scale) + n * c.z).normalize_or_zero();
    if m == Vec3::ZERO || !m.is_finite() || m.dot(n) <= 0.0 {
        n
    } else {
        m
    }
}

/// The frame `(T, B)` around the unit normal `n` from the surface's `∂P/∂u`, `∂P/∂v`
/// (world space): `T` is `∂P/∂u` made orthogonal to `n`, `B = ±n × T` on the side of
/// `∂P/∂v`. `None` when `∂P/∂u` is (nearly) parallel to `n`.
pub fn frame(n: Vec3, dpdu: Vec3, dpdv: Vec3) -> Option<(Vec3, Vec3)> {
    let t = (dpdu - n * n.dot(dpdu)).normalize_or_zero();
    if t == Vec3::ZERO || !t.is_finite() {
        return None;
    }
    let b = n.cross(t);
    let b = if b.dot(dpdv) < 0.0 { -b } else { b };
    Some((t, b))
}

/// The frame `(T, B)` around the unit normal `n` from a given tangent `t` (world space) and
/// handedness `sign`: `T` is `t` made orthogonal to `n`, `B = ±n × T` with the sign of
/// `sign` (glTF's `w`, times −1 under a mirroring transform). `None` when `t` is (nearly)
/// parallel to `n`.
pub fn frame_from_tangent(n: Vec3, t: Vec3, sign: f32) -> Option<(Vec3, Vec3)> {
    let t = (t - n * n.dot(t)).normalize_or_zero();
    if t == Vec3::ZERO || !t.is_finite() {
        return None;
    }
    let b = n.cross(t);
    Some((t, if sign < 0.0 { -b } else { b }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flat_texel_keeps_the_normal() {
        let flat = Vec3::new(0.5, 0.5, 1.0);
        let m = perturb(Vec3::Z, Vec3::X, Vec3::Y, flat, 1.0);
        assert!((m - Vec3::Z).length() < 1e-6, "{m}");
    }

    #[test]
    fn red_tilts_along_the_tangent_green_along_the_bitangent() {
        // c = (0.75, 0.5, 1): (0.5, 0, 1) → tilt of atan(0.5) toward +T.
        let m = perturb(Vec3::Z, Vec3::X, Vec3::Y, Vec3::new(0.75, 0.5, 1.0), 1.0);
        assert!(
            (m - Vec3::new(0.5, 0.0, 1.0).normalize()).length() < 1e-6,
            "{m}"
        );
        let m = perturb(Vec3::Z, Vec3::X, Vec3::Y, Vec3::new(0.5, 0.75, 1.0), 2.0);
        assert!(
            (m - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6,
            "{m}"
        );
        // A texel below the tangent plane keeps the normal.
        let m = perturb(Vec3::Z, Vec3::X, Vec3::Y, Vec3::new(1.0, 0.5, 0.0), 1.0);
        assert_eq!(m, Vec3::Z);
    }

    #[test]
    fn a_given_tangent_is_kept_and_its_sign_flips_the_bitangent() {
        let (t, b) = frame_from_tangent(Vec3::Z, Vec3::new(0.0, 2.0, 0.5), 1.0).unwrap();
        assert!((t - Vec3::Y).length() < 1e-6 && (b + Vec3::X).length() < 1e-6);
        let (_, b) = frame_from_tangent(Vec3::Z, Vec3::Y, -1.0).unwrap();
        assert!((b - Vec3::X).length() < 1e-6);
        assert!(frame_from_tangent(Vec3::Z, Vec3::Z, 1.0).is_none());
    }

    #[test]
    fn the_bitangent_follows_v_and_flips_with_a_mirrored_layout() {
        let (t, b) = frame(Vec3::Z, Vec3::new(2.0, 0.0, 0.3), Vec3::Y).unwrap();
        assert!((t - Vec3::X).length() < 1e-6 && (b - Vec3::Y).length() < 1e-6);
        let (_, b) = frame(Vec3::Z, Vec3::X, -Vec3::Y).unwrap();
        assert!((b + Vec3::Y).length() < 1e-6);
        assert!(frame(Vec3::Z, Vec3::Z, Vec3::Y).is_none());
    }
}
