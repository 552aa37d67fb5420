//! The AVX2 traversal kernels (x86-64 only), selected at run time: the single-ray and batch
//! closest-hit and occlusion loops of `traverse.rs`, compiled for AVX2, with an 8-wide node
//! test (all eight children in one instruction sequence instead of two 4-wide halves).
//!
//! * **Leaves**: a leaf's triangles are tested at once in SIMD lanes (`leaf_wide.rs`), each
//!   lane bit-identical to the scalar watertight test; the SSE fallback tests them one by
//!   one.
//! * **Batches**: [`closest_batch`] and [`occluded_batch`] run the batch kernels of
//!   `traverse.rs` with the same 8-wide node test in every lane, and the lanes push the hit
//!   children as packed block stores (`block.rs`; closest hit in octant order): packed
//!   with `vpcompressq` where the CPU also has AVX-512F/VL (unless `STAGELIGHT_TRAVERSAL=avx2`),
//!   with a `vpermd` table on AVX2 (`pack.rs`; `STAGELIGHT_TRAVERSAL=avx2-loop` keeps the push
//!   loop and the sort, for A/B runs).
//! * **Single rays with AVX-512**: where the CPU has AVX-512F/VL, [`closest`] and
//!   [`occluded`] run `single512.rs`: the same loops, with the hit children stored as one
//!   compressed block instead of a push loop (and unless `STAGELIGHT_TRAVERSAL=avx2`).
//! * **Dispatch**: [`closest`] and [`occluded`] answer `None` when the CPU lacks AVX2 or
//!   the bit operations the single-ray kernels are also compiled with ([`have_bit_ops`]:
//!   `popcnt`, `bmi1`, `bmi2`, `lzcnt`; `is_x86_feature_detected!`, cached by std) or when `STAGELIGHT_TRAVERSAL=sse` (or
//!   `sse-sorted`) was set at the first query (read once; for A/B measurements); the caller then runs the SSE kernel,
//!   which stays the fallback and is tested against this one.
//! * **Same answers**: the node test makes the same operations as the SSE test, lane by lane
//!   (subtract, multiply by the exact reciprocal, `max(n, acc)`/`min(f, acc)` in the same
//!   operand order so a NaN slab is ignored in the same way, far distance times `1 + 2γ3`,
//!   ordered `≤`), so the hit mask, the traversal order and the result are those of the SSE
//!   kernel bit for bit (`wide_equals_sse` below; every BVH-vs-brute-force test runs through
//!   the dispatch).

use std::arch::x86_64::{
    __m256, __m256i, _mm256_and_si256, _mm256_cmp_ps, _mm256_loadu_ps, _mm256_loadu_si256,
    _mm256_max_ps, _mm256_min_ps, _mm256_movemask_ps, _mm256_mul_ps, _mm256_permutevar8x32_epi32,
    _mm256_permutevar8x32_ps, _mm256_set1_epi32, _mm256_set1_ps, _mm256_setr_epi32,
    _mm256_setzero_ps, _mm256_srlv_epi32, _mm256_storeu_ps, _mm256_storeu_si256, _mm256_sub_ps,
    _CMP_LE_OS,
};
use std::sync::OnceLock;

mod block;
mod pack;
mod single512;

use glam::Vec4;

use super::bvh::{Bvh, LeafTri, Node};
use super::leaf_wide::LeafRay4;
use super::traverse::{
    closest_batch_in, closest_in, occluded_batch_in, occluded_in, NodeTest, FAR_SCALE_FACTOR,
};
use super::triangle::WoopRay;
use super::{Hit, Ray};

/// Whether the CPU has the bit-manipulation instructions the single-ray kernels are compiled
/// with besides AVX2 (`popcnt`, `tzcnt`/`lzcnt`, `shlx`): every AVX2 CPU made has them; without
/// them `count_ones` is a table-and-multiply sequence of about ten instructions and
/// `trailing_zeros` a `bsf` with a zero test.
pub(super) fn have_bit_ops() -> bool {
    std::arch::is_x86_feature_detected!("popcnt")
        && std::arch::is_x86_feature_detected!("bmi1")
        && std::arch::is_x86_feature_detected!("bmi2")
        && std::arch::is_x86_feature_detected!("lzcnt")
}

/// Whether the AVX2 kernels run (AVX2 and the bit operations of [`have_bit_ops`] present,
/// and not turned off by the environment).
fn use_avx2() -> bool {
    static CHOICE: OnceLock<bool> = OnceLock::new();
    *CHOICE.get_or_init(|| {
        std::arch::is_x86_feature_detected!("avx2")
            && have_bit_ops()
            && !std::env::var("STAGELIGHT_TRAVERSAL").is_ok_and(|v| v.starts_with("sse"))
    })
}

/// Whether the AVX-512 kernels run, batch and single-ray (AVX-512F and VL present, AVX2
/// kernels on, and not turned off by `STAGELIGHT_TRAVERSAL=avx2`, for A/B runs).
fn use_avx512() -> bool {
    static CHOICE: OnceLock<bool> = OnceLock::new();
    *CHOICE.get_or_init(|| {
        use_avx2()
            && std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512vl")
            && !std::env::var("STAGELIGHT_TRAVERSAL").is_ok_and(|v| v.starts_with("avx2"))
    })
}

/// Whether the AVX2 batch kernels (without AVX-512) push hit children as block stores
/// (`block.rs`) rather than in a loop over the hit mask: on unless
/// `STAGELIGHT_TRAVERSAL=avx2-loop` (for A/B runs; read once). The single-ray AVX2 kernels
/// keep their loop: the same block step measured 0.91–0.93× on coherent rays
/// (`docs/ray-layer.md`, session 23).
fn use_avx2_block() -> bool {
    static CHOICE: OnceLock<bool> = OnceLock::new();
    *CHOICE.get_or_init(|| {
        !std::env::var("STAGELIGHT_TRAVERSAL").is_ok_and(|v| v.starts_with("avx2-loop"))
    })
}

/// Closest hit with the AVX-512 or AVX2 kernel; `None` when neither runs here (the caller
/// falls back).
#[inline]
pub(super) fn closest(bvh: &Bvh, ray: &Ray) -> Option<Option<Hit>> {
    if use_avx512() {
        // SAFETY: AVX2, AVX-512F, AVX-512VL and the bit operations were detected on this
        // CPU just above (`use_avx512` implies `use_avx2`).
        return Some(unsafe { single512::closest_avx512(bvh, ray) });
    }
    if !use_avx2() {
        return None;
    }
    // SAFETY: AVX2 and the bit operations were detected on this CPU just above.
    Some(unsafe { closest_avx2(bvh, ray) })
}

/// Occlusion with the AVX-512 or AVX2 kernel; `None` when neither runs here.
#[inline]
pub(super) fn occluded(bvh: &Bvh, ray: &Ray) -> Option<bool> {
    if use_avx512() {
        // SAFETY: AVX2, AVX-512F, AVX-512VL and the bit operations were detected on this
        // CPU just above (`use_avx512` implies `use_avx2`).
        return Some(unsafe { single512::occluded_avx512(bvh, ray) });
    }
    if !use_avx2() {
        return None;
    }
    // SAFETY: AVX2 and the bit operations were detected on this CPU just above.
    Some(unsafe { occluded_avx2(bvh, ray) })
}

/// Closest hits of a batch with the AVX2 node test in every lane; false (nothing written)
/// when the AVX2 kernels do not run here.
#[inline]
pub(super) fn closest_batch(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>]) -> bool {
    if use_avx512() {
        // SAFETY: AVX2, AVX-512F, AVX-512VL and the bit operations were detected on this
        // CPU just above (`use_avx512` implies `use_avx2`).
        unsafe { block::closest_batch_avx512(bvh, rays, out) };
        return true;
    }
    if !use_avx2() {
        return false;
    }
    // SAFETY: AVX2 and the bit operations were detected on this CPU just above.
    unsafe {
        if use_avx2_block() {
            block::closest_batch_block_avx2(bvh, rays, out);
        } else {
            closest_batch_avx2(bvh, rays, out);
        }
    }
    true
}

/// Occlusion of a batch with the AVX2 node test; false (nothing written) when it does not
/// run here.
#[inline]
pub(super) fn occluded_batch(bvh: &Bvh, rays: &[Ray], out: &mut [bool]) -> bool {
    if use_avx512() {
        // SAFETY: AVX2, AVX-512F, AVX-512VL and the bit operations were detected on this
        // CPU just above (`use_avx512` implies `use_avx2`).
        unsafe { block::occluded_batch_avx512(bvh, rays, out) };
        return true;
    }
    if !use_avx2() {
        return false;
    }
    // SAFETY: AVX2 and the bit operations were detected on this CPU just above.
    unsafe {
        if use_avx2_block() {
            block::occluded_batch_block_avx2(bvh, rays, out);
        } else {
            occluded_batch_avx2(bvh, rays, out);
        }
    }
    true
}

/// # Safety
/// The CPU must support AVX2 and the bit operations of [`have_bit_ops`].
#[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
unsafe fn closest_batch_avx2(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>]) {
    closest_batch_in::<NodeRay8>(bvh, rays, out);
}

/// # Safety
/// The CPU must support AVX2 and the bit operations of [`have_bit_ops`].
#[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
unsafe fn occluded_batch_avx2(bvh: &Bvh, rays: &[Ray], out: &mut [bool]) {
    occluded_batch_in::<NodeRay8>(bvh, rays, out);
}

/// # Safety
/// The CPU must support AVX2 and the bit operations of [`have_bit_ops`].
#[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
unsafe fn closest_avx2(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
    closest_in::<NodeRay8>(bvh, ray)
}

/// # Safety
/// The CPU must support AVX2 and the bit operations of [`have_bit_ops`].
#[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
unsafe fn occluded_avx2(bvh: &Bvh, ray: &Ray) -> bool {
    occluded_in::<NodeRay8>(bvh, ray)
}

/// Per-ray constants of the 8-wide slab test. Only made inside the AVX2 kernels above (the
/// type is private to this file), so its methods may use AVX.
struct NodeRay8 {
    o: [__m256; 3],
    inv: [__m256; 3],
    /// Per axis, the byte offset in [`Node::bounds`] of the plane the ray enters (exits)
    /// through: `32 · (2a + sign)`, below `6 · 32`, so the plane loads need no bounds check
    /// (the batch lanes reload these from their state at every node, where a checked index
    /// cost a compare and a branch per plane).
    near: [usize; 3],
    far: [usize; 3],
    /// The leaf test's constants (`leaf_wide.rs`).
    leaf: LeafRay4,
}

impl NodeTest for NodeRay8 {
    #[inline(always)]
    fn new(ray: &Ray, woop: &WoopRay) -> Self {
        let inv = ray.dir.recip();
        let d = ray.dir.to_array();
        // Written out: `array::map` is not inlined into the AVX2 kernels (a call and a
        // `vzeroupper` per ray).
        const PLANE: usize = std::mem::size_of::<[Vec4; 2]>();
        let near_plane = |a: usize| PLANE * (2 * a + usize::from(d[a].is_sign_negative()));
        let near = [near_plane(0), near_plane(1), near_plane(2)];
        // SAFETY: `_mm256_set1_ps` needs AVX; this type exists only inside the AVX2 kernels.
        let splat = |x: f32| unsafe { _mm256_set1_ps(x) };
        Self {
            o: [
                splat(ray.origin.x),
                splat(ray.origin.y),
                splat(ray.origin.z),
            ],
            inv: [splat(inv.x), splat(inv.y), splat(inv.z)],
            near,
            far: [near[0] ^ PLANE, near[1] ^ PLANE, near[2] ^ PLANE],
            leaf: LeafRay4::new(woop),
        }
    }

    /// The leaf's triangles in SIMD lanes (`leaf_wide.rs`); the lanes the vector test cannot
    /// decide are finished by the scalar test, so every reported hit is the scalar one.
    #[inline(always)]
    fn leaf_hits(
        &self,
        woop: &WoopRay,
        tris: &[LeafTri],
        t_limit: f32,
        mut f: impl FnMut(usize, (f32, f32, f32)) -> bool,
    ) {
        let lanes = self.leaf.test(tris);
        let mut todo = lanes.hit | lanes.slow;
        while todo != 0 {
            let j = todo.trailing_zeros() as usize;
            todo &= todo - 1;
            let hit = if lanes.slow >> j & 1 != 0 {
                match woop.intersect(&tris[j].v) {
                    Some(hit) => hit,
                    None => continue,
                }
            } else {
                (lanes.t[j], lanes.b1[j], lanes.b2[j])
            };
            if hit.0 <= t_limit && f(j, hit) {
                return;
            }
        }
    }

    #[inline(always)]
    fn intersect(&self, node: &Node, t_far: f32) -> (u32, [f32; 8]) {
        let (hit, tn) = self.test(node, t_far);
        // SAFETY: AVX intrinsics; this type exists only inside the AVX2 kernels.
        unsafe {
            let mut entry = [0f32; 8];
            _mm256_storeu_ps(entry.as_mut_ptr(), tn);
            (_mm256_movemask_ps(hit) as u32, entry)
        }
    }

    /// The permutation in registers: the order word's eight 3-bit fields become lane indices
    /// (variable shifts), and the hit lanes, entry distances and child references are
    /// permuted with `vpermps`/`vpermd`.
    #[inline(always)]
    fn intersect_ordered(&self, node: &Node, t_far: f32, order: u32) -> (u32, [f32; 8], [u32; 8]) {
        let (hit, tn) = self.test(node, t_far);
        // SAFETY: AVX2 intrinsics; this type exists only inside the AVX2 kernels. The
        // unaligned load reads the node's `[u32; 8]` child array through a reference to it,
        // the stores write local arrays of the same size.
        unsafe {
            let lanes = _mm256_and_si256(
                _mm256_srlv_epi32(
                    _mm256_set1_epi32(order as i32),
                    _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21),
                ),
                _mm256_set1_epi32(7),
            );
            let mask = _mm256_movemask_ps(_mm256_permutevar8x32_ps(hit, lanes)) as u32;
            let mut t = [0f32; 8];
            _mm256_storeu_ps(t.as_mut_ptr(), _mm256_permutevar8x32_ps(tn, lanes));
            let child = _mm256_loadu_si256(std::ptr::from_ref(&node.child).cast::<__m256i>());
            let mut r = [0u32; 8];
            _mm256_storeu_si256(
                r.as_mut_ptr().cast::<__m256i>(),
                _mm256_permutevar8x32_epi32(child, lanes),
            );
            (mask, t, r)
        }
    }
}

impl NodeRay8 {
    /// The slab test proper: the hit lanes (all ones where a child is entered) and the entry
    /// distances.
    #[inline(always)]
    fn test(&self, node: &Node, t_far: f32) -> (__m256, __m256) {
        let (tn, tf) = self.slabs(node, t_far);
        // SAFETY: AVX intrinsics; this type exists only inside the AVX2 kernels.
        unsafe { (_mm256_cmp_ps::<_CMP_LE_OS>(tn, tf), tn) }
    }

    /// The entry and (scaled) exit distances of the eight children: child `i` is entered
    /// when `tn[i] ≤ tf[i]` (ordered).
    #[inline(always)]
    fn slabs(&self, node: &Node, t_far: f32) -> (__m256, __m256) {
        // SAFETY: AVX intrinsics; this type exists only inside the AVX2 kernels. Each load
        // reads one plane of the node, `bounds[k]` (two `Vec4`s, 32 bytes) at byte offset
        // `32 k` from the array's start, `k < 6` (`near`/`far`: made only by `new`).
        unsafe {
            let bounds = std::ptr::from_ref(&node.bounds).cast::<u8>();
            let plane = |offset: usize| -> __m256 {
                debug_assert!(
                    offset.is_multiple_of(32) && offset < std::mem::size_of_val(&node.bounds)
                );
                _mm256_loadu_ps(bounds.add(offset).cast())
            };
            let mut tn = _mm256_setzero_ps();
            let mut tf = _mm256_set1_ps(t_far);
            for a in 0..3 {
                let n = _mm256_mul_ps(_mm256_sub_ps(plane(self.near[a]), self.o[a]), self.inv[a]);
                let f = _mm256_mul_ps(_mm256_sub_ps(plane(self.far[a]), self.o[a]), self.inv[a]);
                // `max(n, acc)` returns `acc` when either is NaN, as SSE `maxps` does.
                tn = _mm256_max_ps(n, tn);
                tf = _mm256_min_ps(f, tf);
            }
            (tn, _mm256_mul_ps(tf, _mm256_set1_ps(FAR_SCALE_FACTOR)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::bvh::build;
    use super::super::traverse::NodeRay;
    use super::*;
    use crate::settings::BvhQuality;
    use glam::Vec3;

    fn hit_bits(h: Option<Hit>) -> Option<[u32; 4]> {
        h.map(|h| [h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()])
    }

    /// The AVX2 kernels (when this CPU has AVX2) give the SSE fallback's answers bit for bit,
    /// and the same node masks, on a soup with axis-parallel, zero-component (both signs),
    /// on-plane and finite-`t_max` rays; the fallback is forced by calling it directly.
    /// A soup of 4,000 triangles (half on the integer grid) and 3,000 rays with
    /// axis-parallel, zero-component (both signs), on-plane and finite-`t_max` cases.
    pub(super) fn soup_and_rays() -> (Vec<[Vec3; 3]>, Vec<Ray>) {
        let mut rnd = crate::accel::test_random::signed_uniform(0x9e37_79b9_7f4a_7c15u64);
        let tris: Vec<[Vec3; 3]> = (0..4000)
            .map(|i| {
                // Half the triangles on the integer grid, so rays run along box planes.
                let c = if i % 2 == 0 {
                    Vec3::new(rnd(), rnd(), rnd()) * 4.0
                } else {
                    (Vec3::new(rnd(), rnd(), rnd()) * 4.0).round()
                };
                [c, c + Vec3::X * 0.5, c + Vec3::new(0.0, 0.5, rnd() * 0.5)]
            })
            .collect();
        let mut rays = Vec::new();
        for i in 0..3000 {
            let origin = if i % 3 == 0 {
                (Vec3::new(rnd(), rnd(), rnd()) * 5.0).round()
            } else {
                Vec3::new(rnd(), rnd(), rnd()) * 5.0
            };
            let mut dir = Vec3::new(rnd(), rnd(), rnd());
            match i % 5 {
                0 => dir = Vec3::new(0.0, -0.0, 1.0),
                1 => dir = Vec3::new(-0.0, rnd(), 0.0),
                2 => dir.x = 0.0,
                _ => {}
            }
            let t_max = if i % 4 == 0 {
                rnd().abs() * 3.0
            } else {
                f32::INFINITY
            };
            rays.push(Ray { origin, dir, t_max });
        }
        (tris, rays)
    }

    /// The single-ray AVX2 kernels compiled without the bit operations (the kernels before
    /// session 20), for [`wide_equals_sse`].
    #[target_feature(enable = "avx2")]
    unsafe fn plain_avx2(bvh: &Bvh, ray: &Ray) -> (Option<Hit>, bool) {
        (
            closest_in::<NodeRay8>(bvh, ray),
            occluded_in::<NodeRay8>(bvh, ray),
        )
    }

    /// The AVX2 batch kernels compiled without the bit operations (as before session 21),
    /// for [`wide_equals_sse`].
    #[target_feature(enable = "avx2")]
    unsafe fn plain_batch_avx2(
        bvh: &Bvh,
        rays: &[Ray],
        hits: &mut [Option<Hit>],
        occ: &mut [bool],
    ) {
        closest_batch_in::<NodeRay8>(bvh, rays, hits);
        occluded_batch_in::<NodeRay8>(bvh, rays, occ);
    }

    /// The AVX2 kernels answer as the SSE kernel bit for bit (closest hit in octant and
    /// sorted order, occlusion, node masks and permutations), and the single-ray and batch
    /// kernels compiled with the bit operations (`popcnt`, `tzcnt`, …) as those compiled
    /// without.
    #[test]
    fn wide_equals_sse() {
        if !(std::arch::is_x86_feature_detected!("avx2") && have_bit_ops()) {
            eprintln!(
                "no AVX2 (or no POPCNT/BMI1/BMI2/LZCNT) on this CPU: only the SSE kernel runs"
            );
            return;
        }
        let (tris, rays) = soup_and_rays();
        for q in [BvhQuality::Fast, BvhQuality::Medium] {
            let bvh = build(&tris, q);
            let mut hits = 0;
            for r in &rays {
                // SAFETY: AVX2 and the bit operations were detected above.
                let (wide_hit, wide_occ) =
                    unsafe { (closest_avx2(&bvh, r), occluded_avx2(&bvh, r)) };
                // SAFETY: AVX2 was detected above.
                let (plain_hit, plain_occ) = unsafe { plain_avx2(&bvh, r) };
                assert_eq!(
                    (hit_bits(wide_hit), wide_occ),
                    (hit_bits(plain_hit), plain_occ),
                    "{r:?}"
                );
                let sse_hit = closest_in::<NodeRay>(&bvh, r);
                assert_eq!(hit_bits(wide_hit), hit_bits(sse_hit), "{r:?}");
                // SAFETY: AVX2 was detected above.
                let wide_sorted = unsafe { closest_sorted_avx2(&bvh, r) };
                assert_eq!(hit_bits(wide_sorted), hit_bits(sse_hit), "{r:?}");
                assert_eq!(wide_occ, occluded_in::<NodeRay>(&bvh, r), "{r:?}");
                hits += usize::from(sse_hit.is_some());
                for node in bvh.nodes.iter().take(64) {
                    for t_far in [r.t_max, 1.0] {
                        // SAFETY: AVX2 was detected above.
                        let wide = unsafe { mask_avx2(node, r, t_far) };
                        let sse = <NodeRay as NodeTest>::intersect(&NodeRay::new(r), node, t_far).0;
                        assert_eq!(wide, sse, "{r:?}");
                        // The permutation in registers equals the scalar one, every octant
                        // (entry distances compared where a child is hit: the SSE test
                        // leaves an empty second group's distances at 0).
                        for &order in &node.order {
                            // SAFETY: AVX2 was detected above.
                            let (wm, wt, wr) = unsafe { ordered_avx2(node, r, t_far, order) };
                            let (m, t, c) = NodeRay::new(r).intersect_ordered(node, t_far, order);
                            assert_eq!((wm, wr), (m, c));
                            for i in (0..8).filter(|i| m >> i & 1 != 0) {
                                assert_eq!(wt[i].to_bits(), t[i].to_bits());
                            }
                        }
                    }
                }
            }
            assert!(hits > 300, "{hits}");
            // The AVX2 batch kernels (every length around the lane count) answer as the SSE
            // single-ray kernel does, ray by ray.
            for n in [1, 11, 12, 13, rays.len()] {
                let rays = &rays[..n];
                let mut batch_hits = vec![None; n];
                let mut batch_occ = vec![false; n];
                let mut plain_hits = vec![None; n];
                let mut plain_occ = vec![false; n];
                // SAFETY: AVX2 and the bit operations were detected above.
                unsafe {
                    closest_batch_avx2(&bvh, rays, &mut batch_hits);
                    occluded_batch_avx2(&bvh, rays, &mut batch_occ);
                    plain_batch_avx2(&bvh, rays, &mut plain_hits, &mut plain_occ);
                }
                for (i, r) in rays.iter().enumerate() {
                    assert_eq!(hit_bits(batch_hits[i]), hit_bits(plain_hits[i]), "{r:?}");
                    assert_eq!(batch_occ[i], plain_occ[i], "{r:?}");
                    let sse_hit = closest_in::<NodeRay>(&bvh, r);
                    assert_eq!(hit_bits(batch_hits[i]), hit_bits(sse_hit), "{r:?}");
                    assert_eq!(batch_occ[i], occluded_in::<NodeRay>(&bvh, r), "{r:?}");
                }
            }
        }
    }

    /// The batch kernels with block pushes of `P` (octant order and sorted; occlusion), each
    /// batch's answers.
    type BatchAnswers = [Vec<Option<Hit>>; 2];

    /// Runs `closest` (octant order), the sorted closest-hit kernel and `occluded` of the block
    /// batch lanes of `P` on `rays`.
    #[inline(always)]
    fn block_batches<P: pack::Pack>(bvh: &Bvh, rays: &[Ray]) -> (BatchAnswers, Vec<bool>) {
        use super::super::traverse::closest_batch_ordered_in;
        let n = rays.len();
        let (mut octant, mut sorted, mut occ) = (vec![None; n], vec![None; n], vec![false; n]);
        closest_batch_in::<block::NodeRay8k<P>>(bvh, rays, &mut octant);
        closest_batch_ordered_in::<block::NodeRay8k<P>, false>(bvh, rays, &mut sorted);
        occluded_batch_in::<block::NodeRay8k<P>>(bvh, rays, &mut occ);
        ([octant, sorted], occ)
    }

    /// The entries the block push of `P` and the generic loop (with the AVX2 node test) put on
    /// a stack that already holds three (octant order) and on an empty one (occlusion: every
    /// hit child in slot order), as `(reference, entry-distance bits)` from the bottom up.
    #[inline(always)]
    fn block_pushes<P: pack::Pack>(
        node: &Node,
        ray: &Ray,
        t_far: f32,
        order: u32,
    ) -> [[Vec<(u32, u32)>; 2]; 2] {
        use super::super::traverse::BatchStack;
        let woop = WoopRay::new(ray.origin, ray.dir);
        let block = <block::NodeRay8k<P> as NodeTest>::new(ray, &woop);
        let generic = <NodeRay8 as NodeTest>::new(ray, &woop);
        let mut ordered = [3, 3].map(BatchStack::with_entries);
        block.push_ordered(node, t_far, order, &mut ordered[0]);
        generic.push_ordered(node, t_far, order, &mut ordered[1]);
        let mut all = [0, 0].map(BatchStack::with_entries);
        block.push_all(node, t_far, &mut all[0]);
        generic.push_all(node, t_far, &mut all[1]);
        let entries = |s: BatchStack| s.entries().iter().map(|e| (e.r, e.t.to_bits())).collect();
        [ordered.map(entries), all.map(entries)]
    }

    /// Block batches and pushes with the AVX2 table ([`pack::Avx2Pack`]).
    #[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
    unsafe fn block_avx2(bvh: &Bvh, rays: &[Ray]) -> (BatchAnswers, Vec<bool>) {
        block_batches::<pack::Avx2Pack>(bvh, rays)
    }

    #[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
    unsafe fn pushes_avx2(node: &Node, ray: &Ray, t: f32, order: u32) -> [[Vec<(u32, u32)>; 2]; 2] {
        block_pushes::<pack::Avx2Pack>(node, ray, t, order)
    }

    /// Block batches with AVX-512 compress ([`pack::Avx512Pack`]), compiled without the bit
    /// operations (as before session 21).
    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    unsafe fn block_avx512(bvh: &Bvh, rays: &[Ray]) -> (BatchAnswers, Vec<bool>) {
        block_batches::<pack::Avx512Pack>(bvh, rays)
    }

    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    unsafe fn pushes_avx512(
        node: &Node,
        ray: &Ray,
        t: f32,
        order: u32,
    ) -> [[Vec<(u32, u32)>; 2]; 2] {
        block_pushes::<pack::Avx512Pack>(node, ray, t, order)
    }

    /// The block batch kernels — AVX2 with the table (when this CPU has AVX2), AVX-512 with
    /// compress (when it has AVX-512F/VL), and the dispatched `closest_batch`/`occluded_batch`
    /// — give the SSE single-ray kernel's answers bit for bit, in octant order and sorted, and
    /// their block pushes store exactly the entries (references and entry-distance bits, same
    /// order) that the generic loop pushes with the same node test, for every node, octant and
    /// `t_far`.
    #[test]
    fn block_batch_equals_sse() {
        if !(std::arch::is_x86_feature_detected!("avx2") && have_bit_ops()) {
            eprintln!("no AVX2 on this CPU: only the SSE kernel runs");
            return;
        }
        let avx512 = std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512vl");
        let (tris, rays) = soup_and_rays();
        for q in [BvhQuality::Fast, BvhQuality::Medium] {
            let bvh = build(&tris, q);
            for n in [1, 11, 12, 13, rays.len()] {
                let rays = &rays[..n];
                // SAFETY: AVX2 and the bit operations were detected above.
                let mut runs = vec![unsafe { block_avx2(&bvh, rays) }];
                if avx512 {
                    // SAFETY: AVX-512F/VL were detected above.
                    runs.push(unsafe { block_avx512(&bvh, rays) });
                }
                let (mut dispatched, mut dispatched_occ) = (vec![None; n], vec![false; n]);
                assert!(closest_batch(&bvh, rays, &mut dispatched));
                assert!(occluded_batch(&bvh, rays, &mut dispatched_occ));
                runs.push(([dispatched.clone(), dispatched], dispatched_occ));
                for ([octant, sorted], occ) in runs {
                    for (i, r) in rays.iter().enumerate() {
                        let sse_hit = hit_bits(closest_in::<NodeRay>(&bvh, r));
                        assert_eq!(hit_bits(octant[i]), sse_hit, "{r:?}");
                        assert_eq!(hit_bits(sorted[i]), sse_hit, "{r:?}");
                        assert_eq!(occ[i], occluded_in::<NodeRay>(&bvh, r), "{r:?}");
                    }
                }
            }
            let mut pushed = 0;
            for r in rays.iter().step_by(7) {
                for node in bvh.nodes.iter().take(64) {
                    for t_far in [r.t_max, 1.0] {
                        let hit_mask =
                            <NodeRay as NodeTest>::intersect(&NodeRay::new(r), node, t_far).0;
                        let want: Vec<u32> = (0..8)
                            .filter(|&i| hit_mask >> i & 1 != 0)
                            .map(|i| node.child[i])
                            .collect();
                        for &order in &node.order {
                            // SAFETY: AVX2 and the bit operations were detected above.
                            let mut got = vec![unsafe { pushes_avx2(node, r, t_far, order) }];
                            if avx512 {
                                // SAFETY: AVX-512F/VL were detected above.
                                got.push(unsafe { pushes_avx512(node, r, t_far, order) });
                            }
                            for [[block, generic], [all_block, all_generic]] in got {
                                assert_eq!(block, generic, "{r:?}");
                                // Occlusion pushes: the references (the loop leaves the
                                // entry distances unset).
                                for all in [all_block, all_generic] {
                                    let refs: Vec<u32> = all.iter().map(|e| e.0).collect();
                                    assert_eq!(refs, want, "{r:?}");
                                }
                                pushed += block.len() - 3;
                            }
                        }
                    }
                }
            }
            assert!(pushed > 1000, "{pushed}");
        }
    }

    #[target_feature(enable = "avx2")]
    unsafe fn closest_sorted_avx2(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
        super::super::traverse::closest_ordered_in::<NodeRay8, false>(bvh, ray)
    }

    #[target_feature(enable = "avx2")]
    unsafe fn ordered_avx2(
        node: &Node,
        ray: &Ray,
        t_far: f32,
        order: u32,
    ) -> (u32, [f32; 8], [u32; 8]) {
        <NodeRay8 as NodeTest>::new(ray, &WoopRay::new(ray.origin, ray.dir))
            .intersect_ordered(node, t_far, order)
    }

    #[target_feature(enable = "avx2")]
    unsafe fn mask_avx2(node: &Node, ray: &Ray, t_far: f32) -> u32 {
        <NodeRay8 as NodeTest>::new(ray, &WoopRay::new(ray.origin, ray.dir))
            .intersect(node, t_far)
            .0
    }
}
