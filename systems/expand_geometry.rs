//! `expand_geometry`: runs the geometry shaders — quadrics, stairs, grids and scatters.
//!
//! **Reads:** `Procedural` and `Scatter` object entities; `Arc<TriMesh>` of scatter surfaces
//! and prototypes; leaf `Instance`s of scatter objects with their `WorldFromObject`,
//! `MaterialRef` and `Name`.
//! **Writes:** on each `Procedural` object: removes it, inserts a `Surface` (quadrics) or an
//! `Arc<TriMesh>` (stairs, grid; also into every `Instance` of the object) and a
//! `GeneratedFrom`. Each scatter leaf instance is despawned and replaced by `count` prototype
//! instances (`Instance`, `WorldFromObject`, `MaterialRef`, `Name` = `leaf/i`,
//! `GeneratedFrom`); the `Scatter` component is removed.
//! **Runs when:** any entity carries `Procedural` or `Scatter` and something traces rays into
//! the geometry (`scene_view::geometry_discarded`; in a merge, only when it draws contours:
//! `super::merge_skip`).
//! **After this stage:** no `Procedural` or `Scatter` is left; curved shapes wait as `Surface`
//! for `tessellate`, flat ones are meshes.

use std::sync::Arc;

use hecs::{Entity, World};

use super::prelude::*;
use crate::components::{
    GeneratedFrom, Instance, MaterialRef, Name, Procedural, Scatter, TriMesh, WorldFromObject,
};
use crate::features::Feature;
use crate::procedural::{expand, install_mesh, scatter, Expanded};
use crate::schedule::count_with;

/// Run condition: procedural geometry components exist.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if let Some(why) = super::merge_skip(world, frame) {
        return Decision::skip(why);
    }
    let shaders = count_with::<Procedural>(world);
    let scatters = count_with::<Scatter>(world);
    if shaders + scatters == 0 {
        return Decision::skip("no procedural geometry");
    }
    if frame.inputs.settings.disabled.contains(Feature::Geometry) {
        return Decision::skip(format!(
            "geometry shaders disabled ({shaders} geometry shader(s), {scatters} scatter(s) left empty)"
        ));
    }
    if let Some(why) = crate::scene_view::geometry_discarded(world, &frame.inputs) {
        return Decision::skip(why);
    }
    Decision::run(format!(
        "{shaders} geometry shader(s), {scatters} scatter(s)"
    ))
}

/// The name of an entity for messages.
fn name_of(world: &World, e: Entity) -> String {
    world
        .get::<&Name>(e)
        .map(|n| n.0.clone())
        .unwrap_or_else(|_| format!("{e:?}"))
}

/// Expands every geometry shader, then every scatter.
pub fn run(world: &mut World, _frame: &Frame) -> Result<Work, StageError> {
    let mut triangles = 0u64;
    // Quadrics become surfaces (diced later by `tessellate`), the rest triangles.
    let mut surfaces = 0u64;
    let mut shaders: Vec<(Entity, Procedural)> = world
        .query::<(Entity, &Procedural)>()
        .iter()
        .map(|(e, p)| (e, *p))
        .collect();
    shaders.sort_by_key(|(e, _)| e.to_bits());
    for (e, p) in shaders {
        let out = expand(&p).map_err(|err| StageError::Geometry {
            object: name_of(world, e),
            message: format!("{}: {err}", p.kind()),
        })?;
        let gone = |_| StageError::Internal(format!("entity {e:?} vanished"));
        world
            .remove_one::<Procedural>(e)
            .map_err(|_| StageError::Internal(format!("entity {e:?} vanished")))?;
        world
            .insert_one(
                e,
                GeneratedFrom {
                    source: e,
                    generator: p.kind(),
                },
            )
            .map_err(gone)?;
        match out {
            Expanded::Surface(s) => {
                surfaces += 1;
                world.insert_one(e, s).map_err(gone)?
            }
            Expanded::Mesh(m) => {
                triangles += m.triangles.len() as u64;
                install_mesh(world, e, Arc::new(m)).map_err(gone)?;
            }
        }
    }

    let mut scatters: Vec<(Entity, Scatter)> = world
        .query::<(Entity, &Scatter)>()
        .iter()
        .map(|(e, s)| (e, *s))
        .collect();
    scatters.sort_by_key(|(e, _)| e.to_bits());
    for (e, s) in scatters {
        let name = name_of(world, e);
        let surface = world
            .get::<&Arc<TriMesh>>(s.surface)
            .map(|m| (*m).clone())
            .map_err(|_| StageError::Geometry {
                object: name.clone(),
                message: format!(
                    "scatter surface \"{}\" has no mesh (scatter over loaded meshes, grids or stairs)",
                    name_of(world, s.surface)
                ),
            })?;
        let prototype = world
            .get::<&Arc<TriMesh>>(s.prototype)
            .map(|m| (*m).clone())
            .unwrap_or_else(|_| Arc::new(TriMesh::default()));
        // Located at the scatter object, like the loader's errors.
        let xfs =
            scatter::placements(&s, &surface).map_err(|err| match world
                .get::<&crate::components::SourceLink>(
                e,
            ) {
                Ok(at) => StageError::Scene(vec![crate::scene::Diagnostic {
                    file: at.file.clone(),
                    line: at.line,
                    column: at.column,
                    message: format!("object \"{name}\": scatter: {err}"),
                    help: matches!(err, crate::tessellation::GeometryError::MissingData { .. })
                        .then(|| {
                            format!(
                            "scatter over a surface whose triangles have area (\"{}\" has none)",
                            name_of(world, s.surface)
                        )
                        }),
                }]),
                Err(_) => StageError::Geometry {
                    object: name.clone(),
                    message: format!("scatter: {err}"),
                },
            })?;
        let mut leaves: Vec<(Entity, WorldFromObject, MaterialRef, String)> = world
            .query::<(
                Entity,
                &Instance,
                &WorldFromObject,
                &MaterialRef,
                Option<&Name>,
            )>()
            .iter()
            .filter(|(_, i, ..)| i.object == e)
            .map(|(l, _, w, m, n)| (l, *w, *m, n.map_or_else(|| name.clone(), |n| n.0.clone())))
            .collect();
        leaves.sort_by_key(|(l, ..)| l.to_bits());
        for (leaf, xf, material, leaf_name) in leaves {
            world
                .despawn(leaf)
                .map_err(|_| StageError::Internal(format!("instance {leaf:?} vanished")))?;
            let _spawned: Vec<Entity> = world
                .spawn_batch(xfs.iter().enumerate().map(|(i, local)| {
                    (
                        Instance {
                            object: s.prototype,
                            mesh: prototype.clone(),
                        },
                        WorldFromObject(xf.0 * *local),
                        material,
                        Name(format!("{leaf_name}/{i}")),
                        GeneratedFrom {
                            source: e,
                            generator: "scatter",
                        },
                    )
                }))
                .collect();
            triangles += xfs.len() as u64 * prototype.triangles.len() as u64;
        }
        world
            .remove_one::<Scatter>(e)
            .map_err(|_| StageError::Internal(format!("entity {e:?} vanished")))?;
    }
    Ok(made(triangles, surfaces))
}

/// What the stage made, in one unit: the triangles it generated, or, when it made only
/// surfaces (quadrics, whose triangles `tessellate` makes and counts), the surfaces.
fn made(triangles: u64, surfaces: u64) -> Work {
    if triangles == 0 && surfaces > 0 {
        Work::new(surfaces, "surfaces")
    } else {
        Work::new(triangles, "triangles")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::Surface;
    use crate::systems::tiny_scene::{load, scene};

    #[test]
    fn a_sphere_becomes_a_surface_and_nothing_procedural_is_left() {
        let text = scene(
            "",
            "",
            r#"(name: "ball", mesh: Sphere(radius: 0.5)),"#,
            &["ball"],
        );
        let (mut world, frame) = load(&text, false);
        assert!(should_run(&world, &frame).run);
        let work = run(&mut world, &frame).unwrap();
        // A quadric waits for tessellation: one surface made, no triangles yet.
        assert_eq!((work.items, work.unit), (1, "surfaces"));
        assert_eq!(count_with::<Procedural>(&world), 0);
        assert_eq!(count_with::<Surface>(&world), 1);
        assert!(!should_run(&world, &frame).run);
    }

    #[test]
    fn a_grid_becomes_a_mesh_on_its_instances() {
        let text = scene(
            "",
            "",
            r#"(name: "floor", mesh: Grid(size_x: 2, size_y: 2, nx: 3, ny: 2)),"#,
            &["floor"],
        );
        let (mut world, frame) = load(&text, false);
        let work = run(&mut world, &frame).unwrap();
        assert_eq!(work.items, 3 * 2 * 2, "two triangles per grid cell");
        let on_instances: usize = world
            .query::<&Instance>()
            .iter()
            .map(|i| i.mesh.triangles.len())
            .sum();
        assert_eq!(on_instances, 2 + 12, "the square and the grid");
    }

    #[test]
    fn skipped_without_procedural_geometry() {
        let (world, frame) = load(&scene("", "", "", &[]), false);
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("no procedural geometry")
        );
    }
}
