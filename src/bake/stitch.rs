//! Seam stitching: changes the texels under the seams' bilinear taps so that both sides of
//! every seam read alike, by least squares (as Godot's lightmapper blends seams, but solved
//! globally): minimise Σ_pairs (read(a) − read(b))² + λ Σ_texels (x − x₀)² over the texels
//! the pairs read, per channel, by conjugate gradients on the normal equations
//! (DᵀD + λI) x = λ x₀. Sequential and in a fixed order, so deterministic. Texels no pair
//! reads are not touched. A channel whose seams already read alike (every pair's difference
//! exactly 0) is left as it is, and every stitched value is kept within the range of the
//! baked values of the taps its pairs mix (so AO stays ≤ 1 and irradiance ≥ 0).

use glam::Vec3;

use crate::bake::seams::{valid_taps, Seams};
use crate::bake::TexelImage;

/// Weight of keeping texels at their baked values against closing the seams.
const LAMBDA: f64 = 0.01;
/// Conjugate gradients stop when the residual falls below this fraction of the right side.
const TOLERANCE: f64 = 1e-9;
/// Most conjugate-gradient iterations.
const MAX_ITERATIONS: usize = 2000;
/// A pair reads alike when its two sides differ by at most this fraction of its largest tap
/// (a few f32 ulps: the bilinear weights are f32).
const MATCH_TOLERANCE: f64 = 1e-6;

/// One seam pair as a sparse row of D: unknown index and weight (read(a) − read(b)).
type Row = Vec<(u32, f64)>;

/// Stitches `image` across `seams`; returns how many texels it changed.
pub fn stitch(image: &mut TexelImage, seams: &Seams) -> u64 {
    let mut unknown_of = vec![u32::MAX; image.texels.len()];
    let mut texel_of: Vec<usize> = Vec::new();
    let mut rows: Vec<Row> = Vec::with_capacity(seams.pairs.len());
    for pair in &seams.pairs {
        let (Some(a), Some(b)) = (valid_taps(image, pair.a), valid_taps(image, pair.b)) else {
            continue;
        };
        let mut row: Row = Vec::with_capacity(8);
        for (taps, sign) in [(a, 1.0), (b, -1.0)] {
            for (texel, w) in taps {
                if unknown_of[texel] == u32::MAX {
                    unknown_of[texel] = texel_of.len() as u32;
                    texel_of.push(texel);
                }
                let u = unknown_of[texel];
                match row.iter_mut().find(|(v, _)| *v == u) {
                    Some(entry) => entry.1 += sign * w as f64,
                    None => row.push((u, sign * w as f64)),
                }
            }
        }
        if row.iter().any(|&(_, w)| w != 0.0) {
            rows.push(row);
        }
    }
    if rows.is_empty() {
        return 0;
    }
    let mut changed = vec![false; texel_of.len()];
    for c in 0..3 {
        let x0: Vec<f64> = texel_of
            .iter()
            .map(|&t| image.texels[t][c] as f64)
            .collect();
        if rows.iter().all(|row| reads_alike(row, &x0)) {
            continue;
        }
        let range = tap_ranges(&rows, &x0);
        let x = solve(&rows, &x0);
        for (k, &t) in texel_of.iter().enumerate() {
            let (low, high) = range[k];
            let v = x[k].clamp(low, high) as f32;
            if v != image.texels[t][c] {
                changed[k] = true;
            }
            let mut texel: Vec3 = image.texels[t];
            texel[c] = v;
            image.texels[t] = texel;
        }
    }
    changed.iter().filter(|&&c| c).count() as u64
}

/// Whether the two sides of one pair read alike at the values `x`: their difference is at
/// most [`MATCH_TOLERANCE`] of the largest tap (the f32 rounding of the bilinear weights).
fn reads_alike(row: &Row, x: &[f64]) -> bool {
    let difference: f64 = row.iter().map(|&(u, w)| w * x[u as usize]).sum();
    let largest = row
        .iter()
        .map(|&(u, _)| x[u as usize].abs())
        .fold(0.0, f64::max);
    difference.abs() <= MATCH_TOLERANCE * largest
}

/// Per unknown, the lowest and highest value in `x0` of every tap of every pair that reads
/// it: the range its stitched value may take.
fn tap_ranges(rows: &[Row], x0: &[f64]) -> Vec<(f64, f64)> {
    let mut range: Vec<(f64, f64)> = x0.iter().map(|&v| (v, v)).collect();
    for row in rows {
        let (low, high) = row
            .iter()
            .map(|&(u, _)| x0[u as usize])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(v), h.max(v))
            });
        for &(u, _) in row {
            let r = &mut range[u as usize];
            *r = (r.0.min(low), r.1.max(high));
        }
    }
    range
}

/// y = (DᵀD + λI) x.
fn apply(rows: &[Row], x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi = LAMBDA * xi;
    }
    for row in rows {
        let s: f64 = row.iter().map(|&(u, w)| w * x[u as usize]).sum();
        for &(u, w) in row {
            y[u as usize] += w * s;
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Solves (DᵀD + λI) x = λ x₀ by conjugate gradients from x₀.
fn solve(rows: &[Row], x0: &[f64]) -> Vec<f64> {
    let n = x0.len();
    let b: Vec<f64> = x0.iter().map(|v| LAMBDA * v).collect();
    let mut x = x0.to_vec();
    let mut ax = vec![0.0; n];
    apply(rows, &x, &mut ax);
    let mut r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
    let mut p = r.clone();
    let mut rr = dot(&r, &r);
    let stop = (TOLERANCE * TOLERANCE * dot(&b, &b)).max(f64::MIN_POSITIVE);
    let mut ap = vec![0.0; n];
    for _ in 0..MAX_ITERATIONS {
        if rr <= stop {
            break;
        }
        apply(rows, &p, &mut ap);
        let pap = dot(&p, &ap);
        if pap <= 0.0 {
            break;
        }
        let alpha = rr / pap;
        for k in 0..n {
            x[k] += alpha * p[k];
            r[k] -= alpha * ap[k];
        }
        let rr_next = dot(&r, &r);
        let beta = rr_next / rr;
        rr = rr_next;
        for k in 0..n {
            p[k] = r[k] + beta * p[k];
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bake::seams::{seam_difference, SeamPair};
    use glam::Vec2;

    /// A 16 × 8 image whose column 3 and column 12 show the same surface line (a seam between
    /// u = 3.5/16 and u = 12.5/16), with different noisy values on the two sides.
    fn two_sided() -> (TexelImage, Seams) {
        let (w, h) = (16u32, 8u32);
        let mut img = TexelImage::new(w, h);
        for j in 0..h as usize {
            for i in 0..w as usize {
                let noise = ((i * 7 + j * 13) % 5) as f32 * 0.05;
                let base = if i < 8 { 1.0 } else { 0.3 };
                img.texels[j * w as usize + i] = Vec3::new(base + noise, 0.5, base - noise);
                img.valid[j * w as usize + i] = true;
            }
        }
        let pairs = (0..24)
            .map(|k| {
                let v = (k as f32 + 0.5) / 24.0;
                SeamPair {
                    a: Vec2::new(3.5 / 16.0, v),
                    b: Vec2::new(12.5 / 16.0, v),
                }
            })
            .collect();
        (img, Seams { edges: 1, pairs })
    }

    #[test]
    fn closes_the_seam_and_touches_only_texels_it_reads() {
        let (mut img, seams) = two_sided();
        let before = img.clone();
        let d0 = seam_difference(&img, &seams);
        let changed = stitch(&mut img, &seams);
        let d1 = seam_difference(&img, &seams);
        assert!(d0.mean > 0.5, "{d0:?}");
        assert!(d1.max < d0.mean / 50.0, "{d0:?} → {d1:?}");
        assert!(changed > 0);
        for j in 0..8 {
            for i in 0..16 {
                let k = j * 16 + i;
                if i != 3 && i != 12 {
                    assert_eq!(img.texels[k], before.texels[k], "texel ({i}, {j})");
                }
            }
        }
        // The green channel agreed already: unchanged to the last bit or nearly.
        assert!(img.texels.iter().all(|t| (t.y - 0.5).abs() < 1e-6));
    }

    #[test]
    fn stitched_values_stay_within_the_taps_and_matching_seams_are_left_alone() {
        let (mut img, seams) = two_sided();
        let before = img.clone();
        stitch(&mut img, &seams);
        for c in 0..3 {
            let low = before.texels.iter().map(|t| t[c]).fold(f32::MAX, f32::min);
            let high = before.texels.iter().map(|t| t[c]).fold(f32::MIN, f32::max);
            assert!(img.texels.iter().all(|t| (low..=high).contains(&t[c])));
        }
        let (mut flat, seams) = two_sided();
        flat.texels.iter_mut().for_each(|t| *t = Vec3::ONE);
        let before = flat.clone();
        assert_eq!(stitch(&mut flat, &seams), 0);
        assert_eq!(flat, before);
    }

    #[test]
    fn without_seams_nothing_changes() {
        let (mut img, _) = two_sided();
        let before = img.clone();
        assert_eq!(stitch(&mut img, &Seams::default()), 0);
        assert_eq!(img, before);
    }
}
