//! RIB primitive variables of polygon meshes: `st` and `N` per vertex, per face corner
//! (`facevarying`) or, for `N`, per face (`uniform`). A facevarying `st` paints each face
//! with its own texture coordinates (points whose corners differ are split), and a value
//! count that fits no class is a located error naming the counts that would.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use stagelight::scene::desc::MeshDesc;
use stagelight::scene::import::rib::RibScene;

use crate::common::read_rib_text;
use stagelight::scene::{load_scene, load_scene_str};

/// Writes `text` as `name` in a fresh folder of the temporary directory.
fn write_rib(name: &str, text: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_rib_primvars_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Renders the RIB at `path` at its own resolution, without writing files: the beauty pass.
fn render(path: &Path) -> (Vec<Vec3>, usize) {
    let mut scene = load_scene(path).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("an image");
    (image.beauty, image.width as usize)
}

/// The scene read from `text` as `t.rib` (a panic shows the reader's errors).
fn read(text: &str) -> RibScene {
    read_rib_text(text)
}

/// Every message of a refused file.
fn errors(text: &str) -> String {
    match load_scene_str(text, Path::new("t.rib")) {
        Ok(_) => "ok".into(),
        Err(e) => e.to_string(),
    }
}

fn bricks() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/textures/bricks.png")
}

/// Two quads side by side filling a 90° view (the vertical span) at distance 1 of a 2:1
/// image, painted with `bricks.png` under ambient light only: every pixel is the texture at
/// its (s, t). `mesh` is the `PointsPolygons` request.
fn scene(mesh: &str) -> String {
    format!(
        "Format 32 16 1\nPixelSamples 1 1\nPixelFilter \"gaussian\" 0.0001 0.0001\n\
         Exposure 1 1\nProjection \"perspective\" \"fov\" [90]\nWorldBegin\n\
         LightSource \"ambientlight\" 1 \"intensity\" [1]\n\
         Surface \"paintedplastic\" \"Ka\" 1 \"Kd\" 0 \"Ks\" 0 \"texturename\" \"{}\"\n\
         Translate 0 0 1\n{mesh}\nWorldEnd\n",
        bricks().display()
    )
}

/// Each face maps the whole texture, `t` down the image: (0, 1) at its bottom left corner.
const FACE_ST: &str = "0 1  1 1  1 0  0 0";

/// The shared edge's points (1 and 4) take s = 1 in the left face and s = 0 in the right.
fn facevarying() -> String {
    scene(&format!(
        "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] \
         \"P\" [-2 -1 0  0 -1 0  2 -1 0  -2 1 0  0 1 0  2 1 0]\n  \
         \"facevarying float[2] st\" [{FACE_ST}  {FACE_ST}]"
    ))
}

/// The same faces with their own points: per-vertex `st`.
fn per_vertex() -> String {
    scene(&format!(
        "PointsPolygons [4 4] [0 1 2 3  4 5 6 7] \
         \"P\" [-2 -1 0  0 -1 0  0 1 0  -2 1 0  0 -1 0  2 -1 0  2 1 0  0 1 0]\n  \
         \"st\" [{FACE_ST}  {FACE_ST}]"
    ))
}

#[test]
fn facevarying_st_paints_each_face_with_its_own_coordinates() {
    let (beauty, width) = render(&write_rib("facevarying.rib", &facevarying()));
    assert_eq!((width, beauty.len()), (32, 32 * 16));
    let tex = stagelight::shading::texture::image::load(
        &bricks(),
        Some(stagelight::shading::texture::image::Encoding::Linear),
        stagelight::components::graph::Wrap::Repeat,
    )
    .unwrap();
    let mut worst = 0.0f32;
    for y in 0..16 {
        for x in 0..32 {
            // Each half of the image runs s from 0 to 1.
            let s = ((x % 16) as f32 + 0.5) / 16.0;
            let t = (y as f32 + 0.5) / 16.0;
            let expected = tex.sample(Vec2::new(s, 1.0 - t));
            worst = worst.max((beauty[y * width + x] - expected).abs().max_element());
        }
    }
    assert!(worst < 1e-3, "max error {worst}");
    // The two halves are the same picture.
    let halves = (beauty[5 * width + 3] - beauty[5 * width + 19])
        .abs()
        .max_element();
    assert!(halves < 1e-5, "{halves}");
    let (same, _) = render(&write_rib("per_vertex.rib", &per_vertex()));
    let diff = beauty
        .iter()
        .zip(&same)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .fold(0.0f32, f32::max);
    assert!(diff < 1e-5, "per-vertex st renders the same: {diff}");
}

#[test]
fn only_points_whose_corners_differ_are_split() {
    let s = read(&facevarying());
    let MeshDesc::Inline {
        vertices,
        polygons,
        uvs,
        ..
    } = &s.desc.objects[0].mesh
    else {
        panic!("an inline mesh");
    };
    // Points 1 and 4 are copied for the right face (6 and 7); the others stay shared.
    assert_eq!(vertices.len(), 8);
    assert_eq!(polygons, &[vec![0, 1, 4, 3], vec![6, 2, 5, 7]]);
    let uvs = uvs.as_ref().expect("uvs");
    assert_eq!((uvs[1], uvs[4]), ((1.0, 1.0), (1.0, 0.0)));
    assert_eq!((uvs[6], uvs[7]), ((0.0, 1.0), (0.0, 0.0)));
}

#[test]
fn uniform_normals_give_each_face_its_normal() {
    let text = "WorldBegin\nTranslate 0 0 3\nPointsPolygons [4 4] [0 1 4 3  1 2 5 4] \
                \"P\" [-2 -1 0  0 -1 0  2 -1 0  -2 1 0  0 1 0  2 1 0] \
                \"uniform normal N\" [0 0 -1  0 0.6 -0.8]\nWorldEnd\n";
    let s = read(text);
    let MeshDesc::Inline {
        vertices, normals, ..
    } = &s.desc.objects[0].mesh
    else {
        panic!("an inline mesh");
    };
    assert_eq!(vertices.len(), 8);
    let normals = normals.as_ref().expect("normals");
    assert_eq!(
        (normals[0], normals[1]),
        ((0.0, 0.0, -1.0), (0.0, 0.0, -1.0))
    );
    assert_eq!(
        (normals[2], normals[6]),
        ((0.0, 0.6, -0.8), (0.0, 0.6, -0.8))
    );
}

#[test]
fn a_count_that_fits_no_class_is_a_located_error_naming_the_counts() {
    let head = "WorldBegin\nTranslate 0 0 3\n";
    let mesh = "PointsPolygons [4 4] [0 1 4 3 1 2 5 4] \
                \"P\" [-1 -1 0 0 -1 0 1 -1 0 -1 1 0 0 1 0 1 1 0]";
    assert_eq!(
        errors(&format!("{head}{mesh} \"N\" [0 0 -1]\nWorldEnd\n")),
        "t.rib:3:91: error: parameter \"N\" of PointsPolygons takes 18 (3 per vertex, 6 \
         vertices), 24 (3 per face corner, 8 corners) or 6 (3 per face, 2 faces) numbers, \
         found 3"
    );
    assert_eq!(
        errors(&format!("{head}{mesh} \"st\" [0 0 1 0 1 1]\nWorldEnd\n")),
        "t.rib:3:92: error: parameter \"st\" of PointsPolygons takes 12 (2 per vertex, 6 \
         vertices) or 16 (2 per face corner, 8 corners) numbers, found 6"
    );
    assert_eq!(
        errors(&format!(
            "{head}Polygon \"P\" [0 0 0 1 0 0 1 1 0] \"st\" [0 0 1 0]\nWorldEnd\n"
        )),
        "t.rib:3:38: error: parameter \"st\" of Polygon takes 6 numbers (2 per vertex, 3 \
         vertices), found 4"
    );
}
