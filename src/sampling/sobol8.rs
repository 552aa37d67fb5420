//! Eight Owen-scrambled Sobol dimensions of one sample at once: the values
//! `sobol_burley::sample_4d` gives for two consecutive dimension sets, bit for bit.
//!
//! `sobol_burley` computes four dimensions per call and, in this crate's baseline x86-64
//! build, emulates each 32-bit lane multiply with two `pmuludq` and shuffles. Here the work
//! is arranged so a path's dimensions cost less:
//!
//! * the sample index's scramble (the same for every dimension) is made once per sample
//!   ([`scrambled_index`]) instead of once per four dimensions;
//! * the direction-vector XOR over the index's 16 bits is four table lookups, one per
//!   nibble ([`NibbleTables`]: for each pair of dimension sets, nibble position and nibble
//!   value, the XOR of the direction vectors that nibble selects), instead of a loop over
//!   the set bits;
//! * the per-lane hashing and Owen scrambling run over eight lanes in plain Rust, compiled
//!   twice: with AVX2 (eight 32-bit multiplies per instruction; chosen at run time when the
//!   CPU has it) and for the baseline.
//!
//! The operations are those of `sobol_burley::sample_4d` lane by lane, so the floats are the
//! same (`eight_equals_sobol_burley` checks every dimension pair at many indices and seeds).

use std::sync::OnceLock;

use sobol_burley::parts::{hash, owen_scramble_rev, sobol_int4_rev, u32_to_f32_norm};
use sobol_burley::{NUM_DIMENSIONS, NUM_DIMENSION_SETS_4D};

/// Pairs of four-dimension sets (eight dimensions each).
pub const PAIRS: u32 = NUM_DIMENSIONS / 8;

/// `sobol_burley`'s per-lane scramble constants (dimension mod 4).
const LANE_SALT: [u32; 4] = [0x912f69ba, 0x174f18ab, 0x691e72ca, 0xb40cc1b8];

/// For each dimension pair, nibble position (0: the index's top nibble) and nibble value,
/// the XOR of the direction vectors (bit-reversed, as `sobol_burley` keeps them) of the
/// eight dimensions that the nibble's set bits select.
struct NibbleTables(Box<[[[[u32; 8]; 16]; 4]]>);

/// The tables, built on first use (64 KiB) from `sobol_burley`'s own Sobol sums.
fn tables() -> &'static NibbleTables {
    static TABLES: OnceLock<NibbleTables> = OnceLock::new();
    TABLES.get_or_init(|| {
        debug_assert_eq!(NUM_DIMENSION_SETS_4D, 2 * PAIRS);
        let pairs = (0..PAIRS)
            .map(|pair| {
                let mut nibbles = [[[0u32; 8]; 16]; 4];
                for (q, row) in nibbles.iter_mut().enumerate() {
                    for (value, entry) in row.iter_mut().enumerate() {
                        // The reversed index whose only set bits are this nibble's.
                        let index_rev = (value as u32) << (28 - 4 * q);
                        let a: [u32; 4] = sobol_int4_rev(index_rev, 2 * pair).into();
                        let b: [u32; 4] = sobol_int4_rev(index_rev, 2 * pair + 1).into();
                        entry[..4].copy_from_slice(&a);
                        entry[4..].copy_from_slice(&b);
                    }
                }
                nibbles
            })
            .collect();
        NibbleTables(pairs)
    })
}

/// The scrambled, bit-reversed sample index `sobol_burley` feeds to its Sobol sum (only its
/// top 16 bits are used): `owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c68e4a))`.
#[inline]
pub fn scrambled_index(index: u32, seed: u32) -> u32 {
    owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c68e4a)) & 0xffff_0000
}

/// Dimensions `8·pair .. 8·pair + 8` of the sample whose [`scrambled_index`] is `index_rev`,
/// under `seed` (`pair < PAIRS`): `sample_4d(index, 2·pair, seed)` then
/// `sample_4d(index, 2·pair + 1, seed)`.
#[inline]
pub fn eight(index_rev: u32, pair: u32, seed: u32) -> [f32; 8] {
    let t = tables();
    #[cfg(target_arch = "x86_64")]
    if use_avx2() {
        // SAFETY: AVX2 was detected on this CPU.
        return unsafe { eight_avx2(t, index_rev, pair, seed) };
    }
    eight_in(t, index_rev, pair, seed)
}

/// Whether this CPU runs [`eight_avx2`] (detected once).
#[cfg(target_arch = "x86_64")]
fn use_avx2() -> bool {
    static CHOICE: OnceLock<bool> = OnceLock::new();
    *CHOICE.get_or_init(|| std::arch::is_x86_feature_detected!("avx2"))
}

/// Byte indices reversing the byte order of each 32-bit lane (both 128-bit halves).
const REVERSE_BYTES: [u8; 32] = [
    3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, 3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15,
    14, 13, 12,
];

/// Each nibble value reversed, placed in the high nibble of a byte (both halves).
const REVERSED_NIBBLE_HIGH: [u8; 32] = [
    0x00, 0x80, 0x40, 0xc0, 0x20, 0xa0, 0x60, 0xe0, 0x10, 0x90, 0x50, 0xd0, 0x30, 0xb0, 0x70, 0xf0,
    0x00, 0x80, 0x40, 0xc0, 0x20, 0xa0, 0x60, 0xe0, 0x10, 0x90, 0x50, 0xd0, 0x30, 0xb0, 0x70, 0xf0,
];

/// Each nibble value reversed, in the low nibble (both halves).
const REVERSED_NIBBLE_LOW: [u8; 32] = [
    0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf, 0x0, 0x8, 0x4,
    0xc, 0x2, 0xa, 0x6, 0xe, 0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf,
];

/// [`eight_in`] in AVX2 intrinsics: eight 32-bit lanes per instruction, the bit reversal as
/// byte shuffles (byte order, then each nibble through a 16-entry table).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn eight_avx2(t: &NibbleTables, index_rev: u32, pair: u32, seed: u32) -> [f32; 8] {
    use std::arch::x86_64::{__m256i, _mm256_loadu_si256, _mm256_xor_si256};
    let load = |a: &[u32; 8]| _mm256_loadu_si256(a.as_ptr().cast::<__m256i>());
    let rows = &t.0[pair as usize];
    let entry = |q: usize| load(&rows[q][((index_rev >> (28 - 4 * q)) & 0xf) as usize]);
    let sobol = _mm256_xor_si256(
        _mm256_xor_si256(entry(0), entry(1)),
        _mm256_xor_si256(entry(2), entry(3)),
    );
    // The per-lane scramble (`sobol_burley::sample_4d`'s, by dimension set and lane).
    let seed = seed.wrapping_mul(0x9c8f2d3b);
    let mut scramble = [0u32; 8];
    for (lane, s) in scramble.iter_mut().enumerate() {
        *s = seed ^ (2 * pair + (lane / 4) as u32) ^ LANE_SALT[lane % 4];
    }
    scrambled_unit_avx2(sobol, &scramble)
}

/// Dimensions 0 and 1 of four samples (their [`scrambled_index`]es `index_revs`) under
/// `seed`: `[s0d0, s0d1, s1d0, s1d1, …]`, lane by lane what [`eight`] gives for pair 0
/// (dimension set 0, lanes 0 and 1). A bake's hemisphere uses only these two dimensions of
/// each of its samples, so four samples share one pass of the lane arithmetic.
#[inline]
pub fn first_two_of_four(index_revs: [u32; 4], seed: u32) -> [f32; 8] {
    let t = tables();
    #[cfg(target_arch = "x86_64")]
    if use_avx2() {
        // SAFETY: AVX2 was detected on this CPU.
        return unsafe { first_two_of_four_avx2(t, index_revs, seed) };
    }
    let mut out = [0.0; 8];
    for (k, &rev) in index_revs.iter().enumerate() {
        out[2 * k..2 * k + 2].copy_from_slice(&eight_in(t, rev, 0, seed)[..2]);
    }
    out
}

/// [`first_two_of_four`] in AVX2: the Sobol sums of lanes 0 and 1 of each sample as one
/// 64-bit table read per nibble, then [`eight_avx2`]'s scramble on the eight lanes.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn first_two_of_four_avx2(t: &NibbleTables, index_revs: [u32; 4], seed: u32) -> [f32; 8] {
    use std::arch::x86_64::_mm256_set_epi64x;
    let rows = &t.0[0];
    let pair_of = |index_rev: u32| {
        let mut x = 0u64;
        for (q, row) in rows.iter().enumerate() {
            let e = &row[((index_rev >> (28 - 4 * q)) & 0xf) as usize];
            x ^= u64::from(e[0]) | u64::from(e[1]) << 32;
        }
        x as i64
    };
    let sobol = _mm256_set_epi64x(
        pair_of(index_revs[3]),
        pair_of(index_revs[2]),
        pair_of(index_revs[1]),
        pair_of(index_revs[0]),
    );
    let seed = seed.wrapping_mul(0x9c8f2d3b);
    let (d0, d1) = (seed ^ LANE_SALT[0], seed ^ LANE_SALT[1]);
    scrambled_unit_avx2(sobol, &[d0, d1, d0, d1, d0, d1, d0, d1])
}

/// The per-lane hash of `scramble`, the Owen scramble of the Sobol sums `sobol` with it, the
/// bit reversal and the map to `[0, 1)`: `sobol_burley::sample_4d`'s operations after its
/// Sobol sum, eight lanes per instruction.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn scrambled_unit_avx2(sobol: std::arch::x86_64::__m256i, scramble: &[u32; 8]) -> [f32; 8] {
    use std::arch::x86_64::{
        __m256i, _mm256_add_epi32, _mm256_and_si256, _mm256_castsi256_ps, _mm256_loadu_si256,
        _mm256_mullo_epi32, _mm256_or_si256, _mm256_set1_epi32, _mm256_set1_epi8, _mm256_set1_ps,
        _mm256_shuffle_epi8, _mm256_srli_epi16, _mm256_srli_epi32, _mm256_storeu_ps, _mm256_sub_ps,
        _mm256_xor_si256,
    };
    let load = |a: &[u32; 8]| _mm256_loadu_si256(a.as_ptr().cast::<__m256i>());
    let load_bytes = |a: &[u8; 32]| _mm256_loadu_si256(a.as_ptr().cast::<__m256i>());
    let k = |x: u32| _mm256_set1_epi32(x as i32);
    let mut h = load(scramble);
    h = _mm256_xor_si256(h, k(0xe6fe3beb));
    h = _mm256_xor_si256(h, _mm256_srli_epi32(h, 16));
    h = _mm256_mullo_epi32(h, k(0x7feb352d));
    h = _mm256_xor_si256(h, _mm256_srli_epi32(h, 15));
    h = _mm256_mullo_epi32(h, k(0x846ca68b));
    h = _mm256_xor_si256(h, _mm256_srli_epi32(h, 16));
    // Owen scrambling (`sobol_burley::parts::owen_scramble_rev`).
    let mut n = sobol;
    n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, k(0x3d20adea)));
    n = _mm256_add_epi32(n, h);
    n = _mm256_mullo_epi32(n, _mm256_or_si256(_mm256_srli_epi32(h, 16), k(1)));
    n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, k(0x05526c56)));
    n = _mm256_xor_si256(n, _mm256_mullo_epi32(n, k(0x53a22864)));
    // Reverse the bits of each lane: the bytes in reverse order, then in each byte the two
    // nibbles swapped and each reversed.
    n = _mm256_shuffle_epi8(n, load_bytes(&REVERSE_BYTES));
    let nibble = _mm256_set1_epi8(0x0f);
    let lo = _mm256_and_si256(n, nibble);
    let hi = _mm256_and_si256(_mm256_srli_epi16(n, 4), nibble);
    n = _mm256_or_si256(
        _mm256_shuffle_epi8(load_bytes(&REVERSED_NIBBLE_HIGH), lo),
        _mm256_shuffle_epi8(load_bytes(&REVERSED_NIBBLE_LOW), hi),
    );
    // To [0, 1) (`sobol_burley::parts::u32_to_f32_norm`).
    let bits = _mm256_or_si256(_mm256_srli_epi32(n, 9), k(0x3f80_0000));
    let f = _mm256_sub_ps(_mm256_castsi256_ps(bits), _mm256_set1_ps(1.0));
    let mut out = [0f32; 8];
    _mm256_storeu_ps(out.as_mut_ptr(), f);
    out
}

/// The eight lanes in plain Rust, in `sobol_burley::sample_4d`'s order of operations.
#[inline(always)]
fn eight_in(t: &NibbleTables, index_rev: u32, pair: u32, seed: u32) -> [f32; 8] {
    let rows = &t.0[pair as usize];
    let mut sobol = [0u32; 8];
    for (q, row) in rows.iter().enumerate() {
        let entry = &row[((index_rev >> (28 - 4 * q)) & 0xf) as usize];
        for (s, e) in sobol.iter_mut().zip(entry) {
            *s ^= e;
        }
    }
    let seed = seed.wrapping_mul(0x9c8f2d3b);
    let mut out = [0f32; 8];
    for (lane, (o, s)) in out.iter_mut().zip(sobol).enumerate() {
        let set = 2 * pair + (lane / 4) as u32;
        let scramble = seed ^ set ^ LANE_SALT[lane % 4];
        *o = u32_to_f32_norm(owen_scramble_rev(s, hash(scramble)).reverse_bits());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_equals_sobol_burley() {
        for seed in [0u32, 1, 7, 0xdead_beef, 0x9e37_79b9] {
            for index in [0u32, 1, 2, 3, 15, 16, 255, 1000, 4097, 40_000, 65_535] {
                let rev = scrambled_index(index, seed);
                for pair in 0..PAIRS {
                    let got = eight(rev, pair, seed);
                    let a = sobol_burley::sample_4d(index, 2 * pair, seed);
                    let b = sobol_burley::sample_4d(index, 2 * pair + 1, seed);
                    assert_eq!(got[..4], a, "seed {seed} index {index} pair {pair}");
                    assert_eq!(got[4..], b, "seed {seed} index {index} pair {pair}");
                    // The baseline lanes agree with whatever ran above.
                    assert_eq!(eight_in(tables(), rev, pair, seed), got);
                }
            }
        }
    }

    #[test]
    fn first_two_of_four_are_the_first_two_of_eight() {
        for seed in [0u32, 1, 7, 0xdead_beef, 0x9e37_79b9] {
            for first in [0u32, 1, 13, 1000, 40_000, 65_532] {
                let revs: [u32; 4] =
                    std::array::from_fn(|k| scrambled_index(first + k as u32, seed));
                let got = first_two_of_four(revs, seed);
                for (k, &rev) in revs.iter().enumerate() {
                    let want = eight(rev, 0, seed);
                    assert_eq!(
                        got[2 * k..2 * k + 2],
                        want[..2],
                        "seed {seed} index {first}+{k}"
                    );
                    let index = first + k as u32;
                    assert_eq!(got[2 * k], sobol_burley::sample(index, 0, seed));
                    assert_eq!(got[2 * k + 1], sobol_burley::sample(index, 1, seed));
                }
            }
        }
    }
}
