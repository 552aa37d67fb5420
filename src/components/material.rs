//! Materials: which surface shader a surface uses and whether it emits light.
//!
//! Colours are linear RGB. Reflectance-like parameters are weights of BSDF lobes; when the
//! weights of a shader's lobes add up to more than 1 in a channel they are scaled down so the
//! sum is 1 (see `shading::bsdf`), so no material reflects more than it receives.

use std::sync::Arc;

use glam::Vec3;
use hecs::Entity;

use super::environment::MaterialEnvironment;
use super::graph::MaterialGraph;
use super::local_model::LocalModel;
use super::photon_shader::PhotonShader;

/// Surface shaders: the mental ray illumination models, the RenderMan standard surfaces and
/// the physically based building blocks (mirror, glass, `dgs`, opacity).
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
    /// The glTF 2.0 metallic-roughness model (GGX specular with the specification's base
    /// colour / metallic mixing; `shading::bsdf::metallic_roughness`).
    MetallicRoughness {
        /// Base colour (linear RGB, each in \[0, 1\]).
        base_color: Vec3,
        /// Metalness in \[0, 1\].
        metallic: f32,
        /// Perceptual roughness in \[0, 1\] (GGX α = roughness²).
        roughness: f32,
    },
    /// Ideal diffuse reflector: BRDF `albedo / π`.
    Lambert {
        /// Diffuse reflectance in [0, 1] per channel.
        albedo: Vec3,
    },
    /// mental ray Phong (`mi_phong_specular`): Lambert `diffuse` plus the energy-normalised
    /// Phong lobe `specular · (n+2)/(2π) · cosⁿα` about the mirror direction.
    Phong {
        /// Radiance added by the direct-lighting integrator (mental ray's ambient term).
        ambient: Vec3,
        /// Diffuse reflectance.
        diffuse: Vec3,
        /// Specular weight.
        specular: Vec3,
        /// Phong exponent `n` (`spec_exp`).
        spec_exp: f32,
    },
    /// mental ray Blinn (`mi_blinn_specular`): Cook–Torrance with one index of refraction.
    Blinn {
        /// Radiance added by the direct-lighting integrator.
        ambient: Vec3,
        /// Diffuse reflectance.
        diffuse: Vec3,
        /// Specular weight.
        specular: Vec3,
        /// RMS slope of the microfacets (Beckmann).
        roughness: f32,
        /// Relative index of refraction of the Fresnel term.
        ior: f32,
    },
    /// mental ray Cook–Torrance (`mi_cooktorr_specular`): Beckmann microfacets, V-cavity
    /// masking, dielectric Fresnel with one index per colour channel.
    CookTorrance {
        /// Radiance added by the direct-lighting integrator.
        ambient: Vec3,
        /// Diffuse reflectance.
        diffuse: Vec3,
        /// Specular weight.
        specular: Vec3,
        /// RMS slope of the microfacets (Beckmann).
        roughness: f32,
        /// Relative index of refraction per channel.
        ior: Vec3,
    },
    /// Softimage "blong" (`mi_blong_specular`): Blinn's half-vector microfacet form with a
    /// Phong exponent (normalised Blinn–Phong distribution), no Fresnel term.
    Blong {
        /// Radiance added by the direct-lighting integrator.
        ambient: Vec3,
        /// Diffuse reflectance.
        diffuse: Vec3,
        /// Specular weight.
        specular: Vec3,
        /// Blinn–Phong exponent.
        spec_exp: f32,
    },
    /// Fresnel-weighted specular (`mi_fresnel_specular`): Blinn–Phong microfacet lobe
    /// weighted by the dielectric Fresnel reflectance of `ior_in / ior_out`.
    FresnelSpecular {
        /// Radiance added by the direct-lighting integrator.
        ambient: Vec3,
        /// Diffuse reflectance.
        diffuse: Vec3,
        /// Specular weight.
        specular: Vec3,
        /// Blinn–Phong exponent.
        spec_exp: f32,
        /// Index of refraction inside the surface.
        ior_in: f32,
        /// Index of refraction outside the surface.
        ior_out: f32,
    },
    /// RenderMan `matte`: `Kd · color` diffuse.
    Matte {
        /// Ambient weight (no effect in this physically based stand-in; `Local` uses it).
        ka: f32,
        /// Diffuse weight.
        kd: f32,
        /// Surface colour.
        color: Vec3,
    },
    /// RenderMan `plastic`: `Kd · color` diffuse plus `Ks · specularcolor` Blinn–Phong
    /// highlight of exponent `1/roughness`.
    Plastic {
        /// Ambient weight (no effect in this physically based stand-in; `Local` uses it).
        ka: f32,
        /// Diffuse weight.
        kd: f32,
        /// Specular weight.
        ks: f32,
        /// RenderMan roughness; the highlight exponent is `1/roughness`.
        roughness: f32,
        /// Colour of the highlight.
        specular_color: Vec3,
        /// Surface colour.
        color: Vec3,
    },
    /// RenderMan `metal`: `Ks · color` Blinn–Phong highlight of exponent `1/roughness`.
    Metal {
        /// Ambient weight (no effect in this physically based stand-in; `Local` uses it).
        ka: f32,
        /// Specular weight.
        ks: f32,
        /// RenderMan roughness.
        roughness: f32,
        /// Surface colour.
        color: Vec3,
    },
    /// RenderMan `shinymetal`: `metal` plus `Kr · color` times the reflection-map lookup.
    /// Until environment maps exist a traced perfect-mirror reflection of the scene stands in
    /// for the map.
    ShinyMetal {
        /// Ambient weight (no effect in this physically based stand-in; `Local` uses it).
        ka: f32,
        /// Specular weight.
        ks: f32,
        /// Mirror-reflection weight.
        kr: f32,
        /// RenderMan roughness.
        roughness: f32,
        /// Surface colour.
        color: Vec3,
    },
    /// RenderMan `paintedplastic`: `plastic` with `color` multiplied by a texture. The texture
    /// is a binding of `color` (e.g. `Mul(colour, Image(…))`, see `Material::graph`); without
    /// one it is white and the shader equals `plastic`.
    PaintedPlastic {
        /// Ambient weight (no effect in this physically based stand-in; `Local` uses it).
        ka: f32,
        /// Diffuse weight.
        kd: f32,
        /// Specular weight.
        ks: f32,
        /// RenderMan roughness.
        roughness: f32,
        /// Colour of the highlight.
        specular_color: Vec3,
        /// Surface colour.
        color: Vec3,
    },
    /// Perfect mirror reflecting `color`.
    Mirror {
        /// Reflectance per channel.
        color: Vec3,
    },
    /// Smooth dielectric (mental ray `dielectric_material`): Fresnel reflection and
    /// refraction, total internal reflection, absorption inside. Always two-sided: the back
    /// face is the inside.
    Dielectric {
        /// Index of refraction inside.
        ior: f32,
        /// Index of refraction outside.
        ior_out: f32,
        /// Transmittance per unit length inside (`col`): a path of length `d` inside keeps
        /// `col^d` of its energy.
        col: Vec3,
    },
    /// mental ray `dgs_material`: diffuse + glossy (Blinn–Phong exponent `shiny`) + perfect
    /// specular reflection.
    Dgs {
        /// Diffuse reflectance.
        diffuse: Vec3,
        /// Glossy reflectance.
        glossy: Vec3,
        /// Perfect-mirror reflectance.
        specular: Vec3,
        /// Glossy exponent.
        shiny: f32,
    },
    /// A local illumination model evaluated as its specification writes it (RenderMan's
    /// standard surfaces as RIB scenes use them): ambient terms and `Cl`-weighted sums over
    /// the lights, no energy normalisation; a traced mirror term. See [`LocalModel`].
    Local(LocalModel),
    /// mental ray `mib_opacity`: `opacity · input + (1 − opacity) · what lies behind`.
    /// Always two-sided.
    Opacity {
        /// Opacity per channel in [0, 1].
        opacity: Vec3,
        /// The shader blended over what lies behind.
        input: Box<Shader>,
    },
}

impl Shader {
    /// Whether both faces are shaded whatever the material's `two_sided` says (glass has an
    /// inside, a partly transparent sheet is seen from both sides).
    pub fn forces_two_sided(&self) -> bool {
        matches!(self, Shader::Dielectric { .. } | Shader::Opacity { .. })
    }

    /// Radiance the direct-lighting integrator adds as mental ray's ambient term.
    pub fn ambient(&self) -> Vec3 {
        match self {
            Shader::Phong { ambient, .. }
            | Shader::Blinn { ambient, .. }
            | Shader::CookTorrance { ambient, .. }
            | Shader::Blong { ambient, .. }
            | Shader::FresnelSpecular { ambient, .. } => *ambient,
            Shader::Opacity { opacity, input } => *opacity * input.ambient(),
            _ => Vec3::ZERO,
        }
    }
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
    /// Shader parameters driven by texture nodes and the bump map (`None`: the shader's
    /// constants everywhere, no bump).
    pub graph: Option<Arc<MaterialGraph>>,
    /// Light list (mental ray's `"lights"`): indices of the only scene emitters (in entity
    /// order, as the light set lists them) that light this material; `None`: every light.
    pub lights: Option<Arc<[u32]>>,
    /// Shadow shader (mental ray's material `shadow`): the fraction of light per channel a
    /// shadow ray keeps when it crosses this material, overriding what the surface shader
    /// implies (`shading::shadow`); zero blocks. `None`: follow the surface shader.
    pub shadow: Option<Vec3>,
    /// Material environment (mental ray's material `environment`): what specular rays
    /// spawned at this material see when they leave the scene or exceed a trace depth,
    /// instead of the scene's environment. `None`: the scene's.
    pub environment: Option<Arc<MaterialEnvironment>>,
    /// Photon shader (mental ray's material `photon`; AIR's caustic attributes): what
    /// photons do here instead of what the surface shader implies. `None`: follow the
    /// surface shader.
    pub photon: Option<PhotonShader>,
}

impl Default for Material {
    /// The built-in default: RenderMan's `defaultsurface` (ka 0.2, kd 0.8, white), one-sided,
    /// not emitting, no graph, every light, shadows and environment as the scene has them.
    fn default() -> Self {
        Self {
            shader: Shader::DefaultSurface {
                ka: 0.2,
                kd: 0.8,
                color: Vec3::ONE,
            },
            two_sided: false,
            emission: Vec3::ZERO,
            graph: None,
            lights: None,
            shadow: None,
            environment: None,
            photon: None,
        }
    }
}

impl Material {
    /// Whether the light at index `i` of the light set lights this material.
    pub fn sees_light(&self, i: usize) -> bool {
        self.lights
            .as_ref()
            .is_none_or(|l| l.iter().any(|&j| j as usize == i))
    }

    /// Whether the material emits light.
    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// Whether the back face is shaded (the `two_sided` flag or a shader that needs it).
    pub fn shades_back(&self) -> bool {
        self.two_sided || self.shader.forces_two_sided()
    }
}

/// The material an instance is shaded with (a material entity).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MaterialRef(pub Entity);
