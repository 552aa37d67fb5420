//! `write_output`: encodes the render camera's frame buffers into its output files (PNG,
//! EXR); the runner writes them with the run's other files, all or nothing.
//!
//! **Reads:** `outputs.image`; the render `Camera`'s `outputs` as redirected by
//! `inputs.outputs` (`-o`, `bench`'s scratch directory) and its `Imager` (PNG only).
//! **Writes:** files, handed to the runner encoded (`Work::pending`), which commits them.
//! **Runs when:** a shaded image exists and the camera (or the command line) lists outputs.
//! **After the run:** every output file exists complete, or none was touched.

use hecs::World;

use super::prelude::*;
use crate::components::{ImageFormat, OutputSpec, Pass};
use crate::farm::PartRun;
use crate::frame::Slot;
use crate::image_io::{encode_exr, encode_png, PendingFile};
use crate::scene_view::render_view;

/// The outputs this run writes: the camera's, with the command line's overrides.
fn outputs(world: &World, frame: &Frame) -> Result<Vec<OutputSpec>, StageError> {
    let listed = render_view(world)
        .map(|v| v.camera.outputs)
        .unwrap_or_default();
    frame
        .inputs
        .outputs
        .apply(&listed)
        .map_err(StageError::Internal)
}

/// Run condition: an image to write and somewhere to write it.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if !frame.outputs.has(Slot::Image) {
        return Decision::skip("no shaded image");
    }
    if frame.inputs.outputs.discard {
        return Decision::skip("this run keeps its image in memory");
    }
    if let Some(run) = &frame.inputs.part {
        return Decision::run(format!("{}: the part file", run.part));
    }
    let n = outputs(world, frame).map_or(0, |o| o.len());
    if n == 0 {
        return Decision::skip("render camera has no outputs");
    }
    Decision::run(format!("{n} camera output(s)"))
}

/// Encodes and writes every output.
pub fn run(world: &World, frame: &Frame) -> Result<Work, StageError> {
    if let Some(run) = &frame.inputs.part {
        return write_part(run, frame);
    }
    let outputs = outputs(world, frame)?;
    let imager = render_view(world).and_then(|v| v.imager);
    let fb = frame
        .outputs
        .image
        .as_ref()
        .ok_or_else(|| StageError::Internal("no image to write".into()))?;
    let mut pending = Vec::with_capacity(outputs.len());
    for out in &outputs {
        let bytes = match out.format {
            ImageFormat::Png => encode_png(fb, out.passes.contains(&Pass::Alpha), imager.as_ref()),
            ImageFormat::Exr => encode_exr(fb, &out.passes),
        }
        .map_err(|message| StageError::Write {
            path: out.path.clone(),
            message,
        })?;
        pending.push(PendingFile {
            path: out.path.clone(),
            bytes,
        });
    }
    if frame.cancelled() {
        return Err(StageError::Interrupted);
    }
    Ok(Work::new(pending.len() as u64, "files").with_pending(pending))
}

/// A farm part's run writes its part file (to `-o`) instead of the camera outputs.
fn write_part(run: &PartRun, frame: &Frame) -> Result<Work, StageError> {
    let fb = frame
        .outputs
        .image
        .as_ref()
        .ok_or_else(|| StageError::Internal("no image to write".into()))?;
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
    Ok(Work::new(1, "files").with_pending(vec![PendingFile { path, bytes }]))
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
