//! OBJ `mtllib`/`usemtl` in scenes: MTL materials mapped onto our shaders, an OBJ with
//! several materials loaded as one object with a material per face (rendered with them, the
//! same bytes as its pieces placed separately, an instance's `material` replacing them, and
//! baked as one instance), the object's own `material` winning, and located warnings and
//! errors for missing or malformed MTL files (exact texts).

use std::path::{Path, PathBuf};

use crate::common::read_exr_texels;
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

/// Per triangle of the only placed object, the name of its own material (`None`: the
/// instance's).
fn face_material_names(scene: &LoadedScene) -> Vec<Option<String>> {
    let world = &scene.world;
    let mut query = world.query::<&stagelight::components::FaceMaterials>();
    let faces: Vec<_> = query.iter().map(|f| f.0.clone()).collect();
    assert_eq!(faces.len(), 1, "one object with face materials");
    faces[0]
        .iter()
        .map(|m| m.map(|e| world.get::<&Name>(e).unwrap().0.clone()))
        .collect()
}

fn material_named(scene: &LoadedScene, name: &str) -> Material {
    let mut query = scene.world.query::<(&Name, &Material)>();
    let found = query
        .iter()
        .find(|(n, _)| n.0 == name)
        .map(|(_, m)| m.clone());
    found.unwrap_or_else(|| panic!("no material {name}"))
}

#[test]
fn an_obj_with_two_materials_is_one_object_with_a_material_per_face() {
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
    assert_eq!(names, vec![("world/quads_1", "<default>")]);
    let red = Some("quads.red".to_string());
    let blue = Some("quads.blue".to_string());
    assert_eq!(
        face_material_names(&scene),
        vec![red.clone(), red, blue.clone(), blue]
    );
    // Kd/Ks/Ns → Phong; Kd + d + Ke → Opacity over Lambert, emitting.
    let (red, blue) = (
        material_named(&scene, "quads.red"),
        material_named(&scene, "quads.blue"),
    );
    assert_eq!(
        red.shader,
        Shader::Phong {
            ambient: Vec3::ZERO,
            diffuse: Vec3::new(0.8, 0.0, 0.0),
            specular: Vec3::splat(0.5),
            spec_exp: 40.0,
        }
    );
    assert_eq!(
        blue.shader,
        Shader::Opacity {
            opacity: Vec3::splat(0.5),
            input: Box::new(Shader::Lambert {
                albedo: Vec3::new(0.0, 0.0, 0.8)
            }),
        }
    );
    assert_eq!(blue.emission, Vec3::new(0.0, 0.0, 2.0));
    assert_eq!(red.emission, Vec3::ZERO);
}

#[test]
fn each_face_renders_with_its_own_material() {
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
    assert_eq!(names, vec!["<default>"]);
    let red = Some("quads.red".to_string());
    assert_eq!(
        face_material_names(&scene),
        vec![red.clone(), red, None, None]
    );
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

/// A unit box standing on z = 0 whose faces name their materials out of order (`red` twice,
/// apart), one face before any `usemtl`, and an emitting face.
const BOX: &str = "mtllib box.mtl\n\
    v -0.5 -0.5 0\nv -0.5 -0.5 1\nv -0.5 0.5 0\nv -0.5 0.5 1\n\
    v 0.5 -0.5 0\nv 0.5 -0.5 1\nv 0.5 0.5 0\nv 0.5 0.5 1\n\
    f 3 7 5 1\n\
    usemtl red\nf 5 7 8 6\nusemtl blue\nf 3 1 2 4\nusemtl red\nf 7 3 4 8\n\
    usemtl glow\nf 2 6 8 4\nusemtl blue\nf 1 5 6 2\n";

const BOX_MTL: &str = "newmtl red\nKd 0.8 0.1 0.1\nKs 0.3 0.3 0.3\nNs 30\n\
    newmtl blue\nKd 0.1 0.1 0.8\nnewmtl glow\nKd 0.5 0.5 0.5\nKe 4 3 2\n";

/// A path-traced scene of three boxes on a floor (the third with an instance `material`);
/// `boxes` are the box's objects, `extra` more materials, groups and instances.
fn boxes_scene(boxes: &str, extra_materials: &str, extra: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 8, seed: 3, integrator: Path, max_depth: 4),
    cameras: [(name: "cam", fov_y: 50.0, resolution: (48, 32),
        placement: LookAt(eye: (2.2, -3.0, 2.2), target: (0.4, 0, 0.4), up: (0, 0, 1)),
        outputs: [])],
    lights: [(name: "key", kind: Point(position: (1, -2, 3)), intensity: 20)],
    materials: [(name: "white", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
                (name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5))){extra_materials}],
    objects: [{boxes}
        (name: "floor", mesh: Inline(vertices: [(-3, -3, 0), (3, -3, 0), (3, 3, 0), (-3, 3, 0)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
    ],
    instances: [{extra}
        (name: "box_1", of: "box"),
        (name: "box_2", of: "box",
            transform: [Rotate(axis: (0, 0, 1), degrees: 30), Translate((1.3, 0.4, 0))]),
        (name: "box_3", of: "box", material: "white", transform: [Translate((-0.6, 1.4, 0))]),
        (name: "floor_1", of: "floor"),
    ],
    groups: [(name: "world", members: ["box_1", "box_2", "box_3", "floor_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// The beauty pixels of `text` rendered as `dir/scene.ron`.
fn beauty(dir: &Path, text: &str) -> Vec<Vec3> {
    let mut scene = stagelight::scene::load_scene_str(text, &dir.join("scene.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("an image").beauty
}

#[test]
fn one_object_with_face_materials_renders_the_bytes_of_its_pieces_placed_apart() {
    let dir = dir_with(
        "obj_mtl_same_bytes",
        &[("box.obj", BOX), ("box.mtl", BOX_MTL)],
    );
    let whole = boxes_scene(r#"(name: "box", mesh: Obj(file: "box.obj")),"#, "", "");
    // What a multi-material OBJ loaded as before: a group of one object per material.
    let materials = r#",
        (name: "box.red", shader: Phong(ambient: (0, 0, 0), diffuse: (0.8, 0.1, 0.1),
            specular: (0.3, 0.3, 0.3), spec_exp: 30)),
        (name: "box.blue", shader: Lambert(albedo: (0.1, 0.1, 0.8))),
        (name: "box.glow", shader: Lambert(albedo: (0.5, 0.5, 0.5)), emission: (4, 3, 2))"#;
    let mut objects = String::new();
    let mut instances = String::new();
    for (piece, usemtl, material) in [
        ("box.default", "", ""),
        ("box.red", "red", r#", material: "box.red""#),
        ("box.blue", "blue", r#", material: "box.blue""#),
        ("box.glow", "glow", r#", material: "box.glow""#),
    ] {
        objects += &format!(
            r#"(name: "{piece}", mesh: Obj(file: "box.obj", usemtl: "{usemtl}"){material}),"#
        );
        instances += &format!(r#"(name: "{piece}", of: "{piece}"),"#);
    }
    let pieces = boxes_scene(&objects, materials, &instances).replace(
        "groups: [",
        r#"groups: [(name: "box", members: ["box.default", "box.red", "box.blue", "box.glow"]), "#,
    );
    let (a, b) = (beauty(&dir, &whole), beauty(&dir, &pieces));
    assert!(
        a.iter().any(|p| p.x > 0.5 && p.z < 0.3),
        "a red face is seen"
    );
    assert!(
        a.iter().any(|p| p.x > 1.0 && p.y > 0.7),
        "the glowing top is seen"
    );
    let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert_eq!(differ, 0, "pixels differ from the pieces' render");
}

#[test]
fn an_instance_material_replaces_the_mtl_materials_on_every_face() {
    let dir = dir_with(
        "obj_mtl_override",
        &[
            ("quads.obj", TWO_QUADS),
            (
                "paint.mtl",
                "newmtl red\nKd 0.8 0 0\nnewmtl blue\nKd 0 0 0.8\n",
            ),
        ],
    );
    let text = scene(r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#).replace(
        r#"(name: "quads_1", of: "quads")"#,
        r#"(name: "quads_1", of: "quads", material: "white")"#,
    );
    let image = beauty(&dir, &text);
    let grey = image[8 + 1];
    assert!(
        grey.x > 0.1 && grey.x == grey.y && grey.y == grey.z,
        "{grey:?}"
    );
    for y in 1..3 {
        for x in 0..8 {
            assert_eq!(image[y * 8 + x], grey, "pixel ({x}, {y})");
        }
    }
}

/// [`TWO_QUADS`] with UVs side by side (`red` in u < 0.5, `blue` in u > 0.5), for baking.
const TWO_QUADS_UNWRAPPED: &str = "mtllib paint.mtl\n\
    v -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 1 -1 0\nv 1 1 0\n\
    vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 1 0\nvt 1 1\n\
    usemtl red\nf 1/1 2/2 3/3 4/4\nusemtl blue\nf 2/2 5/5 6/6 3/3\n";

/// The quads under a tilted sun with a small roof casting a shadow across both materials;
/// the instance bakes ambient occlusion and the lightmap stored both ways.
fn bake_scene(object: &str) -> String {
    format!(
        r#"Scene(
    options: (seed: 5),
    cameras: [(name: "cam", fov_y: 60.0, resolution: (8, 8),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0), up: (0, 1, 0)), outputs: [])],
    lights: [(name: "sun", kind: Directional(direction: (0.3, 0.2, -1)), intensity: 3)],
    materials: [(name: "white", shader: Lambert(albedo: (0.7, 0.7, 0.7)))],
    objects: [{object},
        (name: "roof", mesh: Inline(vertices: [(-0.5, -0.4, 0.4), (0.6, -0.4, 0.4),
            (0.6, 0.3, 0.4), (-0.5, 0.3, 0.4)], polygons: [[0, 1, 2, 3]]), material: "white")],
    instances: [
        (name: "quads_1", of: "quads", bake: (resolution: (32, 16), uvs: Mesh, outputs: [
            (kind: AmbientOcclusion(samples: 16)),
            (kind: Lightmap(store: Irradiance), file: "irradiance.exr"),
            (kind: Lightmap(store: Radiance), file: "radiance.exr"),
        ])),
        (name: "roof_1", of: "roof"),
    ],
    groups: [(name: "world", members: ["quads_1", "roof_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

#[test]
fn an_instance_of_a_two_material_obj_bakes_each_face_with_its_material() {
    let dir = dir_with(
        "obj_mtl_bake",
        &[
            ("quads.obj", TWO_QUADS_UNWRAPPED),
            (
                "paint.mtl",
                "newmtl red\nKd 0.8 0 0\nmap_Kd grey.png\nnewmtl blue\nKd 0 0 0.8\n",
            ),
        ],
    );
    // The red face's colour is Kd times a uniform texture of sRGB 128.
    crate::common::png::write_rgb(&dir.join("grey.png"), 2, 2, &[[128; 3]; 4]);
    let grey = stagelight::shading::texture::colour::srgb_to_linear(128.0 / 255.0);
    let bake = |object: &str, out: &str| {
        std::fs::write(dir.join("scene.ron"), bake_scene(object)).unwrap();
        let o = crate::common::cli::run_in(&dir, &["bake", "scene.ron", "-o", out]);
        assert!(o.status.success(), "{}", crate::common::cli::stderr_of(&o));
    };
    bake(r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#, "mtl");
    bake(
        r#"(name: "quads", mesh: Obj(file: "quads.obj"), material: "white")"#,
        "white",
    );
    // Occlusion and irradiance do not depend on the baked faces' materials: the same bytes
    // as the bake of the same mesh with one material.
    for file in ["quads_1_ao.exr", "irradiance.exr"] {
        let (a, b) = (dir.join("mtl").join(file), dir.join("white").join(file));
        assert_eq!(
            std::fs::read(a).unwrap(),
            std::fs::read(b).unwrap(),
            "{file}"
        );
    }
    // Radiance is albedo · E / π with each face's own albedo (its texture included): red
    // left, blue right.
    let (w, e) = read_exr_texels(&dir.join("mtl/irradiance.exr"));
    let (_, l) = read_exr_texels(&dir.join("mtl/radiance.exr"));
    let (lit, shaded) = (
        e.iter().fold(0f32, |m, v| m.max(v.x)),
        e.iter().fold(9f32, |m, v| m.min(v.x)),
    );
    assert!(
        lit > 2.0 && shaded < 0.5 * lit,
        "a shadow crosses the quads: {shaded} … {lit}"
    );
    for (k, (e, l)) in e.iter().zip(&l).enumerate() {
        let albedo = if k % w < w / 2 {
            Vec3::new(0.8 * grey, 0.0, 0.0)
        } else {
            Vec3::new(0.0, 0.0, 0.8)
        };
        let expected = albedo * e.x / std::f32::consts::PI;
        assert!(
            (*l - expected).abs().max_element() <= 1e-6 * (1.0 + expected.max_element()),
            "texel {k}: {l:?}, expected {expected:?}"
        );
    }
}

/// An MTL material whose scene name (`<object>.<mtl name>`) a scene material already holds
/// is an error at the object, naming the MTL material and where the scene's one is (the
/// duplicate-name check pointed at the scene's material twice).
#[test]
fn an_mtl_material_named_like_a_scene_material_is_an_error_at_the_object() {
    let dir = dir_with(
        "mtl_name_taken",
        &[("quads.obj", TWO_QUADS), ("paint.mtl", PAINT)],
    );
    let text = scene(r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#).replace(
        r#"materials: [(name: "white","#,
        r#"materials: [(name: "quads.red", shader: Lambert(albedo: (1, 0, 0))), (name: "white","#,
    );
    let path = dir.join("scene.ron");
    let err = stagelight::scene::load_scene_str(&text, &path)
        .err()
        .expect("refused")
        .to_string();
    let at = |line: usize, column: usize| format!("{}:{line}:{column}", path.display());
    assert_eq!(
        err,
        format!(
            "{}: error: material \"red\" of quads.obj would be named \"quads.red\", a name already in use\n  help: the material at {} has it; rename that material, or give object \"quads\" a `material`",
            at(7, 47),
            at(6, 24),
        )
    );
}

/// `usemtl` in an OBJ that loads no material library is a warning at the first `usemtl`
/// (its faces quietly got the default material).
#[test]
fn usemtl_without_a_library_is_a_warning() {
    let obj_text = TWO_QUADS.replace("mtllib paint.mtl\n", "");
    let dir = dir_with("obj_usemtl_no_lib", &[("quads.obj", &obj_text)]);
    let scene = load(&dir, r#"(name: "quads", mesh: Obj(file: "quads.obj"))"#).unwrap();
    assert_eq!(
        scene.located_warnings,
        vec![format!(
            "{}:11:8: warning: usemtl \"red\" but the file loads no material library (mtllib); its faces use the default material\n  help: add `mtllib FILE.mtl` to the OBJ, or give object \"quads\" a `material`",
            dir.join("quads.obj").display()
        )]
    );
    // An object with its own material asks for none of the OBJ's: no warning.
    let own = load(
        &dir,
        r#"(name: "quads", mesh: Obj(file: "quads.obj"), material: "white")"#,
    )
    .unwrap();
    assert_eq!(own.located_warnings, Vec::<String>::new());
}
