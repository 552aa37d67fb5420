//! What a diagnostic view needs from a run's settings, refused before anything runs: the
//! photon view (`--diagnostic photon:…`, `options: (diagnostic: Photon(…))`) shows the photon
//! maps, which are built only with caustics or global illumination on and the `Direct`
//! integrator; without them every pixel would be black. The loader refuses a scene whose own
//! options ask for such a view (located, help in the scene's syntax); the CLI refuses one its
//! flags make ([`missing`]).

use crate::diagnostic::Diagnostic;
use crate::settings::{Integrator, RenderSettings};

/// Why a photon view cannot be drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unmet {
    /// Caustics and global illumination are off: no photon map is built.
    NoPhotonMaps,
    /// The path integrator neither builds nor reads the photon maps.
    PathIntegrator,
}

impl Unmet {
    /// What is wrong, as an error message.
    pub fn reason(self) -> &'static str {
        match self {
            Self::NoPhotonMaps => "the photon diagnostic shows the photon maps, but this scene builds none (caustics and global illumination are off)",
            Self::PathIntegrator => "the photon diagnostic shows the photon maps, but the path integrator neither builds nor reads them",
        }
    }
}

/// Why the diagnostic view of `settings` cannot be drawn; `None` when it can (or there is
/// none).
pub fn unmet(settings: &RenderSettings) -> Option<Unmet> {
    let Some(Diagnostic::Photon { .. }) = settings.diagnostic else {
        return None;
    };
    if !settings.photons.any() {
        return Some(Unmet::NoPhotonMaps);
    }
    if settings.integrator != Integrator::Direct {
        return Some(Unmet::PathIntegrator);
    }
    None
}

/// Why the diagnostic view of `settings` cannot be drawn, with a `help:` line; `None` when
/// it can (or there is none). `no_maps_help` is what turns a photon map on in the scene's
/// format (`crate::format_helps::photon_maps_help`).
pub fn missing(settings: &RenderSettings, no_maps_help: &str) -> Option<String> {
    let unmet = unmet(settings)?;
    let help = match unmet {
        Unmet::NoPhotonMaps => no_maps_help,
        Unmet::PathIntegrator => {
            "render the photon view with the Direct integrator (--integrator direct)"
        }
    };
    Some(format!("{}\n  help: {help}", unmet.reason()))
}
