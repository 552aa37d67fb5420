//! What a diagnostic view needs from a run's settings, refused before anything runs: the
//! photon view (`--diagnostic photon:…`, `options: (diagnostic: Photon(…))`) shows the photon
//! maps, which are built only with caustics or global illumination on and the `Direct`
//! integrator; without them every pixel would be black.

use crate::diagnostic::Diagnostic;
use crate::settings::{Integrator, RenderSettings};

/// Why the diagnostic view of `settings` cannot be drawn, with a `help:` line; `None` when
/// it can (or there is none).
pub fn missing(settings: &RenderSettings) -> Option<String> {
    let Some(Diagnostic::Photon { .. }) = settings.diagnostic else {
        return None;
    };
    if !settings.photons.any() {
        return Some("the photon diagnostic shows the photon maps, but this scene builds none (caustics and global illumination are off)\n  help: turn on `caustics: (…)` or `global_illumination: (…)` in the scene's options".into());
    }
    if settings.integrator != Integrator::Direct {
        return Some("the photon diagnostic shows the photon maps, but the path integrator neither builds nor reads them\n  help: render the photon view with the Direct integrator (--integrator direct)".into());
    }
    None
}
