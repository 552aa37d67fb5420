//! Image writers: PNG (8-bit sRGB; every PNG read and write goes through [`png_codec`]) and
//! OpenEXR (linear f32 layers; every EXR read from outside is size-checked by [`exr_limits`]
//! first), and the all-or-nothing
//! commit of a run's files ([`commit_all`]: temporaries, then renames, rolled back on
//! failure).

mod atomic;
pub mod exr_limits;
pub mod exr_magic;
mod exr_writer;
pub mod imager;
mod imager_pattern;
pub mod png_codec;
mod png_palette;
mod png_writer;
pub mod srgb;

pub use atomic::{commit_all, commit_state, os_reason, remove_stale, PendingFile};
pub(crate) use exr_writer::encode_passes;
pub use png_writer::{encode_alpha_png, encode_png};
