//! Parametric (free-form) surfaces, diced into triangles by the `tessellate` stage, and the
//! Catmull-Clark subdivision control mesh.
//!
//! A surface is a set of patches over a shared parameter grid; neighbouring patches share
//! their boundary curves, which the tessellator evaluates once so that the result is
//! watertight. Positions are object-space.

use glam::{Vec3, Vec4};

use super::procedural::{Cone, Cylinder, Disk, Sphere, Torus};

/// Basis of a bicubic patch mesh (RenderMan `Basis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CubicBasis {
    /// Bézier: each patch has its own 4×4 control points; neighbours share a row (step 3).
    Bezier,
    /// Uniform cubic B-spline: patches overlap by three rows (step 1); C² continuous.
    BSpline,
    /// Catmull-Rom: interpolating, step 1.
    CatmullRom,
}

/// Patch type of a [`PatchMesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PatchKind {
    /// Bilinear: 2×2 points per patch, step 1.
    Bilinear,
    /// Bicubic with the given basis.
    Bicubic(CubicBasis),
}

/// RenderMan's `PatchMesh type nu uwrap nv vwrap "P" [...]` (a single `Patch` is the
/// 2×2 bilinear or 4×4 bicubic case).
///
/// `points` holds `nu × nv` control points, u varying fastest. Patches per direction:
/// bilinear `nu − 1` (periodic: `nu`), Bézier `(nu − 1) / 3` (periodic: `nu / 3`), B-spline
/// and Catmull-Rom `nu − 3` (periodic: `nu`). Texture coordinates run 0…1 over the whole mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchMesh {
    /// Patch type and basis.
    pub kind: PatchKind,
    /// Control points along u.
    pub nu: u32,
    /// Control points along v.
    pub nv: u32,
    /// Periodic in u (the mesh closes on itself; needs at least 3 patches around).
    pub u_wrap: bool,
    /// Periodic in v.
    pub v_wrap: bool,
    /// Control points, `nu × nv`, u fastest.
    pub points: Vec<Vec3>,
    /// User texture coordinates and normals (RenderMan's `s`, `t`, `N`), default none.
    pub vars: SurfaceVariables,
}

impl PatchMesh {
    /// A single bilinear patch with corners P(0,0), P(1,0), P(0,1), P(1,1) — RenderMan's
    /// point order for `Patch "bilinear"`.
    pub fn bilinear(points: [Vec3; 4]) -> Self {
        Self {
            kind: PatchKind::Bilinear,
            nu: 2,
            nv: 2,
            u_wrap: false,
            v_wrap: false,
            points: points.to_vec(),
            vars: SurfaceVariables::default(),
        }
    }
}

/// A non-uniform rational B-spline surface (no trimming curves yet).
///
/// Control points are given as `(x, y, z, w)`: the point `(x, y, z)` with weight `w`
/// (not premultiplied); `points` has
/// `count_u × count_v` entries, u fastest. Knot vectors are non-decreasing with
/// `count + degree + 1` entries. The parameter domain is `[knots[degree], knots[count]]`.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    /// Degree in u (1…7).
    pub degree_u: u32,
    /// Degree in v (1…7).
    pub degree_v: u32,
    /// Control points along u.
    pub count_u: u32,
    /// Control points along v.
    pub count_v: u32,
    /// Knot vector in u.
    pub knots_u: Vec<f32>,
    /// Knot vector in v.
    pub knots_v: Vec<f32>,
    /// Control points `(x, y, z)` with weight `w > 0`, u fastest.
    pub points: Vec<Vec4>,
    /// User texture coordinates and normals (RenderMan's `s`, `t`, `N`), default none.
    pub vars: SurfaceVariables,
}

/// An analytic quadric surface (produced by `expand_geometry` from a geometry shader).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quadric {
    /// See [`Sphere`].
    Sphere(Sphere),
    /// See [`Cylinder`].
    Cylinder(Cylinder),
    /// See [`Cone`].
    Cone(Cone),
    /// See [`Disk`].
    Disk(Disk),
    /// See [`Torus`].
    Torus(Torus),
}

/// A parametric surface on an object entity; `tessellate` replaces it with an
/// `Arc<TriMesh>` according to the object's [`crate::components::Approximation`].
#[derive(Debug, Clone, PartialEq)]
pub enum Surface {
    /// Bilinear or bicubic patch mesh.
    Patches(PatchMesh),
    /// NURBS surface.
    Nurbs(NurbsSurface),
    /// Analytic quadric.
    Quadric(Quadric),
}

impl Surface {
    /// Short name for reports (`"patch mesh"`, `"nurbs"`, `"torus"`, …).
    pub fn kind(&self) -> &'static str {
        match self {
            Surface::Patches(_) => "patch mesh",
            Surface::Nurbs(_) => "nurbs",
            Surface::Quadric(Quadric::Sphere(_)) => "sphere",
            Surface::Quadric(Quadric::Cylinder(_)) => "cylinder",
            Surface::Quadric(Quadric::Cone(_)) => "cone",
            Surface::Quadric(Quadric::Disk(_)) => "disk",
            Surface::Quadric(Quadric::Torus(_)) => "torus",
        }
    }
}

/// A Catmull-Clark subdivision surface: a polygon control mesh (any polygon sizes ≥ 3,
/// manifold), smooth rules in the interior and B-spline curve rules on boundary edges.
#[derive(Debug, Clone, PartialEq)]
pub struct SubdivMesh {
    /// Control vertices.
    pub positions: Vec<Vec3>,
    /// Vertex count of each face (each ≥ 3).
    pub face_sizes: Vec<u32>,
    /// Vertex indices of all faces, concatenated, counter-clockwise seen from outside.
    pub face_indices: Vec<u32>,
    /// User texture coordinates and normals (RenderMan's `s`, `t`, `N`), default none.
    pub vars: SurfaceVariables,
}

/// Values of one primitive variable (`s`, `t` in `x`; `N` as a vector) over a patch mesh,
/// NURBS surface or subdivision mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceValues {
    /// One per control point, interpolated like the positions (RenderMan's `vertex`: the
    /// patch basis, the NURBS basis with the points' weights, Catmull-Clark refinement).
    Control(Vec<Vec3>),
    /// Interpolated bilinearly over each patch from its corners (RenderMan's `varying`,
    /// `facevarying`, `uniform` and `constant`, expanded): four per patch — patch meshes
    /// and NURBS, u-fastest patch order, NURBS counting every knot span, empty ones too —
    /// at its corners (0,0), (1,0), (0,1), (1,1); one per face corner for subdivision
    /// meshes (in `face_indices` order), linear over each face.
    Corners(Vec<Vec3>),
}

impl SurfaceValues {
    /// The values, whichever the interpolation.
    pub fn values(&self) -> &[Vec3] {
        match self {
            SurfaceValues::Control(v) | SurfaceValues::Corners(v) => v,
        }
    }
}

/// The user texture coordinates and normals of a surface; a missing one keeps the
/// surface's own (its parametric `u`, `v`, its geometric normal).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceVariables {
    /// Texture coordinate `s` (the uv's u), in `x`.
    pub s: Option<SurfaceValues>,
    /// Texture coordinate `t` (the uv's v), in `x`.
    pub t: Option<SurfaceValues>,
    /// Shading normals (normalised where used).
    pub normals: Option<SurfaceValues>,
}

impl SurfaceVariables {
    /// No variable given.
    pub fn is_empty(&self) -> bool {
        self.s.is_none() && self.t.is_none() && self.normals.is_none()
    }
}
