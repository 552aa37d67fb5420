//! The shading library: camera rays, pixel filters, light sampling and surface shaders.
//!
//! Stages call into it; it knows nothing about stages or the ECS beyond plain component data.

pub mod camera;
pub mod direct;
pub mod filter;
pub mod lights;
pub mod surface;

pub use camera::CameraRays;
pub use direct::{shade_hit, ShadeContext};
pub use filter::FilterSampler;
pub use lights::{Light, LightSample, LightSet};
