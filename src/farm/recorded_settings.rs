//! The settings a part file records besides their hash, so that `stagelight merge` runs its
//! stages with the settings the parts ran with rather than the scene's: the switched-off
//! features (`--disable`, which decides whether the merge draws contours and how it
//! tessellates) and the integrator (`--integrator`, part of the settings a bake merge checks).
//! They are the `disable` and `integrator` entries of the part metadata (covered by its
//! checksum, like every entry).

use crate::features::Features;
use crate::settings::{Integrator, RenderSettings};

/// The recorded settings of a part run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RecordedSettings {
    /// Every switched-off feature (the scene's `options.disable` and `--disable`).
    pub disabled: Features,
    /// The integrator (the scene's `options.integrator` or `--integrator`).
    pub integrator: Integrator,
}

/// The `disable` entry of a run with nothing switched off.
const NOTHING_DISABLED: &str = "none";

impl RecordedSettings {
    /// What a run with `settings` records.
    pub fn of(settings: &RenderSettings) -> Self {
        Self {
            disabled: settings.disabled,
            integrator: settings.integrator,
        }
    }

    /// Puts the recorded settings into `settings` (the merge's, made from the scene).
    pub fn apply(self, settings: &mut RenderSettings) {
        settings.disabled = self.disabled;
        settings.integrator = self.integrator;
    }

    /// The metadata entries, in order.
    pub(super) fn entries(self) -> [(String, String); 2] {
        let disabled = if self.disabled.is_empty() {
            NOTHING_DISABLED.to_string()
        } else {
            self.disabled.to_string()
        };
        [
            ("disable".into(), disabled),
            ("integrator".into(), integrator_name(self.integrator).into()),
        ]
    }

    /// The first recorded setting in which `other` differs from these, as `(what, these,
    /// other's)`: `("integrator", "direct", "path")`, `("disabled features", "none",
    /// "lens")`; `None` when they agree.
    pub(super) fn first_difference(self, other: Self) -> Option<(&'static str, String, String)> {
        let names = ["disabled features", "integrator"];
        names
            .into_iter()
            .zip(self.entries().into_iter().zip(other.entries()))
            .find(|(_, (a, b))| a != b)
            .map(|(what, (a, b))| (what, a.1, b.1))
    }

    /// The settings recorded as the entries `disable` and `integrator`; the error is the
    /// key of the malformed entry.
    pub(super) fn parse(disable: &str, integrator: &str) -> Result<Self, &'static str> {
        let disabled = match disable {
            NOTHING_DISABLED => Features::NONE,
            list => Features::parse_list(list).map_err(|_| "disable")?,
        };
        let integrator = match integrator {
            "direct" => Integrator::Direct,
            "path" => Integrator::Path,
            _ => return Err("integrator"),
        };
        Ok(Self {
            disabled,
            integrator,
        })
    }
}

/// The `--integrator` spelling of `integrator`.
fn integrator_name(integrator: Integrator) -> &'static str {
    match integrator {
        Integrator::Direct => "direct",
        Integrator::Path => "path",
    }
}
