//! Texel-space denoising: an edge-aware à-trous filter (B3-spline 5 × 5 kernel at steps 1,
//! 2, 4, …) over the baked texels of one texture. A texel mixes only with texels that were
//! baked from the surface (the validity mask), lie in the **same UV chart** (never across a
//! chart border, however close the charts are packed: godotengine/godot#82607), face the
//! same way (normal weight) and lie on its tangent plane (position weight), with a colour
//! weight that keeps value edges larger than the noise: its width is `sigma_color` standard
//! deviations of the texel's luminance noise, estimated from the 3 × 3 same-chart
//! neighbourhood of the input and carried through the passes as SVGF does
//! (var′ = Σ w² var / (Σ w)²), so more samples (less noise) blur less and the bias vanishes
//! with the noise. Every pass reads the previous pass's texels only, so the result does not
//! depend on the thread count.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::bake::raster::Coverage;
use crate::bake::seams::charts;
use crate::bake::TexelImage;
use crate::components::{Denoise, TriMesh};

/// B3-spline à-trous weights for offsets −2 … 2.
const KERNEL: [f32; 5] = [1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0];
/// Exponent of the normal weight max(0, n·n′)^k.
const NORMAL_POWER: i32 = 64;
/// Plane distance (in texel sizes, per unit of step) at which the position weight is 1/e.
const PLANE_TEXELS: f32 = 0.5;
/// Smallest noise standard deviation the colour weight assumes (a noiseless texel still
/// mixes with exactly equal neighbours).
const MIN_STD: f32 = 1e-6;
/// No texel.
const NONE: u32 = u32::MAX;

/// What the filter knows of each texel: its chart (or none when not baked), position and
/// normal (object space), and the object-space size of a texel.
#[derive(Debug, Clone)]
pub struct TexelGuide {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Chart of each texel's first sample position; `u32::MAX` where the texel holds no
    /// sample.
    pub chart: Vec<u32>,
    /// Surface position at each texel's first sample position.
    pub position: Vec<Vec3>,
    /// Unit normal there (the mesh's shading normal, or the face normal).
    pub normal: Vec<Vec3>,
    /// √(surface area / covered texels): a texel's side on the surface.
    pub texel_size: f32,
}

/// The guide of a rasterized bake of `mesh` through per-triangle `uvs`.
pub fn guide(coverage: &Coverage, mesh: &TriMesh, uvs: &[[Vec2; 3]]) -> TexelGuide {
    let chart_of = charts(&mesh.positions, &mesh.triangles, uvs);
    let n = coverage.width as usize * coverage.height as usize;
    let mut g = TexelGuide {
        width: coverage.width,
        height: coverage.height,
        chart: vec![NONE; n],
        position: vec![Vec3::ZERO; n],
        normal: vec![Vec3::ZERO; n],
        texel_size: 0.0,
    };
    for j in 0..coverage.height {
        for i in 0..coverage.width {
            let Some(s) = coverage.texel(i, j).iter().flatten().next() else {
                continue;
            };
            let k = j as usize * coverage.width as usize + i as usize;
            let t = s.triangle as usize;
            let b = [1.0 - s.b1 - s.b2, s.b1, s.b2];
            let [p0, p1, p2] = mesh.triangle(t);
            g.chart[k] = chart_of[t];
            g.position[k] = p0 * b[0] + p1 * b[1] + p2 * b[2];
            let face = (p1 - p0).cross(p2 - p0).normalize_or_zero();
            g.normal[k] = match &mesh.normals {
                Some(normals) => {
                    let idx = mesh.triangles[t];
                    (0..3)
                        .map(|c| normals[idx[c] as usize] * b[c])
                        .sum::<Vec3>()
                        .try_normalize()
                        .unwrap_or(face)
                }
                None => face,
            };
        }
    }
    let area: f64 = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.triangle(t);
            0.5 * (b - a).cross(c - a).length() as f64
        })
        .sum();
    let covered = coverage.covered_texels().max(1) as f64;
    g.texel_size = (area / covered).sqrt() as f32;
    g
}

fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// Luminance variance of every baked texel over its 3 × 3 same-chart baked neighbourhood.
fn local_variance(lum: &[f32], baked: &[bool], guide: &TexelGuide) -> Vec<f32> {
    let (w, h) = (guide.width as i64, guide.height as i64);
    (0..h * w)
        .map(|k| {
            let (i, j) = (k % w, k / w);
            let k = k as usize;
            if !baked[k] || guide.chart[k] == NONE {
                return 0.0;
            }
            let (mut n, mut sum, mut sum2) = (0.0f32, 0.0f32, 0.0f32);
            for y in (j - 1).max(0)..=(j + 1).min(h - 1) {
                for x in (i - 1).max(0)..=(i + 1).min(w - 1) {
                    let q = (y * w + x) as usize;
                    if baked[q] && guide.chart[q] == guide.chart[k] {
                        n += 1.0;
                        sum += lum[q];
                        sum2 += lum[q] * lum[q];
                    }
                }
            }
            let mean = sum / n;
            (sum2 / n - mean * mean).max(0.0)
        })
        .collect()
}

/// Denoises the texels of `image` marked in `baked` (texels baked from the surface; others
/// are neither read nor written). Returns the filtered image.
pub fn denoise(
    image: &TexelImage,
    baked: &[bool],
    guide: &TexelGuide,
    settings: Denoise,
) -> TexelImage {
    let (w, h) = (image.width as i64, image.height as i64);
    let mut current = image.texels.clone();
    let lum: Vec<f32> = current.iter().map(|&c| luminance(c)).collect();
    let mut variance = local_variance(&lum, baked, guide);
    for pass in 0..settings.passes {
        let step = 1i64 << pass;
        let plane_scale = PLANE_TEXELS * guide.texel_size * step as f32;
        let sigma = settings.sigma_color;
        let (prev, prev_var) = (&current, &variance);
        let next: Vec<(Vec3, f32)> = (0..h)
            .into_par_iter()
            .flat_map_iter(|j| {
                (0..w).map(move |i| {
                    let k = (j * w + i) as usize;
                    if !baked[k] || guide.chart[k] == NONE {
                        return (prev[k], prev_var[k]);
                    }
                    let (n, p) = (guide.normal[k], guide.position[k]);
                    let l = luminance(prev[k]);
                    let width = sigma * prev_var[k].sqrt().max(MIN_STD);
                    let mut sum = Vec3::ZERO;
                    let mut var_sum = 0.0f32;
                    let mut weight = 0.0f32;
                    for (dy, ky) in KERNEL.iter().enumerate() {
                        for (dx, kx) in KERNEL.iter().enumerate() {
                            let (x, y) = (i + (dx as i64 - 2) * step, j + (dy as i64 - 2) * step);
                            if x < 0 || y < 0 || x >= w || y >= h {
                                continue;
                            }
                            let q = (y * w + x) as usize;
                            if !baked[q] || guide.chart[q] != guide.chart[k] {
                                continue;
                            }
                            let wn = n.dot(guide.normal[q]).max(0.0).powi(NORMAL_POWER);
                            let plane = n.dot(guide.position[q] - p).abs();
                            let wp = if plane_scale > 0.0 {
                                (-plane / plane_scale).exp()
                            } else {
                                1.0
                            };
                            let wc = (-(l - luminance(prev[q])).abs() / width).exp();
                            let wgt = kx * ky * wn * wp * wc;
                            sum += prev[q] * wgt;
                            var_sum += wgt * wgt * prev_var[q];
                            weight += wgt;
                        }
                    }
                    if weight > 0.0 {
                        (sum / weight, var_sum / (weight * weight))
                    } else {
                        (prev[k], prev_var[k])
                    }
                })
            })
            .collect();
        (current, variance) = next.into_iter().unzip();
    }
    TexelImage {
        texels: current,
        ..image.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat `w × h` guide in the plane z = 0 (normal +z), texel size 1, charts split at
    /// column `split`.
    fn flat_guide(w: u32, h: u32, split: u32) -> TexelGuide {
        let n = (w * h) as usize;
        TexelGuide {
            width: w,
            height: h,
            chart: (0..n).map(|k| u32::from(k as u32 % w >= split)).collect(),
            position: (0..n)
                .map(|k| Vec3::new((k as u32 % w) as f32, (k as u32 / w) as f32, 0.0))
                .collect(),
            normal: vec![Vec3::Z; n],
            texel_size: 1.0,
        }
    }

    /// Values ≈ `left` (columns < split) and ≈ `right`, with ±`noise` hashed noise.
    fn noisy(w: u32, h: u32, split: u32, left: f32, right: f32, noise: f32) -> TexelImage {
        let mut img = TexelImage::new(w, h);
        for k in 0..(w * h) as usize {
            let base = if (k as u32 % w) < split { left } else { right };
            let r = (crate::sampling::hash_combine(&[k as u32, 7]) as f32 / u32::MAX as f32) * 2.0
                - 1.0;
            img.texels[k] = Vec3::splat(base + noise * r);
            img.valid[k] = true;
        }
        img
    }

    fn rms(img: &TexelImage, w: u32, split: u32, left: f32, right: f32) -> f32 {
        let s: f32 = img
            .texels
            .iter()
            .enumerate()
            .map(|(k, t)| {
                let want = if (k as u32 % w) < split { left } else { right };
                (t.x - want).powi(2)
            })
            .sum();
        (s / img.texels.len() as f32).sqrt()
    }

    #[test]
    fn reduces_noise_within_a_chart() {
        let (w, h) = (32, 32);
        let img = noisy(w, h, w, 0.6, 0.6, 0.1);
        let g = flat_guide(w, h, w);
        let out = denoise(&img, &img.valid, &g, Denoise::default());
        let (before, after) = (rms(&img, w, w, 0.6, 0.6), rms(&out, w, w, 0.6, 0.6));
        assert!(after < before / 3.0, "rms {before} → {after}");
    }

    #[test]
    fn never_mixes_two_charts_packed_side_by_side() {
        // The same plane, the same normal: only the chart tells the halves apart.
        let (w, h) = (32, 16);
        let img = noisy(w, h, 16, 1.0, 0.01, 0.05);
        let g = flat_guide(w, h, 16);
        let wide = Denoise {
            passes: 5,
            sigma_color: 1e6,
        };
        let out = denoise(&img, &img.valid, &g, wide);
        for (k, t) in out.texels.iter().enumerate() {
            let left = (k as u32 % w) < 16;
            let range = if left { 0.95..=1.05 } else { -0.04..=0.06 };
            assert!(range.contains(&t.x), "texel {k}: {}", t.x);
        }
        // The same filter with one chart leaks: the test above would see it.
        let one = flat_guide(w, h, w);
        let leaked = denoise(&img, &img.valid, &one, wide);
        assert!(leaked.texels[8 * w as usize + 15].x < 0.9);
    }

    #[test]
    fn unbaked_texels_are_neither_read_nor_written() {
        let (w, h) = (16, 16);
        let mut img = noisy(w, h, w, 0.5, 0.5, 0.1);
        let mut baked = img.valid.clone();
        baked[..w as usize].fill(false);
        img.texels[..w as usize].fill(Vec3::splat(100.0));
        let out = denoise(&img, &baked, &flat_guide(w, h, w), Denoise::default());
        assert!(out.texels[w as usize..].iter().all(|t| t.x < 1.0));
        assert!(out.texels[..w as usize].iter().all(|t| t.x == 100.0));
    }

    #[test]
    fn the_same_bits_at_one_and_three_threads() {
        let (w, h) = (40, 24);
        let img = noisy(w, h, 20, 0.8, 0.2, 0.2);
        let g = flat_guide(w, h, 20);
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| denoise(&img, &img.valid, &g, Denoise::default()))
        };
        let (one, three) = (run(1), run(3));
        let bits = |i: &TexelImage| -> Vec<u32> {
            i.texels
                .iter()
                .flat_map(|t| t.to_array().map(f32::to_bits))
                .collect()
        };
        assert_eq!(bits(&one), bits(&three));
        assert_ne!(bits(&one), bits(&img), "it filtered");
    }
}
