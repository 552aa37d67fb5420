//! Adaptive anti-aliasing (mental ray's `samples min max` with a `contrast`): how many camera
//! samples each pixel takes.
//!
//! The rule, in two deterministic passes over the image:
//! 1. every pixel takes `min` samples;
//! 2. a pixel is refined when the standard error of its mean (sample standard deviation /
//!    √n) exceeds `contrast` in some channel, or when its mean differs from the pass-1 mean
//!    of one of its eight neighbours by more than `contrast` in some channel (an edge its own
//!    few samples may have missed). A refined pixel doubles its sample count until its
//!    error estimate is at most `contrast` in every channel or it reaches `max`. The error
//!    estimate is the standard error, but for a pixel refined because of a neighbour that
//!    differs by Δ at least `√3·Δ / n`: by the rule of three, n agreeing samples only show
//!    that an edge of contrast Δ covers less than 3/n of the pixel.
//!
//! Every decision reads only pass-1 results and the pixel's own samples, which are indexed
//! by (seed, pixel, sample): the image is the same for any thread count or tile order.

use glam::{DVec3, Vec3};

use crate::exact_sum::ExactSum;
use crate::settings::RenderSettings;

/// How many samples pixels take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleBudget {
    /// Samples of pass 1 (every pixel).
    pub min: u32,
    /// Most samples of one pixel.
    pub max: u32,
    /// Per-channel threshold (standard error, and difference between neighbours).
    pub contrast: Vec3,
}

impl SampleBudget {
    /// The budget of `settings`: adaptive, or `spp` everywhere (`min = max`).
    pub fn new(settings: &RenderSettings) -> Self {
        match settings.adaptive {
            Some(a) => {
                let min = a.min.max(1);
                Self {
                    min,
                    max: a.max.max(min),
                    contrast: a.contrast,
                }
            }
            None => {
                let n = settings.spp.max(1);
                Self {
                    min: n,
                    max: n,
                    contrast: Vec3::INFINITY,
                }
            }
        }
    }

    /// Whether any pixel can take more than `min` samples.
    pub fn refines(&self) -> bool {
        self.max > self.min
    }

    /// Size of the next batch of a refined pixel that has taken `taken` samples (doubling,
    /// capped at `max`); 0 when it is done.
    pub fn next_batch(&self, taken: u32) -> u32 {
        taken.max(1).min(self.max.saturating_sub(taken))
    }
}

/// The samples one pixel has taken: their exact sums (so that parts of a farm render merge
/// to the same bits, see `crate::farm`), per-channel variance (Welford, f64), coverage and
/// non-finite drops.
#[derive(Debug, Clone, Default)]
pub struct PixelSamples {
    sums: [ExactSum; 3],
    n: u64,
    mean: DVec3,
    m2: DVec3,
    /// Samples whose camera ray hit something.
    pub covered: u32,
    /// Samples taken (including dropped ones).
    pub taken: u32,
    /// Non-finite samples dropped (counted as black).
    pub dropped: u32,
}

impl PixelSamples {
    /// Records one sample: its radiance (`None` when non-finite) and whether it hit.
    pub fn add(&mut self, radiance: Vec3, hit: bool) {
        if !self.add_to_sums(radiance, hit) {
            return;
        }
        let x = radiance.as_dvec3();
        self.n += 1;
        let d = x - self.mean;
        self.mean += d / self.n as f64;
        self.m2 += d * (x - self.mean);
    }

    /// Records one sample like [`Self::add`] but without the variance estimate, for a pixel
    /// that is never refined: the sums and counts (so [`Self::value`], [`Self::alpha`] and
    /// [`Self::sums`]) are the same bits, and [`Self::converged`] stays false. Always inlined:
    /// it is the per-sample step of both sample loops in `shade`, and called out of line it
    /// cost 0.25 % of the Cornell box's path-traced instructions.
    #[inline(always)]
    pub fn add_unmeasured(&mut self, radiance: Vec3, hit: bool) {
        self.add_to_sums(radiance, hit);
    }

    /// The sums and counts of [`Self::add`]; whether the sample was finite.
    #[inline(always)]
    fn add_to_sums(&mut self, radiance: Vec3, hit: bool) -> bool {
        self.taken += 1;
        self.covered += u32::from(hit);
        if !radiance.is_finite() {
            self.dropped += 1;
            return false;
        }
        self.sums[0].add(radiance.x);
        self.sums[1].add(radiance.y);
        self.sums[2].add(radiance.z);
        true
    }

    /// The pixel value: sum over the samples taken.
    pub fn value(&self) -> Vec3 {
        pixel_value(&self.sums, self.taken)
    }

    /// The exact per-channel sums of the finite samples.
    pub fn sums(&self) -> &[ExactSum; 3] {
        &self.sums
    }

    /// Coverage in [0, 1].
    pub fn alpha(&self) -> f32 {
        pixel_alpha(self.covered, self.taken)
    }

    /// Whether the standard error of the mean is at most `contrast` in every channel (never
    /// with fewer than two samples).
    pub fn converged(&self, contrast: Vec3) -> bool {
        self.converged_near(contrast, Vec3::ZERO)
    }

    /// [`Self::converged`] for a pixel whose neighbours differ from it by up to `delta`:
    /// the error estimate is at least `√3·delta / n` (see the module doc).
    pub fn converged_near(&self, contrast: Vec3, delta: Vec3) -> bool {
        if self.n < 2 {
            return false;
        }
        let n = self.n as f64;
        let se2 = self.m2 / ((n - 1.0) * n);
        let edge = delta.as_dvec3() * (3f64.sqrt() / n);
        let c = contrast.as_dvec3();
        se2.cmple(c * c).all() && edge.cmple(c).all()
    }
}

/// A pixel's value from the exact sums of its samples over the `taken` samples (dropped
/// ones count as black), rounded once per channel.
pub fn pixel_value(sums: &[ExactSum; 3], taken: u32) -> Vec3 {
    if taken == 0 {
        return Vec3::ZERO;
    }
    let n = f64::from(taken);
    Vec3::new(
        (sums[0].to_f64() / n) as f32,
        (sums[1].to_f64() / n) as f32,
        (sums[2].to_f64() / n) as f32,
    )
}

/// A pixel's coverage in [0, 1]: the share of its samples whose camera ray hit something.
pub fn pixel_alpha(covered: u32, taken: u32) -> f32 {
    if taken == 0 {
        0.0
    } else {
        covered as f32 / taken as f32
    }
}

/// Which pixels of a `width × height` image pass 2 refines, from the pass-1 samples
/// (row-major): `None` for pixels that are done, else the largest per-channel difference to
/// a neighbour that exceeds `contrast` (zero when only the pixel's own error triggered it).
pub fn refine_flags(
    pass1: &[PixelSamples],
    width: usize,
    height: usize,
    contrast: Vec3,
) -> Vec<Option<Vec3>> {
    let means: Vec<Vec3> = pass1.iter().map(PixelSamples::value).collect();
    (0..width * height)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            let mut delta = Vec3::ZERO;
            for ny in y.saturating_sub(1)..(y + 2).min(height) {
                for nx in x.saturating_sub(1)..(x + 2).min(width) {
                    let d = (means[i] - means[ny * width + nx]).abs();
                    if d.cmpgt(contrast).any() {
                        delta = delta.max(d);
                    }
                }
            }
            (delta != Vec3::ZERO || !pass1[i].converged(contrast)).then_some(delta)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixel(values: &[f32]) -> PixelSamples {
        let mut p = PixelSamples::default();
        for &v in values {
            p.add(Vec3::splat(v), true);
        }
        p
    }

    #[test]
    fn standard_error_decides_convergence() {
        // Two values 0 and 1: sd 0.707, standard error 0.5.
        let p = pixel(&[0.0, 1.0]);
        assert!(p.converged(Vec3::splat(0.51)) && !p.converged(Vec3::splat(0.49)));
        assert!(pixel(&[0.3; 4]).converged(Vec3::ZERO));
        assert!(!pixel(&[0.3]).converged(Vec3::splat(1.0)));
        // Agreeing samples next to a neighbour differing by 1: √3/n ≤ 0.1 needs n ≥ 18.
        assert!(!pixel(&[0.0; 16]).converged_near(Vec3::splat(0.1), Vec3::ONE));
        assert!(pixel(&[0.0; 18]).converged_near(Vec3::splat(0.1), Vec3::ONE));
        let mut nan = pixel(&[0.5, 0.5]);
        nan.add(Vec3::NAN, true);
        assert_eq!(nan.dropped, 1);
        assert!((nan.value().x - 1.0 / 3.0).abs() < 1e-6);
    }

    #[test]
    fn unmeasured_samples_give_the_same_sums_and_counts_bit_for_bit() {
        let (mut measured, mut unmeasured) = (PixelSamples::default(), PixelSamples::default());
        let mut state = 0x2545_f491u32;
        for k in 0..5000u32 {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            let v = match k % 97 {
                0 => f32::NAN,
                1 => f32::INFINITY,
                2 => -0.0,
                3 => f32::from_bits(1),
                _ => f32::from_bits(state & 0x7f7f_ffff) * if k % 3 == 0 { -1.0 } else { 1.0 },
            };
            let radiance = Vec3::new(v, v * 0.5, (k as f32).sqrt());
            measured.add(radiance, k % 7 != 0);
            unmeasured.add_unmeasured(radiance, k % 7 != 0);
            assert_eq!(measured.sums(), unmeasured.sums());
            assert_eq!(
                (measured.taken, measured.covered, measured.dropped),
                (unmeasured.taken, unmeasured.covered, unmeasured.dropped)
            );
            assert_eq!(
                measured.value().to_array().map(f32::to_bits),
                unmeasured.value().to_array().map(f32::to_bits)
            );
            assert_eq!(measured.alpha().to_bits(), unmeasured.alpha().to_bits());
        }
        assert!(measured.dropped > 0);
        assert!(
            !unmeasured.converged(Vec3::INFINITY),
            "no variance estimate, never converged"
        );
    }

    #[test]
    fn neighbours_that_differ_are_refined() {
        // 3×1 image: flat 0, flat 0, flat 1 → the middle and right pixels differ.
        let pass1 = vec![pixel(&[0.0; 4]), pixel(&[0.0; 4]), pixel(&[1.0; 4])];
        let flags = refine_flags(&pass1, 3, 1, Vec3::splat(0.1));
        assert_eq!(flags, vec![None, Some(Vec3::ONE), Some(Vec3::ONE)]);
    }

    #[test]
    fn batches_double_up_to_max() {
        let b = SampleBudget {
            min: 4,
            max: 20,
            contrast: Vec3::ZERO,
        };
        assert_eq!(
            [
                b.next_batch(4),
                b.next_batch(8),
                b.next_batch(16),
                b.next_batch(20)
            ],
            [4, 8, 4, 0]
        );
    }
}
