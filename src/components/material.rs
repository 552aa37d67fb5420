//! Materials: which surface shader a surface uses and whether it emits light.

use glam::Vec3;
use hecs::Entity;

/// Surface shaders of scene format v1.
#[derive(Debug, Clone, PartialEq)]
pub enum Shader {
    /// Flat colour, independent of lights (mental ray / RenderMan `constant`).
    Constant {
        /// Output colour (linear RGB).
        color: Vec3,
    },
    /// RenderMan's `defaultsurface`: `color · (Ka + Kd·|N·I|)`; needs no lights.
    DefaultSurface {
        /// Ambient weight.
        ka: f32,
        /// Diffuse weight of the view-facing term.
        kd: f32,
        /// Surface colour (linear RGB).
        color: Vec3,
    },
    /// Ideal diffuse reflector: BRDF `albedo / π`.
    Lambert {
        /// Diffuse reflectance in [0, 1] per channel.
        albedo: Vec3,
    },
}

/// A material entity's data.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// The surface shader.
    pub shader: Shader,
    /// Two-sided surfaces shade both faces; one-sided ones are black seen from the back
    /// (and emit only from the front).
    pub two_sided: bool,
    /// Emitted radiance in W/(sr·m²) per RGB channel; zero for non-emitters.
    pub emission: Vec3,
}

impl Material {
    /// Whether the material emits light.
    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }
}

/// The material an instance is shaded with (a material entity).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MaterialRef(pub Entity);
