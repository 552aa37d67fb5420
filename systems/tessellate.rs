//! `tessellate`: dices parametric surfaces and subdivision meshes into triangles and applies
//! true displacement, crack-free.
//!
//! **Reads:** object entities with `Surface`, `SubdivMesh`, or `Arc<TriMesh>` plus a
//! `Displacement` in `True` mode; their `Approximation` (default when absent),
//! `DerivativeRequest` and `Name`; for raster-space approximations the `RenderCamera` and the
//! `WorldFromObject` of every `Instance` of the object.
//! **Writes:** on each such object: an `Arc<TriMesh>` (also into every `Instance` of it),
//! `SurfaceDerivatives` when requested, `GeneratedFrom`; removes the consumed `Surface`,
//! `SubdivMesh` and true `Displacement`. Bump displacement is left in place for shading.
//! **Runs when:** any parametric surface, subdivision mesh or true displacement exists and
//! something traces rays into the geometry (`scene_view::geometry_discarded`: a render whose
//! image is read, or a bake; in a merge, only when it draws contours: `super::merge_skip`).
//! **After this stage:** every object is a triangle mesh with normals and uvs; shared patch
//! edges are diced identically (no cracks, bitwise); displaced meshes carry normals of the
//! displaced surface.

use std::sync::Arc;

use crate::features::{Feature, Features};
use glam::DAffine3;
use hecs::{Entity, World};
use rayon::prelude::*;

use super::prelude::*;
use crate::budget::estimate::{approximation_at, max_triangles, BYTES_PER_TRIANGLE};
use crate::budget::human;
use crate::components::{
    Approximation, DerivativeRequest, Displacement, DisplacementMode, GeneratedFrom, Instance,
    LengthSpace, Name, Procedural, SubdivMesh, Surface, Technique, TriMesh, WorldFromObject,
};
use crate::procedural::{expands_to_surface, install_mesh};
use crate::scene::syntax::Helps;
use crate::tessellation::{
    tessellate_mesh, tessellate_subdiv, tessellate_surface, GeometryError, Options, RasterView,
    Tessellation,
};

/// The help of a refusal past the memory budget in a RON (or glTF) scene.
const COARSEN_RON: &str = "coarsen the approximation (a larger `edge` or `distance`, a smaller `max_subdiv`), or raise the budget with --memory-limit BYTES";

/// Why an object cannot be tessellated. Rates past the memory budget are a located error at
/// the object's approximation (what to change), in the words of the load-time estimates.
fn refusal(world: &World, frame: &Frame, job: &Job, err: GeometryError) -> StageError {
    let GeometryError::TooManyTriangles { triangles, limit } = err else {
        return StageError::Geometry {
            object: job.name.clone(),
            message: err.to_string(),
        };
    };
    let Some(at) = approximation_at(world, job.entity) else {
        return StageError::Geometry {
            object: job.name.clone(),
            message: err.to_string(),
        };
    };
    let syntax = crate::scene::import::syntax_of(&at.file);
    StageError::Scene(vec![crate::scene::Diagnostic {
        file: at.file,
        line: at.line,
        column: at.column,
        message: format!(
            "object \"{}\": its approximation would make {triangles} triangles, about {}, more than the {limit} the memory budget of {} allows one object",
            job.name,
            human(triangles.saturating_mul(BYTES_PER_TRIANGLE)),
            frame.inputs.budget
        ),
        help: Some(
            syntax.help_each(Helps {
                ron: COARSEN_RON,
                mi: "coarsen the approximation (a larger `spatial` edge or `distance`, a smaller max subdivision), or raise the budget with --memory-limit BYTES",
                rib: "coarsen the dicing (a larger `ShadingRate`), or raise the budget with --memory-limit BYTES",
                gltf: COARSEN_RON,
            }),
        ),
    }])
}

/// What an object is tessellated from.
enum Input {
    Surface(Surface),
    Subdiv(SubdivMesh),
    Mesh(Arc<TriMesh>),
}

/// Counts (surfaces, subdivision meshes, true displacements on meshes, bump displacements).
/// Quadrics that `expand_geometry` has yet to turn into surfaces count as surfaces, so a
/// plan made before any stage runs decides as the run will.
fn census(world: &World, off: Features) -> (usize, usize, usize, usize) {
    let pending = if off.contains(Feature::Geometry) {
        0
    } else {
        world
            .query::<&Procedural>()
            .iter()
            .filter(|p| expands_to_surface(p))
            .count()
    };
    let surfaces = world.query::<&Surface>().iter().count() + pending;
    let subdivs = world.query::<&SubdivMesh>().iter().count();
    let (mut displaced, mut bump) = (0, 0);
    // A shape left unexpanded (geometry shaders disabled) has nothing to displace.
    let unexpanded = |procedural: bool, geometry: bool| {
        procedural && !geometry && off.contains(Feature::Geometry)
    };
    for (d, procedural, surface, subdiv, mesh) in world
        .query::<(
            &Displacement,
            Option<&Procedural>,
            Option<&Surface>,
            Option<&SubdivMesh>,
            Option<&Arc<TriMesh>>,
        )>()
        .iter()
    {
        let geometry = surface.is_some() || subdiv.is_some() || mesh.is_some();
        if unexpanded(procedural.is_some(), geometry) {
            continue;
        }
        match d.mode {
            DisplacementMode::True => displaced += 1,
            DisplacementMode::Bump => bump += 1,
        }
    }
    (surfaces, subdivs, displaced, bump)
}

/// Run condition: parametric surfaces, subdivision meshes or true displacement exist.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if let Some(why) = super::merge_skip(world, frame) {
        return Decision::skip(why);
    }
    let off = frame.inputs.settings.disabled;
    let (surfaces, subdivs, displaced, bump) = census(world, off);
    if off.contains(Feature::Displacement) && surfaces + subdivs == 0 && displaced + bump > 0 {
        return Decision::skip(format!(
            "displacement disabled ({} displacement shader(s) left out)",
            displaced + bump
        ));
    }
    if surfaces + subdivs + displaced == 0 {
        let unexpanded = world
            .query::<&Procedural>()
            .iter()
            .filter(|p| expands_to_surface(p))
            .count();
        if off.contains(Feature::Geometry) && unexpanded > 0 {
            return Decision::skip(format!(
                "geometry shaders disabled ({unexpanded} shape(s) not expanded into surfaces)"
            ));
        }
        return if bump > 0 {
            Decision::skip(format!(
                "no parametric surfaces or true displacement ({bump} bump displacement(s) are left to shading)"
            ))
        } else {
            Decision::skip("no parametric surfaces or displacement")
        };
    }
    if let Some(why) = crate::scene_view::geometry_discarded(world, &frame.inputs) {
        return Decision::skip(why);
    }
    if off.contains(Feature::Displacement) {
        return Decision::run(format!(
            "{surfaces} surface(s), {subdivs} subdivision mesh(es); displacement disabled"
        ));
    }
    Decision::run(format!(
        "{surfaces} surface(s), {subdivs} subdivision mesh(es), {displaced} true displacement(s)"
    ))
}

/// Widens a transform to f64.
fn to_f64(a: glam::Affine3A) -> DAffine3 {
    DAffine3 {
        matrix3: glam::DMat3::from_cols(
            a.matrix3.x_axis.as_dvec3(),
            a.matrix3.y_axis.as_dvec3(),
            a.matrix3.z_axis.as_dvec3(),
        ),
        translation: a.translation.as_dvec3(),
    }
}

/// The raster view of `object` (its instances seen from the render camera).
fn raster_view(world: &World, object: Entity) -> Option<RasterView> {
    let camera = crate::scene_view::render_view(world)?.camera;
    let camera_from_world = to_f64(camera.world_from_camera).inverse();
    let pixels_per_unit = camera.height as f64 * 0.5 / (camera.fov_y as f64 * 0.5).tan();
    let camera_from_object = world
        .query::<(&Instance, &WorldFromObject)>()
        .iter()
        .filter(|(i, _)| i.object == object)
        .map(|(_, w)| camera_from_world * to_f64(w.0))
        .collect();
    Some(RasterView {
        camera_from_object,
        pixels_per_unit,
    })
}

/// One object's job.
struct Job {
    entity: Entity,
    name: String,
    input: Input,
    approx: Approximation,
    displacement: Option<Displacement>,
    derivatives: bool,
    view: Option<RasterView>,
}

/// Tessellates every object that needs it.
pub fn run(world: &mut World, frame: &Frame) -> Result<Work, StageError> {
    let mut jobs = Vec::new();
    let displace = !frame
        .inputs
        .settings
        .disabled
        .contains(Feature::Displacement);
    for (e, surface, subdiv, mesh, disp, approx, deriv, name) in world
        .query::<(
            Entity,
            Option<&Surface>,
            Option<&SubdivMesh>,
            Option<&Arc<TriMesh>>,
            Option<&Displacement>,
            Option<&Approximation>,
            Option<&DerivativeRequest>,
            Option<&Name>,
        )>()
        .iter()
    {
        let displacement = disp
            .filter(|d| displace && d.mode == DisplacementMode::True)
            .cloned();
        let input = match (surface, subdiv, mesh) {
            (Some(s), ..) => Input::Surface(s.clone()),
            (None, Some(s), _) => Input::Subdiv(s.clone()),
            (None, None, Some(m)) if displacement.is_some() => Input::Mesh(m.clone()),
            _ => continue,
        };
        jobs.push(Job {
            entity: e,
            name: name.map_or_else(|| format!("{e:?}"), |n| n.0.clone()),
            input,
            approx: approx.copied().unwrap_or_default(),
            displacement,
            derivatives: deriv.is_some(),
            view: None,
        });
    }
    jobs.sort_by_key(|j| j.entity.to_bits());
    for job in &mut jobs {
        if matches!(
            job.approx.technique,
            Technique::Spatial {
                space: LengthSpace::Raster,
                ..
            }
        ) {
            job.view = raster_view(world, job.entity);
        }
    }

    // Objects one after another; each goes wide inside (edges, patches).
    let results: Vec<Result<Tessellation, GeometryError>> = jobs
        .iter()
        .map(|job| {
            let opts = Options {
                approximation: &job.approx,
                displacement: job.displacement.as_ref(),
                view: job.view.as_ref(),
                derivatives: job.derivatives,
                max_triangles: max_triangles(&frame.inputs.budget),
            };
            match &job.input {
                Input::Surface(s) => tessellate_surface(s, &opts),
                Input::Subdiv(s) => tessellate_subdiv(s, &opts),
                Input::Mesh(m) => tessellate_mesh(m, &opts),
            }
        })
        .collect::<Vec<_>>()
        .into_par_iter()
        .collect();

    let mut triangles = 0u64;
    for (job, result) in jobs.into_iter().zip(results) {
        let t = result.map_err(|err| refusal(world, frame, &job, err))?;
        triangles += t.mesh.triangles.len() as u64;
        let e = job.entity;
        let gone = |_| StageError::Internal(format!("entity {e:?} vanished"));
        let generator = match &job.input {
            Input::Surface(s) => s.kind(),
            Input::Subdiv(_) => "subdiv",
            Input::Mesh(_) => "displaced mesh",
        };
        match job.input {
            Input::Surface(_) => drop(world.remove_one::<Surface>(e)),
            Input::Subdiv(_) => drop(world.remove_one::<SubdivMesh>(e)),
            Input::Mesh(_) => {}
        }
        if job.displacement.is_some() {
            drop(world.remove_one::<Displacement>(e));
        }
        if !world.satisfies::<&GeneratedFrom>(e) {
            world
                .insert_one(
                    e,
                    GeneratedFrom {
                        source: e,
                        generator,
                    },
                )
                .map_err(gone)?;
        }
        if let Some(d) = t.derivatives {
            world.insert_one(e, d).map_err(gone)?;
        }
        install_mesh(world, e, Arc::new(t.mesh)).map_err(gone)?;
    }
    Ok(Work::new(triangles, "triangles"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::count_with;
    use crate::systems::tiny_scene::{load, run_until, scene};

    #[test]
    fn a_parametric_sphere_is_diced_into_its_instances() {
        let text = scene(
            "",
            "",
            r#"(name: "ball", mesh: Sphere(radius: 0.5), approximation: Parametric(u: 8, v: 4)),"#,
            &["ball"],
        );
        let (mut world, mut frame) = load(&text, false);
        // Planned before expansion, the quadric already counts.
        assert!(should_run(&world, &frame).run);
        run_until("tessellate", &mut world, &mut frame);
        assert!(should_run(&world, &frame).run);
        let work = run(&mut world, &frame).unwrap();
        assert!(work.items > 0);
        assert_eq!(count_with::<Surface>(&world), 0, "the surface is consumed");
        let on_instances: usize = world
            .query::<&Instance>()
            .iter()
            .map(|i| i.mesh.triangles.len())
            .sum();
        assert_eq!(
            on_instances as u64,
            2 + work.items,
            "the square and the diced ball"
        );
        assert!(!should_run(&world, &frame).run, "nothing left to dice");
    }

    /// True displacement of an object whose orientation is reversed moves the surface along
    /// the reversed normal: a constant 0.25 shrinks a sphere of radius 0.5 to 0.25 instead of
    /// growing it to 0.75.
    #[test]
    fn true_displacement_follows_a_reversed_orientation() {
        let radius = |reverse: bool| {
            let object = format!(
                r#"(name: "ball", mesh: Sphere(radius: 0.5), approximation: Parametric(u: 8, v: 4),
                    displacement: (shader: Constant(0.25), mode: True),
                    reverse_orientation: {reverse}),"#
            );
            let (mut world, mut frame) = load(&scene("", "", &object, &["ball"]), false);
            run_until("tessellate", &mut world, &mut frame);
            run(&mut world, &frame).unwrap();
            let mut radii: Vec<f32> = Vec::new();
            for (mesh, name) in world.query::<(&Arc<TriMesh>, &Name)>().iter() {
                if name.0 == "ball" {
                    radii.extend(mesh.positions.iter().map(|p| p.length()));
                }
            }
            assert!(!radii.is_empty());
            let (lo, hi) = radii
                .iter()
                .fold((f32::MAX, f32::MIN), |(a, b), &r| (a.min(r), b.max(r)));
            assert!(hi - lo < 1e-5, "{lo}..{hi}");
            lo
        };
        assert!((radius(false) - 0.75).abs() < 1e-5);
        assert!((radius(true) - 0.25).abs() < 1e-5);
    }

    #[test]
    fn skipped_without_surfaces_or_displacement() {
        let (world, frame) = load(&scene("", "", "", &[]), false);
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("no parametric surfaces or displacement")
        );
    }
}
