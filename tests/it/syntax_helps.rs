//! Helps that name what to write in the scene are written in the scene's own format: a RIB
//! or glTF scene is not told to add RON fields it cannot hold (it is told what its format
//! does instead, or to convert to RON first), a `.mi` scene gets `.mi` statements. Tester
//! report 45, problem 3.

use std::path::Path;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// A RIB scene: a lit sphere seen by the one camera a RIB file declares.
const RIB: &str = "Display \"out.png\" \"file\" \"rgb\"\nFormat 16 12 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\nLightSource \"pointlight\" 1 \"from\" [0 2 -2] \"intensity\" 4\nSphere 1 -1 1 360\nWorldEnd\n";

/// A `.mi` scene with two cameras, `Front_inst` rendered and `Side_inst`.
const MI: &str = r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space end options
camera "Cam" output "rgb" "png" "out.png" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "Front_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
instance "Side_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -6 1 end instance
material "m" opaque "mib_illum_lambert" ("ambient" 1 1 1) end material
object "Tri" group 0 0 0  1 0 0  0 1 0  v 0 v 1 v 2  p "m" 0 1 2 end group end object
instance "Tri_inst" "Tri" material "m" end instance
instgroup "root" "Front_inst" "Side_inst" "Tri_inst" end instgroup
render "root" "Front_inst" "opt"
"#;

/// Writes the scene `name` (`text`) in a fresh directory and runs `args` there: the exit
/// code and stderr.
fn run(test: &str, name: &str, text: &str, args: &[&str]) -> (Option<i32>, String) {
    let dir = scratch_dir(test);
    std::fs::write(dir.join(name), text).unwrap();
    let o = run_in(&dir, args);
    assert!(!dir.join("p1.exr").exists() && !dir.join("l.svg").exists());
    (o.status.code(), stderr_of(&o))
}

/// `-o x.svg` without contour shaders: RIB has none, so its help converts the scene to RON
/// first; `.mi` and RON say what to add in their own syntax.
#[test]
fn a_vector_output_without_contour_shaders_is_helped_in_the_scenes_format() {
    let (code, err) = run(
        "help-svg-rib",
        "s.rib",
        RIB,
        &["render", "s.rib", "-o", "l.svg"],
    );
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: -o l.svg writes contour lines, but no material of the scene has a contour shader\n  \
         help: RIB has no contour shaders: write the scene as RON (`stagelight convert s.rib -o s.ron`) \
         and give a material `contour: Simple(color: (0, 0, 0, 1), width: 0.5)` there, or write a .png or .exr\n"
    );
    let (code, err) = run(
        "help-svg-mi",
        "c.mi",
        MI,
        &["render", "c.mi", "-o", "l.svg"],
    );
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: -o l.svg writes contour lines, but no material of the scene has a contour shader\n  \
         help: add `contour store \"contour_store_function\" ()` and `contour contrast \"contour_contrast_function_levels\" ()` \
         to the options and `contour \"contour_shader_simple\" (\"color\" 0 0 0 1, \"width\" 0.5)` to a material, \
         or write a .png or .exr\n"
    );
}

/// `--camera` with `--part`: the help says how the scene's format chooses its render
/// camera — the `.mi` `render` statement's camera instance, RON's `render: (camera: …)`;
/// a RIB file declares one camera.
#[test]
fn camera_with_part_names_how_each_format_chooses_its_render_camera() {
    let args = |scene: &'static str, camera: &'static str| {
        [
            "render", scene, "--camera", camera, "--part", "1/2", "-o", "p1.exr",
        ]
    };
    let refusal = "error: --camera cannot be combined with --part\n  help: the merge job renders the scene's render camera; ";
    let (code, err) = run("help-camera-mi", "c.mi", MI, &args("c.mi", "Side_inst"));
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        format!("{refusal}name that camera instance in the scene's `render` statement instead (`render \"…\" \"Side_inst\" \"…\"`)\n")
    );
    let (code, err) = run("help-camera-rib", "s.rib", RIB, &args("s.rib", "camera"));
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        format!("{refusal}a RIB file declares one camera (the transformation current at `WorldBegin`, named \"camera\"): leave out --camera\n")
    );
    let ron = crate::common::cli::small_scene(
        &crate::common::cli::quad_object("quad"),
        "(name: \"q\", of: \"quad\")",
        "(file: \"out.png\")",
        "",
    );
    let (code, err) = run("help-camera-ron", "s.ron", &ron, &args("s.ron", "cam"));
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        format!("{refusal}set `render: (camera: \"cam\")` in the scene instead\n")
    );
}

/// `stagelight photons` helps in the scene's format: where to keep the maps (`.mi`'s
/// `photonmap file`; a RIB file names none) and how to turn a map on (AIR's caustic light).
#[test]
fn photon_helps_are_written_in_the_scenes_format() {
    let (code, err) = run("help-photons-mi", "c.mi", MI, &["photons", "c.mi"]);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: nowhere to keep the photon maps of c.mi\n  help: give --photon-cache DIR, or add `photonmap file \"scene.pmap\"` to the options block\n"
    );
    let (code, err) = run("help-photons-rib", "s.rib", RIB, &["photons", "s.rib"]);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: nowhere to keep the photon maps of s.rib\n  help: give --photon-cache DIR (a RIB file names no photon map file)\n"
    );
    let cache = ["photons", "s.rib", "--photon-cache", "cache"];
    let (code, err) = run("help-photons-rib-off", "s.rib", RIB, &cache);
    assert_eq!(code, Some(1), "{err}");
    assert_eq!(
        err,
        "error: s.rib traces no photons: caustics and global illumination are off\n  help: photon maps are built for caustics or global illumination, with the Direct integrator: add AIR's caustic light, `LightSource \"caustic\" 1`, which turns the caustic photon map on\n"
    );
    let view = ["render", "s.rib", "--diagnostic", "photon:density:1000"];
    let (code, err) = run("help-photon-view-rib", "s.rib", RIB, &view);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: the photon diagnostic shows the photon maps, but this scene builds none (caustics and global illumination are off)\n  help: add AIR's caustic light, `LightSource \"caustic\" 1`, which turns the caustic photon map on\n"
    );
}

/// `bake` of a scene whose format cannot ask for bakes converts it to RON first.
#[test]
fn a_bake_of_a_mi_or_rib_scene_converts_it_to_ron_first() {
    for (name, text) in [("c.mi", MI), ("s.rib", RIB)] {
        let stem = Path::new(name).with_extension("ron");
        let (code, err) = run("help-bake", name, text, &["bake", name]);
        assert_eq!(code, Some(1), "{err}");
        let format = if name.ends_with(".mi") { ".mi" } else { "RIB" };
        assert_eq!(
            err,
            format!(
                "error: {name} has no bake requests\n  help: a {format} file asks for no bakes: write the scene as RON (`stagelight convert {name} -o {}`) and add `bake: (resolution: (512, 512), outputs: [(kind: AmbientOcclusion())])` to an instance there\n",
                stem.display()
            )
        );
    }
}
