//! Component passes (`Emission`, `DiffuseDirect`, `DiffuseIndirect`, `Specular`,
//! `Transmission`, `Volume`): on every example scene, with both integrators, the six layers
//! sum to the beauty per pixel within 1e-5 relative, and asking for them leaves the beauty
//! bit-identical; each layer carries light somewhere; the EXR layers are written, and a PNG
//! or a farm part cannot hold them.

use std::path::{Path, PathBuf};

use glam::Vec3;
use stagelight::components::{Camera, ImageFormat, OutputSpec, Pass, RenderCamera};
use stagelight::frame::Frame;
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::load_scene;
use stagelight::settings::Integrator;

use crate::common::cli::{bin, run, scratch, stderr};
use crate::common::example_scenes;

/// Renders `path` shrunk to at most 12 pixels across with at most 2 samples (adaptive
/// sampling capped at 4) with `integrator`; `components`: an EXR output asking for the six
/// component passes is added to the render camera.
fn render(path: &Path, integrator: Integrator, components: bool) -> FrameBuffers {
    let mut scene = load_scene(path).unwrap_or_else(|e| panic!("{}:\n{e}", path.display()));
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        let scale = (12.0 / camera.width.max(camera.height) as f32).min(1.0);
        camera.width = ((camera.width as f32 * scale).round() as u32).max(1);
        camera.height = ((camera.height as f32 * scale).round() as u32).max(1);
        if components {
            camera.outputs.push(OutputSpec {
                path: PathBuf::from("components.exr"),
                format: ImageFormat::Exr,
                passes: Pass::COMPONENTS.to_vec(),
                beauty_alpha: true,
            });
        }
    }
    let mut settings = scene.settings.clone();
    settings.spp = settings.spp.min(2);
    settings.integrator = integrator;
    if let Some(a) = &mut settings.adaptive {
        a.max = a.max.min(4);
        a.min = a.min.min(a.max);
    }
    let mut frame = Frame::new(settings);
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    frame.outputs.image.take().expect("an image")
}

/// Checks every example scene with `integrator`; returns the largest value each component
/// reached over all scenes.
fn components_sum_to_the_beauty(integrator: Integrator) -> [f32; 6] {
    let mut largest = [0.0f32; 6];
    for path in example_scenes() {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let plain = render(&path, integrator, false);
        assert!(plain.components.is_none(), "{name}: no components unasked");
        let split = render(&path, integrator, true);
        let bits = |fb: &FrameBuffers| -> Vec<u32> {
            fb.beauty
                .iter()
                .flat_map(|c| c.to_array().map(f32::to_bits))
                .collect()
        };
        assert_eq!(bits(&plain), bits(&split), "{name}: the beauty changed");
        let layers = split.components.as_ref().expect("component buffers");
        assert_eq!(layers.len(), split.beauty.len());
        for (i, (parts, beauty)) in layers.iter().zip(&split.beauty).enumerate() {
            let sum = parts.iter().fold(Vec3::ZERO, |s, p| s + *p);
            for c in 0..3 {
                let (s, b) = (sum[c], beauty[c]);
                assert!(
                    (s - b).abs() <= 1e-5 * b.abs(),
                    "{name} {integrator:?} pixel {i} channel {c}: layers sum to {s}, beauty {b} ({parts:?})"
                );
            }
            for (k, p) in parts.iter().enumerate() {
                largest[k] = largest[k].max(p.max_element());
            }
        }
    }
    largest
}

#[test]
fn direct_integrator_layers_sum_to_the_beauty_on_every_example_scene() {
    let largest = components_sum_to_the_beauty(Integrator::Direct);
    println!("largest per component (Direct): {largest:?}");
    // Emission (visible lights, emitting surfaces, the environment), diffuse direct,
    // diffuse indirect (ambient terms, photon maps), specular (mirror.ron, highlights),
    // transmission (glass.ron), volume (fog.ron): each carries light somewhere.
    for (k, v) in largest.iter().enumerate() {
        assert!(
            *v > 1e-3,
            "{:?} is empty on every scene",
            Pass::COMPONENTS[k]
        );
    }
}

#[test]
fn path_tracer_layers_sum_to_the_beauty_on_every_example_scene() {
    let largest = components_sum_to_the_beauty(Integrator::Path);
    println!("largest per component (Path): {largest:?}");
    for (k, v) in largest.iter().enumerate() {
        assert!(
            *v > 1e-3,
            "{:?} is empty on every scene",
            Pass::COMPONENTS[k]
        );
    }
}

/// A Lambert floor (albedo 0.5, emission 0.25) under a point light of 2 W/sr at height 2:
/// the camera pixel straight below sees emission 0.25 and diffuse direct ρ/π·I/d², nothing
/// else, with either integrator (the path tracer's further bounces escape: no other surface).
#[test]
fn a_lit_emitting_floor_splits_into_emission_and_diffuse_direct() {
    let scene = r#"Scene(
    cameras: [(name: "cam", fov_y: 10, resolution: (3, 3),
        placement: LookAt(eye: (0, 2, 0), target: (0, 0, 0), up: (0, 0, -1)),
        outputs: [(file: "out.exr", passes: [Beauty, Emission, DiffuseDirect, DiffuseIndirect, Specular, Transmission, Volume])])],
    materials: [(name: "floor", shader: Lambert(albedo: (0.5, 0.5, 0.5)), emission: (0.25, 0.25, 0.25))],
    objects: [(name: "quad", mesh: Inline(vertices: [(-50, 0, -50), (50, 0, -50), (50, 0, 50), (-50, 0, 50)], polygons: [[0, 3, 2, 1]]))],
    instances: [(name: "q", of: "quad", material: "floor")],
    lights: [(name: "lamp", kind: Point(position: (0, 2, 0)), color: (1, 1, 1), intensity: 2)],
    groups: [(name: "world", members: ["q"])],
    render: (root: "world", camera: "cam"),
)
"#;
    let dir = scratch("components_floor");
    let path = dir.join("floor.ron");
    std::fs::write(&path, scene).unwrap();
    let expected = 0.5 / std::f32::consts::PI * 2.0 / 4.0;
    for integrator in [Integrator::Direct, Integrator::Path] {
        let fb = render(&path, integrator, false);
        let parts = fb.components.as_ref().expect("asked for by the scene")[4];
        println!("{integrator:?}: {parts:?}");
        assert!((parts[0] - Vec3::splat(0.25)).abs().max_element() < 1e-6);
        assert!(
            (parts[1] - Vec3::splat(expected)).abs().max_element() < 2e-3 * expected,
            "{integrator:?}: {} vs {expected}",
            parts[1]
        );
        for p in &parts[2..] {
            assert_eq!(*p, Vec3::ZERO, "{integrator:?}");
        }
    }
}

/// The CLI writes the component layers as `emission.R` … channels; a PNG output cannot hold
/// them (located error) and a farm part refuses them.
#[test]
fn component_layers_go_to_exr_only() {
    let dir = scratch("components_cli");
    let scene = dir.join("c.ron");
    let text = r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (6, 4),
        placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)),
        outputs: [(file: "c.exr", passes: [Beauty, Specular, Emission])])],
    objects: [(name: "tri", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]))],
    instances: [(name: "t", of: "tri")],
    groups: [(name: "world", members: ["t"])],
    render: (root: "world", camera: "cam"),
)
"#;
    std::fs::write(&scene, text).unwrap();
    let o = run(bin().current_dir(&dir).arg("render").arg(&scene));
    assert!(o.status.success(), "{}", stderr(&o));
    let read = exr::prelude::read_all_flat_layers_from_file(dir.join("c.exr")).unwrap();
    let mut names: Vec<String> = read.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "A",
            "B",
            "G",
            "R",
            "emission.B",
            "emission.G",
            "emission.R",
            "specular.B",
            "specular.G",
            "specular.R"
        ]
    );

    let o = run(bin()
        .current_dir(&dir)
        .args([
            "render", "--part", "1/2", "--split", "samples", "-o", "p.exr",
        ])
        .arg(&scene));
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim_end(),
        "error: --part 1/2 --split samples cannot carry the component passes (Specular, Emission) of c.exr\n  help: use --split tiles (the default), or leave them out of the farm render's outputs"
    );
    assert!(!dir.join("p.exr").exists());

    std::fs::write(&scene, text.replace("c.exr", "c.png")).unwrap();
    let o = run(bin().arg("check").arg(&scene));
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains(
            "c.ron:4:52: error: a PNG output cannot hold the Specular pass\n  help: write the Specular pass to an .exr output"
        ),
        "{}",
        stderr(&o)
    );
}

/// Tile parts carry the component values of the pixels they own: `merge` writes the same EXR
/// bytes, layers included, as the single render.
#[test]
fn component_passes_go_through_tile_parts_bit_identically() {
    let dir = scratch("component-parts");
    let text = r#"Scene(
    options: (samples: 4),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (12, 8),
        placement: LookAt(eye: (0, -3, 3), target: (0, 0, 0)),
        outputs: [(file: "c.exr", passes: [Beauty, DiffuseDirect, Specular])])],
    lights: [(name: "sun", kind: Point(position: (1, -1, 3)), intensity: 4.0)],
    materials: [(name: "plastic", shader: Phong(diffuse: (0.5, 0.4, 0.3), specular: (0.4, 0.4, 0.4), spec_exp: 20))],
    objects: [(name: "ball", mesh: Sphere(radius: 1), material: "plastic")],
    instances: [(name: "b", of: "ball")],
    groups: [(name: "world", members: ["b"])],
    render: (root: "world", camera: "cam"),
)
"#;
    std::fs::write(dir.join("c.ron"), text).unwrap();
    let ok = |args: &[&str]| {
        let o = run(bin().current_dir(&dir).args(args));
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    };
    ok(&["render", "c.ron", "-o", "single.exr"]);
    for k in 1..=3 {
        let part = format!("{k}/3");
        let name = format!("part_{k}.exr");
        ok(&["render", "c.ron", "--part", &part, "-o", &name]);
    }
    ok(&[
        "merge",
        "part_1.exr",
        "part_2.exr",
        "part_3.exr",
        "-o",
        "merged.exr",
    ]);
    let single = std::fs::read(dir.join("single.exr")).unwrap();
    assert!(std::fs::read(dir.join("merged.exr")).unwrap() == single);
    let read = exr::prelude::read_all_flat_layers_from_file(dir.join("single.exr")).unwrap();
    let lit = read.layer_data[0]
        .channel_data
        .list
        .iter()
        .filter(|c| {
            c.name.to_string().starts_with("diffuse_direct")
                || c.name.to_string().starts_with("specular")
        })
        .all(|c| c.sample_data.values_as_f32().any(|v| v > 0.0));
    assert!(lit, "every requested layer carries light somewhere");
}
