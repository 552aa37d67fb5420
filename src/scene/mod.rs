//! Scene loading: scene files → validated descriptions → an ECS world.
//!
//! The pipeline, one module per step:
//! 1. [`include`] reads the root file and, depth-first, its includes, each through the
//!    reader seam ([`import`]): the file's extension picks its reader (`.ron` today), which
//!    produces the format-neutral description ([`desc`]) and a map of where every value was
//!    written. A reader's errors (syntax, types), an unknown format or an unreadable
//!    include stop loading here.
//! 2. [`validate`] merges the files and checks every value; [`names`] resolves references;
//!    [`dag`] builds instance transforms, rejects cycles and flattens the instance DAG from
//!    the render root; [`mesh_load`] builds the meshes of reachable objects; [`geometry`]
//!    checks generated meshes (geometry shaders, free-form surfaces, subdivision meshes,
//!    scatters), approximations and displacements with the geometry code's own rules.
//!    All errors of this step are collected and reported together, ordered by file (load
//!    order) and position, each located through its file's source map, so they read the
//!    same whatever the format.
//!    [`rebase`] then moves everything into render space (world space less the scene
//!    origin, in f64) before cameras and lights are rounded to f32.
//! 3. [`spawn`] creates the entities.
//!
//! The format is documented in `docs/scene-format.md`.

pub(crate) mod bake;
pub(crate) mod camera_rotation;
pub(crate) mod checker;
pub(crate) mod contours;
pub(crate) mod dag;
pub mod desc;
pub mod desc_camera;
pub mod desc_contour;
pub mod desc_diagnostic;
pub mod desc_environment;
pub mod desc_geometry;
pub mod desc_material_shaders;
pub mod desc_photon_depth;
pub mod desc_values;
pub(crate) mod diagnostics;
pub(crate) mod environment;
pub(crate) mod geometry;
pub(crate) mod imager;
pub mod import;
pub(crate) mod include;
pub mod inputs;
pub(crate) mod lens;
pub(crate) mod light_lists;
pub(crate) mod lights;
pub(crate) mod loaded_images;
pub(crate) mod material_shaders;
pub mod mesh_files;
pub(crate) mod mesh_load;
pub(crate) mod message;
pub(crate) mod missing_file;
pub(crate) mod names;
pub(crate) mod nodes;
pub mod nodes_desc;
pub(crate) mod obj_materials;
pub(crate) mod photon_flags;
mod ray_flags;
pub(crate) mod rebase;
pub(crate) mod samples;
pub(crate) mod shaders;
pub(crate) mod spawn;
pub(crate) mod suggest;
pub mod syntax;
pub(crate) mod unique_keys;
pub(crate) mod unrendered;
pub(crate) mod validate;
pub(crate) mod volume;
pub mod world_checks;

use std::path::Path;
use std::sync::Arc;

use glam::{DAffine3, DVec3};

pub use diagnostics::{Diagnostic, SceneErrors, Severity};
pub use environment::read_exr as read_lat_long;

use crate::memory_budget::Budget;
use crate::settings::RenderSettings;
use checker::Checker;
use desc::MeshDesc;
use diagnostics::Sources;
use include::LoadedFiles;
use mesh_load::BuiltMesh;
use spawn::{CameraParts, MaterialParts, ObjectParts};
use validate::Merged;

/// A loaded, validated scene.
pub struct LoadedScene {
    /// The world with every scene entity spawned.
    pub world: hecs::World,
    /// Settings from the scene's `options`.
    pub settings: RenderSettings,
    /// Located warnings from the readers and validation, each a complete text as printed:
    /// `file:line:col: warning: …` (plus a `help:` line), in file and position order.
    pub located_warnings: Vec<String>,
    /// FNV-1a over the bytes of the scene file, every include, RIB archive and `.mi` include,
    /// in load order (part of the farm's scene content hash, `crate::farm::scene_hash`).
    pub source_hash: u64,
}

/// Loads and validates the scene at `path`, with no memory budget.
pub fn load_scene(path: &Path) -> Result<LoadedScene, SceneErrors> {
    load_scene_within(path, &Budget::unlimited())
}

/// Loads and validates the scene at `path`; image textures are counted against `budget`
/// from their headers before they are decoded (one that takes the textures past it is a
/// located error at its `file`).
pub fn load_scene_within(path: &Path, budget: &Budget) -> Result<LoadedScene, SceneErrors> {
    load(path, None, import::FORMATS, budget).and_then(world_checks::check_loaded)
}

/// Loads a scene from `text` as if it were the file at `path` (includes and OBJ files are
/// still read from disk, relative to `path`), with no memory budget.
pub fn load_scene_str(text: &str, path: &Path) -> Result<LoadedScene, SceneErrors> {
    load(path, Some(text), import::FORMATS, &Budget::unlimited())
        .and_then(world_checks::check_loaded)
}

/// Parses OBJ text into a checked triangle mesh (degenerate triangles dropped, a
/// non-finite position an error), as the loader does for `Obj(file: …)` meshes. For tools and the fuzz target;
/// the error is the message the loader would report.
pub fn parse_obj_bytes(bytes: &[u8]) -> Result<crate::components::TriMesh, String> {
    parse_mesh_bytes(mesh_files::MeshFormat::Obj, bytes)
}

/// Parses a mesh file of `format` from its bytes into a checked triangle mesh, as the loader
/// does (degenerate triangles dropped, a non-finite position an error, positions in the
/// file's object space). For tools and the fuzz targets; the error says where and what.
pub fn parse_mesh_bytes(
    format: mesh_files::MeshFormat,
    bytes: &[u8],
) -> Result<crate::components::TriMesh, String> {
    format
        .parse(bytes)
        .map(|data| {
            let mut built = mesh_load::from_data(data);
            built.uncentre();
            built.mesh
        })
        .map_err(|e| e.to_string())
}

/// Loads the scene at `path` (or `text` as that file), reading each file with the format
/// its extension names in `formats` ([`import::FORMATS`] outside tests).
fn load(
    path: &Path,
    text: Option<&str>,
    formats: &[import::Format],
    budget: &Budget,
) -> Result<LoadedScene, SceneErrors> {
    let LoadedFiles {
        mut sources,
        mut scenes,
        content_hash,
        ..
    } = include::load_files(path, text, formats);
    if sources.has_errors() {
        return Err(sources.refuse());
    }
    obj_materials::expand(&mut sources, &mut scenes, &mut Vec::new());
    if sources.has_errors() {
        return Err(sources.refuse());
    }
    sources.images = loaded_images::LoadedImages::new(budget.clone());
    let src = &mut sources;
    let merged = validate::merge(src, &scenes);
    let settings = validate::settings(src, merged.options.as_ref());
    // Each pass over the elements keeps its place: errors at the same position are
    // reported in discovery order.
    let mut cameras: Vec<CameraParts> = merged
        .cameras
        .iter()
        .map(|c| CameraParts {
            imager: imager::imager(src, c),
            ..CameraParts::default()
        })
        .collect();
    for (parts, c) in cameras.iter_mut().zip(&merged.cameras) {
        parts.lenses = lens::lenses(src, c);
    }
    for (parts, c) in cameras.iter_mut().zip(&merged.cameras) {
        parts.atmosphere = volume::atmosphere(src, c);
    }
    let interiors: Vec<_> = merged
        .materials
        .iter()
        .map(|m| volume::interior(src, m))
        .collect();
    let environment = environment::environment(src, &scenes);
    let mut materials: Vec<_> = merged
        .materials
        .iter()
        .map(|mat| validate::material(src, mat))
        .collect();
    let mut phenomena = nodes::check_phenomena(src, &merged, budget);
    nodes::attach(src, &merged, &mut phenomena, &mut materials);
    let contour_shaders: Vec<_> = merged
        .materials
        .iter()
        .map(|m| contours::contour(src, m))
        .collect();
    let contrast = contours::contrast(src, merged.options.as_ref());
    contours::check_contrast_off(src, merged.options.as_ref(), &merged.materials, &contrast);
    let contours_shown = contours::check_pairing(src, &merged.cameras, &merged.materials);
    light_lists::attach(src, &merged, &mut materials);
    let materials: Vec<MaterialParts> = materials
        .into_iter()
        .zip(interiors)
        .zip(contour_shaders)
        .map(|((material, interior), contour)| MaterialParts {
            material,
            interior,
            contour,
        })
        .collect();
    photon_flags::check(src, &merged);
    let resolved = names::resolve(src, &merged);
    unrendered::warn(src, &merged, &resolved);
    let scatters = geometry::scatter::resolve(src, &merged);
    let object_geometry = geometry::check_objects(src, &merged, &scatters);
    let locals = dag::instance_transforms(src, &merged);
    let acyclic = dag::check_cycles(src, &merged, &resolved);
    let mut reachable = dag::reachable_objects(&merged, &resolved);
    geometry::scatter::extend_reachable(&mut reachable, &scatters);
    let mut built = build_meshes(src, &merged, &reachable);
    // Scatters place copies in their surface's and prototype's object space: keep it.
    for &(prototype, surface) in scatters.iter().flatten() {
        for o in [prototype, surface] {
            if let Some(Some(b)) = built.get_mut(o) {
                b.uncentre();
            }
        }
    }
    let offsets: Vec<DVec3> = built
        .iter()
        .map(|b| b.as_ref().map_or(DVec3::ZERO, |b| b.offset))
        .collect();
    let mut leaves = if acyclic {
        let locals: Vec<DAffine3> = locals
            .iter()
            .map(|l| l.unwrap_or(DAffine3::IDENTITY))
            .collect();
        dag::flatten(src, &merged, &resolved, &locals, &offsets)
    } else {
        Vec::new()
    };
    // Render space (hard case H5): subtract the scene origin in f64 before rounding.
    let object_bounds: Vec<_> = built
        .iter()
        .map(|b| b.as_ref().and_then(|b| rebase::mesh_bounds(&b.mesh)))
        .collect();
    let mut origin = rebase::scene_origin(&leaves, &object_bounds);
    if !rebase::rebase_leaves(&mut leaves, origin) {
        origin = DVec3::ZERO;
    }
    for (parts, c) in cameras.iter_mut().zip(&merged.cameras) {
        let desc = rebase::camera(c.desc, origin);
        parts.camera = validate::camera(src, &rebased(c, &desc));
        parts.output_links = (0..c.desc.outputs.len())
            .map(|k| {
                src.pos(c.file, &c.at(&format!(".outputs[{k}].file")))
                    .into()
            })
            .collect();
        parts.resolution_link = Some(src.pos(c.file, &c.at(".resolution[0]")).into());
    }
    let lights: Vec<_> = merged
        .lights
        .iter()
        .map(|l| {
            let desc = rebase::light(l.desc, origin);
            validate::light(src, &rebased(l, &desc))
        })
        .collect();
    geometry::scatter::copy_materials(&mut leaves, &scatters, &resolved.object_material);
    let used = used_materials(merged.materials.len(), &leaves, &resolved.polygon_materials);
    contours::warn_unshown_shaders(src, &merged.materials, contours_shown, &used);
    geometry::scatter::check_bakes(src, &merged, &leaves);
    // `None`: the mesh did not load (its error is reported), so its UVs are not checked.
    let has_uvs: Vec<Option<[bool; 2]>> = merged
        .objects
        .iter()
        .zip(&built)
        .map(|(it, b)| {
            let generated = !matches!(it.desc.mesh, MeshDesc::Inline { .. })
                && mesh_files::mesh_file(&it.desc.mesh).is_none();
            (b.is_some() || generated).then(|| {
                [
                    b.as_ref().is_some_and(|b| b.mesh.uvs.is_some())
                        || geometry::generated_has_uvs(&it.desc.mesh),
                    b.as_ref().is_some_and(|b| b.uvs1.is_some()),
                ]
            })
        })
        .collect();
    // What the mesh loader dropped, located at the object's mesh.
    for (it, b) in merged.objects.iter().zip(&built) {
        let Some(b) = b else { continue };
        let name = &it.desc.name;
        let mut warn_with = |message: String, help: Option<String>| {
            let pos = src.pos(it.file, &it.at(".mesh"));
            src.push_warning(it.file, Diagnostic::at(pos, message, help));
        };
        let mut warn = |message: String| warn_with(message, None);
        if b.dropped > 0 {
            let s = if b.dropped == 1 { "" } else { "s" };
            warn(format!(
                "mesh \"{name}\": dropped {} degenerate triangle{s}",
                b.dropped
            ));
        }
        if b.dropped_normals {
            warn(format!(
                "mesh \"{name}\": ignored its normals (one is non-finite or zero)"
            ));
        }
        let file = mesh_files::mesh_file(&it.desc.mesh).map_or("", |(_, f)| f);
        for (what, statement, at) in [
            ("texture coordinates", "vt", b.partial.uvs),
            ("normals", "vn", b.partial.normals),
        ] {
            if let Some((line, column)) = at {
                warn_with(
                    format!("mesh \"{name}\": has no {what}: the face vertex at {file}:{line}:{column} names no `{statement}` while others do"),
                    Some(format!("a mesh keeps {what} only when every face vertex names one: give that face's vertices `{statement}` indices")),
                );
            }
        }
    }
    let bakes = bake::bake_requests(src, &merged, &leaves, &has_uvs);
    if sources.has_errors() {
        return Err(sources.refuse());
    }

    geometry::warnings(&mut sources, &merged, &object_geometry);
    let objects = built
        .into_iter()
        .zip(object_geometry)
        .zip(&resolved.polygon_materials)
        .zip(&merged.objects)
        .map(|(((b, geometry), polygons), it)| {
            let uvs1 = b.as_ref().and_then(|b| b.uvs1.clone()).map(Arc::new);
            let colours = b.as_ref().and_then(|b| b.colours.clone()).map(Arc::new);
            let tangents = b.as_ref().and_then(|b| b.tangents.clone()).map(Arc::new);
            let face_materials = b
                .as_ref()
                .zip(polygons.as_ref())
                .map(|(b, polygons)| b.polygon_of.iter().map(|&p| polygons[p as usize]).collect());
            ObjectParts {
                mesh: b.map(|b| Arc::new(b.mesh)),
                uvs1,
                colours,
                tangents,
                geometry,
                face_materials,
                instance_material_wins: matches!(
                    it.desc.mesh,
                    MeshDesc::Obj {
                        materials: Some(_),
                        ..
                    }
                ),
            }
        })
        .collect();
    let checked: Vec<_> = materials.iter().map(|p| p.material.as_ref()).collect();
    let placed = leaves.iter().map(|l| photon_flags::PlacedFlags {
        path: &l.path,
        instance: l.instance,
        object: l.object,
        material: l.material,
        photon: l.photon,
    });
    photon_flags::warn_shadow_casters(
        &mut sources,
        &merged,
        placed,
        &checked,
        settings.photons.caustics.is_some(),
    );
    let parts = spawn::Parts {
        cameras,
        render_camera: resolved.camera,
        lights,
        materials,
        objects,
        leaves,
        bakes,
        origin,
    };
    let mut world = spawn::spawn(&sources, &merged, parts);
    // The decoded image textures, environment maps and displacement images, for the
    // run-wide memory estimate.
    let textures = phenomena
        .decoded_textures()
        .iter()
        .map(|t| (&t.name, &t.at, t.image));
    let others = sources
        .images
        .listed()
        .iter()
        .map(|i| (&i.name, &i.at, i.image));
    for (name, at, image) in textures.chain(others) {
        world.spawn((
            crate::components::Name(name.clone()),
            crate::components::SourceLink::from(at.clone()),
            image,
        ));
    }
    if let Some(env) = environment {
        world.spawn((crate::components::Name("environment".into()), env));
    }
    let has_contours = world
        .query::<&crate::components::ContourShader>()
        .iter()
        .next()
        .is_some();
    if has_contours {
        world.spawn((crate::components::Name("contours".into()), contrast));
    }
    Ok(LoadedScene {
        world,
        settings,
        located_warnings: sources.warnings(),
        source_hash: content_hash.finish(),
    })
}

/// Which of `count` materials an instance places: a leaf's material (its instance's, its
/// object's, a scatter's prototype's) or one of its object's polygon materials — the
/// materials `spawn` makes entities of.
fn used_materials(
    count: usize,
    leaves: &[dag::Leaf],
    polygon_materials: &[Option<Vec<Option<usize>>>],
) -> Vec<bool> {
    let mut used = vec![false; count];
    let mut mark = |m: Option<usize>| {
        if let Some(u) = m.and_then(|m| used.get_mut(m)) {
            *u = true;
        }
    };
    for leaf in leaves {
        mark(leaf.material);
        if let Some(Some(polygons)) = polygon_materials.get(leaf.object) {
            polygons.iter().for_each(|&m| mark(m));
        }
    }
    used
}

/// The same element with a rebased description (see [`rebase`]).
fn rebased<'a, T>(item: &validate::Item<'_, T>, desc: &'a T) -> validate::Item<'a, T> {
    validate::Item {
        file: item.file,
        path: item.path.clone(),
        pos: item.pos.clone(),
        desc,
    }
}

/// Checks every object's mesh and builds those reachable from the root. A missing mesh file
/// is reported for every object; parse errors only for reachable ones (others are not
/// read).
fn build_meshes(src: &mut Sources, m: &Merged<'_>, reachable: &[bool]) -> Vec<Option<BuiltMesh>> {
    m.objects
        .iter()
        .zip(reachable)
        .map(|(it, &reachable)| match &it.desc.mesh {
            MeshDesc::Inline {
                vertices,
                polygons,
                normals,
                uvs,
                ..
            } => {
                let mut ck = Checker { src, file: it.file };
                let ok = mesh_load::check_inline(
                    &mut ck,
                    &it.at(".mesh.Inline"),
                    vertices,
                    polygons,
                    normals.as_deref(),
                    uvs.as_deref(),
                );
                (ok && reachable).then(|| {
                    mesh_load::build_inline(vertices, polygons, normals.as_deref(), uvs.as_deref())
                })
            }
            mesh => match mesh_files::mesh_file(mesh) {
                Some((format, file)) => mesh_load::load_file(src, it, format, file, reachable),
                // Generated by the geometry stages (checked in `geometry`).
                None => None,
            },
        })
        .collect()
}
