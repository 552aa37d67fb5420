//! Triangle meshes (object prototypes) and their placed instances.

use std::sync::Arc;

use glam::{Vec2, Vec3, Vec4};
use hecs::Entity;

/// An indexed triangle mesh in object space. Shared by every instance of the object.
///
/// Invariants established by the loader: every index is in range, no triangle is degenerate
/// (zero area) and no position is NaN or infinite.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions in object space.
    pub positions: Vec<Vec3>,
    /// Optional per-vertex shading normals (same length as `positions`).
    pub normals: Option<Vec<Vec3>>,
    /// Optional per-vertex texture coordinates (same length as `positions`).
    pub uvs: Option<Vec<Vec2>>,
    /// Triangles as vertex indices, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// The three object-space vertices of triangle `i`.
    pub fn triangle(&self, i: usize) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[i];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }
}

/// The second texture-coordinate set of an object's mesh (glTF `TEXCOORD_1`, the usual
/// lightmap UVs), one per vertex of its [`TriMesh`], v up. Carried by the object entity
/// beside its `Arc<TriMesh>`; bakes with `uvs: MeshSet(1)` read it.
#[derive(Debug, Clone, PartialEq)]
pub struct SecondUvs(pub Arc<Vec<Vec2>>);

/// Per-vertex colours of an object's mesh (PLY `red green blue`), linear RGB, one per
/// vertex of its [`TriMesh`]. Carried by the object entity beside its `Arc<TriMesh>`; the
/// shader-graph node `VertexColor` reads them.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexColours(pub Arc<Vec<Vec3>>);

/// Per-vertex tangents of an object's mesh (glTF `TANGENT`): object-space unit `xyz` and the
/// bitangent's handedness `w` = ±1 (B = w · N × T), one per vertex of its [`TriMesh`].
/// Carried by the object entity beside its `Arc<TriMesh>`; normal maps use them instead of
/// tangents generated from the uvs.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexTangents(pub Arc<Vec<Vec4>>);

/// The materials an object's own polygons name (`materials` of an inline mesh, `.mi`
/// `p "material" …`): one entry per triangle of its [`TriMesh`], `Some` the polygon's
/// material entity, `None` the material the instance resolves to
/// ([`crate::components::MaterialRef`]). Carried by the object entity beside its mesh; an
/// instance entity carrying its own (all `None`: an instance `material` replacing an OBJ's
/// MTL materials) uses that instead.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceMaterials(pub Arc<Vec<Option<Entity>>>);

/// Marker on an object entity: its front is the object-space back (the side its winding
/// calls the back). `build_accel` swaps two corners of its world triangles, as it does for a
/// mirroring instance (see `crate::geometry`), so every geometric normal, one-sided shading,
/// emission and bump follow the reversed front.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReverseOrientation;

/// A placed copy of an object: the leaf of the resolved instance DAG. The entity also carries
/// [`crate::components::WorldFromObject`] and [`crate::components::MaterialRef`].
#[derive(Debug, Clone)]
pub struct Instance {
    /// The object entity (it carries an `Arc<TriMesh>` component).
    pub object: Entity,
    /// The mesh, shared with the object entity (cheap clone).
    pub mesh: Arc<TriMesh>,
}
