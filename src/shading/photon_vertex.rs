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

use glam::Vec3;

use crate::accel::{spawn_ray, Hit, Ray};
use crate::components::Shader;
use crate::geometry::ShadingPoint;
use crate::settings::Face;
use crate::shading::bsdf::Bsdf;
use crate::shading::frame::ShadingFrame;
use crate::shading::integrator::{ShadeContext, Vertex};
use crate::shading::texture::bump;

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
    /// Direction back along the arriving ray, world space (unit).
    pub wo_world: Vec3,
    /// Transmittance of the segment that reached this vertex (absorption inside a dielectric).
    pub transmittance: Vec3,
}

/// Whether two vectors have the same bit patterns.
#[inline]
fn same_bits(a: Vec3, b: Vec3) -> bool {
    a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)
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
            wo_world: v.wo_world,
            transmittance: v.transmittance,
        }
    }
}

impl<'a> PhotonVertex<'a> {
    /// The shading point of `hit` as [`Vertex::new`] computes it (through the context's
    /// normal table when it keeps one).
    #[inline(always)]
    pub fn shading_point(ctx: &ShadeContext<'_>, hit: &Hit) -> ShadingPoint {
        match ctx.normals {
            Some(n) => n.shading_point(ctx.geometry, hit),
            None => ctx.geometry.shading_point(hit),
        }
    }

    /// The vertex where `ray` hits `hit`, whose shading point is `sp`
    /// ([`PhotonVertex::shading_point`]): [`Vertex::new`]'s fields, bit for bit.
    #[inline(always)]
    pub fn new(ctx: &ShadeContext<'a>, ray: &Ray, hit: &Hit, sp: ShadingPoint) -> Self {
        let material = &ctx.geometry.materials[sp.material as usize];
        let inst = &ctx.geometry.instances[sp.instance as usize];
        if material.graph.is_some() || inst.bump.is_some() {
            return Vertex::new(ctx, ray, hit).into();
        }
        // `Vertex::new` with no texture to evaluate, step for step.
        let mut sp = sp;
        let shader = Cow::Borrowed(&material.shader);
        let wo_world = -ray.dir.normalize();
        let front = sp.surface.ng.dot(wo_world) > 0.0;
        if !front {
            sp.normal = -sp.normal;
        }
        let ng = if front { sp.surface.ng } else { -sp.surface.ng };
        if sp.normal != ng {
            sp.normal = bump::ensure_valid_reflection(ng, wo_world, sp.normal);
        }
        let visible = front || material.shades_back() || ctx.face == Face::Both;
        let transmittance = match &*shader {
            Shader::Dielectric { col, .. } if !front => {
                let d = hit.t * ray.dir.length();
                Vec3::new(col.x.powf(d), col.y.powf(d), col.z.powf(d))
            }
            _ => Vec3::ONE,
        };
        let frame = match ctx.normals.and_then(|t| t.frame(hit.prim)) {
            Some(kept) if same_bits(sp.normal, ng) => {
                if front {
                    *kept
                } else {
                    kept.flipped()
                }
            }
            _ => ShadingFrame::from_normal(sp.normal),
        };
        Self {
            sp,
            ng,
            front,
            visible,
            shader,
            frame,
            wo: frame.to_local(wo_world),
            wo_world,
            transmittance,
        }
    }

    /// [`Vertex::bsdf_ref`]'s BSDF: the material's kept BSDF when the context keeps them and
    /// no texture drives this point's shader, else built in `scratch` (only then: the
    /// 168-byte empty BSDF is not written at every hit).
    #[inline]
    pub fn bsdf_ref<'b>(
        &'b self,
        ctx: &ShadeContext<'b>,
        scratch: &'b mut Option<Bsdf>,
    ) -> &'b Bsdf {
        match (ctx.bsdfs, &self.shader) {
            (Some(kept), Cow::Borrowed(_)) => kept.get(self.sp.material, self.front),
            _ => {
                let b = scratch.insert(Bsdf::empty());
                b.set_shader(&self.shader, self.front);
                b
            }
        }
    }

    /// [`Vertex::spawn`]: a ray leaving along the local direction `wi` if it lies on the
    /// geometric side its kind requires (reflection: the photon's side; transmission: the
    /// other side).
    #[inline(always)]
    pub fn spawn(&self, wi_local: Vec3, transmits: bool) -> Option<Ray> {
        let wi = self.frame.to_world(wi_local);
        let side = self.ng.dot(wi);
        let ok = if transmits { side < 0.0 } else { side > 0.0 };
        (ok && wi.is_finite()).then(|| spawn_ray(&self.sp.surface, wi))
    }
}
