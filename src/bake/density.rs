//! How much surface a bake's texture holds: the placed area of an instance's mesh, in f64
//! from the object-space triangles and the linear part of its placement (so a translation
//! never changes it), the area its UVs cover, and the share of that UV area inside the unit
//! square (what is baked). `request.rs` sizes density bakes from these, and the memory
//! estimate (`crate::budget::estimate`) sizes them the same way before any stage runs.

use glam::{Affine3A, DVec3, Vec2};

use super::uv::{bake_resolution, BakeUvError};
use crate::components::{BakeResolution, TriMesh};

/// The world-space area of each triangle of `mesh` placed by `world_from_object`, in f64:
/// the object-space edges times the linear part of the transform, crossed. A translation
/// (where the object is placed) does not enter.
pub fn placed_triangle_areas<'a>(
    mesh: &'a TriMesh,
    world_from_object: &Affine3A,
) -> impl Iterator<Item = f64> + 'a {
    let m = world_from_object.matrix3;
    let columns = [m.x_axis, m.y_axis, m.z_axis].map(|c| c.as_dvec3());
    let linear = move |v: DVec3| columns[0] * v.x + columns[1] * v.y + columns[2] * v.z;
    mesh.triangles.iter().map(move |t| {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
        0.5 * linear(b - a).cross(linear(c - a)).length()
    })
}

/// The world-space area of `mesh` placed by `world_from_object` ([`placed_triangle_areas`]).
pub fn placed_area(mesh: &TriMesh, world_from_object: &Affine3A) -> f64 {
    placed_triangle_areas(mesh, world_from_object).sum()
}

/// The area the corner UVs `uvs` cover (in the unit square's units; overlaps count twice).
pub fn uv_area(uvs: &[[Vec2; 3]]) -> f64 {
    uvs.iter().map(triangle_uv_area).sum()
}

fn triangle_uv_area(uv: &[Vec2; 3]) -> f64 {
    let [a, b, c] = uv.map(|p| p.as_dvec2());
    0.5 * (b - a).perp_dot(c - a).abs()
}

/// The area of a UV triangle inside the unit square [0, 1]² (Sutherland–Hodgman clipping).
fn triangle_uv_area_inside(uv: &[Vec2; 3]) -> f64 {
    let mut polygon: Vec<glam::DVec2> = uv.iter().map(|p| p.as_dvec2()).collect();
    // Each edge of the square as (axis, bound, keep the side ≥ bound).
    for (axis, bound, above) in [
        (0, 0.0, true),
        (0, 1.0, false),
        (1, 0.0, true),
        (1, 1.0, false),
    ] {
        let inside = |p: glam::DVec2| {
            if above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let mut clipped = Vec::with_capacity(polygon.len() + 2);
        for k in 0..polygon.len() {
            let (p, q) = (polygon[k], polygon[(k + 1) % polygon.len()]);
            if inside(p) {
                clipped.push(p);
            }
            if inside(p) != inside(q) {
                let t = (bound - p[axis]) / (q[axis] - p[axis]);
                clipped.push(p + (q - p) * t);
            }
        }
        polygon = clipped;
        if polygon.len() < 3 {
            return 0.0;
        }
    }
    let twice: f64 = (0..polygon.len())
        .map(|k| polygon[k].perp_dot(polygon[(k + 1) % polygon.len()]))
        .sum();
    0.5 * twice.abs()
}

/// How a request's UVs place the surface in the texture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvPlacement {
    /// The UV area of all triangles.
    pub uv_area: f64,
    /// The share of that UV area outside the unit square (not baked), 0 … 1.
    pub outside_share: f64,
    /// The world-space area of the part of the surface whose UVs lie inside the unit square
    /// (each triangle's placed area times the share of its UV area inside).
    pub baked_world_area: f64,
}

/// Where the corner UVs `uvs` of `mesh` (placed by `world_from_object`) put its surface.
pub fn uv_placement(
    mesh: &TriMesh,
    world_from_object: &Affine3A,
    uvs: &[[Vec2; 3]],
) -> UvPlacement {
    let mut uv_total = 0.0;
    let mut uv_inside = 0.0;
    let mut baked_world_area = 0.0;
    for (uv, world) in uvs
        .iter()
        .zip(placed_triangle_areas(mesh, world_from_object))
    {
        let area = triangle_uv_area(uv);
        let inside = triangle_uv_area_inside(uv).min(area);
        uv_total += area;
        uv_inside += inside;
        if area > 0.0 {
            baked_world_area += world * inside / area;
        }
    }
    UvPlacement {
        uv_area: uv_total,
        outside_share: if uv_total > 0.0 {
            ((uv_total - uv_inside) / uv_total).max(0.0)
        } else {
            0.0
        },
        baked_world_area,
    }
}

/// The texture size of a request with the mesh's own (or second-set) corner UVs `uvs`, on
/// `mesh` placed by `world_from_object`: what [`bake_resolution`] gives for its placed area.
pub fn mesh_uv_resolution(
    resolution: BakeResolution,
    mesh: &TriMesh,
    world_from_object: &Affine3A,
    uvs: &[[Vec2; 3]],
) -> Result<(u32, u32), BakeUvError> {
    bake_resolution(
        resolution,
        placed_area(mesh, world_from_object),
        uv_area(uvs),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn quad(half: f32, uvs: [Vec2; 4]) -> (TriMesh, Vec<[Vec2; 3]>) {
        let mesh = TriMesh {
            positions: vec![
                Vec3::new(-half, 0.0, half),
                Vec3::new(half, 0.0, half),
                Vec3::new(half, 0.0, -half),
                Vec3::new(-half, 0.0, -half),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            ..TriMesh::default()
        };
        let corners = vec![[uvs[0], uvs[1], uvs[2]], [uvs[0], uvs[2], uvs[3]]];
        (mesh, corners)
    }

    #[test]
    fn the_placed_area_does_not_depend_on_the_translation() {
        let (mesh, _) = quad(0.1, [Vec2::ZERO; 4]);
        let at = |x: f32| placed_area(&mesh, &Affine3A::from_translation(Vec3::new(x, 0.0, 0.0)));
        let here = at(0.0);
        assert!((here - 0.04).abs() < 1e-8, "{here}");
        for x in [0.5, 1.0, 2.0, 1000.0, -3.7] {
            assert_eq!(at(x), here, "x = {x}");
        }
        let scaled = placed_area(&mesh, &Affine3A::from_scale(Vec3::new(2.0, 1.0, 3.0)));
        assert!((scaled - 0.24).abs() < 1e-7, "{scaled}");
    }

    #[test]
    fn uvs_from_minus_a_half_to_one_and_a_half_are_three_quarters_outside() {
        let (mesh, uvs) = quad(
            1.0,
            [
                Vec2::new(-0.5, -0.5),
                Vec2::new(1.5, -0.5),
                Vec2::new(1.5, 1.5),
                Vec2::new(-0.5, 1.5),
            ],
        );
        let p = uv_placement(&mesh, &Affine3A::IDENTITY, &uvs);
        assert!((p.uv_area - 4.0).abs() < 1e-12, "{p:?}");
        assert!((p.outside_share - 0.75).abs() < 1e-12, "{p:?}");
        assert!((p.baked_world_area - 1.0).abs() < 1e-9, "{p:?}");
        let (mesh, uvs) = quad(1.0, [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]);
        let inside = uv_placement(&mesh, &Affine3A::IDENTITY, &uvs);
        assert_eq!(inside.outside_share, 0.0);
        assert!((inside.baked_world_area - 4.0).abs() < 1e-9);
    }
}
