//! How large expanded graphs may grow: phenomena are expanded inline at every call, so a
//! phenomenon that calls another twice doubles it, and 2 KB of text calling down 24 such
//! phenomena expanded to 2²⁵ nodes (33 s and 1 GB in `check`). Every compilation — a
//! material's program, or a phenomenon's body where it is checked — counts its nodes as it
//! expands, against [`MAX_EXPANDED_NODES`] for itself and [`MAX_SCENE_EXPANDED_NODES`] for
//! the scene's compilations together (many materials each calling a large phenomenon); a
//! call made past either is not expanded, and the call that crossed it is refused where it
//! was written.

use super::{At, Compiler};

/// The most nodes one expanded graph may have (one material's `bind` and `bump` entries
/// together, or one phenomenon's body). Real graphs have tens to hundreds of nodes; this is
/// a thousand times that, and bounds a material's program to a few MB of memory and its
/// evaluation at every shading point to well under a millisecond per sample.
pub const MAX_EXPANDED_NODES: usize = 100_000;

/// The most nodes all of a scene's compilations may expand to together: ten graphs at the
/// limit, or a thousand materials of a thousand nodes (some tens of MB).
pub const MAX_SCENE_EXPANDED_NODES: usize = 1_000_000;

/// Which limit a compilation passed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::scene) enum Limit {
    /// [`MAX_EXPANDED_NODES`].
    Graph,
    /// [`MAX_SCENE_EXPANDED_NODES`].
    Scene,
}

/// Where a compilation stands with the limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(in crate::scene) enum Size {
    /// Below both.
    #[default]
    Within,
    /// Past one; not reported yet (the crossing call was inside an expansion).
    Crossed(Limit),
    /// Past one and reported.
    Reported,
}

impl Compiler<'_, '_> {
    /// Whether the graph has passed a limit (no further call is expanded).
    pub(super) fn past_size_limit(&mut self) -> bool {
        if self.size == Size::Within {
            let own = self.prog.ops.len();
            if own > MAX_EXPANDED_NODES {
                self.size = Size::Crossed(Limit::Graph);
            } else if self.ph.expanded + own > MAX_SCENE_EXPANDED_NODES {
                self.size = Size::Crossed(Limit::Scene);
            }
        }
        self.size != Size::Within
    }

    /// Refuses the call of phenomenon `name` at `at` that took the graph past a limit, once,
    /// at the outermost call written where errors are reported (the scene's limit once per
    /// scene).
    pub(super) fn refuse_oversized_call(&mut self, at: At<'_>, name: &str) {
        let Size::Crossed(limit) = self.size else {
            return;
        };
        if !self.report {
            return;
        }
        self.size = Size::Reported;
        let message = match limit {
            Limit::Graph => format!(
                "phenomenon \"{name}\" called here makes the expanded graph larger than {MAX_EXPANDED_NODES} nodes, the limit for one graph"
            ),
            Limit::Scene if !self.ph.scene_size_reported => format!(
                "phenomenon \"{name}\" called here makes the scene's expanded graphs larger than {MAX_SCENE_EXPANDED_NODES} nodes together, the limit for one scene"
            ),
            Limit::Scene => return,
        };
        self.ph.scene_size_reported |= limit == Limit::Scene;
        self.error(
            at,
            message,
            Some(
                "every call is expanded in full: call a phenomenon once and pass its result in as a parameter to reuse it (Param(\"x\") used twice costs nothing), or nest fewer calls".into(),
            ),
        );
    }

    /// Counts this compilation's nodes into the scene's total (when it is done).
    pub(super) fn count_expanded(&mut self) {
        self.ph.expanded += self.prog.ops.len();
    }
}
