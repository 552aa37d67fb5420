//! `Display name type mode`: the output file and its passes.
//!
//! RISpec 3.2's modes: `rgb`, `rgba`, `rgbz`, `rgbaz`, `a`, `az`, `z`; and the output
//! variables stagelight has a pass for: `N` (the Normal pass). `P` (position) has no pass: a
//! located warning says it is not written. The depth (`z`) is stagelight's Depth pass — the
//! distance along each pixel's centre ray — and the normal its world-space shading normal,
//! not RenderMan's camera-space `z` and `N`: a warning says so. Depth and normals are written
//! to EXR only: another file name becomes the `.exr` of the same stem (a warning), as in the
//! `.mi` reader; colour and alpha go to PNG unless the name ends in `.exr`.

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
    /// The output, `None` for a mode stagelight does not write (`P`).
    pub display: Option<Display>,
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
        "rgbz" => vec![PassDesc::Beauty, PassDesc::Depth],
        "rgbaz" => vec![PassDesc::Beauty, PassDesc::Alpha, PassDesc::Depth],
        "a" => vec![PassDesc::Alpha],
        "az" => vec![PassDesc::Alpha, PassDesc::Depth],
        "z" => vec![PassDesc::Depth],
        "N" => vec![PassDesc::Normal],
        "P" => {
            problems.push(Problem::warning(
                mpos,
                format!(
                    "display mode \"P\" (position) is not written: stagelight has no position \
                     pass, so \"{name}\" is not made"
                ),
            ));
            return Ok(DisplayRequest {
                append,
                display: None,
            });
        }
        other => {
            let mut e = Problem::error(mpos, format!("display mode \"{other}\" is not supported"));
            e.help = suggestion(other, MODES, "display modes");
            return Err(e);
        }
    };
    if passes.contains(&PassDesc::Depth) {
        problems.push(Problem::warning(
            mpos,
            format!(
                "display mode \"{mode}\": the depth (EXR channel Z) is the distance along each \
                 pixel's centre ray, not RenderMan's camera-space z"
            ),
        ));
    }
    if passes.contains(&PassDesc::Normal) {
        problems.push(Problem::warning(
            mpos,
            "display mode \"N\": the normals (EXR channels N.X N.Y N.Z) are world-space shading \
             normals, not RenderMan's camera-space N",
        ));
    }
    let data = passes
        .iter()
        .any(|p| matches!(p, PassDesc::Depth | PassDesc::Normal));
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
                "depth and normals are written to EXR only"
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
    Ok(DisplayRequest {
        append,
        display: Some(Display { file, pos, passes }),
    })
}

fn ignored(p: &Param) -> Problem {
    Problem::warning(
        p.name_pos,
        format!("ignored parameter \"{}\" of Display", p.name),
    )
}
