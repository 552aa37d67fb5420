//! Mesh files through the scene loader: what a bad file reports (exact messages, located in
//! the mesh file, with the scene position that loads it) and what a good one builds.

use std::path::Path;
use std::sync::Arc;

use stagelight::components::TriMesh;

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
    expect("tri_ascii.ply", "1:1", "\"ply\" is not an OBJ statement");
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
            "{DIR}/scene.ron:2:47: error: cannot read OBJ file \"{DIR}/nothing.obj\": file not found"
        )]
    );
}
