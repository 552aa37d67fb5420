//! The AVX-512 batch closest-hit kernel (x86-64 with AVX-512F and VL, picked at run time by
//! `traverse_wide.rs`): the batch lanes of `traverse.rs` with the 8-wide node test of
//! [`NodeRay8`], whose pushes are one block store instead of a loop.
//!
//! * **Push**: the hit children go onto the lane's stack in the node's octant order, farthest
//!   first, without a loop over the hit mask: the order word becomes lane indices (reversed,
//!   so the farthest comes first), the entry and exit distances are permuted into that order
//!   and compared into a mask register, the child references and entry distances are
//!   interleaved into eight `(r, t)` pairs by one two-table permute (`vpermt2d`), the hit
//!   pairs are packed to the bottom (`vpcompressq`, register form) and stored as one 64-byte
//!   block above the stack top; the stack grows by the mask's popcount.
//! * **Same answers**: the node test is [`NodeRay8`]'s (same operations, same ordered `≤`), so
//!   the pushed children and their order are those of the generic octant-order push
//!   ([`NodeTest::push_ordered`]), and the results are the SSE kernel's bit for bit
//!   (`avx512_equals_sse` in `traverse_wide.rs`).

use std::arch::x86_64::{
    __m256i, _mm256_and_si256, _mm256_castps_si256, _mm256_cmp_ps_mask, _mm256_loadu_si256,
    _mm256_maskz_compress_epi64, _mm256_permute2x128_si256, _mm256_permutevar8x32_epi32,
    _mm256_permutevar8x32_ps, _mm256_set1_epi32, _mm256_setr_epi32, _mm256_srlv_epi32,
    _mm256_storeu_si256, _mm256_unpackhi_epi32, _mm256_unpacklo_epi32, _mm512_add_epi64,
    _mm512_castsi256_si512, _mm512_cvtepu32_epi64, _mm512_maskz_compress_epi64, _mm512_or_si512,
    _mm512_permutex2var_epi32, _mm512_set1_epi64, _mm512_setr_epi32, _mm512_slli_epi64,
    _mm512_storeu_si512, _CMP_LE_OS,
};

use glam::Vec3;

use super::super::bvh::{Bvh, Node};
use super::super::traverse::{closest_batch_in, occluded_batch_in, BatchStack, Entry, NodeTest};
use super::super::triangle::WoopRay;
use super::super::{Hit, Ray};
use super::NodeRay8;

/// Closest hits of a batch with the AVX-512 push in every lane.
///
/// # Safety
/// The CPU must support AVX2, AVX-512F and AVX-512VL.
#[target_feature(enable = "avx2,avx512f,avx512vl")]
pub(super) unsafe fn closest_batch_avx512(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>]) {
    if ymm_only() {
        closest_batch_in::<NodeRay8k<true>>(bvh, rays, out);
    } else {
        closest_batch_in::<NodeRay8k<false>>(bvh, rays, out);
    }
}

/// `STAGELIGHT_TRAVERSAL=avx512y`: the block stores in two 256-bit halves (no 512-bit
/// register), for A/B runs.
pub(super) fn ymm_only() -> bool {
    static CHOICE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *CHOICE.get_or_init(|| std::env::var("STAGELIGHT_TRAVERSAL").is_ok_and(|v| v == "avx512y"))
}

/// Occlusion of a batch with the AVX-512 push in every lane.
///
/// # Safety
/// The CPU must support AVX2, AVX-512F and AVX-512VL.
#[target_feature(enable = "avx2,avx512f,avx512vl")]
pub(super) unsafe fn occluded_batch_avx512(bvh: &Bvh, rays: &[Ray], out: &mut [bool]) {
    if ymm_only() {
        occluded_batch_in::<NodeRay8k<true>>(bvh, rays, out);
    } else {
        occluded_batch_in::<NodeRay8k<false>>(bvh, rays, out);
    }
}

/// [`NodeRay8`] with the AVX-512 push. Only made inside the AVX-512 kernel above (the type is
/// private to this file), so its methods may use AVX-512.
/// `YMM`: the block is stored as two 256-bit halves instead of one 512-bit register.
pub(super) struct NodeRay8k<const YMM: bool>(NodeRay8);

impl<const YMM: bool> NodeTest for NodeRay8k<YMM> {
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
    fn push_ordered(&self, node: &Node, t_far: f32, order: u32, stack: &mut BatchStack) {
        let n = self.store_block(node, t_far, order, stack.block());
        stack.grow(n);
    }

    #[inline(always)]
    fn push_all(&self, node: &Node, t_far: f32, stack: &mut BatchStack) {
        let (tn, tf) = self.0.slabs(node, t_far);
        // SAFETY: AVX2 and AVX-512F/VL intrinsics; this type exists only inside the AVX-512
        // kernels. The load reads the node's `[u32; 8]` child array through a reference to
        // it; the store writes the stack's eight-entry block (64 bytes) through a reference.
        unsafe {
            let hit = _mm256_cmp_ps_mask::<_CMP_LE_OS>(tn, tf);
            let child = _mm256_loadu_si256(std::ptr::from_ref(&node.child).cast::<__m256i>());
            let block = stack.block();
            if YMM {
                Self::store_halves(child, _mm256_castps_si256(tn), hit, block);
                stack.grow(hit.count_ones() as usize);
                return;
            }
            // Pair j = (child[j], tn[j]), packed to the bottom in slot order.
            _mm512_storeu_si512(
                std::ptr::from_mut(block).cast(),
                _mm512_maskz_compress_epi64(
                    hit,
                    _mm512_permutex2var_epi32(
                        _mm512_castsi256_si512(child),
                        _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23),
                        _mm512_castsi256_si512(_mm256_castps_si256(tn)),
                    ),
                ),
            );
            stack.grow(hit.count_ones() as usize);
        }
    }
}

impl<const YMM: bool> NodeRay8k<YMM> {
    /// Stores the pairs `(c[j], t[j])`, `j = 0..8`, whose bit is set in `hit`, packed to the
    /// bottom of `block` in `j` order, with 256-bit operations only (two halves of four).
    ///
    /// # Safety
    /// AVX2 and AVX-512F/VL intrinsics: call only inside the AVX-512 kernels.
    #[inline(always)]
    unsafe fn store_halves(c: __m256i, t: __m256i, hit: u8, block: &mut [Entry; 8]) {
        // SAFETY: see above; the stores write four entries (32 bytes) at `block[0..4]` and
        // `block[n..n + 4]`, n ≤ 4, through references into `block`.
        unsafe {
            let lo = _mm256_unpacklo_epi32(c, t); // pairs 0, 1 | 4, 5
            let hi = _mm256_unpackhi_epi32(c, t); // pairs 2, 3 | 6, 7
            let first = _mm256_permute2x128_si256::<0x20>(lo, hi);
            let second = _mm256_permute2x128_si256::<0x31>(lo, hi);
            let n = (hit & 15).count_ones() as usize;
            _mm256_storeu_si256(
                std::ptr::from_mut(&mut block[..4]).cast(),
                _mm256_maskz_compress_epi64(hit & 15, first),
            );
            _mm256_storeu_si256(
                std::ptr::from_mut(&mut block[n..n + 4]).cast(),
                _mm256_maskz_compress_epi64(hit >> 4, second),
            );
        }
    }

    /// Writes the children of `node` entered within `[0, t_far]` to the bottom of `block` in
    /// the visiting order `order` reversed (the farthest first), as `(reference, entry
    /// distance)`; returns how many. The rest of `block` is zeroed.
    #[inline(always)]
    fn store_block(&self, node: &Node, t_far: f32, order: u32, block: &mut [Entry; 8]) -> usize {
        let (tn, tf) = self.0.slabs(node, t_far);
        // SAFETY: AVX2 and AVX-512F/VL intrinsics; this type exists only inside the AVX-512
        // kernel. The unaligned load reads the node's `[u32; 8]` child array through a
        // reference to it; the store writes the stack's eight-entry block (64 bytes, `Entry`
        // is `repr(C)` `(u32, f32)`) through a reference to it.
        unsafe {
            // Lane j: the slot visited (7 − j)-th, so the farthest is pushed first.
            let slots = _mm256_and_si256(
                _mm256_srlv_epi32(
                    _mm256_set1_epi32(order as i32),
                    _mm256_setr_epi32(21, 18, 15, 12, 9, 6, 3, 0),
                ),
                _mm256_set1_epi32(7),
            );
            let tn_slots = _mm256_permutevar8x32_ps(tn, slots);
            let hit =
                _mm256_cmp_ps_mask::<_CMP_LE_OS>(tn_slots, _mm256_permutevar8x32_ps(tf, slots));
            if YMM {
                let child = _mm256_loadu_si256(std::ptr::from_ref(&node.child).cast::<__m256i>());
                Self::store_halves(
                    _mm256_permutevar8x32_epi32(child, slots),
                    _mm256_castps_si256(tn_slots),
                    hit,
                    block,
                );
                return hit.count_ones() as usize;
            }
            // Pair j = (child[slot j], tn[slot j]): 32-bit index `slot` in the first table
            // (the references), `16 + slot` in the second (the distances).
            let wide = _mm512_cvtepu32_epi64(slots);
            let pairs = _mm512_or_si512(
                wide,
                _mm512_slli_epi64::<32>(_mm512_add_epi64(wide, _mm512_set1_epi64(16))),
            );
            let child = _mm256_loadu_si256(std::ptr::from_ref(&node.child).cast::<__m256i>());
            let entries = _mm512_permutex2var_epi32(
                _mm512_castsi256_si512(child),
                pairs,
                _mm512_castsi256_si512(_mm256_castps_si256(tn)),
            );
            _mm512_storeu_si512(
                std::ptr::from_mut(block).cast(),
                _mm512_maskz_compress_epi64(hit, entries),
            );
            hit.count_ones() as usize
        }
    }
}
