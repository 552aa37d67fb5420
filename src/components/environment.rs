//! The scene's environment (mental ray's camera environment shader): the radiance of rays
//! that leave the scene, which is also a light source.

use std::sync::Arc;

use glam::Vec3;

/// What rays that exceed a trace-depth budget return (the seed's environment shader is
/// called "when a ray leaves the scene, or when a ray exceeds the trace depth").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthExceeded {
    /// The environment along the ray's direction.
    Environment,
    /// Black.
    Black,
}

/// An equirectangular (latitude–longitude) radiance map, +Y up.
///
/// Texel `(x, y)` (row 0 at the top) covers `u ∈ [x/W, (x+1)/W)`, `v ∈ [y/H, (y+1)/H)`, where
/// a direction `d` (after undoing `rotation`) has `u = ½ + atan2(d.x, −d.z)/(2π)` and
/// `v = acos(d.y)/π`: the map's centre is seen looking down −Z, its top row is straight up.
/// Radiance is constant over a texel (nearest lookup), so importance sampling is exact.
#[derive(Debug, Clone, PartialEq)]
pub struct LatLongMap {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Radiance per texel, W/(sr·m²), row-major from the top row; finite and ≥ 0.
    pub texels: Vec<Vec3>,
    /// Rotation of the map about +Y, radians (counter-clockwise seen from above).
    pub rotation: f32,
}

/// Where the environment's radiance comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum EnvironmentSource {
    /// The same radiance from every direction, W/(sr·m²).
    Constant(Vec3),
    /// A lat-long map (shared: maps can be large).
    LatLong(Arc<LatLongMap>),
}

/// The scene's environment entity.
#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    /// Radiance source (intensity already applied).
    pub source: EnvironmentSource,
    /// Light samples per shading point for the direct integrator.
    pub samples: u32,
    /// What rays beyond a reflection/refraction budget see.
    pub depth_exceeded: DepthExceeded,
}

/// A material's own environment (mental ray's material `environment` shader): what the
/// specular rays spawned at that material see when they leave the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialEnvironment {
    /// Radiance source (intensity already applied).
    pub source: EnvironmentSource,
    /// What the material's rays beyond a reflection/refraction budget see.
    pub depth_exceeded: DepthExceeded,
}
