//! Hit points with floating-point error bounds, and rays spawned from them without
//! self-intersection (pbrt-v4 `InteractionFromIntersection`, `OffsetRayOrigin`, `SpawnRay`,
//! `SpawnRayTo`).
//!
//! The hit point is computed from barycentrics, `p = b0·p0 + b1·p1 + b2·p2`, never as
//! `o + t·d`, and carries the per-axis bound `pErr = γ7·(|b0·p0| + |b1·p1| + |b2·p2|)`. A
//! spawned ray starts at `p` moved along the geometric normal by `dot(|n|, pErr)` — exactly far
//! enough to leave the error box — onto the side of the outgoing direction, and each coordinate
//! is rounded one more ulp away. No fixed epsilon is involved anywhere, so the offset scales
//! with the magnitude of the coordinates (1e-3 … 1e6 and beyond).

use glam::{BVec3A, DVec3, Vec3, Vec3A};

use super::triangle::gamma;
use super::{Ray, SurfacePoint};

/// Shadow segments end at `t_max = 1 − SHADOW_EPSILON` (pbrt-v4's `ShadowEpsilon`), a fraction
/// of the segment's own length, so the target's surface (whose position error is unknown to
/// [`spawn_ray_to`]) is never reported as an occluder.
pub const SHADOW_EPSILON: f32 = 1e-4;

/// Builds the surface point of barycentrics `(b1, b2)` on `tri` with its error bound and unit
/// geometric normal `(v1 − v0) × (v2 − v0)` (recomputed in `f64` when `f32` underflows).
pub(crate) fn surface_point(tri: &[Vec3; 3], b1: f32, b2: f32) -> SurfacePoint {
    surface_point_with_normal(tri, b1, b2, geometric_normal(tri))
}

/// [`Accel::surface_point`](super::Accel::surface_point) on a triangle whose unit geometric
/// normal `ng` ([`geometric_normal`]) the caller keeps (e.g. a light's triangles, sampled
/// over and over): the same point, bit for bit, without recomputing the normal.
#[inline]
pub fn surface_point_with_normal(tri: &[Vec3; 3], b1: f32, b2: f32, ng: Vec3) -> SurfacePoint {
    let b0 = 1.0 - b1 - b2;
    // In `Vec3A` lanes, with the scalar operations' order: the same bits.
    let [v0, v1, v2] = tri.map(Vec3A::from);
    let (w0, w1, w2) = (v0 * b0, v1 * b1, v2 * b2);
    let p = w0 + w1 + w2;
    let p_err = gamma(7) * (w0.abs() + w1.abs() + w2.abs());
    SurfacePoint {
        p: p.into(),
        p_err: p_err.into(),
        ng,
    }
}

/// Unit geometric normal of a triangle, `(v1 − v0) × (v2 − v0)` normalised (in `f64` when
/// `f32` underflows); `Vec3::ZERO` only for degenerate input.
pub fn geometric_normal(tri: &[Vec3; 3]) -> Vec3 {
    let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize_or_zero();
    if n != Vec3::ZERO {
        return n;
    }
    // Tiny triangles: the f32 cross product underflows; f64 has the range.
    let [a, b, c] = tri.map(|v| v.as_dvec3());
    let n: DVec3 = (b - a).cross(c - a).normalize_or_zero();
    n.as_vec3()
}

/// pbrt-v4 `OffsetRayOrigin`: moves `p` along `n` by `dot(|n|, p_err)` toward the side of `w`
/// (`+n` when `w` is tangent) and rounds each moved coordinate one ulp further away.
///
/// In `Vec3A` lanes, with the scalar operations in the same order, and without a branch: the
/// side is a select, and the three coordinates step together ([`step_toward_signs`]).
#[inline(always)]
pub fn offset_ray_origin(p: Vec3, p_err: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    let (p, p_err, n, w) = (
        Vec3A::from(p),
        Vec3A::from(p_err),
        Vec3A::from(n),
        Vec3A::from(w),
    );
    let d = n.abs().dot(p_err);
    let offset = n * d;
    let offset = Vec3A::select(BVec3A::splat(w.dot(n) < 0.0), -offset, offset);
    let po = p + offset;
    step_toward_signs(po, offset).into()
}

/// Per lane, `x.next_up()` where `side > 0`, `x.next_down()` where `side < 0`, `x` otherwise
/// (also for a NaN `side`): the same bits as those library calls, computed on the bit
/// patterns with lane masks (SSE2, part of x86-64), so no branch on data (the signs of a
/// hit's offset change from ray to ray: a branch on them mispredicted on about a sixth of
/// its runs, cachegrind on the photon pass).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn step_toward_signs(x: Vec3A, side: Vec3A) -> Vec3A {
    use std::arch::x86_64::{
        __m128, __m128i, _mm_add_epi32, _mm_and_si128, _mm_andnot_si128, _mm_castps_si128,
        _mm_castsi128_ps, _mm_cmpeq_epi32, _mm_cmpgt_epi32, _mm_cmpgt_ps, _mm_cmplt_ps,
        _mm_or_si128, _mm_set1_epi32, _mm_setzero_ps, _mm_setzero_si128, _mm_srai_epi32,
        _mm_sub_epi32, _mm_xor_si128,
    };
    // SAFETY: SSE2 intrinsics on values; SSE2 is part of every x86-64 CPU.
    unsafe {
        // `mask ? a : b`, lane by lane.
        let pick = |mask: __m128i, a: __m128i, b: __m128i| {
            _mm_or_si128(_mm_and_si128(mask, a), _mm_andnot_si128(mask, b))
        };
        let bits = _mm_castps_si128(__m128::from(x));
        let side = __m128::from(side);
        let up = _mm_castps_si128(_mm_cmpgt_ps(side, _mm_setzero_ps()));
        let down = _mm_castps_si128(_mm_cmplt_ps(side, _mm_setzero_ps()));
        // A step up grows a positive number's magnitude and shrinks a negative one's.
        let grows = _mm_xor_si128(up, _mm_srai_epi32::<31>(bits));
        let magnitude = _mm_and_si128(bits, _mm_set1_epi32(0x7fff_ffff));
        // ±1 ulp of the magnitude (`grows`: +1, else −1); from ±0 the smallest subnormal of
        // the step's sign.
        let one = _mm_set1_epi32(1);
        let delta = _mm_sub_epi32(_mm_and_si128(grows, _mm_set1_epi32(2)), one);
        let stepped_nonzero = _mm_add_epi32(bits, delta);
        let stepped_zero = _mm_xor_si128(
            _mm_set1_epi32(0x8000_0001_u32 as i32),
            _mm_and_si128(up, _mm_set1_epi32(i32::MIN)),
        );
        let zero = _mm_cmpeq_epi32(magnitude, _mm_setzero_si128());
        let stepped = pick(zero, stepped_zero, stepped_nonzero);
        // NaN stays; +∞ does not step up, −∞ does not step down (the library's rules).
        let inf = _mm_set1_epi32(0x7f80_0000);
        let is_nan = _mm_cmpgt_epi32(magnitude, inf);
        let at_end = _mm_and_si128(_mm_cmpeq_epi32(magnitude, inf), grows);
        let still = _mm_cmpeq_epi32(_mm_or_si128(up, down), _mm_setzero_si128());
        let keep = _mm_or_si128(_mm_or_si128(still, is_nan), at_end);
        Vec3A::from(_mm_castsi128_ps(pick(keep, bits, stepped)))
    }
}

/// [`step_toward_signs`] one coordinate at a time (other architectures).
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn step_toward_signs(x: Vec3A, side: Vec3A) -> Vec3A {
    Vec3A::new(
        step_toward_sign(x.x, side.x),
        step_toward_sign(x.y, side.y),
        step_toward_sign(x.z, side.z),
    )
}

/// One coordinate of [`step_toward_signs`], with the same masks.
#[cfg_attr(target_arch = "x86_64", allow(dead_code))]
#[inline(always)]
fn step_toward_sign(x: f32, side: f32) -> f32 {
    let bits = x.to_bits();
    let magnitude = bits & 0x7fff_ffff;
    let up = u32::from(side > 0.0);
    let down = u32::from(side < 0.0);
    let grows = up ^ (bits >> 31);
    // All ones where `c` holds.
    let mask = |c: bool| 0u32.wrapping_sub(u32::from(c));
    let stepped_nonzero = bits.wrapping_add((grows << 1).wrapping_sub(1));
    let stepped_zero = 0x8000_0001 ^ (up << 31);
    let zero = mask(magnitude == 0);
    let stepped = (stepped_zero & zero) | (stepped_nonzero & !zero);
    let is_nan = magnitude > 0x7f80_0000;
    let at_end = magnitude == 0x7f80_0000 && grows != 0;
    let keep = mask((up | down) == 0 || is_nan || at_end);
    f32::from_bits((bits & keep) | (stepped & !keep))
}

/// A ray leaving the surface point `from` in direction `dir` (any length), offset so that it
/// cannot re-hit the surface it starts on; `t_max = ∞`.
#[inline(always)]
pub fn spawn_ray(from: &SurfacePoint, dir: Vec3) -> Ray {
    Ray {
        origin: offset_ray_origin(from.p, from.p_err, from.ng, dir),
        dir,
        t_max: f32::INFINITY,
    }
}

/// A shadow segment from the surface point `from` toward the point `target` (a point light or
/// a light sample): `dir = target − origin`, so `t = 1` is the target, and `t_max = 1 −`
/// [`SHADOW_EPSILON`] stops it just short. For targets on a surface with a known error bound
/// prefer [`spawn_ray_to_surface`].
#[inline(always)]
pub fn spawn_ray_to(from: &SurfacePoint, target: Vec3) -> Ray {
    let origin = offset_ray_origin(from.p, from.p_err, from.ng, target - from.p);
    Ray {
        origin,
        dir: target - origin,
        t_max: 1.0 - SHADOW_EPSILON,
    }
}

/// A shadow segment between two surface points with both ends offset off their surfaces
/// (pbrt-v4 `SpawnRayTo(pFrom, nFrom, pTo, nTo)`): `t = 1` is the offset far end, and `t_max =
/// 1 −` [`SHADOW_EPSILON`].
#[inline(always)]
pub fn spawn_ray_to_surface(from: &SurfacePoint, to: &SurfacePoint) -> Ray {
    let pf = offset_ray_origin(from.p, from.p_err, from.ng, to.p - from.p);
    let pt = offset_ray_origin(to.p, to.p_err, to.ng, pf - to.p);
    Ray {
        origin: pf,
        dir: pt - pf,
        t_max: 1.0 - SHADOW_EPSILON,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_bound_is_gamma7_of_weighted_vertices() {
        let tri = [
            Vec3::new(1e3, 0.0, 0.0),
            Vec3::new(0.0, 2e3, 0.0),
            Vec3::new(0.0, 0.0, -4e3),
        ];
        let sp = surface_point(&tri, 0.25, 0.5);
        let expect = gamma(7) * Vec3::new(250.0, 500.0, 2000.0);
        assert!((sp.p_err - expect).abs().max_element() <= expect.max_element() * 1e-6);
        assert!((sp.ng.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn offset_leaves_error_box_on_requested_side() {
        let p = Vec3::new(1e5, -3.0, 7.5);
        let err = Vec3::new(0.01, 1e-6, 1e-6);
        let n = Vec3::new(1.0, 1.0, 0.0).normalize();
        let up = offset_ray_origin(p, err, n, Vec3::X);
        let down = offset_ray_origin(p, err, n, -Vec3::X);
        let d = n.abs().dot(err);
        assert!((up - p).dot(n) >= d * 0.999);
        assert!((down - p).dot(n) <= -d * 0.999);
        // A zero error bound means no offset at all.
        let o = offset_ray_origin(Vec3::ONE, Vec3::ZERO, Vec3::Z, Vec3::Z);
        assert_eq!(o, Vec3::ONE);
    }

    /// The reference for [`step_toward_sign`]: the library's `next_up` / `next_down`.
    fn step_with_library(x: f32, side: f32) -> f32 {
        if side > 0.0 {
            x.next_up()
        } else if side < 0.0 {
            x.next_down()
        } else {
            x
        }
    }

    #[test]
    fn branchless_step_equals_next_up_and_next_down_bit_for_bit() {
        let mut xs = vec![
            0.0f32,
            -0.0,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::from_bits(1),
            f32::from_bits(0x8000_0001),
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            1.0,
            -1.0,
            556.0,
            -0.1,
        ];
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            xs.push(f32::from_bits((state >> 16) as u32));
        }
        let sides = [
            1.0f32,
            -1.0,
            0.0,
            -0.0,
            1e-30,
            -1e-30,
            f32::NAN,
            f32::INFINITY,
        ];
        for &x in &xs {
            for &side in &sides {
                let want = step_with_library(x, side);
                let got = step_toward_sign(x, side);
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "x {x:e} ({:#010x}), side {side}",
                    x.to_bits()
                );
                // Each lane of the vector step, with different neighbours in the others.
                let lanes = step_toward_signs(Vec3A::new(x, -x, 1.5), Vec3A::new(side, -1.0, side));
                assert_eq!(
                    lanes.x.to_bits(),
                    want.to_bits(),
                    "lane x: {x:e}, side {side}"
                );
                let other = step_with_library(-x, -1.0);
                assert_eq!(lanes.y.to_bits(), other.to_bits(), "lane y: {x:e}");
                let third = step_with_library(1.5, side);
                assert_eq!(lanes.z.to_bits(), third.to_bits(), "lane z: side {side}");
            }
        }
    }

    /// The lane version of `OffsetRayOrigin` is the scalar one (Vec3 arithmetic, a branch on
    /// the side, the library's `next_up`/`next_down`) bit for bit: random points, error
    /// bounds, normals and directions at many scales, with zero and negative-zero
    /// components and directions tangent to the normal.
    #[test]
    fn offset_equals_the_scalar_offset_bit_for_bit() {
        let scalar = |p: Vec3, p_err: Vec3, n: Vec3, w: Vec3| {
            let d = n.abs().dot(p_err);
            let mut offset = n * d;
            if w.dot(n) < 0.0 {
                offset = -offset;
            }
            let po = p + offset;
            Vec3::new(
                step_with_library(po.x, offset.x),
                step_with_library(po.y, offset.y),
                step_with_library(po.z, offset.z),
            )
        };
        let mut rnd = crate::accel::test_random::signed_uniform(0x0ff5_e7a1_9e37_79b9);
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        for i in 0..200_000 {
            let scale = [1e-30, 1e-6, 1.0, 1e4, 1e30][i % 5];
            let mut v = || Vec3::new(rnd(), rnd(), rnd());
            let mut p = v() * scale;
            let p_err = v().abs() * scale * 1e-6;
            let mut n = v().normalize_or(Vec3::Z);
            let mut w = v();
            match i % 9 {
                0 => p.x = 0.0,
                1 => p.y = -0.0,
                2 => n = Vec3::new(0.0, -0.0, 1.0),
                3 => w = n.cross(Vec3::X),
                4 => n.z = -0.0,
                _ => {}
            }
            assert_eq!(
                bits(offset_ray_origin(p, p_err, n, w)),
                bits(scalar(p, p_err, n, w)),
                "p {p} err {p_err} n {n} w {w}"
            );
        }
    }

    #[test]
    fn tiny_triangle_normal_uses_f64() {
        let s = 1e-25;
        let tri = [Vec3::ZERO, Vec3::new(s, 0.0, 0.0), Vec3::new(0.0, s, 0.0)];
        assert_eq!(geometric_normal(&tri), Vec3::Z);
    }

    #[test]
    fn spawn_to_ends_before_target() {
        let sp = SurfacePoint {
            p: Vec3::ZERO,
            p_err: Vec3::splat(1e-7),
            ng: Vec3::Y,
        };
        let r = spawn_ray_to(&sp, Vec3::new(0.0, 5.0, 0.0));
        assert_eq!(r.origin + r.dir, Vec3::new(0.0, 5.0, 0.0));
        assert!(r.t_max < 1.0 && r.origin.y > 0.0);
        let to = SurfacePoint {
            p: Vec3::new(0.0, 5.0, 0.0),
            p_err: Vec3::splat(1e-6),
            ng: Vec3::Y,
        };
        let r = spawn_ray_to_surface(&sp, &to);
        // The far end is offset to the -y side of the target (toward the origin).
        assert!((r.origin + r.dir).y < 5.0);
    }
}
