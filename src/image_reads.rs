//! What a run reads of the render camera's image: its camera samples (the shaded colour,
//! the coverage, the component passes), or only what the pixel-centre rays give (depth,
//! normal, ids, and the diagnostic views drawn from those rays). `shade` takes no sample
//! where nothing reads one, traces no pixel-centre ray where nothing reads a pixel-centre
//! pass, and `trace_photons` traces no map that only the samples read.

use hecs::World;

use crate::components::{ImageFormat, OutputSpec, Pass};
use crate::diagnostic::Diagnostic;
use crate::frame::RunInputs;

/// Why this run takes no camera sample (`None`: something reads them): every output it
/// writes (after `-o`) holds only pixel-centre passes (depth, normal, camera-space passes,
/// ids), or a diagnostic view drawn from the pixel-centre rays replaces the beauty (grid,
/// photon, bvh) and no output reads the coverage or a component pass.
///
/// Samples are read by the `Beauty` pass (unless such a view replaces it), the coverage (an
/// `Alpha` pass, an EXR's `A` beside `Beauty`, a PNG imager's `background`, composited by
/// it), the component passes and drawn contours (their store keeps each pixel's shaded
/// colour). A caller that keeps the image, a farm part (its merge may write any output)
/// and a merge read them always.
pub fn samples_unread(world: &World, inputs: &RunInputs) -> Option<String> {
    if inputs.caller_keeps_image || inputs.part.is_some() || inputs.merging() {
        return None;
    }
    let outputs = crate::scene_view::written_outputs(world, inputs).ok()?;
    if outputs.is_empty() {
        return None; // `shade` skips: nothing reads the image at all.
    }
    let view = inputs.settings.diagnostic.filter(|d| centre_view(*d));
    let mut colour_read = false;
    let imager_background = crate::scene_view::render_view(world)
        .and_then(|v| v.imager)
        .is_some_and(|i| i.background.is_some() || i.pattern.is_some());
    let contours = crate::scene_view::contours_drawn(world, inputs).is_ok();
    for out in &outputs {
        let colour = out.passes.contains(&Pass::Beauty)
            || (contours && (is_vector(out) || out.passes.contains(&Pass::Contours)));
        let coverage = match out.format {
            ImageFormat::Exr => out.exr_alpha(),
            ImageFormat::Png => {
                out.passes.contains(&Pass::Alpha)
                    || (imager_background && out.passes.contains(&Pass::Beauty))
            }
            ImageFormat::Svg | ImageFormat::Eps => false,
        };
        let components = out.passes.iter().any(|p| p.component().is_some());
        if coverage || components || (colour && view.is_none()) {
            return None;
        }
        colour_read |= colour;
    }
    Some(match view {
        Some(d) if colour_read => format!(
            "the diagnostic {} view is drawn from pixel-centre rays and no output reads the coverage or a component pass",
            d.name()
        ),
        _ => format!(
            "no output reads the shaded image: {}",
            centre_passes_text(&outputs)
        ),
    })
}

/// Whether the run reads the pixel-centre passes `shade` fills from one ray through each
/// pixel centre (depth, normal, ids; the camera-space passes are derived from them): an
/// output it writes (after `-o`) holds one, or a caller that keeps the image, a farm part
/// (its file carries them for the merge) or a merge reads them. Nothing else does: the
/// coverage and the beauty come from the samples, and the diagnostic views
/// ([`crate::diagnostic_view`]) and the contour store trace their own centre rays. Where
/// nothing reads them, `shade` traces no pixel-centre ray.
pub fn centres_read(world: &World, inputs: &RunInputs) -> bool {
    if inputs.caller_keeps_image || inputs.part.is_some() || inputs.merging() {
        return true;
    }
    crate::scene_view::written_outputs(world, inputs).map_or(true, |outputs| {
        outputs
            .iter()
            .any(|o| o.passes.iter().any(|p| centre_pass(*p)))
    })
}

/// Whether pass `p` comes from the pixel-centre rays rather than the samples.
fn centre_pass(p: Pass) -> bool {
    matches!(
        p,
        Pass::Depth | Pass::Normal | Pass::ObjectId | Pass::MaterialId
    ) || Pass::CAMERA_SPACE.contains(&p)
}

/// Whether `d` is drawn from the pixel-centre rays alone (grid, photon, bvh), rather than
/// from the samples (`Samples`: the number each pixel took).
pub fn centre_view(d: Diagnostic) -> bool {
    !matches!(d, Diagnostic::Samples)
}

fn is_vector(out: &OutputSpec) -> bool {
    matches!(out.format, ImageFormat::Svg | ImageFormat::Eps)
}

/// `only pixel-centre passes ("depth.exr": Depth, ObjectId)`, every output named.
fn centre_passes_text(outputs: &[OutputSpec]) -> String {
    let each: Vec<String> = outputs
        .iter()
        .map(|o| {
            let passes: Vec<String> = o.passes.iter().map(|p| format!("{p:?}")).collect();
            format!("\"{}\": {}", o.path.display(), passes.join(", "))
        })
        .collect();
    format!("only pixel-centre passes ({})", each.join("; "))
}
