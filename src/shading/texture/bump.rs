//! Bump mapping and the shading-normal safeguards that keep bent normals from painting
//! black spots (hard case H11) or leaking light (H12).
//!
//! * [`perturb`]: the bumped normal of the surface `P + h·N` from the height's derivatives
//!   along the surface tangents `∂P/∂u`, `∂P/∂v` (Blinn 1978; pbrt's `BumpMap` without the
//!   `h·∂N/∂u` term).
//! * [`ensure_valid_reflection`]: Cycles' `ensure_valid_specular_reflection` — rotates a
//!   shading normal toward the geometric normal just enough that the mirror direction of the
//!   view lies at least `min(0.9·cosθ, 0.01)` above the geometric surface. Afterwards the view
//!   direction is always above the shading normal, so no lobe returns black for it.
//! * [`shadowing`]: the microfacet bump shadowing term of Conty Estevez et al. (Ray Tracing
//!   Gems ch. 12), which fades light that the bumped normal faces but the geometry barely
//!   does (the bump terminator).
//!
//! Which side a direction lies on (reflection or transmission) is always decided by the
//! geometric normal, never by the shading normal (see `integrator::Vertex::spawn` and the
//! light loop).

use glam::{Vec2, Vec3};

/// `∂P/∂u`, `∂P/∂v` of the triangle `p` with texture coordinates `uv` (pbrt's triangle
/// derivatives); `None` when the uv mapping is degenerate.
pub fn tangents(p: [Vec3; 3], uv: [Vec2; 3]) -> Option<(Vec3, Vec3)> {
    let (duv02, duv12) = (uv[0] - uv[2], uv[1] - uv[2]);
    let (dp02, dp12) = (p[0] - p[2], p[1] - p[2]);
    let det = duv02.x * duv12.y - duv02.y * duv12.x;
    if det.is_nan() || det.abs() <= 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let dpdu = (dp02 * duv12.y - dp12 * duv02.y) * inv;
    let dpdv = (dp12 * duv02.x - dp02 * duv12.x) * inv;
    (dpdu.is_finite() && dpdv.is_finite() && dpdu.cross(dpdv).length_squared() > 0.0)
        .then_some((dpdu, dpdv))
}

/// The normal of the bumped surface `P + h·n`, given `∂h/∂u`, `∂h/∂v` along the tangents
/// `dpdu`, `dpdv` of the unit normal `n`; on the side of `n`. Falls back to `n` when the
/// result is not finite.
pub fn perturb(n: Vec3, dpdu: Vec3, dpdv: Vec3, dhdu: f32, dhdv: f32) -> Vec3 {
    let du = dpdu + n * dhdu;
    let dv = dpdv + n * dhdv;
    let mut b = du.cross(dv);
    // Keep the sense of the bump when the uv mapping is mirrored.
    if dpdu.cross(dpdv).dot(n) < 0.0 {
        b = -b;
    }
    let b = b.normalize_or_zero();
    if b == Vec3::ZERO || !b.is_finite() {
        n
    } else {
        b
    }
}

/// Cycles' `ensure_valid_specular_reflection(Ng, I, N)`: `n` rotated toward `ng` (both unit,
/// `ng` on the side of the unit view direction `wo`) until the reflection of `wo` about it is
/// at least `min(0.9·(wo·ng), 0.01)` above the geometric surface; `n` itself when that holds
/// already. The test is inline (every hit on a smoothly shaded surface makes it, and almost
/// every one passes); the rotation is a call.
#[inline]
pub fn ensure_valid_reflection(ng: Vec3, wo: Vec3, n: Vec3) -> Vec3 {
    let iz = wo.dot(ng);
    if iz.is_nan() || iz <= 0.0 || !n.is_finite() {
        return ng;
    }
    let r = 2.0 * n.dot(wo) * n - wo;
    let threshold = (0.9 * iz).min(0.01);
    if r.dot(ng) >= threshold {
        return n;
    }
    rotate_toward_ng(ng, wo, n, iz, threshold)
}

/// [`ensure_valid_reflection`]'s rotation of `n` toward `ng`, where the reflection of `wo`
/// about `n` lies below `threshold` (`iz = wo·ng > 0`, `n` finite).
#[inline(never)]
fn rotate_toward_ng(ng: Vec3, wo: Vec3, n: Vec3, iz: f32, threshold: f32) -> Vec3 {
    // Frame with ng as Z and n in the X–Z plane; solve for n'.z so that the reflection has
    // height exactly `threshold` (a quadratic in n'.z²; the larger root is the one nearer ng).
    let x = (n - n.dot(ng) * ng).normalize_or_zero();
    let x = if x == Vec3::ZERO {
        (wo - iz * ng).normalize_or_zero()
    } else {
        x
    };
    let ix = wo.dot(x);
    let a = ix * ix + iz * iz;
    let b = 2.0 * (a + iz * threshold);
    let c = (threshold + iz) * (threshold + iz);
    let nz2 = (0.25 * (b + (b * b - 4.0 * a * c).max(0.0).sqrt()) / a).clamp(0.0, 1.0);
    let out = (x * (1.0 - nz2).sqrt() + ng * nz2.sqrt()).normalize_or_zero();
    if out == Vec3::ZERO || !out.is_finite() {
        ng
    } else {
        out
    }
}

/// The microfacet-based bump shadowing term of Conty Estevez, Lecocq and Stein (Ray Tracing
/// Gems ch. 12, Mitsuba's `use_shadowing_function`) for light from `wi` at a point with
/// geometric normal `ng` and shading normal `ns` (unit vectors): the Smith masking of a GGX
/// surface whose roughness is set by how far `ns` tilts from `ng`. 1 for an unperturbed
/// normal; falls toward 0 for light grazing the geometry under a strongly bent normal.
pub fn shadowing(ng: Vec3, ns: Vec3, wi: Vec3) -> f32 {
    match shadowing_roughness(ng, ns) {
        Some(alpha2) => shadowing_at(alpha2, ng, wi),
        None => 1.0,
    }
}

/// The part of [`shadowing`] that does not depend on `wi`: the squared GGX roughness `α²` the
/// bent normal `ns` stands for, or `None` where the term is 1 for every `wi` (`ns` not
/// bent away from `ng`). A light loop makes it once per shading point.
#[inline]
pub fn shadowing_roughness(ng: Vec3, ns: Vec3) -> Option<f32> {
    let cos_d = ng.dot(ns).abs().min(1.0);
    if cos_d.is_nan() || cos_d >= 1.0 {
        return None;
    }
    let cos_d2 = (cos_d * cos_d).max(1e-12);
    Some((0.125 * (1.0 - cos_d2) / cos_d2).clamp(0.0, 1.0))
}

/// [`shadowing`] for light from `wi`, given the roughness [`shadowing_roughness`] made of its
/// normals.
#[inline]
pub fn shadowing_at(alpha2: f32, ng: Vec3, wi: Vec3) -> f32 {
    let cos_i = ng.dot(wi);
    if cos_i.is_nan() || cos_i <= 0.0 {
        return 0.0;
    }
    let cos_i2 = (cos_i * cos_i).clamp(1e-12, 1.0);
    let tan2_i = (1.0 - cos_i2) / cos_i2;
    2.0 / (1.0 + (1.0 + alpha2 * tan2_i).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The term as one function (before the split into [`shadowing_roughness`] and
    /// [`shadowing_at`]), kept to check the split bit for bit.
    fn shadowing_whole(ng: Vec3, ns: Vec3, wi: Vec3) -> f32 {
        let cos_d = ng.dot(ns).abs().min(1.0);
        if cos_d.is_nan() || cos_d >= 1.0 {
            return 1.0;
        }
        let cos_i = ng.dot(wi);
        if cos_i.is_nan() || cos_i <= 0.0 {
            return 0.0;
        }
        let cos_d2 = (cos_d * cos_d).max(1e-12);
        let alpha2 = (0.125 * (1.0 - cos_d2) / cos_d2).clamp(0.0, 1.0);
        let cos_i2 = (cos_i * cos_i).clamp(1e-12, 1.0);
        let tan2_i = (1.0 - cos_i2) / cos_i2;
        2.0 / (1.0 + (1.0 + alpha2 * tan2_i).sqrt())
    }

    #[test]
    fn split_shadowing_equals_the_whole_term_bit_for_bit() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let mut bent = 0;
        for i in 0..50_000 {
            let ng = Vec3::new(rnd(), rnd(), rnd()).normalize_or(Vec3::Z);
            let ns = match i % 5 {
                0 => ng,
                1 => -ng,
                2 => (ng + 1e-4 * Vec3::new(rnd(), rnd(), rnd())).normalize(),
                3 => Vec3::new(f32::NAN, 0.0, 1.0),
                _ => Vec3::new(rnd(), rnd(), rnd()).normalize_or(Vec3::X),
            };
            let wi = match i % 7 {
                0 => ng,
                1 => -ng,
                2 => Vec3::new(0.0, f32::NAN, 0.0),
                _ => Vec3::new(rnd(), rnd(), rnd()).normalize_or(Vec3::Y),
            };
            let want = shadowing_whole(ng, ns, wi);
            assert_eq!(
                shadowing(ng, ns, wi).to_bits(),
                want.to_bits(),
                "{ng} {ns} {wi}"
            );
            let split = shadowing_roughness(ng, ns).map_or(1.0, |a| shadowing_at(a, ng, wi));
            assert_eq!(split.to_bits(), want.to_bits());
            bent += usize::from(want != 1.0);
        }
        assert!(bent > 10_000, "{bent}");
    }

    #[test]
    fn tangents_of_a_unit_square_triangle() {
        let p = [
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 3.0, 0.0),
        ];
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        let (du, dv) = tangents(p, uv).unwrap();
        assert!((du - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-6);
        assert!((dv - Vec3::new(0.0, 3.0, 0.0)).length() < 1e-6);
        assert!(tangents(p, [Vec2::ZERO; 3]).is_none());
    }

    #[test]
    fn perturb_gives_the_height_field_normal() {
        // h(u, v) = u on the z = 0 plane: surface z = x, normal (−1, 0, 1)/√2.
        let n = perturb(Vec3::Z, Vec3::X, Vec3::Y, 1.0, 0.0);
        assert!(
            (n - Vec3::new(-1.0, 0.0, 1.0).normalize()).length() < 1e-6,
            "{n}"
        );
        // Mirrored uv (∂P/∂v = −y) bends the same way.
        let m = perturb(Vec3::Z, Vec3::X, Vec3::NEG_Y, 1.0, 0.0);
        assert!((m - n).length() < 1e-6, "{m}");
    }

    #[test]
    fn valid_reflection_lifts_the_mirror_direction() {
        let ng = Vec3::Z;
        let wo = Vec3::new(-1.0, -1.0, 0.5).normalize();
        // The mitsuba3 normal-map case: the view is behind the perturbed normal.
        let n = Vec3::ONE.normalize();
        assert!(n.dot(wo) < 0.0);
        let fixed = ensure_valid_reflection(ng, wo, n);
        assert!((fixed.length() - 1.0).abs() < 1e-5);
        assert!(fixed.dot(wo) > 0.0, "view above the corrected normal");
        let r = 2.0 * fixed.dot(wo) * fixed - wo;
        let t = (0.9 * wo.z).min(0.01);
        assert!((r.dot(ng) - t).abs() < 1e-4, "{}", r.dot(ng));
        // A valid normal is left alone.
        let ok = Vec3::new(0.1, 0.0, 1.0).normalize();
        assert_eq!(ensure_valid_reflection(ng, wo, ok), ok);
        // Grazing views and hostile input stay finite and unit.
        for wo in [
            Vec3::new(1.0, 0.0, 1e-6).normalize(),
            Vec3::new(0.0, 1.0, 1e-3),
        ] {
            for n in [Vec3::X, Vec3::NEG_X, Vec3::new(0.0, -1.0, 1e-3).normalize()] {
                let f = ensure_valid_reflection(ng, wo.normalize(), n);
                assert!(f.is_finite() && (f.length() - 1.0).abs() < 1e-4, "{f}");
                assert!(f.dot(wo) >= 0.0);
            }
        }
        assert_eq!(ensure_valid_reflection(ng, wo, Vec3::NAN), ng);
    }

    /// H11 (a), mitsuba3 `test_normalmap.py test03`: view normalize(−1, −1, 0.5), bent
    /// normal normalize(1, 1, 1), light from (0, 0, 1), Lambert: in the bent frame the view is
    /// below the normal, so eval, pdf and sampling are all 0; with the corrected normal all
    /// are positive.
    #[test]
    fn h11_mitsuba_normalmap_case_is_not_black() {
        use crate::components::Shader;
        use crate::shading::bsdf::Bsdf;
        use crate::shading::frame::ShadingFrame;
        let bsdf = Bsdf::new(&Shader::Lambert { albedo: Vec3::ONE }, true).unwrap();
        let (ng, view, light) = (Vec3::Z, Vec3::new(-1.0, -1.0, 0.5).normalize(), Vec3::Z);
        let probe = |n: Vec3| {
            let f = ShadingFrame::from_normal(n);
            let (wo, wi) = (f.to_local(view), f.to_local(light));
            let weight = bsdf
                .sample(wo, Vec3::new(0.5, 0.3, 0.7))
                .map_or(0.0, |s| s.weight().x);
            (
                bsdf.eval(wo, wi).x * wi.z.max(0.0),
                bsdf.pdf(wo, wi),
                weight,
            )
        };
        let bent = Vec3::ONE.normalize();
        assert_eq!(probe(bent), (0.0, 0.0, 0.0));
        let (eval, pdf, weight) = probe(ensure_valid_reflection(ng, view, bent));
        assert!(
            eval > 0.0 && pdf > 0.0 && weight > 0.0,
            "{eval} {pdf} {weight}"
        );
    }

    #[test]
    fn shadowing_term_mitsuba_case() {
        // mitsuba3 test_normalmap test04: viewer straight above, shading normal and light
        // both along normalize(1, 0.01, 0.01), almost on the horizon. Lambert (albedo 1) in
        // the shading frame gives eval = cos/π ≈ 1/π without the term; with it < 0.01.
        let ns = Vec3::new(1.0, 0.01, 0.01).normalize();
        let wi = ns;
        let eval = ns.dot(wi) / std::f32::consts::PI;
        assert!((eval - 1.0 / std::f32::consts::PI).abs() < 1e-6);
        let g = shadowing(Vec3::Z, ns, wi);
        assert!(eval * g < 0.01, "{}", eval * g);
        // Unperturbed normal: no change.
        assert_eq!(
            shadowing(Vec3::Z, Vec3::Z, Vec3::new(0.3, 0.0, 0.9).normalize()),
            1.0
        );
    }
}
