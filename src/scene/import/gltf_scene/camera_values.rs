//! Checking a glTF perspective camera's `yfov` and `aspectRatio` before they become a scene
//! camera: glTF 2.0 requires both to be greater than 0, and a field of view of π radians
//! (180°) or more is no perspective view. Each problem is an error naming the camera and the
//! value, at the value's line and column in a `.gltf` (at the start of a `.glb`); nothing is
//! clamped in silence.

use super::json_positions::{value_position, Step};
use super::view::CAMERA_WIDTH;
use super::Walk;
use crate::scene::message::Diagnostic;

/// Tallest image a glTF camera may ask for through its aspect ratio (the width is
/// [`CAMERA_WIDTH`]).
pub const MAX_CAMERA_HEIGHT: u32 = 16384;

/// A perspective camera's usable values: `fov_y` in degrees, and the image height.
pub struct CameraValues {
    /// Vertical field of view, degrees, in (0, 180).
    pub fov_y: f64,
    /// Image height in pixels (from `aspectRatio`, 4:3 without one).
    pub height: u32,
}

/// Checks camera `camera`'s perspective values; `None` (with errors pushed, once per camera
/// however many nodes use it) where one is unusable.
pub fn check(
    w: &mut Walk<'_>,
    camera: &gltf::Camera<'_>,
    p: &gltf::camera::Perspective<'_>,
) -> Option<CameraValues> {
    let index = camera.index();
    let label = match camera.name() {
        Some(n) => format!("cameras[{index}] (\"{n}\")"),
        None => format!("cameras[{index}]"),
    };
    let yfov = p.yfov();
    let fov_y = f64::from(yfov).to_degrees();
    let fov_ok = fov_y > 0.0 && fov_y < 180.0;
    if !fov_ok {
        error(
            w,
            index,
            "yfov",
            format!(
                "{label}: \"yfov\" must be greater than 0 and less than π radians (180°), found {yfov}"
            ),
            "\"yfov\" is the vertical field of view in radians: 0.8 is about 46°",
        );
    }
    let aspect = p.aspect_ratio();
    let height = match aspect {
        None => Some(CAMERA_WIDTH * 3 / 4),
        Some(a) if a.is_finite() && a > 0.0 => {
            let h = (f64::from(CAMERA_WIDTH) / f64::from(a)).round();
            (1.0..=f64::from(MAX_CAMERA_HEIGHT))
                .contains(&h)
                .then_some(h as u32)
        }
        Some(_) => None,
    };
    if let (Some(a), None) = (aspect, height) {
        let message = if a > 0.0 {
            format!(
                "{label}: \"aspectRatio\" {a} makes the image {CAMERA_WIDTH} pixels wide and {} high; glTF cameras are read {CAMERA_WIDTH} wide and 1 … {MAX_CAMERA_HEIGHT} high",
                CAMERA_WIDTH as f32 / a
            )
        } else {
            format!("{label}: \"aspectRatio\" must be greater than 0, found {a}")
        };
        error(
            w,
            index,
            "aspectRatio",
            message,
            "\"aspectRatio\" is the image's width / height: 1.5 for 3:2; leave it out for 4:3",
        );
    }
    Some(CameraValues {
        fov_y: fov_ok.then_some(fov_y)?,
        height: height?,
    })
}

/// Pushes an error at `cameras[index].perspective.<key>` (once).
fn error(w: &mut Walk<'_>, index: usize, key: &str, message: String, help: &str) {
    let path = [
        Step::Key("cameras"),
        Step::Index(index),
        Step::Key("perspective"),
        Step::Key(key),
    ];
    let (line, column) = w
        .json
        .and_then(|json| value_position(json, &path))
        .unwrap_or((1, 1));
    if w.errors.iter().any(|e| e.message == message) {
        return;
    }
    w.errors.push(Diagnostic {
        file: w.path.to_path_buf(),
        line,
        column,
        message,
        help: Some(help.into()),
    });
}
