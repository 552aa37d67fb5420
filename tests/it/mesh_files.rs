//! Mesh files through the scene loader: what a bad file reports (exact messages, located in
//! the mesh file, with the scene position that loads it) and what a good one builds.

use std::path::Path;
use std::sync::Arc;

use glam::Vec3;
use stagelight::components::TriMesh;
use stagelight::scene::mesh_files::MeshFormat;

const DIR: &str = "tests/fixtures/meshes";

/// A scene whose one object loads `mesh` (a RON mesh value) from [`DIR`]; a file name in
/// `Obj(file: …)` or `Ply(file: …)` is at line 2, column 47.
fn scene(mesh: &str) -> String {
    format!(
        r#"Scene(
    objects: [(name: "thing", mesh: {mesh})],
    instances: [(name: "t1", of: "thing")],
    groups: [(name: "world", members: ["t1"])],
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn load(mesh: &str) -> Result<stagelight::scene::LoadedScene, Vec<String>> {
    stagelight::scene::load_scene_str(&scene(mesh), &Path::new(DIR).join("scene.ron"))
        .map_err(|e| e.0.iter().map(|d| d.to_string()).collect())
}

/// The diagnostics of loading `file` as an OBJ mesh.
fn obj_errors(file: &str) -> Vec<String> {
    match load(&format!("Obj(file: \"{file}\")")) {
        Ok(_) => panic!("{file} loaded"),
        Err(e) => e,
    }
}

fn expect(file: &str, at: &str, message: &str) {
    assert_eq!(
        obj_errors(file),
        [format!(
            "{DIR}/{file}:{at}: error: invalid OBJ file \"{DIR}/{file}\": {message}\n  \
             help: loaded for object \"thing\" at {DIR}/scene.ron:2:47"
        )]
    );
}

/// The mesh of the scene's one object.
fn mesh_of(scene: &stagelight::scene::LoadedScene) -> TriMesh {
    let mut query = scene.world.query::<&Arc<TriMesh>>();
    let meshes: Vec<TriMesh> = query.iter().map(|m| (**m).clone()).collect();
    assert_eq!(meshes.len(), 1);
    meshes.into_iter().next().unwrap()
}

/// Binary data is not an empty mesh: the first line's first word is not an OBJ statement.
#[test]
fn binary_data_is_not_obj() {
    expect("not_obj.png", "1:1", "\"\\x89PNG\" is not an OBJ statement");
}

/// Prose is not an empty mesh either.
#[test]
fn prose_is_not_obj() {
    expect("prose.txt", "1:1", "\"This\" is not an OBJ statement");
}

/// A PLY file named as an OBJ file is located at its magic word.
#[test]
fn a_ply_file_is_not_obj() {
    expect(
        "tri_ascii.ply",
        "1:1",
        "\"ply\" is not an OBJ statement: this is a PLY file (load it with Ply(file: …))",
    );
}

/// A face naming a texture coordinate the file does not have.
#[test]
fn face_with_missing_vt() {
    expect(
        "missing_vt.obj",
        "6:11",
        "texture coordinate index 3 is out of range: the file has 2 texture coordinates",
    );
}

/// A face naming normals in a file without any.
#[test]
fn face_with_missing_vn() {
    expect(
        "missing_vn.obj",
        "4:3",
        "normal index 1 is out of range: the file has no \"vn\" lines",
    );
}

/// Texture coordinates and normals that some faces name and one does not are dropped for the
/// whole mesh with a warning at the object's mesh naming the face vertex that lacks them
/// (they were dropped silently, and a bake with `uvs: Mesh` then said the mesh had none).
#[test]
fn attributes_some_faces_leave_out_are_dropped_with_a_warning() {
    let scene = load("Obj(file: \"partial_vt_vn.obj\")").unwrap_or_else(|e| panic!("{e:?}"));
    let mesh = mesh_of(&scene);
    assert_eq!((mesh.uvs.is_some(), mesh.normals.is_some()), (false, false));
    assert_eq!(
        scene.located_warnings,
        [
            format!("{DIR}/scene.ron:2:37: warning: mesh \"thing\": has no texture coordinates: the face vertex at partial_vt_vn.obj:14:3 names no `vt` while others do\n  help: a mesh keeps texture coordinates only when every face vertex names one: give that face's vertices `vt` indices"),
            format!("{DIR}/scene.ron:2:37: warning: mesh \"thing\": has no normals: the face vertex at partial_vt_vn.obj:14:3 names no `vn` while others do\n  help: a mesh keeps normals only when every face vertex names one: give that face's vertices `vn` indices"),
        ]
    );
    // A file whose faces all name them keeps them, with no warning.
    let scene = load("Obj(file: \"box.obj\")").unwrap_or_else(|e| panic!("{e:?}"));
    assert!(mesh_of(&scene).uvs.is_some());
    assert!(
        scene.located_warnings.is_empty(),
        "{:?}",
        scene.located_warnings
    );
}

/// An object name that is not UTF-8 is an error at its first bad byte.
#[test]
fn name_that_is_not_utf8() {
    expect("latin1_name.obj", "4:6", "the object name is not UTF-8");
}

/// Bytes that are not UTF-8 in comments do not matter.
#[test]
fn comments_may_hold_any_bytes() {
    let scene = load("Obj(file: \"latin1_comment.obj\")").unwrap();
    let m = mesh_of(&scene);
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
    assert_eq!(m.positions[1], glam::Vec3::new(1.0, 0.0, 0.0));
}

/// A missing file is reported at the file name in the scene, with its resolved path.
#[test]
fn missing_file() {
    assert_eq!(
        obj_errors("nothing.obj"),
        [format!(
            "{DIR}/scene.ron:2:47: error: cannot read OBJ file \"{DIR}/nothing.obj\": file not found\n  \
             help: \"nothing.obj\" is read relative to {DIR}/scene.ron, the file that names it"
        )]
    );
}

/// The diagnostics of loading `file` as a PLY mesh.
fn ply_errors(file: &str) -> Vec<String> {
    match load(&format!("Ply(file: \"{file}\")")) {
        Ok(_) => panic!("{file} loaded"),
        Err(e) => e,
    }
}

/// A box of quads with an octagonal lid, normals and UVs: `box.obj` and the same mesh
/// written as PLY by `plyfile` (`scripts/make_mesh_fixtures.py`), ASCII and binary of both
/// byte orders, load to the same bits and render the same bytes.
#[test]
fn obj_and_ply_render_the_same_bytes() {
    let render = |mesh: &str| {
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
        let mut scene =
            stagelight::scene::load_scene_str(&text, &Path::new(DIR).join("render.ron"))
                .unwrap_or_else(|e| panic!("{mesh}: {e}"));
        assert_eq!(scene.located_warnings, Vec::<String>::new());
        let mesh = mesh_of(&scene);
        let mut frame = stagelight::frame::Frame::new(scene.settings.clone());
        let stages: Vec<_> = stagelight::systems::STAGES
            .iter()
            .copied()
            .filter(|s| s.name != "write_output")
            .collect();
        stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame).expect("render");
        let beauty: Vec<[u32; 3]> = frame
            .outputs
            .image
            .expect("an image")
            .beauty
            .iter()
            .map(|c| c.to_array().map(f32::to_bits))
            .collect();
        (mesh, beauty)
    };
    let (obj, obj_image) = render("Obj(file: \"box.obj\")");
    assert_eq!((obj.positions.len(), obj.triangles.len()), (28, 16));
    assert!(obj.normals.is_some() && obj.uvs.is_some());
    assert!(obj_image.iter().any(|c| c[0] != 0), "the box is lit");
    for file in ["box_ascii.ply", "box_le.ply", "box_be.ply"] {
        let (ply, ply_image) = render(&format!("Ply(file: \"{file}\")"));
        assert_eq!(format!("{ply:?}"), format!("{obj:?}"), "{file}");
        assert!(ply_image == obj_image, "{file}: the images differ");
    }
}

/// A bad PLY header is an error at its line and column in the PLY file.
#[test]
fn ply_bad_header() {
    assert_eq!(
        ply_errors("missing_vt.obj"),
        [format!(
            "{DIR}/missing_vt.obj:1:1: error: invalid PLY file \"{DIR}/missing_vt.obj\": a PLY \
             file starts with the line \"ply\"\n  help: loaded for object \"thing\" at \
             {DIR}/scene.ron:2:47"
        )]
    );
}

/// An error in binary data is reported at the file name with its byte offset.
#[test]
fn ply_truncated_binary_data() {
    assert_eq!(
        ply_errors("truncated_le.ply"),
        [format!(
            "{DIR}/scene.ron:2:47: error: invalid PLY file \"{DIR}/truncated_le.ply\": at byte \
             1810: the file ends inside face 5 of the 6 faces the header declares (its \
             \"vertex_indices\" value)\n  help: loaded for object \"thing\" at {DIR}/scene.ron:2:47"
        )]
    );
}

/// A face that names a vertex the file does not have, in ASCII data.
#[test]
fn ply_index_out_of_range() {
    assert_eq!(
        ply_errors("bad_index.ply"),
        [format!(
            "{DIR}/bad_index.ply:14:7: error: invalid PLY file \"{DIR}/bad_index.ply\": face 0 \
             refers to vertex 3, but the file has 3 vertices\n  help: loaded for object \
             \"thing\" at {DIR}/scene.ron:2:47"
        )]
    );
}

/// Replays the PLY fuzz corpus (`fuzz/corpus/ply/`) through the fuzz target's checks.
#[test]
fn ply_corpus_parses_to_checked_meshes_or_errors() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/ply");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(files.len() >= 4, "{files:?}");
    let mut loaded = 0;
    for path in files {
        let bytes = std::fs::read(&path).unwrap();
        if let Ok(mesh) = stagelight::scene::parse_mesh_bytes(MeshFormat::Ply, &bytes) {
            let n = mesh.positions.len();
            assert!(
                mesh.triangles.iter().flatten().all(|&i| (i as usize) < n),
                "{}",
                path.display()
            );
            assert!(mesh.positions.iter().all(|p| p.is_finite()));
            loaded += 1;
        }
    }
    assert!(loaded >= 2);
}

/// A NaN or infinite vertex position is an error of `check` at its value in every mesh
/// format (PLY ASCII at line:column, binary PLY at its byte offset, OBJ at line:column),
/// instead of a warning about a dropped triangle and a vertex bake that fails late.
#[test]
fn non_finite_positions_fail_check_where_they_are() {
    use crate::common::cli::{run_in, scratch_dir, stderr_of};
    let dir = scratch_dir("mesh-nan");
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                end_header\n";
    std::fs::write(
        dir.join("nan.ply"),
        format!("{head}0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n"),
    )
    .unwrap();
    let binary_head = head.replace("ascii", "binary_little_endian");
    let mut binary = binary_head.clone().into_bytes();
    for x in [0.0f32, 0.0, 0.0, 1.0, 0.0, f32::INFINITY, 0.0, 1.0, 0.0] {
        binary.extend(x.to_le_bytes());
    }
    binary.push(3);
    for i in 0..3i32 {
        binary.extend(i.to_le_bytes());
    }
    std::fs::write(dir.join("inf_le.ply"), &binary).unwrap();
    std::fs::write(
        dir.join("nan.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 nan\nf 1 2 3\n",
    )
    .unwrap();
    // Vertex 1's z: after vertex 0 (12 bytes) and vertex 1's x and y.
    let z_at = binary_head.len() + 20;
    let cases = [
        (
            "Ply(file: \"nan.ply\")",
            "nan.ply:12:3: error: invalid PLY file \"nan.ply\": vertex 2 has y = NaN: a vertex position must be a finite number".to_string(),
        ),
        (
            "Ply(file: \"inf_le.ply\")",
            format!("scene.ron:2:47: error: invalid PLY file \"inf_le.ply\": at byte {z_at}: vertex 1 has z = inf: a vertex position must be a finite number"),
        ),
        (
            "Obj(file: \"nan.obj\")",
            "nan.obj:3:7: error: invalid OBJ file \"nan.obj\": position z = NaN: a vertex position must be a finite number".to_string(),
        ),
    ];
    for (mesh, expected) in cases {
        std::fs::write(dir.join("scene.ron"), scene(mesh)).unwrap();
        let o = run_in(&dir, &["check", "scene.ron"]);
        assert_eq!(o.status.code(), Some(1), "{mesh}");
        assert_eq!(
            stderr_of(&o),
            format!(
                "{expected}\n  help: loaded for object \"thing\" at scene.ron:2:47\n\
                 1 error in scene.ron\n"
            ),
            "{mesh}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// ASCII PLY data is one element per line; blank lines between the elements (here between
/// the vertex and the face block, as some exporters write) are skipped.
#[test]
fn blank_lines_in_ascii_ply_data_are_skipped() {
    let dir = crate::common::cli::scratch_dir("mesh-blank");
    std::fs::write(
        dir.join("blank.ply"),
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
         end_header\n0\t0 0\n1 0 0  \n0 1 0\n\n3 0 1 2\n",
    )
    .unwrap();
    let scene = stagelight::scene::load_scene_str(
        &scene("Ply(file: \"blank.ply\")"),
        &dir.join("scene.ron"),
    )
    .unwrap_or_else(|e| panic!("{}", e.0[0]));
    let mesh = mesh_of(&scene);
    assert_eq!(mesh.positions, [Vec3::ZERO, Vec3::X, Vec3::Y]);
    assert_eq!(mesh.triangles, [[0, 1, 2]]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A line ending in a backslash continues on the next (the OBJ specification's line
/// continuation): a quad written over three lines is two triangles.
#[test]
fn continued_lines_are_one_statement() {
    let loaded = load("Obj(file: \"continued.obj\")").expect("continued.obj loads");
    let mesh = mesh_of(&loaded);
    assert_eq!(mesh.triangles.len(), 2);
    assert!(mesh.positions.contains(&Vec3::new(1.0, 0.0, 0.0)));
}

/// An error inside a continued statement names the line and column where the word is.
#[test]
fn errors_in_continued_lines_keep_their_place() {
    expect(
        "continued_bad.obj",
        "5:5",
        "position index 9 is out of range: the file has 3 positions",
    );
}
