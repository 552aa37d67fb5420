//! `stagelight sweep`: what accuracy costs in time. Renders (or bakes) a scene once per value
//! of one accuracy knob and per seed, times every stage, compares each result with a
//! converged reference, and writes a CSV/JSON table and a log–log plot of relMSE against
//! seconds (of a crop, e.g. a caustic, with `--crop`).
//!
//! The driver takes the pipeline as a function (`main.rs` passes the stage table), so this
//! module does not depend on `systems/`.

pub mod bake_reference;
pub mod budget_check;
pub mod crop;
pub mod integrator_check;
pub mod knob;
pub mod leftovers;
pub mod metrics;
pub mod photon_knobs;
pub mod plot;
pub mod reference_file;
pub mod reference_setting;
pub mod report;
pub mod runner;

pub use crop::Crop;
pub use knob::{Knob, KnobError};
pub use leftovers::SweepFiles;
pub use metrics::{compare, ErrorMetrics};
pub use report::{SweepRow, SweepSummary};
pub use runner::{run_sweep, Pipeline, SweepError, SweepOptions};
