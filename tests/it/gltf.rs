//! glTF 2.0: `Gltf(file: …)` meshes (the same box through OBJ, PLY, `.glb`, embedded and
//! external `.gltf` renders the same bytes), whole glTF files as scenes (hierarchy, shared
//! meshes, camera, punctual lights; or included by a RON scene under its own group),
//! `uvs: MeshSet(1)` bakes on `TEXCOORD_1`, and bad files
//! reported with the element or byte offset (exact texts). Fixtures are written by the
//! third-party writer `pygltflib` (`scripts/make_gltf_fixtures.py`).

use std::path::Path;
use std::sync::Arc;

use glam::Vec3;
use stagelight::components::{Instance, TriMesh, WorldFromObject};
use stagelight::frame::{Frame, Tasks};

const DIR: &str = "tests/fixtures/gltf";

/// Renders a 24² image of `mesh` (a RON mesh value, relative to [`DIR`]); returns the mesh
/// and the beauty pixels' bits.
fn render_mesh(mesh: &str) -> (TriMesh, Vec<[u32; 3]>) {
    let text = format!(
        r#"Scene(
    options: (samples: 4, seed: 3, integrator: Path, max_depth: 2),
    cameras: [(name: "cam", fov_y: 50.0, resolution: (24, 24),
        placement: LookAt(eye: (2.5, 2.2, 2.8), target: (0.8, 0.4, 0.3), up: (0, 1, 0)), outputs: [])],
    lights: [(name: "bulb", kind: Point(position: (1.5, 3, 2)), intensity: 4)],
    materials: [(name: "white", shader: Lambert(albedo: (0.7, 0.7, 0.7)))],
    objects: [(name: "box", mesh: {mesh}, material: "white")],
    instances: [(name: "box_1", of: "box")],
    groups: [(name: "world", members: ["box_1"])],
    render: (root: "world", camera: "cam"),
)"#
    );
    let mut scene = stagelight::scene::load_scene_str(&text, &Path::new(DIR).join("render.ron"))
        .unwrap_or_else(|e| panic!("{mesh}: {e}"));
    assert_eq!(scene.located_warnings, Vec::<String>::new());
    let meshes: Vec<TriMesh> = scene
        .world
        .query::<&Arc<TriMesh>>()
        .iter()
        .map(|m| (**m).clone())
        .collect();
    assert_eq!(meshes.len(), 1);
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let beauty = frame
        .outputs
        .image
        .expect("an image")
        .beauty
        .iter()
        .map(|c| c.to_array().map(f32::to_bits))
        .collect();
    (meshes.into_iter().next().unwrap(), beauty)
}

/// The box of `box.obj` and `box_le.ply`, written by pygltflib as `.glb`, `.gltf` with a
/// base64 buffer and `.gltf` with `box.bin`: the same positions, normals and triangles, and
/// the same image bytes.
#[test]
fn obj_ply_and_gltf_render_the_same_bytes() {
    let (obj, obj_image) = render_mesh("Obj(file: \"../meshes/box.obj\")");
    let (ply, ply_image) = render_mesh("Ply(file: \"../meshes/box_le.ply\")");
    assert_eq!(ply.positions, obj.positions);
    assert!(ply_image == obj_image);
    assert!(obj_image.iter().any(|c| c[0] != 0), "the box is lit");
    for file in ["box.glb", "box_embedded.gltf", "box_external.gltf"] {
        let (gltf, image) = render_mesh(&format!("Gltf(file: \"{file}\", mesh: \"box\")"));
        assert_eq!(gltf.positions, obj.positions, "{file}");
        assert_eq!(gltf.normals, obj.normals, "{file}");
        assert_eq!(gltf.triangles, obj.triangles, "{file}");
        // UVs: u as written; v flipped back (`1 − v`, exact where the result is an f32).
        // The file holds the f32 nearest 1 − v, not 1 − (the OBJ's f32 v), so v agrees only
        // to within a few f32 steps (below 2⁻²³) — bit for bit where 1 − v is exact (0, ½, 1).
        let (uv_gltf, uv_obj) = (gltf.uvs.unwrap(), obj.uvs.clone().unwrap());
        let mut rounded = 0;
        for (a, b) in uv_gltf.iter().zip(&uv_obj) {
            assert_eq!(a.x, b.x, "{file}: u as written");
            assert!(
                (a.y - b.y).abs() <= 2f32.powi(-23),
                "{file}: v is flipped back"
            );
            if [0.0, 0.5, 1.0].contains(&b.y) {
                assert_eq!(a.y, b.y, "{file}: an exact v");
            }
            rounded += usize::from(a.y != b.y);
        }
        assert!(rounded > 0, "{file}: the box has UVs that 1 − v rounds");
        assert!(image == obj_image, "{file}: the images differ");
    }
    // `mesh` may be left out when the file holds one mesh.
    let (_, image) = render_mesh("Gltf(file: \"box.glb\")");
    assert!(image == obj_image);
}

fn load_errors(file: &str) -> Vec<String> {
    match stagelight::scene::load_scene(&Path::new(DIR).join(file)) {
        Ok(_) => panic!("{file} loaded"),
        Err(e) => e.0.iter().map(|d| d.to_string()).collect(),
    }
}

/// Bad files are refused with the glTF element or byte offset, never a panic.
#[test]
fn bad_files_are_located_errors() {
    let at = |f: &str| format!("{DIR}/{f}:1:1: error: invalid glTF file");
    let located =
        |f: &str, line_column: &str| format!("{DIR}/{f}:{line_column}: error: invalid glTF file");
    assert_eq!(
        load_errors("truncated.glb"),
        [format!(
            "{}: byte 8: truncated binary glTF: the header gives a length of 2108 bytes, the file has 1054",
            at("truncated.glb")
        )]
    );
    assert_eq!(
        load_errors("wrong_magic.glb"),
        [format!(
            "{}: byte 0: not a glTF file: it starts with \"glTX\", expected the binary glTF magic \"glTF\" or a JSON object",
            at("wrong_magic.glb")
        )]
    );
    // A .gltf's error is at the element's line and column: the buffer's uri.
    assert_eq!(
        load_errors("missing_buffer.gltf"),
        [format!(
            "{DIR}/missing_buffer.gltf:78:14: error: invalid glTF file: buffers[0].uri: cannot read \"{DIR}/nowhere.bin\": file not found"
        )]
    );
    // gltf-json 1.4's validator indexes the POSITION accessor unchecked: a panic before.
    assert_eq!(
        load_errors("missing_position_accessor.gltf"),
        [format!(
            "{}: meshes[0].primitives[0].attributes.POSITION: invalid glTF: accessor 0 is out of range: the file has 0 accessors",
            located("missing_position_accessor.gltf", "6:78")
        )]
    );
    // The glTF crate's `Image::source` unwraps these: a panic before.
    assert_eq!(
        load_errors("image_without_source.gltf"),
        [format!(
            "{}: images[0]: invalid glTF: an image needs a uri or a bufferView",
            located("image_without_source.gltf", "47:3")
        )]
    );
    assert_eq!(
        load_errors("image_view_without_mime_type.gltf"),
        [format!(
            "{}: images[0]: invalid glTF: an image in a bufferView needs its mimeType",
            located("image_view_without_mime_type.gltf", "47:3")
        )]
    );
    let mesh_error = |f: &str, object: &str, message: &str| {
        [format!(
            "{} \"{DIR}/{f}\": {message}\n  help: loaded for object \"{object}\" at {DIR}/{f}:1:1",
            at(f)
        )]
    };
    assert_eq!(
        load_errors("bad_accessor.glb"),
        mesh_error(
            "bad_accessor.glb",
            "tri_mesh",
            "accessors[0]: POSITION: 1000 elements of 12 bytes from byte 0 (stride 12) run past the end of bufferViews[0] (36 bytes)"
        )
    );
    assert_eq!(
        load_errors("bad_index.glb"),
        mesh_error(
            "bad_index.glb",
            "tri_mesh",
            "accessors[3]: index 7 (element 2) is out of range: the primitive has 3 vertices"
        )
    );
    // A NaN in POSITION (glTF allows none in accessor data) was a dropped triangle and a
    // vertex count that no longer matched the primitive's.
    assert_eq!(
        load_errors("nan_position.glb"),
        mesh_error(
            "nan_position.glb",
            "quad_mesh",
            "accessors[0]: POSITION of meshes[0].primitives[0]: vertex 3 is (NaN, 1, 0): a vertex position must be a finite number"
        )
    );
    assert_eq!(
        load_errors("points.glb"),
        mesh_error(
            "points.glb",
            "dots_mesh",
            "meshes[0].primitives[0]: primitive mode Points is not supported: only triangles (mode 4, TRIANGLES; 5, TRIANGLE_STRIP; 6, TRIANGLE_FAN)"
        )
    );
}

/// A mesh named in a RON scene that the file does not hold lists what it holds.
#[test]
fn an_unknown_mesh_name_lists_the_meshes() {
    let text = r#"Scene(
    objects: [(name: "thing", mesh: Gltf(file: "hierarchy.glb", mesh: "teapot"))],
    instances: [(name: "t1", of: "thing")],
    groups: [(name: "world", members: ["t1"])],
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
    render: (root: "world", camera: "cam"),
)"#;
    let errors = stagelight::scene::load_scene_str(text, &Path::new(DIR).join("s.ron"))
        .err()
        .expect("refused");
    assert_eq!(
        errors.0[0].to_string(),
        format!(
            "{DIR}/s.ron:2:48: error: invalid glTF file \"{DIR}/hierarchy.glb\": meshes: no mesh named \"teapot\"; the file holds \"tri\"\n  help: loaded for object \"thing\" at {DIR}/s.ron:2:48"
        )
    );
    // An index past the file's meshes says so (it said "no mesh named").
    let errors = stagelight::scene::load_scene_str(
        &text.replace("teapot", "#9"),
        &Path::new(DIR).join("s.ron"),
    )
    .err()
    .expect("refused");
    assert_eq!(
        errors.0[0].to_string(),
        format!(
            "{DIR}/s.ron:2:48: error: invalid glTF file \"{DIR}/hierarchy.glb\": meshes: mesh \"#9\" is out of range: the file has one mesh (\"#0\"): \"tri\"\n  help: loaded for object \"thing\" at {DIR}/s.ron:2:48"
        )
    );
}

/// A RON scene that includes `hierarchy.glb` places the file's root group (`scene`) where it
/// wants, under its own group; the file's camera and light come in, its render entry does
/// not compete with the includer's.
#[test]
fn a_ron_scene_places_an_included_gltf_files_nodes_under_its_group() {
    let text = r#"Scene(
    include: ["hierarchy.glb"],
    instances: [(name: "level", of: "scene", transform: [Translate((1, 0.5, 0))])],
    groups: [(name: "top", members: ["level"])],
    render: (root: "top", camera: "view"),
)"#;
    let scene = stagelight::scene::load_scene_str(text, &Path::new(DIR).join("inc.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut placed: Vec<(String, Vec3)> = scene
        .world
        .query::<(&stagelight::components::Name, &Instance, &WorldFromObject)>()
        .iter()
        .map(|(n, _, w)| (n.0.clone(), Vec3::from(w.0.translation)))
        .collect();
    placed.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));
    let at: Vec<Vec3> = placed.iter().map(|p| p.1).collect();
    assert_eq!(
        at,
        [
            Vec3::new(-1.0, 0.5, -5.0),
            Vec3::new(1.0, 0.5, -5.0),
            Vec3::new(3.0, 0.5, -5.0)
        ]
    );
    assert!(
        placed.iter().all(|p| p.0.starts_with("top/level/")),
        "{placed:?}"
    );
    let lights = scene
        .world
        .query::<&stagelight::components::Emitter>()
        .iter()
        .count();
    assert_eq!(lights, 1, "the file's punctual light");
}

/// One mesh used by three nodes under a translated parent: three placements of one shared
/// mesh, at the composed translations; the first camera and the punctual light are read.
#[test]
fn a_shared_mesh_under_a_parent_gives_three_placements() {
    let scene = stagelight::scene::load_scene(&Path::new(DIR).join("hierarchy.glb"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut placed: Vec<(Vec3, *const TriMesh)> = scene
        .world
        .query::<(&Instance, &WorldFromObject)>()
        .iter()
        .map(|(i, w)| (Vec3::from(w.0.translation), Arc::as_ptr(&i.mesh)))
        .collect();
    placed.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
    let at: Vec<Vec3> = placed.iter().map(|p| p.0).collect();
    assert_eq!(
        at,
        [
            Vec3::new(-2.0, 0.0, -5.0),
            Vec3::new(0.0, 0.0, -5.0),
            Vec3::new(2.0, 0.0, -5.0)
        ]
    );
    assert!(placed.iter().all(|p| p.1 == placed[0].1), "one shared mesh");
    let desc = stagelight::scene::import::gltf_scene::read(
        &Path::new(DIR).join("hierarchy.glb"),
        &std::fs::read(Path::new(DIR).join("hierarchy.glb")).unwrap(),
    )
    .unwrap()
    .desc;
    assert_eq!(desc.cameras[0].name, "view");
    assert_eq!(desc.cameras[0].resolution, (640, 320), "aspect ratio 2");
    assert!((desc.cameras[0].fov_y - 0.8f64.to_degrees()).abs() < 1e-4);
    assert_eq!(desc.lights.len(), 1);
    assert_eq!(desc.lights[0].intensity, 1.0, "683 cd = 1 W/sr");
    assert!(
        desc.environment.is_none(),
        "a lit file gets no default light"
    );
}

fn bake_covered(uvs: &str) -> u64 {
    let text = format!(
        r#"Scene(
    objects: [(name: "quad", mesh: Gltf(file: "two_uv_sets.glb"))],
    instances: [(name: "q", of: "quad", bake: (resolution: (8, 8), uvs: {uvs}, padding: 0,
        outputs: [(kind: AmbientOcclusion(samples: 4))]))],
    groups: [(name: "world", members: ["q"])],
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
    render: (root: "world", camera: "cam"),
)"#
    );
    let mut scene = stagelight::scene::load_scene_str(&text, &Path::new(DIR).join("bake.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut frame = Frame::new(scene.settings.clone());
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    frame.inputs.bake_dir = crate::common::scratch_root().join(format!(
        "stagelight-gltf-bake-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    frame.inputs.hold_files = true;
    stagelight::systems::run(&mut scene.world, &mut frame).expect("bake");
    let reports = frame.outputs.bake_reports;
    let _ = std::fs::remove_dir_all(&frame.inputs.bake_dir);
    reports[0].covered_texels
}

/// `uvs: MeshSet(1)` bakes on TEXCOORD_1 (a quarter of the page), `MeshSet(0)` on
/// TEXCOORD_0 (all of it).
#[test]
fn a_bake_on_uv_set_one_covers_the_second_set() {
    assert_eq!(bake_covered("MeshSet(0)"), 64);
    assert_eq!(bake_covered("MeshSet(1)"), 16);
}

/// `uvs: MeshSet(1)` on a mesh without TEXCOORD_1 is refused at load.
#[test]
fn a_missing_second_uv_set_is_a_load_error() {
    let text = r#"Scene(
    objects: [(name: "box", mesh: Gltf(file: "box.glb"))],
    instances: [(name: "b", of: "box", bake: (resolution: (8, 8), uvs: MeshSet(1),
        outputs: [(kind: AmbientOcclusion(samples: 4))]))],
    groups: [(name: "world", members: ["b"])],
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
    render: (root: "world", camera: "cam"),
)"#;
    let errors = stagelight::scene::load_scene_str(text, &Path::new(DIR).join("s.ron"))
        .err()
        .expect("refused");
    assert_eq!(
        errors.0[0].message,
        "`uvs: MeshSet(1)`, but the mesh of \"b\" has no texture coordinates of set 1"
    );
}

/// The CLI renders a glTF file as a scene, with its camera's output named after the file.
#[test]
fn the_cli_renders_a_glb_scene() {
    let dir = crate::common::cli::scratch("gltf_cli_render");
    let glb = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(DIR)
        .join("hierarchy.glb");
    let out = dir.join("h.png");
    let o = crate::common::cli::run(crate::common::cli::bin().args([
        "render",
        glb.to_str().unwrap(),
        "--spp",
        "1",
        "-o",
        out.to_str().unwrap(),
    ]));
    assert!(o.status.success(), "{}", crate::common::cli::stderr(&o));
    assert!(out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Whatever bytes the mesh reader gets, it returns a checked mesh or an error (the fuzz
/// target's property, on the corpus).
#[test]
fn the_fuzz_corpus_reads_or_reports() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/gltf");
    for entry in std::fs::read_dir(&dir).unwrap() {
        let bytes = std::fs::read(entry.unwrap().path()).unwrap();
        let format = stagelight::scene::mesh_files::MeshFormat::Gltf;
        if let Ok(mesh) = stagelight::scene::parse_mesh_bytes(format, &bytes) {
            let n = mesh.positions.len() as u32;
            assert!(mesh.triangles.iter().all(|t| t.iter().all(|&i| i < n)));
        }
        let path = Path::new("fuzz.glb");
        if let Err(errors) = stagelight::scene::import::gltf_scene::read(path, &bytes) {
            assert!(!errors.errors.is_empty());
        }
    }
}

/// `stagelight bake model.glb --write-gltf` writes `DIR/model.glb`: the gltf crate reads it
/// back, the primitive's material has the AO as `occlusionTexture` and the lightmap as
/// `MSFT_lightmap`, both on TEXCOORD_1, and the embedded bytes are the baked PNG files.
#[test]
fn a_baked_glb_embeds_the_baked_pngs() {
    use crate::common::cli;
    let dir = cli::scratch("gltf_write_gltf");
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(DIR)
        .join("two_uv_sets.glb");
    let o = cli::run(cli::bin().args([
        "bake",
        source.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
        "--write-gltf",
    ]));
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let bytes = std::fs::read(dir.join("two_uv_sets.glb")).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    let view_bytes = |image: gltf::Image<'_>| -> Vec<u8> {
        let gltf::image::Source::View { view, mime_type } = image.source() else {
            panic!("the image is embedded");
        };
        assert_eq!(mime_type, "image/png");
        blob[view.offset()..view.offset() + view.length()].to_vec()
    };
    let node = glb.nodes().find(|n| n.name() == Some("quad")).unwrap();
    let prim = node.mesh().unwrap().primitives().next().unwrap();
    let material = prim.material();
    let occlusion = material.occlusion_texture().expect("occlusionTexture");
    assert_eq!(occlusion.tex_coord(), 1);
    let ao = std::fs::read(dir.join("quad_ao.png")).unwrap();
    assert!(view_bytes(occlusion.texture().source()) == ao);
    // The lightmap, through the JSON (MSFT_lightmap is not modelled by the gltf crate).
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let m = &json["materials"][material.index().unwrap()];
    let lightmap = &m["extensions"]["MSFT_lightmap"]["lightmapTexture"];
    assert_eq!(lightmap["texCoord"], 1);
    let texture = glb
        .textures()
        .nth(lightmap["index"].as_u64().unwrap() as usize)
        .unwrap();
    let baked = std::fs::read(dir.join("quad_lightmap.png")).unwrap();
    assert!(view_bytes(texture.source()) == baked);
    // The geometry is the source's: the copy re-reads to the same mesh.
    let pick = stagelight::scene::mesh_files::gltf_file::MeshPick {
        mesh: Some(format!("#{}", node.mesh().unwrap().index())),
        primitive: None,
    };
    let copy = stagelight::scene::mesh_files::gltf_file::parse(&bytes, None, &pick);
    let original = stagelight::scene::mesh_files::gltf_file::parse(
        &std::fs::read(&source).unwrap(),
        None,
        &Default::default(),
    );
    assert_eq!(copy.unwrap(), original.unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two baked nodes sharing a mesh and its material: the baked copy gives each its own mesh
/// and material with its own textures, and leaves no mesh or material unused (the last node
/// takes the original; the copy kept the original mesh and material unused, which glTF
/// validators flag).
#[test]
fn a_baked_glb_leaves_no_mesh_or_material_unused() {
    use crate::common::cli;
    use crate::gltf_spec::{quad, LIST, MATERIAL, PLAIN_UVS};
    let dir = cli::scratch("gltf_write_gltf_shared");
    let text = quad(PLAIN_UVS, &LIST)
        .replace(
            "PRIMITIVE",
            r#"{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 1}, "indices": 3, "material": 0}"#,
        )
        .replace("MATERIALS", MATERIAL)
        .replace(
            "NODES",
            r#"{"name": "a", "mesh": 0}, {"name": "b", "mesh": 0, "translation": [2, 0, 0]}"#,
        )
        .replace("ROOTS", "0, 1");
    let source = crate::gltf_spec::write(&dir, "shared.gltf", &text);
    let out = dir.join("out");
    let o = cli::run(cli::bin().args([
        "bake",
        source.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--write-gltf",
        "--threads",
        "1",
    ]));
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let bytes = std::fs::read(out.join("shared.glb")).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let nodes = json["nodes"].as_array().unwrap();
    let meshes: Vec<u64> = nodes.iter().map(|n| n["mesh"].as_u64().unwrap()).collect();
    assert_eq!(json["meshes"].as_array().unwrap().len(), 2);
    assert_ne!(meshes[0], meshes[1]);
    let materials: Vec<u64> = meshes
        .iter()
        .map(|&m| {
            json["meshes"][m as usize]["primitives"][0]["material"]
                .as_u64()
                .unwrap()
        })
        .collect();
    assert_eq!(json["materials"].as_array().unwrap().len(), 2);
    assert_ne!(materials[0], materials[1]);
    let occlusion: Vec<&serde_json::Value> = materials
        .iter()
        .map(|&m| &json["materials"][m as usize]["occlusionTexture"]["index"])
        .collect();
    assert_ne!(occlusion[0], occlusion[1]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The example asset loads with a default bake request on each of its three primitive
/// instances (all have TEXCOORD_1), its camera and its light.
#[test]
fn the_room_asset_loads_with_its_bake_requests() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/gltf/lightmap_room.glb");
    let scene = stagelight::scene::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let mut names: Vec<String> = scene
        .world
        .query::<&stagelight::components::BakeRequest>()
        .iter()
        .map(|r| r.name.clone())
        .collect();
    names.sort();
    assert_eq!(names, ["crate", "floor", "walls"]);
    assert_eq!(scene.located_warnings, Vec::<String>::new());
}

/// A file without a camera is framed by the default camera: it looks at the centre of the
/// bounds from +Z, raised by 20°.
#[test]
fn a_file_without_a_camera_gets_the_default_framing() {
    let path = Path::new(DIR).join("box.glb");
    let desc = stagelight::scene::import::gltf_scene::read(&path, &std::fs::read(&path).unwrap())
        .unwrap()
        .desc;
    let camera = &desc.cameras[0];
    assert_eq!(camera.name, "default_camera");
    let stagelight::scene::desc::PlacementDesc::LookAt { eye, target, .. } = camera.placement
    else {
        panic!("a look-at placement");
    };
    // box.glb spans (0.3, 0.1, −0.3) … (1.3, 0.9, 0.9).
    let centre = (0.8, 0.5, 0.3);
    assert!((target.0 - centre.0).abs() < 1e-6 && (target.2 - centre.2).abs() < 1e-6);
    let (dy, dz) = (eye.1 - target.1, eye.2 - target.2);
    assert!((dy.atan2(dz).to_degrees() - 20.0).abs() < 1e-6);
    assert!(
        desc.environment.is_some(),
        "no lights: the white environment"
    );
}
