//! The small-scene path (x86-64, AVX2 at run time): when the whole mesh has few triangles,
//! single-ray closest-hit and occlusion queries test every triangle in SIMD lanes instead of
//! walking the tree — no node tests, no stack, no leaf gathers.
//!
//! * **Layout**: the non-degenerate triangles, in the tree's order (so that the triangles of
//!   a group lie close together and a ray's line misses whole groups more often), are kept
//!   pre-transposed in groups of eight (structure of arrays: per vertex, per axis, eight
//!   lanes; one triangle per lane). A ray's axis permutation (`WoopRay`) picks which axis
//!   arrays a lane reads, so no triangle is shuffled per ray. Spare lanes of the last group
//!   hold NaN vertices, which every lane test answers as a miss (NaN edge functions make the
//!   determinant NaN, which fails the sign test, and `NaN == 0` is false, so the lane is not
//!   sent to the scalar test either).
//! * **Same answers, bit for bit**: each lane makes [`WoopRay::intersect`]'s IEEE operations
//!   in its order (subtract, shear, edge functions, determinant, `t`, the conservative `δt`
//!   bound; no fused multiply-add, an exact division), as `leaf_wide.rs` does for four lanes.
//!   The lanes the scalar test would finish in `f64` (an edge function exactly zero; `t ≤ δt`)
//!   are *slow* and are decided by the scalar test itself. A group whose lanes are all
//!   outside their triangles (or all behind the origin) stops before the division. The
//!   closest hit is the least `(t, prim)` among hits with `0 < t < t_max` (ties at equal `t`
//!   go to the smallest `prim`) — what `brute.rs` returns, and the tree but for coplanar
//!   faces, where its box cull can drop a hit a few ulps nearer (`docs/ray-layer.md`, issue 17,
//!   session 15). Occlusion stops at the first group with a hit below `t_max`.
//! * **Dispatch** ([`SmallScene::closest`], [`SmallScene::occluded`]): `None` when the CPU
//!   lacks AVX2 or `STAGELIGHT_TRAVERSAL=sse…` was set at the first query; the caller then
//!   walks the tree. [`SmallScene::build`] makes the path only for meshes of at most
//!   [`max_triangles`] triangles (`STAGELIGHT_SMALL_SCENE=N` overrides the threshold, `0`
//!   turns the path off; for A/B runs). A 16-lane AVX-512 kernel was measured and did not
//!   pay (`docs/ray-layer.md`, issue 17, session 15).

use std::arch::x86_64::{
    __m128, __m256, _mm256_add_ps, _mm256_and_ps, _mm256_andnot_ps, _mm256_broadcastss_ps,
    _mm256_cmp_ps, _mm256_div_ps, _mm256_load_ps, _mm256_max_ps, _mm256_movemask_ps, _mm256_mul_ps,
    _mm256_or_ps, _mm256_set1_ps, _mm256_setzero_ps, _mm256_storeu_ps, _mm256_sub_ps,
    _mm256_xor_ps, _mm_blend_ps, _mm_div_ps, _mm_permutevar_ps, _mm_set1_ps, _mm_setr_epi32,
    _mm_setr_ps, _mm_shuffle_ps, _mm_xor_ps, _CMP_EQ_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ,
};
use std::sync::OnceLock;

use glam::Vec3;

use super::bvh::LeafTri;
use super::triangle::{gamma, is_degenerate, ray_is_valid, WoopRay};
use super::{Hit, Ray};

/// Triangles per group (one per AVX2 lane).
const LANES: usize = 8;

/// The default largest mesh (triangles given to `Accel::build`) answered without the tree;
/// measured in `docs/ray-layer.md` (issue 17, session 15).
pub(super) const DEFAULT_MAX_TRIANGLES: usize = 32;

/// The largest mesh answered without the tree: `STAGELIGHT_SMALL_SCENE=N` when set to a
/// number (0 turns the path off), else [`DEFAULT_MAX_TRIANGLES`].
pub(super) fn max_triangles() -> usize {
    std::env::var("STAGELIGHT_SMALL_SCENE")
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(DEFAULT_MAX_TRIANGLES)
}

/// Whether the AVX2 kernel runs (AVX2 present and not turned off by
/// `STAGELIGHT_TRAVERSAL=sse…`, read once).
fn use_avx2() -> bool {
    static CHOICE: OnceLock<bool> = OnceLock::new();
    *CHOICE.get_or_init(|| {
        std::arch::is_x86_feature_detected!("avx2")
            && !std::env::var("STAGELIGHT_TRAVERSAL").is_ok_and(|v| v.starts_with("sse"))
    })
}

/// Eight triangles transposed: `v[vertex][axis][lane]`.
#[derive(Clone, Copy)]
#[repr(C, align(32))]
struct Group {
    v: [[[f32; LANES]; 3]; 3],
}

/// What a group test found: bit `j` of `hit` for a lane decided as a hit with `t` below the
/// limit (its `t`, `b1`, `b2` are lane `j` of the arrays), bit `j` of `slow` for a lane the
/// caller must decide with the scalar test. Lanes in neither mask are misses (or hits at or
/// beyond the limit).
struct Lanes {
    hit: u32,
    slow: u32,
    t: [f32; LANES],
    b1: [f32; LANES],
    b2: [f32; LANES],
}

impl Lanes {
    const MISS: Self = Self {
        hit: 0,
        slow: 0,
        t: [0.0; LANES],
        b1: [0.0; LANES],
        b2: [0.0; LANES],
    };
}

/// Every non-degenerate triangle of a small mesh in lane groups.
pub(super) struct SmallScene {
    groups: Vec<Group>,
    /// The same triangles, slot by slot (for the scalar test of slow lanes).
    tris: Vec<[Vec3; 3]>,
    /// The caller's index of each slot.
    prims: Vec<u32>,
}

impl SmallScene {
    /// The lane groups of `tris` (degenerate ones left out) in the order given, each with its
    /// caller's index; `None` when there are more than `max` triangles. `Accel` gives them in
    /// the tree's order, so that the triangles of a group lie close together and a ray misses
    /// whole groups more often.
    pub(super) fn build(tris: &[LeafTri], max: usize) -> Option<Self> {
        if tris.len() > max {
            return None;
        }
        let (prims, tris): (Vec<u32>, Vec<[Vec3; 3]>) = tris
            .iter()
            .filter(|t| !is_degenerate(&t.v))
            .map(|t| (t.prim, t.v))
            .unzip();
        let mut groups = vec![
            Group {
                v: [[[f32::NAN; LANES]; 3]; 3],
            };
            tris.len().div_ceil(LANES)
        ];
        for (slot, tri) in tris.iter().enumerate() {
            let g = &mut groups[slot / LANES];
            for (v, p) in tri.iter().enumerate() {
                for (a, x) in p.to_array().into_iter().enumerate() {
                    g.v[v][a][slot % LANES] = x;
                }
            }
        }
        Some(Self {
            groups,
            tris,
            prims,
        })
    }

    /// Closest hit, as `Accel::intersect` answers it; `None` when no SIMD kernel runs here
    /// (the caller walks the tree).
    #[inline]
    pub(super) fn closest(&self, ray: &Ray) -> Option<Option<Hit>> {
        if !use_avx2() {
            return None;
        }
        // SAFETY: AVX2 was detected on this CPU just above.
        Some(unsafe { self.closest_avx2(ray) })
    }

    /// Occlusion, as `Accel::occluded` answers it; `None` when no SIMD kernel runs here.
    #[inline]
    pub(super) fn occluded(&self, ray: &Ray) -> Option<bool> {
        if !use_avx2() {
            return None;
        }
        // SAFETY: AVX2 was detected on this CPU just above.
        Some(unsafe { self.occluded_avx2(ray) })
    }

    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn closest_avx2(&self, ray: &Ray) -> Option<Hit> {
        let ray = &read_by_field(ray);
        if !ray_is_valid(ray) {
            return None;
        }
        let lr = LaneRay8::new(ray);
        // The scalar test's ray, made only when a slow lane needs it (rare).
        let mut woop: Option<WoopRay> = None;
        let mut best: Option<(usize, f32, f32)> = None;
        let mut best_t = ray.t_max;
        let mut best_prim = u32::MAX;
        // One scratch per ray: the group tests write only the lanes they report.
        let mut lanes = Lanes::MISS;
        for (gi, g) in self.groups.iter().enumerate() {
            lr.test(g, best_t, &mut lanes);
            let mut todo = lanes.hit | lanes.slow;
            while todo != 0 {
                let j = todo.trailing_zeros() as usize;
                todo &= todo - 1;
                let slot = gi * LANES + j;
                let (t, b1, b2) = if lanes.slow >> j & 1 != 0 {
                    let woop = woop.get_or_insert_with(|| WoopRay::new(ray.origin, ray.dir));
                    match woop.intersect(&self.tris[slot]) {
                        Some(hit) => hit,
                        None => continue,
                    }
                } else {
                    (lanes.t[j], lanes.b1[j], lanes.b2[j])
                };
                // The least (t, prim); `t == t_max` only ties with a hit found before.
                let prim = self.prims[slot];
                if t < best_t || (t == best_t && best.is_some() && prim < best_prim) {
                    best = Some((slot, b1, b2));
                    best_t = t;
                    best_prim = prim;
                }
            }
        }
        best.map(|(_, b1, b2)| Hit {
            t: best_t,
            prim: best_prim,
            b1,
            b2,
        })
    }

    /// Stops at the first group with a hit.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn occluded_avx2(&self, ray: &Ray) -> bool {
        let ray = &read_by_field(ray);
        if !ray_is_valid(ray) {
            return false;
        }
        let lr = LaneRay8::new(ray);
        let mut lanes = Lanes::MISS;
        // `t ≤ next_down(t_max)` is `t < t_max`.
        let limit = ray.t_max.next_down();
        for (gi, g) in self.groups.iter().enumerate() {
            lr.test(g, limit, &mut lanes);
            if lanes.hit != 0 {
                return true;
            }
            let mut slow = lanes.slow;
            while slow != 0 {
                let j = slow.trailing_zeros() as usize;
                slow &= slow - 1;
                if WoopRay::new(ray.origin, ray.dir)
                    .intersect(&self.tris[gi * LANES + j])
                    .is_some_and(|(t, _, _)| t < ray.t_max)
                {
                    return true;
                }
            }
        }
        false
    }
}

/// A copy of `ray` read one `f32` field at a time. The caller has just stored the ray (a
/// shadow or continuation ray made in registers), often as an 8-byte and a 4-byte store per
/// vector; a wider load across two such stores cannot be forwarded from them and waits for
/// the stores to retire (≈ 7 % of an occlusion query measured). A 4-byte load lies inside
/// whichever store wrote its field, so it is forwarded; volatile reads keep the compiler
/// from merging them into wider loads.
#[inline(always)]
fn read_by_field(ray: &Ray) -> Ray {
    // SAFETY: each pointer comes from a reference to an initialised, aligned `f32` field.
    let f = |x: &f32| unsafe { std::ptr::read_volatile(x) };
    Ray {
        origin: Vec3::new(f(&ray.origin.x), f(&ray.origin.y), f(&ray.origin.z)),
        dir: Vec3::new(f(&ray.dir.x), f(&ray.dir.y), f(&ray.dir.z)),
        t_max: f(&ray.t_max),
    }
}

/// Per-ray constants of the 8-lane (AVX2) test. Made only inside the AVX2 functions above, so
/// its methods may use AVX2.
struct LaneRay8 {
    /// The axis permutation `[kx, ky, kz]` (each < 3).
    axes: [usize; 3],
    /// The origin in the ray's axis order.
    o: [__m256; 3],
    sx: __m256,
    sy: __m256,
    sz: __m256,
}

impl LaneRay8 {
    /// The constants of `ray` (valid, [`ray_is_valid`]): [`WoopRay::new`]'s axis permutation
    /// and shear, the same bits (`−d[kx] / d[kz]`, `−d[ky] / d[kz]`, `1 / d[kz]` as one
    /// four-lane IEEE division), made in registers. Reading them out of a `WoopRay` went
    /// through memory: its origin array, indexed by the permutation, was stored and read back
    /// with loads of other widths (a failed store-to-load forward, ≈ 6 % of each query).
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        let (o, d) = (ray.origin, ray.dir);
        let a = d.abs();
        // `WoopRay::new`'s choice of the dominant axis, in its order of comparisons.
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
        // SAFETY: AVX intrinsics on values; this type exists only inside the AVX2 functions.
        unsafe {
            let idx = _mm_setr_epi32(kx as i32, ky as i32, kz as i32, kz as i32);
            let op = _mm_permutevar_ps(_mm_setr_ps(o.x, o.y, o.z, 0.0), idx);
            let dp = _mm_permutevar_ps(_mm_setr_ps(d.x, d.y, d.z, 0.0), idx);
            // (−d[kx], −d[ky], 1, 1) / d[kz]: each lane the scalar division's bits.
            let dz = _mm_shuffle_ps::<0b1010_1010>(dp, dp);
            let negated = _mm_xor_ps(dp, _mm_setr_ps(-0.0, -0.0, 0.0, 0.0));
            let num = _mm_blend_ps::<0b1100>(negated, _mm_set1_ps(1.0));
            let s = _mm_div_ps(num, dz);
            let lane = |v: __m128, i: i32| -> __m256 {
                match i {
                    0 => _mm256_broadcastss_ps(v),
                    1 => _mm256_broadcastss_ps(_mm_shuffle_ps::<0b0101_0101>(v, v)),
                    _ => _mm256_broadcastss_ps(_mm_shuffle_ps::<0b1010_1010>(v, v)),
                }
            };
            Self {
                axes: [kx, ky, kz],
                o: [lane(op, 0), lane(op, 1), lane(op, 2)],
                sx: lane(s, 0),
                sy: lane(s, 1),
                sz: lane(s, 2),
            }
        }
    }
}

impl LaneRay8 {
    /// Vertex `v` of the group's eight triangles: `(x, y, z)` translated to the origin, in
    /// the ray's axis order.
    #[inline(always)]
    fn vertex(&self, g: &Group, v: usize) -> [__m256; 3] {
        let [kx, ky, kz] = self.axes;
        // SAFETY: AVX intrinsics (AVX2 functions only); the aligned loads read the 8-float
        // arrays of a `Group`, which is 32-byte aligned with every array at a multiple of 32
        // bytes.
        unsafe {
            let load = |a: &[f32; LANES]| _mm256_load_ps(a.as_ptr());
            [
                _mm256_sub_ps(load(&g.v[v][kx]), self.o[0]),
                _mm256_sub_ps(load(&g.v[v][ky]), self.o[1]),
                _mm256_sub_ps(load(&g.v[v][kz]), self.o[2]),
            ]
        }
    }

    /// Tests the group's eight triangles into `out` (its masks are overwritten, its arrays
    /// only where `hit` is set); hits beyond `t_limit` are left out of `hit` (but not of
    /// `slow`), hits at `t_limit` are kept (ties at equal `t` go to the smaller prim).
    #[inline(always)]
    fn test(&self, g: &Group, t_limit: f32, out: &mut Lanes) {
        out.hit = 0;
        out.slow = 0;
        let [x0, y0, z0] = self.vertex(g, 0);
        let [x1, y1, z1] = self.vertex(g, 1);
        let [x2, y2, z2] = self.vertex(g, 2);
        // SAFETY: AVX intrinsics on values (AVX2 functions only); the stores write the
        // eight-float arrays of `out`.
        unsafe {
            let abs = |v: __m256| _mm256_andnot_ps(_mm256_set1_ps(-0.0), v);
            let max3 = |a: __m256, b: __m256, c: __m256| _mm256_max_ps(_mm256_max_ps(a, b), c);
            let g = |n: u32| _mm256_set1_ps(gamma(n));
            let eq = |a: __m256, b: __m256| _mm256_cmp_ps::<_CMP_EQ_OQ>(a, b);
            let lt = |a: __m256, b: __m256| _mm256_cmp_ps::<_CMP_LT_OQ>(a, b);
            let gt = |a: __m256, b: __m256| _mm256_cmp_ps::<_CMP_GT_OQ>(a, b);
            let le = |a: __m256, b: __m256| _mm256_cmp_ps::<_CMP_LE_OQ>(a, b);
            let zero = _mm256_setzero_ps();
            // Shear.
            let x0 = _mm256_add_ps(x0, _mm256_mul_ps(self.sx, z0));
            let y0 = _mm256_add_ps(y0, _mm256_mul_ps(self.sy, z0));
            let x1 = _mm256_add_ps(x1, _mm256_mul_ps(self.sx, z1));
            let y1 = _mm256_add_ps(y1, _mm256_mul_ps(self.sy, z1));
            let x2 = _mm256_add_ps(x2, _mm256_mul_ps(self.sx, z2));
            let y2 = _mm256_add_ps(y2, _mm256_mul_ps(self.sy, z2));
            // Edge functions.
            let e0 = _mm256_sub_ps(_mm256_mul_ps(x1, y2), _mm256_mul_ps(y1, x2));
            let e1 = _mm256_sub_ps(_mm256_mul_ps(x2, y0), _mm256_mul_ps(y2, x0));
            let e2 = _mm256_sub_ps(_mm256_mul_ps(x0, y1), _mm256_mul_ps(y0, x1));
            let zero_lanes = _mm256_movemask_ps(_mm256_or_ps(
                _mm256_or_ps(eq(e0, zero), eq(e1, zero)),
                eq(e2, zero),
            )) as u32;
            // Outside: two edge functions of different signs. For the lanes that matter (no
            // edge function zero, none NaN) the sign bit is the sign; a lane with a NaN edge
            // function has a NaN determinant and fails the sign test below either way.
            let outside =
                _mm256_movemask_ps(_mm256_or_ps(_mm256_xor_ps(e0, e1), _mm256_xor_ps(e0, e2)))
                    as u32;
            let inside = !outside & 0xff & !zero_lanes;
            // Most halves are missed by every lane: stop before the division.
            if zero_lanes | inside == 0 {
                return;
            }
            let det = _mm256_add_ps(_mm256_add_ps(e0, e1), e2);
            let zs0 = _mm256_mul_ps(z0, self.sz);
            let zs1 = _mm256_mul_ps(z1, self.sz);
            let zs2 = _mm256_mul_ps(z2, self.sz);
            let t_scaled = _mm256_add_ps(
                _mm256_add_ps(_mm256_mul_ps(e0, zs0), _mm256_mul_ps(e1, zs1)),
                _mm256_mul_ps(e2, zs2),
            );
            let same_sign = _mm256_or_ps(
                _mm256_and_ps(gt(det, zero), gt(t_scaled, zero)),
                _mm256_and_ps(lt(det, zero), lt(t_scaled, zero)),
            );
            let candidate = _mm256_movemask_ps(same_sign) as u32 & inside;
            // No candidate in front of the origin and nothing for the scalar test.
            if zero_lanes | candidate == 0 {
                return;
            }
            let inv_det = _mm256_div_ps(_mm256_set1_ps(1.0), det);
            let t = _mm256_mul_ps(t_scaled, inv_det);
            let max_zt = max3(abs(zs0), abs(zs1), abs(zs2));
            let delta_z = _mm256_mul_ps(g(3), max_zt);
            let max_xt = max3(abs(x0), abs(x1), abs(x2));
            let max_yt = max3(abs(y0), abs(y1), abs(y2));
            let max_z = max3(abs(z0), abs(z1), abs(z2));
            let delta_x = _mm256_mul_ps(g(5), _mm256_add_ps(max_xt, max_z));
            let delta_y = _mm256_mul_ps(g(5), _mm256_add_ps(max_yt, max_z));
            let delta_e = _mm256_mul_ps(
                _mm256_set1_ps(2.0),
                _mm256_add_ps(
                    _mm256_add_ps(
                        _mm256_mul_ps(_mm256_mul_ps(g(2), max_xt), max_yt),
                        _mm256_mul_ps(delta_y, max_xt),
                    ),
                    _mm256_mul_ps(delta_x, max_yt),
                ),
            );
            let max_e = max3(abs(e0), abs(e1), abs(e2));
            let delta_t = _mm256_mul_ps(
                _mm256_mul_ps(
                    _mm256_set1_ps(3.0),
                    _mm256_add_ps(
                        _mm256_add_ps(
                            _mm256_mul_ps(_mm256_mul_ps(g(3), max_e), max_zt),
                            _mm256_mul_ps(delta_e, max_zt),
                        ),
                        _mm256_mul_ps(delta_z, max_e),
                    ),
                ),
                abs(inv_det),
            );
            let sure = _mm256_movemask_ps(gt(t, delta_t)) as u32;
            let near = _mm256_movemask_ps(le(t, _mm256_set1_ps(t_limit))) as u32;
            let hit = candidate & sure & near;
            out.hit = hit;
            out.slow = zero_lanes | (candidate & !sure);
            if hit != 0 {
                _mm256_storeu_ps(out.t.as_mut_ptr(), t);
                _mm256_storeu_ps(out.b1.as_mut_ptr(), _mm256_mul_ps(e1, inv_det));
                _mm256_storeu_ps(out.b2.as_mut_ptr(), _mm256_mul_ps(e2, inv_det));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::brute_force_intersect;
    use super::super::bvh::build;
    use super::super::traverse;
    use super::*;
    use crate::settings::BvhQuality;

    fn bits(h: Option<Hit>) -> Option<[u32; 4]> {
        h.map(|h| [h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()])
    }

    /// The small path over `tris` in the tree's order, as `Accel::build` makes it.
    fn small(tris: &[[Vec3; 3]]) -> (SmallScene, super::super::bvh::Bvh) {
        let bvh = build(tris, BvhQuality::Medium);
        let s = SmallScene::build(&bvh.tris, usize::MAX).unwrap();
        (s, bvh)
    }

    /// Small path, brute force and tree agree bit for bit (`t`, `prim`, `b1`, `b2`) on
    /// random soups of 1 to 70 triangles (sizes that are not multiples of 8 included), on a
    /// grid so that triangles share edges and vertices and coincide (ties at equal `t`), with
    /// degenerate and non-finite triangles mixed in, and rays through vertices and edge
    /// midpoints, axis-parallel and with ±0 components, from on a triangle (t ≈ 0, the slow
    /// lanes), with finite and infinite `t_max`, and invalid rays. Occlusion likewise.
    #[test]
    fn small_path_equals_brute_force_and_tree() {
        if !use_avx2() {
            eprintln!("no AVX2 on this CPU: the tree answers");
            return;
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x5a11_5ce0_e5ee_d123u64);
        let (mut hits, mut ties, mut slow_cases, mut rays) = (0, 0, 0, 0);
        for round in 0..400 {
            let n = 1 + round % 70;
            let scale = [1e-3, 1.0, 1e4][round % 3];
            let grid = round % 2 == 0;
            let point = |rnd: &mut dyn FnMut() -> f32| {
                let p = Vec3::new(rnd(), rnd(), rnd()) * 3.0;
                (if grid { p.round() } else { p }) * scale
            };
            let mut tris: Vec<[Vec3; 3]> = (0..n)
                .map(|_| [point(&mut rnd), point(&mut rnd), point(&mut rnd)])
                .collect();
            // Coincident copies (ties), degenerate and non-finite triangles.
            if n > 4 {
                tris[n - 1] = tris[0];
                tris[n / 2] = [tris[1][0], tris[1][1], tris[1][0]];
                tris[n / 3][2].x = [f32::NAN, f32::INFINITY][round % 2];
            }
            let (s, bvh) = small(&tris);
            for i in 0..150 {
                let tri = tris[i % n];
                let origin = match i % 6 {
                    0 => tri[0] * 0.25 + tri[1] * 0.5 + tri[2] * 0.25,
                    _ => point(&mut rnd) * 1.5,
                };
                let target = match i % 5 {
                    0 => tri[i % 3],
                    1 => (tri[0] + tri[1]) * 0.5,
                    _ => point(&mut rnd),
                };
                let mut dir = target - origin;
                match i % 11 {
                    0 => dir = Vec3::new(0.0, -0.0, [1.0, -1.0][round % 2]),
                    1 => dir.y = -0.0,
                    2 => dir = Vec3::new(rnd(), 0.0, 0.0),
                    3 => dir = Vec3::ZERO,
                    _ => {}
                }
                let t_max = match i % 4 {
                    0 => f32::INFINITY,
                    1 => 0.5 + rnd().abs(),
                    2 => 1.0,
                    _ => 1e30,
                };
                let ray = Ray { origin, dir, t_max };
                let got = s.closest(&ray).unwrap();
                let want = brute_force_intersect(&tris, &ray);
                assert_eq!(bits(got), bits(want), "{ray:?} in {tris:?}");
                assert_eq!(bits(got), bits(traverse::closest(&bvh, &ray)), "{ray:?}");
                assert_eq!(s.occluded(&ray).unwrap(), want.is_some(), "{ray:?}");
                assert_eq!(
                    s.occluded(&ray).unwrap(),
                    traverse::occluded(&bvh, &ray),
                    "{ray:?}"
                );
                rays += 1;
                hits += usize::from(want.is_some());
                if let Some(h) = want {
                    let copies = tris.iter().filter(|t| **t == tris[h.prim as usize]).count();
                    ties += usize::from(copies > 1);
                    slow_cases += usize::from(i % 6 == 0);
                }
            }
        }
        // Not vacuous: many hits, ties between coincident copies, hits from on a surface.
        assert!(hits > 20_000, "{hits} of {rays}");
        assert!(ties > 500, "{ties}");
        assert!(slow_cases > 1_000, "{slow_cases}");
    }

    /// The lanes of a `LaneRay8` (`o`, `sx`, `sy`, `sz`), as bits.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn lane_ray_bits(ray: &Ray) -> ([usize; 3], [[u32; LANES]; 6]) {
        let lr = LaneRay8::new(&read_by_field(ray));
        let bits = |v: __m256| {
            let mut a = [0.0f32; LANES];
            // SAFETY: an unaligned store of eight floats into an eight-float array.
            unsafe { _mm256_storeu_ps(a.as_mut_ptr(), v) };
            a.map(f32::to_bits)
        };
        let [o0, o1, o2] = lr.o;
        (
            lr.axes,
            [
                bits(o0),
                bits(o1),
                bits(o2),
                bits(lr.sx),
                bits(lr.sy),
                bits(lr.sz),
            ],
        )
    }

    /// The per-ray lane constants made in registers equal `WoopRay::new`'s axis permutation,
    /// origin and shear bit for bit in every lane: random directions (each axis dominant,
    /// ties between components, ±0, subnormal and huge components) and origins.
    #[test]
    fn lane_ray_constants_equal_the_scalar_woop_ray() {
        if !use_avx2() {
            return;
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x1a9e_5eed_0000_0017u64);
        for i in 0..20_000 {
            let mut d = Vec3::new(rnd(), rnd(), rnd());
            match i % 9 {
                0 => d = Vec3::splat(d.x),
                1 => d.y = d.x,
                2 => d.z = -d.y,
                3 => d = Vec3::new(0.0, -0.0, d.z),
                4 => d.x = f32::from_bits(1),
                5 => d *= 1e30,
                6 => d *= 1e-30,
                _ => {}
            }
            let origin = Vec3::new(rnd(), rnd(), rnd()) * [1e-3, 1.0, 1e4][i % 3];
            let ray = Ray {
                origin,
                dir: d,
                t_max: f32::INFINITY,
            };
            if !ray_is_valid(&ray) {
                continue;
            }
            let woop = WoopRay::new(ray.origin, ray.dir);
            let axes = woop.axes();
            let o = woop.origin();
            let (sx, sy, sz) = woop.shear();
            let want =
                [o[axes[0]], o[axes[1]], o[axes[2]], sx, sy, sz].map(|x| [x.to_bits(); LANES]);
            // SAFETY: AVX2 was detected above.
            let got = unsafe { lane_ray_bits(&ray) };
            assert_eq!(got, (axes, want), "{ray:?}");
        }
    }

    /// Ties at equal `t` go to the smallest prim even when the tree's order puts a larger
    /// prim first: four copies of one triangle among others, every order of the copies.
    #[test]
    fn ties_go_to_the_smallest_prim() {
        if !use_avx2() {
            return;
        }
        let wall = [
            Vec3::new(-1.0, -1.0, 2.0),
            Vec3::new(3.0, -1.0, 2.0),
            Vec3::new(-1.0, 3.0, 2.0),
        ];
        for first in 0..19 {
            let mut tris: Vec<[Vec3; 3]> = (0..19)
                .map(|i| {
                    let c = Vec3::new(i as f32 * 3.0 + 10.0, 0.0, 0.0);
                    [c, c + Vec3::X, c + Vec3::Y]
                })
                .collect();
            for k in [first, (first + 5) % 19, (first + 11) % 19, 18] {
                tris[k] = wall;
            }
            let smallest = first.min((first + 5) % 19).min((first + 11) % 19);
            let (s, _) = small(&tris);
            let ray = Ray {
                origin: Vec3::new(0.1, 0.2, 0.0),
                dir: Vec3::Z,
                t_max: f32::INFINITY,
            };
            let hit = s.closest(&ray).unwrap().unwrap();
            assert_eq!((hit.prim, hit.t), (smallest as u32, 2.0));
            // t_max exclusive: a segment ending on the wall sees nothing.
            let short = Ray { t_max: 2.0, ..ray };
            assert!(s.closest(&short).unwrap().is_none() && !s.occluded(&short).unwrap());
        }
    }

    /// A closed low-resolution sphere (32 triangles, at the threshold): rays from inside
    /// aimed exactly at vertices and edge midpoints never leak, and hit what brute force hits.
    #[test]
    fn closed_small_mesh_does_not_leak() {
        if !use_avx2() {
            return;
        }
        let (rings, segs) = (3, 8);
        let v = |r: usize, k: usize| {
            let th = std::f32::consts::PI * r as f32 / rings as f32;
            let ph = std::f32::consts::TAU * k as f32 / segs as f32;
            Vec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()) * 2.0
        };
        let mut tris = Vec::new();
        for r in 0..rings {
            for k in 0..segs {
                let (a, b, c, d) = (v(r, k), v(r, k + 1), v(r + 1, k), v(r + 1, k + 1));
                if r > 0 {
                    tris.push([a, b, c]);
                }
                if r + 1 < rings {
                    tris.push([b, d, c]);
                }
            }
        }
        assert!(tris.len() <= DEFAULT_MAX_TRIANGLES, "{}", tris.len());
        let (s, _) = small(&tris);
        let o = Vec3::new(0.1, -0.05, 0.2);
        let mut misses = 0;
        for tri in &tris {
            for target in [tri[0], tri[1], tri[2], (tri[0] + tri[1]) * 0.5] {
                let ray = Ray {
                    origin: o,
                    dir: target - o,
                    t_max: f32::INFINITY,
                };
                let got = s.closest(&ray).unwrap();
                assert_eq!(bits(got), bits(brute_force_intersect(&tris, &ray)));
                misses += usize::from(got.is_none() || !s.occluded(&ray).unwrap());
            }
        }
        assert_eq!(misses, 0);
    }

    /// Threshold and the degenerate ones: more than `max` triangles make no small path;
    /// degenerate triangles take no slot, and only they make an all-miss scene.
    #[test]
    fn build_threshold_and_degenerate_slots() {
        let t = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let leaf = LeafTri::numbered;
        assert!(SmallScene::build(&leaf(&[t; 9]), 8).is_none());
        let s = SmallScene::build(&leaf(&[t; 9]), 9).unwrap();
        assert_eq!((s.groups.len(), s.tris.len()), (2, 9));
        let degenerate = [[Vec3::ONE; 3], [Vec3::NAN, Vec3::X, Vec3::Y], t];
        let s = SmallScene::build(&leaf(&degenerate), 64).unwrap();
        assert_eq!((s.prims.as_slice(), s.groups.len()), ([2].as_slice(), 1));
    }

    /// Through `Accel`: a small mesh is answered by this path, and every query — plain and by
    /// ray kind with per-triangle masks (`ray_kind.rs` steps over hidden surfaces through
    /// `intersect`/`occluded`) — answers as the same `Accel` with the tree only.
    #[test]
    fn accel_queries_and_ray_kinds_equal_the_tree() {
        use super::super::{Accel, RayKind};
        use crate::components::{ALL_RAYS, CAMERA_RAYS, SECONDARY_RAYS, SHADOW_RAYS};
        let mut rnd = crate::accel::test_random::signed_uniform(0x0dd5_ca1e_b0a7_0001u64);
        let tris: Vec<[Vec3; 3]> = (0..30)
            .map(|_| {
                let c = Vec3::new(rnd(), rnd(), rnd()) * 2.0;
                let e = |r: &mut dyn FnMut() -> f32| Vec3::new(r(), r(), r()) * 0.7;
                [c, c + e(&mut rnd), c + e(&mut rnd)]
            })
            .collect();
        let masks: Vec<u8> = (0..tris.len())
            .map(|i| [ALL_RAYS, CAMERA_RAYS, SHADOW_RAYS, SECONDARY_RAYS, ALL_RAYS][i % 5])
            .collect();
        let mut small = Accel::build(tris.clone(), BvhQuality::Medium);
        assert_eq!(small.small.is_some(), max_triangles() >= tris.len());
        let mut tree = Accel::build(tris, BvhQuality::Medium);
        tree.small = None;
        small.set_ray_masks(masks.clone());
        tree.set_ray_masks(masks);
        for _ in 0..3000 {
            let ray = Ray {
                origin: Vec3::new(rnd(), rnd(), rnd()) * 3.0,
                dir: Vec3::new(rnd(), rnd(), rnd()),
                t_max: [f32::INFINITY, 2.0][usize::from(rnd() > 0.0)],
            };
            assert_eq!(bits(small.intersect(&ray)), bits(tree.intersect(&ray)));
            assert_eq!(small.occluded(&ray), tree.occluded(&ray));
            for kind in [RayKind::Camera, RayKind::Shadow, RayKind::Secondary] {
                assert_eq!(
                    bits(small.intersect_as(&ray, kind)),
                    bits(tree.intersect_as(&ray, kind))
                );
                assert_eq!(small.occluded_as(&ray, kind), tree.occluded_as(&ray, kind));
            }
        }
    }

    /// `glass.ron`'s floor and a glass block's bottom face are coplanar (y = 0); a ray
    /// crossing both gets two `t`s a few ulps apart from the watertight test (each triangle is
    /// translated to the ray origin on its own). The small path returns the least, as brute
    /// force does; the tree (main 7f32217) returns the block face, whose `t` is larger — its
    /// box test culls the floor's node once the block face is found (`docs/ray-layer.md`,
    /// issue 17, session 15).
    #[test]
    fn coplanar_faces_give_the_least_t_as_brute_force() {
        if !use_avx2() {
            return;
        }
        let v = |b: [u32; 3]| Vec3::from_array(b.map(f32::from_bits));
        let floor = [
            v([3240099840, 0, 3240099840]),
            v([3240099840, 0, 1092616192]),
            v([1092616192, 0, 1092616192]),
        ];
        let block = [
            v([3219547750, 0, 3209481421]),
            v([3192704205, 0, 1061997773]),
            v([3219547750, 0, 1061997773]),
        ];
        let ray = Ray {
            origin: v([3219547744, 1012082997, 1033915251]),
            dir: v([1038690154, 3194083262, 1064828243]),
            t_max: f32::INFINITY,
        };
        let mut tris = vec![floor];
        tris.extend((1..15).map(|i| {
            let c = Vec3::new(50.0 + i as f32, 5.0, 0.0);
            [c, c + Vec3::X, c + Vec3::Y]
        }));
        tris.push(block);
        let (s, _) = small(&tris);
        let got = s.closest(&ray).unwrap();
        assert_eq!(bits(got), bits(brute_force_intersect(&tris, &ray)));
        let hit = got.unwrap();
        let block_t = WoopRay::new(ray.origin, ray.dir)
            .intersect(&block)
            .unwrap()
            .0;
        assert!(hit.prim == 0 && hit.t < block_t, "{hit:?} {block_t}");
    }
}
