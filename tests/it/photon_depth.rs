//! Issue 13: the photon trace depth (`options.photon_depth`, mental ray `photon trace
//! depth r t s`). A glass ball's caustic needs two refractions (in and out): with a
//! refraction limit of 0 or 1 nothing lands under the ball; with 2 the caustic map is the
//! unlimited one exactly (a photon cannot refract a third time through one convex ball);
//! a reflection or sum limit keeps a subset of the unlimited map's photons.

use stagelight::photon::Photon;

/// A glass ball (radius 0.6, centre height 0.9) over a floor under a point light; a caustic
/// map of 4000 photons aimed at the ball; `depth` is the `photon_depth` text, if any.
fn scene(depth: &str) -> String {
    format!(
        r#"Scene(
    options: (caustics: (photons: 4000), {depth}),
    cameras: [(name: "cam", fov_y: 40, resolution: (2, 2),
        placement: LookAt(eye: (0, -4.5, 3.0), target: (0, 0, 0.5), up: (0, 0, 1)),
        outputs: [(file: "out.png")])],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 4)), intensity: 40)],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
        (name: "glass", shader: Dielectric(ior: 1.5)),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 6, size_y: 6), material: "floor"),
        (name: "ball", mesh: Sphere(radius: 0.6), material: "glass",
         approximation: Parametric(u: 16, v: 8)),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "ball_1", of: "ball", transform: [Translate((0, 0, 0.9))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn caustic_photons(depth: &str) -> Vec<Photon> {
    let text = scene(depth);
    let frame = crate::common::photon_frame(&text, "ball.ron");
    frame
        .outputs
        .photons
        .and_then(|m| m.caustics)
        .map_or_else(Vec::new, |m| m.map.photons().to_vec())
}

/// Photons within 0.3 of the point under the ball's centre (where only light refracted in and
/// out of the ball lands).
fn under_ball(photons: &[Photon]) -> usize {
    photons
        .iter()
        .filter(|p| p.position.truncate().length() < 0.3)
        .count()
}

/// Whether every photon of `part` is one of `whole` (the kd-tree orders each map its own way).
fn is_subset(part: &[Photon], whole: &[Photon]) -> bool {
    part.iter().all(|p| whole.contains(p))
}

#[test]
fn a_glass_ball_caustic_needs_two_refractions() {
    let unlimited = caustic_photons("");
    let counts: Vec<usize> = (0..3)
        .map(|t| {
            under_ball(&caustic_photons(&format!(
                "photon_depth: (refraction: {t})"
            )))
        })
        .collect();
    println!(
        "photons under the ball: unlimited {}, refraction depth 0/1/2: {counts:?}",
        under_ball(&unlimited)
    );
    assert!(under_ball(&unlimited) > 200, "{}", under_ball(&unlimited));
    assert_eq!(counts[..2], [0, 0]);
    // Two refractions are all a photon makes through one ball: the same map, bit for bit.
    let two = caustic_photons("photon_depth: (refraction: 2)");
    assert_eq!(two, unlimited);
    // No reflections (Fresnel, total internal): fewer photons, each one of the unlimited map.
    let no_reflection = caustic_photons("photon_depth: (reflection: 0)");
    assert!(no_reflection.len() < unlimited.len());
    assert!(is_subset(&no_reflection, &unlimited));
    // Nothing scatters at all: no caustic.
    assert!(caustic_photons("photon_depth: (sum: 0)").is_empty());
}
