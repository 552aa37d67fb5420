//! Issue 16, item 9: the shipped `caustics.ron` renders clean at its own settings — its back
//! wall, lit indirectly by final gathering into a 20 000-photon global map, shows no speckles
//! (they came from caustic photons in the global map, read by a few gather rays).

use std::path::PathBuf;

use stagelight::components::{Camera, RenderCamera};
use stagelight::scene::load_scene;

#[test]
fn the_caustics_scene_has_no_speckles_on_its_back_wall() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/caustics.ron");
    let mut scene = load_scene(&path).expect("caustics scene loads");
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        camera.width = 64;
        camera.height = 48;
    }
    // The wall's light is the global map's: the caustic map does not reach it.
    let mut settings = scene.settings.clone();
    settings.photons.caustics = None;
    let frame = crate::common::render(&mut scene.world, settings);
    let image = frame.outputs.image.as_ref().expect("image");
    let (w, h) = (image.width as usize, image.height as usize);
    // The top quarter is wall, but for the ball in the middle.
    let mut wall: Vec<f32> = (0..h / 4)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, _)| (x as f32) < 0.3 * w as f32 || (x as f32) > 0.7 * w as f32)
        .map(|(x, y)| image.beauty[y * w + x].element_sum())
        .collect();
    wall.sort_by(f32::total_cmp);
    let median = wall[wall.len() / 2];
    let max = wall[wall.len() - 1];
    println!(
        "wall: median {median:.4}, max {max:.4} ({} pixels)",
        wall.len()
    );
    assert!(
        median > 0.0 && max < 1.5 * median,
        "speckle: {max} vs median {median}"
    );
}
