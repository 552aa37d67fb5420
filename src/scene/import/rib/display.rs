//! `Display name type mode`: the output file and its passes.
//!
//! RISpec 3.2's modes: `rgb`, `rgba`, `rgbz`, `rgbaz`, `a`, `az`, `z`; and the output
//! variables `N` and `P`. The depth (`z`), normals (`N`) and positions (`P`) are what a
//! RenderMan renderer writes: camera-space values (stagelight's `CameraDepth`,
//! `CameraNormal` and `CameraPosition` passes, in RenderMan's left-handed camera space, not
//! the reader's mirrored world; see `crate::camera_space`). They are written to EXR only:
//! another file name becomes the `.exr` of the same stem (a warning), as in the `.mi`
//! reader; colour and alpha go to PNG unless the name ends in `.exr`. A file holds the
//! channels its mode's letters name: `rgbz` writes `R G B Z`, no `A`.

use std::path::Path;

use super::super::located::Problem;
use super::camera::Display;
use super::params::{Args, Declarations, Param};
use crate::scene::desc::PassDesc;
use crate::scene::suggest::suggestion;

/// The display modes read, in the order the help lists them.
const MODES: &[&str] = &["rgb", "rgba", "rgbz", "rgbaz", "a", "az", "z", "N", "P"];

/// What a `Display` request asks for.
pub struct DisplayRequest {
    /// `+name`: added to the displays, not replacing them.
    pub append: bool,
    /// The output.
    pub display: Display,
}

/// Reads a `Display` request's arguments.
pub fn read(
    mut a: Args<'_>,
    decls: &Declarations,
    problems: &mut Vec<Problem>,
) -> Result<DisplayRequest, Problem> {
    let (name, pos) = a.string("name")?;
    let (ty, tpos) = a.string("type")?;
    let (mode, mpos) = a.string("mode")?;
    // Display parameters are the display driver's (`quantize`, `dither`, `compression`,
    // …): none is mapped, and an undeclared one is no error.
    for p in a.params_lenient(decls, problems) {
        problems.push(ignored(&p));
    }
    let (append, name) = match name.strip_prefix('+') {
        Some(n) => (true, n.to_string()),
        None => (false, name),
    };
    if !matches!(
        ty.as_str(),
        "file" | "tiff" | "framebuffer" | "png" | "exr" | "openexr"
    ) {
        problems.push(Problem::warning(
            tpos,
            format!("display type \"{ty}\" is not supported: writing a file"),
        ));
    }
    let passes = match mode.as_str() {
        "rgb" => vec![PassDesc::Beauty],
        "rgba" => vec![PassDesc::Beauty, PassDesc::Alpha],
        "rgbz" => vec![PassDesc::Beauty, PassDesc::CameraDepth],
        "rgbaz" => vec![PassDesc::Beauty, PassDesc::Alpha, PassDesc::CameraDepth],
        "a" => vec![PassDesc::Alpha],
        "az" => vec![PassDesc::Alpha, PassDesc::CameraDepth],
        "z" => vec![PassDesc::CameraDepth],
        "N" => vec![PassDesc::CameraNormal],
        "P" => vec![PassDesc::CameraPosition],
        other => {
            let mut e = Problem::error(mpos, format!("display mode \"{other}\" is not supported"));
            e.help = suggestion(other, MODES, "display modes");
            return Err(e);
        }
    };
    let data = passes.iter().any(|p| {
        matches!(
            p,
            PassDesc::CameraDepth | PassDesc::CameraNormal | PassDesc::CameraPosition
        )
    });
    let path = Path::new(&name);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let file = match ext.as_deref() {
        Some("png") if !data => name.clone(),
        Some("exr") => name.clone(),
        _ => {
            let new = path
                .with_extension(if data { "exr" } else { "png" })
                .display()
                .to_string();
            let why = if data && ext.as_deref() == Some("png") {
                "depth, normals and positions are written to EXR only"
            } else {
                "stagelight writes PNG and EXR"
            };
            problems.push(Problem::warning(
                pos,
                format!("writing \"{new}\" for display \"{name}\": {why}"),
            ));
            new
        }
    };
    // The channels are those the mode's letters name: colour without `a` writes no alpha
    // (an EXR's `Beauty` otherwise brings the coverage as `A`; a PNG writes it only with
    // `Alpha`).
    let exr = file.to_ascii_lowercase().ends_with(".exr");
    let beauty_alpha =
        (exr && passes.contains(&PassDesc::Beauty) && !passes.contains(&PassDesc::Alpha))
            .then_some(false);
    Ok(DisplayRequest {
        append,
        display: Display {
            file,
            pos,
            passes,
            beauty_alpha,
        },
    })
}

fn ignored(p: &Param) -> Problem {
    Problem::warning(
        p.name_pos,
        format!("ignored parameter \"{}\" of Display", p.name),
    )
}
