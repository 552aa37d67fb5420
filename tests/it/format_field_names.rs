//! Error and warning texts about a value of a `.mi` or RIB scene name the value as that file
//! writes it, not as the RON field it becomes: a `.mi` contour's `"max_width"` (not
//! `dark_width`), `"ndelta"` (not `normal_angle`), a `mib_illum_*` `"diffuse"` (not `color`),
//! a light's `"start"`/`"stop"`, the `approximate` statement's subdivision bounds; a RIB
//! surface's `Kd`, `Ks`, `specularcolor` and `roughness` (once, not as the `specular` colour
//! `Ks` is multiplied into), an area light's `intensity`, a light's `lightcolor`, the
//! tutorial light's `near`/`far`, a spot or distant light's `from`/`to` and
//! `beamdistribution`, the fog's `background`, a quadric's `zmax`/`phimax`, the
//! `displacementbound`. The RON texts stay as they were. (The adaptive-approximation budget
//! warning: `tests/it/syntax_helps.rs`.)

use std::path::{Path, PathBuf};

use stagelight::scene::load_scene;

fn dir(name: &str) -> PathBuf {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight_format_names_{name}_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// What loading `text` as the file `name` in `dir` says (paths relative to `dir`).
fn messages(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let got = match load_scene(&path) {
        Ok(_) => "ok".to_string(),
        Err(e) => e.to_string(),
    };
    got.replace(&format!("{}/", dir.display()), "")
        .trim_end()
        .to_string()
}

fn replaced(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

/// The `.mi` contour fixture (a lit square, a `contour_shader_simple`, an EPS output).
fn mi_fixture() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_contours/square.mi");
    std::fs::read_to_string(path).unwrap()
}

const WIDTH_HELP: &str = "  help: widths are in percent of the smaller image dimension, e.g. \
                          `\"width\" 0.5`; to draw no contours, leave out the material's \
                          `contour` shader";

/// The fixture's contour shader call, replaced in the cases below.
const SIMPLE: &str = "contour_shader_simple\" (\n\"color\" 1.0 0.0 0.0 1.0,\n\"width\" 1.0";

#[test]
fn mi_contour_values_are_named_by_their_mi_parameters() {
    let text = mi_fixture();
    let dir = dir("mi_contours");
    let cases = [
        (
            replaced(
                &text,
                SIMPLE,
                "contour_shader_widthfromlight\" (\n\"color\" 1.0 0.0 0.0 1.0,\n\"max_width\" -1.0, \"min_width\" 200",
            ),
            format!(
                "bad.mi:76:13: error: contour max_width must be positive, found -1\n{WIDTH_HELP}\n\
                 bad.mi:76:31: error: contour min_width must be at most 100 (percent), found 200"
            ),
        ),
        (
            replaced(
                &text,
                SIMPLE,
                "contour_shader_depthfade\" (\n\"near_z\" -1, \"far_z\" 0",
            ),
            "bad.mi:75:22: error: far_z must lie farther from the camera than near_z (distance 1), found distance 0".to_string(),
        ),
        (
            replaced(&text, SIMPLE, "contour_shader_layerthinner\" (\"factor\" 2"),
            "bad.mi:74:49: error: factor must be in (0, 1], found 2".to_string(),
        ),
        (
            replaced(&text, "\"ndelta\" 20.0,", "\"ndelta\" 200,"),
            "bad.mi:15:10: error: ndelta must be in (0, 180] degrees, found 200".to_string(),
        ),
    ];
    for (bad, want) in cases {
        assert_eq!(messages(&dir, "bad.mi", &bad), want);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn mi_material_light_and_camera_values_are_named_by_their_mi_parameters() {
    let text = mi_fixture();
    let dir = dir("mi_values");
    let lamp = "\"atten\" false,\n\"start\" 0,\n\"stop\" 1";
    let physical = "\"mib_light_point\" (\n\n\"color\" 1.0 1.0 1.0,\n\"shadow\" false,\n\"factor\" 1,\n\"atten\" false,\n\"start\" 0,\n\"stop\" 1\n";
    let cases = [
        (
            replaced(&text, "\"diffuse\" 0.5 0.5 0.5", "\"diffuse\" -0.5 0.5 0.5"),
            "bad.mi:71:11: error: diffuse must not be negative, found -0.5\n  help: diffuse takes 0 or more: write 0.5 if only the sign is wrong".to_string(),
        ),
        (
            replaced(&text, lamp, "\"atten\" true,\n\"start\" 2,\n\"stop\" 1"),
            "bad.mi:51:8: error: stop must be greater than start (2), found 1\n  \
             help: light falls off linearly from full at `start` to none at `stop`"
                .to_string(),
        ),
        (
            replaced(&text, lamp, "\"atten\" true,\n\"start\" -3,\n\"stop\" 1"),
            "bad.mi:50:9: error: start must not be negative, found -3".to_string(),
        ),
        (
            replaced(&text, physical, "\"physical_light\" (\"color\" 1e30 1 1"),
            "bad.mi:50:1: error: the light's emitted \"color\" 7.957747154594767e28 is brighter \
             than stagelight carries (at most 1e20)\n  help: radiant values above 1e20 overflow \
             f32 arithmetic in sampling; scale the scene's light down (the camera's imager \
             exposure can scale the image back)"
                .to_string(),
        ),
        (
            replaced(&text, "aspect 1.33333333333", "aspect 0"),
            "bad.mi:27:10: error: the vertical field of view 2·atan(aperture / (2·focal·aspect)) \
             must be between 0 and 180 degrees (exclusive), found 180\n  help: the camera's \
             `aperture`, `focal` and `aspect` give the view's vertical angle: with `aspect` and \
             `focal` above 0 and an `aperture` of a few times `focal` or less it lies well below \
             180 degrees\n\
             bad.mi:28:8: error: aspect must be positive, found 0"
                .to_string(),
        ),
        (
            replaced(
                &text,
                "origin 0.0 0.0 0.0\n",
                "origin 0.0 0.0 0.0\nrectangle 1 0 0  2 0 0\n",
            ),
            "bad.mi:55:11: error: the two edges of `rectangle` must span a non-zero area"
                .to_string(),
        ),
        (
            replaced(
                &replaced(&text, "\"mib_light_point\" (", "\"mib_light_spot\" ("),
                "origin 0.0 0.0 0.0\n",
                "origin 0.0 0.0 0.0\ndirection 0 0 0\nspread 0.9\n",
            ),
            "bad.mi:55:11: error: direction must not be zero".to_string(),
        ),
    ];
    for (bad, want) in cases {
        assert_eq!(messages(&dir, "bad.mi", &bad), want);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `.mi` bilinear patch approximated `spatial 0.1 5 2`: its lower subdivision bound above
/// its upper one.
const MI_PATCH: &str = r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space end options
camera "Cam" output "rgb" "png" "out.png" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "Front_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
material "m" "mib_illum_lambert" ("ambient" 1 1 1) end material
object "Tri"
  basis "lin" bezier 1
  group 0 0 0  1 0 0  0 1 0  1 1 0  v 0 v 1 v 2 v 3
  surface "patch" "m" "lin" 0.0 1.0 0.0 1.0 "lin" 0.0 1.0 0.0 1.0 0 1 2 3
  approximate surface spatial 0.1 5 2 "patch"
  end group
end object
instance "Tri_inst" "Tri" material "m" end instance
instgroup "root" "Front_inst" "Tri_inst" end instgroup
render "root" "Front_inst" "opt"
"#;

#[test]
fn mi_subdivision_bounds_are_named_as_the_approximate_statement_writes_them() {
    let dir = dir("mi_subdiv");
    assert_eq!(
        messages(&dir, "c.mi", MI_PATCH),
        "c.mi:10:3: error: the `approximate` statement's min subdivision (5) must not exceed \
         its max subdivision (2)"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A RIB scene: a point light, then `SHAPE` under `ATTRS`.
fn rib(attrs: &str, shape: &str) -> String {
    format!(
        "Format 32 24 1\nWorldBegin\nLightSource \"pointlight\" 1 \"intensity\" [4]\n\
         Translate 0 0 3\n{attrs}\n{shape}\nWorldEnd\n"
    )
}

const SPHERE: &str = "Sphere 1 -1 1 360";

#[test]
fn rib_surface_and_light_values_are_named_by_their_rib_parameters() {
    let dir = dir("rib_values");
    let cases = [
        (
            rib("Surface \"plastic\" \"Kd\" -0.5", SPHERE),
            "t.rib:5:24: error: Kd of \"plastic\" must not be negative, found -0.5",
        ),
        // Once, as written: not three times as the `specular` colour Ks × specularcolor.
        (
            rib("Surface \"plastic\" \"Ks\" -0.5", SPHERE),
            "t.rib:5:24: error: Ks of \"plastic\" must not be negative, found -0.5",
        ),
        (
            rib("Surface \"plastic\" \"specularcolor\" [1 -1 1]", SPHERE),
            "t.rib:5:38: error: specularcolor of \"plastic\" must not be negative, found 1 -1 1",
        ),
        (
            rib("Surface \"metal\" \"roughness\" 0", SPHERE),
            "t.rib:5:29: error: roughness of \"metal\" must be positive, found 0",
        ),
        (
            rib("Surface \"matte\" \"Ka\" 1e39", SPHERE),
            "t.rib:5:22: error: Ka of \"matte\" 1e39 is beyond the f32 range",
        ),
        (
            rib("AreaLightSource \"arealight\" 5 \"intensity\" -1", SPHERE),
            "t.rib:5:43: error: intensity of \"arealight\" must not be negative, found -1",
        ),
        (
            rib(
                "LightSource \"pointlight\" 2 \"lightcolor\" [-1 1 1]",
                SPHERE,
            ),
            "t.rib:5:41: error: lightcolor must not be negative, found -1\n  help: lightcolor takes 0 or more: write 1 if only the sign is wrong",
        ),
        (
            rib("LightSource \"pointlight\" 2 \"intensity\" 1e30", SPHERE),
            "t.rib:5:40: error: intensity × lightcolor 1e30 is brighter than stagelight carries \
             (at most 1e20)\n  help: radiant values above 1e20 overflow f32 arithmetic in \
             sampling; scale the scene's light down (the camera's imager exposure can scale the \
             image back)",
        ),
        (
            rib(
                "LightSource \"myLight\" 2 \"float near\" 5 \"float far\" 1",
                SPHERE,
            ),
            "t.rib:5:52: error: far must be greater than near (5), found 1\n  \
             help: light falls off linearly from full at `near` to none at `far`",
        ),
        (
            rib(
                "LightSource \"spotlight\" 2 \"beamdistribution\" -1",
                SPHERE,
            ),
            "t.rib:5:46: error: beamdistribution must not be negative, found -1\n  help: beamdistribution takes 0 or more: write 1 if only the sign is wrong",
        ),
        (
            rib(
                "LightSource \"spotlight\" 2 \"from\" [0 1 0] \"to\" [0 1 0]",
                SPHERE,
            ),
            "t.rib:5:47: error: \"to\" must differ from \"from\"",
        ),
        (
            rib(
                "LightSource \"distantlight\" 2 \"from\" [1 1 1] \"to\" [1 1 1]",
                SPHERE,
            ),
            "t.rib:5:50: error: \"to\" must differ from \"from\"",
        ),
        (
            rib("Atmosphere \"fog\" \"background\" [-1 0 0]", SPHERE),
            "t.rib:5:32: error: background of \"fog\" must not be negative, found -1 0 0",
        ),
        (
            rib(
                "Attribute \"displacementbound\" \"sphere\" [-1]\nDisplacement \"sine\"",
                SPHERE,
            ),
            "t.rib:5:40: error: object \"sphere_1\" (displacement): parameter `displacementbound` \
             = -1 is out of range (expected ≥ 0)",
        ),
    ];
    for (bad, want) in cases {
        assert_eq!(messages(&dir, "t.rib", &bad), want, "{bad}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn rib_quadric_parameters_are_named_as_the_requests_write_them() {
    let dir = dir("rib_quadrics");
    let cases = [
        (
            rib("", "Sphere 1 2 3 360"),
            "t.rib:6:12: error: object \"sphere_1\" (sphere): parameter `zmax` = 3 is out of \
             range (expected > zmin, both clamped to [-radius, radius])",
        ),
        (
            rib("", "Torus 1 0.2 30 20 360"),
            "t.rib:6:16: error: object \"torus_1\" (torus): parameter `phimax` = 20 is out of \
             range (expected phimin < phimax ≤ phimin + 360)",
        ),
        (
            rib("", "Torus 1 -0.2 0 360 360"),
            "t.rib:6:9: error: object \"torus_1\" (torus): parameter `minorradius` = -0.2 is out \
             of range (expected > 0)",
        ),
        (
            rib("", "Cylinder 1 0 1 0"),
            "t.rib:6:16: error: object \"cylinder_1\" (cylinder): parameter `thetamax` = 0 is out \
             of range (expected (0, 360] degrees)",
        ),
    ];
    for (bad, want) in cases {
        assert_eq!(messages(&dir, "t.rib", &bad), want, "{bad}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same values written in RON keep their RON names.
#[test]
fn ron_values_keep_their_ron_names() {
    let dir = dir("ron_values");
    let scene = |material: &str, light: &str, options: &str| {
        format!(
            "Scene(\n    options: ({options}),\n    materials: [{material}],\n    lights: [{light}],\n    objects: [(name: \"q\", mesh: Sphere(radius: 1.0), material: \"m\")],\n    instances: [(name: \"qi\", of: \"q\")],\n    groups: [(name: \"world\", members: [\"qi\"])],\n    cameras: [(name: \"cam\", fov_y: 40.0, resolution: (8, 8),\n        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)), outputs: [(file: \"o.png\"), (file: \"l.svg\")])],\n    render: (root: \"world\", camera: \"cam\"),\n)\n"
        )
    };
    let lamp = "(name: \"sun\", kind: Point(position: (0, 0, 3)), intensity: 10.0)";
    let contour =
        |c: &str| format!("(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)), contour: {c})");
    let plain = contour("Simple(color: (0, 0, 0, 1), width: 0.5)");
    let cases = [
        (
            scene(
                &contour("WidthFromLight(color: (0, 0, 0, 1), dark_width: -1, lit_width: 0.5)"),
                lamp,
                "contours: ()",
            ),
            "s.ron:3:128: error: contour dark_width must be positive, found -1\n  help: widths \
             are in percent of the smaller image dimension, e.g. `width: 0.5`; to draw no \
             contours, leave out `contour`",
        ),
        (
            scene(
                &contour("Layered(color: (0, 0, 0, 1), width: 0.5, thinning: 2)"),
                lamp,
                "contours: ()",
            ),
            "s.ron:3:131: error: thinning must be in (0, 1], found 2",
        ),
        (
            scene(
                &plain,
                lamp,
                "contours: (contrast: (normal_angle: 200))",
            ),
            "s.ron:2:51: error: normal_angle must be in (0, 180] degrees, found 200",
        ),
        (
            scene(
                &plain,
                "(name: \"sun\", kind: Point(position: (0, 0, 3)), intensity: 10.0, attenuation: Some((2, 1)))",
                "contours: ()",
            ),
            "s.ron:4:101: error: attenuation end must be greater than start (2), found 1\n  \
             help: light falls off linearly from full at `start` to none at `end`",
        ),
        (
            scene(
                &plain,
                "(name: \"sun\", kind: Point(position: (0, 0, 3)), intensity: 1e30)",
                "contours: ()",
            ),
            "s.ron:4:73: error: color × intensity 1e30 is brighter than stagelight carries (at \
             most 1e20)\n  help: radiant values above 1e20 overflow f32 arithmetic in sampling; \
             scale the scene's light down (the camera's imager exposure can scale the image back)",
        ),
    ];
    for (bad, want) in cases {
        assert_eq!(messages(&dir, "s.ron", &bad), want, "{bad}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
