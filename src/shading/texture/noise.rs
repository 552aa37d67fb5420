//! Solid noise for texture nodes: Perlin gradient noise, fractal Brownian motion and
//! turbulence. Deterministic: the value depends only on the point and the node's parameters
//! (the seed is a parameter), never on threads or sample order. The lattice noise is the
//! one displacement uses ([`crate::noise::perlin`]).

use glam::{DVec3, Vec3};

pub use crate::components::graph::Fractal;
use crate::noise::perlin;

/// Conservative bound of one octave of [`noise`] (gradient noise with cube-edge gradients).
pub const OCTAVE_BOUND: f32 = crate::noise::PERLIN_BOUND as f32;

impl Fractal {
    /// A bound of |fbm| and of turbulence: `OCTAVE_BOUND · Σ |gain|^i`.
    pub fn bound(&self) -> f32 {
        let g = self.gain.abs();
        let sum: f32 = (0..self.octaves.clamp(1, 12))
            .map(|i| g.powi(i as i32))
            .sum();
        OCTAVE_BOUND * sum
    }

    fn octaves(&self, p: Vec3, mut f: impl FnMut(f32) -> f32) -> f32 {
        let p = p.as_dvec3();
        let mut sum = 0.0;
        let mut freq = self.frequency as f64;
        let mut amp = 1.0f32;
        for i in 0..self.octaves.clamp(1, 12) {
            let seed = self.seed ^ u64::from(i).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            sum += amp * f(perlin(p * freq + octave_offset(i), seed) as f32);
            freq *= self.lacunarity as f64;
            amp *= self.gain;
        }
        if sum.is_finite() {
            sum
        } else {
            0.0
        }
    }
}

/// Offset of octave `i` so octaves do not all vanish together at the origin.
fn octave_offset(i: u32) -> DVec3 {
    let k = f64::from(i);
    DVec3::new(17.31 * k, 43.97 * k, 71.13 * k)
}

/// One octave of Perlin noise at `p · frequency`, in about [−1, 1].
pub fn noise(p: Vec3, frequency: f32, seed: u64) -> f32 {
    let v = perlin(p.as_dvec3() * frequency as f64, seed) as f32;
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

/// Fractal Brownian motion `Σ gain^i · noise(frequency · lacunarity^i · p)`; signed.
pub fn fbm(p: Vec3, fractal: &Fractal) -> f32 {
    fractal.octaves(p, |n| n)
}

/// Turbulence `Σ gain^i · |noise(frequency · lacunarity^i · p)|`; non-negative.
pub fn turbulence(p: Vec3, fractal: &Fractal) -> f32 {
    fractal.octaves(p, f32::abs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fractal(seed: u64) -> Fractal {
        Fractal {
            frequency: 3.0,
            octaves: 5,
            lacunarity: 2.0,
            gain: 0.5,
            seed,
        }
    }

    fn points() -> impl Iterator<Item = Vec3> {
        (0..4000).map(|i| {
            let i = i as f32;
            Vec3::new(
                (i * 0.618_034).fract() * 7.0 - 3.0,
                (i * 0.414_214).fract() * 5.0,
                (i * 0.732_051).fract() * 3.0 - 9.0,
            )
        })
    }

    #[test]
    fn noise_is_deterministic_and_bounded() {
        let f = fractal(7);
        let mut spread = (f32::MAX, f32::MIN);
        for p in points() {
            let n = noise(p, 2.0, 7);
            assert_eq!(n.to_bits(), noise(p, 2.0, 7).to_bits());
            assert!(n.abs() <= OCTAVE_BOUND, "{n}");
            let b = fbm(p, &f);
            assert_eq!(b.to_bits(), fbm(p, &f).to_bits());
            assert!(b.abs() <= f.bound(), "{b}");
            let t = turbulence(p, &f);
            assert!((0.0..=f.bound()).contains(&t), "{t}");
            spread = (spread.0.min(n), spread.1.max(n));
        }
        // Not degenerate: it really varies over about [−1, 1].
        assert!(spread.0 < -0.5 && spread.1 > 0.5, "{spread:?}");
    }

    #[test]
    fn seeds_give_different_patterns_and_non_finite_points_give_zero() {
        let differ = points()
            .filter(|&p| fbm(p, &fractal(1)) != fbm(p, &fractal(2)))
            .count();
        assert!(differ > 3900, "{differ}");
        assert_eq!(fbm(Vec3::splat(f32::NAN), &fractal(1)), 0.0);
        assert_eq!(noise(Vec3::splat(f32::INFINITY), 1.0, 0), 0.0);
        // Huge but finite points saturate the lattice coordinates without overflow.
        assert!(noise(Vec3::splat(1e30), 1e30, 0).is_finite());
        assert!(fbm(Vec3::splat(-3e38), &fractal(1)).is_finite());
    }
}
