//! Geometry shaders: what `expand_geometry` turns each [`Procedural`] into.
//!
//! Quadrics become a [`Surface`] (diced by `tessellate` with the object's approximation);
//! stairs and grids are exact polygon meshes and become a [`TriMesh`] at once; a
//! [`crate::components::Scatter`] becomes placements ([`scatter`]).

pub mod scatter;
pub mod stairs;

use crate::components::{Procedural, Quadric, Surface, TriMesh};
use crate::tessellation::quadric::QuadricSource;
use crate::tessellation::GeometryError;

/// The result of expanding one geometry shader.
#[derive(Debug, Clone, PartialEq)]
pub enum Expanded {
    /// A parametric surface still to be tessellated.
    Surface(Surface),
    /// A finished mesh.
    Mesh(TriMesh),
}

/// Checks a geometry shader's parameters (the loader calls this to report errors early).
pub fn validate(p: &Procedural) -> Result<(), GeometryError> {
    expand(p).map(drop)
}

/// Expands a geometry shader.
pub fn expand(p: &Procedural) -> Result<Expanded, GeometryError> {
    let quadric = |q: Quadric| -> Result<Expanded, GeometryError> {
        QuadricSource::new(&q)?;
        Ok(Expanded::Surface(Surface::Quadric(q)))
    };
    match *p {
        Procedural::Sphere(s) => quadric(Quadric::Sphere(s)),
        Procedural::Cylinder(c) => quadric(Quadric::Cylinder(c)),
        Procedural::Cone(c) => quadric(Quadric::Cone(c)),
        Procedural::Disk(d) => quadric(Quadric::Disk(d)),
        Procedural::Torus(t) => quadric(Quadric::Torus(t)),
        Procedural::Stairs(s) => stairs::stairs(&s).map(Expanded::Mesh),
        Procedural::Grid(g) => stairs::grid(&g).map(Expanded::Mesh),
    }
}

/// Whether `p` expands into a parametric surface that `tessellate` dices (the quadrics),
/// rather than straight into a mesh (stairs, grids). For planning: the tessellation stage
/// runs for the surfaces expansion is about to make.
pub fn expands_to_surface(p: &Procedural) -> bool {
    !matches!(p, Procedural::Stairs(_) | Procedural::Grid(_))
}

/// Puts a generated mesh on its object entity and on every leaf instance of that object, so
/// that `build_accel` sees it like a loaded one.
pub fn install_mesh(
    world: &mut hecs::World,
    object: hecs::Entity,
    mesh: std::sync::Arc<TriMesh>,
) -> Result<(), hecs::NoSuchEntity> {
    world.insert_one(object, mesh.clone())?;
    for inst in world.query_mut::<&mut crate::components::Instance>() {
        if inst.object == object {
            inst.mesh = mesh.clone();
        }
    }
    Ok(())
}

/// The mesh placeholder a scene loader gives leaf instances of objects whose mesh a geometry
/// stage generates (procedural, parametric, subdivision, scatter): empty until then.
pub fn pending_instance(object: hecs::Entity) -> crate::components::Instance {
    crate::components::Instance {
        object,
        mesh: std::sync::Arc::new(TriMesh::default()),
    }
}
