//! Pixel reconstruction filters, sampled by importance: a sample's film offset is drawn from
//! the filter itself, so every sample has weight one and a pixel is a plain average of its own
//! samples (deterministic, no cross-pixel splatting).

use glam::Vec2;

use crate::settings::PixelFilter;

const TABLE_SIZE: usize = 256;

/// Draws film offsets (relative to the pixel centre, in pixels) from a pixel filter.
#[derive(Debug, Clone)]
pub struct FilterSampler {
    kind: PixelFilter,
    /// Tabulated CDF of the 1-D truncated Gaussian over [−radius, radius].
    cdf: Vec<f32>,
}

impl FilterSampler {
    /// Prepares sampling tables for `filter`.
    pub fn new(filter: PixelFilter) -> Self {
        let cdf = match filter {
            PixelFilter::Box => Vec::new(),
            PixelFilter::Gaussian { sigma, radius } => {
                let sigma = sigma.max(1e-3) as f64;
                let radius = radius.max(1e-3) as f64;
                let g = |x: f64| (-(x * x) / (2.0 * sigma * sigma)).exp();
                let floor = g(radius);
                let mut cdf = vec![0.0f64; TABLE_SIZE + 1];
                for i in 0..TABLE_SIZE {
                    let x0 = -radius + 2.0 * radius * i as f64 / TABLE_SIZE as f64;
                    let x1 = -radius + 2.0 * radius * (i + 1) as f64 / TABLE_SIZE as f64;
                    let v = 0.5 * ((g(x0) - floor).max(0.0) + (g(x1) - floor).max(0.0));
                    cdf[i + 1] = cdf[i] + v;
                }
                let total = cdf[TABLE_SIZE].max(f64::MIN_POSITIVE);
                cdf.iter().map(|c| (c / total) as f32).collect()
            }
        };
        Self { kind: filter, cdf }
    }

    /// Film offset from the pixel centre for `u ∈ [0,1)²`.
    pub fn sample(&self, u: Vec2) -> Vec2 {
        match self.kind {
            PixelFilter::Box => u - Vec2::splat(0.5),
            PixelFilter::Gaussian { radius, .. } => {
                Vec2::new(self.sample_1d(u.x, radius), self.sample_1d(u.y, radius))
            }
        }
    }

    fn sample_1d(&self, u: f32, radius: f32) -> f32 {
        // Last index with cdf[i] <= u.
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, TABLE_SIZE) - 1;
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let frac = if c1 > c0 { (u - c0) / (c1 - c0) } else { 0.5 };
        let x = (i as f32 + frac.clamp(0.0, 1.0)) / TABLE_SIZE as f32;
        (2.0 * x - 1.0) * radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_offsets_cover_the_pixel() {
        let f = FilterSampler::new(PixelFilter::Box);
        assert_eq!(f.sample(Vec2::ZERO), Vec2::splat(-0.5));
        assert_eq!(f.sample(Vec2::splat(0.5)), Vec2::ZERO);
    }

    #[test]
    fn gaussian_offsets_have_the_filter_variance() {
        let sigma = 0.5;
        let f = FilterSampler::new(PixelFilter::Gaussian { sigma, radius: 3.0 });
        let n = 20000;
        let mut sum = 0.0f64;
        let mut sum2 = 0.0f64;
        for i in 0..n {
            let x = f.sample(Vec2::new((i as f32 + 0.5) / n as f32, 0.5)).x as f64;
            assert!(x.abs() <= 3.0);
            sum += x;
            sum2 += x * x;
        }
        let mean = sum / n as f64;
        let var = sum2 / n as f64 - mean * mean;
        assert!(mean.abs() < 1e-3, "mean {mean}");
        // Truncated at 6σ the variance is σ² up to table resolution.
        assert!(
            (var.sqrt() - sigma as f64).abs() < 0.01,
            "std {}",
            var.sqrt()
        );
    }
}
