//! Issue 13: the ray flags `visible`, `shadow`, `trace` (mental ray) on objects and
//! instances, from RON and from `.mi`, each pixel-checked: an invisible object still casts
//! its shadow and shows in a mirror, `shadow: false` removes its shadow only, `trace: false`
//! hides it from the mirror only; instance flags override the object's down the DAG.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::{load_scene_str, LoadedScene};

use crate::common::render;

/// Image side, pixels.
const SIDE: u32 = 40;
/// The row through the scene's axis y = 0.
const ROW: u32 = 20;
/// A pixel of the Lambert half inside the card's shadow (floor x ≈ −1.14).
const SHADOW: u32 = 11;
/// A pixel of the mirror half where only the card's reflection is seen (x ≈ 0.60).
const REFLECTION: u32 = 24;
/// A pixel where the camera sees the card itself (x ≈ 1.14 on the floor).
const DIRECT: u32 = 27;
/// The card's flat colour.
const CARD: Vec3 = Vec3::new(0.2, 0.5, 0.9);

/// Looking straight down from z = 10 at a floor whose x < 0 half is Lambert and x > 0 half
/// a mirror; a constant-colour card at z = 3 over the mirror half (x ∈ [0.6, 1], seen directly
/// at floor x ∈ [0.86, 1.43], in the mirror at x ∈ [0.46, 0.77]) under a directional light
/// travelling along (−2, 0, −3), which puts its shadow at x ∈ [−1.4, −1] on the Lambert
/// half. `card`: the card object's extra fields; `placed`: its instance's; `group`: the
/// instance of the group holding it. `with_card` false leaves the card out.
fn scene(card: &str, placed: &str, group: &str, with_card: bool) -> String {
    let members = if with_card {
        r#""floor_1", "mirror_1", "cards_1""#
    } else {
        r#""floor_1", "mirror_1""#
    };
    format!(
        r#"Scene(
    options: (samples: 1, face: Both),
    cameras: [(name: "cam", fov_y: 30, resolution: ({SIDE}, {SIDE}),
        placement: LookAt(eye: (0, 0, 10), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "flags.png")])],
    lights: [(name: "sun", kind: Directional(direction: (-2, 0, -3)), intensity: 2)],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
        (name: "mirror", shader: Mirror(color: (1, 1, 1))),
        (name: "card", shader: Constant(color: ({}, {}, {}))),
    ],
    objects: [
        (name: "floor", mesh: Inline(vertices: [(-3, -3, 0), (0, -3, 0), (0, 3, 0), (-3, 3, 0)],
            polygons: [[0, 1, 2, 3]]), material: "floor"),
        (name: "mirror", mesh: Inline(vertices: [(0, -3, 0), (3, -3, 0), (3, 3, 0), (0, 3, 0)],
            polygons: [[0, 1, 2, 3]]), material: "mirror"),
        (name: "card", mesh: Inline(vertices: [(0.6, -0.5, 3), (1, -0.5, 3), (1, 0.5, 3), (0.6, 0.5, 3)],
            polygons: [[0, 1, 2, 3]]), material: "card"{card}),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "mirror_1", of: "mirror"),
        (name: "card_1", of: "card"{placed}),
        (name: "cards_1", of: "cards"{group}),
    ],
    groups: [
        (name: "cards", members: ["card_1"]),
        (name: "world", members: [{members}]),
    ],
    render: (root: "world", camera: "cam"),
)"#,
        CARD.x, CARD.y, CARD.z
    )
}

fn load(text: &str, name: &str) -> LoadedScene {
    load_scene_str(text, Path::new(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// The beauty image (row-major, `SIDE × SIDE`).
fn image(text: &str) -> Vec<Vec3> {
    let mut scene = load(text, "flags.ron");
    let settings = scene.settings.clone();
    render(&mut scene.world, settings)
        .outputs
        .image
        .expect("an image")
        .beauty
}

fn at(img: &[Vec3], x: u32) -> Vec3 {
    img[(ROW * SIDE + x) as usize]
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() <= 1e-5
}

#[test]
fn the_layout_shows_card_shadow_and_reflection_without_flags() {
    let plain = image(&scene("", "", "", true));
    let empty = image(&scene("", "", "", false));
    assert!(close(at(&plain, DIRECT), CARD), "{}", at(&plain, DIRECT));
    assert!(close(at(&plain, REFLECTION), CARD));
    assert_eq!(at(&plain, SHADOW), Vec3::ZERO);
    assert!(at(&empty, SHADOW).min_element() > 0.1);
    assert_eq!(at(&empty, REFLECTION), Vec3::ZERO);
    assert_eq!(at(&empty, DIRECT), Vec3::ZERO);
}

#[test]
fn an_invisible_object_still_casts_its_shadow_and_shows_in_a_mirror() {
    let empty = image(&scene("", "", "", false));
    for (card, placed, group) in [
        (", visible: false", "", ""),
        ("", ", visible: false", ""),
        ("", "", ", visible: false"),
        // The closest instance wins over the group's instance and the object.
        (", visible: true", ", visible: false", ", visible: true"),
    ] {
        let img = image(&scene(card, placed, group, true));
        let case = format!("object{card} / instance{placed} / group{group}");
        assert_eq!(
            at(&img, DIRECT),
            at(&empty, DIRECT),
            "{case}: the camera sees through"
        );
        assert!(
            close(at(&img, REFLECTION), CARD),
            "{case}: the mirror shows it"
        );
        assert_eq!(at(&img, SHADOW), Vec3::ZERO, "{case}: it still shadows");
    }
    let shown = image(&scene(", visible: false", ", visible: true", "", true));
    assert!(
        close(at(&shown, DIRECT), CARD),
        "the instance overrides the object"
    );
}

#[test]
fn shadow_false_removes_the_shadow_only() {
    let empty = image(&scene("", "", "", false));
    let img = image(&scene(", shadow: false", "", "", true));
    assert_eq!(at(&img, SHADOW), at(&empty, SHADOW));
    assert!(close(at(&img, DIRECT), CARD));
    assert!(close(at(&img, REFLECTION), CARD));
    // Everything else of the floor is lit as without the card.
    let lit = (0..SIDE / 2 - 1)
        .filter(|&x| at(&img, x) == at(&empty, x))
        .count();
    assert_eq!(lit as u32, SIDE / 2 - 1);
}

#[test]
fn trace_false_hides_the_object_from_the_mirror_only() {
    let empty = image(&scene("", "", "", false));
    let img = image(&scene("", "", ", trace: false", true));
    assert_eq!(at(&img, REFLECTION), at(&empty, REFLECTION));
    assert!(close(at(&img, DIRECT), CARD));
    assert_eq!(at(&img, SHADOW), Vec3::ZERO);
}

/// The §3.2.2 plane with the lamp casting full shadows (`"shadow" true`, and `"factor" 0`:
/// the printed factor 1 would let all the light through) and a lambert card halfway between
/// the eye (where the lamp is) and the plane, carrying `flags`.
fn plane_with_card(flags: &str, card: bool) -> String {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/seeds/mi/plane.mi"),
    )
    .unwrap()
    .replace("\"shadow\" false", "\"shadow\" true")
    .replace("\"factor\" 1,", "\"factor\" 0,");
    let card_block = format!(
        "material \"card_mtl\"\nopaque\n\"mib_illum_lambert\" (\"diffuse\" 0.4 0.4 0.4, \
         \"lights\" [\"Lamp_inst\"])\nend material\n\nobject \"Card\"\n{flags}\ngroup\n0.2 0.2 0.5\n0.2 -0.2 0.5\n-0.2 -0.2 0.5\n\
         -0.2 0.2 0.5\nv 0\nv 1\nv 2\nv 3\np \"card_mtl\" 0 3 2 1\nend group\nend object\n\n\
         instance \"Card_inst\" \"Card\"\ntransform\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 1 1\n\
         end instance\n\ninstgroup \"rootgrp\"\n"
    );
    if card {
        text.replace("instgroup \"rootgrp\"\n", &card_block)
            .replace("\"Plane_inst\"\n", "\"Plane_inst\"\n\"Card_inst\"\n")
    } else {
        text
    }
}

fn mi_centre(text: &str) -> (Vec3, Vec3) {
    let mut scene = load(text, "card.mi");
    for (camera, _) in scene.world.query_mut::<(
        &mut stagelight::components::Camera,
        &stagelight::components::RenderCamera,
    )>() {
        (camera.width, camera.height) = (64, 48);
    }
    let mut settings = scene.settings.clone();
    settings.spp = 1;
    settings.adaptive = None;
    let beauty = render(&mut scene.world, settings)
        .outputs
        .image
        .expect("an image")
        .beauty;
    // The card spans ±0.4 on the plane, ±9.6 pixels about the centre; (48, 24) is off it.
    (beauty[24 * 64 + 32], beauty[24 * 64 + 48])
}

#[test]
fn mi_flags_map_onto_the_engine() {
    let (bare_centre, bare_off) = mi_centre(&plane_with_card("", false));
    assert!(bare_centre.x > 0.5);
    let (card, off) = mi_centre(&plane_with_card("visible trace shadow", true));
    assert!(
        card.x > 0.3 && card.x < 0.5,
        "the lit card (diffuse 0.4): {card}"
    );
    assert_eq!(off, bare_off);
    let (hidden, off) = mi_centre(&plane_with_card("visible off", true));
    assert_eq!(
        hidden,
        Vec3::ZERO,
        "the hidden card still shadows the plane"
    );
    assert_eq!(off, bare_off);
    let (gone, _) = mi_centre(&plane_with_card("visible off\nshadow off", true));
    assert_eq!(gone, bare_centre);
    let (seen, _) = mi_centre(&plane_with_card("shadow off", true));
    assert_eq!(seen, card);
    // `trace off` reaches the description (the pixels of trace are checked from RON).
    let text = plane_with_card("trace off", true);
    let read = read_mi(Path::new("card.mi"), text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"));
    let card = read.desc.objects.iter().find(|o| o.name == "Card").unwrap();
    assert_eq!(
        (card.visible, card.shadow, card.trace),
        (None, None, Some(false))
    );
    assert!(
        read.warnings
            .iter()
            .all(|w| !w.problem.message.contains("trace")),
        "{:?}",
        read.warnings
    );
}
