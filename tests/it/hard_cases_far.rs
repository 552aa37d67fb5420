//! Hard case H5 (`../shared/HARDCASES.md`): scenes far from the origin. The loader rebases
//! the scene in f64 (`src/scene/rebase.rs`), so a scene translated by T·(1, 1, 1) renders the
//! very same image as at T = 0, and bakes far away stay exact.

use std::path::Path;

use glam::Vec3;
use stagelight::frame::{Frame, Tasks};
use stagelight::framebuffer::FrameBuffers;

/// Translations of the hard-case catalogue.
const TS: [f64; 5] = [0.0, 1e3, 1e4, 1e5, 1e6];

/// A Cornell-like box of size 1 (open at z = 0, where the camera looks in), a short block,
/// a ceiling area light and a point light; 32×32, 16 spp, path tracing. `placed` puts the
/// geometry at the origin and moves it with the root instance's transform; otherwise the
/// inline vertices themselves are written at T + v. Cameras and lights are written at T + p.
fn cornell(t: f64, placed: bool) -> String {
    let off = if placed { 0.0 } else { t };
    let v = |x: f64, y: f64, z: f64| format!("({}, {}, {})", x + off, y + off, z + off);
    let p = |x: f64, y: f64, z: f64| format!("({}, {}, {})", x + t, y + t, z + t);
    let quad = |name: &str, c: [(f64, f64, f64); 4], mat: &str| {
        let vs: Vec<String> = c.iter().map(|&(x, y, z)| v(x, y, z)).collect();
        format!(
            "(name: \"{name}\", mesh: Inline(vertices: [{}], polygons: [[0, 1, 2, 3]]), material: \"{mat}\"),",
            vs.join(", ")
        )
    };
    let objects = [
        quad(
            "floor",
            [(0., 0., 0.), (0., 0., 1.), (1., 0., 1.), (1., 0., 0.)],
            "white",
        ),
        quad(
            "ceiling",
            [(0., 1., 0.), (1., 1., 0.), (1., 1., 1.), (0., 1., 1.)],
            "white",
        ),
        quad(
            "back",
            [(0., 0., 1.), (0., 1., 1.), (1., 1., 1.), (1., 0., 1.)],
            "white",
        ),
        quad(
            "left",
            [(0., 0., 0.), (0., 1., 0.), (0., 1., 1.), (0., 0., 1.)],
            "red",
        ),
        quad(
            "right",
            [(1., 0., 0.), (1., 0., 1.), (1., 1., 1.), (1., 1., 0.)],
            "green",
        ),
        quad(
            "block_top",
            [
                (0.25, 0.375, 0.25),
                (0.25, 0.375, 0.625),
                (0.625, 0.375, 0.625),
                (0.625, 0.375, 0.25),
            ],
            "white",
        ),
        quad(
            "block_front",
            [
                (0.25, 0., 0.25),
                (0.25, 0.375, 0.25),
                (0.625, 0.375, 0.25),
                (0.625, 0., 0.25),
            ],
            "white",
        ),
        quad(
            "block_side",
            [
                (0.625, 0., 0.25),
                (0.625, 0.375, 0.25),
                (0.625, 0.375, 0.625),
                (0.625, 0., 0.625),
            ],
            "white",
        ),
    ]
    .join("\n        ");
    let names = [
        "floor",
        "ceiling",
        "back",
        "left",
        "right",
        "block_top",
        "block_front",
        "block_side",
    ];
    let instances: String = names
        .iter()
        .map(|n| format!("(name: \"{n}_1\", of: \"{n}\"),"))
        .collect();
    let members: Vec<String> = names.iter().map(|n| format!("\"{n}_1\"")).collect();
    let root_transform = if placed {
        format!("transform: [Translate(({t}, {t}, {t}))]")
    } else {
        "transform: []".into()
    };
    format!(
        r#"Scene(
    options: (samples: 16, seed: 7, integrator: Path, max_depth: 3),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (32, 32),
        placement: LookAt(eye: {eye}, target: {target}, up: (0, 1, 0)),
        outputs: [(file: "far.exr", passes: [Beauty, Depth, Normal])])],
    lights: [
        (name: "panel", kind: Rect(corner: {corner}, edge_u: (0.25, 0, 0), edge_v: (0, 0, 0.25)), intensity: 8.0, samples: 4),
        (name: "bulb", kind: Point(position: {bulb}), intensity: 0.25),
        (name: "ball", kind: Sphere(center: {ball}, radius: 0.0625), intensity: 1.0, samples: 2),
    ],
    materials: [
        (name: "white", shader: Lambert(albedo: (0.75, 0.75, 0.75))),
        (name: "red", shader: Lambert(albedo: (0.75, 0.25, 0.25))),
        (name: "green", shader: Lambert(albedo: (0.25, 0.75, 0.25))),
    ],
    objects: [
        {objects}
    ],
    instances: [
        {instances}
        (name: "box_1", of: "box", {root_transform}),
    ],
    groups: [
        (name: "box", members: [{members}]),
        (name: "world", members: ["box_1"]),
    ],
    render: (root: "world", camera: "cam"),
)"#,
        eye = p(0.5, 0.5, -1.25),
        target = p(0.5, 0.5, 0.5),
        corner = p(0.375, 0.9921875, 0.375),
        bulb = p(0.75, 0.75, 0.375),
        ball = p(0.25, 0.75, 0.75),
        members = members.join(", "),
    )
}

/// Loads the scene text and renders it (no files written).
fn render(text: &str) -> FrameBuffers {
    let mut scene = stagelight::scene::load_scene_str(text, Path::new("far.ron"))
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("an image")
}

fn bits(v: &[Vec3]) -> Vec<[u32; 3]> {
    v.iter()
        .map(|c| [c.x.to_bits(), c.y.to_bits(), c.z.to_bits()])
        .collect()
}

/// relMSE (pbrt's MRSE form) of `a` against the reference `r`.
fn rel_mse(a: &[Vec3], r: &[Vec3]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(r)
        .flat_map(|(a, r)| (0..3).map(move |k| (a[k] as f64, r[k] as f64)))
        .map(|(a, r)| (a - r).powi(2) / (r + 0.01).powi(2))
        .sum();
    sum / (3 * a.len()) as f64
}

#[test]
fn h05_scene_far_from_origin() {
    for placed in [true, false] {
        let reference = render(&cornell(0.0, placed));
        let lit = reference
            .beauty
            .iter()
            .filter(|c| c.max_element() > 0.0)
            .count();
        assert!(
            lit > reference.beauty.len() / 2,
            "the box is lit: {lit} pixels"
        );
        for t in TS {
            let img = render(&cornell(t, placed));
            let non_finite = img.beauty.iter().filter(|c| !c.is_finite()).count();
            assert_eq!(non_finite, 0, "T = {t}: non-finite pixels");
            let rel = rel_mse(&img.beauty, &reference.beauty);
            assert!(
                bits(&img.beauty) == bits(&reference.beauty),
                "T = {t} (placed {placed}): beauty differs from T = 0, relMSE {rel:e}"
            );
            assert_eq!(
                bits(&img.normal),
                bits(&reference.normal),
                "T = {t}: normals"
            );
            let depth = |f: &FrameBuffers| f.depth.iter().map(|d| d.to_bits()).collect::<Vec<_>>();
            assert_eq!(depth(&img), depth(&reference), "T = {t}: depth");
        }
    }
}

/// An open plane at 1e6 bakes ambient occlusion exactly 1, and its `positions` bake holds
/// the absolute world positions (rounded once to f32).
#[test]
fn h05_bake_far_from_origin() {
    let t = 1e6;
    let text = format!(
        r#"Scene(
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "plane", material: "grey", mesh: Inline(
        vertices: [({x0}, {y0}, {t}), ({x1}, {y0}, {t}), ({x1}, {y1}, {t}), ({x0}, {y1}, {t})],
        polygons: [[0, 1, 2, 3]],
        uvs: [(0, 0), (1, 0), (1, 1), (0, 1)]))],
    instances: [(name: "plane_1", of: "plane", bake: (
        resolution: (8, 8), uvs: Mesh, texel_samples: 1, padding: 0,
        outputs: [(kind: AmbientOcclusion(samples: 256), format: Exr), (kind: Positions, format: Exr)]))],
    groups: [(name: "world", members: ["plane_1"])],
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
        placement: LookAt(eye: ({x1}, {y0}, {z}), target: ({x0}, {y1}, {t}), up: (0, 0, 1)), outputs: [])],
    render: (root: "world", camera: "cam"),
)"#,
        z = t + 4.0,
        x0 = t + 2.0,
        x1 = t + 3.0,
        y0 = t - 0.5,
        y1 = t + 0.5,
    );
    let mut scene = stagelight::scene::load_scene_str(&text, Path::new("far_bake.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut frame = Frame::new(scene.settings.clone());
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    frame.inputs.bake_dir =
        crate::common::scratch_root().join(format!("stagelight-h05-bake-{}", std::process::id()));
    stagelight::systems::run(&mut scene.world, &mut frame).expect("bake");
    let read = |path: &Path| -> Vec<Vec3> {
        use exr::prelude::*;
        let image = read_first_rgba_layer_from_file(
            path,
            |res, _| (res.width(), vec![Vec3::ZERO; res.width() * res.height()]),
            |(w, px): &mut (usize, Vec<Vec3>), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
                px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b);
            },
        )
        .unwrap();
        image.layer_data.channel_data.pixels.1
    };
    let find = |kind: &str| {
        frame
            .report
            .written
            .iter()
            .find(|p| p.to_string_lossy().contains(kind))
            .unwrap_or_else(|| panic!("no {kind} file in {:?}", frame.report.written))
            .clone()
    };
    let ao = read(&find("_ao"));
    assert_eq!(ao.len(), 64);
    assert!(
        ao.iter().all(|a| a.x == 1.0),
        "a ray hit the open plane at 1e6: {ao:?}"
    );
    let positions = read(&find("_positions"));
    for j in 0..8 {
        for i in 0..8 {
            let p = positions[j * 8 + i];
            // Texel centre (i + ½)/8, 1 − (j + ½)/8 on the plane [t+2, t+3] × [t−½, t+½].
            let exact = glam::DVec3::new(
                t + 2.0 + (i as f64 + 0.5) / 8.0,
                t - 0.5 + 1.0 - (j as f64 + 0.5) / 8.0,
                t,
            );
            assert_eq!(p, exact.as_vec3(), "texel ({i}, {j})");
        }
    }
    let _ = std::fs::remove_dir_all(&frame.inputs.bake_dir);
}

/// OBJ files are read in f64 and re-centred before rounding: a box written at 1e6 in an OBJ
/// file renders the same image as the box written at the origin.
#[test]
fn h05_obj_far_from_origin() {
    let dir =
        crate::common::scratch_root().join(format!("stagelight-h05-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let render_at = |t: f64| {
        let corners = [
            (0., 0., 0.),
            (1., 0., 0.),
            (1., 0., 1.),
            (0., 0., 1.),
            (0., 1., 1.),
            (1., 1., 1.),
        ];
        let mut obj = String::new();
        for (x, y, z) in corners {
            // 0.3 and 1.3 are not representable at 1e6 in f32: an f32 parser would move them.
            obj.push_str(&format!("v {} {} {}\n", x + 0.3 + t, y + t, z + 0.3 + t));
        }
        // Floor (facing +y) and back wall (facing -z).
        obj.push_str("f 1 4 3 2\nf 4 5 6 3\n");
        let name = format!("box_{t}.obj");
        std::fs::write(dir.join(&name), obj).unwrap();
        let p = |x: f64, y: f64, z: f64| format!("({}, {}, {})", x + t, y + t, z + t);
        let text = format!(
            r#"Scene(
    options: (samples: 4, seed: 3, integrator: Path, max_depth: 2),
    cameras: [(name: "cam", fov_y: 50.0, resolution: (24, 24),
        placement: LookAt(eye: {eye}, target: {target}, up: (0, 1, 0)), outputs: [])],
    lights: [(name: "bulb", kind: Point(position: {bulb}), intensity: 0.5)],
    materials: [(name: "white", shader: Lambert(albedo: (0.7, 0.7, 0.7)))],
    objects: [(name: "box", mesh: Obj(file: "{name}"), material: "white")],
    instances: [(name: "box_1", of: "box")],
    groups: [(name: "world", members: ["box_1"])],
    render: (root: "world", camera: "cam"),
)"#,
            eye = p(0.5, 0.75, -1.0),
            target = p(0.5, 0.25, 0.75),
            bulb = p(0.5, 0.875, 0.25),
        );
        let mut scene = stagelight::scene::load_scene_str(&text, &dir.join("obj.ron"))
            .unwrap_or_else(|e| panic!("{e}"));
        let frame = crate::common::render(&mut scene.world, scene.settings.clone());
        frame.outputs.image.expect("an image").beauty
    };
    let reference = render_at(0.0);
    assert!(reference.iter().any(|c| c.max_element() > 0.0));
    for t in [1e5, 1e6] {
        let img = render_at(t);
        assert!(img.iter().all(|c| c.is_finite()));
        assert!(
            bits(&img) == bits(&reference),
            "T = {t}: relMSE {:e}",
            rel_mse(&img, &reference)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
