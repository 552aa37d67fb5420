//! The environment as a light: radiance lookup for rays that leave the scene, and importance
//! sampling for next-event estimation.
//!
//! A constant environment is sampled uniformly over the sphere (pdf `1/(4π)`). A lat-long map
//! is sampled from a piecewise-constant 2D distribution over its texels weighted by
//! luminance × sinθ (the solid angle of a texel row), then mapped to a direction; the
//! solid-angle pdf is `pdf_uv / (2π² sinθ)`. Radiance is constant over a texel (nearest
//! lookup), so the sampler follows the map exactly.

pub mod distribution;
pub mod footprint;

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::LightSample;
use crate::components::{DepthExceeded, Environment, EnvironmentSource, LatLongMap};
pub use distribution::{Distribution1D, Distribution2D};

/// The environment prepared for lookups and sampling.
#[derive(Debug, Clone)]
pub struct EnvLight {
    source: Source,
    /// Light samples per shading point (direct integrator).
    pub samples: u32,
    /// Rays beyond a trace-depth budget see the environment (else black).
    pub depth_exceeded_environment: bool,
}

#[derive(Debug, Clone)]
enum Source {
    Constant(Vec3),
    Map {
        map: std::sync::Arc<LatLongMap>,
        /// (cos, sin) of the rotation about +Y.
        rotation: (f32, f32),
        distribution: Distribution2D,
    },
}

/// The texel of `map` (rotated by `(cos, sin)` about +Y) seen along the unit world
/// direction `dir`.
fn map_radiance(map: &LatLongMap, rotation: (f32, f32), dir: Vec3) -> Vec3 {
    let uv = direction_to_uv(EnvLight::to_map(rotation, dir));
    if !uv.is_finite() {
        return Vec3::ZERO;
    }
    let (w, h) = (map.width as usize, map.height as usize);
    let x = ((uv.x * w as f32) as usize).min(w - 1);
    let y = ((uv.y * h as f32) as usize).min(h - 1);
    map.texels[y * w + x]
}

/// Radiance of an environment source along the world direction `dir` (any length): what a
/// material's own environment returns (it is looked up, never sampled as a light).
pub fn source_radiance(source: &EnvironmentSource, dir: Vec3) -> Vec3 {
    match source {
        EnvironmentSource::Constant(c) => *c,
        EnvironmentSource::LatLong(map) => map_radiance(
            map,
            (map.rotation.cos(), map.rotation.sin()),
            dir.normalize_or_zero(),
        ),
    }
}

/// Relative luminance of linear Rec. 709 RGB.
fn luminance(c: Vec3) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// Map coordinates `(u, v) ∈ [0, 1)²` of the unit map-space direction `d`.
pub fn direction_to_uv(d: Vec3) -> Vec2 {
    let mut u = 0.5 + d.x.atan2(-d.z) / (2.0 * PI);
    if u >= 1.0 {
        u -= 1.0;
    }
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    Vec2::new(u.clamp(0.0, 1.0), v.clamp(0.0, 1.0))
}

/// The unit map-space direction of map coordinates `(u, v)`.
pub fn uv_to_direction(uv: Vec2) -> Vec3 {
    let phi = 2.0 * PI * (uv.x - 0.5);
    let theta = PI * uv.y;
    let s = theta.sin();
    Vec3::new(s * phi.sin(), theta.cos(), -s * phi.cos())
}

impl EnvLight {
    /// Prepares `env` (builds the sampling distribution of a map).
    pub fn new(env: &Environment) -> Self {
        let source = match &env.source {
            EnvironmentSource::Constant(c) => Source::Constant(*c),
            EnvironmentSource::LatLong(map) => {
                let (w, h) = (map.width as usize, map.height as usize);
                let mut f = vec![0f32; w * h];
                for y in 0..h {
                    let sin_t = (PI * (y as f32 + 0.5) / h as f32).sin();
                    for x in 0..w {
                        f[y * w + x] = luminance(map.texels[y * w + x]).max(0.0) * sin_t;
                    }
                }
                Source::Map {
                    distribution: Distribution2D::new(&f, w, h),
                    rotation: (map.rotation.cos(), map.rotation.sin()),
                    map: map.clone(),
                }
            }
        };
        Self {
            source,
            samples: env.samples.max(1),
            depth_exceeded_environment: env.depth_exceeded == DepthExceeded::Environment,
        }
    }

    /// Bytes of the heap allocations of its sampling tables (0 for a constant environment);
    /// the map's texels are the loader's, shared.
    pub fn table_bytes(&self) -> u64 {
        match &self.source {
            Source::Constant(_) => 0,
            Source::Map { distribution, .. } => distribution.heap_bytes(),
        }
    }

    /// Whether the environment sends any light (it has something to sample).
    pub fn can_sample(&self) -> bool {
        match &self.source {
            Source::Constant(c) => c.max_element() > 0.0,
            Source::Map { distribution, .. } => distribution.integral() > 0.0,
        }
    }

    /// World direction → map direction (undo the rotation about +Y).
    fn to_map((c, s): (f32, f32), d: Vec3) -> Vec3 {
        Vec3::new(c * d.x - s * d.z, d.y, s * d.x + c * d.z)
    }

    /// Map direction → world direction.
    fn to_world((c, s): (f32, f32), d: Vec3) -> Vec3 {
        Vec3::new(c * d.x + s * d.z, d.y, -s * d.x + c * d.z)
    }

    /// Radiance arriving from the unit world direction `dir` (W/(sr·m²)).
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        match &self.source {
            Source::Constant(c) => *c,
            Source::Map { map, rotation, .. } => map_radiance(map, *rotation, dir),
        }
    }

    /// Solid-angle pdf with which [`EnvLight::sample`] picks the unit world direction `dir`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        match &self.source {
            Source::Constant(c) => {
                if c.max_element() > 0.0 {
                    1.0 / (4.0 * PI)
                } else {
                    0.0
                }
            }
            Source::Map {
                rotation,
                distribution,
                ..
            } => {
                if distribution.integral() <= 0.0 {
                    return 0.0;
                }
                let d = Self::to_map(*rotation, dir);
                let sin_t = (1.0 - d.y * d.y).max(0.0).sqrt();
                if sin_t <= 0.0 {
                    return 0.0;
                }
                let uv = direction_to_uv(d);
                if !uv.is_finite() {
                    return 0.0;
                }
                distribution.pdf(uv) / (2.0 * PI * PI * sin_t)
            }
        }
    }

    /// A direction toward the environment (shadow ray to infinity).
    pub fn sample(&self, u: Vec2) -> Option<LightSample> {
        let (wi, pdf) = match &self.source {
            Source::Constant(c) => {
                if c.max_element() <= 0.0 {
                    return None;
                }
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * u.y;
                (Vec3::new(r * phi.cos(), r * phi.sin(), z), 1.0 / (4.0 * PI))
            }
            Source::Map {
                rotation,
                distribution,
                ..
            } => {
                if distribution.integral() <= 0.0 {
                    return None;
                }
                let (uv, _) = distribution.sample(u);
                let d = Self::to_world(*rotation, uv_to_direction(uv));
                // Radiance and pdf both from the direction, so that they always describe the
                // same texel (the sampler keeps clear of texel edges, see `Distribution1D`).
                (d, self.pdf(d))
            }
        };
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let le = self.radiance(wi);
        let contribution = le / pdf;
        (pdf.is_finite() && contribution.is_finite() && le.max_element() > 0.0).then_some(
            LightSample {
                wi,
                contribution,
                target: None,
                shadows: true,
                shadow_factor: 0.0,
                pdf,
                distance: f32::INFINITY,
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_mapping_round_trips_and_centre_looks_down_minus_z() {
        assert!((uv_to_direction(Vec2::new(0.5, 0.5)) - Vec3::NEG_Z).length() < 1e-6);
        assert!((uv_to_direction(Vec2::new(0.3, 0.0)) - Vec3::Y).length() < 1e-6);
        for uv in [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.8, 0.7),
            Vec2::new(0.55, 0.95),
        ] {
            let back = direction_to_uv(uv_to_direction(uv));
            assert!((back - uv).length() < 1e-5, "{uv} → {back}");
        }
    }

    #[test]
    fn rotation_turns_the_map_about_y() {
        let mut texels = vec![Vec3::ZERO; 8 * 4];
        texels[8 + 4] = Vec3::ONE; // u ∈ [0.5, 0.625): just left of… the −Z centre column
        let map = LatLongMap {
            width: 8,
            height: 4,
            texels,
            rotation: 0.0,
        };
        let env = |rot: f32| {
            EnvLight::new(&Environment {
                source: EnvironmentSource::LatLong(std::sync::Arc::new(LatLongMap {
                    rotation: rot,
                    ..map.clone()
                })),
                samples: 1,
                depth_exceeded: DepthExceeded::Black,
            })
        };
        let d = uv_to_direction(Vec2::new(0.56, 0.4));
        assert_eq!(env(0.0).radiance(d), Vec3::ONE);
        let rot = 90f32.to_radians();
        let rotated = Vec3::new(
            rot.cos() * d.x + rot.sin() * d.z,
            d.y,
            -rot.sin() * d.x + rot.cos() * d.z,
        );
        assert_eq!(env(rot).radiance(rotated), Vec3::ONE);
        assert_eq!(env(rot).radiance(d), Vec3::ZERO);
    }
}
