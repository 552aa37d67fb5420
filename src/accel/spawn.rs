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

use glam::{DVec3, Vec3, Vec3A};

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
#[inline(always)]
pub fn offset_ray_origin(p: Vec3, p_err: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    let d = n.abs().dot(p_err);
    let mut offset = n * d;
    if w.dot(n) < 0.0 {
        offset = -offset;
    }
    let po = p + offset;
    Vec3::new(
        step_toward_sign(po.x, offset.x),
        step_toward_sign(po.y, offset.y),
        step_toward_sign(po.z, offset.z),
    )
}

/// `x.next_up()` where `side > 0`, `x.next_down()` where `side < 0`, `x` otherwise (also for
/// a NaN `side`): the same bits as those library calls, without branches on data (the signs
/// of a hit's offset change from ray to ray, so branches on them mispredict).
#[inline(always)]
fn step_toward_sign(x: f32, side: f32) -> f32 {
    let bits = x.to_bits();
    let magnitude = bits & 0x7fff_ffff;
    let up = side > 0.0;
    let down = side < 0.0;
    let negative = bits >> 31 != 0;
    // A step up grows a positive number's magnitude and shrinks a negative one's.
    let grows = up != negative;
    let stepped = if magnitude == 0 {
        // From ±0 the smallest subnormal of the step's sign.
        if up {
            1
        } else {
            0x8000_0001
        }
    } else if grows {
        bits.wrapping_add(1)
    } else {
        bits.wrapping_sub(1)
    };
    // NaN stays; +∞ does not step up, −∞ does not step down (the library's rules).
    let is_nan = magnitude > 0x7f80_0000;
    let at_end = magnitude == 0x7f80_0000 && grows;
    let keep = !(up || down) || is_nan || at_end;
    f32::from_bits(if keep { bits } else { stepped })
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
            }
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
