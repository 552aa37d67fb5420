//! Instances whose transform mirrors (negative determinant) keep the front side their
//! object-space winding defines (glTF's rule, pbrt's `transformSwapsHandedness`): a mirrored
//! one-sided cube renders as the mirror image of the plain one (RON and glTF), its AO bake
//! is open everywhere (texels and vertices), a mirrored emitter lights what its front faces
//! (light sampling and photons), fog fills the inside of a mirrored box, and RIB's `Sides 1`
//! shows the outside RenderMan shows (the reader mirrors every RIB world through z = 0).

use std::path::Path;

use glam::Vec3;
use stagelight::framebuffer::FrameBuffers;
use stagelight::settings::PixelFilter;

use crate::common::cli::{run_in, scratch_dir, stderr_of};
use crate::common::{png, render_text};
use crate::vertex_bake::BakedPly;

/// Side of the rendered images, pixels.
const SIDE: u32 = 48;

/// A cube `[-0.5, 0.5]³`, faces counter-clockwise seen from outside, as an inline object
/// `cube` with material `material`.
fn cube(material: &str) -> String {
    format!(
        r#"(name: "cube", mesh: Inline(
            vertices: [(-0.5, -0.5, -0.5), (0.5, -0.5, -0.5), (0.5, 0.5, -0.5), (-0.5, 0.5, -0.5),
                       (-0.5, -0.5, 0.5), (0.5, -0.5, 0.5), (0.5, 0.5, 0.5), (-0.5, 0.5, 0.5)],
            polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 4, 7, 3], [1, 2, 6, 5], [3, 7, 6, 2], [0, 1, 5, 4]]),
            material: "{material}"),"#
    )
}

/// One sample per pixel at its centre (a pinpoint filter), no adaptivity: a scene and its
/// mirror image through x = 0 sample mirrored points.
fn render(text: &str) -> FrameBuffers {
    render_spp(text, 1)
}

/// [`render`] with `spp` samples per pixel, all at its centre.
fn render_spp(text: &str, spp: u32) -> FrameBuffers {
    render_text(text, |s| {
        s.spp = spp;
        s.adaptive = None;
        s.filter = PixelFilter::Gaussian {
            sigma: 1e-3,
            radius: 1e-3,
        };
    })
    .0
}

/// A `SIDE`² camera on the plane x = 0 (at `eye`, looking at the origin), a point lamp at
/// `lamp` (on that plane too), the objects, and one instance `it` of `of` placed by
/// `transform`: mirroring the placement through x = 0 mirrors the whole scene.
fn scene(
    eye: Vec3,
    lamp: Vec3,
    materials: &str,
    objects: &str,
    of: &str,
    transform: &str,
) -> String {
    format!(
        r#"Scene(
    options: (max_depth: 2),
    cameras: [(name: "cam", fov_y: 40, resolution: ({SIDE}, {SIDE}),
        placement: LookAt(eye: ({}, {}, {}), target: (0, 0, 0)), outputs: [(file: "out.png")])],
    lights: [(name: "lamp", kind: Point(position: ({}, {}, {})), intensity: 30)],
    materials: [{materials}],
    objects: [{objects}],
    instances: [(name: "it", of: "{of}", transform: {transform})],
    groups: [(name: "world", members: ["it"])],
    render: (root: "world", camera: "cam"),
)"#,
        eye.x, eye.y, eye.z, lamp.x, lamp.y, lamp.z
    )
}

/// Mean absolute difference between `a` and the left-right mirror image of `b`, relative to
/// `a`'s mean brightness.
fn mirror_difference(a: &FrameBuffers, b: &FrameBuffers) -> f32 {
    let (w, h) = (a.width as usize, a.height as usize);
    let mut diff = 0.0;
    let mut sum = 0.0;
    for y in 0..h {
        for x in 0..w {
            let p = a.beauty[y * w + x];
            let q = b.beauty[y * w + (w - 1 - x)];
            diff += (p - q).abs().element_sum();
            sum += p.element_sum();
        }
    }
    assert!(sum > 0.0, "the plain image is black");
    diff / sum
}

/// Mean absolute difference between `a` and `b`, relative to `a`'s mean brightness.
fn difference(a: &FrameBuffers, b: &FrameBuffers) -> f32 {
    let diff: f32 = a
        .beauty
        .iter()
        .zip(&b.beauty)
        .map(|(p, q)| (*p - *q).abs().element_sum())
        .sum();
    let sum: f32 = a.beauty.iter().map(|p| p.element_sum()).sum();
    assert!(sum > 0.0, "the plain image is black");
    diff / sum
}

const RED: &str = r#"(name: "red", shader: Lambert(albedo: (0.8, 0.2, 0.2)))"#;
const TURNED: &str =
    "Rotate(axis: (0, 1, 0), degrees: 35), Rotate(axis: (1, 0, 0), degrees: 20), Translate((0.4, 0.1, 0))";

/// A one-sided cube turned and moved off the axis; mirrored through x = 0 (the last step) it
/// renders the mirror image of the plain one, and mirrored through z in object space (the
/// first step; the cube is symmetric) it renders the plain image. Before the rule, both
/// mirrored cubes showed their black back faces (relative differences ≈ 1).
#[test]
fn a_mirrored_one_sided_cube_renders_the_mirror_image_of_the_plain_one() {
    let at = |transform: &str| {
        render(&scene(
            Vec3::new(0.0, 1.0, 4.0),
            Vec3::new(0.0, 2.0, 4.0),
            RED,
            &cube("red"),
            "cube",
            transform,
        ))
    };
    let plain = at(&format!("[{TURNED}]"));
    let through_x = at(&format!("[{TURNED}, Scale((-1, 1, 1))]"));
    let through_z = at(&format!("[Scale((1, 1, -1)), {TURNED}]"));
    let lit = plain.beauty.iter().filter(|c| c.x > 0.05).count();
    assert!(lit > 200, "{lit} lit pixels");
    let (x, z) = (
        mirror_difference(&plain, &through_x),
        difference(&plain, &through_z),
    );
    println!("relative difference: mirror image {x:.2e}, object-space mirror {z:.2e}");
    assert!(x < 0.02, "mirrored through x: {x}");
    assert!(z < 0.02, "mirrored through z: {z}");
}

/// The glTF rule itself: a node whose global transform has a negative determinant (scale
/// `[-1, 1, 1]`) renders as the mirror image of the plain node under the default camera
/// (which frames the mirrored bounds symmetrically) and white environment.
#[test]
fn a_gltf_node_with_a_negative_scale_renders_the_mirror_image() {
    let dir = scratch_dir("mirrored-gltf");
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/gltf");
    std::fs::copy(fixtures.join("box.bin"), dir.join("box.bin")).unwrap();
    let text = std::fs::read_to_string(fixtures.join("box_external.gltf")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    std::fs::write(dir.join("plain.gltf"), json.to_string()).unwrap();
    json["nodes"][0]["scale"] = serde_json::json!([-1, 1, 1]);
    std::fs::write(dir.join("mirrored.gltf"), json.to_string()).unwrap();
    let at = |file: &str| {
        let mut scene = stagelight::scene::load_scene(&dir.join(file))
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        for (camera, _) in scene.world.query_mut::<(
            &mut stagelight::components::Camera,
            &stagelight::components::RenderCamera,
        )>() {
            camera.width = SIDE;
            camera.height = SIDE;
            camera.aspect = 1.0;
        }
        let mut settings = scene.settings.clone();
        settings.spp = 16;
        settings.adaptive = None;
        settings.filter = PixelFilter::Gaussian {
            sigma: 1e-3,
            radius: 1e-3,
        };
        crate::common::render(&mut scene.world, settings)
            .outputs
            .image
            .expect("an image")
    };
    let (plain, mirrored) = (at("plain.gltf"), at("mirrored.gltf"));
    let d = mirror_difference(&plain, &mirrored);
    println!("relative difference to the mirror image: {d:.2e}");
    assert!(d < 0.03, "{d}");
}

/// Reads a baked EXR: linear RGB texels.
fn exr(path: &Path) -> Vec<Vec3> {
    crate::common::read_exr_texels(path).1
}

/// An isolated convex cube under mirroring transforms bakes AO 1 at every covered texel and
/// every vertex (nothing but its own back faces could occlude it), and its tangent-space
/// normals are +N: the hemisphere is the outside one. Before the rule the mirrored cube's
/// hemispheres pointed inside (AO ≈ 0.01, and 15× the bake time).
#[test]
fn an_isolated_convex_cube_under_a_mirror_bakes_open_ao() {
    let dir = scratch_dir("mirrored-ao");
    for (k, transform) in [
        "[Scale((1, 1, -1))]",
        "[Rotate(axis: (1, 1, 0), degrees: 30), Scale((-2, 1, 1)), Translate((3, 0, 0))]",
    ]
    .iter()
    .enumerate()
    {
        let text = format!(
            r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
        placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0)), outputs: [(file: "view.png")])],
    materials: [{RED}],
    objects: [{}],
    instances: [(name: "c", of: "cube", transform: {transform}, bake: (
        resolution: (32, 32), uvs: Unwrap, texel_samples: 1, padding: 0, mask: true,
        stitch_seams: false,
        outputs: [
            (kind: AmbientOcclusion(samples: 32)),
            (kind: Normals(space: Tangent)),
            (kind: AmbientOcclusion(samples: 32), target: Vertices),
        ]))],
    groups: [(name: "world", members: ["c"])],
    render: (root: "world", camera: "cam"),
)"#,
            cube("red")
        );
        let name = format!("scene{k}.ron");
        std::fs::write(dir.join(&name), text).unwrap();
        let out = format!("out{k}");
        let o = run_in(&dir, &["bake", &name, "-o", &out]);
        assert!(o.status.success(), "{transform}: {}", stderr_of(&o));
        let out = dir.join(out);
        let mask = png::read(&out.join("c_mask.png"));
        let covered: Vec<usize> = (0..(mask.width * mask.height) as usize)
            .filter(|&p| mask.rgba(p)[0] > 0.5)
            .collect();
        assert!(covered.len() > 100, "{transform}: {} texels", covered.len());
        let (ao, normals) = (exr(&out.join("c_ao.exr")), exr(&out.join("c_normals.exr")));
        for &p in &covered {
            assert_eq!(ao[p], Vec3::ONE, "{transform}: texel {p}");
            assert!(
                normals[p].z > 0.999,
                "{transform}: texel {p}: {}",
                normals[p]
            );
        }
        let ply = BakedPly::read(&out.join("c_ao.ply"));
        assert_eq!(ply.count, 8);
        for v in 0..ply.count {
            assert_eq!(ply.float(v, "baked_r"), 1.0, "{transform}: vertex {v}");
        }
    }
}

/// A one-sided emitting square facing down over a floor, off the axis: mirrored through
/// x = 0 it still faces down, so the floor renders as the mirror image of the plain scene's
/// (mesh-light sampling), and the global photon map stores about the same power on the floor
/// (photon emission). Before the rule the mirrored square emitted upward: a dark floor and
/// no photons on it.
#[test]
fn a_mirrored_emitter_emits_from_its_object_space_front() {
    let materials = r#"(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
        (name: "glow", shader: Lambert(albedo: (0, 0, 0)), emission: (5, 5, 5))"#;
    let objects = r#"(name: "floor", mesh: Inline(vertices: [(-3, 0, -3), (-3, 0, 3), (3, 0, 3), (3, 0, -3)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "panel", mesh: Inline(vertices: [(-0.3, 0, -0.3), (0.3, 0, -0.3), (0.3, 0, 0.3), (-0.3, 0, 0.3)],
            polygons: [[0, 1, 2, 3]]), material: "glow"),"#;
    let text = |transform: &str, options: &str| {
        format!(
            r#"Scene(
    options: ({options}),
    cameras: [(name: "cam", fov_y: 50, resolution: ({SIDE}, {SIDE}),
        placement: LookAt(eye: (0, 4, 3), target: (0, 0, 0)), outputs: [(file: "out.png")])],
    materials: [{materials}],
    objects: [{objects}],
    instances: [(name: "floor_1", of: "floor"), (name: "panel_1", of: "panel", transform: {transform})],
    groups: [(name: "world", members: ["floor_1", "panel_1"])],
    render: (root: "world", camera: "cam"),
)"#
        )
    };
    let plain = "[Translate((0.6, 0.8, 0))]";
    let mirrored = "[Translate((0.6, 0.8, 0)), Scale((-1, 1, 1))]";
    // The panel's winding faces −y (down) in object space: (v1 − v0) × (v2 − v0) = (0, −0.36, 0).
    // 64 light samples per pixel: the images differ by the samples' noise (≈ 0.03).
    let options = "light_samples: 4";
    let (a, b) = (
        render_spp(&text(plain, options), 16),
        render_spp(&text(mirrored, options), 16),
    );
    let d = mirror_difference(&a, &b);
    let brightness = |f: &FrameBuffers| f.beauty.iter().map(|c| c.x).sum::<f32>();
    let ratio = brightness(&b) / brightness(&a);
    println!("relative difference to the mirror image: {d:.2e}, brightness ratio {ratio:.4}");
    assert!(d < 0.08, "{d}");
    assert!((ratio - 1.0).abs() < 0.02, "{ratio}");
    // Photons: the power the global map stores on the floor.
    let stored = |transform: &str| {
        let source = text(transform, "global_illumination: (photons: 4000)");
        let frame = crate::common::photon_frame(&source, "panel.ron");
        frame
            .outputs
            .photons
            .and_then(|m| m.global)
            .map_or(0.0, |m| m.map.total_power().x)
    };
    let (a, b) = (stored(plain), stored(mirrored));
    println!("stored photon power: plain {a:.4} W, mirrored {b:.4} W");
    assert!(a > 0.0);
    assert!((b / a - 1.0).abs() < 0.05, "plain {a}, mirrored {b}");
}

/// A see-through box x, y ∈ [−0.5, 0.5], z ∈ [−1.5, −1] filled with absorbing fog, before a
/// grey wall at z = −2 lit from the eye: the box's ray and shadow-ray segments are dimmed by
/// `e^(−σa·0.5)` each. Mirrored through x (the box is symmetric) the image is the same;
/// before the rule the mirrored box's fog was outside it (1.5 of the 2 units before the
/// wall, and the shadow ray's too).
#[test]
fn fog_fills_the_inside_of_a_mirrored_box() {
    let sigma = 0.8f32;
    let text = |transform: &str| {
        format!(
            r#"Scene(
    options: (samples: 1, max_depth: 4, refraction_depth: 4),
    cameras: [(name: "cam", fov_y: 30, resolution: ({SIDE}, {SIDE}),
        placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1)), outputs: [(file: "out.png")])],
    lights: [(name: "lamp", kind: Point(position: (0, 0, 0)), intensity: 4)],
    materials: [
        (name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
        (name: "shell", shader: Opacity(opacity: (0, 0, 0), input: Lambert(albedo: (0, 0, 0))),
         interior: Fog(sigma_a: ({sigma}, {sigma}, {sigma}), sigma_s: (0, 0, 0), g: 0.0)),
    ],
    objects: [
        (name: "wall", mesh: Inline(vertices: [(-4, -4, -2), (4, -4, -2), (4, 4, -2), (-4, 4, -2)], polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "box", mesh: Inline(
            vertices: [(-0.5, -0.5, -1.5), (0.5, -0.5, -1.5), (0.5, 0.5, -1.5), (-0.5, 0.5, -1.5),
                       (-0.5, -0.5, -1), (0.5, -0.5, -1), (0.5, 0.5, -1), (-0.5, 0.5, -1)],
            polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 4, 7, 3], [1, 2, 6, 5], [3, 7, 6, 2], [0, 1, 5, 4]]),
            material: "shell"),
    ],
    instances: [(name: "wall_1", of: "wall"), (name: "box_1", of: "box", transform: {transform})],
    groups: [(name: "world", members: ["wall_1", "box_1"])],
    render: (root: "world", camera: "cam"),
)"#
        )
    };
    let (plain, mirrored) = (render(&text("[]")), render(&text("[Scale((-1, 1, 1))]")));
    let clear = render(&text("[Translate((0, 10, 0))]"));
    let centre = (SIDE / 2 * SIDE + SIDE / 2) as usize;
    let want = (-2.0 * sigma * 0.5f32).exp();
    for (name, image) in [("plain", &plain), ("mirrored", &mirrored)] {
        let ratio = image.beauty[centre].x / clear.beauty[centre].x;
        assert!(
            (ratio / want - 1.0).abs() < 0.01,
            "{name}: centre dimmed to {ratio}, expected {want}"
        );
    }
    let d = difference(&plain, &mirrored);
    assert!(d < 1e-3, "{d}");
}

/// A RIB world is mirrored through z = 0 by the reader, so every RIB instance mirrors: with
/// `Sides 1` the camera still sees the outside RenderMan shows (`Orientation "outside"`, the
/// default: a polygon faces a viewer who sees its vertices clockwise, a sphere faces out).
#[test]
fn rib_sides_one_shows_the_outside() {
    let dir = scratch_dir("mirrored-rib");
    let centre = |body: &str| {
        let text = format!(
            "Format 16 16 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 1 1\n\
             LightSource \"pointlight\" 1 \"from\" [0 0 0] \"intensity\" [20]\n\
             WorldBegin\nSurface \"matte\"\n{body}\nWorldEnd\n"
        );
        let path = dir.join("scene.rib");
        std::fs::write(&path, text).unwrap();
        let mut scene = stagelight::scene::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
        let frame = crate::common::render(&mut scene.world, scene.settings.clone());
        let image = frame.outputs.image.expect("an image");
        image.beauty[(8 * 16 + 8) as usize].x
    };
    let sphere = "AttributeBegin\nTranslate 0 0 5\nSphere 1 -1 1 360\nAttributeEnd";
    let clockwise = "Polygon \"P\" [-1 -1 5  -1 1 5  1 1 5  1 -1 5]";
    let counter = "Polygon \"P\" [-1 -1 5  1 -1 5  1 1 5  -1 1 5]";
    let two_sided = centre(sphere);
    assert!(two_sided > 0.0);
    assert_eq!(centre(&format!("Sides 1\n{sphere}")), two_sided);
    let lit = centre(clockwise);
    assert!(lit > 0.0);
    assert_eq!(centre(&format!("Sides 1\n{clockwise}")), lit);
    assert_eq!(centre(&format!("Sides 1\n{counter}")), 0.0, "its back");
}
