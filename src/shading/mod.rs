//! The shading library: camera rays and lens shaders, pixel filters, light sampling, BSDFs,
//! volume shaders and the radiance integrators.
//!
//! Stages call into it; it knows nothing about stages or the ECS beyond plain component data.

pub mod bsdf;
pub mod camera;
pub mod filter;
pub mod frame;
pub mod fresnel;
pub mod integrator;
pub mod lights;
pub mod medium;
pub mod microfacet;
pub mod mis;
pub mod photon_vertex;
pub mod shadow;
pub mod surface;
pub mod texture;
pub mod volume;

pub use bsdf::{Bsdf, BsdfSample};
pub use camera::CameraRays;
pub use filter::FilterSampler;
pub use integrator::{shade_hit, ShadeContext};
pub use lights::EnvLight;
pub use lights::{Light, LightSample, LightSet};
pub use volume::Volumes;
