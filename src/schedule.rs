//! The stage runner: stage type, run conditions, and the per-stage report.

use std::time::Instant;

use hecs::World;
use serde::Serialize;

use crate::accel::RayCounts;
use crate::frame::Frame;

/// Whether a stage runs, and the reason (which component or option decided it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decision {
    /// True when the stage has work.
    pub run: bool,
    /// Human-readable reason, e.g. `"3 instances with meshes"` or `"no camera outputs"`.
    pub reason: String,
}

impl Decision {
    /// The stage runs because of `reason`.
    pub fn run(reason: impl Into<String>) -> Self {
        Self {
            run: true,
            reason: reason.into(),
        }
    }
    /// The stage is skipped because of `reason`.
    pub fn skip(reason: impl Into<String>) -> Self {
        Self {
            run: false,
            reason: reason.into(),
        }
    }
}

/// Work a stage did, for throughput figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Work {
    /// Items processed.
    pub items: u64,
    /// What an item is (`"triangles"`, `"samples"`, `"files"`, …).
    pub unit: &'static str,
}

/// Errors a stage can end with.
#[derive(Debug, thiserror::Error)]
pub enum StageError {
    /// Writing an output file failed.
    #[error("cannot write {path}: {message}")]
    Write {
        /// The file.
        path: std::path::PathBuf,
        /// What went wrong.
        message: String,
    },
    /// The user interrupted the run.
    #[error("interrupted")]
    Interrupted,
    /// The world lacks something the stage needs (a bug in a run condition or the loader).
    #[error("{0}")]
    Invalid(String),
}

/// A run condition: a cheap, pure query over the world and frame.
pub type RunCondition = fn(&World, &Frame) -> Decision;
/// A stage body.
pub type StageFn = fn(&mut World, &mut Frame) -> Result<Work, StageError>;

/// One entry of the stage table.
#[derive(Clone, Copy)]
pub struct Stage {
    /// Reported name (equal to the module name in `systems/`).
    pub name: &'static str,
    /// When the stage runs.
    pub condition: RunCondition,
    /// What it does.
    pub run: StageFn,
}

/// What the runner recorded for one stage.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageReport {
    /// Stage name.
    pub stage: &'static str,
    /// Whether it ran.
    pub ran: bool,
    /// Why it ran or was skipped.
    pub reason: String,
    /// Wall time of the stage body (0 when skipped).
    pub seconds: f64,
    /// Items processed.
    pub items: u64,
    /// Unit of `items`.
    pub unit: &'static str,
    /// Items per second (0 when skipped).
    pub items_per_second: f64,
    /// Items per second per worker thread.
    pub items_per_second_per_thread: f64,
    /// Closest-hit rays the stage traced (counted by the accelerator).
    pub rays_closest: u64,
    /// Occlusion (shadow, AO) rays the stage traced.
    pub rays_occlusion: u64,
    /// All rays the stage traced (`rays_closest + rays_occlusion`).
    pub rays: u64,
    /// Rays per second (0 when the stage traced none).
    pub rays_per_second: f64,
    /// Rays per second per worker thread (0 when the stage traced none).
    pub rays_per_second_per_thread: f64,
}

/// The whole run's report.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RunReport {
    /// Worker threads used.
    pub threads: usize,
    /// One entry per stage of the table, in order.
    pub stages: Vec<StageReport>,
    /// Wall time of the whole schedule.
    pub total_seconds: f64,
}

impl RunReport {
    /// The entry for a stage, if it is in the table.
    pub fn stage(&self, name: &str) -> Option<&StageReport> {
        self.stages.iter().find(|s| s.stage == name)
    }

    /// A fixed-width table for `--stats`.
    pub fn to_table(&self) -> String {
        let mut out = String::new();
        out.push_str(&format!(
            "{:<16} {:<4} {:>9} {:>12} {:<10} {:>14} {:>12}  reason\n",
            "stage", "ran", "seconds", "items", "unit", "items/s", "rays"
        ));
        for s in &self.stages {
            out.push_str(&format!(
                "{:<16} {:<4} {:>9.4} {:>12} {:<10} {:>14.0} {:>12}  {}\n",
                s.stage,
                if s.ran { "yes" } else { "no" },
                s.seconds,
                s.items,
                s.unit,
                s.items_per_second,
                s.rays,
                s.reason
            ));
        }
        out.push_str(&format!(
            "total {:.4} s on {} thread(s)\n",
            self.total_seconds, self.threads
        ));
        out
    }
}

impl RunReport {
    /// A throughput table for `stagelight bench`: items, seconds, items/s and items/s per
    /// thread for every stage that ran; skipped stages with their reason.
    pub fn to_throughput_table(&self) -> String {
        let mut out = format!(
            "{:<16} {:>12} {:<10} {:>10} {:>14} {:>16} {:>12} {:>12} {:>14}\n",
            "stage",
            "items",
            "unit",
            "seconds",
            "items/s",
            "items/s/thread",
            "rays",
            "occlusion",
            "rays/s/thread"
        );
        for s in &self.stages {
            if s.ran {
                out.push_str(&format!(
                    "{:<16} {:>12} {:<10} {:>10.4} {:>14.0} {:>16.0} {:>12} {:>12} {:>14.0}\n",
                    s.stage,
                    s.items,
                    s.unit,
                    s.seconds,
                    s.items_per_second,
                    s.items_per_second_per_thread,
                    s.rays,
                    s.rays_occlusion,
                    s.rays_per_second_per_thread
                ));
            } else {
                out.push_str(&format!("{:<16} skipped: {}\n", s.stage, s.reason));
            }
        }
        out.push_str(&format!("total {:.4} s\n", self.total_seconds));
        out
    }
}

/// Runs `stages` in order over `world`, recording each in `frame.report`.
///
/// A stage whose condition says no is recorded as skipped and leaves its outputs `None`.
/// The first failing stage stops the run.
pub fn run_stages(
    stages: &[Stage],
    world: &mut World,
    frame: &mut Frame,
) -> Result<(), StageError> {
    let start = Instant::now();
    frame.report.threads = rayon::current_num_threads();
    frame.report.stages.clear();
    for stage in stages {
        let decision = (stage.condition)(world, frame);
        if !decision.run {
            frame.report.stages.push(StageReport {
                stage: stage.name,
                ran: false,
                reason: decision.reason,
                seconds: 0.0,
                items: 0,
                unit: "",
                items_per_second: 0.0,
                items_per_second_per_thread: 0.0,
                rays_closest: 0,
                rays_occlusion: 0,
                rays: 0,
                rays_per_second: 0.0,
                rays_per_second_per_thread: 0.0,
            });
            continue;
        }
        let rays_before = ray_counts(frame);
        let t0 = Instant::now();
        let work = (stage.run)(world, frame)?;
        let seconds = t0.elapsed().as_secs_f64();
        let rays = ray_counts(frame).since(rays_before);
        let threads = frame.report.threads.max(1) as f64;
        let ray_rate = if seconds > 0.0 {
            rays.total() as f64 / seconds
        } else {
            0.0
        };
        let rate = if seconds > 0.0 {
            work.items as f64 / seconds
        } else {
            0.0
        };
        frame.report.stages.push(StageReport {
            stage: stage.name,
            ran: true,
            reason: decision.reason,
            seconds,
            items: work.items,
            unit: work.unit,
            items_per_second: rate,
            items_per_second_per_thread: rate / threads,
            rays_closest: rays.closest,
            rays_occlusion: rays.occlusion,
            rays: rays.total(),
            rays_per_second: ray_rate,
            rays_per_second_per_thread: ray_rate / threads,
        });
    }
    frame.report.total_seconds = start.elapsed().as_secs_f64();
    Ok(())
}

/// Rays traced so far through the frame's accelerator (zero before `build_accel`).
fn ray_counts(frame: &Frame) -> RayCounts {
    frame
        .geometry
        .as_ref()
        .map_or(RayCounts::default(), |g| g.accel.ray_counts())
}

/// Run-condition helper: does any entity carry component `T`? Scans archetypes only.
pub fn any_with<T: hecs::Component>(world: &World) -> bool {
    world.query::<&T>().iter().next().is_some()
}

/// Run-condition helper: how many entities carry component `T`.
pub fn count_with<T: hecs::Component>(world: &World) -> usize {
    world.query::<&T>().iter().count()
}
