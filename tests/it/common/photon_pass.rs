//! Running the stage table up to and including `trace_photons` (the stages before
//! `bake_lightmaps`), on a world or on a RON scene's text, for tests of the photon maps.

use std::path::Path;

use hecs::World;
use stagelight::frame::Frame;
use stagelight::settings::RenderSettings;

/// Runs every stage before `bake_lightmaps` on `world` with `settings`.
pub fn through_photons(world: &mut World, settings: RenderSettings) -> Frame {
    let mut frame = Frame::new(settings);
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .take_while(|s| s.name != "bake_lightmaps")
        .collect();
    stagelight::schedule::run_stages(&stages, world, &mut frame).expect("photon pass");
    frame
}

/// Loads the RON scene `text` (located as the file `name`) and runs its stages up to the
/// photon maps with its own settings.
pub fn photon_frame(text: &str, name: &str) -> Frame {
    let mut scene =
        stagelight::scene::load_scene_str(text, Path::new(name)).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    through_photons(&mut scene.world, settings)
}
