//! Light emitters: point, spot, directional, the four area-light shapes of mental ray
//! (rectangle, disc, sphere, cylinder), and ambient light (RenderMan's `ambientlight`).

use glam::Vec3;

/// The geometry of a light and its shape-specific parameters (world space).
#[derive(Debug, Clone, PartialEq)]
pub enum LightShape {
    /// Isotropic point light; `Emitter::radiant` is intensity in W/sr.
    Point {
        /// Position.
        position: Vec3,
    },
    /// RenderMan-style spotlight; `Emitter::radiant` is on-axis intensity in W/sr.
    Spot {
        /// Position.
        position: Vec3,
        /// Unit axis direction (where the light points).
        direction: Vec3,
        /// Half-angle of the cone, radians.
        cone_angle: f32,
        /// Width of the penumbra inside the cone edge, radians (`conedeltaangle`).
        penumbra: f32,
        /// Exponent of `cos` falloff from the axis (`beamdistribution`).
        beam_distribution: f32,
    },
    /// Ambient light (RenderMan `ambientlight`): no position or direction. `Emitter::radiant`
    /// is the `Cl` it adds to the ambient term of local illumination models
    /// ([`crate::components::LocalModel`]); physically based shaders do not see it.
    Ambient,
    /// Distant light; `Emitter::radiant` is irradiance in W/m² on a surface facing it.
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
    },
    /// One-sided parallelogram emitting along `edge_u × edge_v`; `Emitter::radiant` is
    /// radiance in W/(sr·m²).
    Rect {
        /// One corner.
        corner: Vec3,
        /// First edge vector from `corner`.
        edge_u: Vec3,
        /// Second edge vector from `corner`.
        edge_v: Vec3,
    },
    /// One-sided disc emitting along `normal`; `Emitter::radiant` is radiance in W/(sr·m²).
    Disc {
        /// Centre.
        center: Vec3,
        /// Unit normal (the emitting side).
        normal: Vec3,
        /// Radius (> 0).
        radius: f32,
    },
    /// Sphere emitting outward; `Emitter::radiant` is radiance in W/(sr·m²).
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius (> 0).
        radius: f32,
    },
    /// Open tube (no caps) from `start` to `end` emitting outward; `Emitter::radiant` is
    /// radiance in W/(sr·m²).
    Cylinder {
        /// Centre of one end.
        start: Vec3,
        /// Centre of the other end (differs from `start`).
        end: Vec3,
        /// Radius (> 0).
        radius: f32,
    },
}

impl LightShape {
    /// Whether the shape has an area (the emitted quantity is radiance, rays can meet it).
    pub fn is_area(&self) -> bool {
        matches!(
            self,
            LightShape::Rect { .. }
                | LightShape::Disc { .. }
                | LightShape::Sphere { .. }
                | LightShape::Cylinder { .. }
        )
    }
}

/// A light entity's data.
#[derive(Debug, Clone, PartialEq)]
pub struct Emitter {
    /// Shape and placement.
    pub shape: LightShape,
    /// Colour × intensity, in the unit the shape states (W/sr, W/m² or W/(sr·m²)).
    pub radiant: Vec3,
    /// Whether shadow rays are traced toward this light.
    pub shadows: bool,
    /// The fraction of the light that passes occluders, in [0, 1] (mental ray's light
    /// `factor`; 0: full shadows, 1: none).
    pub shadow_factor: f32,
    /// Samples per shading point for area lights (1 for delta lights).
    pub samples: u32,
    /// Area lights only: whether camera rays and perfect mirror / refraction rays see the
    /// light's emitting face (mental ray's `visible`). Invisible lights still light surfaces
    /// (glossy highlights included).
    pub visible: bool,
    /// Optional linear near/far falloff `(start, end)` in scene units, on top of the
    /// physical inverse-square law: full strength up to `start`, none beyond `end`.
    pub attenuation: Option<(f32, f32)>,
    /// Point and spot lights: whether the arriving light falls off as 1/d² (physical);
    /// `false` is mental ray's `mib_light_point`/`mib_light_spot`, whose `Cl` is the
    /// intensity itself at every distance (times the near/far ramp). Area shapes: `false`
    /// makes each sample a point light of intensity `radiant` at a point of the shape
    /// (mental ray's area shape on those shaders; `shading::lights::area_points`).
    pub inverse_square: bool,
}

impl Emitter {
    /// A light of `shape` emitting `radiant`, casting shadows, one sample (16 for area
    /// lights), invisible, without near/far attenuation, falling off as 1/d².
    pub fn new(shape: LightShape, radiant: Vec3) -> Self {
        let samples = if shape.is_area() { 16 } else { 1 };
        Self {
            shape,
            radiant,
            shadows: true,
            shadow_factor: 0.0,
            samples,
            visible: false,
            attenuation: None,
            inverse_square: true,
        }
    }
}

/// Linear near/far attenuation factor at distance `d`: 1 up to `start`, 0 from `end` on.
pub fn attenuation_factor(attenuation: Option<(f32, f32)>, d: f32) -> f32 {
    match attenuation {
        None => 1.0,
        Some((start, end)) => {
            if d <= start {
                1.0
            } else if d >= end {
                0.0
            } else {
                (end - d) / (end - start)
            }
        }
    }
}
