//! What a diagnostic view needs from a run's settings, refused before anything runs: the
//! photon view (`--diagnostic photon:…`, `options: (diagnostic: Photon(…))`) shows the photon
//! maps, which are built only with caustics or global illumination on and the `Direct`
//! integrator; without them every pixel would be black. The loader refuses a scene whose own
//! options ask for such a view (located, help in the scene's syntax); the CLI refuses one its
//! flags make ([`missing`]).

use std::path::Path;

use crate::diagnostic::Diagnostic;
use crate::scene::syntax::{convert_command, Helps, Syntax};
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

/// Why the diagnostic view of `settings` cannot be drawn, with a `help:` line written in
/// the `syntax` of the scene file `scene`; `None` when it can (or there is none).
pub fn missing(settings: &RenderSettings, syntax: Syntax, scene: &Path) -> Option<String> {
    let unmet = unmet(settings)?;
    let help = match unmet {
        Unmet::NoPhotonMaps => photon_maps_help(syntax, scene),
        Unmet::PathIntegrator => {
            "render the photon view with the Direct integrator (--integrator direct)".into()
        }
    };
    Some(format!("{}\n  help: {help}", unmet.reason()))
}

/// How the scene file `scene`, written in `syntax`, turns a photon map on: RON's
/// `caustics:`/`global_illumination:` options, `.mi`'s `caustic on`/`globillum on`, RIB's
/// AIR caustic light; a glTF file has none, so its help converts the scene to RON.
pub fn photon_maps_help(syntax: Syntax, scene: &Path) -> String {
    let ron = "turn on `caustics: (…)` or `global_illumination: (…)` in the scene's options";
    syntax.help_each(Helps {
        ron,
        mi: "add `caustic on` or `globillum on` to the options block",
        rib: "add AIR's caustic light, `LightSource \"caustic\" 1`, which turns the caustic photon map on",
        gltf: &format!(
            "glTF has no photon maps: write the scene as RON (`{}`) and {ron} there",
            convert_command(scene)
        ),
    })
}
