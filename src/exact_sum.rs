//! Exact, order-independent sums of f32 values, so that a pixel's samples summed in one
//! process or in several parts merged later give the same bits.
//!
//! An [`ExactSum`] is a 320-bit two's-complement fixed-point number whose lowest bit is
//! 2⁻¹⁴⁹ (the smallest f32 subnormal): every finite f32 is an integer multiple of it and
//! the largest (< 2¹²⁸) fits with 2³² summands of headroom below the sign bit, so adding is
//! integer addition — exact, associative and commutative. Rounding happens once, when the
//! sum is read ([`ExactSum::to_f64`], correctly rounded to nearest).

/// Limbs of the fixed-point number, least significant first.
pub const LIMBS: usize = 5;

/// The exponent of bit 0: the value of the number is `limbs × 2^SCALE_EXP`.
const SCALE_EXP: i32 = -149;

/// An exact sum of finite f32 values (see the module header).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct ExactSum {
    limbs: [u64; LIMBS],
}

/// A finite, non-zero `x` as `(negative, limb, wide)`: `|x| = wide · 2^(64·limb − 149)`
/// with `wide` spanning limbs `limb` and `limb + 1 < LIMBS` (`limb ≤ 3`: the exponent's
/// shift is at most 253). `None` for zeros and non-finite values.
#[inline(always)]
fn term_of(x: f32) -> Option<(bool, usize, u128)> {
    let bits = x.to_bits();
    let exponent = (bits >> 23) & 0xff;
    if exponent == 0xff {
        return None;
    }
    let fraction = u64::from(bits & 0x7f_ffff);
    let (mantissa, shift) = if exponent == 0 {
        (fraction, 0)
    } else {
        (fraction | 0x80_0000, exponent - 1)
    };
    if mantissa == 0 {
        return None;
    }
    let wide = u128::from(mantissa) << (shift % 64);
    Some((bits >> 31 == 1, (shift / 64) as usize, wide))
}

impl ExactSum {
    /// The sum with these raw limbs (least significant first), as [`ExactSum::limbs`] gave.
    pub fn from_limbs(limbs: [u64; LIMBS]) -> Self {
        Self { limbs }
    }

    /// The raw limbs, least significant first (for storing a sum losslessly).
    pub fn limbs(&self) -> [u64; LIMBS] {
        self.limbs
    }

    /// Adds `x`; non-finite values are ignored (callers count them as dropped).
    #[inline]
    pub fn add(&mut self, x: f32) {
        match term_of(x) {
            Some((false, limb, wide)) => self.add_at(limb, wide),
            Some((true, limb, wide)) => self.sub_at(limb, wide),
            None => {}
        }
    }

    /// Adds `wide · 2^(64·limb)`: the two limbs it covers, then the carry only as far as
    /// it goes (integer addition mod 2³²⁰, the same bits as adding the whole term).
    #[inline(always)]
    fn add_at(&mut self, limb: usize, wide: u128) {
        self.step_at(limb, wide, u64::overflowing_add);
    }

    /// Subtracts `wide · 2^(64·limb)` (as [`Self::add_at`], with the borrow).
    #[inline(always)]
    fn sub_at(&mut self, limb: usize, wide: u128) {
        self.step_at(limb, wide, u64::overflowing_sub);
    }

    /// [`Self::add_at`] or [`Self::sub_at`]: `step` is `overflowing_add` or
    /// `overflowing_sub`, its flag the carry or the borrow, passed up only while it is set.
    #[inline(always)]
    fn step_at(&mut self, limb: usize, wide: u128, step: impl Fn(u64, u64) -> (u64, bool)) {
        let l = &mut self.limbs;
        let (s, c0) = step(l[limb], wide as u64);
        l[limb] = s;
        let (s, c1) = step(l[limb + 1], (wide >> 64) as u64);
        let (s, c2) = step(s, u64::from(c0));
        l[limb + 1] = s;
        let mut carry = c1 | c2;
        let mut i = limb + 2;
        while carry && i < LIMBS {
            let (s, c) = step(l[i], 1);
            l[i] = s;
            carry = c;
            i += 1;
        }
    }

    /// Adds another exact sum (merging partial sums).
    #[inline]
    pub fn merge(&mut self, other: &ExactSum) {
        self.add_limbs(&other.limbs);
    }

    fn add_limbs(&mut self, term: &[u64; LIMBS]) {
        let mut carry = false;
        for (a, &b) in self.limbs.iter_mut().zip(term) {
            let (s, c1) = a.overflowing_add(b);
            let (s, c2) = s.overflowing_add(u64::from(carry));
            *a = s;
            carry = c1 || c2;
        }
    }

    /// The sum, correctly rounded to the nearest f64.
    pub fn to_f64(&self) -> f64 {
        let negative = self.limbs[LIMBS - 1] >> 63 == 1;
        let magnitude = if negative {
            negated(self.limbs)
        } else {
            self.limbs
        };
        let Some(top) = (0..LIMBS).rev().find(|&i| magnitude[i] != 0) else {
            return 0.0;
        };
        let high = u128::from(magnitude[top]) << 64;
        let low = if top > 0 { magnitude[top - 1] } else { 0 };
        // Bits below the two top limbs only decide ties: fold them into a sticky bit (the
        // 128-bit window holds at least 65 significant bits, more than f64's 53 + guard).
        let sticky = magnitude[..top.saturating_sub(1)].iter().any(|&l| l != 0);
        let window = high | u128::from(low) | u128::from(sticky);
        let exponent = 64 * (top as i32 - 1) + SCALE_EXP;
        let value = window as f64 * power_of_two(exponent);
        if negative {
            -value
        } else {
            value
        }
    }
}

/// Two's-complement negation.
fn negated(mut limbs: [u64; LIMBS]) -> [u64; LIMBS] {
    let mut carry = true;
    for l in &mut limbs {
        let (s, c) = (!*l).overflowing_add(u64::from(carry));
        *l = s;
        carry = c;
    }
    limbs
}

/// 2^e for the exponents [`ExactSum::to_f64`] needs (−213 … 43), exactly.
fn power_of_two(e: i32) -> f64 {
    f64::from_bits(((1023 + e) as u64) << 52)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum(values: &[f32]) -> ExactSum {
        let mut s = ExactSum::default();
        for &v in values {
            s.add(v);
        }
        s
    }

    #[test]
    fn small_sums_are_exact() {
        assert_eq!(sum(&[]).to_f64(), 0.0);
        assert_eq!(sum(&[1.0, 2.0, 0.5]).to_f64(), 3.5);
        assert_eq!(sum(&[1.0, -3.0]).to_f64(), -2.0);
        assert_eq!(
            sum(&[f32::MIN_POSITIVE / 4.0]).to_f64(),
            f64::from(f32::MIN_POSITIVE) / 4.0
        );
        assert_eq!(
            sum(&[f32::MAX, f32::MAX]).to_f64(),
            2.0 * f64::from(f32::MAX)
        );
        assert_eq!(sum(&[f32::NAN, f32::INFINITY, 1.0]).to_f64(), 1.0);
    }

    #[test]
    fn large_and_tiny_terms_do_not_absorb_each_other() {
        // 1e30 + 1e-30 - 1e30 is exactly 1e-30 (as f32), where any float sum gives 0.
        let tiny = 1e-30f32;
        assert_eq!(sum(&[1e30, tiny, -1e30]).to_f64(), f64::from(tiny));
    }

    #[test]
    fn any_split_and_order_give_the_same_bits() {
        let values: Vec<f32> = (0..1000u32)
            .map(|i| (i.wrapping_mul(2_654_435_761) % 10_007) as f32 * 1.37e-3 - 3.1)
            .collect();
        let whole = sum(&values);
        for parts in [2, 3, 7] {
            let mut merged = ExactSum::default();
            for chunk in values.chunks(values.len().div_ceil(parts)).rev() {
                merged.merge(&sum(chunk));
            }
            assert_eq!(merged, whole);
        }
        let mut reversed = values.clone();
        reversed.reverse();
        assert_eq!(sum(&reversed), whole);
        let reference: f64 = values.iter().map(|&v| f64::from(v)).sum();
        assert!((whole.to_f64() - reference).abs() < 1e-9);
    }

    /// The former `add`: the whole 320-bit term built, negated for a negative `x`, added.
    fn add_by_whole_term(s: &mut ExactSum, x: f32) {
        let Some((negative, limb, wide)) = term_of(x) else {
            return;
        };
        let mut term = [0u64; LIMBS];
        term[limb] = wide as u64;
        term[limb + 1] = (wide >> 64) as u64;
        if negative {
            term = negated(term);
        }
        s.merge(&ExactSum::from_limbs(term));
    }

    /// `add` (the term's two limbs, then the carry or borrow only as far as it goes) gives
    /// the bits of adding the whole term, for every kind of f32 (zeros, subnormals, both
    /// signs, the largest, non-finite) and accumulators whose limbs sit at the carry and
    /// borrow edges (all ones, zero, sign changes).
    #[test]
    fn add_at_two_limbs_equals_adding_the_whole_term() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let edges = [0u64, 1, u64::MAX, u64::MAX - 1, 1 << 63, (1 << 63) - 1];
        let mut values: Vec<f32> = [
            0.0,
            -0.0,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NAN,
            1.0,
            -1.0,
        ]
        .to_vec();
        for _ in 0..2000 {
            values.push(f32::from_bits(next() as u32));
        }
        for round in 0..3000 {
            let mut limbs = [0u64; LIMBS];
            for l in &mut limbs {
                *l = if next() % 2 == 0 {
                    edges[(next() % edges.len() as u64) as usize]
                } else {
                    next()
                };
            }
            let (mut fast, mut whole) = (ExactSum::from_limbs(limbs), ExactSum::from_limbs(limbs));
            for k in 0..8 {
                let x = values[(round * 8 + k) % values.len()];
                fast.add(x);
                add_by_whole_term(&mut whole, x);
                assert_eq!(
                    fast,
                    whole,
                    "limbs {limbs:x?}, x = {x:e} ({:#x})",
                    x.to_bits()
                );
            }
        }
    }

    #[test]
    fn limbs_round_trip() {
        let s = sum(&[0.25, -7.5, 1e-40]);
        assert_eq!(ExactSum::from_limbs(s.limbs()), s);
    }
}
