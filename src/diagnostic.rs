//! Diagnostic modes (mental ray's `diagnostic samples on`; RON `options.diagnostic`; CLI
//! `render --diagnostic samples`): the beauty pass replaced by a false-colour view of how
//! the renderer worked, for tuning a scene's options.

use glam::Vec3;

/// One diagnostic view.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Diagnostic {
    /// Samples per pixel: grey level `samples taken / most samples a pixel may take`, so
    /// where adaptive sampling refined shows bright (uniform sampling: every pixel 1).
    Samples,
}

impl Diagnostic {
    /// Parses a diagnostic's command-line name (`samples`).
    pub fn parse(text: &str) -> Result<Self, String> {
        match text.trim() {
            "samples" => Ok(Self::Samples),
            other => Err(format!("unknown diagnostic \"{other}\" (expected samples)")),
        }
    }

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Samples => "samples",
        }
    }
}

/// The samples view of per-pixel sample counts: `taken / max` in every channel (`max` ≥ 1).
pub fn samples_view(samples: &[u32], max: u32) -> Vec<Vec3> {
    let max = max.max(1) as f32;
    samples
        .iter()
        .map(|&n| Vec3::splat(n as f32 / max))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_scaled_to_the_most_a_pixel_may_take() {
        assert_eq!(
            samples_view(&[4, 16, 8], 16),
            [Vec3::splat(0.25), Vec3::ONE, Vec3::splat(0.5)]
        );
        assert_eq!(Diagnostic::parse("samples"), Ok(Diagnostic::Samples));
        assert_eq!(
            Diagnostic::parse("grid").unwrap_err(),
            "unknown diagnostic \"grid\" (expected samples)"
        );
    }
}
