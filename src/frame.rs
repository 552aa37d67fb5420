//! The per-run state shared by stages: settings, the typed outputs of each stage and the
//! run report. A skipped stage leaves its output `None`; consumers treat `None` as "no
//! contribution".

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use crate::bake::BakeReport;
use crate::framebuffer::FrameBuffers;
use crate::geometry::SceneGeometry;
use crate::photon::PhotonMaps;
use crate::schedule::RunReport;
use crate::settings::RenderSettings;

/// What the user asked this run to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tasks {
    /// Render the render camera (`stagelight render`).
    pub render: bool,
    /// Bake the scene's bake requests (`stagelight bake`, or `render --bake`).
    pub bake: bool,
}

impl Default for Tasks {
    fn default() -> Self {
        Self {
            render: true,
            bake: false,
        }
    }
}

/// Everything stages pass forward to each other.
pub struct Frame {
    /// Render settings (scene `options` plus command-line overrides).
    pub settings: RenderSettings,
    /// What to do: render, bake or both.
    pub tasks: Tasks,
    /// Directory for baked textures (relative paths resolve against the working directory).
    pub bake_dir: PathBuf,
    /// Written by `build_accel`: world-space triangles, their BVH and shading attributes.
    pub geometry: Option<SceneGeometry>,
    /// Written by `trace_photons`: the caustic and global photon maps.
    pub photons: Option<PhotonMaps>,
    /// Written by `shade`: the render camera's frame buffers.
    pub image: Option<FrameBuffers>,
    /// Written by `bake_lightmaps`: one report per bake request.
    pub bake_reports: Vec<BakeReport>,
    /// Written by `write_output` and `bake_lightmaps`: the files that now exist.
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
            tasks: Tasks::default(),
            bake_dir: PathBuf::from("."),
            geometry: None,
            photons: None,
            bake_reports: Vec::new(),
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
