//! The EXR file of a camera output: the passes it lists, as channels of one layer, and extra
//! layers (the contours). The frame buffers' own passes are written as they are; the
//! camera-space passes (`CameraDepth`, `CameraNormal`, `CameraPosition`) are derived here,
//! from the centre-sample depth and normal and the camera that rendered them
//! ([`crate::camera_space`]). The camera is part of the call, so every writer of a camera
//! output — `write_output` for a render, a farm merge and a bench run, and library callers —
//! derives them in this one place, and no writer can meet one underived: a merged image
//! carries only the depth and normal, and its EXR is the single render's bytes.

use crate::camera_space::CameraSpace;
use crate::components::{OutputSpec, Pass};
use crate::framebuffer::FrameBuffers;
use crate::image_io::encode_passes;

/// Encodes `passes` of `fb`, rendered by `camera`, into an EXR file in memory, with the
/// `extra` f32 channels of the same size (e.g. the contour layer); `Beauty` and `Alpha`
/// each bring the coverage as channel `A`.
pub fn encode_exr_with(
    fb: &FrameBuffers,
    camera: &CameraSpace,
    passes: &[Pass],
    extra: Vec<(&str, Vec<f32>)>,
) -> Result<Vec<u8>, String> {
    let alpha = passes.contains(&Pass::Beauty) || passes.contains(&Pass::Alpha);
    encode(fb, camera, passes, alpha, extra)
}

/// The EXR file of the camera output `out`: [`encode_exr_with`] with the coverage as
/// channel `A` only where the output asks for it ([`OutputSpec::exr_alpha`]: RIB's `rgbz`
/// display writes `R G B Z`).
pub fn encode_output(
    fb: &FrameBuffers,
    camera: &CameraSpace,
    out: &OutputSpec,
    extra: Vec<(&str, Vec<f32>)>,
) -> Result<Vec<u8>, String> {
    encode(fb, camera, &out.passes, out.exr_alpha(), extra)
}

fn encode(
    fb: &FrameBuffers,
    camera: &CameraSpace,
    passes: &[Pass],
    alpha: bool,
    extra: Vec<(&str, Vec<f32>)>,
) -> Result<Vec<u8>, String> {
    let mut channels = extra;
    channels.extend(camera.exr_channels(fb, passes));
    encode_passes(fb, passes, alpha, channels)
}

/// [`encode_exr_with`] without extra channels.
pub fn encode_exr(
    fb: &FrameBuffers,
    camera: &CameraSpace,
    passes: &[Pass],
) -> Result<Vec<u8>, String> {
    encode_exr_with(fb, camera, passes, Vec::new())
}
