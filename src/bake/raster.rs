//! Texel coverage: rasterizes UV triangles into texel space with conservative coverage and
//! several sample positions per texel.
//!
//! A texel is covered by a triangle when their areas overlap (separating-axis test; touching
//! along an edge or at a corner is not overlap).
//! Each covered texel gets the sub-sample positions (a k×k grid) that lie inside a triangle,
//! first triangle wins; a covered texel with no sub-sample inside any triangle (a sliver) gets
//! one sample at the point of the first overlapping triangle closest to the texel centre, so
//! chart borders are baked from the surface itself instead of left empty.

use glam::{DVec2, Vec2};

/// One sample position of a texel on the mesh: a local triangle and barycentrics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TexelSample {
    /// Mesh-local triangle index.
    pub triangle: u32,
    /// Barycentric weight of vertex 1.
    pub b1: f32,
    /// Barycentric weight of vertex 2.
    pub b2: f32,
}

/// The rasterized coverage of one bake.
#[derive(Debug, Clone)]
pub struct Coverage {
    /// Texture width.
    pub width: u32,
    /// Texture height.
    pub height: u32,
    /// Sub-samples per texel (k²).
    pub per_texel: u32,
    /// `width · height · per_texel` slots, texel-major, row 0 at the top.
    pub samples: Vec<Option<TexelSample>>,
    /// Sub-samples inside two or more triangles (UV overlap), each counted once (so at most
    /// `inside`).
    pub overlaps: u64,
    /// Sub-samples inside some triangle.
    pub inside: u64,
}

impl Coverage {
    /// The sample slots of texel `(i, j)`.
    pub fn texel(&self, i: u32, j: u32) -> &[Option<TexelSample>] {
        let k = self.per_texel as usize;
        let t = (j as usize * self.width as usize + i as usize) * k;
        &self.samples[t..t + k]
    }

    /// Whether texel `(i, j)` has at least one sample.
    pub fn is_covered(&self, i: u32, j: u32) -> bool {
        self.texel(i, j).iter().any(Option::is_some)
    }

    /// Number of covered texels.
    pub fn covered_texels(&self) -> u64 {
        let k = self.per_texel as usize;
        self.samples
            .chunks_exact(k)
            .filter(|t| t.iter().any(Option::is_some))
            .count() as u64
    }
}

/// Rasterizes per-triangle corner UVs (v up) into a `width × height` texture with
/// `texel_samples` (rounded up to k²) sample positions per texel.
pub fn rasterize(uvs: &[[Vec2; 3]], width: u32, height: u32, texel_samples: u32) -> Coverage {
    let k = (texel_samples.max(1) as f64).sqrt().ceil() as u32;
    let per_texel = k * k;
    let mut samples = vec![None; width as usize * height as usize * per_texel as usize];
    let mut fallback: Vec<Option<TexelSample>> = vec![None; width as usize * height as usize];
    let mut overlaps = 0u64;
    let mut claimed_twice = vec![false; samples.len()];
    let mut inside_count = 0u64;
    let (w, h) = (width as f64, height as f64);
    for (t, corners) in uvs.iter().enumerate() {
        // Texel space: x right, y down, texel (i, j) covers [i, i+1] × [j, j+1].
        let p = corners.map(|uv| DVec2::new(uv.x as f64 * w, (1.0 - uv.y as f64) * h));
        let area2 = (p[1] - p[0]).perp_dot(p[2] - p[0]);
        if !area2.is_finite() || area2 == 0.0 {
            continue;
        }
        let lo = p[0].min(p[1]).min(p[2]);
        let hi = p[0].max(p[1]).max(p[2]);
        let i0 = lo.x.floor().max(0.0) as i64;
        let j0 = lo.y.floor().max(0.0) as i64;
        let i1 = (hi.x.ceil() as i64).min(width as i64 - 1);
        let j1 = (hi.y.ceil() as i64).min(height as i64 - 1);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let cell_lo = DVec2::new(i as f64, j as f64);
                if !triangle_overlaps_cell(&p, cell_lo) {
                    continue;
                }
                let texel = j as usize * width as usize + i as usize;
                let mut any_inside = false;
                for s in 0..per_texel {
                    let q = cell_lo
                        + DVec2::new(
                            ((s % k) as f64 + 0.5) / k as f64,
                            ((s / k) as f64 + 0.5) / k as f64,
                        );
                    let Some((b1, b2, strict)) = barycentric(&p, area2, q) else {
                        continue;
                    };
                    any_inside = true;
                    let index = texel * per_texel as usize + s as usize;
                    let slot = &mut samples[index];
                    match slot {
                        None => {
                            *slot = Some(TexelSample {
                                triangle: t as u32,
                                b1: b1 as f32,
                                b2: b2 as f32,
                            });
                            inside_count += 1;
                        }
                        Some(_) if strict && !claimed_twice[index] => {
                            claimed_twice[index] = true;
                            overlaps += 1;
                        }
                        Some(_) => {}
                    }
                }
                if !any_inside && fallback[texel].is_none() {
                    let centre = cell_lo + DVec2::splat(0.5);
                    let (b1, b2) = closest_barycentric(&p, centre);
                    fallback[texel] = Some(TexelSample {
                        triangle: t as u32,
                        b1: b1 as f32,
                        b2: b2 as f32,
                    });
                }
            }
        }
    }
    for (texel, fb) in fallback.into_iter().enumerate() {
        let slots = &mut samples[texel * per_texel as usize..(texel + 1) * per_texel as usize];
        if fb.is_some() && slots.iter().all(Option::is_none) {
            slots[0] = fb;
        }
    }
    Coverage {
        width,
        height,
        per_texel,
        samples,
        overlaps,
        inside: inside_count,
    }
}

/// Barycentrics (b1, b2) of `q` when inside the triangle (edges included), and whether it
/// is strictly inside (not within 1e-9 of an edge, in relative barycentric terms).
fn barycentric(p: &[DVec2; 3], area2: f64, q: DVec2) -> Option<(f64, f64, bool)> {
    let b0 = (p[1] - q).perp_dot(p[2] - q) / area2;
    let b1 = (p[2] - q).perp_dot(p[0] - q) / area2;
    let b2 = 1.0 - b0 - b1;
    let eps = 1e-9;
    if b0 < -eps || b1 < -eps || b2 < -eps {
        return None;
    }
    let strict = b0 > 1e-6 && b1 > 1e-6 && b2 > 1e-6;
    Some((b1.clamp(0.0, 1.0), b2.clamp(0.0, 1.0), strict))
}

/// Separating-axis test of a triangle against the unit cell at `lo`.
fn triangle_overlaps_cell(p: &[DVec2; 3], lo: DVec2) -> bool {
    let hi = lo + DVec2::ONE;
    let tmin = p[0].min(p[1]).min(p[2]);
    let tmax = p[0].max(p[1]).max(p[2]);
    if tmax.x <= lo.x || tmin.x >= hi.x || tmax.y <= lo.y || tmin.y >= hi.y {
        return false;
    }
    let corners = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    for e in 0..3 {
        let a = p[e];
        let b = p[(e + 1) % 3];
        let c = p[(e + 2) % 3];
        let n = (b - a).perp();
        let side_c = n.dot(c - a);
        // All cell corners on the other side of this edge from the triangle (or on its line:
        // touching is not overlapping).
        if corners.iter().all(|&q| n.dot(q - a) * side_c <= 0.0) {
            return false;
        }
    }
    true
}

/// Barycentrics (b1, b2) of the point of the triangle closest to `q`.
fn closest_barycentric(p: &[DVec2; 3], q: DVec2) -> (f64, f64) {
    let area2 = (p[1] - p[0]).perp_dot(p[2] - p[0]);
    if let Some((b1, b2, _)) = barycentric(p, area2, q) {
        return (b1, b2);
    }
    let mut best = (f64::INFINITY, 0.0, 0.0);
    for e in 0..3 {
        let a = p[e];
        let b = p[(e + 1) % 3];
        let ab = b - a;
        let t = ((q - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        let d = (a + ab * t - q).length_squared();
        if d < best.0 {
            // Weights of vertices e and e+1 are (1−t, t).
            let mut w = [0.0; 3];
            w[e] = 1.0 - t;
            w[(e + 1) % 3] = t;
            best = (d, w[1], w[2]);
        }
    }
    (best.1, best.2)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad_uvs() -> Vec<[Vec2; 3]> {
        vec![
            [
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(1.0, 1.0),
            ],
            [
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0, 1.0),
                Vec2::new(0.0, 1.0),
            ],
        ]
    }

    #[test]
    fn full_square_covers_every_texel_without_overlap() {
        let c = rasterize(&quad_uvs(), 8, 4, 4);
        assert_eq!(c.covered_texels(), 32);
        assert_eq!(c.overlaps, 0);
        assert_eq!(c.inside, 32 * 4);
    }

    #[test]
    fn texel_centres_follow_the_v_up_convention() {
        // A triangle covering only the top-left corner region of UV space (v near 1).
        let uvs = vec![[
            Vec2::new(0.0, 1.0),
            Vec2::new(0.2, 1.0),
            Vec2::new(0.0, 0.8),
        ]];
        let c = rasterize(&uvs, 10, 10, 1);
        assert!(c.is_covered(0, 0), "row 0 is the top (v = 1)");
        assert!(!c.is_covered(0, 9));
        // Texel (0, 0) centre is uv (0.05, 0.95): barycentrics of that point.
        let s = c.texel(0, 0)[0].unwrap();
        // uv = (1−b1−b2)·(0,1) + b1·(0.2,1) + b2·(0,0.8) ⇒ b1 = 0.25, b2 = 0.25.
        assert!(
            (s.b1 - 0.25).abs() < 1e-6 && (s.b2 - 0.25).abs() < 1e-6,
            "{s:?}"
        );
    }

    #[test]
    fn overlapping_triangles_are_counted() {
        let mut uvs = quad_uvs();
        uvs.extend(quad_uvs());
        let c = rasterize(&uvs, 4, 4, 1);
        assert!(c.overlaps >= 8, "{}", c.overlaps);
    }

    #[test]
    fn slivers_get_a_fallback_sample_on_the_triangle() {
        // A thin triangle crossing texel (1, 1) without containing its single centre sample.
        let uvs = vec![[
            Vec2::new(0.1, 0.61),
            Vec2::new(0.9, 0.61),
            Vec2::new(0.1, 0.62),
        ]];
        let c = rasterize(&uvs, 4, 4, 1);
        let s = c.texel(1, 1)[0].expect("conservative coverage");
        assert!(s.b1 >= 0.0 && s.b2 >= 0.0 && s.b1 + s.b2 <= 1.0 + 1e-6);
    }
}
