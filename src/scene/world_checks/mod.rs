//! The checks of a loaded scene that need the spawned world: the supported extent
//! ([`extent`]), objects without geometry ([`empty`]) and lights at a foggy eye
//! ([`light_at_eye`]). `load_scene` runs them, so every
//! caller of the loader gets them.

pub mod empty;
pub mod extent;
pub mod light_at_eye;

use super::{LoadedScene, SceneErrors};

/// Refuses the scene with every extent problem located, and adds the warnings about
/// objects without geometry.
pub fn check_loaded(mut scene: LoadedScene) -> Result<LoadedScene, SceneErrors> {
    let errors = extent::check_world(&scene.world);
    scene.located_warnings.extend(empty::warnings(&scene.world));
    scene
        .located_warnings
        .extend(light_at_eye::warnings(&scene.world));
    if errors.is_empty() {
        Ok(scene)
    } else {
        Err(SceneErrors(errors, scene.located_warnings))
    }
}
