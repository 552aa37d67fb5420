//! mental ray's `$include` is textual: inside a block it reads the file in place (a
//! camera's statements, a group's vectors), errors in the included file are located there,
//! and a cycle or a missing file is an error at the file name.

use std::path::{Path, PathBuf};

use stagelight::scene::load_scene;

const MAIN: &str = "options \"opt\"
object space
end options
camera \"cam\"
$include \"camera_body.mi\"
end camera
light \"lamp\" \"mib_light_point\" (\"color\" 1 1 1) origin 0 0 0 end light
material \"mtl\" \"mib_illum_lambert\" (\"diffuse\" 0.8 0.8 0.8, \"lights\" [\"lamp_inst\"]) end material
object \"quad\" group
$include \"vectors.mi\"
v 0 v 1 v 2 v 3
p \"mtl\" 0 3 2 1
end group end object
instance \"cam_inst\" \"cam\" end instance
instance \"lamp_inst\" \"lamp\" end instance
instance \"quad_inst\" \"quad\" end instance
instgroup \"root\" \"cam_inst\" \"lamp_inst\" \"quad_inst\" end instgroup
render \"root\" \"cam_inst\" \"opt\"
";

const VECTORS: &str = "1 1 -1  1 -1 -1\n-1 -1 -1  -1 1 -1\n";

fn dir(name: &str) -> PathBuf {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight_mi_include_{name}_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `files` into `dir` and loads `main.mi`: the scene, or its messages with `dir/`
/// left out.
fn load(dir: &Path, files: &[(&str, &str)]) -> Result<stagelight::scene::LoadedScene, String> {
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    load_scene(&dir.join("main.mi")).map_err(|e| {
        e.to_string()
            .replace(&format!("{}/", dir.display()), "")
            .trim_end()
            .to_string()
    })
}

#[test]
fn an_include_inside_a_block_is_read_in_place() {
    let dir = dir("ok");
    let scene = load(
        &dir,
        &[
            ("main.mi", MAIN),
            ("camera_body.mi", "resolution 4 3\nfocal 1\naperture 1\n"),
            ("vectors.mi", VECTORS),
        ],
    )
    .unwrap();
    let camera = stagelight::scene_view::render_view(&scene.world)
        .unwrap()
        .camera;
    assert_eq!((camera.width, camera.height), (4, 3));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn errors_inside_a_block_include_are_located_in_the_included_file() {
    let dir = dir("bad");
    let vectors = ("vectors.mi", VECTORS);
    let cases = [
        (
            "resolution 0 3\nfocal 1\naperture 1\n",
            "camera_body.mi:1:12: error: resolution width must be at least 1, found 0\n  help: the image is width × height pixels, each at least 1: `resolution 640 480`",
        ),
        (
            "resolution 4 3\nfocul 1\n",
            "camera_body.mi:2:1: error: unknown camera statement \"focul\"\n  help: did you mean \"focal\"?",
        ),
        (
            "$include \"camera_body.mi\"\n",
            "camera_body.mi:1:10: error: \"camera_body.mi\" includes itself",
        ),
        (
            "$include \"nowhere.mi\"\n",
            "camera_body.mi:1:10: error: cannot read include \"nowhere.mi\": file not found",
        ),
    ];
    for (body, want) in cases {
        let got = load(
            &dir,
            &[("main.mi", MAIN), ("camera_body.mi", body), vectors],
        );
        assert_eq!(got.err().as_deref(), Some(want), "{body}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
