//! `write_output`: encodes the render camera's frame buffers into its output files (PNG,
//! EXR) and writes them whole-or-nothing.
//!
//! **Reads:** `frame.image`; the render `Camera`'s `outputs` and its `Imager` (PNG only).
//! **Writes:** files on disk; `frame.written`.
//! **Runs when:** a shaded image exists and the camera lists outputs.
//! **After this stage:** every output file exists complete, or none was touched.

use hecs::World;

use super::prelude::*;
use crate::components::{Camera, ImageFormat, Imager, Pass, RenderCamera};
use crate::image_io::{commit_all, encode_exr, encode_png, PendingFile};

/// Run condition: an image to write and somewhere to write it.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if frame.image.is_none() {
        return Decision::skip("no shaded image");
    }
    let outputs = world
        .query::<(&Camera, &RenderCamera)>()
        .iter()
        .next()
        .map(|(c, _)| c.outputs.len())
        .unwrap_or(0);
    if outputs == 0 {
        return Decision::skip("render camera has no outputs");
    }
    Decision::run(format!("{outputs} camera output(s)"))
}

/// Encodes and writes every output.
pub fn run(world: &mut World, frame: &mut Frame) -> Result<Work, StageError> {
    let (outputs, imager) = world
        .query::<(&Camera, &RenderCamera, Option<&Imager>)>()
        .iter()
        .next()
        .map(|(c, _, i)| (c.outputs.clone(), i.copied()))
        .unwrap_or_default();
    let fb = frame
        .image
        .as_ref()
        .ok_or_else(|| StageError::Invalid("no image to write".into()))?;
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
    let written = commit_all(&pending).map_err(|(path, e)| StageError::Write {
        path,
        message: e.to_string(),
    })?;
    let n = written.len() as u64;
    frame.written = written;
    Ok(Work {
        items: n,
        unit: "files",
    })
}
