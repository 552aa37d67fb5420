//! `sweep --reference FILE`, refused before the scene is read when the sweep could not
//! compare with it: a file that cannot be read, or one that is not an EXR image; and, once
//! read, before any run, one whose width and height are not the runs' (a bake sweep's
//! texture size is known after its first run) or whose R, G and B channels cannot be read
//! (a part file of `render --part`, a cut file).

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

/// The refusal (without `error: `) of a `--reference` that is an EXR file whose R, G and B
/// channels could not be read (`reason` is the reader's): a part file of `render --part`
/// (sums, not an image), an EXR file without those channels, or one cut short.
pub fn unreadable(path: &Path, reason: &str) -> String {
    let shown = path.display();
    let headers = exr::meta::MetaData::read_from_file(path, false).map(|m| m.headers);
    let Ok(headers) = headers else {
        return format!(
            "--reference {shown} is not a readable EXR file ({reason}); it may be truncated\n  help: {EXPECTED}"
        );
    };
    if headers
        .iter()
        .any(|h| crate::farm::exr_meta::read_header(h).is_some())
    {
        return format!(
            "--reference {shown} is a stagelight part file, which holds a part's sample sums, not an image\n  help: merge the parts first (`stagelight merge PART.exr… -o reference.exr`) and give the merged EXR, or {EXPECTED}"
        );
    }
    let has = |h: &exr::meta::header::Header, name: &str| {
        h.channels
            .list
            .iter()
            .any(|c| c.name.to_string().eq_ignore_ascii_case(name))
    };
    if !headers
        .iter()
        .any(|h| ["R", "G", "B"].iter().all(|c| has(h, c)))
    {
        return format!(
            "--reference {shown} has no R, G and B channels to compare\n  help: {EXPECTED}"
        );
    }
    format!("--reference {shown} cannot be read as an RGB image ({reason})\n  help: {EXPECTED}")
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
