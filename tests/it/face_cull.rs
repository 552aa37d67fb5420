//! `face: Cull` (mental ray's `options` `face front`, RenderMan's `Sides 1`): the back face
//! of a one-sided surface is left out of every ray, which goes on beyond it. Camera rays see
//! what lies behind a sheet seen from its back (the closed-form lit wall, not black);
//! shadow rays, traced from the shaded point toward the light, are blocked by a sheet whose
//! front faces the point and pass one whose back does; RIB `Sides 1` culls the inside
//! (`.mi` `face front` reading as `Cull`: `mi_controls`).

use std::path::Path;

use stagelight::scene::load_scene_str;

use crate::common::render;

/// Image side, pixels.
const SIDE: u32 = 32;
/// World width of one pixel on the wall (z = 0) seen from z = 10 with a 40° field of view.
fn pixel_width() -> f32 {
    2.0 * 10.0 * 20f32.to_radians().tan() / SIDE as f32
}

/// The column whose centre ray meets the wall nearest `x` (row through y = 0).
fn column(x: f32) -> u32 {
    (SIDE as f32 / 2.0 + x / pixel_width()).floor() as u32
}

/// Irradiance of the directional light on a facing surface, W/m².
const SUN: f32 = 2.0;
/// Wall and sheet albedos.
const WALL: f32 = 0.5;
const SHEET: f32 = 0.8;

/// Radiance of a Lambert surface of albedo `rho` lit by the sun at 45°.
fn lit(rho: f32) -> f32 {
    rho / std::f32::consts::PI * SUN * std::f32::consts::FRAC_1_SQRT_2
}

/// Looking straight down from z = 10 at a Lambert wall (z = 0, facing up) under a sun
/// travelling along (−1, 0, −1); a one-sided Lambert sheet at z = 2 over x, y ∈ [−0.5, 0.5]
/// facing down (`facing_up` false: the camera and the sun meet its back) or up. Its shadow
/// on the wall is x ∈ [−2.5, −1.5], which the camera sees beside the sheet.
fn scene(face: &str, facing_up: bool, with_sheet: bool) -> String {
    let sheet = if facing_up {
        "[0, 1, 2, 3]"
    } else {
        "[3, 2, 1, 0]"
    };
    let members = if with_sheet {
        r#""wall_1", "sheet_1""#
    } else {
        r#""wall_1""#
    };
    format!(
        r#"Scene(
    options: (samples: 1, face: {face}),
    cameras: [(name: "cam", fov_y: 40, resolution: ({SIDE}, {SIDE}),
        placement: LookAt(eye: (0, 0, 10), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "cull.png")])],
    lights: [(name: "sun", kind: Directional(direction: (-1, 0, -1)), intensity: {SUN})],
    materials: [
        (name: "wall", shader: Lambert(albedo: ({WALL}, {WALL}, {WALL}))),
        (name: "sheet", shader: Lambert(albedo: ({SHEET}, {SHEET}, {SHEET}))),
    ],
    objects: [
        (name: "wall", mesh: Inline(vertices: [(-6, -6, 0), (6, -6, 0), (6, 6, 0), (-6, 6, 0)],
            polygons: [[0, 1, 2, 3]]), material: "wall"),
        (name: "sheet", mesh: Inline(
            vertices: [(-0.5, -0.5, 2), (0.5, -0.5, 2), (0.5, 0.5, 2), (-0.5, 0.5, 2)],
            polygons: [{sheet}]), material: "sheet"),
    ],
    instances: [(name: "wall_1", of: "wall"), (name: "sheet_1", of: "sheet")],
    groups: [(name: "world", members: [{members}])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// Red values of the row through y = 0.
fn row(text: &str) -> Vec<f32> {
    let mut scene = load_scene_str(text, Path::new("cull.ron")).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    let beauty = render(&mut scene.world, settings)
        .outputs
        .image
        .expect("an image")
        .beauty;
    let y = SIDE / 2;
    (0..SIDE)
        .map(|x| beauty[(y * SIDE + x) as usize].x)
        .collect()
}

fn close(got: f32, want: f32) -> bool {
    (got - want).abs() <= 1e-4 * want.max(1.0)
}

/// Columns: through the sheet's middle, in its shadow, on the open wall.
fn columns() -> (usize, usize, usize) {
    (
        column(0.05) as usize,
        column(-2.0) as usize,
        column(3.0) as usize,
    )
}

#[test]
fn the_camera_sees_the_wall_through_a_culled_back_face() {
    let (through, shadow, open) = columns();
    let culled = row(&scene("Cull", false, true));
    let bare = row(&scene("Cull", false, false));
    assert!(
        close(culled[open], lit(WALL)),
        "{} vs {}",
        culled[open],
        lit(WALL)
    );
    // Not black: the wall behind, as without the sheet (and its closed form).
    assert!(
        close(culled[through], lit(WALL)),
        "{} vs {}",
        culled[through],
        lit(WALL)
    );
    assert!(close(culled[through], bare[through]));
    // The sheet's front faces the wall: shadow rays from there meet it and are blocked.
    assert_eq!(culled[shadow], 0.0);
    assert!(close(bare[shadow], lit(WALL)));
    // `Front` draws the back face black.
    let black = row(&scene("Front", false, true));
    assert_eq!(black[through], 0.0);
    assert_eq!(black[shadow], 0.0);
}

#[test]
fn a_shadow_ray_passes_a_culled_back_face() {
    let (through, shadow, open) = columns();
    let culled = row(&scene("Cull", true, true));
    // The camera meets the sheet's lit front.
    assert!(
        close(culled[through], lit(SHEET)),
        "{} vs {}",
        culled[through],
        lit(SHEET)
    );
    // Seen from the wall the sheet shows its back: no shadow.
    assert!(
        close(culled[shadow], lit(WALL)),
        "{} vs {}",
        culled[shadow],
        lit(WALL)
    );
    assert!(close(culled[open], lit(WALL)));
    // `Front` and `Both` keep the back face as an occluder.
    assert_eq!(row(&scene("Front", true, true))[shadow], 0.0);
    assert_eq!(row(&scene("Both", true, true))[shadow], 0.0);
}

/// RenderMan's `Sides 1` surface shows only its outside: a polygon seen from its inside
/// (counter-clockwise from the camera) in front of one seen from outside lets the camera
/// see the second, lit by an ambient light (`matte`: `Ka·ambient`, Ka 1).
#[test]
fn rib_sides_one_culls_the_inside() {
    let text = "Format 16 16 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 1 1\n\
                LightSource \"ambientlight\" 1 \"intensity\" [0.5]\n\
                WorldBegin\nSurface \"matte\"\nSides 1\n\
                Polygon \"P\" [-2 -2 4  2 -2 4  2 2 4  -2 2 4]\n\
                Polygon \"P\" [-2 -2 5  -2 2 5  2 2 5  2 -2 5]\nWorldEnd\n";
    let mut scene = load_scene_str(text, Path::new("t.rib")).unwrap_or_else(|e| panic!("{e}"));
    let frame = render(&mut scene.world, scene.settings.clone());
    let centre = frame.outputs.image.expect("an image").beauty[8 * 16 + 8].x;
    assert!(close(centre, 0.5), "{centre}");
}
