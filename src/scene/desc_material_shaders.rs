//! Scene description of a material's `shadow:` shader (mental ray's material shadow
//! shader; see `docs/scene-format.md`, "Material shadow and environment shaders").

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
