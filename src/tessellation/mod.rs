//! Tessellation: parametric surfaces, subdivision meshes and displaced meshes → triangles.
//!
//! Every input is first seen as a *patch complex* ([`PatchSource`]): quadrilateral patches
//! over `[0, 1]²` whose corners carry shared ids. [`complex`] dices it: the rate of each edge
//! is decided from the edge alone (sampled by one owner patch in canonical corner order), the
//! vertices of shared corners and edges are evaluated and displaced once, and patches stitch
//! their interiors to those shared vertices — so the result is watertight bit for bit.
//!
//! | module | job |
//! | --- | --- |
//! | [`complex`] | edge rates → shared vertices → per-patch dicing and stitching |
//! | [`rates`] | the approximation techniques as "segments for this curve" |
//! | [`displace`] | scalar displacement nodes, Perlin noise |
//! | [`grid`] | corner ids of a grid of patches (wraps, poles) |
//! | [`quadric`] | sphere, cylinder, cone, disk, torus as patch sources |
//! | [`patch`] | bilinear and bicubic patch meshes |
//! | [`nurbs`] | NURBS surfaces |
//! | [`subdiv`] | Catmull-Clark refinement to a quad control cage |
//! | [`variables`] | user texture coordinates and normals on patch meshes and NURBS |
//! | [`subdiv_variables`] | the same on subdivision meshes' limit cages |
//! | [`polymesh`] | triangle meshes as patch sources (for displacement) |

pub mod complex;
pub mod displace;
mod error;
pub mod grid;
pub mod nurbs;
pub mod patch;
pub mod polymesh;
pub mod quadric;
pub mod rates;
pub mod subdiv;
pub mod subdiv_variables;
pub mod variables;

use glam::{DAffine3, DVec2, DVec3};

pub use error::GeometryError;
pub(crate) use error::{as_written, finite, positive, sweep};

use crate::components::{
    Approximation, Displacement, SubdivMesh, Surface, SurfaceDerivatives, TriMesh,
};

/// A point on a parametric surface, evaluated in f64.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceSample {
    /// Position (object space).
    pub p: DVec3,
    /// ∂P/∂u per unit of the texture coordinate u.
    pub dpdu: DVec3,
    /// ∂P/∂v per unit of the texture coordinate v.
    pub dpdv: DVec3,
    /// Unit outward normal (also where the derivatives degenerate, e.g. at a pole).
    pub n: DVec3,
    /// Texture coordinates.
    pub uv: DVec2,
}

/// A set of quadrilateral patches sharing corners: the input of the dicer.
///
/// Patch corners are listed as (0,0), (1,0), (1,1), (0,1) in the patch's own parameters.
/// Two patches share an edge exactly when they share both of its corner ids; an edge whose
/// two corners have the same id is degenerate (a pole or an apex). Two distinct edges must
/// not join the same pair of corners.
pub trait PatchSource: Sync {
    /// Number of patches.
    fn patch_count(&self) -> usize;
    /// Number of distinct corner ids (ids are `0..corner_count`).
    fn corner_count(&self) -> usize;
    /// Corner ids of `patch`.
    fn corners(&self, patch: usize) -> [u32; 4];
    /// Evaluates `patch` at local parameters `(u, v) ∈ [0, 1]²`.
    fn eval(&self, patch: usize, u: f64, v: f64) -> SurfaceSample;
    /// Patches along u and v of a regular grid (for [`crate::components::Technique::Regular`]);
    /// `(1, 1)` when the complex is not a grid.
    fn grid(&self) -> (usize, usize) {
        (1, 1)
    }
}

/// The render camera as the raster-space approximation sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct RasterView {
    /// Camera-from-object transform of each instance of the object (camera looks down −Z).
    pub camera_from_object: Vec<DAffine3>,
    /// Pixels per object unit at distance 1: `(height / 2) / tan(fov_y / 2)`.
    pub pixels_per_unit: f64,
}

/// What the tessellator produced.
#[derive(Debug, Clone, PartialEq)]
pub struct Tessellation {
    /// The triangle mesh (f32), with normals and uvs.
    pub mesh: TriMesh,
    /// Per-vertex derivatives, when asked for.
    pub derivatives: Option<SurfaceDerivatives>,
}

/// Options of one tessellation run.
#[derive(Debug, Clone, Copy)]
pub struct Options<'a> {
    /// The approximation (clamped as documented).
    pub approximation: &'a Approximation,
    /// True displacement to apply (bump displacement is not passed here).
    pub displacement: Option<&'a Displacement>,
    /// The view, for raster-space approximations.
    pub view: Option<&'a RasterView>,
    /// Store per-vertex derivatives.
    pub derivatives: bool,
    /// The most triangles the rates may ask for: checked before dicing, so a hostile rate
    /// (`Parametric(u: 4096, v: 4096)`, a tiny `Spatial` edge) fails instead of allocating
    /// (`u64::MAX`: no limit; the stage derives it from the run's memory budget).
    pub max_triangles: u64,
}

/// Tessellates a parametric surface component.
pub fn tessellate_surface(
    surface: &Surface,
    opts: &Options,
) -> Result<Tessellation, GeometryError> {
    match surface {
        Surface::Patches(mesh) => {
            let src = patch::PatchMeshSource::new(mesh)?;
            if mesh.vars.is_empty() {
                complex::tessellate(&src, opts)
            } else {
                complex::tessellate(&variables::Varied::patches(&src, mesh)?, opts)
            }
        }
        Surface::Nurbs(n) => {
            let src = nurbs::NurbsSource::new(n)?;
            if n.vars.is_empty() {
                complex::tessellate(&src, opts)
            } else {
                complex::tessellate(&variables::Varied::nurbs(&src, n)?, opts)
            }
        }
        Surface::Quadric(q) => complex::tessellate(&quadric::QuadricSource::new(q)?, opts),
    }
}

/// Tessellates a Catmull-Clark subdivision mesh (refined to its limit, then diced).
pub fn tessellate_subdiv(mesh: &SubdivMesh, opts: &Options) -> Result<Tessellation, GeometryError> {
    complex::tessellate(&subdiv::limit_cage(mesh, opts.approximation)?, opts)
}

/// Re-tessellates a triangle mesh for displacement: each triangle becomes three bilinear
/// quads over welded vertices, diced with the approximation (on the displaced surface).
pub fn tessellate_mesh(mesh: &TriMesh, opts: &Options) -> Result<Tessellation, GeometryError> {
    complex::tessellate(&polymesh::QuadCage::from_trimesh(mesh)?, opts)
}
