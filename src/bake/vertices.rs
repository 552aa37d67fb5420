//! Per-vertex bakes (`target: Vertices`): the sample positions of each mesh vertex, laid out
//! as the texels of a [`Coverage`] so the texel estimators, their seeding and the farm's
//! tile split apply unchanged; and the values read back per vertex, with vertices that got
//! no value (every sample inside other geometry, or on no triangle) filled from their
//! neighbours or the nearest vertex with a value ([`fill_missing`]).
//!
//! Vertex `v` of an `N`-vertex mesh is texel `(v mod W, v div W)` of a `W × H` grid with
//! `W = ⌈√N⌉`, `H = ⌈N / W⌉` (square, so rows spread over threads and farm tiles).
//!
//! Sample positions: the vertex's dual cell — in every triangle around it, the quad of the
//! vertex, the two edge midpoints beside it and the centroid (a third of the triangle's
//! area), split into two triangles of equal area. The `k²` sample slots (the request's
//! `texel_samples` rounded up as for textures) are dealt to these pieces by world area
//! ([`deal_slots`]), so each triangle gets samples in proportion to its area
//! (area-weighted), and the slots of a piece are stratified inside it by a fixed
//! low-discrepancy pattern ([`point_in_piece`]) that keeps every position strictly inside
//! the piece: never on the vertex or a triangle edge, which a neighbouring face's plane may
//! contain. No randomness: the positions are the same in every run.

use glam::{Affine3A, Vec2, Vec3};

use super::raster::{Coverage, TexelSample};
use super::TexelImage;
use crate::components::TriMesh;

/// The grid `(width, height)` that holds `vertices` vertices.
pub fn grid(vertices: usize) -> (u32, u32) {
    let n = vertices.max(1);
    let width = (n as f64).sqrt().ceil() as usize;
    let height = n.div_ceil(width);
    (width as u32, height as u32)
}

/// The triangles around each vertex: (triangle, corner) pairs, in triangle order.
fn corners_of_vertices(mesh: &TriMesh) -> Vec<Vec<(u32, usize)>> {
    let mut around = vec![Vec::new(); mesh.positions.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for (c, &v) in tri.iter().enumerate() {
            if let Some(list) = around.get_mut(v as usize) {
                list.push((t as u32, c));
            }
        }
    }
    around
}

/// Barycentric weights `(λ0, λ1, λ2)` of the point `(a, b) ∈ [0, 1)²` mapped uniformly
/// onto half `half` (0 or 1) of corner `corner`'s dual cell.
fn dual_cell_point(corner: usize, half: usize, a: f64, b: f64) -> [f64; 3] {
    let unit = |i: usize| {
        let mut e = [0.0; 3];
        e[i] = 1.0;
        e
    };
    let mid = |i: usize, j: usize| {
        let (x, y) = (unit(i), unit(j));
        [
            (x[0] + y[0]) / 2.0,
            (x[1] + y[1]) / 2.0,
            (x[2] + y[2]) / 2.0,
        ]
    };
    let vertex = unit(corner);
    let centroid = [1.0 / 3.0; 3];
    let (p, q) = if half == 0 {
        (mid(corner, (corner + 1) % 3), centroid)
    } else {
        (centroid, mid(corner, (corner + 2) % 3))
    };
    // Uniform on the triangle (vertex, p, q).
    let r = a.sqrt();
    let (wv, wp, wq) = (1.0 - r, r * (1.0 - b), r * b);
    [0, 1, 2].map(|i| wv * vertex[i] + wp * p[i] + wq * q[i])
}

/// The piece of each of `slots` slots: slot `s` goes to the piece that holds the point
/// `(s + ½) / slots` of the cell's area (pieces laid end to end by their weight `.3`), so
/// each piece gets slots in proportion to its area.
fn deal_slots(pieces: &[(u32, usize, usize, f64)], slots: usize) -> Vec<usize> {
    let total: f64 = pieces.iter().map(|p| p.3).sum();
    let mut piece = 0;
    let mut before = 0.0;
    (0..slots)
        .map(|s| {
            let u = (s as f64 + 0.5) / slots as f64 * total;
            while piece + 1 < pieces.len() && before + pieces[piece].3 <= u {
                before += pieces[piece].3;
                piece += 1;
            }
            piece
        })
        .collect()
}

/// Golden ratio conjugate, the step of the second coordinate's sequence.
const GOLDEN: f64 = 0.618_033_988_749_894_9;

/// The point `(a, b)` for [`dual_cell_point`] of slot `j` of the `m` slots a piece holds:
/// `a = (j + ½) / m` (strata of equal area from the vertex outward) and the golden-ratio
/// sequence `b = frac(½ + j · φ⁻¹)`, both strictly inside `(0, 1)`: the point lies inside the
/// piece, never on the vertex or on the triangle's edges, where a neighbouring face's plane
/// may contain it (a floor's vertex at the foot of a wall).
fn point_in_piece(j: usize, m: usize) -> (f64, f64) {
    let a = (j as f64 + 0.5) / m as f64;
    let b = (0.5 + j as f64 * GOLDEN).fract().clamp(1e-6, 1.0 - 1e-6);
    (a, b)
}

/// The sample positions of every vertex of `mesh` (placed by `world_from_object`, for the
/// area weights) with `texel_samples` (rounded up to `k²`) slots per vertex.
pub fn vertex_coverage(
    mesh: &TriMesh,
    world_from_object: &Affine3A,
    texel_samples: u32,
) -> Coverage {
    let k = (texel_samples.max(1) as f64).sqrt().ceil() as u32;
    let per_texel = (k * k) as usize;
    let (width, height) = grid(mesh.positions.len());
    let mut samples = vec![None; width as usize * height as usize * per_texel];
    let area: Vec<f64> = mesh
        .triangles
        .iter()
        .enumerate()
        .map(|(t, _)| {
            let [a, b, c] = mesh
                .triangle(t)
                .map(|p| world_from_object.transform_point3(p));
            let twice = (b - a).cross(c - a).length() as f64;
            if twice.is_finite() {
                twice / 2.0
            } else {
                0.0
            }
        })
        .collect();
    let mut inside = 0u64;
    for (v, around) in corners_of_vertices(mesh).iter().enumerate() {
        // Two pieces per triangle, each a sixth of its area.
        let pieces: Vec<(u32, usize, usize, f64)> = around
            .iter()
            .filter(|&&(t, _)| area[t as usize] > 0.0)
            .flat_map(|&(t, c)| [0, 1].map(|half| (t, c, half, area[t as usize] / 6.0)))
            .collect();
        let total: f64 = pieces.iter().map(|p| p.3).sum();
        if pieces.is_empty() || total <= 0.0 {
            continue;
        }
        let piece_of_slot = deal_slots(&pieces, per_texel);
        let mut slots_in = vec![0usize; pieces.len()];
        for &p in &piece_of_slot {
            slots_in[p] += 1;
        }
        let mut placed = vec![0usize; pieces.len()];
        for (s, &p) in piece_of_slot.iter().enumerate() {
            let (t, c, half, _) = pieces[p];
            let (a, b) = point_in_piece(placed[p], slots_in[p]);
            placed[p] += 1;
            let l = dual_cell_point(c, half, a, b);
            samples[v * per_texel + s] = Some(TexelSample {
                triangle: t,
                b1: l[1] as f32,
                b2: l[2] as f32,
            });
            inside += 1;
        }
    }
    Coverage {
        width,
        height,
        per_texel: per_texel as u32,
        samples,
        overlaps: 0,
        inside,
    }
}

/// Zero corner UVs for every triangle (per-vertex bakes have no texture frame).
pub fn no_uvs(mesh: &TriMesh) -> Vec<[Vec2; 3]> {
    vec![[Vec2::ZERO; 3]; mesh.triangles.len()]
}

/// The values of the first `vertices` texels of `img` (vertex order), `None` where no value
/// was baked.
pub fn vertex_values(img: &TexelImage, vertices: usize) -> Vec<Option<Vec3>> {
    (0..vertices)
        .map(|v| {
            img.valid
                .get(v)
                .copied()
                .unwrap_or(false)
                .then(|| img.texels[v])
        })
        .collect()
}

/// Passes of neighbour filling for vertices without a value.
const FILL_PASSES: usize = 16;

/// Gives every vertex without a value one, in three steps:
/// 1. the mean of its neighbours' values (vertices sharing a triangle), pass by pass from the
///    previous pass's values (so the order of vertices does not matter), at most
///    [`FILL_PASSES`] passes;
/// 2. a vertex still without one — on no triangle of the mesh (unused, or used only by
///    degenerate triangles the loader dropped) or in a part of the mesh without any value —
///    takes the value of the nearest vertex that has one after step 1 (object-space
///    distance, ties to the lower index; a vertex at a baked vertex's position gets exactly
///    its value);
/// 3. zero, only when no vertex of the mesh has a value.
///
/// Returns how many vertices were filled.
pub fn fill_missing(mesh: &TriMesh, values: &mut [Option<Vec3>]) -> u64 {
    let mut filled = 0u64;
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); values.len()];
    for tri in &mesh.triangles {
        for (c, &v) in tri.iter().enumerate() {
            for d in 1..3 {
                let w = tri[(c + d) % 3];
                if let Some(list) = neighbours.get_mut(v as usize) {
                    if (w as usize) < values.len() && !list.contains(&w) {
                        list.push(w);
                    }
                }
            }
        }
    }
    for _ in 0..FILL_PASSES {
        let before = values.to_vec();
        let mut changed = false;
        for (v, value) in values.iter_mut().enumerate() {
            if value.is_some() {
                continue;
            }
            let known: Vec<Vec3> = neighbours[v]
                .iter()
                .filter_map(|&w| before[w as usize])
                .collect();
            if !known.is_empty() {
                *value = Some(known.iter().sum::<Vec3>() / known.len() as f32);
                filled += 1;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    filled + fill_from_nearest(mesh, values)
}

/// Walks `side` (vertices with their x, moving away from `q.x`) until the x distance alone
/// exceeds `best`'s distance, keeping in `best` the nearest (squared distance, index; the
/// lower index on a tie).
fn scan<'a>(
    side: impl Iterator<Item = &'a (f64, usize)>,
    q: glam::DVec3,
    best: &mut (f64, usize),
    position: &impl Fn(usize) -> glam::DVec3,
) {
    for &(x, w) in side {
        if (x - q.x) * (x - q.x) > best.0 {
            break;
        }
        let d = position(w).distance_squared(q);
        if d < best.0 || (d == best.0 && w < best.1) {
            *best = (d, w);
        }
    }
}

/// Step 2 and 3 of [`fill_missing`]: every vertex without a value takes the value of the
/// nearest vertex with one (read before any is filled here), or zero when none has one.
/// Returns how many vertices were filled.
fn fill_from_nearest(mesh: &TriMesh, values: &mut [Option<Vec3>]) -> u64 {
    let missing: Vec<usize> = (0..values.len()).filter(|&v| values[v].is_none()).collect();
    if missing.is_empty() {
        return 0;
    }
    let position = |v: usize| {
        mesh.positions
            .get(v)
            .map_or(glam::DVec3::ZERO, |p| p.as_dvec3())
    };
    // The vertices with a value, by x (then index): a query scans outward from its own x
    // and stops where the x distance alone exceeds the best distance found.
    let mut known: Vec<(f64, usize)> = (0..values.len())
        .filter(|&v| values[v].is_some())
        .map(|v| (position(v).x, v))
        .collect();
    known.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let found: Vec<(usize, Vec3)> = missing
        .iter()
        .map(|&v| {
            let q = position(v);
            let mut best = (f64::INFINITY, usize::MAX);
            let start = known.partition_point(|&(x, _)| x < q.x);
            scan(known[start..].iter(), q, &mut best, &position);
            scan(known[..start].iter().rev(), q, &mut best, &position);
            let value = values.get(best.1).copied().flatten();
            (v, value.unwrap_or(Vec3::ZERO))
        })
        .collect();
    for &(v, value) in &found {
        values[v] = Some(value);
    }
    found.len() as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> TriMesh {
        TriMesh {
            positions: vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
                Vec3::new(5.0, 5.0, 5.0),
            ],
            normals: None,
            uvs: None,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn the_grid_is_square_and_holds_every_vertex() {
        assert_eq!(grid(1), (1, 1));
        assert_eq!(grid(5), (3, 2));
        assert_eq!(grid(16), (4, 4));
        assert_eq!(grid(17), (5, 4));
    }

    #[test]
    fn samples_stay_in_the_dual_cell_and_follow_the_area() {
        let mesh = square();
        let cov = vertex_coverage(&mesh, &Affine3A::IDENTITY, 64);
        assert_eq!((cov.width, cov.height, cov.per_texel), (3, 2, 64));
        // Vertex 4 is on no triangle: no samples.
        assert!(!cov.is_covered(1, 1));
        // Vertex 0 is on both triangles (equal areas): half of its samples in each, each
        // with vertex 0's weight at least the others' (inside the dual cell).
        let slots = cov.texel(0, 0);
        let mut per_triangle = [0; 2];
        for s in slots.iter().flatten() {
            per_triangle[s.triangle as usize] += 1;
            let l0 = 1.0 - s.b1 - s.b2;
            assert!(l0 + 1e-6 >= s.b1 && l0 + 1e-6 >= s.b2, "{s:?}");
        }
        assert_eq!(per_triangle, [32, 32]);
        // Vertex 1 is on the first triangle only.
        assert!(cov.texel(1, 0).iter().flatten().all(|s| s.triangle == 0));
        // The mean sample position of vertex 0 is near its dual cell's centroid: the
        // hexagon (0,0) (½,0) (⅔,⅓) (½,½) (⅓,⅔) (0,½), centroid (7/24, 7/24).
        let mean: Vec3 = slots
            .iter()
            .flatten()
            .map(|s| {
                let [a, b, c] = mesh.triangle(s.triangle as usize);
                a * (1.0 - s.b1 - s.b2) + b * s.b1 + c * s.b2
            })
            .sum::<Vec3>()
            / 64.0;
        assert!(
            (mean - Vec3::new(7.0 / 24.0, 7.0 / 24.0, 0.0)).length() < 0.02,
            "{mean}"
        );
    }

    /// A fan of `n` triangles around vertex 0 (45° each, in the plane z = 0).
    fn fan(n: usize) -> TriMesh {
        let mut positions = vec![Vec3::ZERO];
        for i in 0..=n {
            let angle = i as f32 * std::f32::consts::FRAC_PI_4;
            positions.push(Vec3::new(angle.cos(), angle.sin(), 0.0));
        }
        TriMesh {
            positions,
            normals: None,
            uvs: None,
            triangles: (0..n as u32).map(|i| [0, i + 1, i + 2]).collect(),
        }
    }

    /// Every sample position lies strictly inside its triangle (all three barycentric
    /// weights positive: not on the vertex, not on an edge) for every number of triangles
    /// around the vertex and of slots, the counts where a slot's stratum once fell exactly
    /// on a boundary between pieces and its position collapsed onto the vertex (2 × 4
    /// triangles ÷ 4 slots, 2 × 2 ÷ 1, …); and no two slots of a vertex share a position.
    #[test]
    fn sample_positions_never_sit_on_the_vertex_or_an_edge() {
        for triangles in 1..=8 {
            let mesh = fan(triangles);
            for texel_samples in [1, 4, 9, 16, 64] {
                let cov = vertex_coverage(&mesh, &Affine3A::IDENTITY, texel_samples);
                let slots: Vec<TexelSample> = cov.texel(0, 0).iter().flatten().copied().collect();
                assert_eq!(slots.len(), cov.per_texel as usize);
                for s in &slots {
                    let l0 = 1.0 - s.b1 - s.b2;
                    assert!(
                        l0 < 1.0 - 1e-4 && s.b1 > 1e-4 && s.b2 > 1e-4,
                        "{triangles} triangles, {texel_samples} samples: {s:?}"
                    );
                    assert!(l0 + 1e-6 >= s.b1 && l0 + 1e-6 >= s.b2, "{s:?}");
                }
                for (i, s) in slots.iter().enumerate() {
                    assert!(
                        !slots[..i].contains(s),
                        "{triangles} triangles, {texel_samples} samples: {s:?} twice"
                    );
                }
            }
        }
    }

    #[test]
    fn missing_vertices_take_their_neighbours_mean() {
        let mesh = square();
        let mut values = vec![Some(Vec3::ONE), None, Some(Vec3::splat(3.0)), None, None];
        let filled = fill_missing(&mesh, &mut values);
        assert_eq!(filled, 3);
        assert_eq!(values[1], Some(Vec3::splat(2.0)));
        assert_eq!(values[3], Some(Vec3::splat(2.0)));
        assert_eq!(
            values[4],
            Some(Vec3::splat(3.0)),
            "no neighbours: the nearest, 2"
        );
    }

    /// A vertex on no triangle takes the value of the nearest vertex with one (exactly its
    /// value at the same position, the lower index on a tie); a mesh with no value at all
    /// gets zeros.
    #[test]
    fn vertices_on_no_triangle_take_the_nearest_value() {
        let mut mesh = square();
        mesh.positions.push(Vec3::new(1.0, 1.0, 0.0));
        mesh.positions.push(Vec3::new(0.5, 2.0, 0.0));
        mesh.positions.push(Vec3::new(0.5, -0.5, 0.0));
        let baked = [1.0, 2.0, 3.0, 4.0].map(|x| Some(Vec3::splat(x)));
        let mut values: Vec<Option<Vec3>> = baked.to_vec();
        values.extend([None, None, None, None]);
        assert_eq!(fill_missing(&mesh, &mut values), 4);
        let got: Vec<f32> = values.iter().map(|v| v.unwrap().x).collect();
        // 4 at (5, 5, 5): nearest is vertex 2 at (1, 1); 5 sits on vertex 2; 6 at
        // (0.5, 2) is as far from 2 as from 3: the lower index; 7 at (0.5, -0.5) ties 0
        // and 1: vertex 0.
        assert_eq!(got, [1.0, 2.0, 3.0, 4.0, 3.0, 3.0, 3.0, 1.0]);
        let mut none = vec![None; 5];
        assert_eq!(fill_missing(&square(), &mut none), 5);
        assert!(none.iter().all(|v| *v == Some(Vec3::ZERO)));
    }
}
