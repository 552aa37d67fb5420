//! Every example scene in `assets/scenes/` loads and renders (at a reduced resolution) with
//! finite, non-negative pixels in every pass.

use crate::common::example_scenes;
use stagelight::components::{Camera, RenderCamera};
use stagelight::frame::Frame;
use stagelight::scene::load_scene;

#[test]
fn every_example_scene_renders_without_nan_or_inf() {
    for path in example_scenes() {
        let mut scene = load_scene(&path).unwrap_or_else(|e| panic!("{}:\n{e}", path.display()));
        // Shrink the render camera so the whole set stays fast.
        for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
            let scale = (48.0 / camera.width.max(camera.height) as f32).min(1.0);
            camera.width = ((camera.width as f32 * scale).round() as u32).max(1);
            camera.height = ((camera.height as f32 * scale).round() as u32).max(1);
        }
        let mut settings = scene.settings.clone();
        settings.spp = settings.spp.min(4);
        let mut frame = Frame::new(settings);
        let stages: Vec<_> = stagelight::systems::STAGES
            .iter()
            .copied()
            .filter(|s| s.name != "write_output")
            .collect();
        stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let fb = frame
            .outputs
            .image
            .unwrap_or_else(|| panic!("{}: no image", path.display()));
        let name = path.display();
        assert!(
            fb.beauty
                .iter()
                .all(|c| c.is_finite() && c.min_element() >= 0.0),
            "{name}: beauty"
        );
        assert!(fb.alpha.iter().all(|a| a.is_finite()), "{name}: alpha");
        assert!(fb.normal.iter().all(|n| n.is_finite()), "{name}: normal");
        assert!(fb.depth.iter().all(|d| !d.is_nan()), "{name}: depth");
        assert!(
            fb.beauty.iter().any(|c| c.max_element() > 0.0),
            "{name}: image is black"
        );
    }
}
