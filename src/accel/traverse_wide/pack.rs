//! Ordering and packing a node's hit children into a stack block, shared by the block node
//! steps of `single512.rs` (single rays, AVX-512) and `block.rs` (batch lanes, AVX-512 or
//! AVX2): the hit lanes in the node's octant order reversed ([`reversed_order`]), the child
//! references and entry distances interleaved into eight `(r, t)` pairs and the hit pairs
//! packed to the bottom of the block in lane order, as two halves of four ([`store_pairs`]).
//!
//! * **Two instruction sets, one layout** ([`Pack`]): with AVX-512F/VL a half is packed by
//!   `vpcompressq` (register form) and the `≤` mask comes from a mask register
//!   ([`Avx512Pack`]); on AVX2 alone a half is permuted with `vpermd` by a row of a 16-entry
//!   table indexed by its four mask bits ([`Avx2Pack`], a table-driven left-pack): the same
//!   pairs in the same slots, so both give the generic push loop's stack entries.

use std::arch::x86_64::{
    __m256, __m256i, _mm256_and_si256, _mm256_castps_si256, _mm256_cmp_ps, _mm256_cmp_ps_mask,
    _mm256_load_si256, _mm256_maskz_compress_epi64, _mm256_movemask_ps, _mm256_permute2x128_si256,
    _mm256_permutevar8x32_epi32, _mm256_permutevar8x32_ps, _mm256_set1_epi32, _mm256_setr_epi32,
    _mm256_srlv_epi32, _mm256_storeu_si256, _mm256_unpackhi_epi32, _mm256_unpacklo_epi32,
    _CMP_LE_OS,
};

use super::super::traverse::Entry;

/// How a block step makes its hit mask and packs a half of four pairs.
///
/// # Safety
/// The methods use the instruction set the implementor names; call them only inside kernels
/// compiled for it (every implementor is private to the kernels that use it).
pub(super) trait Pack {
    /// Bit `j` set where `tn[j] ≤ tf[j]` (ordered: false when either is NaN).
    ///
    /// # Safety
    /// The CPU must support the implementor's instruction set.
    unsafe fn le_mask(tn: __m256, tf: __m256) -> u8;

    /// The 64-bit lanes of `v` whose bit is set in the low four bits of `mask`, moved to the
    /// bottom in lane order; the lanes above them hold unspecified values.
    ///
    /// # Safety
    /// The CPU must support the implementor's instruction set.
    unsafe fn pack4(mask: u8, v: __m256i) -> __m256i;
}

/// AVX-512F/VL: a mask register and `vpcompressq`.
pub(super) struct Avx512Pack;

impl Pack for Avx512Pack {
    #[inline(always)]
    unsafe fn le_mask(tn: __m256, tf: __m256) -> u8 {
        // SAFETY: AVX-512F/VL, which the caller guarantees.
        unsafe { _mm256_cmp_ps_mask::<_CMP_LE_OS>(tn, tf) }
    }

    #[inline(always)]
    unsafe fn pack4(mask: u8, v: __m256i) -> __m256i {
        // SAFETY: AVX-512F/VL, which the caller guarantees.
        unsafe { _mm256_maskz_compress_epi64(mask & 15, v) }
    }
}

/// AVX2: `vmovmskps` and a `vpermd` by [`PACK_TABLE`].
pub(super) struct Avx2Pack;

impl Pack for Avx2Pack {
    #[inline(always)]
    unsafe fn le_mask(tn: __m256, tf: __m256) -> u8 {
        // SAFETY: AVX, which the caller guarantees.
        unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(tn, tf)) as u8 }
    }

    #[inline(always)]
    unsafe fn pack4(mask: u8, v: __m256i) -> __m256i {
        // SAFETY: AVX2, which the caller guarantees; the aligned load reads one 32-byte,
        // 32-byte-aligned row of the table (`mask & 15 < 16`).
        unsafe {
            let row = _mm256_load_si256(PACK_TABLE.0[usize::from(mask & 15)].as_ptr().cast());
            _mm256_permutevar8x32_epi32(v, row)
        }
    }
}

/// Row `m`: the 32-bit lane indices that move the 64-bit lanes selected by the four bits of
/// `m` to the bottom, in order (lane `k` of the result is selected lane `s`'s halves
/// `2s, 2s + 1`); rows are padded with lane 0.
#[repr(C, align(32))]
struct PackTable([[u32; 8]; 16]);

static PACK_TABLE: PackTable = PackTable(pack_table());

const fn pack_table() -> [[u32; 8]; 16] {
    let mut table = [[0u32; 8]; 16];
    let mut m = 0;
    while m < 16 {
        let mut k = 0;
        let mut s = 0;
        while s < 4 {
            if m >> s & 1 != 0 {
                table[m][2 * k] = 2 * s as u32;
                table[m][2 * k + 1] = 2 * s as u32 + 1;
                k += 1;
            }
            s += 1;
        }
        m += 1;
    }
    table
}

/// The slab test's entry and exit distances `tn`, `tf` (slot order) in the visiting order
/// `order` (a `Node::order` word) reversed — lane `j` is the slot visited `(7 − j)`-th, so a
/// block stored from them puts the farthest first and the nearest on top — as
/// `(slots, tn, hit)`: the lanes' slot indices, the permuted entry distances and `P`'s `≤`
/// mask of the permuted lanes.
///
/// # Safety
/// The CPU must support `P`'s instruction set and AVX2.
#[inline(always)]
pub(super) unsafe fn reversed_order<P: Pack>(
    tn: __m256,
    tf: __m256,
    order: u32,
) -> (__m256i, __m256, u8) {
    // SAFETY: intrinsics on values, as the caller guarantees.
    unsafe {
        let slots = _mm256_and_si256(
            _mm256_srlv_epi32(
                _mm256_set1_epi32(order as i32),
                _mm256_setr_epi32(21, 18, 15, 12, 9, 6, 3, 0),
            ),
            _mm256_set1_epi32(7),
        );
        let tn = _mm256_permutevar8x32_ps(tn, slots);
        let hit = P::le_mask(tn, _mm256_permutevar8x32_ps(tf, slots));
        (slots, tn, hit)
    }
}

/// Stores the pairs `(c[j], t[j])` whose bit `j` is set in `hit` packed to the bottom of the
/// eight slots at `block`, in `j` order (`Entry` is `repr(C)` `(u32, f32)`), as two packed
/// halves of four; the slots above them get unspecified values, and slots
/// `0..max(4, popcount(hit))` are all written.
///
/// # Safety
/// The CPU must support `P`'s instruction set and AVX2, and `block` must point at eight
/// writable slots ([`Stack::top_block`](super::super::traverse::Stack::top_block)).
#[inline(always)]
pub(super) unsafe fn store_pairs<P: Pack>(c: __m256i, t: __m256, hit: u8, block: *mut Entry) {
    // SAFETY: intrinsics as above; the stores write four entries (32 bytes) each, at
    // `block[0..4]` and `block[n..n + 4]` with n ≤ 4, inside the caller's eight slots.
    unsafe {
        let t = _mm256_castps_si256(t);
        let lo = _mm256_unpacklo_epi32(c, t); // pairs 0, 1 | 4, 5
        let hi = _mm256_unpackhi_epi32(c, t); // pairs 2, 3 | 6, 7
        let first = _mm256_permute2x128_si256::<0x20>(lo, hi);
        let second = _mm256_permute2x128_si256::<0x31>(lo, hi);
        let n = (hit & 15).count_ones() as usize;
        _mm256_storeu_si256(block.cast(), P::pack4(hit, first));
        _mm256_storeu_si256(block.add(n).cast(), P::pack4(hit >> 4, second));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row moves exactly the selected pairs, in order, to the bottom.
    #[test]
    fn pack_table_rows_select_the_masked_pairs_in_order() {
        for (m, row) in pack_table().iter().enumerate() {
            let selected: Vec<u32> = (0..4).filter(|s| m >> s & 1 != 0).collect();
            for (k, &s) in selected.iter().enumerate() {
                assert_eq!([row[2 * k], row[2 * k + 1]], [2 * s, 2 * s + 1], "row {m}");
            }
            assert!(row.iter().all(|&i| i < 8), "row {m}");
        }
    }
}
