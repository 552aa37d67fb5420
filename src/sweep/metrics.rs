//! Error of an image (or baked texture) against a reference: MSE, relMSE, maximum error,
//! non-finite values, and — over several seeds — bias² and variance (`None` from one seed,
//! which cannot tell them apart: the CSV leaves them empty, the JSON writes `null`).

use glam::Vec3;
use serde::Serialize;

/// relMSE denominator offset (pbrt's `--mse` convention keeps dark pixels from dominating).
pub const REL_EPSILON: f64 = 1e-2;

/// Error metrics of one knob value (over all its seeds).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ErrorMetrics {
    /// Mean squared error per channel, averaged over seeds.
    pub mse: f64,
    /// Mean of `(x − r)² / (r² + 0.01)` per channel, averaged over seeds.
    pub rel_mse: f64,
    /// Largest absolute channel error over all seeds.
    pub max_error: f64,
    /// Channels that are NaN or infinite, over all seeds.
    pub non_finite: u64,
    /// Mean over channels of (mean over seeds − reference)² (`None` with one seed).
    pub bias2: Option<f64>,
    /// Mean over channels of the variance across seeds (`None` with one seed).
    pub variance: Option<f64>,
}

/// Compares the images of several seeds (same size as `reference`) with the reference.
pub fn compare(images: &[Vec<Vec3>], reference: &[Vec3]) -> ErrorMetrics {
    let mut m = ErrorMetrics::default();
    if images.is_empty() || reference.is_empty() {
        return m;
    }
    let n = reference.len() as f64 * 3.0;
    for img in images {
        let (mut se, mut rel) = (0.0f64, 0.0f64);
        for (x, r) in img.iter().zip(reference) {
            for c in 0..3 {
                let (x, r) = (x[c] as f64, r[c] as f64);
                if !x.is_finite() {
                    m.non_finite += 1;
                    continue;
                }
                let d = x - r;
                se += d * d;
                rel += d * d / (r * r + REL_EPSILON);
                m.max_error = m.max_error.max(d.abs());
            }
        }
        m.mse += se / n;
        m.rel_mse += rel / n;
    }
    let k = images.len() as f64;
    m.mse /= k;
    m.rel_mse /= k;
    if images.len() > 1 {
        let (mut bias2, mut var) = (0.0f64, 0.0f64);
        for (p, r) in reference.iter().enumerate() {
            for c in 0..3 {
                let values = images
                    .iter()
                    .map(|img| img[p][c] as f64)
                    .filter(|v| v.is_finite());
                let (mut sum, mut sum2, mut count) = (0.0, 0.0, 0.0);
                for v in values {
                    sum += v;
                    sum2 += v * v;
                    count += 1.0;
                }
                if count < 2.0 {
                    continue;
                }
                let mean = sum / count;
                bias2 += (mean - r[c] as f64).powi(2);
                var += (sum2 - count * mean * mean).max(0.0) / (count - 1.0);
            }
        }
        m.bias2 = Some(bias2 / n);
        m.variance = Some(var / n);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_images_have_zero_error() {
        let r = vec![Vec3::new(0.5, 1.0, 2.0); 4];
        let m = compare(&[r.clone(), r.clone()], &r);
        assert_eq!(
            (m.mse, m.rel_mse, m.max_error, m.bias2, m.variance),
            (0.0, 0.0, 0.0, Some(0.0), Some(0.0))
        );
    }

    #[test]
    fn bias_and_variance_split_the_error() {
        let r = vec![Vec3::ZERO; 1];
        // Two seeds at +1 and +3: mean 2 → bias² 4, sample variance 2, MSE (1 + 9)/2 = 5.
        let a = vec![Vec3::splat(1.0)];
        let b = vec![Vec3::splat(3.0)];
        let m = compare(&[a, b], &r);
        let (bias2, variance) = (m.bias2.unwrap(), m.variance.unwrap());
        assert!((bias2 - 4.0).abs() < 1e-12 && (variance - 2.0).abs() < 1e-12);
        assert!((m.mse - 5.0).abs() < 1e-12 && m.max_error == 3.0);
    }

    #[test]
    fn non_finite_values_are_counted_not_averaged() {
        let r = vec![Vec3::ONE; 2];
        let img = vec![Vec3::new(f32::NAN, 1.0, 1.0), Vec3::ONE];
        let m = compare(&[img], &r);
        assert_eq!(m.non_finite, 1);
        assert_eq!(m.mse, 0.0);
        // One seed cannot split its error into bias and variance.
        assert_eq!((m.bias2, m.variance), (None, None));
    }
}
