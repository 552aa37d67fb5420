//! Evaluating a material's graph at a ray hit: the inputs (uv, object-space position,
//! normal), the bound shader, and the bump-mapped normal with its tangents.
//!
//! **uv.** Meshes with texture coordinates (OBJ `vt`, inline `uvs`) interpolate them;
//! generated surfaces (spheres, tori, patches, NURBS, stairs, …) carry their parametric uv.
//! A mesh without uvs reads uv = (0, 0) everywhere, and its bump tangents come from an
//! arbitrary frame around the normal (the height is then differentiated along object-space
//! steps of `BUMP_STEP`).

use glam::{Mat3, Vec3};

use super::{bump, Inputs, MaterialGraph};
use crate::accel::Hit;
use crate::components::Shader;
use crate::geometry::{SceneGeometry, ShadingPoint};
use crate::shading::frame::ShadingFrame;

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

/// Evaluates `graph` for `shader` at the shading point `sp` of `hit`.
pub fn evaluate(
    geometry: &SceneGeometry,
    sp: &ShadingPoint,
    hit: &Hit,
    graph: &MaterialGraph,
    shader: &Shader,
) -> Textured {
    let inst = &geometry.instances[sp.instance as usize];
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
    let mut regs = Vec::with_capacity(graph.program.ops.len());
    let bound = graph.bind(shader, &inputs, &mut regs);
    if graph.bump.is_none() {
        return Textured {
            shader: bound,
            normal: sp.normal,
            bumped: false,
        };
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
    let normal = graph.bumped_normal(&inputs, [dpdu, dpdv, du_obj, dv_obj], has_uv, &mut regs);
    Textured {
        shader: bound,
        normal,
        bumped: true,
    }
}
