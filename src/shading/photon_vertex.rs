//! The photon walk's surface vertex: what a photon's interaction reads of a hit (the point
//! and its error bound, the oriented normals and frame, the material's shader, the segment's
//! transmittance), built from a shading point the caller already has.
//!
//! It is [`Vertex::new`]'s work less what the walk never reads: for a material without a
//! shader graph on an instance without bump displacement (no texture to evaluate) it skips
//! the texture evaluation and the emission, and it takes the [`ShadingPoint`] as an input,
//! so a batch of walks can compute its hits' shading points in one tight loop first (their
//! triangle, index and normal loads then overlap instead of stalling one walk at a time).
//! Every field it has is [`Vertex::new`]'s bit for bit; textured or bumped points are made
//! by [`Vertex::new`] itself.

use std::borrow::Cow;

use glam::{Vec3, Vec3A};

use crate::accel::{Hit, Ray};
use crate::components::Shader;
use crate::geometry::ShadingPoint;
use crate::shading::bsdf::Bsdf;
use crate::shading::frame::ShadingFrame;
use crate::shading::integrator::orient::{
    bsdf_kept_or_in, orient, shading_point, spawn_along, Orientation,
};
use crate::shading::integrator::{ShadeContext, Vertex};
use crate::shading::texture::hit::is_textured;

/// A photon's shading point, oriented toward where the photon came from (the fields of
/// [`Vertex`] of the same names, with the same values).
pub struct PhotonVertex<'a> {
    /// Hit point; `normal` faces the arriving photon, `surface.ng` is the unflipped
    /// geometric normal.
    pub sp: ShadingPoint,
    /// Geometric normal on the arriving photon's side.
    pub ng: Vec3,
    /// Whether the front face was hit.
    pub front: bool,
    /// Whether this face is shaded (false: back of a one-sided surface, black but opaque).
    pub visible: bool,
    /// The material's shader at this point.
    pub shader: Cow<'a, Shader>,
    /// Frame around `sp.normal`.
    pub frame: ShadingFrame,
    /// Direction back along the arriving ray, local.
    pub wo: Vec3,
    /// Direction back along the arriving ray, world space (unit). In a [`Vec3A`]: the vertex
    /// is built on the stack in two ways (this module's or [`Vertex::new`]'s), and the walk's
    /// read of a 12-byte `Vec3` there was an 8-byte load spanning two stores (a failed store
    /// forward, the walk's hottest instruction); one 16-byte store and load forward.
    pub wo_world: Vec3A,
    /// Transmittance of the segment that reached this vertex (absorption inside a dielectric).
    pub transmittance: Vec3,
}

impl<'a> From<Vertex<'a>> for PhotonVertex<'a> {
    fn from(v: Vertex<'a>) -> Self {
        Self {
            sp: v.sp,
            ng: v.ng,
            front: v.front,
            visible: v.visible,
            shader: v.shader,
            frame: v.frame,
            wo: v.wo,
            wo_world: v.wo_world.into(),
            transmittance: v.transmittance,
        }
    }
}

impl<'a> PhotonVertex<'a> {
    /// The shading point of `hit` as [`Vertex::new`] computes it (through the context's
    /// normal table when it keeps one).
    #[inline(always)]
    pub fn shading_point(ctx: &ShadeContext<'_>, hit: &Hit) -> ShadingPoint {
        shading_point(ctx, hit)
    }

    /// The vertex where `ray` hits `hit`, whose shading point is `sp`
    /// ([`PhotonVertex::shading_point`]): [`Vertex::new`]'s fields, bit for bit.
    #[inline(always)]
    pub fn new(ctx: &ShadeContext<'a>, ray: &Ray, hit: &Hit, sp: ShadingPoint) -> Self {
        let material = &ctx.geometry.materials[sp.material as usize];
        let inst = &ctx.geometry.instances[sp.instance as usize];
        if is_textured(inst, material) {
            return Vertex::new(ctx, ray, hit).into();
        }
        // `Vertex::new` with no texture to evaluate, step for step.
        let mut sp = sp;
        let shader = Cow::Borrowed(&material.shader);
        let Orientation {
            ng,
            front,
            visible,
            transmittance,
            frame,
            wo_world,
        } = orient(ctx, ray, hit, &mut sp, material, &shader, false);
        Self {
            sp,
            ng,
            front,
            visible,
            shader,
            frame,
            wo: frame.to_local(wo_world),
            wo_world: wo_world.into(),
            transmittance,
        }
    }

    /// [`Vertex::bsdf_ref`]: the material's kept BSDF when the context keeps them and no
    /// texture drives this point's shader, else built in `scratch`, made only then.
    #[inline]
    pub fn bsdf_ref<'b>(
        &'b self,
        ctx: &ShadeContext<'b>,
        scratch: &'b mut Option<Bsdf>,
    ) -> &'b Bsdf {
        bsdf_kept_or_in(ctx, self.sp.material, self.front, &self.shader, scratch)
    }

    /// [`Vertex::spawn`]: a ray leaving along the local direction `wi` if it lies on the
    /// geometric side its kind requires (reflection: the photon's side; transmission: the
    /// other side).
    #[inline(always)]
    pub fn spawn(&self, wi_local: Vec3, transmits: bool) -> Option<Ray> {
        spawn_along(&self.frame, self.ng, &self.sp.surface, wi_local, transmits)
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::Vec2;

    use super::*;
    use crate::components::TriMesh;
    use crate::geometry::SceneGeometry;
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture;
    use crate::shading::integrator::material_bsdfs::MaterialBsdfs;
    use crate::shading::integrator::triangle_normals::TriangleNormals;
    use crate::shading::lights::LightSet;
    use crate::shading::texture::{Binding, BumpMap, MaterialGraph, Op, Program};

    /// A closed cube seen from inside with smooth normals bent toward its centre and uvs; a
    /// coloured glass floor (hit from above and below); a wall panel whose albedo and bump
    /// a graph drives; a panel with bump displacement.
    fn scene() -> SceneGeometry {
        let mut textured = fixture::lambert(0.5);
        let mut p = Program::default();
        let uv = p.push(Op::Uv);
        let scale = p.push(Op::Const(Vec3::splat(4.0)));
        let a = p.push(Op::Const(Vec3::splat(0.9)));
        let b = p.push(Op::Const(Vec3::splat(0.1)));
        let c = p.push(Op::Checker { uv, scale, a, b });
        let u = p.push(Op::Channel(uv, 0));
        textured.graph = Some(Arc::new(MaterialGraph {
            program: p,
            bindings: vec![Binding {
                param: "albedo".into(),
                reg: c,
            }],
            bump: Some(BumpMap {
                height: u,
                scale: 0.3,
            }),
            normal_map: None,
            object_normal: None,
            emission: None,
        }));
        let mut g =
            fixture::room_with_panels(Vec3::new(0.9, 0.5, 0.2), [textured, fixture::lambert(0.3)]);
        let cube = &mut g.instances[0];
        let positions = cube.mesh.positions.clone();
        cube.mesh = Arc::new(TriMesh {
            triangles: cube.mesh.triangles.clone(),
            normals: Some(positions.iter().map(|&p| (-p).normalize()).collect()),
            uvs: Some(positions.iter().map(|&p| Vec2::new(p.x, p.y)).collect()),
            positions,
        });
        g.instances[3].bump = Some(fixture::sine_bump());
        g
    }

    #[test]
    fn photon_vertices_are_vertices_bit_for_bit() {
        let g = scene();
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let normals = TriangleNormals::new(&g).expect("a small scene keeps its table");
        let bsdfs = MaterialBsdfs::new(&g);
        let contexts = [
            ShadeContext::new(&g, &lights, &s),
            ShadeContext::new(&g, &lights, &s)
                .with_normals(Some(&normals))
                .with_bsdfs(Some(&bsdfs)),
        ];
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        let mut seen = [0usize; 4];
        let mut back = 0;
        for ctx in &contexts {
            for i in 0..3000 {
                let a = i as f32 * 0.37;
                let dir = Vec3::new(a.cos(), a.sin(), (i as f32 * 0.11).sin());
                let origin = [Vec3::new(0.1, -0.2, 0.3), Vec3::new(-0.2, 0.3, -0.6)][i % 2];
                let (ray, hit) = fixture::hit(&g, origin, dir);
                let want = Vertex::new(ctx, &ray, &hit);
                let sp = PhotonVertex::shading_point(ctx, &hit);
                let got = PhotonVertex::new(ctx, &ray, &hit, sp);
                seen[got.sp.instance as usize] += 1;
                back += usize::from(!got.front);
                let (w, o) = (&want.sp, &got.sp);
                assert_eq!(bits(o.surface.p), bits(w.surface.p));
                assert_eq!(bits(o.surface.p_err), bits(w.surface.p_err));
                assert_eq!(bits(o.surface.ng), bits(w.surface.ng));
                assert_eq!(bits(o.normal), bits(w.normal), "ray {i}");
                assert_eq!(
                    (o.material, o.instance, o.prim),
                    (w.material, w.instance, w.prim)
                );
                assert_eq!(bits(got.ng), bits(want.ng));
                assert_eq!((got.front, got.visible), (want.front, want.visible));
                assert_eq!(*got.shader, *want.shader);
                assert_eq!(
                    matches!(got.shader, Cow::Borrowed(_)),
                    matches!(want.shader, Cow::Borrowed(_))
                );
                for (x, y) in [
                    (got.frame.s, want.frame.s),
                    (got.frame.t, want.frame.t),
                    (got.frame.n, want.frame.n),
                    (got.wo, want.wo),
                    (got.wo_world.into(), want.wo_world),
                    (got.transmittance, want.transmittance),
                ] {
                    assert_eq!(bits(x), bits(y), "ray {i}");
                }
                let (mut a, mut b) = (None, None);
                assert_eq!(got.bsdf_ref(ctx, &mut b), want.bsdf_ref(ctx, &mut a));
                let wi = Vec3::new(0.3, -0.4, 0.8).normalize();
                for transmits in [false, true] {
                    assert_eq!(got.spawn(wi, transmits), want.spawn(wi, transmits));
                }
            }
        }
        println!("hits per instance {seen:?}, {back} back faces");
        assert!(seen.iter().all(|&n| n > 50), "{seen:?}");
        assert!(back > 50, "{back}");
    }

    /// `is_textured` is exactly where `evaluate` has something to return: the graph-driven
    /// panel and the displaced panel, not the plain cube, glass floor or panel.
    #[test]
    fn is_textured_is_where_evaluate_returns_a_texture() {
        let g = scene();
        let mut seen = [0usize; 2];
        for i in 0..3000 {
            let a = i as f32 * 0.37;
            let dir = Vec3::new(a.cos(), a.sin(), (i as f32 * 0.11).sin());
            let origin = [Vec3::new(0.1, -0.2, 0.3), Vec3::new(-0.2, 0.3, -0.6)][i % 2];
            let (_, hit) = fixture::hit(&g, origin, dir);
            let sp = g.shading_point(&hit);
            let material = &g.materials[sp.material as usize];
            let inst = &g.instances[sp.instance as usize];
            let textured = is_textured(inst, material);
            let evaluated = crate::shading::texture::hit::evaluate(&g, &sp, &hit, material);
            assert_eq!(textured, evaluated.is_some(), "ray {i}");
            seen[usize::from(textured)] += 1;
        }
        assert!(seen.iter().all(|&n| n > 50), "{seen:?}");
    }
}
