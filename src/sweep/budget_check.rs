//! The memory budget of a sweep, checked before its first run: every setting the sweep will
//! run — each knob value, and the reference when it is rendered — is loaded and configured as
//! its run will be and estimated as `render` estimates a scene ([`crate::budget::estimate`]).
//! A setting that would not fit refuses the whole sweep up front, so nothing is half-swept
//! and nothing is written. (Adaptive tessellation is known only once diced: the tessellator
//! refuses it in the run, under the same budget.)

use std::path::Path;

use hecs::World;

use crate::budget::Budget;
use crate::scene::{load_scene_within, Diagnostic, SceneErrors};
use crate::settings::RenderSettings;
use crate::tasks::Tasks;

/// Configures a freshly loaded scene as one run of the sweep will.
pub type Configure<'a> = &'a dyn Fn(&mut World, &mut RenderSettings);

/// The runs of a sweep, as the budget sees them.
pub struct Runs<'a> {
    /// The scene file.
    pub scene: &'a Path,
    /// Render or bake.
    pub tasks: Tasks,
    /// The budget every run has.
    pub budget: &'a Budget,
    /// The reference run's configuration (its knob setting the most accurate one for a knob
    /// whose accuracy is a setting: `reference_setting`).
    pub reference: Configure<'a>,
    /// The reference's configuration with the scene's own knob setting: what the scene
    /// itself refuses.
    pub own: Configure<'a>,
    /// Whether the reference is rendered (not given with `--reference`, not cached).
    pub reference_runs: bool,
    /// Each knob value as `NAME=VALUE`, with its configuration.
    pub values: Vec<(String, Configure<'a>)>,
}

/// The refusals of the sweep's runs, in run order (reference, then the values). A refusal
/// the scene's own setting has too is shown once, as `render` shows it; one that only a
/// knob value brings names the value.
pub fn refusals(runs: &Runs<'_>) -> Result<Vec<Diagnostic>, SceneErrors> {
    let own = estimate(runs, runs.own)?;
    let values = runs
        .values
        .iter()
        .map(|(value, configure)| Ok((value, estimate(runs, *configure)?)))
        .collect::<Result<Vec<_>, SceneErrors>>()?;
    let mut shown: Vec<Diagnostic> = Vec::new();
    if runs.reference_runs {
        for d in estimate(runs, runs.reference)? {
            // A reference at a knob value's setting is refused with that value, below.
            if own.contains(&d) {
                shown.push(d);
            } else if !values.iter().any(|(_, refused)| refused.contains(&d)) {
                shown.push(Diagnostic {
                    message: format!("the reference, {}", d.message),
                    ..d
                });
            }
        }
    }
    for (value, refused) in values {
        for d in refused {
            if own.contains(&d) {
                if !shown.contains(&d) {
                    shown.push(d);
                }
                continue;
            }
            shown.push(Diagnostic {
                message: format!("with --knob {value}, {}", d.message),
                help: Some(format!(
                    "leave {value} out of the sweep; or {}",
                    d.help
                        .as_deref()
                        .unwrap_or("raise the budget with --memory-limit BYTES")
                )),
                ..d
            });
        }
    }
    Ok(shown)
}

/// One configuration's refusals under the budget, located as `render` locates them.
fn estimate(runs: &Runs<'_>, configure: Configure<'_>) -> Result<Vec<Diagnostic>, SceneErrors> {
    let mut scene = load_scene_within(runs.scene, runs.budget)?;
    let mut settings = scene.settings.clone();
    configure(&mut scene.world, &mut settings);
    let refused = crate::budget::estimate::check(&scene.world, &settings, runs.tasks, runs.budget);
    Ok(crate::guard::locate::options_located(runs.scene, refused))
}
