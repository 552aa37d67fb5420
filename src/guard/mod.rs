//! Guards against hostile input (issue 18): checks that run on a loaded scene and on a run's
//! plan before any stage does, so that input the renderer cannot handle is refused with a
//! located error instead of reaching a panic, an abort or a clobbered file.
//!
//! - [`extent`]: coordinates beyond what `f32` tracing supports;
//! - [`outputs`]: outputs that would overwrite an input or each other;
//! - [`part_files`]: outputs of a merge (or of a farm's merge job) that would overwrite a part file;
//! - [`dir_flags`]: output paths and directories of flags that cannot be used (a file in the
//!   way, a directory that takes no file or cannot be created);
//! - [`writable`]: whether a path could be written, tried before the first stage;
//! - [`empty`]: placed objects without geometry (a located warning);
//! - [`limits`]: hard limits (worker threads, file sizes);
//! - [`interrupt`]: SIGINT and SIGTERM stop a run within [`interrupt::GRACE`];
//! - [`cancellable`]: long work that cannot poll the cancel flag (the BVH build), waited
//!   for in a way that can stop.
//!
//! The README's "Reliability" section lists every guarantee with its limit and its test.

pub use crate::scene::world_checks::{empty, extent};
pub mod cancellable;
pub mod dir_flags;
pub mod interrupt;
pub use crate::limits;
pub mod locate;
pub mod outputs;
pub mod part_files;
pub mod writable;

pub use crate::scene::message::io_reason;
