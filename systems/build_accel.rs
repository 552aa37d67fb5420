//! `build_accel`: flattens every instance's triangles into world space and builds the BVH.
//!
//! **Reads:** `Instance`, `WorldFromObject`, `MaterialRef` entities; `Material` entities;
//! the `SceneOrigin` (copied into the geometry);
//! `settings.bvh_quality`.
//! **Writes:** `frame.geometry`.
//! **Runs when:** at least one instance has triangles and something consumes rays (a render
//! camera in a run that renders, or bake requests in a run that bakes).
//! **After this stage:** `frame.geometry` holds world triangles in instance order (each
//! instance contiguous), their BVH, and per-instance shading data.

use std::collections::HashMap;

use glam::Vec3;
use hecs::{Entity, World};

use super::prelude::*;
use crate::accel::Accel;
use crate::components::{
    BakeRequest, Instance, Material, MaterialRef, RenderCamera, SceneOrigin, WorldFromObject,
};
use crate::geometry::{InstanceGeometry, SceneGeometry};

/// Run condition: instances with triangles, and a render camera to trace for.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    let mut instances = 0usize;
    let mut triangles = 0usize;
    for inst in world.query::<&Instance>().iter() {
        instances += 1;
        triangles += inst.mesh.triangles.len();
    }
    if triangles == 0 {
        return Decision::skip("no instance has triangles");
    }
    let renders = frame.tasks.render && crate::schedule::any_with::<RenderCamera>(world);
    let bakes = frame.tasks.bake && crate::schedule::any_with::<BakeRequest>(world);
    if !renders && !bakes {
        return Decision::skip(if frame.tasks.render {
            "no render camera traces rays"
        } else {
            "nothing in this run traces rays"
        });
    }
    Decision::run(format!(
        "{instances} instance(s) with {triangles} triangles"
    ))
}

/// Builds `frame.geometry`.
pub fn run(world: &mut World, frame: &mut Frame) -> Result<Work, StageError> {
    // Gather in entity order so the triangle order, and thus every output byte, is fixed.
    let mut placed: Vec<(Entity, Instance, WorldFromObject, MaterialRef)> = world
        .query::<(Entity, &Instance, &WorldFromObject, &MaterialRef)>()
        .iter()
        .map(|(e, i, w, m)| (e, i.clone(), *w, *m))
        .collect();
    placed.sort_by_key(|(e, ..)| e.to_bits());

    let mut material_slot: HashMap<Entity, u32> = HashMap::new();
    let mut materials = Vec::new();
    let mut material_entities = Vec::new();
    let mut instances = Vec::with_capacity(placed.len());
    let total: usize = placed.iter().map(|(_, i, ..)| i.mesh.triangles.len()).sum();
    let mut triangles: Vec<[Vec3; 3]> = Vec::with_capacity(total);
    let mut triangle_instance = Vec::with_capacity(total);

    for (entity, instance, world_from_object, material_ref) in placed {
        let slot = match material_slot.get(&material_ref.0) {
            Some(&s) => s,
            None => {
                let material = world.get::<&Material>(material_ref.0).map_err(|_| {
                    StageError::Invalid(format!("instance {entity:?} has no material"))
                })?;
                let s = materials.len() as u32;
                materials.push((*material).clone());
                material_entities.push(material_ref.0);
                material_slot.insert(material_ref.0, s);
                s
            }
        };
        let xf = world_from_object.0;
        let first = triangles.len() as u32;
        let index = instances.len() as u32;
        let mesh = &instance.mesh;
        for tri in &mesh.triangles {
            triangles.push(tri.map(|i| xf.transform_point3(mesh.positions[i as usize])));
            triangle_instance.push(index);
        }
        instances.push(InstanceGeometry {
            entity,
            mesh: instance.mesh.clone(),
            world_from_object: xf,
            normal_from_object: glam::Mat3::from(xf.matrix3).inverse().transpose(),
            material: slot,
            first_triangle: first,
        });
    }
    let count = triangles.len() as u64;
    let accel = Accel::build(triangles, frame.settings.bvh_quality);
    frame.geometry = Some(SceneGeometry {
        accel,
        triangle_instance,
        instances,
        materials,
        material_entities,
        origin: world
            .query::<&SceneOrigin>()
            .iter()
            .next()
            .map_or(glam::DVec3::ZERO, |o| o.0),
    });
    Ok(Work {
        items: count,
        unit: "triangles",
    })
}
