//! The power heuristic as the integrators' loops evaluate it: [`power_heuristic`](crate::shading::mis::power_heuristic)'s value bit
//! for bit, with its "positive and finite" test as one integer compare
//! ([`usable_pdf`]) instead of the class test LLVM makes of the two float compares
//! (≈ 20 integer instructions on baseline x86-64, at every MIS weight).

use crate::sampling::usable_pdf;
#[cfg(test)]
use crate::shading::mis::power_heuristic;

/// [`power_heuristic`](crate::shading::mis::power_heuristic)`(a, b)`, the same bits for every pair of `f32`.
#[inline(always)]
pub(crate) fn power_weight(a: f32, b: f32) -> f32 {
    if a.is_infinite() {
        return 1.0;
    }
    let (a2, b2) = (a * a, b * b);
    let sum = a2 + b2;
    if !usable_pdf(sum) {
        return if a >= b { 1.0 } else { 0.0 };
    }
    a2 / sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::hash_u32;

    #[test]
    fn power_weight_equals_the_power_heuristic_bit_for_bit() {
        let special = [
            0.0f32,
            -0.0,
            f32::from_bits(1),
            f32::MIN_POSITIVE,
            1e-20,
            1e-19,
            0.5,
            1.0,
            3.0,
            1e19,
            1e20,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -1.0,
        ];
        let mut pairs: Vec<(f32, f32)> = special
            .iter()
            .flat_map(|&a| special.iter().map(move |&b| (a, b)))
            .collect();
        let mut h = 0x9e37_79b9u32;
        for _ in 0..200_000 {
            h = hash_u32(h);
            let a = f32::from_bits(h);
            h = hash_u32(h);
            let b = f32::from_bits(h);
            // Raw bit patterns, and pdf-like values of every scale.
            pairs.push((a, b));
            pairs.push((a.abs() % 1e4, b.abs() % 1e4));
        }
        for (a, b) in pairs {
            assert_eq!(
                power_weight(a, b).to_bits(),
                power_heuristic(a, b).to_bits(),
                "{a} {b}"
            );
        }
    }
}
