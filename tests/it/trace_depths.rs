//! `max_depth`, `reflection_depth` and `refraction_depth` do what the format reference
//! (*Integrators and trace depths*) says, counted in rays and read in pixels: a vertex up to
//! `max_depth` is lit and traces its mirror rays within `reflection_depth`, a deeper vertex
//! only shows its emission, and a ray past the reflection budget sees the environment's
//! `depth_exceeded` (black here: no environment). `.mi` `trace depth r t s` maps onto them as
//! mental ray counts (the camera ray's hit lit after up to `s` reflection and refraction rays).

use std::path::Path;

use stagelight::frame::Frame;

/// Two facing mirrors, far larger than the view: the camera (between them, looking at `A`)
/// sees `A`, a white mirror at z = −2; what `A` reflects is `B` at z = 3, a `Local` surface
/// that emits red 1, is lit green 1 by an `Ambient` light, and mirrors half of what it sees
/// back at `A`. Each pixel's path alternates A (vertex 1, 3, …) and B (vertex 2, 4, …).
fn scene(max_depth: u32, reflection_depth: u32) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, seed: 1, integrator: Direct, face: Both,
        max_depth: {max_depth}, reflection_depth: {reflection_depth}),
    cameras: [(name: "cam", fov_y: 10.0, resolution: (4, 4),
        placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1), up: (0, 1, 0)),
        outputs: [(file: "depths.exr", passes: [Beauty])])],
    lights: [(name: "sky", kind: Ambient, intensity: 1.0)],
    materials: [
        (name: "mirror", shader: Mirror(color: (1, 1, 1))),
        (name: "lit", emission: (1, 0, 0), shader: Local(color: (0, 1, 0), ka: 1, kd: 0,
            specular: (0, 0, 0), reflection: (0.5, 0.5, 0.5))),
    ],
    objects: [
        (name: "a", material: "mirror", mesh: Inline(
            vertices: [(-50, -50, -2), (50, -50, -2), (50, 50, -2), (-50, 50, -2)],
            polygons: [[0, 1, 2, 3]])),
        (name: "b", material: "lit", mesh: Inline(
            vertices: [(-50, -50, 3), (-50, 50, 3), (50, 50, 3), (50, -50, 3)],
            polygons: [[0, 1, 2, 3]])),
    ],
    instances: [(name: "a_1", of: "a"), (name: "b_1", of: "b")],
    groups: [(name: "world", members: ["a_1", "b_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

fn render(text: &str, name: &str) -> Frame {
    let mut scene = stagelight::scene::load_scene_str(text, Path::new(name)).expect("scene loads");
    crate::common::render(&mut scene.world, scene.settings.clone())
}

/// Every pixel's beauty (all pixels see the same), and the closest-hit rays `shade` traced
/// per pixel beyond the pixel-centre ray of the id passes.
fn measure(frame: &Frame) -> ([f32; 3], u64) {
    let beauty = &frame.outputs.image.as_ref().expect("an image").beauty;
    let first = beauty[0];
    for p in beauty {
        assert!((*p - first).abs().max_element() < 1e-5, "{p} vs {first}");
    }
    let shade = frame.report.stage("shade").unwrap();
    let pixels = beauty.len() as u64;
    assert_eq!(shade.rays_closest % pixels, 0, "{shade:?}");
    (first.to_array(), shade.rays_closest / pixels - 1)
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-5)
}

#[test]
fn max_depth_and_reflection_depth_bound_the_mirror_rays_as_documented() {
    // (max_depth, reflection_depth) → (pixel, closest-hit rays per camera sample).
    let cases = [
        // No reflection ray: the mirror shows what the exceeded depth sees (black).
        ((1, 0), ([0.0, 0.0, 0.0], 1)),
        // `max_depth: 1` is direct light only, not "camera and shadow rays only": the mirror's
        // ray is traced and B, at vertex 2, shows its emission (red) but is not lit (green).
        ((1, 1), ([1.0, 0.0, 0.0], 2)),
        // A larger reflection budget changes nothing: vertex 2 traces no further ray.
        ((1, 2), ([1.0, 0.0, 0.0], 2)),
        // B at vertex 2 is lit; its own reflection (the second) is past the budget.
        ((2, 1), ([1.0, 1.0, 0.0], 2)),
        // B's reflection is traced, and A at vertex 3 (past max_depth) adds nothing.
        ((2, 2), ([1.0, 1.0, 0.0], 3)),
        // A at vertex 3 reflects B at vertex 4, lit, at half weight; the fourth is past budget.
        ((4, 3), ([1.5, 1.5, 0.0], 4)),
    ];
    for ((max_depth, reflection_depth), expected) in cases {
        let frame = render(&scene(max_depth, reflection_depth), "depths.ron");
        let (pixel, rays) = measure(&frame);
        assert!(
            close(pixel, expected.0) && rays == expected.1,
            "max_depth {max_depth}, reflection_depth {reflection_depth}: {pixel:?}, {rays} rays \
             per sample, expected {expected:?}"
        );
    }
}

/// The `.mi` version of the two mirrors, with `trace depth {depths}`: `A` a `dgs_material`
/// mirror, `B` a `mib_illum_lambert` whose only term is its green ambient (so it shows green
/// where it is lit, black where it is not).
fn mi_scene(depths: &str) -> String {
    let preamble = crate::common::mi_preamble(crate::common::BASE, "")
        .replace(
            "object space\n",
            &format!("object space\nface both\ntrace depth {depths}\n"),
        )
        .replace("resolution 160 120", "resolution 8 6");
    format!(
        r#"{preamble}material "mirror"
"dgs_material" ("specular" 1 1 1)
end material
material "lit"
"mib_illum_lambert" ("ambient" 0 1 0, "ambience" 1 1 1, "diffuse" 0 0 0)
end material
object "Walls"
group
-50 -50 -2
50 -50 -2
50 50 -2
-50 50 -2
-50 -50 3
-50 50 3
50 50 3
50 -50 3
v 0
v 1
v 2
v 3
v 4
v 5
v 6
v 7
p "mirror" 0 1 2 3
p "lit" 4 5 6 7
end group
end object
instance "Walls_inst" "Walls"
end instance
instgroup "rootgrp"
"Camera_inst" "Walls_inst"
end instgroup
render "rootgrp" "Camera_inst" "opt"
"#
    )
}

#[test]
fn mi_trace_depth_lights_the_hit_of_every_ray_mental_ray_traces() {
    // (trace depth, what the mirror shows, closest-hit rays per camera sample). mental ray
    // counts reflection and refraction rays (the camera ray is level 0) and shades the hit of
    // each one it traces, so one reflection shows B lit; a sum of 0 traces none.
    let cases = [
        ("1 1 1", [0.0, 1.0, 0.0], 2),
        ("2 2", [0.0, 1.0, 0.0], 2),
        ("0 0 0", [0.0, 0.0, 0.0], 1),
        ("1 1 0", [0.0, 0.0, 0.0], 1),
        ("0 1", [0.0, 0.0, 0.0], 1),
    ];
    for (depths, pixel, rays) in cases {
        let frame = render(&mi_scene(depths), "depths.mi");
        let measured = measure(&frame);
        assert!(
            close(measured.0, pixel) && measured.1 == rays,
            "trace depth {depths}: {measured:?}, expected {pixel:?} and {rays} rays"
        );
    }
    let read = stagelight::scene::import::mi::read_mi(
        Path::new("depths.mi"),
        mi_scene("3 2 4").as_bytes(),
    )
    .unwrap();
    let o = read.desc.options.unwrap();
    assert_eq!(
        (o.reflection_depth, o.refraction_depth, o.max_depth),
        (3, 2, 5)
    );
    let read = stagelight::scene::import::mi::read_mi(
        Path::new("depths.mi"),
        mi_scene("4 4 2").as_bytes(),
    )
    .unwrap();
    let o = read.desc.options.unwrap();
    assert_eq!(
        (o.reflection_depth, o.refraction_depth, o.max_depth),
        (2, 2, 3)
    );
}
