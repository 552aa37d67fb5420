//! `build_accel`: flattens every instance's triangles into world space and builds the BVH.
//!
//! **Reads:** `Instance`, `WorldFromObject`, `MaterialRef` entities; `Material` entities;
//! the objects' `Displacement` in `Bump` mode (kept for shading);
//! the `SceneOrigin` (copied into the geometry); instances' `RayFlags` (per-triangle ray
//! masks in the BVH);
//! `settings.face` (with `Cull`, the triangles of one-sided materials are marked
//! `FRONT_ONLY` in those masks: no ray sees their back faces);
//! `settings.bvh_quality`; objects' `FaceMaterials` (per-triangle material slots; an
//! instance's own `FaceMaterials` wins over its object's); objects' `VertexColours`,
//! `VertexTangents` and `ReverseOrientation`.
//! **Refuses:** placed triangles beyond the supported coordinate range
//! (`crate::guard::extent`), located at their object.
//! **Stops:** when the run is interrupted, even inside obvhs's build (waited for through
//! `crate::guard::cancellable`).
//! **Writes:** `outputs.geometry` (returned to the runner).
//! **Runs when:** at least one instance has triangles and something consumes rays (a render
//! camera in a run that renders, or bake requests in a run that bakes), not in a farm part
//! that owns nothing (`crate::scene_view::geometry_unused`: a render part without pixels or
//! samples, a bake part past the last texel tile of fixed-size texture requests,
//! `crate::scene_view::idle_bake_part`); in a merge, only when it draws contours (`super::merge_skip`). A bake merge (`inputs.merged_bake`) places the
//! triangles without building the BVH ([`Accel::without_hierarchy`]): it reads them and
//! traces no ray.
//! **After this stage:** `outputs.geometry` holds world triangles in instance order (each
//! instance contiguous; a mirrored instance's with two corners swapped, so that they keep
//! their object-space front, and so are those of an unmirrored instance of an object whose
//! orientation is reversed), their BVH, and per-instance shading data.

use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec3;
use hecs::{Entity, World};

use super::prelude::*;
use crate::accel::Accel;
use crate::components::{
    Displacement, DisplacementMode, FaceMaterials, Instance, Material, MaterialRef, ObjectLabel,
    Procedural, RayFlags, ReverseOrientation, Scatter, SubdivMesh, Surface, VertexColours,
    VertexTangents, WorldFromObject, ALL_RAYS, FRONT_ONLY,
};
use crate::features::Feature;
use crate::geometry::{InstanceGeometry, SceneGeometry};
use crate::guard::extent::{located, out_of_range, reach};
use crate::schedule::any_with;
use crate::settings::Face;

/// Run condition: instances with triangles, and a render camera to trace for.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if let Some(why) = super::merge_skip(world, frame) {
        return Decision::skip(why);
    }
    let mut instances = 0usize;
    let mut triangles = 0usize;
    for inst in world.query::<&Instance>().iter() {
        instances += 1;
        triangles += inst.mesh.triangles.len();
    }
    // Before the geometry stages run (a plan), generated geometry is still components.
    let generates = !frame.inputs.settings.disabled.contains(Feature::Geometry);
    let pending = generates && (any_with::<Procedural>(world) || any_with::<Scatter>(world))
        || any_with::<Surface>(world)
        || any_with::<SubdivMesh>(world);
    if triangles == 0 && !pending {
        return Decision::skip("no instance has triangles");
    }
    if let Some(why) = crate::scene_view::geometry_unused(world, &frame.inputs) {
        return Decision::skip(why);
    }
    // True displacement re-dices its meshes in `tessellate`: their count is not final yet.
    let displaces = !frame
        .inputs
        .settings
        .disabled
        .contains(Feature::Displacement)
        && world
            .query::<&Displacement>()
            .iter()
            .any(|d| d.mode == DisplacementMode::True);
    let counted = format!("{instances} instance(s) with {triangles} triangles");
    let mut why = match (pending, displaces) {
        (true, true) => format!("{counted} so far (before displacement), more to be generated"),
        (true, false) => format!("{counted} so far, more to be generated"),
        (false, true) => {
            format!("{counted} before displacement, which dices the displaced meshes again")
        }
        (false, false) => counted,
    };
    if frame.inputs.merged_bake.is_some() {
        why.push_str("; placed without a BVH: a bake merge traces no rays");
    }
    Decision::run(why)
}

/// Builds the scene geometry.
pub fn run(world: &World, frame: &Frame) -> Result<Work, StageError> {
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
    let mut too_far: Vec<(Entity, f32)> = Vec::new();
    let mut ray_masks: Vec<u8> = Vec::new();
    let cull = frame.inputs.settings.face == Face::Cull;
    let displace = !frame
        .inputs
        .settings
        .disabled
        .contains(crate::features::Feature::Displacement);

    for (entity, instance, world_from_object, material_ref) in placed {
        if frame.cancelled() {
            return Err(StageError::Interrupted);
        }
        let mut slot_of = |material: Entity| -> Result<u32, StageError> {
            if let Some(&s) = material_slot.get(&material) {
                return Ok(s);
            }
            let m = world.get::<&Material>(material).map_err(|_| {
                StageError::Internal(format!("instance {entity:?} has no material"))
            })?;
            let s = materials.len() as u32;
            materials.push((*m).clone());
            material_entities.push(material);
            material_slot.insert(material, s);
            Ok(s)
        };
        let slot = slot_of(material_ref.0)?;
        let own = world.get::<&FaceMaterials>(entity);
        let face_materials = match own.or_else(|_| world.get::<&FaceMaterials>(instance.object)) {
            Ok(faces) if faces.0.len() == instance.mesh.triangles.len() => Some(Arc::new(
                faces
                    .0
                    .iter()
                    .map(|m| m.map_or(Ok(slot), &mut slot_of))
                    .collect::<Result<Vec<u32>, _>>()?,
            )),
            Ok(_) => {
                return Err(StageError::Internal(format!(
                    "the polygon materials of instance {entity:?} do not match its triangles"
                )))
            }
            Err(_) => None,
        };
        let xf = world_from_object.0;
        let first = triangles.len() as u32;
        let index = instances.len() as u32;
        let mesh = &instance.mesh;
        // A mirroring transform reverses the winding: swap two corners back, so the world
        // triangle's geometric normal is on its object-space front (`geometry.rs`); an object
        // whose orientation is reversed swaps them once more.
        let mirrored = InstanceGeometry::mirrors(&xf);
        let reversed = world.satisfies::<&ReverseOrientation>(instance.object);
        for tri in &mesh.triangles {
            let corners = tri.map(|i| xf.transform_point3(mesh.positions[i as usize]));
            triangles.push(InstanceGeometry::in_world_order(
                mirrored != reversed,
                corners,
            ));
            triangle_instance.push(index);
        }
        let mask = world
            .get::<&RayFlags>(entity)
            .map_or(ALL_RAYS, |f| f.mask());
        if cull {
            let front_only = |slot: u32| {
                let one_sided = !materials[slot as usize].shades_back();
                mask | if one_sided { FRONT_ONLY } else { 0 }
            };
            match &face_materials {
                Some(slots) => ray_masks.extend(slots.iter().map(|&s| front_only(s))),
                None => ray_masks.resize(triangles.len(), front_only(slot)),
            }
        } else {
            ray_masks.resize(triangles.len(), mask);
        }
        let r = reach(triangles[first as usize..].iter().flatten().copied());
        if out_of_range(r) && !too_far.iter().any(|(o, _)| *o == instance.object) {
            too_far.push((instance.object, r));
        }
        instances.push(InstanceGeometry {
            entity,
            mesh: instance.mesh.clone(),
            world_from_object: xf,
            // Inverted in `Mat3` as before (the values every earlier image was made with);
            // only the storage is in SIMD columns.
            normal_from_object: glam::Mat3A::from(
                glam::Mat3::from(xf.matrix3).inverse().transpose(),
            ),
            material: slot,
            face_materials,
            first_triangle: first,
            bump: world
                .get::<&Displacement>(instance.object)
                .ok()
                .filter(|d| displace && d.mode == DisplacementMode::Bump)
                .map(|d| Arc::new((*d).clone())),
            colours: world
                .get::<&VertexColours>(instance.object)
                .ok()
                .map(|c| c.0.clone())
                .filter(|c| c.len() == instance.mesh.positions.len()),
            tangents: world
                .get::<&VertexTangents>(instance.object)
                .ok()
                .map(|t| t.0.clone())
                .filter(|t| t.len() == instance.mesh.positions.len()),
            mirrored,
            reversed,
            label: world.get::<&ObjectLabel>(instance.object).ok().map(|l| l.0),
        });
    }
    // Generated geometry is only known now: refuse what the f32 BVH and triangle test cannot
    // handle (located at the object) instead of letting obvhs index out of bounds.
    if !too_far.is_empty() {
        return Err(StageError::Scene(
            too_far
                .into_iter()
                .map(|(object, r)| located(world, object, r))
                .collect(),
        ));
    }
    let count = triangles.len() as u64;
    let mut accel = if frame.inputs.merged_bake.is_some() {
        // A bake merge reads the placed triangles (texel coverage, seams, mesh lights) and
        // takes every texel from the parts: it traces no ray, so no hierarchy is built.
        Accel::without_hierarchy(triangles)
    } else {
        // obvhs cannot poll the cancel flag: build on a thread of its own and stop waiting
        // when the run is interrupted.
        let quality = frame.inputs.settings.bvh_quality;
        let built = crate::guard::cancellable::until_cancelled(&frame.inputs.cancel, move || {
            Accel::build(triangles, quality)
        })
        .map_err(|e| StageError::Internal(format!("cannot start the BVH build: {e}")))?;
        let Some(accel) = built else {
            return Err(StageError::Interrupted);
        };
        accel
    };
    accel.set_ray_masks(ray_masks);
    let geometry = SceneGeometry {
        accel,
        triangle_instance,
        instances,
        materials,
        material_entities,
        origin: crate::scene_view::scene_origin(world),
    };
    Ok(Work::new(count, "triangles").with_output(StageOutput::Geometry(geometry)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Tasks;
    use crate::systems::tiny_scene::{load, scene};

    #[test]
    fn the_square_becomes_two_world_triangles() {
        let (world, frame) = load(&scene("", "", "", &[]), false);
        let d = should_run(&world, &frame);
        assert_eq!(d, Decision::run("1 instance(s) with 2 triangles"));
        let work = run(&world, &frame).unwrap();
        assert_eq!(work.items, 2);
        let Some(StageOutput::Geometry(g)) = work.output else {
            panic!("build_accel returns the geometry");
        };
        assert_eq!(g.instances.len(), 1);
        assert_eq!(g.triangle_instance, vec![0, 0]);
    }

    /// A plan's count of a truly displaced mesh is its count before `tessellate` dices it.
    #[test]
    fn a_displaced_mesh_is_counted_before_displacement() {
        let bumpy = r#"(name: "bumpy", mesh: Inline(vertices: [(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],
            polygons: [[0, 1, 2, 3]]), material: "grey",
            displacement: (shader: Sine(amplitude: 0.2, factor: 2), bound: 0.2),
            approximation: Parametric(u: 8, v: 8)),"#;
        let (world, mut frame) = load(&scene("", "", bumpy, &["bumpy_inst"]), false);
        assert_eq!(
            should_run(&world, &frame),
            Decision::run(
                "2 instance(s) with 4 triangles before displacement, which dices the displaced meshes again"
            )
        );
        frame.inputs.settings.disabled.insert(Feature::Displacement);
        assert_eq!(
            should_run(&world, &frame),
            Decision::run("2 instance(s) with 4 triangles")
        );
    }

    #[test]
    fn skipped_when_nothing_traces_rays() {
        let (world, mut frame) = load(&scene("", "", "", &[]), false);
        frame.inputs.tasks = Tasks {
            render: false,
            bake: true,
        };
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("nothing in this run traces rays")
        );
    }
}
