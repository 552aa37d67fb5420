//! `.mi` camera `output` statements in mental ray's form `output ["type"] "format" [opt]
//! "filename"` (seed 001 §3: a format without a type writes rgba): each form maps onto an
//! output with its passes and file, formats stagelight cannot write become a PNG or EXR of
//! the same stem (warned), options are read and warned; bad ones are located errors that
//! read well.

use std::path::Path;

use stagelight::scene::desc::{FormatDesc, OutputDesc, PassDesc};
use stagelight::scene::import::mi::read_mi;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// A scene whose camera has the `outputs` lines.
fn scene(outputs: &str) -> String {
    format!(
        r#"options "opt"
object space
end options
camera "cam"
{outputs}
focal 1
aperture 1
aspect 1
resolution 4 4
end camera
instance "cam_inst" "cam" end instance
light "lamp" "mib_light_point" ("color" 1 1 1) origin 0 0 0 end light
instance "lamp_inst" "lamp" end instance
material "mtl" "mib_illum_lambert" ("diffuse" 0.8 0.8 0.8, "lights" ["lamp_inst"]) end material
object "quad" group
1 1 -1  1 -1 -1  -1 -1 -1  -1 1 -1
v 0 v 1 v 2 v 3
p "mtl" 0 3 2 1
end group end object
instance "quad_inst" "quad" end instance
instgroup "root" "cam_inst" "lamp_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#
    )
}

/// The camera's outputs and the reader's warnings (`line:column: message`).
fn read(outputs: &str) -> (Vec<OutputDesc>, Vec<String>) {
    let text = scene(outputs);
    let read = read_mi(Path::new("out.mi"), text.as_bytes()).unwrap_or_else(|e| panic!("{}", e[0]));
    let warnings = read
        .warnings
        .iter()
        .map(|w| {
            let p = w.problem.pos;
            format!("{}:{}: {}", p.line, p.column, w.problem.message)
        })
        .collect();
    (read.desc.cameras[0].outputs.clone(), warnings)
}

fn errors(outputs: &str) -> String {
    let text = scene(outputs);
    match read_mi(Path::new("out.mi"), text.as_bytes()) {
        Ok(_) => panic!("reads: {outputs}"),
        Err(e) => e
            .iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join("\n"),
    }
}

fn out(file: &str, format: FormatDesc, passes: &[PassDesc]) -> String {
    format!(
        "{:?}",
        OutputDesc {
            file: file.into(),
            format: Some(format),
            passes: Some(passes.to_vec()),
            beauty_alpha: None,
        }
    )
}

#[test]
fn output_forms_map_onto_passes_and_files() {
    use FormatDesc::{Exr, Png};
    use PassDesc::{Alpha, Beauty, CameraDepth};
    let cases: &[(&str, String, &[&str])] = &[
        // A format alone: its default type, rgba (the seed's "rgb" case too).
        (
            "output \"png\" \"test.png\"",
            out("test.png", Png, &[Beauty, Alpha]),
            &[],
        ),
        (
            "output \"rgb\" \"test.rgb\"",
            out("test.png", Png, &[Beauty, Alpha]),
            &["5:14: output \"test.rgb\" is written as \"test.png\" (stagelight writes PNG and EXR files, not format \"rgb\")"],
        ),
        // Type, format, an option number, file.
        (
            "output \"rgba\" \"tif\" 1 \"test.tif\"",
            out("test.png", Png, &[Beauty, Alpha]),
            &[
                "5:21: the options of output format \"tif\" are read and not used (stagelight writes PNG and EXR with their own settings)",
                "5:23: output \"test.tif\" is written as \"test.png\" (stagelight writes PNG and EXR files, not format \"tif\")",
            ],
        ),
        ("output \"rgb\" \"png\" \"x.png\"", out("x.png", Png, &[Beauty]), &[]),
        (
            "output \"rgba\" \"exr\" \"x.exr\"",
            out("x.exr", Exr, &[Beauty, Alpha]),
            &[],
        ),
        // A data type's format, written as EXR.
        (
            "output \"z\" \"zt\" \"d.zt\"",
            out("d.exr", Exr, &[CameraDepth]),
            &["5:17: output \"d.zt\" is written as \"d.exr\" (stagelight writes PNG and EXR files, not format \"zt\")"],
        ),
        (
            "output \"zt\" \"d.exr\"",
            out("d.exr", Exr, &[CameraDepth]),
            &[],
        ),
        // A data type and a file (no format): read as before.
        (
            "output \"rgba\" \"a.png\"",
            out("a.png", Png, &[Beauty, Alpha]),
            &[],
        ),
    ];
    for (line, want, warned) in cases {
        let (outputs, warnings) = read(line);
        assert_eq!(outputs.len(), 1, "{line}");
        assert_eq!(format!("{:?}", outputs[0]), *want, "{line}");
        assert_eq!(warnings, *warned, "{line}");
    }
}

/// Types deeper than 8 bits per channel: named as PNG they are written 8-bit, with a warning
/// at the type (and its help naming EXR); in a format stagelight does not write they go to
/// an EXR of the same stem, which keeps their precision, as data types do.
#[test]
fn deep_output_types_warn_as_png_and_keep_their_precision_elsewhere() {
    use FormatDesc::{Exr, Png};
    use PassDesc::{Alpha, Beauty};
    let cases: &[(&str, String, &[&str])] = &[
        (
            "output \"rgba_16\" \"png\" \"u1.png\"",
            out("u1.png", Png, &[Beauty, Alpha]),
            &["5:8: output type \"rgba_16\" is 16 bits per channel, but \"u1.png\" is written as an 8-bit PNG"],
        ),
        (
            "output \"rgb_fp\" \"f.png\"",
            out("f.png", Png, &[Beauty]),
            &["5:8: output type \"rgb_fp\" is floating point, but \"f.png\" is written as an 8-bit PNG"],
        ),
        (
            "output \"rgba_h\" \"ct\" \"h.ct\"",
            out("h.exr", Exr, &[Beauty, Alpha]),
            &["5:22: output \"h.ct\" is written as \"h.exr\" (stagelight writes PNG and EXR files, not format \"ct\")"],
        ),
        (
            "output \"rgba_fp\" \"exr\" \"f.exr\"",
            out("f.exr", Exr, &[Beauty, Alpha]),
            &[],
        ),
    ];
    for (line, want, warned) in cases {
        let (outputs, warnings) = read(line);
        assert_eq!(format!("{:?}", outputs[0]), *want, "{line}");
        assert_eq!(warnings, *warned, "{line}");
    }
    // The help names the format that keeps the precision.
    let text = scene("output \"rgba_16\" \"png\" \"u1.png\"");
    let read = read_mi(Path::new("out.mi"), text.as_bytes()).unwrap();
    assert_eq!(
        read.warnings[0].problem.help.as_deref(),
        Some("name an .exr file (or format \"exr\") to keep its precision")
    );
}

#[test]
fn bad_output_statements_are_located_errors_that_read_well() {
    let cases = [
        (
            "output \"rgba\" \"pgn\" \"x.png\"",
            "out.mi:5:15: error: unknown output format \"pgn\"\n  help: did you mean \"png\"?",
        ),
        (
            "output \"rgbz\" \"x.png\"",
            "out.mi:5:8: error: output type \"rgbz\" is not supported\n  help: expected \"rgb\", \"rgba\", \"z\", \"n\", \"tag\" or \"contour\", or a file format (\"png\", \"exr\", \"rgb\", \"tif\", …)",
        ),
        (
            "output \"rgba\" \"tif\" 1 2",
            "out.mi:6:1: error: expected a string for the output file, found \"focal\"",
        ),
        (
            "resolution 4 4 4",
            "out.mi:5:16: error: unexpected number in camera\n  help: expected a camera statement (a word such as \"frame\") or \"end camera\"",
        ),
    ];
    for (line, want) in cases {
        assert_eq!(errors(line), want, "{line}");
    }
}

#[test]
fn cli_render_of_output_png_writes_an_rgba_png() {
    let dir = scratch_dir("mi_output_png");
    std::fs::write(dir.join("test.mi"), scene("output \"png\" \"test.png\"")).unwrap();
    let o = run_in(&dir, &["render", "test.mi"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let png = crate::common::png::read(&dir.join("test.png"));
    assert_eq!((png.width, png.height, png.channels), (4, 4, 4));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The channels of an EXR output are those its type names, as RIB's `Display` modes: `rgb`
/// (and its deeper `_16`, `_h`, `_fp` forms) writes no alpha channel, `rgba` writes `A`
/// (EXR sorts the channels by name).
#[test]
fn an_rgb_exr_output_writes_no_alpha_channel_and_rgba_does() {
    let types: [(&str, &[&str]); 6] = [
        ("rgb", &["B", "G", "R"]),
        ("rgb_16", &["B", "G", "R"]),
        ("rgb_h", &["B", "G", "R"]),
        ("rgb_fp", &["B", "G", "R"]),
        ("rgba", &["A", "B", "G", "R"]),
        ("rgba_fp", &["A", "B", "G", "R"]),
    ];
    let outputs: Vec<String> = types
        .iter()
        .map(|(t, _)| format!("output \"{t}\" \"exr\" \"{t}.exr\""))
        .collect();
    let dir = scratch_dir("mi_output_exr_channels");
    std::fs::write(dir.join("c.mi"), scene(&outputs.join("\n"))).unwrap();
    let o = run_in(&dir, &["render", "c.mi"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    for (kind, expected) in types {
        let path = dir.join(format!("{kind}.exr"));
        let image = exr::prelude::read_all_flat_layers_from_file(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let names: Vec<String> = image.layer_data[0]
            .channel_data
            .list
            .iter()
            .map(|c| c.name.to_string())
            .collect();
        assert_eq!(names, expected, "output type {kind}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
