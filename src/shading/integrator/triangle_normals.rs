//! Unit geometric normals of the world triangles, kept for the length of a render so that
//! turning a hit into a shading point does not normalise a cross product per hit.
//!
//! The normals are [`geometric_normal`] of each triangle, so shading points are the same
//! bit for bit with or without the table. The table is kept only for scenes of at most
//! [`TriangleNormals::MAX_TRIANGLES`] triangles: there its 12 bytes per triangle stay in
//! the cache next to the triangles traversal just touched, and a lookup is cheaper than the
//! square root and division it replaces; in a large scene a lookup would be a cache miss,
//! dearer than the arithmetic, so none is built. Scenes of at most
//! [`TriangleNormals::MAX_FRAMES`] triangles also keep each normal's shading frame, which
//! flat-shaded hits read instead of building it (the same frame, bit for bit).

use glam::Vec3;

use crate::accel::{geometric_normal, surface_point_with_normal, Hit};
use crate::geometry::{SceneGeometry, ShadingPoint};
use crate::shading::frame::ShadingFrame;

/// The unit geometric normal of every world triangle, indexed by `prim`, and in small
/// scenes the shading frame around it.
#[derive(Debug, Clone)]
pub struct TriangleNormals {
    normals: Vec<Vec3>,
    /// `ShadingFrame::from_normal` of each normal (empty above [`Self::MAX_FRAMES`]).
    frames: Vec<ShadingFrame>,
}

impl TriangleNormals {
    /// Most triangles of a scene for which the table is built (768 KiB of normals).
    pub const MAX_TRIANGLES: usize = 1 << 16;

    /// Most triangles for which the frames are kept too (144 KiB): a flat-shaded hit then
    /// reads its frame (the front face's, or [`ShadingFrame::flipped`] for the back) instead
    /// of building it (a division and a dozen products). Larger scenes build it per hit,
    /// where a lookup could miss the cache.
    pub const MAX_FRAMES: usize = 1 << 12;

    /// The normals of `g`'s triangles; `None` for scenes above [`Self::MAX_TRIANGLES`].
    pub fn new(g: &SceneGeometry) -> Option<Self> {
        let n = g.triangle_count();
        (n <= Self::MAX_TRIANGLES).then(|| {
            let normals: Vec<Vec3> = (0..n as u32)
                .map(|prim| geometric_normal(&g.accel.triangle(prim)))
                .collect();
            let frames = if n <= Self::MAX_FRAMES {
                normals
                    .iter()
                    .map(|&n| ShadingFrame::from_normal(n))
                    .collect()
            } else {
                Vec::new()
            };
            Self { normals, frames }
        })
    }

    /// `ShadingFrame::from_normal` of triangle `prim`'s unit geometric normal (the same
    /// value), when kept.
    #[inline]
    pub fn frame(&self, prim: u32) -> Option<&ShadingFrame> {
        self.frames.get(prim as usize)
    }

    /// The shading point of `hit` in `g` (the geometry the table was made of): the same as
    /// [`SceneGeometry::shading_point`], with the normal read from the table.
    #[inline(always)]
    pub fn shading_point(&self, g: &SceneGeometry, hit: &Hit) -> ShadingPoint {
        let tri = g.accel.triangle(hit.prim);
        let surface =
            surface_point_with_normal(&tri, hit.b1, hit.b2, self.normals[hit.prim as usize]);
        g.shading_point_on(hit, surface)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::integrator::fixture::{self, Object};

    /// A closed cube seen from inside and a floor below it.
    fn cube_and_floor() -> SceneGeometry {
        fixture::geometry(vec![
            Object {
                triangles: fixture::inward_cube(1.5),
                material: fixture::lambert(0.5),
            },
            Object {
                triangles: fixture::floor(3.0, -0.25),
                material: fixture::lambert(0.8),
            },
        ])
    }

    #[test]
    fn table_shading_points_equal_computed_ones() {
        let g = cube_and_floor();
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

    #[test]
    fn kept_frames_equal_built_ones_on_both_faces() {
        use crate::settings::RenderSettings;
        use crate::shading::integrator::{ShadeContext, Vertex};
        use crate::shading::lights::LightSet;

        // A closed cube seen from inside (front faces) and a floor seen from below (back
        // faces), with axis-aligned normals where the frame's sums cancel to zero.
        let g = cube_and_floor();
        let normals = TriangleNormals::new(&g).expect("a small scene keeps its table");
        assert!(normals.frame(0).is_some());
        let lights = LightSet::new(&[], None, 1);
        let s = RenderSettings::default();
        let plain = ShadeContext::new(&g, &lights, &s);
        let kept = ShadeContext::new(&g, &lights, &s).with_normals(Some(&normals));
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        let mut back = 0;
        for i in 0..400 {
            let a = i as f32 * 0.37;
            let dir = Vec3::new(a.cos(), a.sin(), (i as f32 * 0.11).sin());
            for origin in [Vec3::new(0.1, -0.2, 0.3), Vec3::new(0.1, -0.2, -1.0)] {
                let (ray, hit) = fixture::hit(&g, origin, dir);
                let (want, got) = (
                    Vertex::new(&plain, &ray, &hit),
                    Vertex::new(&kept, &ray, &hit),
                );
                back += usize::from(!got.front);
                for (w, g) in [(want.frame.s, got.frame.s), (want.frame.t, got.frame.t)] {
                    assert_eq!(bits(w), bits(g), "hit {hit:?}");
                }
                assert_eq!(bits(want.frame.n), bits(got.frame.n));
                assert_eq!(bits(want.wo), bits(got.wo));
            }
        }
        assert!(back > 0, "some rays meet a back face");
    }
}
