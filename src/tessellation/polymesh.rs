//! Polygon meshes as patch sources: a *quad cage* of bilinear patches over welded vertices.
//!
//! A triangle mesh (for displacement) becomes three quads per triangle (corner, edge
//! midpoints, centroid); a Catmull-Clark mesh ([`super::subdiv`]) is all quads after one
//! refinement. Corners are welded by bitwise position, so vertices split for uv seams or
//! hard edges still share one displaced position (one displacement normal, averaged).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::{GeometryError, PatchSource, SurfaceSample};
use crate::components::TriMesh;

/// Bilinear quads over welded vertices, with per-quad-corner normals and uvs.
#[derive(Debug, Clone, Default)]
pub struct QuadCage {
    /// Welded vertex positions.
    pub positions: Vec<DVec3>,
    /// Corner ids of each quad, counter-clockwise: (0,0), (1,0), (1,1), (0,1).
    pub quads: Vec<[u32; 4]>,
    /// Shading normal at each quad corner (unit).
    pub normals: Vec<[DVec3; 4]>,
    /// Texture coordinates at each quad corner.
    pub uvs: Vec<[DVec2; 4]>,
}

impl QuadCage {
    /// Splits every triangle of `mesh` into three quads, welding vertices by position.
    pub fn from_trimesh(mesh: &TriMesh) -> Result<Self, GeometryError> {
        let n = mesh.positions.len();
        if mesh.triangles.iter().flatten().any(|&i| i as usize >= n) {
            return Err(GeometryError::BadCount {
                message: format!("mesh: a triangle index is beyond the {n} positions"),
            });
        }
        if mesh.positions.iter().any(|p| !p.is_finite()) {
            return Err(GeometryError::NotFinite {
                parameter: "positions",
            });
        }
        let mut cage = QuadCage::default();
        let mut weld: HashMap<[u32; 3], u32> = HashMap::new();
        let welded: Vec<u32> = mesh
            .positions
            .iter()
            .map(|p| {
                let key = p.to_array().map(f32::to_bits);
                *weld.entry(key).or_insert_with(|| {
                    cage.positions.push(p.as_dvec3());
                    cage.positions.len() as u32 - 1
                })
            })
            .collect();
        let mut mids: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &mesh.triangles {
            let w = t.map(|i| welded[i as usize]);
            let p = w.map(|i| cage.positions[i as usize]);
            let face_n = (p[1] - p[0])
                .cross(p[2] - p[0])
                .try_normalize()
                .unwrap_or(DVec3::Z);
            let nrm: [DVec3; 3] = match &mesh.normals {
                Some(ns) => t.map(|i| ns[i as usize].as_dvec3().try_normalize().unwrap_or(face_n)),
                None => [face_n; 3],
            };
            let uv: [DVec2; 3] = match &mesh.uvs {
                Some(uvs) => t.map(|i| uvs[i as usize].as_dvec2()),
                None => [DVec2::ZERO, DVec2::X, DVec2::Y],
            };
            let mut mid = |a: usize, b: usize| {
                let key = (w[a].min(w[b]), w[a].max(w[b]));
                *mids.entry(key).or_insert_with(|| {
                    cage.positions.push((p[a] + p[b]) * 0.5);
                    cage.positions.len() as u32 - 1
                })
            };
            let m = [mid(0, 1), mid(1, 2), mid(2, 0)];
            cage.positions.push((p[0] + p[1] + p[2]) / 3.0);
            let c = cage.positions.len() as u32 - 1;
            let avg = |x: &[DVec3]| x.iter().sum::<DVec3>().try_normalize().unwrap_or(face_n);
            let nm = [avg(&nrm[0..2]), avg(&nrm[1..3]), avg(&[nrm[2], nrm[0]])];
            let nc = avg(&nrm);
            let um = [
                (uv[0] + uv[1]) * 0.5,
                (uv[1] + uv[2]) * 0.5,
                (uv[2] + uv[0]) * 0.5,
            ];
            let uc = (uv[0] + uv[1] + uv[2]) / 3.0;
            for k in 0..3 {
                let prev = (k + 2) % 3;
                cage.quads.push([w[k], m[k], c, m[prev]]);
                cage.normals.push([nrm[k], nm[k], nc, nm[prev]]);
                cage.uvs.push([uv[k], um[k], uc, um[prev]]);
            }
        }
        Ok(cage)
    }
}

impl PatchSource for QuadCage {
    fn patch_count(&self) -> usize {
        self.quads.len()
    }
    fn corner_count(&self) -> usize {
        self.positions.len()
    }
    fn corners(&self, patch: usize) -> [u32; 4] {
        self.quads[patch]
    }
    fn eval(&self, patch: usize, u: f64, v: f64) -> SurfaceSample {
        let [a, b, c, d] = self.quads[patch].map(|i| self.positions[i as usize]);
        let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
        let p = a * w[0] + b * w[1] + c * w[2] + d * w[3];
        let ps = (b - a) * (1.0 - v) + (c - d) * v;
        let pt = (d - a) * (1.0 - u) + (c - b) * u;
        let ns = self.normals[patch];
        let n = (ns[0] * w[0] + ns[1] * w[1] + ns[2] * w[2] + ns[3] * w[3])
            .try_normalize()
            .or_else(|| ps.cross(pt).try_normalize())
            .unwrap_or(DVec3::Z);
        let t = self.uvs[patch];
        let uv = t[0] * w[0] + t[1] * w[1] + t[2] * w[2] + t[3] * w[3];
        // dP/d(uv) from dP/d(s,t) and the uv Jacobian; local derivatives if it is singular.
        let us = (t[1] - t[0]) * (1.0 - v) + (t[2] - t[3]) * v;
        let ut = (t[3] - t[0]) * (1.0 - u) + (t[2] - t[1]) * u;
        let det = us.x * ut.y - us.y * ut.x;
        let (dpdu, dpdv) = if det.abs() > 1e-300 {
            ((ps * ut.y - pt * us.y) / det, (pt * us.x - ps * ut.x) / det)
        } else {
            (ps, pt)
        };
        SurfaceSample {
            p,
            dpdu,
            dpdv,
            n,
            uv,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};

    #[test]
    fn triangles_split_into_welded_quads() {
        // Two triangles sharing an edge, with the shared vertices duplicated (a uv seam).
        let mesh = TriMesh {
            positions: vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Y,
                Vec3::X,
                Vec3::Y,
                Vec3::new(1.0, 1.0, 0.0),
            ],
            normals: None,
            uvs: Some(vec![
                Vec2::ZERO,
                Vec2::X,
                Vec2::Y,
                Vec2::X,
                Vec2::Y,
                Vec2::ONE,
            ]),
            triangles: vec![[0, 1, 2], [3, 5, 4]],
        };
        let cage = QuadCage::from_trimesh(&mesh).unwrap();
        // 4 welded corners + 5 edge midpoints + 2 centroids.
        assert_eq!(cage.positions.len(), 11);
        assert_eq!(cage.quads.len(), 6);
        let s = cage.eval(0, 0.5, 0.5);
        assert!(s.n.z > 0.99);
        // uv (0,0)→(½,0) along local s over a local span of 1: dP/du = (1, 0, 0).
        assert!((s.dpdu - DVec3::X).length() < 1e-12, "{:?}", s.dpdu);
    }
}
