//! `sweep --reference FILE`, refused before the scene is read when the sweep could not
//! compare with it: a file that cannot be read, or one that is not an EXR image.

use std::path::Path;

use crate::image_io::exr_magic::file_could_be_exr;

/// What the help of a refused `--reference` asks for.
const EXPECTED: &str = "give a linear EXR image of the runs' size (without --reference, the sweep renders one and caches it in --out)";

/// Refuses a `--reference` that cannot be read or is not an EXR file; the message (without
/// `error: `) names the flag, the file and what is expected.
pub fn usable(path: &Path) -> Result<(), String> {
    match file_could_be_exr(path) {
        Ok(true) => Ok(()),
        Ok(false) => Err(format!(
            "--reference {} is not an EXR file\n  help: {EXPECTED}",
            path.display()
        )),
        Err(e) => Err(format!(
            "--reference {}: cannot read it: {}\n  help: {EXPECTED}",
            path.display(),
            crate::scene::message::io_reason(&e)
        )),
    }
}
