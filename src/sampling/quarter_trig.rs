//! Sine and cosine of an angle in [−π/4, π/4] as short polynomials (the Cephes `sinf`/`cosf`
//! minimax kernels), for the concentric disk map, whose angle never leaves a quarter turn
//! once its two branches are folded onto one ([`super::sample_concentric_disk`]). Within 2 ulp
//! of the correctly rounded values there; no range reduction, no library call.

/// `(sin a, cos a)` for `|a| ≤ π/4`.
#[inline]
pub fn sin_cos_quarter(a: f32) -> (f32, f32) {
    let z = a * a;
    let sin = ((-1.951_529_6e-4 * z + 8.332_161e-3) * z - 1.666_665_5e-1) * z * a + a;
    let cos = ((2.443_315_7e-5 * z - 1.388_731_6e-3) * z + 4.166_664_6e-2) * z * z - 0.5 * z + 1.0;
    (sin, cos)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between two finite floats of one sign.
    fn ulps(a: f32, b: f32) -> u32 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs() as u32
    }

    #[test]
    fn within_two_ulp_of_the_library_on_the_quarter_turn() {
        let n = 200_000;
        let q = std::f32::consts::FRAC_PI_4;
        let mut worst = (0u32, 0u32);
        for i in 0..=n {
            let a = -q + 2.0 * q * i as f32 / n as f32;
            let (s, c) = sin_cos_quarter(a);
            let (rs, rc) = ((a as f64).sin() as f32, (a as f64).cos() as f32);
            // Near zero the sine's relative error is what matters; compare by ulp there too.
            worst.0 = worst.0.max(ulps(s, rs));
            worst.1 = worst.1.max(ulps(c, rc));
        }
        assert!(worst.0 <= 2 && worst.1 <= 2, "worst ulp error {worst:?}");
        assert_eq!(sin_cos_quarter(0.0), (0.0, 1.0));
    }
}
