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

/// A `.mi` scene with contours on, a material whose contour shader has width `WIDTH`, and a
/// contour output.
const MI_CONTOURS: &str = r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space
  contour store "contour_store_function" ()
  contour contrast "contour_contrast_function_levels" ()
end options
camera "Cam" output "contour" "ps" "l.ps" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "Front_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
material "m" "mib_illum_lambert" ("ambient" 1 1 1) contour "contour_shader_simple" ("color" 0 0 0 1, "width" WIDTH) end material
object "Tri" group 0 0 0  1 0 0  0 1 0  v 0 v 1 v 2  p "m" 0 1 2 end group end object
instance "Tri_inst" "Tri" material "m" end instance
instgroup "root" "Front_inst" "Tri_inst" end instgroup
render "root" "Front_inst" "opt"
"#;

/// A `.mi` contour width that is not positive: the help writes the width as a `.mi`
/// parameter, not as RON's `width: 0.5`.
#[test]
fn a_mi_contour_width_that_is_not_positive_is_helped_in_mi_syntax() {
    let text = MI_CONTOURS.replace("WIDTH", "0");
    let (code, err) = run("help-contour-width-mi", "c.mi", &text, &["check", "c.mi"]);
    assert_eq!(code, Some(1), "{err}");
    assert_eq!(
        err,
        "c.mi:9:110: error: contour width must be positive, found 0\n  \
         help: widths are in percent of the smaller image dimension, e.g. `\"width\" 0.5`; \
         to draw no contours, leave out the material's `contour` shader\n1 error in c.mi\n"
    );
}

/// A `.mi` scene with a caustic map, a point light and a triangle flagged `caustic 1` whose
/// glass material has a shadow shader that lets light through.
const MI_CAUSTIC_CASTER: &str = r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space caustic on end options
camera "Cam" output "rgb" "png" "out.png" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "Front_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
light "L" "mib_light_point" ("color" 1 1 1) origin 0 2 -2 end light
instance "L_inst" "L" end instance
material "glass" "dielectric_material" ("ior" 1.5) shadow "mib_shadow_transparency" ("color" 1 1 1, "transp" 1) end material
object "Tri" caustic 1 group 0 0 0  1 0 0  0 1 0  v 0 v 1 v 2  p "glass" 0 1 2 end group end object
instance "Tri_inst" "Tri" material "glass" end instance
instgroup "root" "Front_inst" "L_inst" "Tri_inst" end instgroup
render "root" "Front_inst" "opt"
"#;

/// The RIB scene with AIR's caustic light and a half-transparent sphere with a caustic
/// refraction colour: it casts caustics and lets shadow rays through.
const RIB_CAUSTIC_CASTER: &str = "Display \"out.png\" \"file\" \"rgb\"\nFormat 16 12 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\nLightSource \"caustic\" 1\nLightSource \"pointlight\" 2 \"from\" [0 2 -2] \"intensity\" 4\nAttributeBegin\nOpacity 0.5 0.5 0.5\nAttribute \"caustic\" \"refractioncolor\" [0.9 0.9 0.9]\nSphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n";

/// A caustic caster whose material lets shadow rays through: `.mi` is told `caustic 0` or
/// `caustic 2` and to leave out the shadow shader; RIB, whose flag AIR's caustic colours
/// set, to make the primitive opaque or its caustic colours black.
#[test]
fn a_caustic_caster_that_passes_shadows_is_helped_in_the_scenes_format() {
    let (code, err) = run(
        "help-caustic-caster-mi",
        "c.mi",
        MI_CAUSTIC_CASTER,
        &["check", "c.mi"],
    );
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        err,
        "c.mi:9:1: warning: \"root/Tri_inst\" casts caustics (caustic 1) but its material \"glass\" \
         lets shadow rays through: the light it transmits is counted twice, by shadow rays and by \
         caustic photons\n  help: set `caustic 0` or `caustic 2` on it, or leave out the material's \
         `shadow` shader\n"
    );
    let (code, err) = run(
        "help-caustic-caster-rib",
        "s.rib",
        RIB_CAUSTIC_CASTER,
        &["check", "s.rib"],
    );
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        err,
        "s.rib:11:1: warning: \"world/sphere_1\" casts caustics but its material \"defaultsurface_1\" \
         lets shadow rays through: the light it transmits is counted twice, by shadow rays and by \
         caustic photons\n  help: make it opaque (`Opacity 1 1 1`), or make its `Attribute \"caustic\"` \
         colours black so that it casts no caustics\n"
    );
}

/// A `.mi` bilinear Bézier patch approximated `spatial 0.000001 0 12`: past a 1 MiB budget.
const MI_FINE_PATCH: &str = r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space end options
camera "Cam" output "rgb" "png" "out.png" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "Front_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
material "m" "mib_illum_lambert" ("ambient" 1 1 1) end material
object "Tri"
  basis "lin" bezier 1
  group 0 0 0  1 0 0  0 1 0  1 1 0  v 0 v 1 v 2 v 3
  surface "patch" "m" "lin" 0.0 1.0 0.0 1.0 "lin" 0.0 1.0 0.0 1.0 0 1 2 3
  approximate surface spatial 0.000001 0 12 "patch"
  end group
end object
instance "Tri_inst" "Tri" material "m" end instance
instgroup "root" "Front_inst" "Tri_inst" end instgroup
render "root" "Front_inst" "opt"
"#;

/// The RIB scene's sphere diced at `ShadingRate 0.0001` (subdivided up to 7 times).
fn rib_fine_sphere() -> String {
    RIB.replace("Sphere 1", "ShadingRate 0.0001\nSphere 1")
}

/// An adaptive approximation past the memory budget: `check`'s worst-case warning and
/// `render`'s refusal say how to bound it in `.mi` (the `approximate` statement's
/// subdivision bounds) and in RIB (RON's `max_subdiv`; a larger `ShadingRate`), and the
/// warning names the bound it reached as the format sets it (the `approximate` statement's
/// max subdivision, the subdivisions a `ShadingRate` allows; RON's `max_subdiv` stays in
/// `tests/it/hostile_budget.rs`).
#[test]
fn an_approximation_past_the_budget_is_helped_in_the_scenes_format() {
    let check = ["check", "c.mi", "--memory-limit", "1M"];
    let (code, err) = run("help-budget-mi", "c.mi", MI_FINE_PATCH, &check);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        err,
        "c.mi:10:3: warning: object \"Tri\": its adaptive approximation may make up to 33554432 \
         triangles (1 patch(es) × 4096² at the `approximate` statement's max subdivision 12, about \
         12.0 GiB), more than the 2730 the \
         memory budget of 1.0 MiB (--memory-limit) allows one object; render refuses it if dicing \
         makes more\n  help: adaptive rates usually stay far below this bound; to be sure it fits, \
         end the `approximate` technique with the subdivision bounds `0 5` (at most 2048 \
         triangles), or raise the budget with --memory-limit BYTES\n"
    );
    let render = ["render", "c.mi", "--memory-limit", "1M", "-o", "x.png"];
    let (code, err) = run("help-budget-mi-render", "c.mi", MI_FINE_PATCH, &render);
    assert_eq!(code, Some(1), "{err}");
    assert_eq!(
        err,
        "c.mi:10:3: error: object \"Tri\": its approximation would make 33554432 triangles, about \
         12.0 GiB, more than the 2730 the memory budget of 1.0 MiB (--memory-limit) allows one \
         object\n  help: coarsen the approximation (a larger `spatial` edge or `distance`, a \
         smaller max subdivision), or raise the budget with --memory-limit BYTES\n"
    );
    let check = ["check", "s.rib", "--memory-limit", "1M"];
    let (code, err) = run("help-budget-rib", "s.rib", &rib_fine_sphere(), &check);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        err,
        "s.rib:7:13: warning: object \"sphere_1\": its adaptive approximation may make up to 262144 \
         triangles (8 patch(es) × 128² at the 7 subdivisions a `ShadingRate` allows, about 96.0 \
         MiB), more than the 2730 the \
         memory budget of 1.0 MiB (--memory-limit) allows one object; render refuses it if dicing \
         makes more\n  help: adaptive rates usually stay far below this bound; to be sure it fits, \
         write the scene as RON and set `max_subdiv: 3` there (at most 1024 triangles; a RIB \
         `ShadingRate` subdivides up to 7 times), or raise the budget with --memory-limit BYTES\n"
    );
    let render = ["render", "s.rib", "--memory-limit", "1M", "-o", "x.png"];
    let (code, err) = run(
        "help-budget-rib-render",
        "s.rib",
        &rib_fine_sphere(),
        &render,
    );
    assert_eq!(code, Some(1), "{err}");
    assert_eq!(
        err,
        "s.rib:7:13: error: object \"sphere_1\": its approximation would make 262144 triangles, \
         about 96.0 MiB, more than the 2730 the memory budget of 1.0 MiB (--memory-limit) allows \
         one object\n  help: coarsen the dicing (a larger `ShadingRate`), or raise the budget with \
         --memory-limit BYTES\n"
    );
}

/// A glTF file: the quad of `gltf_spec` placed by one node (the default camera frames it).
fn gltf_quad() -> String {
    crate::gltf_spec::one_node(crate::gltf_spec::PRIMITIVE, r#"{"name": "q", "mesh": 0}"#)
}

/// The photon helps and `--camera` with `--part` for a glTF scene: it names no photon map
/// file, has no photon maps (convert to RON first) and renders the first camera of its
/// nodes (convert to RON to choose another).
#[test]
fn photon_and_camera_helps_of_a_gltf_scene_convert_it_to_ron_first() {
    let gltf = gltf_quad();
    let (code, err) = run("help-photons-gltf", "q.gltf", &gltf, &["photons", "q.gltf"]);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: nowhere to keep the photon maps of q.gltf\n  help: give --photon-cache DIR (a glTF file names no photon map file)\n"
    );
    let to_ron = "glTF has no photon maps: write the scene as RON (`stagelight convert q.gltf -o q.ron`) \
                  and turn on `caustics: (…)` or `global_illumination: (…)` in the scene's options there";
    let cache = ["photons", "q.gltf", "--photon-cache", "cache"];
    let (code, err) = run("help-photons-gltf-off", "q.gltf", &gltf, &cache);
    assert_eq!(code, Some(1), "{err}");
    assert_eq!(
        err,
        format!("error: q.gltf traces no photons: caustics and global illumination are off\n  help: photon maps are built for caustics or global illumination, with the Direct integrator: {to_ron}\n")
    );
    let view = ["render", "q.gltf", "--diagnostic", "photon:density:1000"];
    let (code, err) = run("help-photon-view-gltf", "q.gltf", &gltf, &view);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        format!("error: the photon diagnostic shows the photon maps, but this scene builds none (caustics and global illumination are off)\n  help: {to_ron}\n")
    );
    let part = [
        "render", "q.gltf", "--camera", "cam", "--part", "1/2", "-o", "p1.exr",
    ];
    let (code, err) = run("help-camera-gltf", "q.gltf", &gltf, &part);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(
        err,
        "error: --camera cannot be combined with --part\n  help: the merge job renders the scene's render camera; \
         a glTF file renders the first camera of its nodes: write the scene as RON \
         (`stagelight convert q.gltf -o q.ron`) and set `render: (camera: \"cam\")` there\n"
    );
}

/// A `ShadingRate` over a RIB polygon without true displacement dices nothing: the help says
/// when RIB dices a polygon, not RON's `approximation` and `displacement` fields.
#[test]
fn a_shading_rate_on_a_rib_polygon_is_helped_in_rib_terms() {
    let text = "Display \"out.png\" \"file\" \"rgb\"\nFormat 16 12 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\nShadingRate 4\nPolygon \"P\" [0 0 0 1 0 0 0 1 0]\nWorldEnd\n";
    let (code, err) = run("help-rate-polygon-rib", "p.rib", text, &["check", "p.rib"]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        err,
        "p.rib:6:13: warning: object \"polygon_1\": the approximation has no effect on an inline \
         mesh without true displacement\n  help: a polygon is diced only under true displacement \
         (a `Displacement` shader with `Attribute \"render\" \"truedisplacement\" [1]`): give \
         `ShadingRate` only to the surfaces it dices (inside their `AttributeBegin`/`AttributeEnd`)\n"
    );
}
