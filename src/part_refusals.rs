//! What a farm part refuses before anything runs: `render --part K/N` checks it, and so does
//! `stagelight farm` before it writes scripts whose every part would be refused. The
//! messages are the user's, with a `help:` line; the caller exits with status 2.

use std::path::Path;

use hecs::World;

use crate::farm::{PartNumber, Split};
use crate::settings::RenderSettings;

/// Whether `-o path` names a part file (`.exr`); the refusal says what to give instead.
pub fn part_file_output(number: PartNumber, output: Option<&Path>) -> Result<(), String> {
    let exr = output.is_some_and(|o| o.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")));
    if exr {
        return Ok(());
    }
    let (k, n) = (number.index, number.count);
    let given = match output {
        Some(o) => format!(
            ", which is an OpenEXR file: -o {} must end in .exr",
            o.display()
        ),
        None => ": give it with -o PART.exr".to_string(),
    };
    Err(format!(
        "--part {k}/{n} writes a part file{given}\n  help: e.g. -o part_{k}.exr, then `stagelight merge part_*.exr -o image.png`"
    ))
}

/// The first reason the parts of a render with `settings` of the scene in `world`, divided
/// by `split`, cannot be merged into the single render's outputs. `diagnostic_flag` says
/// whether a diagnostic view came from `--diagnostic` (else from the scene's options).
pub fn part_refusal(
    world: &World,
    settings: &RenderSettings,
    number: PartNumber,
    split: Split,
    diagnostic_flag: bool,
) -> Option<String> {
    let (k, n) = (number.index, number.count);
    if let Some(d) = settings.diagnostic {
        let source = if diagnostic_flag {
            format!("--diagnostic {}", d.name())
        } else {
            format!("the scene's `options: (diagnostic: …)` ({})", d.name())
        };
        return Some(format!(
            "--part {k}/{n} cannot render a diagnostic view ({source})\n  help: parts carry the shaded sums, which the merge turns into the beauty image, not the view; render the diagnostic view without --part"
        ));
    }
    if split == Split::Samples && settings.adaptive.is_some() {
        return Some("--split samples cannot divide adaptive sampling (a pixel's second pass depends on all of its first-pass samples)\n  help: use --split tiles, or a fixed count with --spp N".into());
    }
    component_passes_in_samples_part(world, number, split)
}

/// Tile parts carry the component passes of the pixels they own; a samples part would need
/// exact component sums: the refusal of `--part … --split samples` for a camera output that
/// asks for them.
fn component_passes_in_samples_part(
    world: &World,
    number: PartNumber,
    split: Split,
) -> Option<String> {
    if split == Split::Tiles {
        return None;
    }
    let view = crate::scene_view::render_view(world)?;
    view.camera.outputs.iter().find_map(|o| {
        let names: Vec<String> = (o.passes.iter())
            .filter(|p| p.component().is_some())
            .map(|p| format!("{p:?}"))
            .collect();
        (!names.is_empty()).then(|| format!(
            "--part {}/{} --split samples cannot carry the component passes ({}) of {}\n  help: use --split tiles (the default), or leave them out of the farm render's outputs",
            number.index, number.count, names.join(", "), o.path.display()
        ))
    })
}
