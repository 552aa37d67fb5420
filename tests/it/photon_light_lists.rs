//! Issue 13: light lists in the photon pass — a material whose light list leaves a light out
//! receives none of its caustic or global photons, and every other surface keeps exactly the
//! photons it has without the list.

use stagelight::photon::{Photon, PhotonMaps};

/// A floor in two halves (`left` x < 0 with material `left`, `right` x > 0) under a
/// downward-facing mirror at height 3, lit by point lights `a` (over the left half) and `b`
/// (over the right half), each emitting its own caustic and global photons (`b_photons`
/// for `b`); `list` is the extra text of the left material.
fn scene(b_photons: u32, list: &str) -> String {
    format!(
        r#"Scene(
    options: (caustics: (photons: 1000), global_illumination: (photons: 1000)),
    cameras: [(name: "cam", fov_y: 40, resolution: (2, 2),
        placement: LookAt(eye: (0, -8, 6), target: (0, 0, 0), up: (0, 0, 1)),
        outputs: [(file: "floor.png")])],
    lights: [
        (name: "a", kind: Point(position: (-1.5, 0, 1)), intensity: 1,
            caustic_photons: 6000, globillum_photons: 6000),
        (name: "b", kind: Point(position: (1.5, 0, 2)), intensity: 1,
            caustic_photons: {b_photons}, globillum_photons: {b_photons}),
    ],
    materials: [
        (name: "left", shader: Lambert(albedo: (0.5, 0.5, 0.5)){list}),
        (name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
        (name: "mirror", shader: Mirror(color: (1, 1, 1))),
    ],
    objects: [
        (name: "left", mesh: Grid(size_x: 20, size_y: 40), material: "left"),
        (name: "right", mesh: Grid(size_x: 20, size_y: 40), material: "grey"),
        (name: "mirror", mesh: Grid(size_x: 8, size_y: 8), material: "mirror"),
    ],
    instances: [
        (name: "left_1", of: "left", transform: [Translate((-10, 0, 0))]),
        (name: "right_1", of: "right", transform: [Translate((10, 0, 0))]),
        (name: "mirror_1", of: "mirror",
            transform: [Rotate(axis: (1, 0, 0), degrees: 180), Translate((0, 0, 3))]),
    ],
    groups: [(name: "world", members: ["left_1", "right_1", "mirror_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn maps(text: &str) -> PhotonMaps {
    let frame = crate::common::photon_frame(text, "floor.ron");
    frame.outputs.photons.expect("photon maps")
}

/// The caustic and global photons on one half of the floor (`left`: x < 0), sorted by their
/// bits (the kd-tree's order depends on every photon of the map).
fn on_half(maps: &PhotonMaps, left: bool) -> [Vec<Photon>; 2] {
    [&maps.caustics, &maps.global].map(|m| {
        let mut half: Vec<Photon> = m
            .as_ref()
            .expect("both maps are traced")
            .map
            .photons()
            .iter()
            .filter(|p| (p.position.x < 0.0) == left)
            .copied()
            .collect();
        let bits = |p: &Photon| {
            [p.position, p.power, p.incoming, p.normal].map(|v| v.to_array().map(f32::to_bits))
        };
        half.sort_by_key(bits);
        half
    })
}

fn power(photons: &[Photon]) -> f32 {
    photons.iter().map(|p| p.power.x).sum()
}

#[test]
fn a_material_that_lists_out_a_light_receives_none_of_its_photons() {
    let listed = maps(&scene(6000, r#", lights: ["a"]"#));
    let only_a = maps(&scene(0, ""));
    let unlisted = maps(&scene(6000, ""));
    let [caustic, global] = on_half(&listed, true);
    println!(
        "left half: {} caustic / {} global photons with the list, {} / {} from both lights",
        caustic.len(),
        global.len(),
        on_half(&unlisted, true)[0].len(),
        on_half(&unlisted, true)[1].len(),
    );
    // The listed half stores exactly the single-light run's photons (same seeds per light).
    assert_eq!(on_half(&listed, true), on_half(&only_a, true));
    assert!(caustic.len() > 100 && global.len() > 1000);
    // Without the list, `b`'s photons land there too: both maps gain power.
    let both = on_half(&unlisted, true);
    assert!(power(&both[0]) > 1.2 * power(&caustic), "caustic");
    assert!(power(&both[1]) > 1.2 * power(&global), "global");
    // The other half is untouched by the list: the same photons, bit for bit.
    assert_eq!(on_half(&listed, false), on_half(&unlisted, false));
}
