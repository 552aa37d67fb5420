//! A point light at the eye of a camera whose atmosphere scatters light makes the in-scattered
//! light infinite (every camera ray starts at the light): a located warning says so, and
//! only then (a light 1 cm off the eye, or no scattering, loads without one).

use std::path::Path;

use stagelight::scene::load_scene_str;

fn scene(light: &str, fog: &str) -> String {
    format!(
        r#"Scene(
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    lights: [(name: "p", kind: {light}, intensity: 5.0)],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "grey")],
    instances: [(name: "b", of: "ball")],
    groups: [(name: "world", members: ["b"])],
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
        placement: LookAt(eye: (0, -6, 3), target: (0, 0, 0)), outputs: [(file: "o.png")],
        atmosphere: {fog})],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

fn warnings(light: &str, fog: &str) -> Vec<String> {
    let text = scene(light, fog);
    match load_scene_str(&text, Path::new("fog.ron")) {
        Ok(s) => s.located_warnings,
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn a_point_light_at_a_foggy_eye_is_warned_about() {
    let fog = "Fog(sigma_s: (0.3, 0.3, 0.3))";
    assert_eq!(
        warnings("Point(position: (0, -6, 3))", fog),
        ["fog.ron:3:14: warning: light \"p\" is at the eye of camera \"cam\", whose atmosphere \
          scatters light: the light scattered toward the eye is infinite, and the image will not \
          converge\n  help: move the light off the eye (a small offset is enough), or use an area light"]
    );
    let spot = "Spot(position: (0, -6, 3), target: (0, 0, 0), cone_angle: 30)";
    assert_eq!(warnings(spot, fog).len(), 1);
    assert!(warnings("Point(position: (0, -6, 3.01))", fog).is_empty());
    let absorbing = "Fog(sigma_a: (0.3, 0.3, 0.3))";
    assert!(warnings("Point(position: (0, -6, 3))", absorbing).is_empty());
}
