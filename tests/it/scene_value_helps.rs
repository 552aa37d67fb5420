//! Every value error a hand-written scene commonly meets says what to write instead: one
//! table of small edits to a valid scene, each with the exact report `check` prints (the
//! errors and their `help:` lines). The helps are in the scene file's own syntax: a `.mi`
//! or RIB file reaching the same checks gets no RON in its help.

use crate::common::{run_in, scratch_dir, stderr_of};

/// A valid scene; each case replaces one piece of it.
const BASE: &str = r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (8, 8), placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0)), outputs: [(file: "o.png")])],
    lights: [(name: "key", kind: Point(position: (0, 4, 2)), intensity: 10.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "tri", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]), material: "grey")],
    instances: [(name: "t", of: "tri")],
    groups: [(name: "world", members: ["t"])],
    render: (root: "world", camera: "cam"),
)
"#;

const INLINE: &str =
    "mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]])";

/// (case, what is replaced, by what, `file:line:col: error: …` after `<case>.ron:`, help).
const CASES: &[(&str, &str, &str, &str, &str)] = &[
    (
        "zero_scale",
        r#"(name: "t", of: "tri")"#,
        r#"(name: "t", of: "tri", transform: [Scale((1, 0, 1))])"#,
        "6:52: error: scale (1, 0, 1) has a zero component: the transform is not invertible",
        "every factor must be non-zero: 1 keeps an axis as it is, and a thin object takes a small factor such as 0.001 (a negative factor mirrors)",
    ),
    (
        "zero_axis",
        r#"(name: "t", of: "tri")"#,
        r#"(name: "t", of: "tri", transform: [Rotate(axis: (0, 0, 0), degrees: 30)])"#,
        "6:65: error: rotation axis must not be zero",
        "the axis is the direction to turn about: `axis: (0, 1, 0)` turns about y, `(1, 0, 0)` about x",
    ),
    (
        "singular",
        r#"(name: "t", of: "tri")"#,
        r#"(name: "t", of: "tri", transform: [Matrix(((1, 0, 0, 0), (0, 0, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)))])"#,
        "6:52: error: transform matrix is singular (determinant 0): not invertible",
        "the matrix flattens space onto a plane, a line or a point (a scale of 0, or two axes mapped to the same direction): every axis must keep a non-zero length and a direction of its own",
    ),
    (
        "last_row",
        r#"(name: "t", of: "tri")"#,
        r#"(name: "t", of: "tri", transform: [Matrix(((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, -1, 1)))])"#,
        "6:102: error: the last row of a transform matrix must be (0, 0, 0, 1), found (0, 0, -1, 1)",
        "the rows are written in order with the translation in the last column, `((a, b, c, tx), (d, e, f, ty), (g, h, i, tz), (0, 0, 0, 1))`: a matrix written column by column (translation in the last row) must be transposed",
    ),
    (
        "not_rigid",
        "placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0))",
        "placement: Matrix(((2, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 5), (0, 0, 0, 1)))",
        "2:78: error: a camera matrix must be rigid: orthonormal rotation with determinant 1, no scale, shear or mirroring",
        "the 3×3 part must be a rotation (columns of length 1 at right angles, determinant 1): scale the objects instead, or place the camera with `LookAt(eye: …, target: …, up: …)`",
    ),
    (
        "fov_200",
        "fov_y: 40",
        "fov_y: 200",
        "2:36: error: fov_y must be between 0 and 180 degrees (exclusive), found 200",
        "fov_y is the full vertical angle of the view in degrees, such as 40 (a normal lens) or 90 (a wide one); a view of 180° or more needs a fisheye lens, `lens: [Fisheye(fov: 180)]`",
    ),
    (
        "fov_0",
        "fov_y: 40",
        "fov_y: 0",
        "2:36: error: fov_y must be between 0 and 180 degrees (exclusive), found 0",
        "fov_y is the full vertical angle of the view in degrees, such as 40 (a normal lens) or 90 (a wide one)",
    ),
    (
        "intensity",
        "intensity: 10.0",
        "intensity: -3",
        "3:73: error: intensity must not be negative, found -3",
        "intensity takes 0 or more: write 3 if only the sign is wrong",
    ),
    (
        "albedo",
        "albedo: (0.5, 0.5, 0.5)",
        "albedo: (2, 0.5, 0.5)",
        "4:57: error: albedo must be at most 1 (energy conservation), found 2",
        "albedo is the fraction of the light arriving that goes on, 0 to 1 per channel (0.8 is a bright white): a surface that gives off light of its own needs an emission, not more albedo",
    ),
    (
        "cone",
        "kind: Point(position: (0, 4, 2))",
        "kind: Spot(position: (0, 4, 2), target: (0, 0, 0), cone_angle: 95)",
        "3:91: error: cone_angle must be in (0, 90] degrees, found 95",
        "cone_angle is the angle in degrees from the spot's axis to the edge of its cone (90 lights a half space, a cone 180° across); a light that shines every way is a point light",
    ),
    (
        "disc",
        "kind: Point(position: (0, 4, 2))",
        "kind: Disc(center: (0, 4, 2), normal: (0, -1, 0), radius: 0)",
        "3:86: error: radius must be positive, found 0",
        "the radius is the light's size in scene units, above 0 (such as 0.5); a light with no size is a point light",
    ),
    (
        "resolution",
        "resolution: (8, 8)",
        "resolution: (0, 8)",
        "2:53: error: resolution width must be at least 1, found 0",
        "the image is width × height pixels, each at least 1: `resolution: (640, 480)`",
    ),
    (
        "eye_target",
        "target: (0, 0, 0))",
        "target: (0, 0, 5))",
        "2:102: error: target must differ from eye",
        "the camera at eye looks toward target: make target the point to look at, such as the middle of the scene",
    ),
    (
        "up_z",
        "target: (0, 0, 0))",
        "target: (0, 0, 0), up: (0, 0, 1))",
        "2:117: error: up must not be zero or parallel to the view direction",
        "up is the direction that is up in the image; it must lean away from the line from eye to target: `up: (0, 1, 0)` does for this view",
    ),
    (
        "up_y",
        "eye: (0, 0, 5), target: (0, 0, 0))",
        "eye: (0, 5, 0), target: (0, 0, 0))",
        "2:71: error: up must not be zero or parallel to the view direction",
        "up is the direction that is up in the image; it must lean away from the line from eye to target: `up: (0, 0, 1)` does for this view",
    ),
    (
        "pass_twice",
        r#"(file: "o.png")"#,
        r#"(file: "o.exr", passes: [Beauty, Depth, Beauty])"#,
        "2:164: error: pass Beauty is listed twice",
        "an output writes each pass once: remove this Beauty",
    ),
    (
        "no_pass",
        r#"(file: "o.png")"#,
        r#"(file: "o.exr", passes: [])"#,
        "2:148: error: an output needs at least one pass",
        "leave out `passes` to write the Beauty pass, or list the passes to write, such as `passes: [Beauty, Alpha]`",
    ),
    (
        "listed_twice",
        r#"members: ["t"]"#,
        r#"members: ["t", "t"]"#,
        "7:45: error: instance \"t\" is listed twice in group \"world\"",
        "a group places each of its instances once: remove this \"t\", or add a second instance such as `(name: \"t_2\", of: \"tri\", transform: [Translate((2, 0, 0))])` and list that",
    ),
    (
        "missing_obj",
        INLINE,
        r#"mesh: Obj(file: "meshes/cube2.obj")"#,
        "5:45: error: cannot read OBJ file \"meshes/cube2.obj\": file not found",
        "\"meshes/cube2.obj\" is read relative to missing_obj.ron, the file that names it; did you mean \"meshes/cube.obj\"?",
    ),
    (
        "missing_obj_dir",
        INLINE,
        r#"mesh: Obj(file: "models/cube.obj")"#,
        "5:45: error: cannot read OBJ file \"models/cube.obj\": file not found",
        "\"models/cube.obj\" is read relative to missing_obj_dir.ron, the file that names it; there is no directory models",
    ),
    (
        "missing_include",
        "Scene(\n",
        "Scene(\n    include: [\"lib/material.ron\"],\n",
        "2:15: error: cannot read include file \"lib/material.ron\": file not found",
        "\"lib/material.ron\" is read relative to missing_include.ron, the file that names it; did you mean \"lib/materials.ron\"?",
    ),
];

#[test]
fn each_value_error_has_a_help_saying_what_to_write() {
    let dir = scratch_dir("value-helps");
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    std::fs::write(
        dir.join("meshes/cube.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(dir.join("lib/materials.ron"), "Scene()\n").unwrap();
    let mut failures = Vec::new();
    for &(case, from, to, error, help) in CASES {
        assert!(BASE.contains(from), "{case}");
        let file = format!("{case}.ron");
        std::fs::write(dir.join(&file), BASE.replacen(from, to, 1)).unwrap();
        let o = run_in(&dir, &["check", &file]);
        let expected = format!("{file}:{error}\n  help: {help}\n1 error in {file}\n");
        let got = stderr_of(&o);
        if o.status.code() != Some(1) || got != expected {
            failures.push(format!("--- {case}: expected\n{expected}--- got\n{got}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// An instance left without a name is reported once: the group's reference to the name it
/// had is not also "unknown instance" with "no instances are defined" (one is defined).
#[test]
fn an_empty_instance_name_is_not_followed_by_an_unknown_reference() {
    let dir = scratch_dir("value-helps-empty-name");
    let text = BASE.replacen(r#"(name: "t", of: "tri")"#, r#"(name: "", of: "tri")"#, 1);
    std::fs::write(dir.join("s.ron"), text).unwrap();
    let o = run_in(&dir, &["check", "s.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "s.ron:6:24: error: instance name is empty\n1 error in s.ron\n"
    );
}

/// A reference close to a defined name is still reported next to an empty name: its "did
/// you mean" is true.
#[test]
fn a_misspelt_reference_beside_an_empty_name_is_still_reported() {
    let dir = scratch_dir("value-helps-empty-name-typo");
    let text = BASE
        .replacen(
            r#"(name: "t", of: "tri")"#,
            r#"(name: "", of: "tri"), (name: "tee", of: "tri")"#,
            1,
        )
        .replacen(r#"members: ["t"]"#, r#"members: ["tea"]"#, 1);
    std::fs::write(dir.join("s.ron"), text).unwrap();
    let o = run_in(&dir, &["check", "s.ron"]);
    assert_eq!(
        stderr_of(&o),
        "s.ron:6:47: warning: instance \"tee\" is never placed: no group reachable from the render root \"world\" lists it\n  \
         help: add \"tee\" to the `members` of group \"world\" (or of a group placed in it), or remove the instance\n\
         s.ron:6:24: error: instance name is empty\n\
         s.ron:7:40: error: unknown instance \"tea\"\n  help: did you mean \"tee\"?\n\
         2 errors and 1 warning in s.ron\n"
    );
}

/// The `.mi` scene of the tests below: a camera, a light and a quad, with `{camera}`,
/// `{resolution}` marks.
fn mi_scene(camera_transform: &str, resolution: &str) -> String {
    format!(
        r#"options "opt"
object space
end options
camera "cam"
resolution {resolution}
focal 1
aperture 1
end camera
instance "cam_inst" "cam" {camera_transform}end instance
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

/// `.mi` and RIB scenes reach some of the same checks: their helps name `.mi` statements,
/// or no syntax at all, never RON's.
#[test]
fn mi_and_rib_scenes_get_helps_in_their_own_terms() {
    let dir = scratch_dir("value-helps-formats");
    let rib = "Display \"o.png\" \"file\" \"rgb\"\nFormat 8 6 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\nScale 1 0 1\nSphere 1 -1 1 360\nWorldEnd\n";
    let cases = [
        (
            "res.mi",
            mi_scene("", "0 6"),
            "res.mi:5:12: error: resolution width must be at least 1, found 0\n  \
             help: the image is width × height pixels, each at least 1: `resolution 640 480`\n",
        ),
        (
            "shear.mi",
            mi_scene("transform 1 0 0 0 0.5 1 0 0 0 0 1 0 0 0 0 1 ", "8 6"),
            "shear.mi:9:37: error: a camera matrix must be rigid: orthonormal rotation with determinant 1, no scale, shear or mirroring\n  \
             help: a camera instance's transform may rotate, move and scale evenly, but not shear, stretch unevenly or mirror: scale the objects' instances instead\n",
        ),
        (
            "flat.rib",
            rib.to_string(),
            "flat.rib:7:1: error: transform matrix is singular (determinant 0): not invertible\n  \
             help: the matrix flattens space onto a plane, a line or a point (a scale of 0, or two axes mapped to the same direction): every axis must keep a non-zero length and a direction of its own\n",
        ),
    ];
    for (file, text, error) in cases {
        std::fs::write(dir.join(file), text).unwrap();
        let o = run_in(&dir, &["check", file]);
        assert_eq!(o.status.code(), Some(1), "{file}");
        assert_eq!(stderr_of(&o), format!("{error}1 error in {file}\n"));
    }
}
