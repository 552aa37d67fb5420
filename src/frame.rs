//! The per-run state shared by stages: settings, the typed outputs of each stage and the
//! run report. A skipped stage leaves its output `None`; consumers treat `None` as "no
//! contribution".

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use crate::framebuffer::FrameBuffers;
use crate::geometry::SceneGeometry;
use crate::schedule::RunReport;
use crate::settings::RenderSettings;

/// Everything stages pass forward to each other.
pub struct Frame {
    /// Render settings (scene `options` plus command-line overrides).
    pub settings: RenderSettings,
    /// Written by `build_accel`: world-space triangles, their BVH and shading attributes.
    pub geometry: Option<SceneGeometry>,
    /// Written by `shade`: the render camera's frame buffers.
    pub image: Option<FrameBuffers>,
    /// Written by `write_output`: the files that now exist.
    pub written: Vec<PathBuf>,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Set from another thread (SIGINT) to stop the run; stages poll it.
    pub cancel: Arc<AtomicBool>,
    /// Per-stage report, filled by the runner.
    pub report: RunReport,
}

impl Frame {
    /// A fresh frame with no stage outputs yet.
    pub fn new(settings: RenderSettings) -> Self {
        Self {
            settings,
            geometry: None,
            image: None,
            written: Vec::new(),
            progress: false,
            cancel: Arc::new(AtomicBool::new(false)),
            report: RunReport::default(),
        }
    }

    /// Whether the run was interrupted.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}
