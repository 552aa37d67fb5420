//! The small-scene path (x86-64, AVX2 at run time): when the whole mesh has few triangles,
//! single-ray closest-hit and occlusion queries test every triangle in SIMD lanes instead of
//! walking the tree — no node tests, no stack, no leaf gathers.
//!
//! * **Layout**: the non-degenerate triangles, in the caller's order, are kept
//!   pre-transposed in groups of sixteen (structure of arrays: per vertex, per axis, sixteen
//!   lanes; one triangle per lane), which the AVX2 kernel reads as two halves of eight and
//!   the AVX-512 kernel (`small_scene/avx512.rs`) in one register. A ray's axis permutation (`WoopRay`) picks which axis
//!   arrays a lane reads, so no triangle is shuffled per ray. Spare lanes of the last group
//!   hold NaN vertices, which every lane test answers as a miss (NaN edge functions make the
//!   determinant NaN, which fails the sign test, and `NaN == 0` is false, so the lane is not
//!   sent to the scalar test either).
//! * **Same answers, bit for bit**: each lane makes [`WoopRay::intersect`]'s IEEE operations
//!   in its order (subtract, shear, edge functions, determinant, `t`, the conservative `δt`
//!   bound; no fused multiply-add, an exact division), as `leaf_wide.rs` does for four lanes.
//!   The lanes the scalar test would finish in `f64` (an edge function exactly zero; `t ≤ δt`)
//!   are *slow* and are decided by the scalar test itself. The closest hit is the least
//!   `(t, prim)` among hits with `0 < t < t_max`: groups and lanes run in ascending `prim`
//!   order and only a strictly smaller `t` replaces the best, so a tie goes to the smallest
//!   `prim` — what the tree and `brute.rs` return. Occlusion stops at the first group with a
//!   hit below `t_max`.
//! * **Dispatch** ([`SmallScene::closest`], [`SmallScene::occluded`]): AVX-512 (F) when the
//!   CPU has it and `STAGELIGHT_TRAVERSAL=avx2…` is not set, else AVX2; `None` when the CPU
//!   lacks AVX2 or `STAGELIGHT_TRAVERSAL=sse…` was set at the first query; the caller then
//!   walks the tree. [`SmallScene::build`] makes the path only for meshes of at most
//!   [`max_triangles`] triangles (`STAGELIGHT_SMALL_SCENE=N` overrides the threshold, `0`
//!   turns the path off; for A/B runs).

use std::arch::x86_64::{
    __m256, _mm256_add_ps, _mm256_and_ps, _mm256_andnot_ps, _mm256_cmp_ps, _mm256_div_ps,
    _mm256_load_ps, _mm256_max_ps, _mm256_movemask_ps, _mm256_mul_ps, _mm256_or_ps, _mm256_set1_ps,
    _mm256_setzero_ps, _mm256_storeu_ps, _mm256_sub_ps, _mm256_xor_ps, _CMP_EQ_OQ, _CMP_GT_OQ,
    _CMP_LT_OQ,
};
use std::sync::OnceLock;

use glam::Vec3;

use super::triangle::{gamma, is_degenerate, ray_is_valid, WoopRay};
use super::{Hit, Ray};

mod avx512;

/// Triangles per group (one per AVX-512 lane, two halves of AVX2 lanes).
const LANES: usize = 16;

/// The default largest mesh (triangles given to `Accel::build`) answered without the tree;
/// measured in `docs/ray-layer.md` (issue 17, session 15).
pub(super) const DEFAULT_MAX_TRIANGLES: usize = 64;

/// The largest mesh answered without the tree: `STAGELIGHT_SMALL_SCENE=N` when set to a
/// number (0 turns the path off), else [`DEFAULT_MAX_TRIANGLES`].
pub(super) fn max_triangles() -> usize {
    std::env::var("STAGELIGHT_SMALL_SCENE")
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(DEFAULT_MAX_TRIANGLES)
}

/// The kernel this CPU runs, chosen once.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kernel {
    /// No AVX2, or `STAGELIGHT_TRAVERSAL=sse…`: the caller walks the tree.
    Tree,
    Avx2,
    Avx512,
}

fn kernel() -> Kernel {
    static CHOICE: OnceLock<Kernel> = OnceLock::new();
    *CHOICE.get_or_init(|| {
        let env = std::env::var("STAGELIGHT_TRAVERSAL").unwrap_or_default();
        if !std::arch::is_x86_feature_detected!("avx2") || env.starts_with("sse") {
            Kernel::Tree
        } else if std::arch::is_x86_feature_detected!("avx512f") && !env.starts_with("avx2") {
            Kernel::Avx512
        } else {
            Kernel::Avx2
        }
    })
}

/// Sixteen triangles transposed: `v[vertex][axis][lane]`.
#[derive(Clone, Copy)]
#[repr(C, align(64))]
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

/// A group test with per-ray constants (made only inside the `target_feature` functions of
/// its kernel).
trait GroupTest {
    fn new(woop: &WoopRay) -> Self;
    /// Tests the group's sixteen triangles into `out` (its masks are overwritten, its arrays
    /// only where `hit` is set); hits at or beyond `t_limit` are left out of `hit` (but not
    /// of `slow`).
    fn test(&self, g: &Group, t_limit: f32, out: &mut Lanes);
}

/// Every non-degenerate triangle of a small mesh in lane groups.
pub(super) struct SmallScene {
    groups: Vec<Group>,
    /// The same triangles, slot by slot (for the scalar test of slow lanes).
    tris: Vec<[Vec3; 3]>,
    /// The caller's index of each slot (ascending).
    prims: Vec<u32>,
}

impl SmallScene {
    /// The lane groups of `triangles` (degenerate ones left out), or `None` when the mesh has
    /// more than `max` triangles.
    pub(super) fn build(triangles: &[[Vec3; 3]], max: usize) -> Option<Self> {
        if triangles.len() > max {
            return None;
        }
        let (prims, tris): (Vec<u32>, Vec<[Vec3; 3]>) = triangles
            .iter()
            .enumerate()
            .filter(|(_, t)| !is_degenerate(t))
            .map(|(i, t)| (i as u32, *t))
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
        match kernel() {
            // SAFETY: AVX-512F (and AVX2) were detected on this CPU.
            Kernel::Avx512 => Some(unsafe { avx512::closest(self, ray) }),
            // SAFETY: AVX2 was detected on this CPU.
            Kernel::Avx2 => Some(unsafe { self.closest_avx2(ray) }),
            Kernel::Tree => None,
        }
    }

    /// Occlusion, as `Accel::occluded` answers it; `None` when no SIMD kernel runs here.
    #[inline]
    pub(super) fn occluded(&self, ray: &Ray) -> Option<bool> {
        match kernel() {
            // SAFETY: AVX-512F (and AVX2) were detected on this CPU.
            Kernel::Avx512 => Some(unsafe { avx512::occluded(self, ray) }),
            // SAFETY: AVX2 was detected on this CPU.
            Kernel::Avx2 => Some(unsafe { self.occluded_avx2(ray) }),
            Kernel::Tree => None,
        }
    }

    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn closest_avx2(&self, ray: &Ray) -> Option<Hit> {
        self.closest_with::<LaneRay8>(ray)
    }

    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn occluded_avx2(&self, ray: &Ray) -> bool {
        self.occluded_with::<LaneRay8>(ray)
    }

    /// The closest hit with the group test `K`.
    #[inline(always)]
    fn closest_with<K: GroupTest>(&self, ray: &Ray) -> Option<Hit> {
        if !ray_is_valid(ray) {
            return None;
        }
        let woop = WoopRay::new(ray.origin, ray.dir);
        let lr = K::new(&woop);
        let mut best: Option<(usize, f32, f32)> = None;
        let mut best_t = ray.t_max;
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
                    match woop.intersect(&self.tris[slot]) {
                        Some(hit) => hit,
                        None => continue,
                    }
                } else {
                    (lanes.t[j], lanes.b1[j], lanes.b2[j])
                };
                // Ascending slots: a tie keeps the smaller prim.
                if t < best_t {
                    best = Some((slot, b1, b2));
                    best_t = t;
                }
            }
        }
        best.map(|(slot, b1, b2)| Hit {
            t: best_t,
            prim: self.prims[slot],
            b1,
            b2,
        })
    }

    /// Occlusion with the group test `K`: stops at the first group with a hit.
    #[inline(always)]
    fn occluded_with<K: GroupTest>(&self, ray: &Ray) -> bool {
        if !ray_is_valid(ray) {
            return false;
        }
        let woop = WoopRay::new(ray.origin, ray.dir);
        let lr = K::new(&woop);
        let mut lanes = Lanes::MISS;
        for (gi, g) in self.groups.iter().enumerate() {
            lr.test(g, ray.t_max, &mut lanes);
            if lanes.hit != 0 {
                return true;
            }
            let mut slow = lanes.slow;
            while slow != 0 {
                let j = slow.trailing_zeros() as usize;
                slow &= slow - 1;
                if woop
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

/// Per-ray constants of the 8-lane (AVX2) test, which takes a group as two halves.
struct LaneRay8 {
    /// The axis permutation `[kx, ky, kz]` (each < 3).
    axes: [usize; 3],
    /// The origin in the ray's axis order.
    o: [__m256; 3],
    sx: __m256,
    sy: __m256,
    sz: __m256,
}

impl GroupTest for LaneRay8 {
    #[inline(always)]
    fn new(woop: &WoopRay) -> Self {
        let [kx, ky, kz] = woop.axes();
        let axes = [kx.min(2), ky.min(2), kz.min(2)];
        let o = woop.origin();
        let (sx, sy, sz) = woop.shear();
        // SAFETY: AVX intrinsics on values; this type exists only inside the AVX2 functions.
        let splat = |x: f32| unsafe { _mm256_set1_ps(x) };
        Self {
            axes,
            o: [splat(o[axes[0]]), splat(o[axes[1]]), splat(o[axes[2]])],
            sx: splat(sx),
            sy: splat(sy),
            sz: splat(sz),
        }
    }

    #[inline(always)]
    fn test(&self, g: &Group, t_limit: f32, out: &mut Lanes) {
        out.hit = 0;
        out.slow = 0;
        self.test_half(g, 0, t_limit, out);
        self.test_half(g, 8, t_limit, out);
    }
}

impl LaneRay8 {
    /// Vertex `v` of the eight triangles from lane `first` of the group: `(x, y, z)`
    /// translated to the origin, in the ray's axis order.
    #[inline(always)]
    fn vertex(&self, g: &Group, v: usize, first: usize) -> [__m256; 3] {
        let [kx, ky, kz] = self.axes;
        // SAFETY: AVX intrinsics (AVX2 functions only); the aligned loads read eight floats
        // at lane 0 or 8 of a 16-float array of a `Group`, which is 64-byte aligned with every
        // array at a multiple of 64 bytes (`first` is 0 or 8).
        unsafe {
            let load = |a: &[f32; LANES]| _mm256_load_ps(a[first..first + 8].as_ptr());
            [
                _mm256_sub_ps(load(&g.v[v][kx]), self.o[0]),
                _mm256_sub_ps(load(&g.v[v][ky]), self.o[1]),
                _mm256_sub_ps(load(&g.v[v][kz]), self.o[2]),
            ]
        }
    }

    /// Tests lanes `first..first + 8` (`first` 0 or 8) and writes them into `out`.
    #[inline(always)]
    fn test_half(&self, g: &Group, first: usize, t_limit: f32, out: &mut Lanes) {
        let [x0, y0, z0] = self.vertex(g, 0, first);
        let [x1, y1, z1] = self.vertex(g, 1, first);
        let [x2, y2, z2] = self.vertex(g, 2, first);
        // SAFETY: AVX intrinsics on values (AVX2 functions only); the stores write eight
        // floats at lane `first` (0 or 8) of sixteen-float arrays.
        unsafe {
            let abs = |v: __m256| _mm256_andnot_ps(_mm256_set1_ps(-0.0), v);
            let max3 = |a: __m256, b: __m256, c: __m256| _mm256_max_ps(_mm256_max_ps(a, b), c);
            let g = |n: u32| _mm256_set1_ps(gamma(n));
            let eq = |a: __m256, b: __m256| _mm256_cmp_ps::<_CMP_EQ_OQ>(a, b);
            let lt = |a: __m256, b: __m256| _mm256_cmp_ps::<_CMP_LT_OQ>(a, b);
            let gt = |a: __m256, b: __m256| _mm256_cmp_ps::<_CMP_GT_OQ>(a, b);
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
            let near = _mm256_movemask_ps(lt(t, _mm256_set1_ps(t_limit))) as u32;
            let hit = candidate & sure & near;
            out.hit |= hit << first;
            out.slow |= (zero_lanes | (candidate & !sure)) << first;
            if hit != 0 {
                _mm256_storeu_ps(out.t[first..first + 8].as_mut_ptr(), t);
                _mm256_storeu_ps(
                    out.b1[first..first + 8].as_mut_ptr(),
                    _mm256_mul_ps(e1, inv_det),
                );
                _mm256_storeu_ps(
                    out.b2[first..first + 8].as_mut_ptr(),
                    _mm256_mul_ps(e2, inv_det),
                );
            }
        }
    }
}
