//! Matrices printed with a few digits (tester report 45, problem 1): a `.mi` instance
//! `transform` rounded to 4 digits is inverted as the affine transform it is (no stray
//! bottom row), a camera rotation rounded to 3 or 4 digits (`.mi` and RIB) renders as the
//! exact rotation, a uniformly scaled `.mi` camera instance renders as the unscaled one with
//! the scale in `space_scale`; a projective row, a sheared camera and a sheared RIB camera
//! transformation are still refused, at the matrix.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::desc::PlacementDesc;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene_str;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// √½ as the exact scenes write it.
const EXACT: &str = "0.70710678";

/// A 16 × 16 `.mi` scene: a constant-white triangle placed by `tri`, looked at by the
/// camera instance `transform` `cam` (both 16 numbers, row by row).
fn mi_scene(cam: &str, tri: &str) -> String {
    format!(
        r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space end options
camera "Camera" output "rgb" "png" "out.png" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "Camera_inst" "Camera" transform {cam} end instance
material "m" opaque "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 1 1 1) end material
object "Tri" group 0 0 0  1 0 0  0 1 0  v 0 v 1 v 2  p "m" 0 1 2 end group end object
instance "Tri_inst" "Tri" material "m" transform {tri} end instance
instgroup "root" "Camera_inst" "Tri_inst" end instgroup
render "root" "Camera_inst" "opt"
"#
    )
}

/// The identity, and a camera 5 units back (world → camera).
const IDENTITY: &str = "1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1";
const BACK_5: &str = "1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1";

/// A 45° turn about z (`c` for √½).
fn turn_z(c: &str) -> String {
    format!("{c} {c} 0 0  -{c} {c} 0 0  0 0 1 0  0 0 0 1")
}

/// A 45° turn about y, 5 units back (`c` for √½).
fn camera_turn_y(c: &str) -> String {
    format!("{c} 0 {c} 0  0 1 0 0  -{c} 0 {c} 0  0 0 -5 1")
}

/// The beauty pass of `text` read as `name`.
fn beauty(text: &str, name: &str) -> Vec<Vec3> {
    let mut s = load_scene_str(text, Path::new(name)).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut s.world, s.settings.clone());
    frame.outputs.image.expect("an image").beauty
}

/// The largest difference of a channel between two images of the same size.
fn largest_difference(a: &[Vec3], b: &[Vec3]) -> f32 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0, f32::max)
}

/// Pixels that see the white triangle.
fn lit(image: &[Vec3]) -> usize {
    image.iter().filter(|p| p.x > 0.5).count()
}

/// The tester's `rot.mi` (`0.7071` in the triangle's `transform`) used to be refused as
/// "the last row … found (-0, 0, -0, 0.9999999999999999)"; it renders as the scene written
/// with `0.70710678`, and the turn shows (not the unturned triangle).
#[test]
fn an_instance_transform_rounded_to_4_digits_renders_like_the_exact_one() {
    let rounded = beauty(&mi_scene(BACK_5, &turn_z("0.7071")), "rot.mi");
    let exact = beauty(&mi_scene(BACK_5, &turn_z(EXACT)), "rot.mi");
    assert!(largest_difference(&rounded, &exact) <= 1e-3);
    let unturned = beauty(&mi_scene(BACK_5, IDENTITY), "rot.mi");
    assert!(lit(&rounded) > 0 && rounded != unturned);
}

/// A camera instance turned with `0.7071` or `0.707` renders as the one turned with
/// `0.70710678` (the rotation is snapped, the translation kept as written).
#[test]
fn a_camera_rotation_rounded_to_3_or_4_digits_renders_like_the_exact_one() {
    let exact = beauty(&mi_scene(&camera_turn_y(EXACT), IDENTITY), "c.mi");
    for c in ["0.7071", "0.707"] {
        let rounded = beauty(&mi_scene(&camera_turn_y(c), IDENTITY), "c.mi");
        assert!(largest_difference(&rounded, &exact) <= 1e-3, "{c}");
    }
    let unturned = beauty(&mi_scene(BACK_5, IDENTITY), "c.mi");
    assert!(lit(&exact) > 0 && exact != unturned);
}

/// `transform 0.5 … 0 0 -2.5 1` (the camera 5 world units back, camera space at half the
/// world's scale) renders as the unscaled camera and keeps the scale as `space_scale`.
#[test]
fn a_uniformly_scaled_mi_camera_renders_like_the_unscaled_one() {
    let scaled = mi_scene("0.5 0 0 0  0 0.5 0 0  0 0 0.5 0  0 0 -2.5 1", IDENTITY);
    let read = read_mi(Path::new("s.mi"), scaled.as_bytes()).unwrap_or_else(|e| panic!("{}", e[0]));
    let camera = &read.desc.cameras[0];
    assert_eq!(camera.space_scale, Some(0.5));
    let PlacementDesc::Matrix(m) = camera.placement else {
        panic!("{:?}", camera.placement)
    };
    assert_eq!(
        m,
        [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 5.0],
            [0.0, 0.0, 0.0, 1.0]
        ]
    );
    let image = beauty(&scaled, "s.mi");
    assert!(lit(&image) > 0);
    assert_eq!(image, beauty(&mi_scene(BACK_5, IDENTITY), "s.mi"));
}

/// A 16 × 16 RIB scene of a constant triangle seen through `camera` (requests before
/// `WorldBegin`, on lines 3…).
fn rib_scene(camera: &str) -> String {
    format!(
        "Format 16 16 1\nPixelSamples 1 1\n{camera}\nWorldBegin\nSurface \"constant\"\n\
         Polygon \"P\" [0 0 0  1 0 0  0 1 0]\nWorldEnd\n"
    )
}

/// `ConcatTransform` with a 45° turn about y written `c` for √½, 5 units back.
fn rib_turn(c: &str) -> String {
    format!("ConcatTransform [{c} 0 {c} 0  0 1 0 0  -{c} 0 {c} 0  0 0 5 1]")
}

/// The tester's `rc3.rib` (`0.707`) was refused as not rigid; it renders as the camera
/// written with `0.70710678`, without a `space_scale` (3-digit rounding is no scale).
#[test]
fn a_rib_camera_rotation_rounded_to_3_digits_renders_like_the_exact_one() {
    let exact = beauty(&rib_scene(&rib_turn(EXACT)), "c.rib");
    let rounded_text = rib_scene(&rib_turn("0.707"));
    let rounded = beauty(&rounded_text, "c.rib");
    assert!(largest_difference(&rounded, &exact) <= 1e-3);
    let unturned = beauty(&rib_scene("Translate 0 0 5"), "c.rib");
    assert!(lit(&exact) > 0 && exact != unturned);
    let scene = load_scene_str(&rounded_text, Path::new("c.rib")).unwrap();
    let mut cameras = scene.world.query::<&stagelight::components::Camera>();
    let camera = cameras.iter().next().map(|c| c.space_scale);
    assert_eq!(camera, Some(1.0));
}

/// Runs `stagelight check` on `text` written as `name`: exit code and stderr.
fn check(test: &str, name: &str, text: &str) -> (Option<i32>, String) {
    let dir = scratch_dir(test);
    std::fs::write(dir.join(name), text).unwrap();
    let o = run_in(&dir, &["check", name]);
    (o.status.code(), stderr_of(&o))
}

const MI_RIGID_HELP: &str = "a camera instance's transform may rotate, move and scale evenly, \
                             but not shear, stretch unevenly or mirror: scale the objects' \
                             instances instead";

const RIB_RIGID_HELP: &str = "a camera is placed by a rotation and a translation only: its axes \
                              must be at right angles and not mirrored";

const NOT_RIGID: &str = "error: a camera matrix must be rigid: orthonormal rotation with \
                         determinant 1, no scale, shear or mirroring";

/// A sheared `.mi` camera instance is refused at its `transform`'s first number (line 5,
/// after `instance "Camera_inst" "Camera" transform `), a projective row of a `.mi`
/// instance at the number out of place.
#[test]
fn a_sheared_or_projective_mi_matrix_is_refused_at_the_matrix() {
    let sheared = mi_scene("1 0 0 0  0.3 1 0 0  0 0 1 0  0 0 -5 1", IDENTITY);
    let (code, err) = check("mi-shear-camera", "s.mi", &sheared);
    assert_eq!(code, Some(1));
    assert_eq!(
        err,
        format!("s.mi:5:43: {NOT_RIGID}\n  help: {MI_RIGID_HELP}\n1 error in s.mi\n")
    );
    // Through an instance group: at the group instance's transform that shears.
    let nested = sheared
        .replace(
            "transform 1 0 0 0  0.3 1 0 0  0 0 1 0  0 0 -5 1",
            &format!("transform {BACK_5}"),
        )
        .replace(
            "instgroup \"root\" \"Camera_inst\" \"Tri_inst\" end instgroup",
            "instgroup \"rig\" \"Camera_inst\" end instgroup\n\
             instance \"Rig_inst\" \"rig\" transform 1 0 0 0  0 2 0 0  0 0 1 0  0 0 0 1 end instance\n\
             instgroup \"root\" \"Rig_inst\" \"Tri_inst\" end instgroup",
        );
    let (code, err) = check("mi-shear-rig", "s.mi", &nested);
    assert_eq!(code, Some(1));
    assert_eq!(
        err,
        format!("s.mi:10:37: {NOT_RIGID}\n  help: {MI_RIGID_HELP}\n1 error in s.mi\n")
    );

    let projective = mi_scene(BACK_5, "1 0 0 0  0 1 0 0  0 0 1 -1  0 0 0 1");
    let (code, err) = check("mi-projective-row", "p.mi", &projective);
    assert_eq!(code, Some(1));
    assert_eq!(
        err,
        "p.mi:8:74: error: the last column of a transform must be (0, 0, 0, w) with w ≠ 0, found (0, 0, -1, 1)\n  \
         help: an instance transform is affine, written row by row with the translation in the last row: \
         its last column is (0, 0, 0, 1), or (0, 0, 0, w) for a matrix scaled by w\n\
         1 error in p.mi\n"
    );
}

/// A sheared RIB camera transformation is refused at the request that sheared it (line 4's
/// `Scale`, not the `Translate` after it or `WorldBegin`).
#[test]
fn a_sheared_rib_camera_is_refused_at_the_request_that_shears_it() {
    let text = rib_scene("Rotate 30 0 1 0\nScale 1 2 1\nTranslate 0 0 5");
    let (code, err) = check("rib-shear-camera", "s.rib", &text);
    assert_eq!(code, Some(1));
    assert_eq!(
        err,
        format!("s.rib:4:1: {NOT_RIGID}\n  help: {RIB_RIGID_HELP}\n1 error in s.rib\n")
    );
    let text = rib_scene("ConcatTransform [1 0 0 0  0.3 1 0 0  0 0 1 0  0 0 5 1]");
    let (code, err) = check("rib-shear-concat", "s.rib", &text);
    assert_eq!(code, Some(1));
    assert_eq!(
        err,
        format!("s.rib:3:1: {NOT_RIGID}\n  help: {RIB_RIGID_HELP}\n1 error in s.rib\n")
    );
}

/// A RON transform matrix whose bottom row a general inverse left a few bits off is
/// (0, 0, 0, 1); a projective bottom row is still refused at the row.
#[test]
fn a_ron_bottom_row_a_few_bits_off_is_affine_a_projective_one_is_refused() {
    let scene = |row: &str| {
        format!(
            "Scene(\n    objects: [(name: \"tri\", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]))],\n    \
             instances: [(name: \"t\", of: \"tri\", transform: [Matrix(((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), {row}))])],\n    \
             groups: [(name: \"world\", members: [\"t\"])],\n    \
             cameras: [(name: \"cam\", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 1), target: (0, 0, 0)))],\n    \
             render: (root: \"world\", camera: \"cam\"),\n)\n"
        )
    };
    load_scene_str(
        &scene("(-0, 0, -0, 0.9999999999999999)"),
        Path::new("t.ron"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (code, err) = check("ron-projective-row", "t.ron", &scene("(0, 0, -1, 1)"));
    assert_eq!(code, Some(1));
    assert_eq!(
        err,
        "t.ron:3:102: error: the last row of a transform matrix must be (0, 0, 0, 1), found (0, 0, -1, 1)\n  \
         help: the rows are written in order with the translation in the last column, \
         `((a, b, c, tx), (d, e, f, ty), (g, h, i, tz), (0, 0, 0, 1))`: a matrix written column by \
         column (translation in the last row) must be transposed\n\
         1 error in t.ron\n"
    );
}
