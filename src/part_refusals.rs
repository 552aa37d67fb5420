//! What a farm part refuses before anything runs: `render --part K/N` checks it, and so does
//! `stagelight farm` before it writes scripts whose every part would be refused. The
//! messages are the user's, with a `help:` line; the caller exits with status 2. Also what
//! only `farm` refuses: more parts than there is work for ([`part_count_refusal`],
//! [`bake_part_count_refusal`]) and a render whose merge would write nothing
//! ([`no_outputs_refusal`]).

use std::path::Path;

use hecs::World;

use crate::farm::part::{plural, tile_count, useful_parts, TILE};
use crate::farm::{PartNumber, Split};
use crate::frame::OutputOverrides;
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

/// The refusal of `farm --parts N` for a render when some of the N parts would compute
/// nothing: more parts than the image has tiles (`--split tiles`) or than a pixel takes
/// samples (`--split samples`; a part without samples would still trace the centre-sample
/// passes or nothing at all). The message names the largest useful N.
pub fn part_count_refusal(
    world: &World,
    settings: &RenderSettings,
    count: u32,
    split: Split,
) -> Option<String> {
    let camera = crate::scene_view::render_view(world)?.camera;
    let (w, h) = (camera.width, camera.height);
    let spp = crate::adaptive::SampleBudget::new(settings).min;
    let most = useful_parts(split, w, h, spp);
    if u64::from(count) <= most {
        return None;
    }
    let idle = u64::from(count) - most;
    let (work, help) = match split {
        Split::Tiles => (
            format!(
                "the {w}×{h} image has only {} of {TILE}×{TILE} pixels, so {} would own no tile",
                plural(most, "tile", "tiles"),
                plural(idle, "part", "parts")
            ),
            format!("use --parts {most} or fewer"),
        ),
        Split::Samples => (
            format!(
                "a pixel takes only {}, so {} would take none",
                plural(most, "sample", "samples"),
                plural(idle, "part", "parts")
            ),
            format!(
                "use --parts {most} or fewer, more samples (--spp), or --split tiles (up to {} parts)",
                tile_count(w, h)
            ),
        ),
    };
    Some(format!(
        "--parts {count} is more parts than there is work for: {work}\n  help: {help}"
    ))
}

/// The refusal of `farm --bake --parts N` when some of the N parts would own no texel: more
/// parts than the bake requests have tiles of [`TILE`]×[`TILE`] texels (`tiles`, over
/// `requests` requests). The sizes of density-sized and per-vertex requests come from the
/// built geometry, so the caller counts the tiles after the geometry stages.
pub fn bake_part_count_refusal(count: u32, tiles: u64, requests: usize) -> Option<String> {
    if u64::from(count) <= tiles {
        return None;
    }
    Some(format!(
        "--parts {count} is more parts than there is work for: the bake {} only {} of {TILE}×{TILE} texels, so {} would own no texel\n  help: use --parts {tiles} or fewer",
        if requests == 1 { "request has" } else { "requests have" },
        plural(tiles, "tile", "tiles"),
        plural(u64::from(count) - tiles, "part", "parts")
    ))
}

/// The refusal of `farm` for a render whose merge would write nothing: the render camera
/// has no outputs and `-o` names none (`overrides`). A plain `render` skips `shade` for the
/// same reason.
pub fn no_outputs_refusal(world: &World, overrides: &OutputOverrides) -> Option<String> {
    let outputs = crate::scene_view::render_outputs(world, overrides).ok()?;
    outputs.is_empty().then(|| {
        "the render camera has no outputs, so the merge job would write nothing after every part rendered\n  help: name the merged image with -o FILE, e.g. -o image.png".to_string()
    })
}
