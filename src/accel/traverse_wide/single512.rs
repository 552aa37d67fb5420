//! The AVX-512 single-ray kernels (x86-64 with AVX-512F and VL, picked at run time by
//! `traverse_wide.rs`): the single-ray closest-hit and occlusion loops of `traverse.rs` with
//! the 8-wide node test of [`NodeRay8`], whose node step pushes the hit children as one block
//! store instead of a loop over the hit mask.
//!
//! * **Node step** ([`NodeTest::visit_ordered`]): the node test's `≤` goes straight into a
//!   mask register, on the lanes already permuted into the ray's octant order, reversed (lane
//!   `j` is the child visited `(7 − j)`-th); the child references and entry distances are
//!   interleaved into `(r, t)` pairs, the hit ones packed to the bottom (`vpcompressq`,
//!   register form, `pack.rs`) and stored above the stack top, farthest first. The topmost stored pair is
//!   the nearest child: it is read back as the node visited next, and the stack grows by the
//!   popcount less one. No loop over the children, so no mispredicted loop exit.
//! * **Prefetch** (`prefetch_child`: four lines from the child's first byte, no clamping
//!   to a leaf's end): one child per node step, the one popped next (the topmost pushed, or the
//!   nearest itself when nothing is pushed: no branch), not every pushed child as the AVX2
//!   kernel does in its push loop; that loop and its mispredicted exit are what the block
//!   store removes (A/B in `docs/ray-layer.md`, session 19).
//! * **Same answers**: the node test is [`NodeRay8`]'s, the leaf test `leaf_wide.rs`'s, so the
//!   children visited, their order, and the results are those of the AVX2 and SSE kernels bit
//!   for bit (`single_avx512_equals_avx2_and_sse` below).

use std::arch::x86_64::{
    __m256i, _mm256_loadu_si256, _mm256_permutevar8x32_epi32, _mm256_storeu_si256,
};

use glam::Vec3;

use super::super::bvh::{Bvh, Node};
use super::super::traverse::{closest_in, occluded_in, prefetch_child, NodeTest, Stack};
use super::super::triangle::WoopRay;
use super::super::{Hit, Ray};
use super::pack::{reversed_order, store_pairs, Avx512Pack};
use super::NodeRay8;

/// Closest hit with the AVX-512 node step (in octant order, unless sorted: `traverse.rs`).
///
/// # Safety
/// The CPU must support AVX2, AVX-512F, AVX-512VL and the bit operations of
/// [`super::have_bit_ops`].
#[target_feature(enable = "avx2,avx512f,avx512vl,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn closest_avx512(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
    closest_in::<NodeRay8s>(bvh, ray)
}

/// Occlusion with the AVX-512 node step (in octant order, unless sorted).
///
/// # Safety
/// The CPU must support AVX2, AVX-512F, AVX-512VL and the bit operations of
/// [`super::have_bit_ops`].
#[target_feature(enable = "avx2,avx512f,avx512vl,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn occluded_avx512(bvh: &Bvh, ray: &Ray) -> bool {
    occluded_in::<NodeRay8s>(bvh, ray)
}

/// [`NodeRay8`] with the block node step. Only made inside the AVX-512 kernels above (the
/// `NodeTest` methods are reached only through them), so its methods may use AVX-512.
pub(super) struct NodeRay8s(NodeRay8);

impl NodeTest for NodeRay8s {
    #[inline(always)]
    fn new(ray: &Ray, woop: &WoopRay) -> Self {
        Self(NodeRay8::new(ray, woop))
    }

    #[inline(always)]
    fn leaf_hits(
        &self,
        woop: &WoopRay,
        tris: &[[Vec3; 3]],
        t_limit: f32,
        f: impl FnMut(usize, (f32, f32, f32)) -> bool,
    ) {
        self.0.leaf_hits(woop, tris, t_limit, f);
    }

    #[inline(always)]
    fn intersect(&self, node: &Node, t_far: f32) -> (u32, [f32; 8]) {
        self.0.intersect(node, t_far)
    }

    #[inline(always)]
    fn intersect_ordered(&self, node: &Node, t_far: f32, order: u32) -> (u32, [f32; 8], [u32; 8]) {
        self.0.intersect_ordered(node, t_far, order)
    }

    #[inline(always)]
    fn visit_ordered<S: Stack>(
        &self,
        bvh: &Bvh,
        node: &Node,
        t_far: f32,
        order: u32,
        stack: &mut S,
    ) -> Option<u32> {
        let (tn, tf) = self.0.slabs(node, t_far);
        // SAFETY: AVX2 and AVX-512F/VL intrinsics; this type is used only inside the AVX-512
        // kernels. The unaligned load reads the node's `[u32; 8]` child array through a
        // reference to it; `block` is the stack's eight slots above its top.
        unsafe {
            // Lane j: the slot visited (7 − j)-th, so the farthest is stored first.
            let (slots, tn, hit) = reversed_order::<Avx512Pack>(tn, tf, order);
            if hit == 0 {
                return None;
            }
            let child = _mm256_permutevar8x32_epi32(
                _mm256_loadu_si256(std::ptr::from_ref(&node.child).cast::<__m256i>()),
                slots,
            );
            // The nearest is the highest hit lane (also the last pair stored). Read from the
            // permuted references, stored apart: they do not wait for the slab test, so the
            // next node's address does not wait for the compress and the block store.
            let mut r = [0u32; 8];
            _mm256_storeu_si256(r.as_mut_ptr().cast::<__m256i>(), child);
            let next = r[(31 - u32::from(hit).leading_zeros()) as usize & 7];
            let block = stack.top_block();
            store_pairs::<Avx512Pack>(child, tn, hit, block);
            let n = hit.count_ones() as usize;
            // Only the child popped next, after the nearest's subtree, is prefetched: the
            // topmost pushed, or the nearest itself when nothing is pushed (no branch, no loop).
            // The slot read is below `n`, written by `store_pairs`.
            prefetch_child(bvh, (*block.add((n - 1).saturating_sub(1) & 7)).r);
            stack.grow(n - 1);
            Some(next)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::bvh::build;
    use super::super::super::traverse::tests::{soup_and_nested, test_rays};
    use super::super::super::traverse::{closest_ordered_in, BatchStack, NodeRay};
    use super::super::tests::soup_and_rays;
    use super::*;
    use crate::settings::BvhQuality;

    fn hit_bits(h: Option<Hit>) -> Option<[u32; 4]> {
        h.map(|h| [h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()])
    }

    fn have_avx512() -> bool {
        std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512vl")
            && super::super::have_bit_ops()
    }

    #[target_feature(enable = "avx2")]
    unsafe fn avx2(bvh: &Bvh, ray: &Ray) -> (Option<Hit>, bool) {
        (
            closest_ordered_in::<NodeRay8, true>(bvh, ray),
            occluded_in::<NodeRay8>(bvh, ray),
        )
    }

    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    unsafe fn avx512_sorted(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
        closest_ordered_in::<NodeRay8s, false>(bvh, ray)
    }

    /// The AVX-512 single-ray kernels (when this CPU has AVX-512F/VL) give the AVX2 and SSE
    /// kernels' answers bit for bit (closest hit: t, prim, b1, b2; occlusion), on the traverse
    /// tests' soup and nested hierarchy (deeper than the array stack: the heap stack's block
    /// stores) with their rays, and on the wide tests' soup with axis-parallel, zero-component,
    /// on-plane and finite-`t_max` rays, for both BVH qualities.
    #[test]
    fn single_avx512_equals_avx2_and_sse() {
        if !have_avx512() {
            eprintln!("no AVX-512F/VL on this CPU: the AVX2 and SSE kernels run");
            return;
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x3c6e_f372_fe94_f82bu64);
        let [soup, nested] = soup_and_nested(&mut rnd);
        let mut rays = test_rays(&mut rnd, 3000);
        rays[5].dir = Vec3::ZERO;
        rays[17].origin.x = f32::NAN;
        rays[40].t_max = -1.0;
        let (wide_soup, wide_rays) = soup_and_rays();
        let (mut hits, mut occluded) = (0, 0);
        for (tris, rays) in [(soup, &rays), (nested, &rays), (wide_soup, &wide_rays)] {
            for q in [BvhQuality::Fast, BvhQuality::Medium] {
                let bvh = build(&tris, q);
                for (i, r) in rays.iter().enumerate() {
                    let sse = (
                        hit_bits(closest_ordered_in::<NodeRay, true>(&bvh, r)),
                        occluded_in::<NodeRay>(&bvh, r),
                    );
                    // SAFETY: AVX2, AVX-512F/VL and the bit operations were detected above.
                    let (a2, a2_occ) = unsafe { avx2(&bvh, r) };
                    assert_eq!((hit_bits(a2), a2_occ), sse, "ray {i}");
                    // SAFETY: as above.
                    let got = unsafe {
                        [
                            (closest_avx512(&bvh, r), occluded_avx512(&bvh, r)),
                            (avx512_sorted(&bvh, r), sse.1),
                        ]
                    };
                    for (hit, occ) in got {
                        assert_eq!((hit_bits(hit), occ), sse, "ray {i}");
                    }
                    hits += usize::from(sse.0.is_some());
                    occluded += usize::from(sse.1);
                }
            }
        }
        assert!(hits > 3000 && occluded > 3000, "{hits} {occluded}");
    }

    /// A node step's outcome: the child to visit next, and the stack's entries as
    /// `(reference, entry-distance bits)` from the bottom up.
    type Step = (Option<u32>, Vec<(u32, u32)>);

    /// The entries the block step and the generic step (the AVX2 node test, a loop) put on a
    /// stack that already holds three, as `(reference, entry-distance bits)` from the bottom
    /// up, with the child each returns to visit next.
    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    unsafe fn steps(bvh: &Bvh, node: &Node, ray: &Ray, t_far: f32, order: u32) -> [Step; 2] {
        let woop = WoopRay::new(ray.origin, ray.dir);
        let block = <NodeRay8s as NodeTest>::new(ray, &woop);
        let generic = <NodeRay8 as NodeTest>::new(ray, &woop);
        let mut stacks = [3, 3].map(BatchStack::with_entries);
        let next = [
            block.visit_ordered(bvh, node, t_far, order, &mut stacks[0]),
            generic.visit_ordered(bvh, node, t_far, order, &mut stacks[1]),
        ];
        let [a, b] = stacks.map(|s| s.entries().iter().map(|e| (e.r, e.t.to_bits())).collect());
        [(next[0], a), (next[1], b)]
    }

    /// The block node step pushes exactly the entries (references and entry-distance bits,
    /// same order) that the generic loop pushes, and returns the same child to visit next, for
    /// every node of a tree, every octant's order and two `t_far`.
    #[test]
    fn block_step_equals_generic_step() {
        if !have_avx512() {
            eprintln!("no AVX-512F/VL on this CPU: the AVX2 and SSE kernels run");
            return;
        }
        let (tris, rays) = soup_and_rays();
        let bvh = build(&tris, BvhQuality::Medium);
        let (mut pushed, mut visited) = (0, 0);
        for r in rays.iter().step_by(29) {
            for node in &bvh.nodes {
                for t_far in [r.t_max, 1.0] {
                    for &order in &node.order {
                        // SAFETY: AVX2 and AVX-512F/VL were detected above.
                        let [block, generic] = unsafe { steps(&bvh, node, r, t_far, order) };
                        assert_eq!(block, generic, "{r:?}");
                        pushed += block.1.len() - 3;
                        visited += usize::from(block.0.is_some());
                    }
                }
            }
        }
        assert!(pushed > 1000 && visited > 1000, "{pushed} {visited}");
    }
}
