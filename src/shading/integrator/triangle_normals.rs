//! Unit geometric normals of the world triangles, kept for the length of a render so that
//! turning a hit into a shading point does not normalise a cross product per hit.
//!
//! The normals are [`geometric_normal`] of each triangle, so shading points are the same
//! bit for bit with or without the table. The table is kept only for scenes of at most
//! [`TriangleNormals::MAX_TRIANGLES`] triangles: there its 12 bytes per triangle stay in
//! the cache next to the triangles traversal just touched, and a lookup is cheaper than the
//! square root and division it replaces; in a large scene a lookup would be a cache miss,
//! dearer than the arithmetic, so none is built.

use glam::Vec3;

use crate::accel::{geometric_normal, surface_point_with_normal, Hit};
use crate::geometry::{SceneGeometry, ShadingPoint};

/// The unit geometric normal of every world triangle, indexed by `prim`.
#[derive(Debug, Clone)]
pub struct TriangleNormals(Vec<Vec3>);

impl TriangleNormals {
    /// Most triangles of a scene for which the table is built (768 KiB of normals).
    pub const MAX_TRIANGLES: usize = 1 << 16;

    /// The normals of `g`'s triangles; `None` for scenes above [`Self::MAX_TRIANGLES`].
    pub fn new(g: &SceneGeometry) -> Option<Self> {
        let n = g.triangle_count();
        (n <= Self::MAX_TRIANGLES).then(|| {
            Self(
                (0..n as u32)
                    .map(|prim| geometric_normal(&g.accel.triangle(prim)))
                    .collect(),
            )
        })
    }

    /// The shading point of `hit` in `g` (the geometry the table was made of): the same as
    /// [`SceneGeometry::shading_point`], with the normal read from the table.
    #[inline]
    pub fn shading_point(&self, g: &SceneGeometry, hit: &Hit) -> ShadingPoint {
        let tri = g.accel.triangle(hit.prim);
        let surface = surface_point_with_normal(&tri, hit.b1, hit.b2, self.0[hit.prim as usize]);
        g.shading_point_on(hit, surface)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::integrator::fixture::{self, Object};

    #[test]
    fn table_shading_points_equal_computed_ones() {
        let g = fixture::geometry(vec![
            Object {
                triangles: fixture::inward_cube(1.5),
                material: fixture::lambert(0.5),
            },
            Object {
                triangles: fixture::floor(3.0, -0.25),
                material: fixture::lambert(0.8),
            },
        ]);
        let normals = TriangleNormals::new(&g).expect("a small scene keeps its table");
        let mut hits = 0;
        for i in 0..200 {
            let a = i as f32 * 0.37;
            let dir = Vec3::new(a.cos(), a.sin(), (i as f32 * 0.11).sin());
            let (_, hit) = fixture::hit(&g, Vec3::new(0.1, -0.2, 0.3), dir);
            let want = g.shading_point(&hit);
            let got = normals.shading_point(&g, &hit);
            assert_eq!(got.surface.p, want.surface.p);
            assert_eq!(got.surface.p_err, want.surface.p_err);
            assert_eq!(got.surface.ng, want.surface.ng);
            assert_eq!(got.normal, want.normal);
            assert_eq!((got.prim, got.material), (want.prim, want.material));
            hits += 1;
        }
        assert_eq!(hits, 200);
    }
}
