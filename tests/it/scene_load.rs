//! Loading good scenes: the entities and components the loader spawns.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Affine3A, Vec3};
use hecs::{Entity, World};
use stagelight::components::{
    Camera, Emitter, ImageFormat, Instance, LightShape, Material, MaterialRef, Name, Pass,
    RenderCamera, Shader, SourceLink, TriMesh, WorldFromObject,
};
use stagelight::scene::{load_scene, load_scene_str, LoadedScene};
use stagelight::settings::{BvhQuality, Face, PixelFilter, RenderSettings};

fn fixture(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/scenes")
        .join(rel)
}

fn load_good() -> LoadedScene {
    match load_scene(&fixture("good/main.ron")) {
        Ok(scene) => scene,
        Err(e) => panic!("good scene failed:\n{e}"),
    }
}

fn named(world: &World, name: &str) -> Entity {
    world
        .query::<(Entity, &Name)>()
        .iter()
        .find(|(_, n)| n.0 == name)
        .map(|(e, _)| e)
        .unwrap_or_else(|| panic!("no entity named {name}"))
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

/// Material name of the leaf named `path`.
fn leaf_material(world: &World, path: &str) -> String {
    let leaf = named(world, path);
    let mat = world.get::<&MaterialRef>(leaf).unwrap().0;
    world.get::<&Name>(mat).unwrap().0.clone()
}

fn leaf_transform(world: &World, path: &str) -> Affine3A {
    world.get::<&WorldFromObject>(named(world, path)).unwrap().0
}

#[test]
fn leaves_of_a_shared_group_are_all_spawned_with_paths() {
    let scene = load_good();
    let mut names: Vec<String> = scene
        .world
        .query::<(&Name, &Instance)>()
        .iter()
        .map(|(n, _)| n.0.clone())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "world/floor",
            "world/junk_1",
            "world/table_a/leg",
            "world/table_a/top",
            "world/table_b/leg",
            "world/table_b/top",
        ]
    );
    // Every leaf has all its components and shares the object's mesh.
    for (instance, _, _, _) in scene
        .world
        .query::<(&Instance, &WorldFromObject, &MaterialRef, &SourceLink)>()
        .iter()
    {
        let object_mesh = scene.world.get::<&Arc<TriMesh>>(instance.object).unwrap();
        assert!(Arc::ptr_eq(&object_mesh, &instance.mesh));
    }
}

#[test]
fn transforms_compose_in_listed_order_and_along_the_path() {
    let scene = load_good();
    let w = &scene.world;
    // table_a = Translate(5,0,0) · RotateY(90°); leg = Scale(1,2,1).
    let m = leaf_transform(w, "world/table_a/leg");
    assert!(close(
        m.transform_point3(Vec3::new(1.0, 1.0, 0.0)),
        Vec3::new(5.0, 2.0, -1.0)
    ));
    assert!(close(
        m.transform_point3(Vec3::new(0.0, 0.0, 1.0)),
        Vec3::new(6.0, 0.0, 0.0)
    ));
    let expected = Affine3A::from_translation(Vec3::new(5.0, 0.0, 0.0))
        * Affine3A::from_rotation_y(90f32.to_radians())
        * Affine3A::from_scale(Vec3::new(1.0, 2.0, 1.0));
    assert!(m.abs_diff_eq(expected, 1e-6));
    // table_b = Translate(0,0,-5); top = Translate(0,1,0).
    let m = leaf_transform(w, "world/table_b/top");
    assert!(m.abs_diff_eq(Affine3A::from_translation(Vec3::new(0.0, 1.0, -5.0)), 1e-6));
    // Row-major matrix rows (1,0,0,0), (0,0,1,0), (0,-1,0,0): (x, y, z) -> (x, z, -y).
    let m = leaf_transform(w, "world/floor");
    assert!(close(
        m.transform_point3(Vec3::new(1.0, 2.0, 3.0)),
        Vec3::new(1.0, 3.0, -2.0)
    ));
    assert_eq!(leaf_transform(w, "world/junk_1"), Affine3A::IDENTITY);
}

#[test]
fn transform_list_scales_then_rotates_then_translates() {
    let text = r#"Scene(
        objects: [(name: "o", mesh: Inline(vertices: [(0,0,0), (1,0,0), (0,1,0)], polygons: [[0,1,2]]))],
        instances: [(name: "i", of: "o", transform: [Scale((2, 2, 2)), Rotate(axis: (0, 0, 1), degrees: 90), Translate((1, 0, 0))])],
        groups: [(name: "g", members: ["i"])],
        cameras: [(name: "c", fov_y: 40, resolution: (1, 1), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
        render: (root: "g", camera: "c"),
    )"#;
    let scene = load_scene_str(text, &fixture("inline.ron")).unwrap();
    let m = leaf_transform(&scene.world, "g/i");
    // (1,0,0) -> scale (2,0,0) -> rotate (0,2,0) -> translate (1,2,0).
    assert!(close(
        m.transform_point3(Vec3::new(1.0, 0.0, 0.0)),
        Vec3::new(1.0, 2.0, 0.0)
    ));
}

#[test]
fn materials_resolve_innermost_instance_then_outer_then_object_then_default() {
    let scene = load_good();
    let w = &scene.world;
    assert_eq!(leaf_material(w, "world/table_a/top"), "red"); // inner instance over object
    assert_eq!(leaf_material(w, "world/table_b/top"), "red"); // inner over outer "blue"
    assert_eq!(leaf_material(w, "world/table_b/leg"), "blue"); // outer instance
    assert_eq!(leaf_material(w, "world/junk_1"), "white"); // object's material
    assert_eq!(leaf_material(w, "world/table_a/leg"), "<default>");
    let default = named(w, "<default>");
    assert_eq!(
        *w.get::<&Material>(default).unwrap(),
        Material {
            shader: Shader::DefaultSurface {
                ka: 0.2,
                kd: 0.8,
                color: Vec3::ONE
            },
            two_sided: false,
            emission: Vec3::ZERO,
            graph: None,
            ..Default::default()
        }
    );
    // Only used materials are spawned ("spare" is not).
    let mut mats: Vec<String> = w
        .query::<(&Name, &Material)>()
        .iter()
        .map(|(n, _)| n.0.clone())
        .collect();
    mats.sort();
    assert_eq!(mats, ["<default>", "blue", "red", "white"]);
    let red = named(w, "red");
    assert_eq!(
        *w.get::<&Material>(red).unwrap(),
        Material {
            shader: Shader::Constant {
                color: Vec3::new(1.0, 0.0, 0.0)
            },
            two_sided: true,
            emission: Vec3::new(2.0, 0.0, 0.0),
            graph: None,
            ..Default::default()
        }
    );
}

#[test]
fn obj_models_merge_with_uvs_and_normals() {
    let scene = load_good();
    let tri = named(&scene.world, "tri");
    let mesh = scene.world.get::<&Arc<TriMesh>>(tri).unwrap();
    assert_eq!(mesh.positions.len(), 7);
    assert_eq!(mesh.triangles.len(), 3);
    let normals = mesh.normals.as_ref().expect("normals kept");
    assert!(normals.iter().all(|n| close(*n, Vec3::Z)), "normalised");
    let uvs = mesh.uvs.as_ref().expect("uvs kept");
    assert_eq!(uvs.len(), 7);
    assert_eq!(mesh.triangle(0), [Vec3::ZERO, Vec3::X, Vec3::Y]);
    let link = scene.world.get::<&SourceLink>(tri).unwrap();
    assert!(link.file.ends_with("good/main.ron"));
    assert_eq!((link.line, link.column), (29, 9));
}

#[test]
fn inline_polygons_are_fan_triangulated_and_degenerates_dropped() {
    let scene = load_good();
    let quad = named(&scene.world, "quad");
    let mesh = scene.world.get::<&Arc<TriMesh>>(quad).unwrap();
    assert_eq!(mesh.triangles, vec![[0, 3, 2], [0, 2, 1]]);
    assert!(mesh.normals.is_none() && mesh.uvs.is_none());
    let junk = named(&scene.world, "junk");
    let mesh = scene.world.get::<&Arc<TriMesh>>(junk).unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    // Located at the object's mesh.
    let dropped: Vec<&String> = scene
        .located_warnings
        .iter()
        .filter(|w| w.contains("degenerate"))
        .collect();
    assert_eq!(dropped.len(), 1, "{:?}", scene.located_warnings);
    assert!(
        dropped[0].ends_with(
            "good/main.ron:33:19: warning: mesh \"junk\": dropped 2 degenerate triangles"
        ),
        "{}",
        dropped[0]
    );
    // Objects not reachable from the root are not spawned.
    assert!(scene.world.query::<&Name>().iter().all(|n| n.0 != "unused"));
}

#[test]
fn includes_merge_and_a_diamond_loads_once() {
    let scene = load_good();
    let blue = named(&scene.world, "blue");
    let link = scene.world.get::<&SourceLink>(blue).unwrap();
    assert!(link.file.ends_with("good/lib/shared.ron"), "{link:?}");
    // The display path keeps the user's spelling: root dir joined with the include string.
    let root = fixture("good/main.ron");
    assert_eq!(link.file, root.parent().unwrap().join("lib/shared.ron"));
    assert_eq!((link.line, link.column), (3, 9));
}

#[test]
fn cameras_lights_and_settings() {
    let scene = load_good();
    let w = &scene.world;
    assert_eq!(
        scene.settings,
        RenderSettings {
            spp: 16,
            filter: PixelFilter::Gaussian {
                sigma: 0.7,
                radius: 1.5
            },
            seed: 7,
            max_depth: 3,
            face: Face::Both,
            bvh_quality: BvhQuality::High,
            ..RenderSettings::default()
        }
    );
    let cam = named(w, "cam");
    assert!(w.get::<&RenderCamera>(cam).is_ok());
    let c = w.get::<&Camera>(cam).unwrap();
    assert!((c.fov_y - 45f32.to_radians()).abs() < 1e-6);
    assert_eq!((c.width, c.height, c.aspect), (64, 32, 2.0));
    // Looks down -Z from (0,0,5): camera space is world space shifted.
    assert!(c
        .world_from_camera
        .abs_diff_eq(Affine3A::from_translation(Vec3::new(0.0, 0.0, 5.0)), 1e-6));
    assert_eq!(c.outputs.len(), 2);
    assert_eq!(c.outputs[0].path, Path::new("out/beauty.png"));
    assert_eq!(c.outputs[0].format, ImageFormat::Png);
    assert_eq!(c.outputs[0].passes, [Pass::Beauty]);
    assert_eq!(c.outputs[1].format, ImageFormat::Exr);
    assert_eq!(
        c.outputs[1].passes,
        [Pass::Beauty, Pass::Depth, Pass::Normal]
    );
    let side = named(w, "side");
    assert!(w.get::<&RenderCamera>(side).is_err());
    let s = w.get::<&Camera>(side).unwrap();
    assert_eq!(s.aspect, 2.0);
    // Its -Z axis (view direction) is world -X.
    assert!(close(
        s.world_from_camera.transform_vector3(-Vec3::Z),
        -Vec3::X
    ));

    let key = (*w.get::<&Emitter>(named(w, "key")).unwrap()).clone();
    assert_eq!(key.radiant, Vec3::new(10.0, 5.0, 2.5));
    assert!(!key.shadows);
    assert_eq!(key.samples, 1);
    let spot = (*w.get::<&Emitter>(named(w, "spot")).unwrap()).clone();
    match spot.shape {
        LightShape::Spot {
            direction,
            cone_angle,
            penumbra,
            beam_distribution,
            ..
        } => {
            assert!(close(direction, -Vec3::Y));
            assert!((cone_angle - 30f32.to_radians()).abs() < 1e-6);
            assert!((penumbra - 5f32.to_radians()).abs() < 1e-6);
            assert_eq!(beam_distribution, 2.0);
        }
        other => panic!("{other:?}"),
    }
    assert!(spot.shadows);
    let sun = (*w.get::<&Emitter>(named(w, "sun")).unwrap()).clone();
    assert_eq!(
        sun.shape,
        LightShape::Directional {
            direction: -Vec3::Y
        }
    );
    let panel = (*w.get::<&Emitter>(named(w, "panel")).unwrap()).clone();
    assert_eq!(panel.samples, 4);
    assert_eq!(panel.radiant, Vec3::ONE);
}

#[test]
fn options_default_when_absent() {
    let text = r#"Scene(
        groups: [(name: "g")],
        cameras: [(name: "c", fov_y: 40, resolution: (4, 2), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
        render: (root: "g", camera: "c"),
    )"#;
    let scene = load_scene_str(text, &fixture("defaults.ron")).unwrap();
    assert_eq!(scene.settings, RenderSettings::default());
    let cam = named(&scene.world, "c");
    let c = scene.world.get::<&Camera>(cam).unwrap();
    assert_eq!(c.aspect, 2.0);
    assert!(c.outputs.is_empty());
    assert!(scene.located_warnings.is_empty());
}

#[test]
fn rect_light_samples_default_to_16_and_filter_defaults() {
    let text = r#"Scene(
        options: (filter: Gaussian()),
        groups: [(name: "g")],
        lights: [(name: "l", kind: Rect(corner: (0, 0, 0), edge_u: (1, 0, 0), edge_v: (0, 1, 0)))],
        cameras: [(name: "c", fov_y: 40, resolution: (4, 2), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
        render: (root: "g", camera: "c"),
    )"#;
    let scene = load_scene_str(text, &fixture("defaults.ron")).unwrap();
    assert_eq!(
        scene.settings.filter,
        PixelFilter::Gaussian {
            sigma: 0.5,
            radius: 1.5
        }
    );
    let l = (*scene
        .world
        .get::<&Emitter>(named(&scene.world, "l"))
        .unwrap())
    .clone();
    assert_eq!(l.samples, 16);
}

#[test]
fn three_level_dag_with_shared_groups_composes_every_path() {
    // leaf group "post" is placed twice in "fence", and "fence" twice in "world": 4 leaves.
    let text = r#"Scene(
        objects: [(name: "o", mesh: Inline(vertices: [(0,0,0), (1,0,0), (0,1,0)], polygons: [[0,1,2]]))],
        instances: [
            (name: "p", of: "o", transform: [Scale((1, 3, 1))]),
            (name: "left", of: "post", transform: [Translate((-1, 0, 0))]),
            (name: "right", of: "post", transform: [Translate((1, 0, 0))]),
            (name: "near", of: "fence"),
            (name: "far", of: "fence", transform: [Rotate(axis: (0, 1, 0), degrees: 180), Translate((0, 0, -10))]),
        ],
        groups: [
            (name: "post", members: ["p"]),
            (name: "fence", members: ["left", "right"]),
            (name: "world", members: ["near", "far"]),
        ],
        cameras: [(name: "c", fov_y: 40, resolution: (1, 1), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
        render: (root: "world", camera: "c"),
    )"#;
    let scene = load_scene_str(text, &fixture("fence.ron")).unwrap();
    let w = &scene.world;
    assert_eq!(w.query::<&Instance>().iter().count(), 4);
    // Hand-computed images of the object point (1, 1, 0) for every path.
    let cases = [
        ("world/near/left/p", Vec3::new(0.0, 3.0, 0.0)),
        ("world/near/right/p", Vec3::new(2.0, 3.0, 0.0)),
        // far: R_y(180°) maps (x, y, z) to (-x, y, -z), then z - 10.
        ("world/far/left/p", Vec3::new(0.0, 3.0, -10.0)),
        ("world/far/right/p", Vec3::new(-2.0, 3.0, -10.0)),
    ];
    for (path, expected) in cases {
        let p = leaf_transform(w, path).transform_point3(Vec3::new(1.0, 1.0, 0.0));
        assert!(close(p, expected), "{path}: {p} != {expected}");
    }
}
