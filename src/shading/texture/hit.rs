//! Evaluating a material's graph at a ray hit: the inputs (uv, object-space position,
//! normal), the bound shader, the emission's texture, and the normal-mapped, object-space
//! ([`object_normal`]) and bump-mapped normal with its tangents. The object's `displacement` in `Bump` mode adds
//! its amount to the material's bump height.
//!
//! **Vertex colours** (PLY `red green blue`, glTF `COLOR_0`) are interpolated like uvs;
//! white without. **Tangents** of the mesh (glTF `TANGENT`), when it has them, give normal
//! maps their frame; otherwise it is generated from the uvs ([`normal_map`]).
//!
//! **uv.** Meshes with texture coordinates (OBJ `vt`, inline `uvs`) interpolate them;
//! generated surfaces (spheres, tori, patches, NURBS, stairs, …) carry their parametric uv.
//! A mesh without uvs reads uv = (0, 0) everywhere, and its bump tangents come from an
//! arbitrary frame around the normal (the height is then differentiated along object-space
//! steps of `BUMP_STEP`).

use glam::{Mat3, Vec3};

use super::{bump, bumped_normal, normal_map, object_normal, Inputs};
use crate::accel::Hit;
use crate::components::{Displacement, Material, Shader};
use crate::geometry::{InstanceGeometry, SceneGeometry, ShadingPoint};
use crate::shading::frame::ShadingFrame;
use crate::tessellation::displace;

/// The mesh's tangent interpolated at barycentrics `b` of the triangle `idx` (object space)
/// and its handedness (the sign of the interpolated `w`), when the mesh has tangents.
fn file_tangent(inst: &InstanceGeometry, idx: [usize; 3], b: [f32; 3]) -> Option<(Vec3, f32)> {
    let tangents = inst.tangents.as_deref()?;
    let v = idx.map(|i| tangents[i]);
    let t = v[0] * b[0] + v[1] * b[1] + v[2] * b[2];
    Some((t.truncate(), if t.w < 0.0 { -1.0 } else { 1.0 }))
}

/// A shading point's textured material.
#[derive(Debug, Clone, PartialEq)]
pub struct Textured {
    /// The material's shader with every bound parameter evaluated.
    pub shader: Shader,
    /// The shading normal (bumped when the material has a bump map), on the side of the
    /// unperturbed normal.
    pub normal: Vec3,
    /// Whether a bump map, a normal map or an object-space normal changed the normal.
    pub bumped: bool,
    /// Whether `normal` is to be used exactly as given, not made safe (hard case H11): an
    /// object-space normal under a local illumination model, which evaluates its formula
    /// for any normal as its shading language does (RenderMan's `Nf`).
    pub exact: bool,
    /// Emitted radiance here, W/(sr·m²): the material's `emission` times its texture.
    pub emission: Vec3,
}

/// Whether a point of `inst` with `material` has anything for [`evaluate`] to do: a shader
/// graph (bound parameters, bump or normal map) or the instance's bump displacement.
#[inline(always)]
pub fn is_textured(inst: &InstanceGeometry, material: &Material) -> bool {
    material.graph.is_some() || inst.bump.is_some()
}

/// Evaluates the material's graph (bound parameters, bump map) and the object's bump
/// displacement at the shading point `sp` of `hit`; `None` when there is neither. The test
/// is inline (every vertex of every path makes it, and an untextured one stops there); the
/// evaluation is a call.
#[inline(always)]
pub fn evaluate(
    geometry: &SceneGeometry,
    sp: &ShadingPoint,
    hit: &Hit,
    material: &Material,
) -> Option<Textured> {
    let inst = &geometry.instances[sp.instance as usize];
    if !is_textured(inst, material) {
        return None;
    }
    evaluate_textured(inst, sp, hit, material)
}

/// [`evaluate`] at a point where [`is_textured`] holds.
#[inline(never)]
fn evaluate_textured(
    inst: &InstanceGeometry,
    sp: &ShadingPoint,
    hit: &Hit,
    material: &Material,
) -> Option<Textured> {
    let displacement = inst.bump.as_deref();
    let local = (hit.prim - inst.first_triangle) as usize;
    let idx = inst.corners(local);
    let b = [1.0 - hit.b1 - hit.b2, hit.b1, hit.b2];
    let pos = idx.map(|i| inst.mesh.positions[i]);
    let p = pos[0] * b[0] + pos[1] * b[1] + pos[2] * b[2];
    let inputs = Inputs {
        uv: sp.uv,
        p,
        n: sp.normal,
        colour: vertex_colour(inst, idx, b),
    };
    let graph = material.graph.as_deref();
    let mut regs = Vec::with_capacity(graph.map_or(0, |g| g.program.ops.len()));
    let shader = match graph {
        Some(g) => g.bind(&material.shader, &inputs, &mut regs),
        None => material.shader.clone(),
    };
    let emission = match graph.and_then(|g| g.emission) {
        Some(r) => material.emission * regs[r as usize].max(Vec3::ZERO),
        None => material.emission,
    };
    let map = graph.and_then(|g| g.normal_map);
    let object = graph.and_then(|g| g.object_normal);
    let has_bump = graph.is_some_and(|g| g.bump.is_some());
    if !has_bump && map.is_none() && object.is_none() && displacement.is_none() {
        return Some(Textured {
            shader,
            normal: sp.normal,
            bumped: false,
            exact: false,
            emission,
        });
    }
    let m = Mat3::from(inst.world_from_object.matrix3);
    let uv_tangents = inst
        .mesh
        .uvs
        .as_ref()
        .and_then(|uvs| bump::tangents(pos, idx.map(|i| uvs[i])));
    let mut n = sp.normal;
    if let Some(r) = object {
        let on = regs[r as usize];
        n = object_normal::to_world(inst.normal_from_object, on, sp.surface.ng, n);
        if displacement.is_none() {
            let exact = object_normal::is_local(&shader);
            return Some(Textured {
                shader,
                normal: n,
                bumped: true,
                exact,
                emission,
            });
        }
    }
    if let Some(map) = map {
        let tangents = match (file_tangent(inst, idx, b), uv_tangents) {
            (Some((t, w)), _) => normal_map::frame_from_tangent(n, m * t, w * m.determinant()),
            (None, Some((du, dv))) => normal_map::frame(n, m * du, m * dv),
            (None, None) => None,
        };
        let (t, b) = tangents.unwrap_or_else(|| {
            let f = ShadingFrame::from_normal(n);
            (f.s, f.t)
        });
        n = normal_map::perturb(n, t, b, regs[map.texel as usize], map.scale);
        if !has_bump && displacement.is_none() {
            return Some(Textured {
                shader,
                normal: n,
                bumped: true,
                exact: false,
                emission,
            });
        }
    }
    let inputs = Inputs { n, ..inputs };
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
        .filter(|g| g.runs_at_hits())
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
        exact: false,
        emission,
    })
}

/// The instance's vertex colour at the barycentrics `b` of the triangle `idx` (white when
/// the mesh has none).
fn vertex_colour(inst: &InstanceGeometry, idx: [usize; 3], b: [f32; 3]) -> Vec3 {
    match inst.colours.as_deref() {
        Some(c) => c[idx[0]] * b[0] + c[idx[1]] * b[1] + c[idx[2]] * b[2],
        None => Vec3::ONE,
    }
}

/// The emitted radiance of `material` at `hit` (W/(sr·m²)): its `emission` times its
/// emission texture there, if it has one.
pub fn emission_at(geometry: &SceneGeometry, hit: &Hit, material: &Material) -> Vec3 {
    let Some(reg) = material.graph.as_deref().and_then(|g| g.emission) else {
        return material.emission;
    };
    let sp = geometry.shading_point(hit);
    let inst = &geometry.instances[sp.instance as usize];
    let local = (hit.prim - inst.first_triangle) as usize;
    let idx = inst.corners(local);
    let b = [1.0 - hit.b1 - hit.b2, hit.b1, hit.b2];
    let p = idx
        .iter()
        .zip(b)
        .fold(Vec3::ZERO, |s, (&i, w)| s + inst.mesh.positions[i] * w);
    let inputs = Inputs {
        uv: sp.uv,
        p,
        n: sp.normal,
        colour: vertex_colour(inst, idx, b),
    };
    let graph = material.graph.as_deref().expect("checked above");
    let mut regs = Vec::with_capacity(reg as usize + 1);
    graph.program.run_to(&inputs, &mut regs, reg as usize + 1);
    material.emission * regs[reg as usize].max(Vec3::ZERO)
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
