//! What the `.mi` reader, `check` and `plan` make of a tester's `.mi` scenes: a homogeneous
//! instance transform (seed 001 §3.2.2 prints one) is divided by its `w`, a projective one
//! refused as written; a photon view without photon maps is refused by `check` as by
//! `render`, located, with help in `.mi` syntax; standard options mental ray reads
//! (`shutter`, `motion`, …) are warned, not errors; a misspelt `face` is one error; help
//! texts and mesh warnings are located and written in the scene's syntax; `plan` says the
//! photons the lights' own counts emit.

use std::path::Path;

use stagelight::scene::desc::TransformDesc;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene_str;

use crate::common::cli::{run_in, scratch_dir, stderr_of};
use crate::common::{mi_point_lamp, mi_preamble, BASE};

/// The preamble with `options` lines added, a lamp, a lambert material and the quad
/// `quad` (z = −1, ±1) placed by the instance `transform` (16 numbers, or none), then
/// `extra` objects and the render statement.
fn scene(options: &str, transform: &str, extra: &str) -> String {
    let transform = if transform.is_empty() {
        String::new()
    } else {
        format!("transform {transform}\n")
    };
    format!(
        "{}{}material \"mtl\" \"mib_illum_lambert\" (\"diffuse\" 0.8 0.8 0.8, \"lights\" [\"Lamp_inst\"]) end material
object \"quad\" group
1 1 -1  1 -1 -1  -1 -1 -1  -1 1 -1
v 0 v 1 v 2 v 3
p \"mtl\" 0 3 2 1
end group end object
instance \"quad_inst\" \"quad\"
{transform}end instance
{extra}instgroup \"root\" \"Camera_inst\" \"Lamp_inst\" \"quad_inst\" end instgroup
render \"root\" \"Camera_inst\" \"opt\"
",
        mi_preamble(BASE, "").replace("object space\n", &format!("object space\n{options}")),
        mi_point_lamp("\"color\" 1 1 1"),
    )
}

/// Writes `text` as `name` in a fresh directory and runs `stagelight args… name` there.
fn run(test: &str, name: &str, text: &str, args: &[&str]) -> (Option<i32>, String, String) {
    let dir = scratch_dir(test);
    std::fs::write(dir.join(name), text).unwrap();
    let mut all = args.to_vec();
    all.push(name);
    let o = run_in(&dir, &all);
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    (o.status.code(), stderr_of(&o), stdout)
}

/// Line (1-based) of the first line of `text` that starts with `start`.
fn line_of(text: &str, start: &str) -> usize {
    1 + text.lines().position(|l| l.starts_with(start)).unwrap()
}

/// Seed 001 §3.2.2 prints the sphere's transform scaled by 0.2 (`… 0 0 2.0 0.2`): divided by
/// its w it is the translation by 10 — the same transform as the affine matrix, rendered
/// pixel for pixel the same.
#[test]
fn a_homogeneous_transform_is_divided_by_its_w_and_renders_as_the_affine_one() {
    let scaled = scene("", "0.5 0 0 0  0 0.5 0 0  0 0 0.5 0  0 0 1 0.5", "");
    let affine = scene("", "1 0 0 0  0 1 0 0  0 0 1 0  0 0 2 1", "");
    let read = read_mi(Path::new("w.mi"), scaled.as_bytes()).unwrap_or_else(|e| panic!("{}", e[0]));
    let quad = read
        .desc
        .instances
        .iter()
        .find(|i| i.name == "quad_inst")
        .unwrap();
    // world → object moves by +2 in z: the object sits at z = −2.
    let want = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, -2.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    match quad.transform.as_slice() {
        [TransformDesc::Matrix(m)] => assert_eq!(*m, want),
        other => panic!("{other:?}"),
    }
    let beauty = |text: &str| {
        let mut s = load_scene_str(text, Path::new("w.mi")).unwrap_or_else(|e| panic!("{e}"));
        let frame = crate::common::render(&mut s.world, s.settings.clone());
        frame.outputs.image.expect("an image").beauty
    };
    let image = beauty(&scaled);
    assert_eq!(image, beauty(&affine));
    // The quad (±1 at distance 3) covers the middle of the 160 × 120 image, not its corner.
    assert!(image[60 * 160 + 80].x > 0.0 && image[0] == glam::Vec3::ZERO);
}

/// A projective matrix (last column not (0, 0, 0, w)) or w = 0 is refused at the number
/// out of place, describing the last column as the file wrote it.
#[test]
fn a_projective_transform_is_refused_as_written() {
    for (matrix, found, column) in [
        ("1 0 0 0  0 1 0 0  0 0 1 -1  0 0 2 1", "(0, 0, -1, 1)", 35),
        ("1 0 0 0  0 1 0 0  0 0 1 0  0 0 2 0", "(0, 0, 0, 0)", 44),
    ] {
        let text = scene("", matrix, "");
        let line = line_of(&text, "transform");
        let (code, err, _) = run("mi-projective", "p.mi", &text, &["check"]);
        assert_eq!(code, Some(1), "{err}");
        assert_eq!(
            err,
            format!(
                "p.mi:{line}:{column}: error: the last column of a transform must be (0, 0, 0, w) with w ≠ 0, found {found}\n  \
                 help: an instance transform is affine, written row by row with the translation in the last row: \
                 its last column is (0, 0, 0, 1), or (0, 0, 0, w) for a matrix scaled by w\n\
                 1 error in p.mi\n"
            )
        );
    }
}

/// `diagnostic photon` without photon maps: `check` refuses it as `render` does, at the
/// statement, with the help in the syntax of the scene (`.mi`: `caustic on`; RON: the
/// options field).
#[test]
fn check_refuses_a_photon_view_without_photon_maps_located_in_the_scenes_syntax() {
    let text = scene("diagnostic photon density 10\n", "", "");
    let line = line_of(&text, "diagnostic");
    for command in ["check", "render"] {
        let want = format!(
            "d.mi:{line}:1: error: the photon diagnostic shows the photon maps, but this scene builds none (caustics and global illumination are off)\n  \
             help: add `caustic on` or `globillum on` to the options block\n\
             1 error in d.mi{}\n",
            crate::common::refused_tail(command)
        );
        let (code, err, _) = run("mi-photon-view", "d.mi", &text, &[command]);
        assert_eq!((code, err.as_str()), (Some(1), want.as_str()), "{command}");
    }
    let ron = crate::common::cli::small_scene(
        &crate::common::cli::quad_object("quad"),
        "(name: \"quad_1\", of: \"quad\")",
        "(file: \"out.png\")",
        "    options: (diagnostic: Photon(quantity: Density, max: 10)),\n",
    );
    let (code, err, _) = run("ron-photon-view", "d.ron", &ron, &["check"]);
    assert_eq!(code, Some(1), "{err}");
    let line = line_of(&ron, "    options:");
    assert!(
        err.starts_with(&format!(
            "d.ron:{line}:27: error: the photon diagnostic shows the photon maps, but this scene builds none (caustics and global illumination are off)\n  \
             help: turn on `caustics: (…)` or `global_illumination: (…)` in the scene's options\n"
        )),
        "{err}"
    );
}

/// mental ray's standard options that stagelight does not map are read and warned (with
/// what is done instead), not refused as unknown.
#[test]
fn standard_options_are_read_and_warned() {
    let options = "shutter 0.5\nmotion on\nmotion steps 3\nscanline opengl\nacceleration large bsp\nbsp size 10\ntask size 32\nshadowmap on\n";
    let text = scene(options, "", "");
    let read = read_mi(Path::new("o.mi"), text.as_bytes()).unwrap_or_else(|e| {
        panic!(
            "{}",
            e.iter()
                .map(|p| p.to_string())
                .collect::<Vec<_>>()
                .join("\n")
        )
    });
    let first = line_of(&text, "shutter");
    let warnings: Vec<String> = read.warnings.iter().map(|w| w.to_string()).collect();
    let motion = "is read but not mapped: motion blur is not rendered";
    let bvh = "is read but not mapped: stagelight builds its own bounding volume hierarchy";
    assert_eq!(
        warnings,
        [
            format!("o.mi:{first}:1: warning: option \"shutter\" {motion}"),
            format!("o.mi:{}:1: warning: option \"motion\" {motion}", first + 1),
            format!("o.mi:{}:1: warning: option \"motion\" {motion}", first + 2),
            format!("o.mi:{}:1: warning: option \"scanline\" is read but not mapped", first + 3),
            format!("o.mi:{}:1: warning: option \"acceleration\" {bvh}", first + 4),
            format!("o.mi:{}:1: warning: option \"bsp\" {bvh}", first + 5),
            format!(
                "o.mi:{}:1: warning: option \"task\" is read but not mapped: stagelight chooses its own tiles",
                first + 6
            ),
            format!(
                "o.mi:{}:1: warning: option \"shadowmap\" is read but not mapped: shadows are ray traced",
                first + 7
            ),
        ]
    );
}

/// `face fornt` is one error with a did-you-mean, not a second "unknown option".
#[test]
fn a_misspelt_face_is_one_error_with_a_suggestion() {
    let text = scene("face fornt\n", "", "");
    let line = line_of(&text, "face");
    let errors = read_mi(Path::new("f.mi"), text.as_bytes()).unwrap_err();
    let errors: Vec<String> = errors
        .iter()
        .filter(|p| !p.problem.warning)
        .map(|p| p.to_string())
        .collect();
    assert_eq!(
        errors,
        [format!(
            "f.mi:{line}:6: error: expected front, back or both after face, found \"fornt\"\n  help: did you mean \"front\"?"
        )]
    );
}

/// A contour shader without a contour output: the warning's help names the `.mi` output
/// statement.
#[test]
fn the_contour_output_help_is_written_in_mi_syntax() {
    let text = scene("contour store \"contour_store_function\" ()\n", "", "")
        .replace(
            "\"lights\" [\"Lamp_inst\"]) end material",
            "\"lights\" [\"Lamp_inst\"])\ncontour \"contour_shader_simple\" (\"color\" 0 0 0 1, \"width\" 0.5)\nend material",
        );
    // Located at the contour shader (the reader records where each value was written).
    let line = line_of(&text, "contour \"contour_shader_simple\"");
    let (code, err, _) = run("mi-contour-help", "c.mi", &text, &["check"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains(&format!(
            "c.mi:{line}:9: warning: material \"mtl\" has a contour shader, but no camera output shows contours\n  \
             help: add a camera output such as `output \"contour\" \"ps\" \"lines.ps\"`\n"
        )),
        "{err}"
    );
}

/// The triangles the loader drops are reported at the object that has them.
#[test]
fn dropped_degenerate_triangles_are_located_at_the_object() {
    let flat = "object \"flat\" group\n0 0 -1  1 0 -1  2 0 -1  0 1 -1\nv 0 v 1 v 2 v 3\np \"mtl\" 0 1 2\np \"mtl\" 0 1 3\nend group end object\ninstance \"flat_inst\" \"flat\" end instance\n";
    let text = scene("", "", flat).replace(
        "\"quad_inst\" end instgroup",
        "\"quad_inst\" \"flat_inst\" end instgroup",
    );
    let line = line_of(&text, "object \"flat\"");
    let (code, err, _) = run("mi-degenerate", "g.mi", &text, &["check"]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(
        err,
        format!("g.mi:{line}:1: warning: mesh \"flat\": dropped 1 degenerate triangle\n")
    );
}

/// `plan` says what the pass emits: the seed's light asks for 5 000 000 caustic photons,
/// not the map's default 100 000.
#[test]
fn plan_reports_the_photons_the_lights_own_counts_emit() {
    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/seeds/mi/caustics.mi");
    let dir = scratch_dir("mi-plan-photons");
    let o = run_in(&dir, &["plan", seed.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let line = out.lines().find(|l| l.contains("trace_photons")).unwrap();
    assert!(
        line.contains("run  caustics (5000000 photons, the lights' own counts); "),
        "{line}"
    );
}

/// `quad_inst` placed through `levels` nested instance groups (identity transforms); the
/// root holds the outermost.
fn chain(levels: usize) -> String {
    let mut extra = String::new();
    let mut inner = "quad_inst".to_string();
    for k in 0..levels {
        extra += &format!(
            "instgroup \"g{k}\" \"{inner}\" end instgroup\ninstance \"i{k}\" \"g{k}\" end instance\n"
        );
        inner = format!("i{k}");
    }
    scene("", "", &extra).replace(
        "\"Lamp_inst\" \"quad_inst\" end instgroup",
        &format!("\"Lamp_inst\" \"{inner}\" end instgroup"),
    )
}

/// Exporters write each transform node as an instgroup and an instance: a 200-deep chain
/// (no cycle) renders as the quad placed directly; past 1,000 levels the error says so,
/// and a real cycle is still "contains itself" (both used to be "contains itself" past 64).
#[test]
fn deep_instance_group_chains_are_read_and_only_cycles_contain_themselves() {
    let dir = scratch_dir("mi-deep-chain");
    let image = |name: &str, text: &str| {
        std::fs::write(dir.join(name), text).unwrap();
        let o = run_in(&dir, &["render", name, "--spp", "1", "-o", "out.png"]);
        assert!(o.status.success(), "{}", stderr_of(&o));
        std::fs::read(dir.join("out.png")).unwrap()
    };
    let direct = image("direct.mi", &scene("", "", ""));
    let chained = image("chain.mi", &chain(200));
    assert!(
        direct == chained,
        "the 200-deep chain renders the directly placed quad"
    );
    let errors = read_mi(Path::new("c.mi"), chain(1001).as_bytes()).unwrap_err();
    let messages: Vec<String> = errors
        .iter()
        .filter(|p| !p.problem.warning)
        .map(|p| p.problem.message.clone())
        .collect();
    assert_eq!(
        messages,
        ["instgroup \"g0\" is nested more than 1000 instance groups deep"]
    );
    let cycle = chain(3).replace(
        "instgroup \"g0\" \"quad_inst\" end instgroup",
        "instgroup \"g0\" \"quad_inst\" \"i2\" end instgroup",
    );
    let errors = read_mi(Path::new("c.mi"), cycle.as_bytes()).unwrap_err();
    assert!(
        errors
            .iter()
            .any(|p| p.problem.message == "instgroup \"g2\" contains itself"),
        "{errors:?}"
    );
}

/// Maya's exporter names the material shader (`shader "sh1" "mib_illum_lambert" (…)`) and
/// refers to it (`material "mtl" opaque = "sh1" shadow = "sh1" end material`): the seed's
/// plane renders the same bytes as with the shader written inline (the material shader as
/// its own shadow shader is stagelight's rule without one, with a warning that says so),
/// and an unknown name is an error at the reference with a suggestion.
#[test]
fn a_named_material_shader_renders_as_the_inline_one() {
    let seed = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/seeds/mi/plane.mi"),
    )
    .unwrap();
    let (a, b) = (
        seed.find("material \"mtl\"").unwrap(),
        seed.find("end material").unwrap() + "end material".len(),
    );
    let shader = seed[a..b]
        .replace("material \"mtl\"\nopaque\n", "shader \"sh1\"\n")
        .replace("\nend material", "");
    let named = format!(
        "{}{shader}\nmaterial \"mtl\"\nopaque\n    = \"sh1\"\n    shadow = \"sh1\"\nend material{}",
        &seed[..a],
        &seed[b..]
    );
    let dir = scratch_dir("mi-named-material");
    std::fs::write(dir.join("inline.mi"), &seed).unwrap();
    std::fs::write(dir.join("named.mi"), &named).unwrap();
    let image = |name: &str| {
        let o = run_in(&dir, &["render", name, "--spp", "1", "-o", "out.png"]);
        assert!(o.status.success(), "{}", stderr_of(&o));
        std::fs::read(dir.join("out.png")).unwrap()
    };
    assert!(image("inline.mi") == image("named.mi"));
    let o = run_in(&dir, &["check", "named.mi"]);
    assert!(
        stderr_of(&o).contains("warning: material shader \"mib_illum_lambert\" as the shadow shader: shadows follow the material shader, as without one (an opaque surface blocks the light)"),
        "{}",
        stderr_of(&o)
    );
    let bad = named.replace("    = \"sh1\"", "    = \"sh2\"");
    let line = line_of(&bad, "    = \"sh2\"");
    let errors = read_mi(Path::new("bad.mi"), bad.as_bytes()).unwrap_err();
    let errors: Vec<String> = errors
        .iter()
        .filter(|p| !p.problem.warning)
        .map(|p| p.to_string())
        .collect();
    assert_eq!(
        errors,
        [format!(
            "bad.mi:{line}:7: error: no shader named \"sh2\" is defined before the material shader\n  help: did you mean \"sh1\"?"
        )]
    );
}
