//! Spawning the validated scene into a `hecs::World`.
//!
//! Entities, in this order (so entity order is deterministic):
//! 1. materials used by at least one leaf, in file order, then the built-in `"<default>"`
//!    material if some leaf has no material;
//! 2. objects used by at least one leaf, or by the scatter of a used object: `Name`,
//!    `SourceLink`, and `Arc<TriMesh>` for loaded meshes or the generator component
//!    (`Procedural`, `Surface`, `SubdivMesh`, `Scatter`) for generated ones, plus
//!    `Approximation` (with its `ApproximationLink`), `Displacement` and
//!    `DerivativeRequest` when written;
//! 3. one entity per leaf of the instance DAG: `Name` (the DAG path), `SourceLink` (the
//!    innermost instance), `Instance` (with an empty mesh for generated objects:
//!    `procedural::pending_instance`), `WorldFromObject`, `MaterialRef`, `BakeRequest`
//!    when the instance has a `bake` entry, and `FaceMaterials` (all `None`) when the
//!    instance's `material` replaces an OBJ's per-face MTL materials;
//! 4. the scene origin (`SceneOrigin`), when render space is not world space;
//! 5. every light: `Name`, `SourceLink`, `Emitter`;
//! 6. every camera: `Name`, `SourceLink`, `Camera`, plus `RenderCamera` on the render camera
//!    and `Imager`, `Lenses`, `Atmosphere` when written.
//!
//! Materials with an `interior` also carry `Interior`, those with a contour shader
//! `ContourShader`.
//!
//! `SourceLink`s point at the element's opening parenthesis in its file.

use std::collections::HashMap;
use std::sync::Arc;

use hecs::{Entity, EntityBuilder, World};

use super::dag::Leaf;
use super::diagnostics::Sources;
use super::geometry::{Generated, ObjectGeometry};
use super::validate::{default_material, Merged};
use crate::components::{
    Atmosphere, AtmosphereFade, BakeRequest, Camera, ContourShader, Emitter, Fog, Imager, Instance,
    Interior, Lenses, Material, MaterialRef, Name, OutputLinks, RenderCamera, SceneOrigin,
    SourceLink, TriMesh, WorldFromObject,
};
use crate::procedural::pending_instance;

/// What one camera was checked into (`None` where a check failed or nothing is written).
#[derive(Default)]
pub struct CameraParts {
    /// The camera component.
    pub camera: Option<Camera>,
    /// Its imager.
    pub imager: Option<Imager>,
    /// Its lens shaders.
    pub lenses: Option<Lenses>,
    /// Its atmosphere (fog or fade).
    pub atmosphere: Option<super::volume::Atmosphere>,
    /// Where each of its outputs names its file.
    pub output_links: Vec<SourceLink>,
    /// Where its resolution's width is written (the camera when it is not).
    pub resolution_link: Option<SourceLink>,
}

/// What one material was checked into.
pub struct MaterialParts {
    /// The material component.
    pub material: Option<Material>,
    /// Its interior volume.
    pub interior: Option<Fog>,
    /// Its contour shader.
    pub contour: Option<ContourShader>,
}

/// What one object was checked and built into.
pub struct ObjectParts {
    /// Its mesh, if it was built (reachable objects with a loaded mesh).
    pub mesh: Option<Arc<TriMesh>>,
    /// Its mesh's second UV set (glTF `TEXCOORD_1`), spawned as [`crate::components::SecondUvs`].
    pub uvs1: Option<Arc<Vec<glam::Vec2>>>,
    /// Its mesh's vertex colours, spawned as [`crate::components::VertexColours`].
    pub colours: Option<Arc<Vec<glam::Vec3>>>,
    /// Its mesh's tangents, spawned as [`crate::components::VertexTangents`].
    pub tangents: Option<Arc<Vec<glam::Vec4>>>,
    /// Its geometry components (generator, approximation, displacement).
    pub geometry: Option<ObjectGeometry>,
    /// Per triangle of `mesh`, the material its polygon names (`None`: the instance's),
    /// spawned as [`crate::components::FaceMaterials`].
    pub face_materials: Option<Vec<Option<usize>>>,
    /// Whether an instance's `material` replaces `face_materials` (an OBJ's MTL materials)
    /// rather than yielding to them (inline and `.mi` polygon materials).
    pub instance_material_wins: bool,
}

/// Everything checked and built, ready to spawn (one entry per element of the merged lists;
/// `None` for elements that failed a check, which the caller reports instead of spawning).
pub struct Parts {
    /// Per camera.
    pub cameras: Vec<CameraParts>,
    /// Index of the render camera.
    pub render_camera: Option<usize>,
    /// Light components.
    pub lights: Vec<Option<Emitter>>,
    /// Per material.
    pub materials: Vec<MaterialParts>,
    /// Per object.
    pub objects: Vec<ObjectParts>,
    /// The flattened instance DAG.
    pub leaves: Vec<Leaf>,
    /// Bake request of each merged instance (at most one leaf carries each).
    pub bakes: Vec<Option<BakeRequest>>,
    /// The scene origin subtracted from world space (see [`super::rebase`]).
    pub origin: glam::DVec3,
}

/// Objects to spawn, in index order: those of the leaves, and the prototypes and surfaces of
/// the scatters among them.
fn used_objects(parts: &Parts) -> Vec<usize> {
    let mut used = vec![false; parts.objects.len()];
    let mut todo: Vec<usize> = parts.leaves.iter().map(|l| l.object).collect();
    while let Some(o) = todo.pop() {
        if o >= used.len() || std::mem::replace(&mut used[o], true) {
            continue;
        }
        if let Some(Some(ObjectGeometry {
            generated:
                Some(Generated::Scatter {
                    prototype, surface, ..
                }),
            ..
        })) = parts.objects.get(o).map(|p| &p.geometry)
        {
            todo.extend([*prototype, *surface]);
        }
    }
    (0..used.len()).filter(|&o| used[o]).collect()
}

/// Builds the world.
pub fn spawn(src: &Sources, m: &Merged<'_>, parts: Parts) -> World {
    let mut world = World::new();

    let mut material_entity: HashMap<Option<usize>, Entity> = HashMap::new();
    let mut used: Vec<Option<usize>> = parts.leaves.iter().map(|l| l.material).collect();
    for leaf in &parts.leaves {
        if let Some(faces) = parts
            .objects
            .get(leaf.object)
            .and_then(|o| o.face_materials.as_ref())
        {
            used.extend(faces.iter().filter(|f| f.is_some()));
        }
    }
    used.sort_by_key(|u| u.map_or(usize::MAX, |i| i));
    used.dedup();
    for key in used {
        let entity = match key {
            Some(i) => {
                let Some(MaterialParts {
                    material: Some(material),
                    interior,
                    contour,
                }) = parts.materials.get(i)
                else {
                    continue;
                };
                let it = &m.materials[i];
                let entity = world.spawn((
                    Name(it.desc.name.clone()),
                    SourceLink::from(it.pos.clone()),
                    material.clone(),
                ));
                if let Some(fog) = interior {
                    // The entity was just spawned, so inserting cannot fail.
                    let _ = world.insert_one(entity, Interior(*fog));
                }
                if let Some(shader) = contour {
                    // As above.
                    let _ = world.insert_one(entity, *shader);
                }
                entity
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
    for o in used_objects(&parts) {
        let Some(ObjectParts {
            mesh,
            uvs1,
            colours,
            tangents,
            geometry: Some(geometry),
            face_materials,
            ..
        }) = parts.objects.get(o)
        else {
            continue;
        };
        let it = &m.objects[o];
        let mut b = EntityBuilder::new();
        b.add(Name(it.desc.name.clone()));
        b.add(SourceLink::from(it.pos.clone()));
        if geometry.generated.is_none() {
            let Some(mesh) = mesh.clone() else {
                continue;
            };
            b.add(mesh);
            if let Some(uvs) = uvs1 {
                b.add(crate::components::SecondUvs(uvs.clone()));
            }
            if let Some(colours) = colours {
                b.add(crate::components::VertexColours(colours.clone()));
            }
            if let Some(tangents) = tangents {
                b.add(crate::components::VertexTangents(tangents.clone()));
            }
            if let Some(faces) = face_materials {
                let entities = faces
                    .iter()
                    .map(|f| f.and_then(|i| material_entity.get(&Some(i)).copied()))
                    .collect();
                b.add(crate::components::FaceMaterials(Arc::new(entities)));
            }
        }
        geometry.add_to(&mut b);
        if geometry.approximation.is_some() {
            let at = src.pos(it.file, &it.at(".approximation"));
            b.add(crate::components::ApproximationLink(SourceLink::from(at)));
        }
        object_entity.insert(o, world.spawn(b.build()));
    }
    // Scatters name other objects: link them now that every object has its entity.
    for (&o, &entity) in &object_entity {
        if let Some(Some(ObjectGeometry {
            generated:
                Some(Generated::Scatter {
                    prototype,
                    surface,
                    template,
                }),
            ..
        })) = parts.objects.get(o).map(|p| &p.geometry)
        {
            if let (Some(&p), Some(&s)) = (object_entity.get(prototype), object_entity.get(surface))
            {
                let scatter = crate::components::Scatter {
                    prototype: p,
                    surface: s,
                    ..*template
                };
                // The entity was just spawned, so inserting cannot fail.
                let _ = world.insert_one(entity, scatter);
            }
        }
    }

    // Leaves whose instance material replaces their object's per-face materials.
    let mut whole: HashMap<usize, crate::components::FaceMaterials> = HashMap::new();
    for leaf in &parts.leaves {
        let (Some(&object), Some(&material)) = (
            object_entity.get(&leaf.object),
            material_entity.get(&leaf.material),
        ) else {
            continue;
        };
        let mesh = parts.objects.get(leaf.object).and_then(|p| p.mesh.clone());
        let instance = match mesh {
            Some(mesh) => Instance { object, mesh },
            None => pending_instance(object),
        };
        let it = &m.instances[leaf.instance];
        let entity = world.spawn((
            Name(leaf.path.clone()),
            SourceLink::from(it.pos.clone()),
            instance,
            WorldFromObject(leaf.world_from_object),
            MaterialRef(material),
        ));
        if !leaf.photon.is_default() {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, leaf.photon);
        }
        if !leaf.rays.is_default() {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, leaf.rays);
        }
        if let Some(ObjectParts {
            face_materials: Some(faces),
            instance_material_wins: true,
            ..
        }) = parts.objects.get(leaf.object)
        {
            // The object's `material` is unset for these, so the leaf's is the instance's.
            if leaf.material.is_some() {
                let none = whole.entry(leaf.object).or_insert_with(|| {
                    crate::components::FaceMaterials(Arc::new(vec![None; faces.len()]))
                });
                // The entity was just spawned, so inserting cannot fail.
                let _ = world.insert_one(entity, none.clone());
            }
        }
        if let Some(Some(request)) = parts.bakes.get(leaf.instance) {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, request.clone());
        }
    }

    if parts.origin != glam::DVec3::ZERO {
        world.spawn((SceneOrigin(parts.origin),));
    }

    for (it, emitter) in m.lights.iter().zip(parts.lights) {
        let Some(emitter) = emitter else { continue };
        let entity = world.spawn((
            Name(it.desc.name.clone()),
            SourceLink::from(it.pos.clone()),
            emitter,
        ));
        let photons = super::photon_flags::light_photons(it.desc);
        if !photons.is_default() {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, photons);
        }
    }

    for (i, (it, cam)) in m.cameras.iter().zip(parts.cameras).enumerate() {
        let Some(camera) = cam.camera else { continue };
        let entity = world.spawn((
            Name(it.desc.name.clone()),
            SourceLink::from(it.pos.clone()),
            camera,
            OutputLinks(cam.output_links),
        ));
        if let Some(link) = cam.resolution_link {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, crate::components::ResolutionLink(link));
        }
        if let Some(imager) = cam.imager {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, imager);
        }
        if let Some(lenses) = cam.lenses {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, lenses);
        }
        // The entity was just spawned, so inserting cannot fail.
        match cam.atmosphere {
            Some(super::volume::Atmosphere::Fog(fog)) => {
                let _ = world.insert_one(entity, Atmosphere(fog));
            }
            Some(super::volume::Atmosphere::Fade(fade)) => {
                let _ = world.insert_one(entity, AtmosphereFade(fade));
            }
            None => {}
        }
        if Some(i) == parts.render_camera {
            // The entity was just spawned, so inserting cannot fail.
            let _ = world.insert_one(entity, RenderCamera);
        }
    }

    world
}
