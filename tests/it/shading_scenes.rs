//! The shading example scenes, each checked for its defining property at low resolution.

use std::path::PathBuf;

use glam::Vec3;
use stagelight::components::{Camera, RenderCamera};
use stagelight::scene::load_scene;
use stagelight::settings::{Integrator, RenderSettings};

fn render(name: &str, tweak: impl FnOnce(&mut RenderSettings)) -> Vec<Vec3> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name);
    let mut scene = load_scene(&path).unwrap_or_else(|e| panic!("{name}:\n{e}"));
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        camera.width = 40;
        camera.height = 30;
    }
    let mut settings = scene.settings.clone();
    settings.spp = 4;
    tweak(&mut settings);
    let frame = crate::common::render(&mut scene.world, settings);
    frame.outputs.image.expect("image").beauty
}

fn mean(image: &[Vec3]) -> f32 {
    image.iter().map(|c| c.element_sum()).sum::<f32>() / (3 * image.len()) as f32
}

/// `mirror.ron`: the backdrop is a mirror — black with `reflection_depth: 0`, showing the
/// lit floor and boxes with the scene's depth of 2.
#[test]
fn mirror_scene_reflects_only_within_the_reflection_depth() {
    let none = render("mirror.ron", |s| s.reflection_depth = 0);
    let two = render("mirror.ron", |_| {});
    assert!(
        mean(&two) > 1.1 * mean(&none),
        "{} vs {}",
        mean(&two),
        mean(&none)
    );
}

/// `glass.ron`: the glass blocks transmit — with `refraction_depth: 0` they are dark, with
/// the scene's depth they show the lit backdrop and floor through them.
#[test]
fn glass_scene_transmits_within_the_refraction_depth() {
    for integrator in [Integrator::Direct, Integrator::Path] {
        let none = render("glass.ron", |s| {
            s.refraction_depth = 0;
            s.integrator = integrator;
        });
        let six = render("glass.ron", |s| s.integrator = integrator);
        assert!(
            mean(&six) > 1.02 * mean(&none),
            "{integrator:?}: {} vs {}",
            mean(&six),
            mean(&none)
        );
    }
}

/// `materials_plastic_metal.ron` and `materials_mental_ray.ron`: the path tracer adds
/// indirect light to what the direct integrator computes (the scenes are lit by one panel,
/// so interreflection can only brighten them on average).
#[test]
fn material_scenes_gain_indirect_light_with_the_path_tracer() {
    for name in ["materials_plastic_metal.ron", "materials_mental_ray.ron"] {
        let direct = render(name, |s| s.spp = 16);
        let path = render(name, |s| {
            s.spp = 16;
            s.integrator = Integrator::Path;
        });
        assert!(
            mean(&path) > mean(&direct),
            "{name}: {} vs {}",
            mean(&path),
            mean(&direct)
        );
    }
}
