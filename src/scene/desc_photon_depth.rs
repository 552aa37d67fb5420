//! Scene description of the photon trace depth: `options.photon_depth: (reflection: R,
//! refraction: T, sum: S)` (mental ray `photon trace depth R T S`; see
//! `docs/scene-format.md`, "Photon maps").

use serde::{Deserialize, Serialize};

use crate::settings::PhotonDepth;

/// `photon_depth: (...)` in `options`: most reflections, refractions and scattering events
/// in all of one photon; a field left out is not limited.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "PhotonDepth", deny_unknown_fields, default)]
pub struct PhotonDepthDesc {
    /// Most reflections (diffuse, glossy or mirror).
    pub reflection: Option<u32>,
    /// Most transmissions (refraction or pass-through).
    pub refraction: Option<u32>,
    /// Most scattering events of either kind.
    pub sum: Option<u32>,
}

impl PhotonDepthDesc {
    /// The limits (a field left out: unlimited).
    pub fn depth(&self) -> PhotonDepth {
        let or_max = |x: Option<u32>| x.unwrap_or(u32::MAX);
        PhotonDepth {
            reflection: or_max(self.reflection),
            refraction: or_max(self.refraction),
            sum: or_max(self.sum),
        }
    }
}
