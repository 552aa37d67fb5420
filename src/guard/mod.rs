//! Guards against hostile input (issue 18): checks that run on a loaded scene and on a run's
//! plan before any stage does, so that input the renderer cannot handle is refused with a
//! located error instead of reaching a panic, an abort or a clobbered file.
//!
//! - [`extent`]: coordinates beyond what `f32` tracing supports;
//! - [`outputs`]: outputs that would overwrite an input or each other;
//! - [`empty`]: placed objects without geometry (a located warning);
//! - [`limits`]: hard limits (worker threads, file sizes);
//! - [`interrupt`]: SIGINT and SIGTERM stop a run within [`interrupt::GRACE`].
//!
//! The README's "Reliability" section lists every guarantee with its limit and its test.

pub mod empty;
pub mod extent;
pub mod interrupt;
pub mod limits;
pub mod locate;
pub mod outputs;

pub use crate::scene::include::io_reason;
use crate::scene::{LoadedScene, SceneErrors};

/// The checks of a loaded scene that need the spawned world, run by `load_scene`: refuses the
/// scene with every problem located.
pub fn check_loaded(mut scene: LoadedScene) -> Result<LoadedScene, SceneErrors> {
    let errors = extent::check_world(&scene.world);
    if errors.is_empty() {
        scene.located_warnings.extend(empty::warnings(&scene.world));
        Ok(scene)
    } else {
        Err(SceneErrors(errors))
    }
}
