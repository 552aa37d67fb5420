//! A hit turned toward the ray that reached it: the shading normal on the viewer's side and
//! made safe, the face, its visibility, the segment's transmittance and the shading frame —
//! the part of a surface vertex shared by the integrators' [`Vertex`](super::Vertex) and the
//! photon walk's [`PhotonVertex`](crate::shading::photon_vertex::PhotonVertex), and the
//! shading point, BSDF and spawned-ray helpers both go through.

use std::borrow::Cow;

use glam::Vec3;

use crate::accel::{spawn_ray, Hit, Ray, SurfacePoint};
use crate::components::{Material, Shader};
use crate::geometry::ShadingPoint;
use crate::settings::Face;
use crate::shading::bsdf::Bsdf;
use crate::shading::frame::ShadingFrame;
use crate::shading::texture::bump;

use super::ShadeContext;

/// What [`orient`] finds at a hit.
pub(crate) struct Orientation {
    /// Geometric normal on the viewer's side.
    pub ng: Vec3,
    /// Whether the front face was hit.
    pub front: bool,
    /// Whether this face is shaded (false: back of a one-sided surface).
    pub visible: bool,
    /// Transmittance of the segment that reached the hit (absorption inside a dielectric).
    pub transmittance: Vec3,
    /// Frame around the oriented shading normal.
    pub frame: ShadingFrame,
    /// Direction toward the viewer, world space (the unit reverse of the arriving ray).
    pub wo_world: Vec3,
}

/// The shading point of `hit`, through the context's table of triangle normals when it
/// keeps one.
#[inline(always)]
pub(crate) fn shading_point(ctx: &ShadeContext<'_>, hit: &Hit) -> ShadingPoint {
    match ctx.normals {
        Some(n) => n.shading_point(ctx.geometry, hit),
        None => ctx.geometry.shading_point(hit),
    }
}

/// Whether two vectors have the same bit patterns (`-0.0` and `0.0` told apart).
#[inline]
fn same_bits(a: Vec3, b: Vec3) -> bool {
    a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)
}

/// Turns `sp.normal` toward the viewer and makes it safe (hard case H11: rotated toward the
/// geometric normal just enough that the view direction is above it and its mirror direction
/// above the geometric surface, [`bump::ensure_valid_reflection`]) unless `exact` (a normal
/// to use as given: only turned toward the viewer); `shader` is the shader bound at this
/// point (its absorption colour gives the transmittance inside a dielectric).
#[inline(always)]
pub(crate) fn orient(
    ctx: &ShadeContext<'_>,
    ray: &Ray,
    hit: &Hit,
    sp: &mut ShadingPoint,
    material: &Material,
    shader: &Shader,
    exact: bool,
) -> Orientation {
    let wo_world = -ray.dir.normalize();
    let front = sp.surface.ng.dot(wo_world) > 0.0;
    if !front {
        sp.normal = -sp.normal;
    }
    let ng = if front { sp.surface.ng } else { -sp.surface.ng };
    if sp.normal != ng && !exact {
        sp.normal = bump::ensure_valid_reflection(ng, wo_world, sp.normal);
    }
    let visible = front || material.shades_back() || ctx.face == Face::Both;
    let transmittance = match shader {
        // `powf(1, d)` is 1 for every `d` (NaN too): clear glass, the default, needs no powers.
        Shader::Dielectric { col, .. } if !front && *col != Vec3::ONE => {
            let d = hit.t * ray.dir.length();
            Vec3::new(col.x.powf(d), col.y.powf(d), col.z.powf(d))
        }
        _ => Vec3::ONE,
    };
    let frame = match ctx.normals.and_then(|t| t.frame(hit.prim)) {
        // A flat-shaded hit: `sp.normal` is the table's normal or its negation, whose
        // frame is the kept one or its flip (bit for bit; `-0.0` and `0.0` told apart).
        Some(kept) if same_bits(sp.normal, ng) => {
            if front {
                *kept
            } else {
                kept.flipped()
            }
        }
        _ => ShadingFrame::from_normal(sp.normal),
    };
    Orientation {
        ng,
        front,
        visible,
        transmittance,
        frame,
        wo_world,
    }
}

/// The material's kept BSDF for a face, when the context keeps them and no texture drives
/// this point's shader (`shader` borrowed); `None` where the BSDF must be built.
#[allow(clippy::ptr_arg)] // The `Cow`'s variant is what is read: borrowed is the material's.
#[inline(always)]
pub(crate) fn kept_bsdf<'b>(
    ctx: &ShadeContext<'b>,
    material: u32,
    front: bool,
    shader: &Cow<'_, Shader>,
) -> Option<&'b Bsdf> {
    match (ctx.bsdfs, shader) {
        (Some(kept), Cow::Borrowed(_)) => Some(kept.get(material, front)),
        _ => None,
    }
}

/// The BSDF of a face: its [`kept_bsdf`], else built in `scratch`, which is made only then
/// (a path of untextured vertices never builds the 168-byte empty BSDF).
#[inline]
pub(crate) fn bsdf_kept_or_in<'b>(
    ctx: &ShadeContext<'b>,
    material: u32,
    front: bool,
    shader: &'b Cow<'b, Shader>,
    scratch: &'b mut Option<Bsdf>,
) -> &'b Bsdf {
    match kept_bsdf(ctx, material, front, shader) {
        Some(kept) => kept,
        None => {
            let b = scratch.get_or_insert_with(Bsdf::empty);
            b.set_shader(shader, front);
            b
        }
    }
}

/// A ray leaving `surface` along the local direction `wi_local` of `frame` if it lies on the
/// geometric side its kind requires (reflection: `ng`'s side; transmission: the other side).
#[inline(always)]
pub(crate) fn spawn_along(
    frame: &ShadingFrame,
    ng: Vec3,
    surface: &SurfacePoint,
    wi_local: Vec3,
    transmits: bool,
) -> Option<Ray> {
    let wi = frame.to_world(wi_local);
    let side = ng.dot(wi);
    let ok = if transmits { side < 0.0 } else { side > 0.0 };
    (ok && wi.is_finite()).then(|| spawn_ray(surface, wi))
}

#[cfg(test)]
mod tests {
    /// Clear glass skips the absorption powers: `powf(1, d)` is exactly 1 for every segment
    /// length `d` a ray can give, `0`, subnormal, huge, infinite and NaN among them.
    #[test]
    fn clear_glass_transmits_one_for_every_length() {
        let mut lengths = vec![
            0.0f32,
            -0.0,
            f32::from_bits(1),
            f32::MIN_POSITIVE,
            1e-20,
            0.5,
            1.0,
            3.7,
            1e20,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
        ];
        lengths.extend((0..1000).map(|i| (i as f32 * 0.137).exp2() - 1.0));
        for d in lengths {
            assert_eq!(1.0f32.powf(d).to_bits(), 1.0f32.to_bits(), "powf(1, {d})");
        }
    }
}
