//! RIB primitive variables of patches and subdivision meshes: `st` (or `s`, `t`) and `N` in
//! each RenderMan class (`vertex`, `varying`, `facevarying`, `uniform`, `constant`) become
//! the surface's texture coordinates and normals, so a textured patch or subdivision mesh
//! shows the texture at the user's `(s, t)`; `s` without `t` (or `t` without `s`) replaces
//! its own coordinate only; a count that fits no class is a located error naming the counts.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use stagelight::scene::desc::{MeshDesc, SurfaceValuesDesc};
use stagelight::scene::import::rib::RibScene;

use crate::common::read_rib_text;
use stagelight::scene::{load_scene, load_scene_str};
use stagelight::shading::texture::image::{load, Encoding, Texture};

/// Writes `text` as `name` in a fresh folder of the temporary directory.
fn write_rib(name: &str, text: &str) -> PathBuf {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight_rib_surface_vars_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The beauty pass of `text` (rendered from a file beside the texture's absolute path).
fn render(name: &str, text: &str) -> (Vec<Vec3>, usize) {
    let mut scene = load_scene(&write_rib(name, text)).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("an image");
    (image.beauty, image.width as usize)
}

/// The scene read from `text` as `t.rib` (a panic shows the reader's errors).
fn read(text: &str) -> RibScene {
    read_rib_text(text)
}

fn bricks() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/textures/bricks.png")
}

fn texture() -> Texture {
    load(
        &bricks(),
        Some(Encoding::Linear),
        stagelight::components::graph::Wrap::Repeat,
    )
    .unwrap()
}

/// A 32 × 16 image of the plane z = 1 (x from −2 to 2, y from −1 to 1, 8 pixels a unit)
/// painted with `bricks.png` under ambient light only: every pixel is the texture at its
/// `(s, t)`. `surface` is the primitive.
fn scene(surface: &str) -> String {
    format!(
        "Format 32 16 1\nPixelSamples 1 1\nPixelFilter \"gaussian\" 0.0001 0.0001\n\
         Exposure 1 1\nProjection \"perspective\" \"fov\" [90]\nWorldBegin\n\
         LightSource \"ambientlight\" 1 \"intensity\" [1]\n\
         Surface \"paintedplastic\" \"Ka\" 1 \"Kd\" 0 \"Ks\" 0 \"texturename\" \"{}\"\n\
         Translate 0 0 1\n{surface}\nWorldEnd\n",
        bricks().display()
    )
}

/// The largest difference between the image and the texture at `st(x, y)` of the pixel
/// centre `(x, y)` in the plane, over the pixels `inside` says.
fn worst(
    (beauty, width): &(Vec<Vec3>, usize),
    st: impl Fn(f32, f32) -> (f32, f32),
    inside: impl Fn(usize, usize) -> bool,
) -> f32 {
    let tex = texture();
    let mut worst = 0.0f32;
    for (i, pixel) in beauty.iter().enumerate() {
        let (px, py) = (i % width, i / width);
        if !inside(px, py) {
            continue;
        }
        let x = (px as f32 + 0.5) / 8.0 - 2.0;
        let y = 1.0 - (py as f32 + 0.5) / 8.0;
        let (s, t) = st(x, y);
        // `t` runs down the image.
        let expected = tex.sample(Vec2::new(s, 1.0 - t));
        worst = worst.max((*pixel - expected).abs().max_element());
    }
    worst
}

/// Two bilinear patches side by side, each with the texture's whole square
/// (`facevarying`: four values a patch, at (u, v) = (0,0), (1,0), (0,1), (1,1)).
const TWO_PATCHES: &str = "PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" \
    \"P\" [-2 -1 0  0 -1 0  2 -1 0  -2 1 0  0 1 0  2 1 0]\n  \
    \"facevarying float[2] st\" [0 1  1 1  0 0  1 0   0 1  1 1  0 0  1 0]";

#[test]
fn facevarying_st_paints_each_patch_with_its_own_coordinates() {
    let image = render("facevarying.rib", &scene(TWO_PATCHES));
    assert_eq!((image.1, image.0.len()), (32, 32 * 16));
    // Each half runs s from 0 to 1 and t from 0 (top) to 1.
    let st = |x: f32, y: f32| ((x + 2.0) % 2.0 / 2.0, (1.0 - y) / 2.0);
    let e = worst(&image, st, |_, _| true);
    assert!(e < 1e-3, "max error {e}");
}

#[test]
fn varying_st_on_a_patch_and_s_alone_follow_the_closed_form() {
    // s = 2u (the texture twice across), t = 1 − v: both differ from the defaults (u, v).
    let patch = "Patch \"bilinear\" \"P\" [-2 -1 0  2 -1 0  -2 1 0  2 1 0] \
                 \"varying float[2] st\" [0 1  2 1  0 0  2 0]";
    let image = render("varying.rib", &scene(patch));
    let st = |x: f32, y: f32| (2.0 * (x + 2.0) / 4.0, (1.0 - y) / 2.0);
    let e = worst(&image, st, |_, _| true);
    assert!(e < 1e-3, "max error {e}");
    // `s` alone: t stays the parametric v (0 at the bottom).
    let patch = "Patch \"bilinear\" \"P\" [-2 -1 0  2 -1 0  -2 1 0  2 1 0] \
                 \"varying float s\" [0 2 0 2]";
    let image = render("s_alone.rib", &scene(patch));
    let st = |x: f32, y: f32| (2.0 * (x + 2.0) / 4.0, (y + 1.0) / 2.0);
    let e = worst(&image, st, |_, _| true);
    assert!(e < 1e-3, "max error {e}");
}

#[test]
fn vertex_st_on_a_subdivision_mesh_is_refined_with_the_points() {
    // A flat 4 × 2 grid of faces over x ∈ [−4, 4], y ∈ [−3, 3], with s = x/4, t = 0.5 − y/4
    // at its points: refinement is affine, so the limit's (s, t) is the same function of
    // the limit's points. Its boundary shrinks; the pixels inside |x| < 3, |y| < 2 are
    // covered.
    let mut points = String::new();
    let mut st = String::new();
    for j in 0..3 {
        for i in 0..5 {
            let (x, y) = (-4.0 + 2.0 * i as f64, -3.0 + 3.0 * j as f64);
            points += &format!("{x} {y} 0  ");
            st += &format!("{} {}  ", x / 4.0, 0.5 - y / 4.0);
        }
    }
    let mut faces = String::new();
    for j in 0..2 {
        for i in 0..4 {
            let a = 5 * j + i;
            faces += &format!("{} {} {} {}  ", a, a + 1, a + 6, a + 5);
        }
    }
    let mesh = format!(
        "SubdivisionMesh \"catmull-clark\" [4 4 4 4 4 4 4 4] [{faces}] [] [] [] [] \
         \"P\" [{points}] \"vertex float[2] st\" [{st}]"
    );
    let image = render("subdiv.rib", &scene(&mesh));
    let e = worst(&image, |x, y| (x / 4.0, 0.5 - y / 4.0), |_, _| true);
    assert!(e < 1e-3, "max error {e}");
}

#[test]
fn normals_and_coordinates_keep_their_classes_in_the_description() {
    let s = read(&format!(
        "WorldBegin\n{TWO_PATCHES} \"uniform normal N\" [0 0 -1  0 0.6 -0.8]\nWorldEnd\n"
    ));
    let MeshDesc::PatchMesh { variables, .. } = &s.desc.objects[0].mesh else {
        panic!("a patch mesh");
    };
    // One normal per patch, at its four corners.
    let n0 = (0.0, 0.0, -1.0);
    let n1 = (0.0, 0.6, -0.8);
    assert_eq!(
        variables.normals,
        Some(SurfaceValuesDesc::Corners(vec![
            n0, n0, n0, n0, n1, n1, n1, n1
        ]))
    );
    assert_eq!(
        variables.s,
        Some(SurfaceValuesDesc::Corners(vec![
            0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0
        ]))
    );
    // `vertex` on a bicubic patch: one per control point, interpolated like P.
    let mut p = String::new();
    for j in 0..4 {
        for i in 0..4 {
            p += &format!("{i} {j} 0 ");
        }
    }
    let s = read(&format!(
        "WorldBegin\nPatch \"bicubic\" \"P\" [{p}] \"vertex float t\" [{}]\nWorldEnd\n",
        "0.5 ".repeat(16)
    ));
    let MeshDesc::PatchMesh { variables, .. } = &s.desc.objects[0].mesh else {
        panic!("a patch mesh");
    };
    assert_eq!(variables.t, Some(SurfaceValuesDesc::Control(vec![0.5; 16])));
    assert_eq!(variables.s, None);
    // A polygon: `t` alone, with s = 0 (a polygon has no parametric coordinates).
    let s = read("WorldBegin\nPolygon \"P\" [0 0 0 1 0 0 1 1 0] \"t\" [0.25 0.5 0.75]\nWorldEnd\n");
    let MeshDesc::Inline { uvs, .. } = &s.desc.objects[0].mesh else {
        panic!("an inline mesh");
    };
    assert_eq!(
        uvs.as_deref(),
        Some(&[(0.0, 0.25), (0.0, 0.5), (0.0, 0.75)][..])
    );
}

#[test]
fn a_count_that_fits_no_class_is_a_located_error_naming_the_counts() {
    let n = "0 0 -1 ".repeat(4);
    let text = format!("WorldBegin\n{TWO_PATCHES} \"N\" [{n}]\nWorldEnd\n");
    let e = match load_scene_str(&text, Path::new("t.rib")) {
        Ok(_) => "ok".to_string(),
        Err(e) => e.to_string(),
    };
    assert_eq!(
        e,
        "t.rib:3:75: error: parameter \"N\" of PatchMesh takes 18 (3 per vertex, 6 vertices), \
         24 (3 per patch corner, 8 patch corners), 6 (3 per patch, 2 patches) or 3 (constant) \
         numbers, found 12"
    );
}
