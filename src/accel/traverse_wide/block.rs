//! The block node steps (AVX-512F/VL, or AVX2 alone, picked at run time by
//! `traverse_wide.rs`): [`NodeRay8k`], the 8-wide node test of [`NodeRay8`] whose hit
//! children are stored as one packed block instead of pushed in a loop over the hit mask. The
//! batch kernels run it with either packing; the AVX-512 single-ray kernels (`single512.rs`)
//! with `vpcompressq`.
//!
//! * **Batch push** ([`NodeTest::push_ordered`], [`NodeTest::push_all`]): the node test's `≤`
//!   mask; the child references and entry distances are interleaved into eight `(r, t)` pairs,
//!   and the hit pairs are packed to the bottom and stored above the stack top (`pack.rs`:
//!   `vpcompressq` with AVX-512, a `vpermd` table on AVX2); the stack grows by the mask's
//!   popcount. Closest hit: the pairs in the node's octant order for the ray, reversed, so the
//!   farthest goes first and the nearest is popped next. Occlusion: slot order, the order of
//!   the loop it replaces.
//! * **Single-ray step** ([`NodeTest::visit_ordered`]): the same block in octant order; the
//!   topmost stored pair is the nearest child, returned as the node visited next, and the
//!   stack grows by the popcount less one. No loop over the children, so no mispredicted loop
//!   exit. Prefetch (`prefetch_child`): only the child popped next (the topmost pushed, or the
//!   nearest itself when nothing is pushed: no branch), not every pushed child as the loop
//!   kernel does.
//! * **256-bit registers only**: the eight pairs are stored as two packed halves of four (the
//!   second at the first's popcount), not as one 512-bit register: as fast with AVX-512 (A/B
//!   in `docs/ray-layer.md`, session 14), and no 512-bit instruction that could lower the
//!   core's clock for the code that runs after the traversal.
//! * **Same answers**: the node test is [`NodeRay8`]'s (same operations, same ordered `≤`), so
//!   the pushed children and their order are those of the generic loops, and the results are
//!   the SSE kernel's bit for bit (`block_batch_equals_sse` in `traverse_wide.rs`,
//!   `single_avx512_equals_avx2_and_sse` in `single512.rs`).

use std::arch::x86_64::{
    __m256i, _mm256_loadu_si256, _mm256_permutevar8x32_epi32, _mm256_storeu_si256,
};
use std::marker::PhantomData;

use super::super::bvh::{Bvh, LeafTri, Node};
use super::super::traverse::{
    closest_batch_in, occluded_batch_in, prefetch_child, BatchStack, NodeTest, Stack,
};
use super::super::triangle::WoopRay;
use super::super::{Hit, Ray};
use super::pack::{reversed_order, store_pairs, Avx2Pack, Avx512Pack, Pack};
use super::NodeRay8;

/// Closest hits of a batch with the AVX-512 block pushes in every lane.
///
/// # Safety
/// The CPU must support AVX2, AVX-512F, AVX-512VL and the bit operations of
/// [`have_bit_ops`](super::have_bit_ops).
#[target_feature(enable = "avx2,avx512f,avx512vl,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn closest_batch_avx512(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>]) {
    closest_batch_in::<NodeRay8k<Avx512Pack>>(bvh, rays, out);
}

/// Occlusion of a batch with the AVX-512 block pushes in every lane.
///
/// # Safety
/// The CPU must support AVX2, AVX-512F, AVX-512VL and the bit operations of
/// [`have_bit_ops`](super::have_bit_ops).
#[target_feature(enable = "avx2,avx512f,avx512vl,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn occluded_batch_avx512(bvh: &Bvh, rays: &[Ray], out: &mut [bool]) {
    occluded_batch_in::<NodeRay8k<Avx512Pack>>(bvh, rays, out);
}

/// Closest hits of a batch with the AVX2 block pushes in every lane.
///
/// # Safety
/// The CPU must support AVX2 and the bit operations of [`have_bit_ops`](super::have_bit_ops).
#[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn closest_batch_block_avx2(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>]) {
    closest_batch_in::<NodeRay8k<Avx2Pack>>(bvh, rays, out);
}

/// Occlusion of a batch with the AVX2 block pushes in every lane.
///
/// # Safety
/// The CPU must support AVX2 and the bit operations of [`have_bit_ops`](super::have_bit_ops).
#[target_feature(enable = "avx2,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn occluded_batch_block_avx2(bvh: &Bvh, rays: &[Ray], out: &mut [bool]) {
    occluded_batch_in::<NodeRay8k<Avx2Pack>>(bvh, rays, out);
}

/// [`NodeRay8`] with the block node steps, packing with `P`. Only made inside the kernels
/// compiled for AVX2 and `P`'s instruction set (above, and `single512.rs`), so its methods may
/// use them.
pub(super) struct NodeRay8k<P>(NodeRay8, PhantomData<P>);

impl<P: Pack> NodeTest for NodeRay8k<P> {
    const BATCH_OCTANT: bool = true;

    #[inline(always)]
    fn new(ray: &Ray, woop: &WoopRay) -> Self {
        Self(NodeRay8::new(ray, woop), PhantomData)
    }

    #[inline(always)]
    fn leaf_hits(
        &self,
        woop: &WoopRay,
        tris: &[LeafTri],
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
        // SAFETY: AVX2 intrinsics and `P`'s; this type is used only inside the kernels
        // compiled for both. The unaligned load reads the node's `[u32; 8]` child array through a
        // reference to it; `block` is the stack's eight slots above its top.
        unsafe {
            // Lane j: the slot visited (7 − j)-th, so the farthest is stored first.
            let (slots, tn, hit) = reversed_order::<P>(tn, tf, order);
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
            store_pairs::<P>(child, tn, hit, block);
            let n = hit.count_ones() as usize;
            // Only the child popped next, after the nearest's subtree, is prefetched: the
            // topmost pushed, or the nearest itself when nothing is pushed (no branch, no loop).
            // The slot read is below `n`, written by `store_pairs`.
            prefetch_child(bvh, (*block.add((n - 1).saturating_sub(1) & 7)).r);
            stack.grow(n - 1);
            Some(next)
        }
    }

    #[inline(always)]
    fn push_ordered(&self, node: &Node, t_far: f32, order: u32, stack: &mut BatchStack) {
        let (tn, tf) = self.0.slabs(node, t_far);
        // SAFETY: AVX2 intrinsics and `P`'s; this type is used only inside the kernels above,
        // compiled for both. The unaligned load reads the node's `[u32; 8]` child array
        // through a reference to it; the block is the stack's eight slots above its top.
        let n = unsafe {
            // Lane j: the slot visited (7 − j)-th, so the farthest is pushed first.
            let (slots, tn, hit) = reversed_order::<P>(tn, tf, order);
            let child = _mm256_loadu_si256(std::ptr::from_ref(&node.child).cast::<__m256i>());
            store_pairs::<P>(
                _mm256_permutevar8x32_epi32(child, slots),
                tn,
                hit,
                stack.block().as_mut_ptr(),
            );
            hit.count_ones() as usize
        };
        stack.grow(n);
    }

    #[inline(always)]
    fn push_all(&self, node: &Node, t_far: f32, stack: &mut BatchStack) {
        let (tn, tf) = self.0.slabs(node, t_far);
        // SAFETY: as in `push_ordered`.
        let n = unsafe {
            let hit = P::le_mask(tn, tf);
            let child = _mm256_loadu_si256(std::ptr::from_ref(&node.child).cast::<__m256i>());
            store_pairs::<P>(child, tn, hit, stack.block().as_mut_ptr());
            hit.count_ones() as usize
        };
        stack.grow(n);
    }
}
