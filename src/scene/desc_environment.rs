//! Scene description of environments: the scene's `environment: (...)` and a material's
//! `environment:` (mental ray's camera and material environment shaders; see
//! `docs/scene-format.md`, "Environment" and "Material shadow and environment shaders").

use serde::{Deserialize, Serialize};

use super::desc_values::V3;

/// `environment: (...)`: the scene's environment (mental ray's environment shader).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "Environment", deny_unknown_fields)]
pub struct EnvironmentDesc {
    /// Where the radiance comes from.
    pub shader: EnvironmentShaderDesc,
    /// Scale of the radiance, default 1, non-negative.
    #[serde(default = "default_one")]
    pub intensity: f64,
    /// Light samples per shading point (direct integrator), default 16.
    #[serde(default = "default_env_samples")]
    pub samples: u32,
    /// What rays beyond a reflection/refraction budget see, default `Environment`.
    #[serde(default = "default_depth_exceeded")]
    pub depth_exceeded: DepthExceededDesc,
}

fn default_env_samples() -> u32 {
    16
}

fn default_depth_exceeded() -> DepthExceededDesc {
    DepthExceededDesc::Environment
}

/// The environment's radiance (the scene's or a material's).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "EnvironmentShader", deny_unknown_fields)]
pub enum EnvironmentShaderDesc {
    /// The same radiance (W/(sr·m²)) from every direction.
    Constant {
        /// Linear RGB radiance.
        color: V3,
    },
    /// An equirectangular EXR radiance map, +Y up.
    LatLong {
        /// EXR file, relative to the scene file.
        file: String,
        /// Rotation about +Y, degrees, default 0.
        #[serde(default)]
        rotation: f64,
    },
}

/// What rays that exceed a trace-depth budget see.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "DepthExceeded")]
pub enum DepthExceededDesc {
    /// The environment.
    Environment,
    /// Black.
    Black,
}

/// `environment: (...)` on a material: what its specular rays see when they leave the scene
/// or exceed a trace depth, instead of the scene's environment.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(rename = "MaterialEnvironment", deny_unknown_fields)]
pub struct MaterialEnvironmentDesc {
    /// Where the radiance comes from (the scene environment's forms).
    pub shader: EnvironmentShaderDesc,
    /// Scale of the radiance, default 1, non-negative.
    #[serde(default = "default_one")]
    pub intensity: f64,
    /// What this material's rays beyond a reflection/refraction budget see, default
    /// `Environment` (this one).
    #[serde(default = "default_depth_exceeded")]
    pub depth_exceeded: DepthExceededDesc,
}

fn default_one() -> f64 {
    1.0
}
