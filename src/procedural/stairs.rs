//! Exact polygonal generators: the seed's stairs (N steps of real geometry) and flat grids.
//! Faces keep flat normals (vertices split per face, positions shared bit for bit).

use glam::{Vec2, Vec3};

use crate::components::{Grid, Stairs, TriMesh};
use crate::tessellation::{positive, GeometryError};

/// Largest step count.
pub const MAX_STEPS: u32 = 100_000;
/// Largest grid resolution per direction.
pub const MAX_GRID: u32 = 16_384;

/// Accumulates flat-shaded polygons.
#[derive(Default)]
struct Builder {
    mesh: TriMesh,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
}

impl Builder {
    /// A convex polygon (fan from its first vertex), counter-clockwise seen from the front.
    fn polygon(&mut self, pts: &[Vec3], uvs: &[Vec2]) {
        let base = self.mesh.positions.len() as u32;
        let n = (pts[1] - pts[0]).cross(pts[2] - pts[0]).normalize_or_zero();
        for (p, uv) in pts.iter().zip(uvs) {
            self.mesh.positions.push(*p);
            self.normals.push(n);
            self.uvs.push(*uv);
        }
        for k in 1..pts.len() as u32 - 1 {
            self.mesh.triangles.push([base, base + k, base + k + 1]);
        }
    }

    fn finish(mut self) -> TriMesh {
        self.mesh.normals = Some(self.normals);
        self.mesh.uvs = Some(self.uvs);
        self.mesh
    }
}

/// The stairs mesh. Riser k covers v ∈ [k, k + ½]/N and tread k covers [k + ½, k + 1]/N, so
/// the seed's `mod(v·steps, 1) < 0.5` shader sees fronts and tops where they really are.
pub fn stairs(s: &Stairs) -> Result<TriMesh, GeometryError> {
    let w = positive("width", s.width)? as f32;
    let d = positive("depth", s.depth)? as f32;
    let h = positive("height", s.height)? as f32;
    let n = s.steps.clamp(1, MAX_STEPS);
    let y = |k: u32| d * k as f32 / n as f32;
    let z = |k: u32| h * k as f32 / n as f32;
    let x = w * 0.5;
    let v = |k: u32, half: bool| (k as f32 + if half { 0.5 } else { 0.0 }) / n as f32;
    let mut b = Builder::default();
    for k in 0..n {
        let (y0, y1, z0, z1) = (y(k), y(k + 1), z(k), z(k + 1));
        b.polygon(
            &[
                Vec3::new(-x, y0, z0),
                Vec3::new(x, y0, z0),
                Vec3::new(x, y0, z1),
                Vec3::new(-x, y0, z1),
            ],
            &[
                Vec2::new(0.0, v(k, false)),
                Vec2::new(1.0, v(k, false)),
                Vec2::new(1.0, v(k, true)),
                Vec2::new(0.0, v(k, true)),
            ],
        );
        b.polygon(
            &[
                Vec3::new(-x, y0, z1),
                Vec3::new(x, y0, z1),
                Vec3::new(x, y1, z1),
                Vec3::new(-x, y1, z1),
            ],
            &[
                Vec2::new(0.0, v(k, true)),
                Vec2::new(1.0, v(k, true)),
                Vec2::new(1.0, v(k + 1, false)),
                Vec2::new(0.0, v(k + 1, false)),
            ],
        );
    }
    if s.closed {
        let uv = |p: Vec3| Vec2::new(p.y / d, p.z / h);
        for k in 0..n {
            // Side column k: bottom-left, bottom-right, top-right, top-left, and the
            // previous step's top on the left edge (avoids a T-junction with column k−1).
            let (y0, y1, z0, z1) = (y(k), y(k + 1), z(k), z(k + 1));
            for sx in [x, -x] {
                let mut pts = vec![Vec3::new(sx, y1, z1), Vec3::new(sx, y0, z1)];
                if k > 0 {
                    pts.push(Vec3::new(sx, y0, z0));
                }
                pts.push(Vec3::new(sx, y0, 0.0));
                pts.push(Vec3::new(sx, y1, 0.0));
                if sx < 0.0 {
                    pts[1..].reverse();
                }
                let uvs: Vec<Vec2> = pts.iter().map(|p| uv(*p)).collect();
                b.polygon(&pts, &uvs);
            }
            // Bottom strip k, facing −Z.
            let pts = [
                Vec3::new(-x, y0, 0.0),
                Vec3::new(-x, y1, 0.0),
                Vec3::new(x, y1, 0.0),
                Vec3::new(x, y0, 0.0),
            ];
            let uvs: Vec<Vec2> = pts
                .iter()
                .map(|p| Vec2::new(p.x / w + 0.5, p.y / d))
                .collect();
            b.polygon(&pts, &uvs);
        }
        // Back, facing +Y.
        let pts = [
            Vec3::new(x, d, 0.0),
            Vec3::new(-x, d, 0.0),
            Vec3::new(-x, d, h),
            Vec3::new(x, d, h),
        ];
        let uvs: Vec<Vec2> = pts
            .iter()
            .map(|p| Vec2::new(p.x / w + 0.5, p.z / h))
            .collect();
        b.polygon(&pts, &uvs);
    }
    Ok(b.finish())
}

/// A flat `nx × ny` grid in z = 0 facing +Z, uvs (0,0)…(1,1), shared vertices.
pub fn grid(g: &Grid) -> Result<TriMesh, GeometryError> {
    let sx = positive("size_x", g.size_x)? as f32;
    let sy = positive("size_y", g.size_y)? as f32;
    let (nx, ny) = (g.nx.clamp(1, MAX_GRID), g.ny.clamp(1, MAX_GRID));
    let mut mesh = TriMesh::default();
    let mut uvs = Vec::with_capacity(((nx + 1) * (ny + 1)) as usize);
    for j in 0..=ny {
        for i in 0..=nx {
            let uv = Vec2::new(i as f32 / nx as f32, j as f32 / ny as f32);
            mesh.positions
                .push(Vec3::new((uv.x - 0.5) * sx, (uv.y - 0.5) * sy, 0.0));
            uvs.push(uv);
        }
    }
    let at = |i: u32, j: u32| i + j * (nx + 1);
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            mesh.triangles.push([a, b, c]);
            mesh.triangles.push([a, c, d]);
        }
    }
    mesh.normals = Some(vec![Vec3::Z; mesh.positions.len()]);
    mesh.uvs = Some(uvs);
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    #[test]
    fn closed_stairs_are_watertight_with_outward_faces() {
        let s = Stairs {
            steps: 5,
            width: 2.0,
            depth: 2.0,
            height: 1.0,
            closed: true,
        };
        let m = stairs(&s).unwrap();
        let mut edges: HashMap<([u32; 3], [u32; 3]), i32> = HashMap::new();
        let key = |p: Vec3| p.to_array().map(f32::to_bits);
        let mut volume = 0.0f64;
        for t in &m.triangles {
            let p = t.map(|i| m.positions[i as usize]);
            volume += p[0].dot(p[1].cross(p[2])) as f64 / 6.0;
            for k in 0..3 {
                let (a, b) = (key(p[k]), key(p[(k + 1) % 3]));
                // +1 for a→b, −1 for b→a: a closed, consistently oriented mesh sums to 0.
                *edges.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
            }
        }
        assert!(
            edges.values().all(|&c| c == 0),
            "open or inconsistently oriented edges"
        );
        // Volume of 5 steps: Σ depth/5 · width · height·k/5 = 2·2·1·(1+…+5)/25 = 2.4.
        assert!((volume - 2.4).abs() < 1e-5, "{volume}");
    }

    #[test]
    fn grid_counts() {
        let m = grid(&Grid {
            size_x: 2.0,
            size_y: 1.0,
            nx: 4,
            ny: 3,
        })
        .unwrap();
        assert_eq!((m.positions.len(), m.triangles.len()), (20, 24));
        assert!(grid(&Grid {
            size_x: f32::NAN,
            size_y: 1.0,
            nx: 1,
            ny: 1
        })
        .is_err());
    }
}
