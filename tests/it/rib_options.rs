//! RIB camera options and the atmosphere end to end: `Display` modes onto passes (seed 001
//! §4.5's `"N"` and `"P"`), `DepthOfField` onto a thin lens (description and the blur of
//! an out-of-focus edge), `Atmosphere "fog"` onto the camera's exponential fade (description
//! and pixels), and a misspelt shader parameter named at once.

use std::path::Path;

use stagelight::components::{Camera, RenderCamera};
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::desc::{FalloffDesc, LensDesc, PassDesc, VolumeDesc};
use stagelight::scene::import::rib::RibScene;

use crate::common::read_rib_text;
use stagelight::scene::load_scene_str;

use crate::lens_shaders::{blur_diameter, circle_of_confusion, profile};

/// The scene read from `text` as `t.rib` (a panic shows the reader's errors).
fn read(text: &str) -> RibScene {
    read_rib_text(text)
}

fn warnings(s: &RibScene) -> Vec<String> {
    s.warnings.iter().map(ToString::to_string).collect()
}

/// Every message of a refused file.
fn errors(text: &str) -> String {
    match load_scene_str(text, Path::new("t.rib")) {
        Ok(_) => "ok".into(),
        Err(e) => e.to_string(),
    }
}

/// The frame buffers of a RIB scene at its own resolution, `spp` samples per pixel.
fn render(text: &str, spp: u32) -> FrameBuffers {
    let mut scene =
        load_scene_str(text, Path::new("t.rib")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    for (camera, _) in scene.world.query_mut::<(&Camera, &RenderCamera)>() {
        assert!(camera.width > 0);
    }
    let mut settings = scene.settings.clone();
    settings.spp = spp;
    let frame = crate::common::render(&mut scene.world, settings);
    frame.outputs.image.expect("an image")
}

const WORLD: &str = "WorldBegin\nSphere 1 -1 1 360\nWorldEnd\n";

#[test]
fn display_modes_of_the_seed_map_onto_passes() {
    // Seed 001, §4.5: the baking displays. Without '+' the second replaces the first.
    let s = read(&format!(
        "Display \"headP.tif\" \"file\" \"P\" \"quantize\" [0 0 0 0]\n\
         Display \"headN.tif\" \"file\" \"N\" \"quantize\" [0 0 0 0]\n{WORLD}"
    ));
    let outputs = &s.desc.cameras[0].outputs;
    assert_eq!(outputs.len(), 1);
    assert_eq!(outputs[0].file, "headN.exr");
    assert_eq!(outputs[0].passes, Some(vec![PassDesc::CameraNormal]));
    // RenderMan's values (camera space): no warning that they differ, P is written too.
    assert_eq!(
        warnings(&s),
        [
            "t.rib:1:9: warning: writing \"headP.exr\" for display \"headP.tif\": stagelight writes PNG and EXR",
            "t.rib:1:32: warning: ignored parameter \"quantize\" of Display",
            "t.rib:2:9: warning: writing \"headN.exr\" for display \"headN.tif\": stagelight writes PNG and EXR",
            "t.rib:2:32: warning: ignored parameter \"quantize\" of Display",
        ]
    );
    // With '+', both files.
    let s = read(&format!(
        "Display \"headP.tif\" \"file\" \"P\"\nDisplay \"+headN.tif\" \"file\" \"N\"\n{WORLD}"
    ));
    let outputs = &s.desc.cameras[0].outputs;
    assert_eq!(
        outputs
            .iter()
            .map(|o| (o.file.as_str(), o.passes.clone().unwrap()))
            .collect::<Vec<_>>(),
        [
            ("headP.exr", vec![PassDesc::CameraPosition]),
            ("headN.exr", vec![PassDesc::CameraNormal])
        ]
    );
}

#[test]
fn every_standard_display_mode_has_its_passes() {
    use PassDesc::{Alpha, Beauty, CameraDepth, CameraNormal, CameraPosition};
    for (mode, passes, file) in [
        ("rgb", vec![Beauty], "o.png"),
        ("rgba", vec![Beauty, Alpha], "o.png"),
        ("rgbz", vec![Beauty, CameraDepth], "o.exr"),
        ("rgbaz", vec![Beauty, Alpha, CameraDepth], "o.exr"),
        ("a", vec![Alpha], "o.png"),
        ("az", vec![Alpha, CameraDepth], "o.exr"),
        ("z", vec![CameraDepth], "o.exr"),
        ("N", vec![CameraNormal], "o.exr"),
        ("P", vec![CameraPosition], "o.exr"),
    ] {
        let s = read(&format!("Display \"o.png\" \"file\" \"{mode}\"\n{WORLD}"));
        let out = &s.desc.cameras[0].outputs[0];
        assert_eq!(
            (out.file.as_str(), out.passes.as_ref()),
            (file, Some(&passes))
        );
        // An EXR of colour without `a` writes no alpha channel.
        let no_alpha = (mode == "rgbz").then_some(false);
        assert_eq!(out.beauty_alpha, no_alpha, "{mode}");
        let w = warnings(&s);
        if file == "o.exr" {
            assert_eq!(
                w,
                ["t.rib:1:9: warning: writing \"o.exr\" for display \"o.png\": depth, normals and positions are written to EXR only"],
                "{mode}"
            );
        } else {
            assert!(w.is_empty(), "{mode}: {w:?}");
        }
        // The description loads: data passes only go to EXR.
        load_scene_str(
            &format!("Display \"o.png\" \"file\" \"{mode}\"\n{WORLD}"),
            Path::new("t.rib"),
        )
        .unwrap_or_else(|e| panic!("{mode}: {e}"));
    }
    assert_eq!(
        errors(&format!("Display \"o.exr\" \"file\" \"Z\"\n{WORLD}")),
        "t.rib:1:24: error: display mode \"Z\" is not supported\n  help: did you mean \"z\"?"
    );
}

/// The channels of each display mode's EXR file are those its letters name (EXR sorts them
/// by name), and a PNG of colour has an alpha channel only with `a`.
#[test]
fn every_display_mode_writes_exactly_the_channels_its_letters_name() {
    use crate::common::cli::{run_in, scratch_dir, stderr_of};
    let modes: [(&str, &[&str]); 9] = [
        ("rgb", &["B", "G", "R"]),
        ("rgba", &["A", "B", "G", "R"]),
        ("rgbz", &["B", "G", "R", "Z"]),
        ("rgbaz", &["A", "B", "G", "R", "Z"]),
        ("a", &["A"]),
        ("az", &["A", "Z"]),
        ("z", &["Z"]),
        ("N", &["N.X", "N.Y", "N.Z"]),
        ("P", &["P.X", "P.Y", "P.Z"]),
    ];
    let dir = scratch_dir("rib-display-channels");
    let mut rib = String::new();
    for (k, (mode, _)) in modes.iter().enumerate() {
        let plus = if k == 0 { "" } else { "+" };
        rib += &format!("Display \"{plus}{mode}.exr\" \"file\" \"{mode}\"\n");
    }
    rib += "Display \"+rgb.png\" \"file\" \"rgb\"\nDisplay \"+rgba.png\" \"file\" \"rgba\"\n\
             Format 4 4 1\nPixelSamples 1 1\nTranslate 0 0 3\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n";
    std::fs::write(dir.join("modes.rib"), rib).unwrap();
    let o = run_in(&dir, &["render", "modes.rib"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    for (mode, expected) in modes {
        let path = dir.join(format!("{mode}.exr"));
        let image = exr::prelude::read_all_flat_layers_from_file(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let names: Vec<String> = image.layer_data[0]
            .channel_data
            .list
            .iter()
            .map(|c| c.name.to_string())
            .collect();
        assert_eq!(names, expected, "mode {mode}");
    }
    for (name, channels) in [("rgb.png", 3), ("rgba.png", 4)] {
        let png =
            stagelight::image_io::png_codec::decode_png(&std::fs::read(dir.join(name)).unwrap())
                .unwrap();
        assert_eq!(png.channels, channels, "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_misspelt_shader_parameter_is_named_with_the_shaders_own() {
    // Not "undeclared parameter … declare it first": declaring it would only lead here.
    assert_eq!(
        errors("WorldBegin\nSurface \"plastic\" \"roughnes\" [ 0.3 ]\nSphere 1 -1 1 360\nWorldEnd\n"),
        "t.rib:2:19: error: unknown parameter \"roughnes\" of surface \"plastic\"\n  help: did you mean \"roughness\"?"
    );
    // Declared, the same message.
    assert_eq!(
        errors("Declare \"roughnes\" \"float\"\nWorldBegin\nSurface \"plastic\" \"roughnes\" [ 0.3 ]\nSphere 1 -1 1 360\nWorldEnd\n"),
        "t.rib:3:19: error: unknown parameter \"roughnes\" of surface \"plastic\"\n  help: did you mean \"roughness\"?"
    );
    assert_eq!(
        errors("WorldBegin\nLightSource \"pointlight\" 1 \"intensty\" [2]\nWorldEnd\n"),
        "t.rib:2:28: error: unknown parameter \"intensty\" of light \"pointlight\"\n  help: did you mean \"intensity\"?"
    );
    // The tutorial's shaders name their own parameters the same way.
    assert_eq!(
        errors("WorldBegin\nLightSource \"myLight\" 1 \"nearr\" [2]\nWorldEnd\n"),
        "t.rib:2:25: error: unknown parameter \"nearr\" of light \"myLight\"\n  help: did you mean \"near\"?"
    );
    // A shader we do not have still takes declared parameters only.
    assert_eq!(
        errors("WorldBegin\nSurface \"wood\" \"grain\" [ 3 ]\nSphere 1 -1 1 360\nWorldEnd\n"),
        "t.rib:2:9: warning: unknown surface shader \"wood\": using \"defaultsurface\"\n  help: expected one of \"constant\", \"matte\", \"metal\", \"shinymetal\", \"plastic\", \"paintedplastic\", \"defaultsurface\", \"mySurface\", \"simplemirror\" or \"stairs\"\n\
         t.rib:2:16: error: undeclared parameter \"grain\"\n  help: declare it first (Declare \"grain\" \"float\") or write its type inline (\"float grain\")"
    );
}

fn thin_lens(s: &RibScene) -> Option<(f64, f64)> {
    match s.desc.cameras[0].lens.as_slice() {
        [] => None,
        [LensDesc::ThinLens {
            radius: Some(r),
            fstop: None,
            focus_distance,
        }] => Some((*r, *focus_distance)),
        other => panic!("{other:?}"),
    }
}

#[test]
fn depth_of_field_is_a_thin_lens_of_radius_focallength_over_twice_the_fstop() {
    let s = read(&format!("DepthOfField 2.8 0.05 5\n{WORLD}"));
    assert_eq!(thin_lens(&s), Some((0.05 / 5.6, 5.0)));
    assert!(warnings(&s).is_empty(), "{:?}", warnings(&s));
    // Camera-space lengths: a camera transformation that scales by 2 halves them in the world.
    let s = read(&format!("DepthOfField 2.8 0.05 5\nScale 2 2 2\n{WORLD}"));
    let (r, f) = thin_lens(&s).unwrap();
    assert!(
        (r - 0.05 / 5.6 / 2.0).abs() < 1e-15 && (f - 2.5).abs() < 1e-12,
        "{r} {f}"
    );
    // No arguments, or an infinite fstop (RI_INFINITY), turn it off; the last one counts.
    for off in ["DepthOfField", "DepthOfField 1e38 0.05 5"] {
        let s = read(&format!("DepthOfField 2.8 0.05 5\n{off}\n{WORLD}"));
        assert_eq!(thin_lens(&s), None, "{off}");
    }
    assert_eq!(
        errors(&format!("DepthOfField 2.8 0 5\n{WORLD}")),
        "t.rib:1:1: error: DepthOfField needs fstop > 0, focallength > 0 and focaldistance > 0, found 2.8 0 5\n  help: `DepthOfField` without arguments turns depth of field off"
    );
}

/// A white `constant` half-plane `x ≥ 0` at depth `d` seen at fov 20° on 128 × 16 pixels.
fn edge_rib(options: &str, d: f64) -> String {
    format!(
        "Format 128 16 1\nProjection \"perspective\" \"fov\" [20]\nPixelFilter \"box\" 1 1\n\
         {options}\nWorldBegin\nSurface \"constant\"\n\
         Polygon \"P\" [0 -100 {d}  100 -100 {d}  100 100 {d}  0 100 {d}]\nWorldEnd\n"
    )
}

#[test]
fn depth_of_field_blurs_an_out_of_focus_edge_by_the_circle_of_confusion() {
    // Aperture radius 0.5 / (2 · 1) = 0.25, focus 2, edge at 4: 5.67 px.
    let dof = "DepthOfField 1 0.5 2";
    let blurred = blur_diameter(&profile(&render(&edge_rib(dof, 4.0), 256)));
    let expected = circle_of_confusion(0.25, 2.0, 4.0, 20.0, 16);
    assert!(
        (blurred - expected).abs() < 1.0,
        "blur {blurred:.2} px, thin-lens formula {expected:.2} px"
    );
    // In focus, and without DepthOfField, the edge stays sharp.
    for (options, d) in [(dof, 2.0), ("", 4.0)] {
        let sharp = blur_diameter(&profile(&render(&edge_rib(options, d), 64)));
        assert!(sharp < 1.0, "{options:?} at {d}: {sharp:.2} px");
    }
}

/// A `constant` square of colour (0.2, 0.6, 1) at depth `d` filling a 5 × 5 image at a
/// field of view of 1° (every camera ray within 0.71° of the axis), `atmosphere` before it.
fn fog_rib(atmosphere: &str, d: f64) -> String {
    format!(
        "Format 5 5 1\nProjection \"perspective\" \"fov\" [1]\nWorldBegin\n{atmosphere}\n\
         Color [0.2 0.6 1]\nSurface \"constant\"\n\
         Patch \"bilinear\" \"P\" [-1 -1 {d}  1 -1 {d}  -1 1 {d}  1 1 {d}]\nWorldEnd\n"
    )
}

#[test]
fn fog_is_the_exponential_fade_toward_its_background() {
    let fog = "Atmosphere \"fog\" \"distance\" [4] \"background\" [1 0.5 0]";
    let s = read(&fog_rib(fog, 6.0));
    assert!(warnings(&s).is_empty(), "{:?}", warnings(&s));
    assert_eq!(
        s.desc.cameras[0].atmosphere,
        Some(VolumeDesc::Fade {
            color: (1.0, 0.5, 0.0),
            opacity: 1.0,
            max: 4.0,
            falloff: FalloffDesc::Exponential,
        })
    );
    // RISpec's fog: Ci = mix(Ci, background, 1 − exp(−length(I)/distance)), length(I) = 6
    // (at most 6.0005 off the axis: 2.5e-5 in the weight).
    let f = 1.0 - (-6.0f64 / 4.0).exp();
    let expected: Vec<f64> = [0.2, 0.6, 1.0]
        .iter()
        .zip([1.0, 0.5, 0.0])
        .map(|(c, b)| c * (1.0 - f) + b * f)
        .collect();
    let fb = render(&fog_rib(fog, 6.0), 4);
    for (i, px) in fb.beauty.iter().enumerate() {
        for (g, e) in px.to_array().iter().zip(&expected) {
            assert!(
                (f64::from(*g) - e).abs() < 3e-5,
                "pixel {i}: {px:?} vs {expected:?}"
            );
        }
    }
}

#[test]
fn fog_on_some_primitives_only_or_another_volume_shader_is_a_warning() {
    let text = "WorldBegin\nSphere 1 -1 1 360\nAtmosphere \"fog\"\nSphere 1 -1 1 360\nWorldEnd\n";
    let s = read(text);
    assert_eq!(s.desc.cameras[0].atmosphere, None);
    assert_eq!(
        warnings(&s),
        ["t.rib:3:1: warning: ignored Atmosphere \"fog\": it applies to 1 of the 2 primitives, and stagelight's atmosphere fills the whole scene\n  help: write one Atmosphere before the first primitive, for all of them"]
    );
    let s = read("WorldBegin\nAtmosphere \"depthcue\"\nSphere 1 -1 1 360\nWorldEnd\n");
    assert_eq!(s.desc.cameras[0].atmosphere, None);
    assert_eq!(
        warnings(&s),
        ["t.rib:2:12: warning: ignored atmosphere shader \"depthcue\": only \"fog\" is mapped"]
    );
    assert_eq!(
        errors("WorldBegin\nAtmosphere \"fog\" \"distance\" [0]\nSphere 1 -1 1 360\nWorldEnd\n"),
        "t.rib:2:29: error: distance of \"fog\" must be above 0, found 0"
    );
}

#[test]
fn a_projection_other_than_perspective_is_a_located_error() {
    // Not a perspective picture with a warning: stagelight has no orthographic camera.
    for name in ["orthographic", "fisheye"] {
        assert_eq!(
            errors(&format!("Projection \"{name}\"\n{WORLD}")),
            format!(
                "t.rib:1:12: error: Projection \"{name}\" is not supported: stagelight's camera \
                 makes perspective projections only\n  help: use Projection \"perspective\" \
                 \"fov\" [degrees]"
            )
        );
    }
    assert_eq!(
        errors(&format!("Projection \"perspective\" \"fov\" [30]\n{WORLD}")),
        "ok"
    );
}
