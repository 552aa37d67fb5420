//! Catmull-Clark subdivision: uniform refinement of a polygon control mesh, vertices pushed
//! to their limit positions, handed to the dicer as a [`QuadCage`].
//!
//! Interior rules are Catmull-Clark's; boundary edges follow the cubic B-spline curve rules
//! (edge point = midpoint, vertex = (e₀ + 6v + e₁)/8, limit (e₀ + 4v + e₁)/6), and vertices
//! on more than two boundary edges stay fixed. The number of levels comes from the
//! approximation (see [`levels_for`]); the dicer then treats the limit quads as bilinear
//! patches (so displacement refines them further, crack-free).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::polymesh::QuadCage;
use super::GeometryError;
use crate::components::{Approximation, SubdivMesh, Technique};

/// Hard cap on refinement levels (4^levels quads per control quad).
pub const MAX_LEVELS: u32 = 6;

/// A polygon mesh during refinement.
#[derive(Debug, Clone)]
struct Poly {
    positions: Vec<DVec3>,
    faces: Vec<Vec<u32>>,
}

/// Validates and converts the component.
fn poly(m: &SubdivMesh) -> Result<Poly, GeometryError> {
    let n = m.positions.len();
    if m.positions.iter().any(|p| !p.is_finite()) {
        return Err(GeometryError::NotFinite {
            parameter: "positions",
        });
    }
    let total: u64 = m.face_sizes.iter().map(|&s| s as u64).sum();
    if total != m.face_indices.len() as u64 {
        return Err(GeometryError::BadCount {
            message: format!(
                "subdivision mesh: face sizes add up to {total}, but there are {} indices",
                m.face_indices.len()
            ),
        });
    }
    let mut faces = Vec::with_capacity(m.face_sizes.len());
    let mut at = 0usize;
    for (f, &size) in m.face_sizes.iter().enumerate() {
        let idx = &m.face_indices[at..at + size as usize];
        at += size as usize;
        if size < 3 {
            return Err(GeometryError::BadCount {
                message: format!("subdivision mesh: face {f} has {size} vertices (needs ≥ 3)"),
            });
        }
        if let Some(&i) = idx.iter().find(|&&i| i as usize >= n) {
            return Err(GeometryError::BadCount {
                message: format!("subdivision mesh: face {f} uses vertex {i}, but there are {n}"),
            });
        }
        faces.push(idx.to_vec());
    }
    Ok(Poly {
        positions: m.positions.iter().map(|p| p.as_dvec3()).collect(),
        faces,
    })
}

/// Undirected edge (smaller id first) → its first face and its second face, if any.
type EdgeFaces = HashMap<(u32, u32), (u32, Option<u32>)>;

/// Edge → adjacent faces; errors on edges with more than two faces.
fn edge_faces(p: &Poly) -> Result<EdgeFaces, GeometryError> {
    let mut map: EdgeFaces = HashMap::new();
    for (f, face) in p.faces.iter().enumerate() {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            let key = (a.min(b), a.max(b));
            match map.get_mut(&key) {
                None => {
                    map.insert(key, (f as u32, None));
                }
                Some((_, second @ None)) => *second = Some(f as u32),
                Some(_) => {
                    return Err(GeometryError::BadCount {
                        message: format!(
                            "subdivision mesh: edge {a}–{b} is shared by more than two faces"
                        ),
                    })
                }
            }
        }
    }
    Ok(map)
}

/// One Catmull-Clark step.
fn refine(p: &Poly) -> Result<Poly, GeometryError> {
    let edges = edge_faces(p)?;
    let nv = p.positions.len();
    let face_pts: Vec<DVec3> = p
        .faces
        .iter()
        .map(|f| f.iter().map(|&i| p.positions[i as usize]).sum::<DVec3>() / f.len() as f64)
        .collect();
    // Edge points, in a fixed order (sorted keys) so ids are deterministic.
    let mut keys: Vec<(u32, u32)> = edges.keys().copied().collect();
    keys.sort_unstable();
    let mut edge_id: HashMap<(u32, u32), u32> = HashMap::with_capacity(keys.len());
    let mut positions: Vec<DVec3> = vec![DVec3::ZERO; nv];
    let mut face_sum = vec![(DVec3::ZERO, 0u32); nv];
    let mut mid_sum = vec![(DVec3::ZERO, 0u32); nv];
    let mut boundary_nbrs: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for &(a, b) in &keys {
        let (f0, f1) = edges[&(a, b)];
        let (pa, pb) = (p.positions[a as usize], p.positions[b as usize]);
        let ep = match f1 {
            Some(f1) => (pa + pb + face_pts[f0 as usize] + face_pts[f1 as usize]) * 0.25,
            None => {
                boundary_nbrs[a as usize].push(b);
                boundary_nbrs[b as usize].push(a);
                (pa + pb) * 0.5
            }
        };
        edge_id.insert((a, b), positions.len() as u32);
        positions.push(ep);
        for v in [a, b] {
            mid_sum[v as usize].0 += (pa + pb) * 0.5;
            mid_sum[v as usize].1 += 1;
        }
    }
    for (f, face) in p.faces.iter().enumerate() {
        for &v in face {
            face_sum[v as usize].0 += face_pts[f];
            face_sum[v as usize].1 += 1;
        }
    }
    for v in 0..nv {
        let s = p.positions[v];
        positions[v] = match boundary_nbrs[v].len() {
            0 if face_sum[v].1 > 0 => {
                let n = mid_sum[v].1 as f64;
                let q = face_sum[v].0 / face_sum[v].1 as f64;
                let r = mid_sum[v].0 / n;
                (q + 2.0 * r + (n - 3.0) * s) / n
            }
            2 => {
                let [e0, e1] = [0, 1].map(|k| p.positions[boundary_nbrs[v][k] as usize]);
                (e0 + 6.0 * s + e1) / 8.0
            }
            _ => s,
        };
    }
    let first_face = positions.len() as u32;
    positions.extend_from_slice(&face_pts);
    let mut faces = Vec::with_capacity(p.faces.iter().map(Vec::len).sum());
    for (f, face) in p.faces.iter().enumerate() {
        let m = face.len();
        let e = |a: u32, b: u32| edge_id[&(a.min(b), a.max(b))];
        for k in 0..m {
            let (prev, v, next) = (face[(k + m - 1) % m], face[k], face[(k + 1) % m]);
            faces.push(vec![v, e(v, next), first_face + f as u32, e(prev, v)]);
        }
    }
    Ok(Poly { positions, faces })
}

/// Levels of refinement for an approximation, as `(min, max)`: parametric/regular refine
/// exactly `ceil(log2(max(u, v)))` levels; spatial and curvature refine from `min` until
/// [`fine_enough`] (spatial edges are compared in object units even for raster
/// approximations — the dicer applies the raster rule afterwards). Always within
/// `[max(1, min_subdiv), min(max_subdiv, MAX_LEVELS)]`.
pub fn levels_for(approx: &Approximation) -> (u32, u32) {
    let max = approx.max_subdiv.clamp(1, MAX_LEVELS);
    let min = approx.min_subdiv.clamp(1, max);
    match approx.technique {
        Technique::Parametric { u, v } | Technique::Regular { u, v } => {
            let l = 32 - (u.max(v).max(1) - 1).leading_zeros();
            (l.clamp(min, max), l.clamp(min, max))
        }
        _ => (min, max),
    }
}

/// Refines `mesh` and returns the limit quad cage, with the mesh's user texture
/// coordinates and normals (see [`super::subdiv_variables`]) at its quad corners.
pub fn limit_cage(mesh: &SubdivMesh, approx: &Approximation) -> Result<QuadCage, GeometryError> {
    let (min, max) = levels_for(approx);
    let base = poly(mesh)?;
    let mut p = base.clone();
    let mut level = 0;
    loop {
        p = refine(&p)?;
        level += 1;
        let limit = limit_positions(&p)?;
        if level >= max || (level >= min && fine_enough(&p, &limit, approx)) {
            let mut cage = cage(p, limit);
            if !mesh.vars.is_empty() {
                let shape = (base.faces.as_slice(), base.positions.len());
                super::subdiv_variables::apply(&mut cage, &mesh.vars, shape, level, |values| {
                    refine_limit(&base.faces, values, level)
                })?;
            }
            return Ok(cage);
        }
    }
}

/// `values` (one per control vertex) refined `levels` times over `faces` by the position
/// rules and pushed to their limit: one per vertex of the refined mesh.
fn refine_limit(
    faces: &[Vec<u32>],
    values: &[DVec3],
    levels: u32,
) -> Result<Vec<DVec3>, GeometryError> {
    let mut p = Poly {
        positions: values.to_vec(),
        faces: faces.to_vec(),
    };
    for _ in 0..levels {
        p = refine(&p)?;
    }
    limit_positions(&p)
}

/// Whether the refined mesh meets an adaptive tolerance.
fn fine_enough(p: &Poly, limit: &[DVec3], approx: &Approximation) -> bool {
    match approx.technique {
        Technique::Spatial { edge, .. } => p.faces.iter().all(|f| {
            (0..4).all(|k| {
                limit[f[k] as usize].distance(limit[f[(k + 1) % 4] as usize]) <= edge as f64
            })
        }),
        Technique::Curvature { distance, .. } => {
            let d = if distance > 0.0 {
                distance as f64
            } else {
                f64::INFINITY
            };
            p.positions
                .iter()
                .zip(limit)
                .all(|(a, b)| a.distance(*b) <= d)
        }
        _ => false,
    }
}

/// Limit positions of an all-quad mesh.
fn limit_positions(p: &Poly) -> Result<Vec<DVec3>, GeometryError> {
    let edges = edge_faces(p)?;
    let n = p.positions.len();
    let mut edge_sum = vec![DVec3::ZERO; n];
    let mut diag_sum = vec![DVec3::ZERO; n];
    let mut valence = vec![0u32; n];
    for f in &p.faces {
        for k in 0..4 {
            let v = f[k] as usize;
            edge_sum[v] +=
                p.positions[f[(k + 1) % 4] as usize] + p.positions[f[(k + 3) % 4] as usize];
            diag_sum[v] += p.positions[f[(k + 2) % 4] as usize];
            valence[v] += 1;
        }
    }
    let mut boundary: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (&(a, b), &(_, second)) in &edges {
        if second.is_none() {
            boundary[a as usize].push(b);
            boundary[b as usize].push(a);
        }
    }
    Ok((0..n)
        .map(|v| {
            let s = p.positions[v];
            match boundary[v].len() {
                0 if valence[v] > 0 => {
                    let k = valence[v] as f64;
                    (k * k * s + 4.0 * (edge_sum[v] * 0.5) + diag_sum[v]) / (k * (k + 5.0))
                }
                2 => {
                    let mut nb = [boundary[v][0], boundary[v][1]];
                    nb.sort_unstable();
                    (p.positions[nb[0] as usize] + 4.0 * s + p.positions[nb[1] as usize]) / 6.0
                }
                _ => s,
            }
        })
        .collect())
}

/// The quad cage of a refined mesh at its limit positions, with smooth (area-weighted)
/// normals and per-quad local uvs.
fn cage(p: Poly, limit: Vec<DVec3>) -> QuadCage {
    let mut vn = vec![DVec3::ZERO; limit.len()];
    for f in &p.faces {
        let [a, b, c, d] = [0, 1, 2, 3].map(|k| limit[f[k] as usize]);
        let n = (c - a).cross(d - b);
        for &i in f {
            vn[i as usize] += n;
        }
    }
    let quads: Vec<[u32; 4]> = p.faces.iter().map(|f| [f[0], f[1], f[2], f[3]]).collect();
    let normals = quads
        .iter()
        .map(|q| q.map(|i| vn[i as usize].try_normalize().unwrap_or(DVec3::Z)))
        .collect();
    let uvs = vec![[DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]; quads.len()];
    QuadCage {
        positions: limit,
        quads,
        normals,
        uvs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A unit cube as 6 quads, outward.
    pub(crate) fn cube() -> SubdivMesh {
        let positions = (0..8)
            .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32) - 0.5)
            .collect();
        let faces: [[u32; 4]; 6] = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        SubdivMesh {
            positions,
            face_sizes: vec![4; 6],
            face_indices: faces.iter().flatten().copied().collect(),
            vars: Default::default(),
        }
    }

    #[test]
    fn cube_limit_is_a_rounded_closed_surface() {
        let approx = Approximation {
            technique: Technique::Parametric { u: 8, v: 8 },
            ..Approximation::default()
        };
        let cage = limit_cage(&cube(), &approx).unwrap();
        assert_eq!(cage.quads.len(), 6 * 4usize.pow(3));
        // Closed: every edge shared by exactly two quads.
        let mut count: HashMap<(u32, u32), u32> = HashMap::new();
        for q in &cage.quads {
            for k in 0..4 {
                let (a, b) = (q[k], q[(k + 1) % 4]);
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        assert!(count.values().all(|&c| c == 2));
        // The limit surface of a unit cube lies strictly inside it and outside radius 0.3.
        for p in &cage.positions {
            let r = p.length();
            assert!(p.abs().max_element() < 0.5 && r > 0.3, "{p:?}");
        }
    }

    #[test]
    fn non_manifold_and_bad_indices_are_errors() {
        let mut m = cube();
        m.face_indices[0] = 99;
        assert!(limit_cage(&m, &Approximation::default()).is_err());
    }
}
