//! `write_output`: encodes the render camera's frame buffers into its output files (PNG,
//! EXR) and the contour lines into SVG and EPS; the runner writes them with the run's other files,
//! all or nothing.
//!
//! **Reads:** `outputs.image`; `outputs.contours`; the render `Camera`'s `outputs` as redirected by
//! `inputs.outputs` (`-o`, `bench`'s scratch directory), its `Imager` (PNG only) and its
//! placement and lenses (the camera-space passes, derived by `crate::exr_output`).
//! **Writes:** files, handed to the runner encoded (`Work::pending`), which commits them.
//! **Runs when:** a shaded image exists and the camera (or the command line) lists outputs.
//! SVG and EPS outputs hold only contour lines: a run that draws none
//! (`crate::scene_view::unwritten_outputs`: output shaders disabled, every contrast
//! criterion off) leaves them unwritten, its reason names them, and with no other output
//! the stage is skipped.
//! **After the run:** every output file exists complete, or none was touched.

use hecs::World;

use super::prelude::*;
use glam::Vec3;

use crate::camera_space::CameraSpace;
use crate::components::{ImageFormat, Imager, OutputSpec, Pass};
use crate::contour::eps::encode_eps;
use crate::contour::svg::encode_svg;
use crate::contour::{output, ContourImage};
use crate::exr_output::encode_output;
use crate::farm::part::Share;
use crate::farm::PartRun;
use crate::frame::Slot;
use crate::framebuffer::FrameBuffers;
use crate::image_io::{encode_alpha_png, encode_png, PendingFile};
use crate::scene_view::render_view;

/// The outputs this run writes: the camera's, with the command line's overrides, less the
/// contour-only ones when no contours are drawn ([`crate::scene_view::written_outputs`]).
fn outputs(world: &World, frame: &Frame) -> Result<Vec<OutputSpec>, StageError> {
    crate::scene_view::written_outputs(world, &frame.inputs).map_err(StageError::Internal)
}

/// Run condition: an image to write and somewhere to write it. SVG and EPS outputs are
/// left unwritten when the run draws no contours, and the reason says so.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    let unwritten = (frame.inputs.part.is_none() && !frame.inputs.outputs.discard)
        .then(|| crate::scene_view::unwritten_outputs(world, &frame.inputs))
        .flatten();
    let n = outputs(world, frame).map_or(0, |o| o.len());
    if let (Some(unwritten), 0) = (&unwritten, n) {
        return Decision::skip(unwritten.reason());
    }
    if !frame.outputs.has(Slot::Image) {
        if let (Some(run), Some(Share::Nothing(_))) = (
            &frame.inputs.part,
            crate::scene_view::part_share(world, &frame.inputs),
        ) {
            return Decision::run(format!("{}: the part file, empty", run.part));
        }
        return Decision::skip("no shaded image");
    }
    if frame.inputs.outputs.discard {
        return Decision::skip("this run keeps its image in memory");
    }
    if let Some(run) = &frame.inputs.part {
        return Decision::run(format!("{}: the part file", run.part));
    }
    if n == 0 {
        return Decision::skip("render camera has no outputs");
    }
    match unwritten {
        Some(unwritten) => Decision::run(format!("{n} camera output(s); {}", unwritten.reason())),
        None => Decision::run(format!("{n} camera output(s)")),
    }
}

/// Encodes and writes every output.
pub fn run(world: &World, frame: &Frame) -> Result<Work, StageError> {
    if let Some(run) = &frame.inputs.part {
        return write_part(run, world, frame);
    }
    let outputs = outputs(world, frame)?;
    let imager = render_view(world).and_then(|v| v.imager);
    let fb = frame
        .outputs
        .image
        .as_ref()
        .ok_or_else(|| StageError::Internal("no image to write".into()))?;
    let contours = frame.outputs.contours.as_ref();
    // The lenses `shade` traced with: the camera-space passes follow its centre rays.
    let camera_space = CameraSpace::of_render_camera(world, frame.inputs.settings.disabled)
        .ok_or_else(|| StageError::Internal("no render camera".into()))?;
    let mut pending = Vec::with_capacity(outputs.len());
    for out in &outputs {
        let bytes = match out.format {
            ImageFormat::Png => png(fb, contours, out, imager.as_ref()),
            ImageFormat::Exr => {
                let extra = match contours {
                    Some(c) if out.passes.contains(&Pass::Contours) => output::exr_channels(c),
                    _ => Vec::new(),
                };
                encode_output(fb, &camera_space, out, extra)
            }
            ImageFormat::Svg | ImageFormat::Eps => {
                let Some(c) = contours else {
                    return Err(StageError::Internal(format!(
                        "no contour lines for {}",
                        out.path.display()
                    )));
                };
                if out.format == ImageFormat::Svg {
                    Ok(encode_svg(c).into_bytes())
                } else {
                    Ok(encode_eps(c).into_bytes())
                }
            }
        }
        .map_err(|message| StageError::Write {
            path: out.path.clone(),
            message,
        })?;
        pending.push(PendingFile::new(out.path.clone(), bytes));
    }
    if frame.cancelled() {
        return Err(StageError::Interrupted);
    }
    Ok(Work::new(pending.len() as u64, "files").with_pending(pending))
}

/// A PNG output: the alpha pass alone as a grey image when it lists `Alpha` without `Beauty`
/// or `Contours`; else the beauty (straight colour beside its alpha with `Alpha`), with the contours composited when it lists `Contours` (over
/// the beauty when it lists `Beauty` too, else over the imager's background colour, white
/// without one, as an opaque image).
fn png(
    fb: &FrameBuffers,
    contours: Option<&ContourImage>,
    out: &OutputSpec,
    imager: Option<&Imager>,
) -> Result<Vec<u8>, String> {
    let alpha = out.passes.contains(&Pass::Alpha);
    if alpha && !out.passes.contains(&Pass::Beauty) && !out.passes.contains(&Pass::Contours) {
        return encode_alpha_png(fb);
    }
    let Some(c) = contours.filter(|_| out.passes.contains(&Pass::Contours)) else {
        return encode_png(fb, alpha, imager);
    };
    let mut composed = fb.clone();
    if out.passes.contains(&Pass::Beauty) {
        output::composite(&mut composed.beauty, &mut composed.alpha, c, None);
        // The lines cover the environment share as they cover the rest of the beauty.
        if let Some(environment) = &mut composed.environment {
            for (e, line) in environment.iter_mut().zip(&c.layer) {
                *e *= 1.0 - line.w;
            }
        }
        return encode_png(&composed, alpha, imager);
    }
    let paper = imager.and_then(|i| i.background).unwrap_or(Vec3::ONE);
    output::composite(&mut composed.beauty, &mut composed.alpha, c, Some(paper));
    // The paper hides what the camera saw.
    composed.environment = None;
    encode_png(&composed, alpha, None)
}

/// A farm part's run writes its part file (to `-o`) instead of the camera outputs.
/// A part that computes nothing (`shade` skipped) writes the empty part file.
fn write_part(run: &PartRun, world: &World, frame: &Frame) -> Result<Work, StageError> {
    let idle;
    let fb = match frame.outputs.image.as_ref() {
        Some(fb) => fb,
        None => {
            idle = super::shade::idle_part_image(world, frame)
                .ok_or_else(|| StageError::Internal("no image to write".into()))?;
            &idle
        }
    };
    let path = frame
        .inputs
        .outputs
        .first
        .clone()
        .ok_or_else(|| StageError::Internal("a part run without -o".into()))?;
    let file = crate::farm::part_file(run, &frame.inputs.settings, fb)
        .ok_or_else(|| StageError::Internal("a part run without exact sums".into()))?;
    let bytes = crate::farm::part_file::encode(&file).map_err(|message| StageError::Write {
        path: path.clone(),
        message,
    })?;
    if frame.cancelled() {
        return Err(StageError::Interrupted);
    }
    Ok(Work::new(1, "files").with_pending(vec![PendingFile::new(path, bytes)]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::systems::tiny_scene::{load, run_until, scene};

    #[test]
    fn writes_the_camera_output_where_the_run_inputs_say() {
        let dir =
            std::env::temp_dir().join(format!("stagelight-unit-write-{}", std::process::id()));
        let (mut world, mut frame) = load(&scene("", "", "", &[]), false);
        frame.inputs.outputs.directory = Some(dir.clone());
        run_until("write_output", &mut world, &mut frame);
        assert_eq!(
            should_run(&world, &frame),
            Decision::run("1 camera output(s)")
        );
        let work = run(&world, &frame).unwrap();
        assert_eq!(work.files, vec![dir.join("tiny.exr")]);
        assert!(!work.pending[0].bytes.is_empty());
        assert!(!dir.exists(), "the runner, not the stage, writes files");
        assert!(work.output.is_none(), "write_output has no output slot");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn skipped_without_a_shaded_image() {
        let (world, frame) = load(&scene("", "", "", &[]), false);
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("no shaded image")
        );
    }
}
