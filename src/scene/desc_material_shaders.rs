//! Scene description of a material's `shadow:` and `environment:` shaders (mental ray's
//! material shadow and environment shaders; see `docs/scene-format.md`, "Materials").

use serde::{Deserialize, Serialize};

use super::desc::{DepthExceededDesc, EnvironmentShaderDesc, V3};

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

/// `environment: (...)` on a material: what its specular rays see when they leave the scene
/// or exceed a trace depth, instead of the scene's environment.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "MaterialEnvironment", deny_unknown_fields)]
pub struct MaterialEnvironmentDesc {
    /// Where the radiance comes from (the scene environment's forms).
    pub shader: EnvironmentShaderDesc,
    /// Scale of the radiance, default 1, non-negative.
    #[serde(default = "one")]
    pub intensity: f64,
    /// What this material's rays beyond a reflection/refraction budget see, default
    /// `Environment` (this one).
    #[serde(default = "environment")]
    pub depth_exceeded: DepthExceededDesc,
}

fn one() -> f64 {
    1.0
}

fn environment() -> DepthExceededDesc {
    DepthExceededDesc::Environment
}
