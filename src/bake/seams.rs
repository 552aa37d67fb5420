//! UV seams of a bake: mesh edges shared by two triangles (the same two positions, compared
//! by value, so split vertices count) whose UVs differ on the two sides. Each seam edge is
//! sampled into pairs of UV points that show the same surface point in two places of the
//! texture; the seam metric is the difference of the texture read at the two points of each
//! pair. The same edge table gives the UV charts (triangles joined across edges whose UVs
//! agree), which the denoiser keeps apart.

use std::collections::BTreeMap;

use glam::{Vec2, Vec3};

use crate::bake::TexelImage;

/// Seam samples per texel of seam length (the longer of the two sides).
const SAMPLES_PER_TEXEL: f32 = 3.0;
/// UV ends farther apart than this many texels make an edge a seam.
const SEAM_TOLERANCE_TEXELS: f32 = 1e-3;

/// One side of a shared edge: its triangle and the UVs at the edge's lower and higher
/// position (ordered by the positions' bits).
#[derive(Debug, Clone, Copy)]
struct Side {
    triangle: u32,
    uv: [Vec2; 2],
}

/// Two UV points showing the same surface point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeamPair {
    /// The point in the first chart.
    pub a: Vec2,
    /// The point in the second chart.
    pub b: Vec2,
}

/// The seams of a bake: how many edges, and their sample pairs.
#[derive(Debug, Clone, Default)]
pub struct Seams {
    /// Seam edges (edges whose two sides have different UVs).
    pub edges: usize,
    /// Sample pairs along all seam edges, in edge order.
    pub pairs: Vec<SeamPair>,
}

/// Difference across seams of one texture.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SeamDifference {
    /// Mean over the sample pairs of the largest channel difference.
    pub mean: f64,
    /// Largest channel difference of any pair.
    pub max: f64,
}

/// The key of a position: its bits, with −0 as +0.
fn key(p: Vec3) -> [u32; 3] {
    (p + Vec3::ZERO).to_array().map(f32::to_bits)
}

/// Every edge shared by exactly two triangles, as its two sides, in a deterministic order.
fn shared_edges(positions: &[Vec3], triangles: &[[u32; 3]], uvs: &[[Vec2; 3]]) -> Vec<[Side; 2]> {
    let mut edges: BTreeMap<([u32; 3], [u32; 3]), Vec<Side>> = BTreeMap::new();
    for (t, (tri, uv)) in triangles.iter().zip(uvs).enumerate() {
        for e in 0..3 {
            let (i, j) = (e, (e + 1) % 3);
            let (ki, kj) = (
                key(positions[tri[i] as usize]),
                key(positions[tri[j] as usize]),
            );
            if ki == kj {
                continue;
            }
            let (k, side_uv) = if ki < kj {
                ((ki, kj), [uv[i], uv[j]])
            } else {
                ((kj, ki), [uv[j], uv[i]])
            };
            edges.entry(k).or_default().push(Side {
                triangle: t as u32,
                uv: side_uv,
            });
        }
    }
    edges
        .into_values()
        .filter(|sides| sides.len() == 2)
        .map(|sides| [sides[0], sides[1]])
        .collect()
}

/// Whether the two sides map the edge to different UVs (by more than a thousandth of a
/// texel at either end).
fn is_seam(sides: &[Side; 2], size: Vec2) -> bool {
    (0..2).any(|k| {
        ((sides[0].uv[k] - sides[1].uv[k]) * size)
            .abs()
            .max_element()
            > SEAM_TOLERANCE_TEXELS
    })
}

/// The seams of a mesh baked into a `width × height` texture through per-triangle corner
/// `uvs` (aligned with `triangles`). Each seam edge gets `⌈3 · length in texels⌉` sample
/// pairs at the centres of equal parts of the edge.
pub fn find_seams(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    uvs: &[[Vec2; 3]],
    width: u32,
    height: u32,
) -> Seams {
    let size = Vec2::new(width as f32, height as f32);
    let mut seams = Seams::default();
    for sides in shared_edges(positions, triangles, uvs) {
        if !is_seam(&sides, size) {
            continue;
        }
        seams.edges += 1;
        let length = sides
            .iter()
            .map(|s| ((s.uv[1] - s.uv[0]) * size).length())
            .fold(0.0f32, f32::max);
        let n = (length * SAMPLES_PER_TEXEL).ceil().clamp(1.0, 1e6) as u32;
        for k in 0..n {
            let t = (k as f32 + 0.5) / n as f32;
            seams.pairs.push(SeamPair {
                a: sides[0].uv[0].lerp(sides[0].uv[1], t),
                b: sides[1].uv[0].lerp(sides[1].uv[1], t),
            });
        }
    }
    seams
}

/// UV chart of every triangle: triangles sharing an edge with the same UVs on both sides are
/// one chart. Charts are numbered from 0 in order of their lowest triangle.
pub fn charts(positions: &[Vec3], triangles: &[[u32; 3]], uvs: &[[Vec2; 3]]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..triangles.len() as u32).collect();
    fn root(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    for sides in shared_edges(positions, triangles, uvs) {
        // Exact UV equality: a chart is what the texture shows continuously.
        if sides[0].uv != sides[1].uv {
            continue;
        }
        let (a, b) = (
            root(&mut parent, sides[0].triangle),
            root(&mut parent, sides[1].triangle),
        );
        if a != b {
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    let mut number: BTreeMap<u32, u32> = BTreeMap::new();
    (0..triangles.len() as u32)
        .map(|t| {
            let r = root(&mut parent, t);
            let next = number.len() as u32;
            *number.entry(r).or_insert(next)
        })
        .collect()
}

/// The bilinear taps of `uv` on texels that hold a value, weights renormalised to sum 1;
/// `None` when no tap holds one.
pub fn valid_taps(image: &TexelImage, uv: Vec2) -> Option<Vec<(usize, f32)>> {
    let mut taps: Vec<(usize, f32)> = Vec::with_capacity(4);
    for (i, w) in image.bilinear_taps(uv) {
        if w <= 0.0 || !image.valid[i] {
            continue;
        }
        match taps.iter_mut().find(|(j, _)| *j == i) {
            Some(t) => t.1 += w,
            None => taps.push((i, w)),
        }
    }
    let sum: f32 = taps.iter().map(|t| t.1).sum();
    if sum <= 0.0 {
        return None;
    }
    for t in &mut taps {
        t.1 /= sum;
    }
    Some(taps)
}

/// The texture read at `uv` from texels that hold a value.
fn read(image: &TexelImage, uv: Vec2) -> Option<Vec3> {
    valid_taps(image, uv).map(|taps| taps.iter().map(|&(i, w)| image.texels[i] * w).sum())
}

/// Mean and max over the seam pairs of the largest channel difference of `image` read at the
/// two points (pairs with a side reading no texel are left out).
pub fn seam_difference(image: &TexelImage, seams: &Seams) -> SeamDifference {
    let mut sum = 0.0f64;
    let mut max = 0.0f64;
    let mut n = 0u64;
    for pair in &seams.pairs {
        let (Some(a), Some(b)) = (read(image, pair.a), read(image, pair.b)) else {
            continue;
        };
        let d = (a - b).abs().max_element() as f64;
        sum += d;
        max = max.max(d);
        n += 1;
    }
    SeamDifference {
        mean: if n > 0 { sum / n as f64 } else { 0.0 },
        max,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two unit squares side by side in space (x ∈ [0, 2]), each with its own vertices; the
    /// left one maps to u ∈ [0, ½], the right one to u ∈ [½, 1] mirrored, so the shared edge
    /// x = 1 is at u = ½ on the left and u = 1 on the right.
    fn mirrored_pair() -> (Vec<Vec3>, Vec<[u32; 3]>, Vec<[Vec2; 3]>) {
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ];
        let triangles = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
        let uv = |u: f32, v: f32| Vec2::new(u, v);
        let uvs = vec![
            [uv(0.0, 0.0), uv(0.5, 0.0), uv(0.5, 1.0)],
            [uv(0.0, 0.0), uv(0.5, 1.0), uv(0.0, 1.0)],
            [uv(1.0, 0.0), uv(0.5, 0.0), uv(0.5, 1.0)],
            [uv(1.0, 0.0), uv(0.5, 1.0), uv(1.0, 1.0)],
        ];
        (positions, triangles, uvs)
    }

    #[test]
    fn the_shared_edge_of_two_charts_is_one_seam_sampled_three_times_per_texel() {
        let (p, t, uv) = mirrored_pair();
        let seams = find_seams(&p, &t, &uv, 8, 8);
        assert_eq!(seams.edges, 1);
        // The edge is 8 texels long on both sides: 24 pairs.
        assert_eq!(seams.pairs.len(), 24);
        for pair in &seams.pairs {
            assert_eq!(pair.a.x, 0.5);
            assert_eq!(pair.b.x, 1.0);
            assert_eq!(pair.a.y, pair.b.y);
        }
        assert_eq!(charts(&p, &t, &uv), vec![0, 0, 1, 1]);
    }

    #[test]
    fn a_continuous_square_has_no_seam_and_one_chart() {
        let (p, t, mut uv) = mirrored_pair();
        for tri in &mut uv[2..] {
            for c in tri.iter_mut() {
                c.x = 1.5 - c.x; // the right square continues the left one: u = ½ at x = 1
            }
        }
        assert_eq!(find_seams(&p, &t, &uv, 8, 8).edges, 0);
        assert_eq!(charts(&p, &t, &uv), vec![0, 0, 0, 0]);
    }

    #[test]
    fn the_metric_reads_both_sides() {
        let (p, t, uv) = mirrored_pair();
        let seams = find_seams(&p, &t, &uv, 8, 8);
        let mut img = TexelImage::new(8, 8);
        for j in 0..8 {
            for i in 0..8 {
                img.texels[j * 8 + i] = Vec3::splat(if i < 4 { 1.0 } else { 0.25 });
                img.valid[j * 8 + i] = true;
            }
        }
        // u = ½ reads half of column 3 (1) and half of column 4 (¼); u = 1 reads column 7.
        let d = seam_difference(&img, &seams);
        assert!((d.mean - 0.375).abs() < 1e-6, "{d:?}");
        assert!((d.max - 0.375).abs() < 1e-6, "{d:?}");
    }
}
