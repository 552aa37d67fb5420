//! Image writers: PNG (8-bit sRGB) and OpenEXR (linear f32 layers). Files are written to a
//! temporary name in the destination directory and renamed into place, so a file either
//! exists whole or not at all.

mod atomic;
mod exr_writer;
pub mod imager;
mod png_writer;
pub mod srgb;

pub use atomic::{commit_all, PendingFile};
pub use exr_writer::encode_exr;
pub use png_writer::encode_png;
