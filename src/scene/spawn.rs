//! Spawning the validated scene into a `hecs::World`.
//!
//! Entities, in this order (so entity order is deterministic):
//! 1. materials used by at least one leaf, in file order, then the built-in `"<default>"`
//!    material if some leaf has no material;
//! 2. objects used by at least one leaf: `Name`, `SourceLink`, `Arc<TriMesh>`;
//! 3. one entity per leaf of the instance DAG: `Name` (the DAG path), `SourceLink` (the
//!    innermost instance), `Instance`, `WorldFromObject`, `MaterialRef`, and `BakeRequest`
//!    when the instance has a `bake` entry;
//! 4. every light: `Name`, `SourceLink`, `Emitter`;
//! 5. every camera: `Name`, `SourceLink`, `Camera`, plus `RenderCamera` on the render camera.
//!
//! `SourceLink`s point at the element's opening parenthesis in its file.

use std::collections::HashMap;
use std::sync::Arc;

use hecs::{Entity, World};

use super::dag::Leaf;
use super::diagnostics::Sources;
use super::validate::{default_material, Merged};
use crate::components::{
    BakeRequest, Camera, Emitter, Instance, Material, MaterialRef, Name, RenderCamera, SourceLink,
    TriMesh, WorldFromObject,
};

/// Everything checked and built, ready to spawn (indices parallel to the merged lists;
/// `None` for elements that failed a check, which the caller reports instead of spawning).
pub struct Parts {
    /// Camera components.
    pub cameras: Vec<Option<Camera>>,
    /// Index of the render camera.
    pub render_camera: Option<usize>,
    /// Light components.
    pub lights: Vec<Option<Emitter>>,
    /// Material components.
    pub materials: Vec<Option<Material>>,
    /// Meshes of the objects that were built (reachable ones).
    pub meshes: Vec<Option<Arc<TriMesh>>>,
    /// The flattened instance DAG.
    pub leaves: Vec<Leaf>,
    /// Bake request of each merged instance (at most one leaf carries each).
    pub bakes: Vec<Option<BakeRequest>>,
}

/// Builds the world.
pub fn spawn(src: &Sources, m: &Merged<'_>, parts: Parts) -> World {
    let mut world = World::new();

    let mut material_entity: HashMap<Option<usize>, Entity> = HashMap::new();
    let mut used: Vec<Option<usize>> = parts.leaves.iter().map(|l| l.material).collect();
    used.sort_by_key(|u| u.map_or(usize::MAX, |i| i));
    used.dedup();
    for key in used {
        let entity = match key {
            Some(i) => {
                let Some(Some(material)) = parts.materials.get(i) else {
                    continue;
                };
                let it = &m.materials[i];
                world.spawn((
                    Name(it.desc.name.clone()),
                    src.link(it.file, &it.path),
                    material.clone(),
                ))
            }
            None => world.spawn((
                Name("<default>".into()),
                SourceLink {
                    file: src
                        .files
                        .first()
                        .map(|f| f.path.clone())
                        .unwrap_or_default(),
                    line: 1,
                    column: 1,
                },
                default_material(),
            )),
        };
        material_entity.insert(key, entity);
    }

    let mut object_entity: HashMap<usize, Entity> = HashMap::new();
    let mut used_objects: Vec<usize> = parts.leaves.iter().map(|l| l.object).collect();
    used_objects.sort_unstable();
    used_objects.dedup();
    for o in used_objects {
        let Some(mesh) = parts.meshes.get(o).cloned().flatten() else {
            continue;
        };
        let it = &m.objects[o];
        let entity = world.spawn((
            Name(it.desc.name.clone()),
            src.link(it.file, &it.path),
            mesh,
        ));
        object_entity.insert(o, entity);
    }

    for leaf in &parts.leaves {
        let (Some(&object), Some(mesh), Some(&material)) = (
            object_entity.get(&leaf.object),
            parts.meshes.get(leaf.object).cloned().flatten(),
            material_entity.get(&leaf.material),
        ) else {
            continue;
        };
        let it = &m.instances[leaf.instance];
        let entity = world.spawn((
            Name(leaf.path.clone()),
            src.link(it.file, &it.path),
            Instance { object, mesh },
            WorldFromObject(leaf.world_from_object),
            MaterialRef(material),
        ));
        if let Some(Some(request)) = parts.bakes.get(leaf.instance) {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, request.clone());
        }
    }

    for (it, emitter) in m.lights.iter().zip(parts.lights) {
        let Some(emitter) = emitter else { continue };
        world.spawn((
            Name(it.desc.name.clone()),
            src.link(it.file, &it.path),
            emitter,
        ));
    }

    for (i, (it, camera)) in m.cameras.iter().zip(parts.cameras).enumerate() {
        let Some(camera) = camera else { continue };
        let entity = world.spawn((
            Name(it.desc.name.clone()),
            src.link(it.file, &it.path),
            camera,
        ));
        if Some(i) == parts.render_camera {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, RenderCamera);
        }
    }

    world
}
