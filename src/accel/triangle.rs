//! Watertight ray/triangle intersection (Woop, Benthin & Wald, JCGT 2(1) 2013) in `f32`,
//! with pbrt-v4's `f64` fallback when an edge function is exactly zero and pbrt-v4's
//! conservative `t > δt` check (`src/pbrt/shapes.cpp IntersectTriangle`).
//!
//! The test translates the triangle to the ray origin, permutes the axes so that the
//! dominant direction component is z, and shears so that the ray becomes the +z axis. The 2-D
//! edge functions are then evaluated from the *transformed vertices*, so two triangles that
//! share an edge evaluate that edge's function from identical numbers and obtain exactly
//! negated values: a ray through a shared edge or vertex can never slip between them.
//!
//! Everything here is plain `f32` arithmetic without fused multiply-add (the compiler never
//! contracts Rust float expressions), which keeps `a·b − c·d` exactly antisymmetric.

use glam::Vec3;

use super::Ray;

/// Half the distance between 1 and the next `f32` (the unit roundoff, 2⁻²⁴).
pub const MACHINE_EPSILON: f32 = f32::EPSILON * 0.5;

/// pbrt's γₙ = nε / (1 − nε): bound on the relative error of n chained roundings.
pub const fn gamma(n: u32) -> f32 {
    let ne = n as f32 * MACHINE_EPSILON;
    ne / (1.0 - ne)
}

/// True when the triangle can never be hit: a non-finite vertex, or a zero cross product
/// (zero area, collinear or coincident vertices) — pbrt-v4's degeneracy test.
pub fn is_degenerate(tri: &[Vec3; 3]) -> bool {
    if !(tri[0].is_finite() && tri[1].is_finite() && tri[2].is_finite()) {
        return true;
    }
    let c = (tri[2] - tri[0]).cross(tri[1] - tri[0]);
    // NaN also counts as degenerate.
    let len2 = c.length_squared();
    len2.is_nan() || len2 <= 0.0
}

/// Per-ray constants of the watertight test: origin, axis permutation and shear.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WoopRay {
    o: [f32; 3],
    kx: usize,
    ky: usize,
    kz: usize,
    sx: f32,
    sy: f32,
    sz: f32,
    /// Permuted direction, for the f64 refinement of `t`.
    d: [f32; 3],
}

impl WoopRay {
    /// Precomputes the permutation (dominant |dir| component becomes z) and the shear.
    /// Without branches: the nested choice of [`WoopRay::new_nested`] (x if it beats y and z,
    /// else y if it beats z, else z; the same comparisons, so the same axis) as arithmetic on
    /// the comparisons, the permutation from a table, and the three quotients as one 4-lane
    /// division (the same IEEE divisions: `−a / b` is `−(a / b)` exactly). The branches
    /// mispredicted on incoherent directions; three scalar divisions waited on each other.
    #[inline(always)]
    pub(crate) fn new(origin: Vec3, dir: Vec3) -> Self {
        let a = dir.abs();
        let (x_gt_y, x_gt_z, y_gt_z) = (a.x > a.y, a.x > a.z, a.y > a.z);
        let kz = 2 - 2 * usize::from(x_gt_y & x_gt_z) - usize::from(!x_gt_y & y_gt_z);
        // (kx, ky) for kz = 0, 1, 2 (a fourth row keeps the index in range without a check).
        const PERM: [[usize; 2]; 4] = [[1, 2], [2, 0], [0, 1], [0, 1]];
        let [kx, ky] = PERM[kz & 3];
        let d = dir.extend(0.0).to_array();
        let (dx, dy, dz) = (d[kx & 3], d[ky & 3], d[kz & 3]);
        let s = glam::Vec4::new(-dx, -dy, 1.0, 1.0) / glam::Vec4::splat(dz);
        Self {
            o: origin.to_array(),
            kx,
            ky,
            kz,
            sx: s.x,
            sy: s.y,
            sz: s.z,
            d: [dx, dy, dz],
        }
    }

    /// The reference for [`WoopRay::new`]: the nested choice of the dominant axis and three
    /// scalar divisions (pbrt-v4's form).
    #[cfg(test)]
    pub(crate) fn new_nested(origin: Vec3, dir: Vec3) -> Self {
        let a = dir.abs();
        let kz = if a.x > a.y {
            if a.x > a.z {
                0
            } else {
                2
            }
        } else if a.y > a.z {
            1
        } else {
            2
        };
        let kx = if kz == 2 { 0 } else { kz + 1 };
        let ky = if kx == 2 { 0 } else { kx + 1 };
        let d = dir.to_array();
        Self {
            o: origin.to_array(),
            kx,
            ky,
            kz,
            sx: -d[kx] / d[kz],
            sy: -d[ky] / d[kz],
            sz: 1.0 / d[kz],
            d: [d[kx], d[ky], d[kz]],
        }
    }

    /// The axis permutation `[kx, ky, kz]` (`kz` the dominant direction component).
    #[inline(always)]
    pub(crate) fn axes(&self) -> [usize; 3] {
        [self.kx, self.ky, self.kz]
    }

    /// The ray origin, in the caller's axis order.
    #[inline(always)]
    pub(crate) fn origin(&self) -> [f32; 3] {
        self.o
    }

    /// The shear `(sx, sy, sz)`: `x + sx·z`, `y + sy·z`, `z·sz` after the permutation.
    #[inline(always)]
    pub(crate) fn shear(&self) -> (f32, f32, f32) {
        (self.sx, self.sy, self.sz)
    }

    /// Intersects a non-degenerate triangle. Returns `(t, b1, b2)` for a hit with `t > δt`
    /// (conservatively in front of the origin); the caller compares `t` with its `t_max`.
    /// The result depends only on the ray and the triangle, never on a running `t_max`,
    /// so any traversal order finds the same closest hit.
    #[inline(always)]
    pub(crate) fn intersect(&self, tri: &[Vec3; 3]) -> Option<(f32, f32, f32)> {
        let (kx, ky, kz) = (self.kx, self.ky, self.kz);
        let o = self.o;
        // Translate to the ray origin and permute.
        let p0 = tri[0].to_array();
        let p1 = tri[1].to_array();
        let p2 = tri[2].to_array();
        let t0 = [p0[kx] - o[kx], p0[ky] - o[ky], p0[kz] - o[kz]];
        let t1 = [p1[kx] - o[kx], p1[ky] - o[ky], p1[kz] - o[kz]];
        let t2 = [p2[kx] - o[kx], p2[ky] - o[ky], p2[kz] - o[kz]];
        let [x0, y0, z0] = t0;
        let [x1, y1, z1] = t1;
        let [x2, y2, z2] = t2;
        // Shear x and y so that the ray is the +z axis.
        let x0 = x0 + self.sx * z0;
        let y0 = y0 + self.sy * z0;
        let x1 = x1 + self.sx * z1;
        let y1 = y1 + self.sy * z1;
        let x2 = x2 + self.sx * z2;
        let y2 = y2 + self.sy * z2;
        // Edge functions: e0 belongs to vertex 0 (edge v1→v2), etc.
        let mut e0 = x1 * y2 - y1 * x2;
        let mut e1 = x2 * y0 - y2 * x0;
        let mut e2 = x0 * y1 - y0 * x1;
        if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
            [e0, e1, e2] = edge_functions_f64([x0, y0, x1, y1, x2, y2])?;
        } else if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        let zs0 = z0 * self.sz;
        let zs1 = z1 * self.sz;
        let zs2 = z2 * self.sz;
        let t_scaled = e0 * zs0 + e1 * zs1 + e2 * zs2;
        // t = t_scaled / det must be positive; written so that NaN fails.
        if !((det > 0.0 && t_scaled > 0.0) || (det < 0.0 && t_scaled < 0.0)) {
            return None;
        }
        let inv_det = 1.0 / det;
        let t = t_scaled * inv_det;
        // pbrt-v4: ensure that the computed t is conservatively greater than zero.
        let max_zt = zs0.abs().max(zs1.abs()).max(zs2.abs());
        let delta_z = gamma(3) * max_zt;
        let max_xt = x0.abs().max(x1.abs()).max(x2.abs());
        let max_yt = y0.abs().max(y1.abs()).max(y2.abs());
        // The shear adds `s·z` with |s| ≤ 1 to x and y, so their error scales with the
        // *unscaled* z (a length, like x and y). pbrt-v4 uses the t-scaled z here, which is
        // only right for |dir| ≈ 1: far too large for short directions (it rejected true hits
        // of 1e-3-long directions) and too small for long ones.
        let max_z = z0.abs().max(z1.abs()).max(z2.abs());
        let delta_x = gamma(5) * (max_xt + max_z);
        let delta_y = gamma(5) * (max_yt + max_z);
        let delta_e = 2.0 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
        let max_e = e0.abs().max(e1.abs()).max(e2.abs());
        let delta_t =
            3.0 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * inv_det.abs();
        if t > delta_t {
            return Some((t, e1 * inv_det, e2 * inv_det));
        }
        // The f32 bound cannot tell t from 0: near the origin (a spawned ray and its own
        // surface), or at grazing incidence, where δt blows up even for t ≫ 0 and rejecting
        // would leak. Decide with t and δt recomputed in f64 (same formulas, f64 rounding).
        let t = self.refine_t(t0, t1, t2)?;
        Some((t, e1 * inv_det, e2 * inv_det))
    }

    /// `t` and its error bound in f64 from the translated, permuted vertices; `Some(t)` only
    /// when `t > δt` in f64 (and `t` is still positive in f32).
    #[cold]
    #[inline(never)]
    fn refine_t(&self, t0: [f32; 3], t1: [f32; 3], t2: [f32; 3]) -> Option<f32> {
        let g = |n: f64| n * f64::EPSILON * 0.5 / (1.0 - n * f64::EPSILON * 0.5);
        let d = self.d.map(f64::from);
        let (sx, sy, sz) = (-d[0] / d[2], -d[1] / d[2], 1.0 / d[2]);
        let shear = |p: [f32; 3]| {
            let [x, y, z] = p.map(f64::from);
            (x + sx * z, y + sy * z, z)
        };
        let ((x0, y0, z0), (x1, y1, z1), (x2, y2, z2)) = (shear(t0), shear(t1), shear(t2));
        let e0 = x1 * y2 - y1 * x2;
        let e1 = x2 * y0 - y2 * x0;
        let e2 = x0 * y1 - y0 * x1;
        let det = e0 + e1 + e2;
        let (zs0, zs1, zs2) = (z0 * sz, z1 * sz, z2 * sz);
        let t = (e0 * zs0 + e1 * zs1 + e2 * zs2) / det;
        let max_zt = zs0.abs().max(zs1.abs()).max(zs2.abs());
        let max_z = z0.abs().max(z1.abs()).max(z2.abs());
        let max_xt = x0.abs().max(x1.abs()).max(x2.abs());
        let max_yt = y0.abs().max(y1.abs()).max(y2.abs());
        let delta_x = g(5.0) * (max_xt + max_z);
        let delta_y = g(5.0) * (max_yt + max_z);
        let delta_z = g(3.0) * max_zt;
        let delta_e = 2.0 * (g(2.0) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
        let max_e = e0.abs().max(e1.abs()).max(e2.abs());
        let delta_t =
            3.0 * (g(3.0) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) / det.abs();
        let t32 = t as f32;
        (t > delta_t && t32 > 0.0).then_some(t32)
    }
}

/// The edge functions of sheared 2-D vertices `[x0, y0, x1, y1, x2, y2]` in f64, where the
/// products are exact; `None` when their signs differ. Used when an f32 edge function is
/// exactly zero (on an edge, or underflow): the sign test uses the f64 values, so an f32
/// underflow to ±0 cannot turn a miss by a subnormal distance into an edge hit.
#[cold]
#[inline(never)]
fn edge_functions_f64(v: [f32; 6]) -> Option<[f32; 3]> {
    let [x0, y0, x1, y1, x2, y2] = v.map(f64::from);
    let d0 = x1 * y2 - y1 * x2;
    let d1 = x2 * y0 - y2 * x0;
    let d2 = x0 * y1 - y0 * x1;
    if (d0 < 0.0 || d1 < 0.0 || d2 < 0.0) && (d0 > 0.0 || d1 > 0.0 || d2 > 0.0) {
        return None;
    }
    Some([d0 as f32, d1 as f32, d2 as f32])
}

/// The watertight ray/triangle test on its own: `Some((t, b1, b2))` when the ray hits the
/// triangle with `0 < t < ray.t_max` (t conservatively positive), where `b1`, `b2` are the
/// barycentric weights of vertices 1 and 2. Degenerate and non-finite triangles and rays with
/// a non-finite origin or direction (or a zero direction) never hit.
pub fn intersect_triangle(ray: &Ray, tri: &[Vec3; 3]) -> Option<(f32, f32, f32)> {
    if !ray_is_valid(ray) || is_degenerate(tri) {
        return None;
    }
    let hit = WoopRay::new(ray.origin, ray.dir).intersect(tri)?;
    (hit.0 < ray.t_max).then_some(hit)
}

/// Rays that can hit anything: finite origin, finite non-zero direction, `t_max > 0` (NaN
/// fails). Everything else is answered "no hit" without traversal.
#[inline]
pub(crate) fn ray_is_valid(ray: &Ray) -> bool {
    ray.origin.is_finite() && ray.dir.is_finite() && ray.dir != Vec3::ZERO && ray.t_max > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: Vec3, d: Vec3) -> Ray {
        Ray {
            origin: o,
            dir: d,
            t_max: f32::INFINITY,
        }
    }

    const TRI: [Vec3; 3] = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];

    #[test]
    fn gamma_matches_definition() {
        let e = 2f64.powi(-24);
        let g3 = 3.0 * e / (1.0 - 3.0 * e);
        assert!((f64::from(gamma(3)) - g3).abs() < g3 * 1e-6);
        assert!(gamma(7) > 7.0 * MACHINE_EPSILON);
    }

    #[test]
    fn hits_interior_with_barycentrics() {
        let (t, b1, b2) = intersect_triangle(
            &ray(Vec3::new(0.25, 0.5, 2.0), Vec3::new(0.0, 0.0, -2.0)),
            &TRI,
        )
        .unwrap();
        assert_eq!(t, 1.0);
        assert_eq!((b1, b2), (0.25, 0.5));
    }

    #[test]
    fn both_faces_hit_and_behind_misses() {
        assert!(intersect_triangle(&ray(Vec3::new(0.2, 0.2, -1.0), Vec3::Z), &TRI).is_some());
        assert!(intersect_triangle(&ray(Vec3::new(0.2, 0.2, 1.0), Vec3::Z), &TRI).is_none());
    }

    #[test]
    fn t_max_is_exclusive() {
        let mut r = ray(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
        r.t_max = 1.0;
        assert!(intersect_triangle(&r, &TRI).is_none());
        r.t_max = 1.0f32.next_up();
        assert!(intersect_triangle(&r, &TRI).is_some());
    }

    #[test]
    fn exact_edge_and_vertex_hit() {
        // Ray through the hypotenuse midpoint and through each vertex (directions exact).
        for target in [Vec3::new(0.5, 0.5, 0.0), TRI[0], TRI[1], TRI[2]] {
            let o = Vec3::new(0.25, 0.25, 3.0);
            assert!(
                intersect_triangle(&ray(o, target - o), &TRI).is_some(),
                "{target}"
            );
        }
    }

    #[test]
    fn degenerate_and_nan_never_hit() {
        let o = Vec3::new(0.0, 0.0, 5.0);
        let bad = [
            [Vec3::ZERO; 3],
            [Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            [Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Y],
            [Vec3::ZERO, Vec3::new(f32::INFINITY, 0.0, 0.0), Vec3::Y],
        ];
        for tri in bad {
            assert!(is_degenerate(&tri));
            for d in [
                -Vec3::Z,
                Vec3::new(0.1, 0.0, -1.0),
                Vec3::new(0.0, 0.0, -1.0) - o,
            ] {
                assert!(intersect_triangle(&ray(o, d), &tri).is_none());
            }
        }
        assert!(!is_degenerate(&TRI));
    }

    #[test]
    fn invalid_rays_never_hit() {
        let o = Vec3::new(0.2, 0.2, 1.0);
        for r in [
            ray(o, Vec3::ZERO),
            ray(o, Vec3::new(f32::NAN, 0.0, -1.0)),
            ray(Vec3::new(f32::NAN, 0.2, 1.0), -Vec3::Z),
            Ray {
                origin: o,
                dir: -Vec3::Z,
                t_max: f32::NAN,
            },
            Ray {
                origin: o,
                dir: -Vec3::Z,
                t_max: -1.0,
            },
        ] {
            assert!(intersect_triangle(&r, &TRI).is_none());
        }
    }

    #[test]
    fn origin_on_surface_is_not_hit() {
        // t would be ~0: δt rejects it.
        let o = Vec3::new(0.25, 0.25, 0.0);
        assert!(intersect_triangle(&ray(o, Vec3::new(0.3, -0.2, 1.0)), &TRI).is_none());
    }

    /// The branch-free `WoopRay::new` makes the nested reference's permutation, shear and
    /// permuted direction bit for bit: ties between components, zeros of both signs,
    /// subnormals, huge and tiny values, every sign.
    #[test]
    fn woop_ray_new_equals_nested() {
        let values = [
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            0.5,
            -0.3,
            3.0,
            1e-40,
            -1e-40,
            1e30,
            -7e-20,
            f32::MIN_POSITIVE,
            std::f32::consts::FRAC_1_SQRT_2,
        ];
        let bits = |w: &WoopRay| {
            (
                w.axes(),
                [w.sx, w.sy, w.sz, w.d[0], w.d[1], w.d[2]].map(f32::to_bits),
                w.o.map(f32::to_bits),
            )
        };
        let mut n = 0;
        for &x in &values {
            for &y in &values {
                for &z in &values {
                    let (o, d) = (Vec3::new(z, x, y), Vec3::new(x, y, z));
                    if d == Vec3::ZERO {
                        continue;
                    }
                    assert_eq!(
                        bits(&WoopRay::new(o, d)),
                        bits(&WoopRay::new_nested(o, d)),
                        "{d}"
                    );
                    n += 1;
                }
            }
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x2545_f491_4f6c_dd1du64);
        for _ in 0..100_000 {
            let d = Vec3::new(rnd(), rnd(), rnd()) * (rnd() * 60.0).exp2();
            let o = Vec3::new(rnd(), rnd(), rnd());
            assert_eq!(
                bits(&WoopRay::new(o, d)),
                bits(&WoopRay::new_nested(o, d)),
                "{d}"
            );
            n += 1;
        }
        assert!(n > 100_000);
    }
}
