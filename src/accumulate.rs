//! Precise accumulation of samples: Neumaier-compensated sums in f64, so that a pixel or
//! texel mean stays exact to ~1e-15 relative however many samples it averages (a plain f32
//! running sum stops growing once an increment falls below half an ulp).

use glam::{DVec3, Vec3};

/// A compensated (Neumaier) sum of f64 values.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CompensatedSum {
    sum: f64,
    compensation: f64,
}

impl CompensatedSum {
    /// Adds `x`.
    #[inline]
    pub fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.compensation += (self.sum - t) + x;
        } else {
            self.compensation += (x - t) + self.sum;
        }
        self.sum = t;
    }

    /// The sum.
    #[inline]
    pub fn value(&self) -> f64 {
        self.sum + self.compensation
    }
}

/// The mean of RGB samples, accumulated with compensated f64 sums.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SampleMean {
    channels: [CompensatedSum; 3],
    count: u64,
}

impl SampleMean {
    /// Adds one sample.
    #[inline]
    pub fn add(&mut self, v: Vec3) {
        let d = v.as_dvec3();
        self.channels[0].add(d.x);
        self.channels[1].add(d.y);
        self.channels[2].add(d.z);
        self.count += 1;
    }

    /// Samples added.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// Sum of the samples.
    pub fn sum(&self) -> DVec3 {
        DVec3::new(
            self.channels[0].value(),
            self.channels[1].value(),
            self.channels[2].value(),
        )
    }

    /// Sum divided by `n` (the sample count the estimator averages over, which may include
    /// samples that contributed nothing), rounded once to f32.
    pub fn mean_over(&self, n: u64) -> Vec3 {
        if n == 0 {
            return Vec3::ZERO;
        }
        (self.sum() / n as f64).as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compensated_sum_recovers_small_increments() {
        let mut s = CompensatedSum::default();
        s.add(1e16);
        for _ in 0..1000 {
            s.add(1.0);
        }
        s.add(-1e16);
        assert_eq!(s.value(), 1000.0);
    }
}
