//! Evaluating a material's graph at a ray hit: the inputs (uv, object-space position,
//! normal), the bound shader, and the bump-mapped normal with its tangents. The object's
//! `displacement` in `Bump` mode adds its amount to the material's bump height.
//!
//! **uv.** Meshes with texture coordinates (OBJ `vt`, inline `uvs`) interpolate them;
//! generated surfaces (spheres, tori, patches, NURBS, stairs, …) carry their parametric uv.
//! A mesh without uvs reads uv = (0, 0) everywhere, and its bump tangents come from an
//! arbitrary frame around the normal (the height is then differentiated along object-space
//! steps of `BUMP_STEP`).

use glam::{Mat3, Vec3};

use super::{bump, bumped_normal, Inputs};
use crate::accel::Hit;
use crate::components::{Displacement, Material, Shader};
use crate::geometry::{SceneGeometry, ShadingPoint};
use crate::shading::frame::ShadingFrame;
use crate::tessellation::displace;

/// A shading point's textured material.
#[derive(Debug, Clone, PartialEq)]
pub struct Textured {
    /// The material's shader with every bound parameter evaluated.
    pub shader: Shader,
    /// The shading normal (bumped when the material has a bump map), on the side of the
    /// unperturbed normal.
    pub normal: Vec3,
    /// Whether a bump map changed the normal.
    pub bumped: bool,
}

/// Evaluates the material's graph (bound parameters, bump map) and the object's bump
/// displacement at the shading point `sp` of `hit`; `None` when there is neither.
pub fn evaluate(
    geometry: &SceneGeometry,
    sp: &ShadingPoint,
    hit: &Hit,
    material: &Material,
) -> Option<Textured> {
    let inst = &geometry.instances[sp.instance as usize];
    let displacement = inst.bump.as_deref();
    if material.graph.is_none() && displacement.is_none() {
        return None;
    }
    let local = (hit.prim - inst.first_triangle) as usize;
    let idx = inst.mesh.triangles[local].map(|i| i as usize);
    let b = [1.0 - hit.b1 - hit.b2, hit.b1, hit.b2];
    let pos = idx.map(|i| inst.mesh.positions[i]);
    let p = pos[0] * b[0] + pos[1] * b[1] + pos[2] * b[2];
    let inputs = Inputs {
        uv: sp.uv,
        p,
        n: sp.normal,
    };
    let graph = material.graph.as_deref();
    let mut regs = Vec::with_capacity(graph.map_or(0, |g| g.program.ops.len()));
    let shader = match graph {
        Some(g) => g.bind(&material.shader, &inputs, &mut regs),
        None => material.shader.clone(),
    };
    let has_bump = graph.is_some_and(|g| g.bump.is_some());
    if !has_bump && displacement.is_none() {
        return Some(Textured {
            shader,
            normal: sp.normal,
            bumped: false,
        });
    }
    let m = Mat3::from(inst.world_from_object.matrix3);
    let uv_tangents = inst
        .mesh
        .uvs
        .as_ref()
        .and_then(|uvs| bump::tangents(pos, idx.map(|i| uvs[i])));
    let n = sp.normal;
    let (dpdu, dpdv, du_obj, dv_obj, has_uv) = match uv_tangents {
        Some((du, dv)) => (m * du, m * dv, du, dv, true),
        None => {
            let f = ShadingFrame::from_normal(n);
            let inv = m.inverse();
            (f.s, f.t, inv * f.s, inv * f.t, false)
        }
    };
    // Tangents in the plane of the shading normal, so a zero height gradient keeps it.
    let dpdu = dpdu - n * n.dot(dpdu);
    let dpdv = dpdv - n * n.dot(dpdv);
    // Binding ran the whole program at this point already: its height register is the
    // first value the finite differences ask for.
    let mut at_point = graph
        .filter(|g| !g.bindings.is_empty())
        .and_then(|g| g.bump)
        .map(|b| regs[b.height as usize].x * b.scale);
    let height = |i: &Inputs| {
        let mut h = match at_point.take() {
            Some(h) => h,
            None => graph.map_or(0.0, |g| g.bump_height(i, &mut regs)),
        };
        if let Some(d) = displacement {
            h += displacement_height(d, i);
        }
        h
    };
    let normal = bumped_normal(&inputs, [dpdu, dpdv, du_obj, dv_obj], has_uv, height);
    Some(Textured {
        shader,
        normal,
        bumped: true,
    })
}

/// The amount of a `Bump`-mode displacement shader at `i` (object units, clamped to its
/// bound when it has one).
fn displacement_height(d: &Displacement, i: &Inputs) -> f32 {
    let h = displace::eval(&d.shader, i.p.as_dvec3(), i.uv.as_dvec2());
    let h = match d.bound {
        Some(b) => h.clamp(-(b.abs() as f64), b.abs() as f64),
        None => h,
    };
    if h.is_finite() {
        h as f32
    } else {
        0.0
    }
}
