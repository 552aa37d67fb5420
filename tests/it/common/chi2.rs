//! Chi-square goodness-of-fit for direction samplers (after Mitsuba 3's `ChiSquareTest`
//! and pbrt-v4's `bsdfs_test.cpp`): histogram of sampled directions on the sphere in
//! (cosθ, φ) cells of equal solid angle, expected counts from the pdf integrated per cell,
//! cells with expected count < 5 pooled, p-value from the regularised upper incomplete gamma.

use glam::Vec3;
use rayon::prelude::*;

/// A tiny deterministic generator (SplitMix64) for test randomness.
pub struct Rng(pub u64);

impl Rng {
    /// Next uniform number in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Three uniform numbers.
    pub fn next_vec3(&mut self) -> Vec3 {
        Vec3::new(self.next_f32(), self.next_f32(), self.next_f32())
    }
}

/// Šidák-corrected per-test significance for `count` tests at family level `alpha`.
pub fn sidak(alpha: f64, count: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / count as f64)
}

/// Result of one test.
#[derive(Debug)]
pub struct Chi2Outcome {
    /// p-value of the χ² statistic.
    pub p_value: f64,
    /// Degrees of freedom after pooling.
    pub dof: usize,
    /// Fraction of samples that produced a direction.
    pub valid_fraction: f64,
}

/// Runs the test: `sample(u)` draws a unit direction (or `None`), `pdf(w)` is its solid-angle
/// density. Errors on a hard failure (samples where the pdf is zero, pdf integrating to more
/// than 1.02, non-unit or non-finite directions).
pub fn chi2_directions(
    sample: impl FnMut(Vec3) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64 + Sync,
    samples: usize,
    seed: u64,
) -> Result<Chi2Outcome, String> {
    chi2_directions_fine(sample, pdf, samples, seed, 6)
}

/// [`chi2_directions`] integrating the pdf over each cell with `sub × sub` midpoints: for
/// densities with sharp edges inside cells (the cone of a sphere light, a disc's rim).
pub fn chi2_directions_fine(
    mut sample: impl FnMut(Vec3) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64 + Sync,
    samples: usize,
    seed: u64,
    sub: usize,
) -> Result<Chi2Outcome, String> {
    const N_COS: usize = 40;
    const N_PHI: usize = 80;
    let sub = sub.max(1);
    let mut observed = vec![0f64; N_COS * N_PHI];
    let mut rng = Rng(seed);
    let mut valid = 0usize;
    for _ in 0..samples {
        let Some(w) = sample(rng.next_vec3()) else {
            continue;
        };
        if !w.is_finite() || (w.length() - 1.0).abs() > 1e-3 {
            return Err(format!("non-unit or non-finite direction {w}"));
        }
        valid += 1;
        observed[cell(w, N_COS, N_PHI)] += 1.0;
    }
    let d_cos = 2.0 / N_COS as f64;
    let d_phi = 2.0 * std::f64::consts::PI / N_PHI as f64;
    // The cells' pdf integrals (`sub²` pdf calls each, the bulk of the work) are computed in
    // parallel, one cosθ row per task; they are summed below in the serial order.
    let cell_integrals: Vec<f64> = (0..N_COS)
        .into_par_iter()
        .flat_map_iter(|i| {
            let pdf = &pdf;
            (0..N_PHI).map(move |j| {
                let mut acc = 0.0;
                for a in 0..sub {
                    for b in 0..sub {
                        let c = -1.0 + (i as f64 + (a as f64 + 0.5) / sub as f64) * d_cos;
                        let phi = (j as f64 + (b as f64 + 0.5) / sub as f64) * d_phi;
                        let s = (1.0 - c * c).max(0.0).sqrt();
                        let w = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32);
                        acc += pdf(w);
                    }
                }
                acc / (sub * sub) as f64 * d_cos * d_phi
            })
        })
        .collect();
    let mut expected = vec![0f64; N_COS * N_PHI];
    let mut integral = 0.0;
    for (e, cell_integral) in expected.iter_mut().zip(&cell_integrals) {
        integral += cell_integral;
        *e = cell_integral * samples as f64;
    }
    if integral > 1.02 {
        return Err(format!("pdf integrates to {integral}"));
    }
    // Pool small cells; count samples in cells where the pdf vanishes.
    let mut chi2 = 0.0;
    let mut dof = 0usize;
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    let mut stray = 0.0;
    for (o, e) in observed.iter().zip(&expected) {
        if *e == 0.0 {
            stray += o;
        } else if *e < 5.0 {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if stray > 1e-5 * samples as f64 + 1.0 {
        return Err(format!("{stray} samples where the pdf is zero"));
    }
    if pool_e > 0.0 {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        dof += 1;
    }
    let dof = dof.saturating_sub(1).max(1);
    Ok(Chi2Outcome {
        p_value: gamma_q(dof as f64 / 2.0, chi2 / 2.0),
        dof,
        valid_fraction: valid as f64 / samples as f64,
    })
}

fn cell(w: Vec3, n_cos: usize, n_phi: usize) -> usize {
    let c = ((w.z as f64 + 1.0) * 0.5 * n_cos as f64) as usize;
    let mut phi = (w.y as f64).atan2(w.x as f64);
    if phi < 0.0 {
        phi += 2.0 * std::f64::consts::PI;
    }
    let p = (phi / (2.0 * std::f64::consts::PI) * n_phi as f64) as usize;
    c.min(n_cos - 1) * n_phi + p.min(n_phi - 1)
}

fn ln_gamma(x: f64) -> f64 {
    // Lanczos approximation (g = 7, n = 9).
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let t = x + 7.5;
    let mut a = C[0];
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularised upper incomplete gamma Q(a, x).
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let gln = ln_gamma(a);
    if x < a + 1.0 {
        let (mut sum, mut del, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - gln).exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - gln).exp() * h
    }
}
