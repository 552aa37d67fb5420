//! The stage runner: the `Stage` type with its run condition and declared data, the runner
//! that stores each stage's output in its slot and records the report, and the plan that
//! evaluates the same run conditions without running anything (`stagelight plan`).

use std::path::PathBuf;
use std::time::Instant;

use hecs::World;
use serde::Serialize;

use crate::accel::RayCounts;
use crate::frame::{Frame, Slot, StageOutput};
use crate::image_io::{commit_all, PendingFile};
use crate::report::StageReport;
pub use crate::stage_error::StageError;

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

/// What a stage did: work items for throughput figures, the files it produced (encoded, not
/// yet written: the runner commits every stage's files together at the end of the run), and
/// its typed output (stored by the runner in the stage's declared slot).
pub struct Work {
    /// Items processed.
    pub items: u64,
    /// What an item is (`"triangles"`, `"samples"`, `"files"`, …).
    pub unit: &'static str,
    /// Destinations of the files the stage produced, in order.
    pub files: Vec<PathBuf>,
    /// The encoded files, committed by the runner with every other stage's (all or nothing).
    pub pending: Vec<PendingFile>,
    /// The stage's output, if it has a slot.
    pub output: Option<StageOutput>,
    /// Set when the stage found its output ready (a photon map file whose hash matches)
    /// instead of computing it: the report lists the stage as skipped for this reason,
    /// while its output is stored as usual.
    pub reused: Option<String>,
    /// Set when the items were done by the parts a merge reads, in their own runs: the
    /// report gives no rate for them (`n/a`), only the merge's own time.
    pub merged_parts: bool,
}

impl Work {
    /// `items` of `unit`, no files, no output.
    pub fn new(items: u64, unit: &'static str) -> Self {
        Self {
            items,
            unit,
            files: Vec::new(),
            pending: Vec::new(),
            output: None,
            reused: None,
            merged_parts: false,
        }
    }

    /// The same work, its items done by the merged parts in their own runs (no rate).
    pub fn by_merged_parts(mut self) -> Self {
        self.merged_parts = true;
        self
    }

    /// The same work, reported as skipped because its output was reused (`reason`).
    pub fn reused(mut self, reason: impl Into<String>) -> Self {
        self.reused = Some(reason.into());
        self
    }

    /// The same work with the stage's output.
    pub fn with_output(mut self, output: StageOutput) -> Self {
        self.output = Some(output);
        self
    }

    /// The same work with the files the stage produced, for the runner to commit.
    pub fn with_pending(mut self, pending: Vec<PendingFile>) -> Self {
        self.files = pending.iter().map(|f| f.path.clone()).collect();
        self.pending = pending;
        self
    }
}

/// A run condition: a cheap, pure query over the world and the frame. It asks whether
/// earlier outputs exist through `frame.outputs.has(slot)`, so the same condition answers
/// for a real run and for a plan.
pub type RunCondition = fn(&World, &Frame) -> Decision;

/// A stage body. Only the geometry stages may edit the world; the others see it read-only.
/// Both see the frame read-only and return their output in [`Work`].
#[derive(Clone, Copy)]
pub enum StageBody {
    /// A geometry stage: turns components into meshes (structural world edits).
    EditsWorld(fn(&mut World, &Frame) -> Result<Work, StageError>),
    /// Every other stage.
    ReadsWorld(fn(&World, &Frame) -> Result<Work, StageError>),
}

/// One entry of the stage table.
#[derive(Clone, Copy)]
pub struct Stage {
    /// Reported name (equal to the module name in `systems/`).
    pub name: &'static str,
    /// When the stage runs, in words (the documentation table is generated from this).
    pub runs_when: &'static str,
    /// What it reads, in words.
    pub reads: &'static str,
    /// What it writes, in words.
    pub writes: &'static str,
    /// The output slot it fills, if any (the runner refuses any other).
    pub slot: Option<Slot>,
    /// When the stage runs.
    pub condition: RunCondition,
    /// What it does.
    pub body: StageBody,
}

impl Stage {
    /// Runs the stage body once, outside the runner (benchmarks and tests): its output is
    /// returned in the [`Work`], not stored.
    pub fn run_body(&self, world: &mut World, frame: &Frame) -> Result<Work, StageError> {
        match self.body {
            StageBody::EditsWorld(body) => body(world, frame),
            StageBody::ReadsWorld(body) => body(world, frame),
        }
    }
}

/// The markdown table of a stage list (order, name, runs when, reads, writes): the
/// documentation in `systems/mod.rs` and `ARCHITECTURE.md` is checked against it.
pub fn stage_table_markdown(stages: &[Stage]) -> String {
    let mut out = String::from(
        "| order | stage | runs when | reads | writes |\n| --- | --- | --- | --- | --- |\n",
    );
    for (i, s) in stages.iter().enumerate() {
        out.push_str(&format!(
            "| {} | `{}` | {} | {} | {} |\n",
            i + 1,
            s.name,
            s.runs_when,
            s.reads,
            s.writes
        ));
    }
    out
}

/// What a plan says of one stage.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct PlannedStage {
    /// Stage name.
    pub stage: &'static str,
    /// Whether it would run.
    pub run: bool,
    /// The reason its run condition gives.
    pub reason: String,
}

/// Evaluates every stage's run condition in order without running any stage: a stage that
/// would run promises its slot to the conditions after it. The geometry stages' conditions
/// count pending geometry (procedural objects, surfaces) so later stages plan as they run.
pub fn plan(stages: &[Stage], world: &World, frame: &mut Frame) -> Vec<PlannedStage> {
    stages
        .iter()
        .map(|stage| {
            let d = (stage.condition)(world, frame);
            if d.run {
                if let Some(slot) = stage.slot {
                    frame.outputs.promise(slot);
                }
            }
            PlannedStage {
                stage: stage.name,
                run: d.run,
                reason: d.reason,
            }
        })
        .collect()
}

/// Runs `stages` in order over `world`, recording each in `frame.report`.
///
/// A stage whose condition says no is recorded as skipped and leaves its outputs `None`.
/// The runner alone stores stage outputs (in the slot the stage declares) and collects the
/// files the stages produced. The first failing stage stops the run, and nothing is written.
/// After the last stage every file is committed together ([`commit_all`]: all or nothing),
/// unless `frame.inputs.hold_files` asks to leave them in `frame.held_files` for the caller
/// to commit with its own (the CLI's `--stats-json`).
pub fn run_stages(
    stages: &[Stage],
    world: &mut World,
    frame: &mut Frame,
) -> Result<(), StageError> {
    let start = Instant::now();
    frame.report.threads = rayon::current_num_threads();
    frame.report.stages.clear();
    frame.report.written.clear();
    frame.held_files.clear();
    let mut pending: Vec<PendingFile> = Vec::new();
    for stage in stages {
        let decision = (stage.condition)(world, frame);
        if !decision.run {
            frame
                .report
                .stages
                .push(StageReport::skipped(stage.name, decision.reason));
            continue;
        }
        let rays_before = ray_counts(frame);
        let cpu_before = crate::cpu_time::process_cpu_seconds();
        let t0 = Instant::now();
        let mut work = stage.run_body(world, frame)?;
        pending.append(&mut work.pending);
        let seconds = t0.elapsed().as_secs_f64();
        let cpu_seconds = match (cpu_before, crate::cpu_time::process_cpu_seconds()) {
            (Some(a), Some(b)) => (b - a).max(0.0),
            _ => 0.0,
        };
        if let Some(output) = work.output {
            if Some(output.slot()) != stage.slot {
                return Err(StageError::Internal(format!(
                    "stage {} returned a {:?} output but declares {:?}",
                    stage.name,
                    output.slot(),
                    stage.slot
                )));
            }
            frame.outputs.store(output);
        }
        if let Some(reason) = work.reused {
            let mut report = StageReport::skipped(stage.name, reason);
            report.seconds = seconds;
            report.files = work.files;
            frame.report.written.extend(report.files.iter().cloned());
            frame.report.stages.push(report);
            continue;
        }
        let rays = ray_counts(frame).since(rays_before);
        let threads = frame.report.threads.max(1) as f64;
        let per_second = |n: u64| {
            if seconds > 0.0 {
                n as f64 / seconds
            } else {
                0.0
            }
        };
        // Items the merged parts did in their own runs have no rate here.
        let items_rate = if work.merged_parts { 0 } else { work.items };
        let rate = per_second(items_rate);
        let ray_rate = per_second(rays.total());
        let per_cpu_second = |n: u64| {
            if cpu_seconds > 0.0 {
                n as f64 / cpu_seconds
            } else {
                0.0
            }
        };
        frame.report.written.extend(work.files.iter().cloned());
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
            cpu_seconds,
            items_per_cpu_second: per_cpu_second(items_rate),
            rays_per_cpu_second: per_cpu_second(rays.total()),
            files: work.files,
            merged_parts: work.merged_parts,
        });
    }
    if frame.cancelled() {
        return Err(StageError::Interrupted);
    }
    if frame.inputs.hold_files {
        frame.held_files = pending;
    } else if !pending.is_empty() {
        commit_all(&pending).map_err(|(path, e)| StageError::Write {
            path,
            message: crate::scene::include::io_reason(&e),
        })?;
    }
    frame.report.total_seconds = start.elapsed().as_secs_f64();
    Ok(())
}

/// Rays traced so far through the frame's accelerator (zero before `build_accel`).
fn ray_counts(frame: &Frame) -> RayCounts {
    frame
        .outputs
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
