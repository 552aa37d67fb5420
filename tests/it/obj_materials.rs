//! OBJ `mtllib`/`usemtl` in scenes: MTL materials mapped onto our shaders, an OBJ with
//! several materials placed as one piece per material (and rendered with them), the
//! object's own `material` winning, and located warnings and errors for missing or
//! malformed MTL files (exact texts).

use std::path::{Path, PathBuf};

use glam::Vec3;
use stagelight::components::{Material, MaterialRef, Name, Shader};
use stagelight::scene::LoadedScene;

/// Two unit quads side by side in z = 0 (x in [-1, 0] and [0, 1]), the left under
/// `usemtl red`, the right under `usemtl blue`, with texture coordinates.
const TWO_QUADS: &str = "mtllib paint.mtl\n\
    v -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 1 -1 0\nv 1 1 0\n\
    vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
    usemtl red\nf 1/1 2/2 3/3 4/4\nusemtl blue\nf 2/1 5/2 6/3 3/4\n";

const PAINT: &str = "# two paints\nnewmtl red\nKd 0.8 0 0\nKs 0.5 0.5 0.5\nNs 40\n\
    newmtl blue\nKd 0 0 0.8\nd 0.5\nKe 0 0 2\nnewmtl glass\nNi 1.33\nillum 7\n";

/// Writes `files` into a fresh scratch directory and returns it.
fn dir_with(test: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = crate::common::cli::scratch_dir(test);
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

/// A scene that places `object` (a RON object) once, lit from above, seen from +Z.
fn scene(object: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, seed: 1, integrator: Direct, max_depth: 1),
    cameras: [(name: "cam", fov_y: 60.0, resolution: (8, 4),
        placement: LookAt(eye: (0, 0, 0.75), target: (0, 0, 0), up: (0, 1, 0)), outputs: [])],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 3)],
    materials: [(name: "white", shader: Lambert(albedo: (0.7, 0.7, 0.7)))],
    objects: [{object}],
    instances: [(name: "quads_1", of: "quads")],
    groups: [(name: "world", members: ["quads_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn load(dir: &Path, object: &str) -> Result<LoadedScene, String> {
    stagelight::scene::load_scene_str(&scene(object), &dir.join("scene.ron"))
        .map_err(|e| e.to_string())
}

/// Each placed piece's name and its material's name and component, in entity order.
fn placed(scene: &LoadedScene) -> Vec<(String, String, Material)> {
    let world = &scene.world;
    let mut out = Vec::new();
    for (name, material) in world.query::<(&Name, &MaterialRef)>().iter() {
        let m = world.entity(material.0).unwrap();
        let material_name = m.get::<&Name>().unwrap().0.clone();
        let component = (*m.get::<&Material>().unwrap()).clone();
        out.push((name.0.clone(), material_name, component));
    }
    out
}

#[test]
fn an_obj_with_two_materials_places_one_piece_per_material() {
    let dir = dir_with(
        "obj_mtl_pieces",
        &[("quads.obj", TWO_QUADS), ("paint.mtl", PAINT)],
    );
    let scene = load(&dir, r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#).unwrap();
    assert_eq!(scene.located_warnings, Vec::<String>::new());
    let pieces = placed(&scene);
    let names: Vec<(&str, &str)> = pieces
        .iter()
        .map(|(n, m, _)| (n.as_str(), m.as_str()))
        .collect();
    assert_eq!(
        names,
        vec![
            ("world/quads_1/quads.red", "quads.red"),
            ("world/quads_1/quads.blue", "quads.blue")
        ]
    );
    // Kd/Ks/Ns → Phong; Kd + d + Ke → Opacity over Lambert, emitting.
    assert_eq!(
        pieces[0].2.shader,
        Shader::Phong {
            ambient: Vec3::ZERO,
            diffuse: Vec3::new(0.8, 0.0, 0.0),
            specular: Vec3::splat(0.5),
            spec_exp: 40.0,
        }
    );
    assert_eq!(
        pieces[1].2.shader,
        Shader::Opacity {
            opacity: Vec3::splat(0.5),
            input: Box::new(Shader::Lambert {
                albedo: Vec3::new(0.0, 0.0, 0.8)
            }),
        }
    );
    assert_eq!(pieces[1].2.emission, Vec3::new(0.0, 0.0, 2.0));
    assert_eq!(pieces[0].2.emission, Vec3::ZERO);
}

#[test]
fn the_pieces_render_with_their_own_materials() {
    let dir = dir_with(
        "obj_mtl_render",
        &[
            ("quads.obj", TWO_QUADS),
            (
                "paint.mtl",
                "newmtl red\nKd 0.8 0 0\nnewmtl blue\nKd 0 0 0.8\n",
            ),
        ],
    );
    let mut scene = load(&dir, r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#).unwrap();
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("an image");
    let pixel = |x: usize, y: usize| image.beauty[y * 8 + x];
    for y in 1..3 {
        for x in 0..3 {
            let (left, right) = (pixel(x, y), pixel(7 - x, y));
            assert!(left.x > 0.1 && left.y == 0.0 && left.z == 0.0, "{left:?}");
            assert!(
                right.z > 0.1 && right.x == 0.0 && right.y == 0.0,
                "{right:?}"
            );
        }
    }
}

#[test]
fn one_material_becomes_the_objects_material_and_the_objects_own_wins() {
    let obj = "mtllib lib/glass.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\n";
    let dir = dir_with(
        "obj_mtl_single",
        &[("tri.obj", obj), ("lib/glass.mtl", PAINT)],
    );
    let scene = load(&dir, r#"(name: "quads", mesh: Obj(file: "tri.obj"))"#).unwrap();
    let pieces = placed(&scene);
    assert_eq!(pieces.len(), 1);
    assert_eq!(
        (pieces[0].0.as_str(), pieces[0].1.as_str()),
        ("world/quads_1", "quads.glass")
    );
    assert!(matches!(
        pieces[0].2.shader,
        Shader::Dielectric { ior, .. } if ior == 1.33
    ));
    // The object's own material: every face, and the MTL is not read at all.
    std::fs::write(dir.join("lib/glass.mtl"), "this is not MTL\n").unwrap();
    let own = load(
        &dir,
        r#"(name: "quads", mesh: Obj(file: "tri.obj"), material: "white")"#,
    )
    .unwrap();
    let pieces = placed(&own);
    assert_eq!(
        (pieces[0].0.as_str(), pieces[0].1.as_str()),
        ("world/quads_1", "white")
    );
    assert_eq!(own.located_warnings, Vec::<String>::new());
}

#[test]
fn a_missing_library_or_material_is_a_warning_naming_it() {
    let dir = dir_with("obj_mtl_missing", &[("quads.obj", TWO_QUADS)]);
    let scene = load(&dir, r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#).unwrap();
    let obj = dir.join("quads.obj");
    let mtl = dir.join("paint.mtl");
    assert_eq!(
        scene.located_warnings,
        vec![format!(
            "{}:1:8: warning: cannot read material library \"{}\": file not found; faces using its materials use the default material",
            obj.display(),
            mtl.display()
        )]
    );
    // Every face falls back to the default material: one object, no split.
    let pieces = placed(&scene);
    assert_eq!(pieces.len(), 1);
    assert_eq!(pieces[0].1, "<default>");

    std::fs::write(&mtl, "newmtl red\nKd 1 0 0\n").unwrap();
    let scene = load(&dir, r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#).unwrap();
    assert_eq!(
        scene.located_warnings,
        vec![format!(
            "{}:14:8: warning: material \"blue\" is in none of the material libraries (paint.mtl); its faces use the default material",
            obj.display()
        )]
    );
    let names: Vec<String> = placed(&scene).into_iter().map(|p| p.1).collect();
    assert_eq!(names, vec!["quads.red", "<default>"]);
}

#[test]
fn a_malformed_library_is_a_located_error() {
    let dir = dir_with(
        "obj_mtl_bad",
        &[
            ("quads.obj", TWO_QUADS),
            ("paint.mtl", "newmtl red\nKd 0.8 zero 0\n"),
        ],
    );
    let err = load(&dir, r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#)
        .err()
        .expect("a load error");
    let mtl = dir.join("paint.mtl");
    assert_eq!(
        err,
        format!(
            "{}:2:8: error: invalid MTL file \"{}\": \"zero\" is not a number\n  help: material library of \"{}\", loaded for object \"quads\" at {}:7:47",
            mtl.display(),
            mtl.display(),
            dir.join("quads.obj").display(),
            dir.join("scene.ron").display()
        )
    );
}

#[test]
fn textures_are_found_beside_the_library() {
    let dir = dir_with(
        "obj_mtl_texture",
        &[
            (
                "quads.obj",
                TWO_QUADS.replace("paint.mtl", "mat/paint.mtl").as_str(),
            ),
            (
                "mat/paint.mtl",
                "newmtl red\nmap_Kd -clamp on tex/wood.png\nnewmtl blue\nbump -bm 0.01 tex/h.png\n",
            ),
        ],
    );
    let err = load(&dir, r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#)
        .err()
        .expect("a load error");
    let mtl = dir.join("mat/paint.mtl");
    let help = format!(
        "  help: material library of \"{}\", loaded for object \"quads\" at {}:7:47",
        dir.join("quads.obj").display(),
        dir.join("scene.ron").display()
    );
    assert_eq!(
        err,
        format!(
            "{m}:2:18: error: material \"red\": cannot read texture \"{}\": file not found\n{help}\n\
             {m}:4:15: error: material \"blue\": cannot read texture \"{}\": file not found\n{help}",
            dir.join("mat/tex/wood.png").display(),
            dir.join("mat/tex/h.png").display(),
            m = mtl.display(),
        )
    );
}

#[test]
fn usemtl_picks_one_materials_faces() {
    let dir = dir_with("obj_mtl_usemtl", &[("quads.obj", TWO_QUADS)]);
    let scene = load(
        &dir,
        r#"(name: "quads", mesh: Obj(file: "quads.obj", usemtl: "blue"), material: "white")"#,
    )
    .unwrap();
    let meshes: Vec<usize> = scene
        .world
        .query::<&std::sync::Arc<stagelight::components::TriMesh>>()
        .iter()
        .map(|m| m.positions.len() * 100 + m.triangles.len())
        .collect();
    assert_eq!(meshes, vec![402]);
    let err = load(
        &dir,
        r#"(name: "quads", mesh: Obj(file: "quads.obj", usemtl: "green"), material: "white")"#,
    )
    .err()
    .expect("a load error");
    assert!(
        err.contains("usemtl: no face uses material \"green\": it uses \"red\", \"blue\""),
        "{err}"
    );
}
