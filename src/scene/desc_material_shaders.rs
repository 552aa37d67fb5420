//! Scene description of a material's `shadow:` shader (mental ray's material shadow
//! shader) and `photon:` shader (mental ray's material photon shader, in the form AIR's
//! caustic attributes give it); see `docs/scene-format.md`, "Material shadow and
//! environment shaders" and "Material photon shaders".

use serde::{Deserialize, Serialize};

use super::desc_values::V3;

/// `shadow: …` on a material: what shadow rays keep when they cross it, whatever its
/// surface shader implies.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Shadow", deny_unknown_fields)]
pub enum ShadowDesc {
    /// Blocks all light: a black shadow (mental ray: a shadow shader returning black).
    Opaque,
    /// Lets `color` of the light through per channel, each in \[0, 1\] (mental ray
    /// `mib_shadow_transparency`).
    Transparency {
        /// Transmitted fraction per channel.
        color: V3,
    },
}

/// `photon: …` on a material: what photons do at it, whatever its surface shader implies.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Photon", deny_unknown_fields)]
pub enum PhotonShaderDesc {
    /// AIR's caustic model (`Attribute "caustic" "specularcolor"`, `"refractioncolor"`,
    /// `"refractionindex"`): photons are reflected as by a mirror with `specular`, refracted
    /// with `refraction` and index `ior`, absorbed otherwise; where the average intensities
    /// add up to less than 1 the surface stores them.
    Caustic {
        /// Reflected fraction per channel, each in \[0, 1\], default `(0, 0, 0)`.
        #[serde(default)]
        specular: V3,
        /// Refracted fraction per channel, each in \[0, 1\], default `(0, 0, 0)`.
        #[serde(default)]
        refraction: V3,
        /// Index of refraction, > 0, default 1.
        #[serde(default = "one")]
        ior: f64,
    },
}

fn one() -> f64 {
    1.0
}
