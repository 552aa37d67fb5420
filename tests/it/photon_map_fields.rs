//! A photon-map field set on the map it does nothing for — `final_gather` or `precompute`
//! on `caustics`, `aim` on `global_illumination` — is a located warning naming the map it
//! belongs to (it was accepted silently and had no effect). At their defaults, or on their
//! own map, they are not warned about.

use std::path::Path;

use stagelight::scene::load_scene_str;

fn warnings(options: &str) -> Vec<String> {
    let text = format!(
        r#"Scene(
    options: ({options}),
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
        placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0), up: (0, 0, 1)),
        outputs: [(file: "maps.png")])],
    lights: [(name: "l", kind: Point(position: (0, 0, 2)))],
    objects: [(name: "floor", mesh: Grid(size_x: 4, size_y: 4))],
    instances: [(name: "floor_1", of: "floor")],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)"#
    );
    load_scene_str(&text, Path::new("maps.ron"))
        .unwrap_or_else(|e| panic!("{e}"))
        .located_warnings
}

#[test]
fn a_field_of_the_other_map_is_a_located_warning() {
    assert_eq!(
        warnings("caustics: (photons: 100, final_gather: 64, precompute: false)"),
        [
            "maps.ron:2:54: warning: final_gather has no effect on the caustics map: it is a \
             setting of global_illumination\n  help: move it into `global_illumination: (…)`, \
             or remove it",
            "maps.ron:2:70: warning: precompute has no effect on the caustics map: it is a \
             setting of global_illumination\n  help: move it into `global_illumination: (…)`, \
             or remove it",
        ]
    );
    assert_eq!(
        warnings("global_illumination: (photons: 100, aim: false)"),
        [
            "maps.ron:2:56: warning: aim has no effect on the global_illumination map: it is a \
          setting of caustics\n  help: move it into `caustics: (…)`, or remove it"
        ]
    );
    // On their own maps, or at their defaults, nothing to say.
    assert!(warnings(
        "caustics: (photons: 100, aim: false, final_gather: 16), \
         global_illumination: (photons: 100, final_gather: 64, precompute: false, aim: true)"
    )
    .is_empty());
}
