//! Fuzz target: arbitrary text as a scene file. The loader must return `Ok` or located
//! errors, never panic; a loaded scene's numbers are finite.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match stagelight::scene::load_scene_str(text, std::path::Path::new("fuzz.ron")) {
        Ok(scene) => {
            for camera in scene.world.query::<&stagelight::components::Camera>().iter() {
                assert!(camera.fov_y.is_finite() && camera.width > 0 && camera.height > 0);
            }
        }
        Err(errors) => {
            assert!(!errors.0.is_empty());
            for d in &errors.0 {
                assert!(d.line >= 1 && d.column >= 1);
            }
        }
    }
});
