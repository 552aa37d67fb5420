//! `sweep --reference FILE`, refused before the scene is read when the sweep could not
//! compare with it: a file that cannot be read, or one that is not an EXR image; and, once
//! read, before any run, one whose width and height are not the runs' (a bake sweep's
//! texture size is known after its first run).

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

/// The refusal (without `error: `) of a `--reference` of `found` pixels (width, height) for
/// runs of `runs` pixels: compared pixel by pixel, it would be misaligned.
pub fn size_mismatch(path: &Path, found: (u32, u32), runs: (u32, u32)) -> String {
    format!(
        "--reference {} is {}×{} pixels, the runs render {}×{}\n  help: {EXPECTED}",
        path.display(),
        found.0,
        found.1,
        runs.0,
        runs.1
    )
}
