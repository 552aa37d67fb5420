//! Light sampling: point, spot, directional, rectangular area lights and emitting meshes.
//!
//! Every light returns samples as `(direction, distance, contribution)` where `contribution`
//! is the incident radiance already divided by the sampling pdf (in solid-angle terms), so the
//! reflected radiance of a BRDF `f` is `f · contribution · cosθ` averaged over samples.

use glam::{Vec2, Vec3};

use crate::accel::{Ray, SurfacePoint};
use crate::components::{Emitter, LightShape};
use crate::geometry::SceneGeometry;

/// A light prepared for sampling (world space).
#[derive(Debug, Clone)]
pub enum Light {
    /// Isotropic point light.
    Point {
        /// Position.
        position: Vec3,
        /// Intensity, W/sr.
        intensity: Vec3,
        /// Trace shadow rays.
        shadows: bool,
    },
    /// RenderMan-style spotlight.
    Spot {
        /// Position.
        position: Vec3,
        /// Unit axis.
        axis: Vec3,
        /// cos of the cone half-angle (outer edge).
        cos_outer: f32,
        /// cos of (cone angle − penumbra) (inner edge of the penumbra).
        cos_inner: f32,
        /// Exponent of the cosine beam falloff.
        beam_distribution: f32,
        /// On-axis intensity, W/sr.
        intensity: Vec3,
        /// Trace shadow rays.
        shadows: bool,
    },
    /// Distant light.
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
        /// Irradiance on a surface facing the light, W/m².
        irradiance: Vec3,
        /// Trace shadow rays.
        shadows: bool,
    },
    /// One-sided parallelogram light.
    Rect {
        /// Corner.
        corner: Vec3,
        /// First edge.
        edge_u: Vec3,
        /// Second edge.
        edge_v: Vec3,
        /// Unit emitting normal `edge_u × edge_v`.
        normal: Vec3,
        /// Area, m².
        area: f32,
        /// Radiance, W/(sr·m²).
        radiance: Vec3,
        /// Trace shadow rays.
        shadows: bool,
        /// Samples per shading point.
        samples: u32,
    },
    /// All triangles of emitting materials, sampled by area × emitted radiance.
    Mesh {
        /// World triangle ids.
        prims: Vec<u32>,
        /// Normalised CDF over `prims` (length `prims.len() + 1`).
        cdf: Vec<f32>,
        /// Sum of the sampling weights.
        total_weight: f32,
        /// Samples per shading point.
        samples: u32,
    },
}

/// One sample toward a light.
#[derive(Debug, Clone, Copy)]
pub struct LightSample {
    /// Unit direction from the shading point toward the light.
    pub wi: Vec3,
    /// Incident radiance divided by the solid-angle pdf.
    pub contribution: Vec3,
    /// Where the shadow ray must reach: a point (`Some`) or infinity along `wi` (`None`).
    pub target: Option<SurfacePoint>,
    /// Whether a shadow ray is needed.
    pub shadows: bool,
    /// Solid-angle pdf of the sample; 0 for delta lights (point, spot, directional), which
    /// no other strategy can reach.
    pub pdf: f32,
}

impl Light {
    /// Prepares a scene emitter for sampling.
    pub fn from_emitter(e: &Emitter) -> Self {
        match e.shape {
            LightShape::Point { position } => Light::Point {
                position,
                intensity: e.radiant,
                shadows: e.shadows,
            },
            LightShape::Spot {
                position,
                direction,
                cone_angle,
                penumbra,
                beam_distribution,
            } => Light::Spot {
                position,
                axis: direction.normalize_or_zero(),
                cos_outer: cone_angle.cos(),
                cos_inner: (cone_angle - penumbra.max(0.0)).max(0.0).cos(),
                beam_distribution,
                intensity: e.radiant,
                shadows: e.shadows,
            },
            LightShape::Directional { direction } => Light::Directional {
                direction: direction.normalize_or_zero(),
                irradiance: e.radiant,
                shadows: e.shadows,
            },
            LightShape::Rect {
                corner,
                edge_u,
                edge_v,
            } => {
                let c = edge_u.cross(edge_v);
                Light::Rect {
                    corner,
                    edge_u,
                    edge_v,
                    normal: c.normalize_or_zero(),
                    area: c.length(),
                    radiance: e.radiant,
                    shadows: e.shadows,
                    samples: e.samples.max(1),
                }
            }
        }
    }

    /// Samples this light per shading point (1 for delta lights).
    pub fn sample_count(&self) -> u32 {
        match self {
            Light::Rect { samples, .. } | Light::Mesh { samples, .. } => *samples,
            _ => 1,
        }
    }

    /// Draws a sample toward the light from `p`; `None` when the light cannot reach `p`.
    pub fn sample(
        &self,
        p: Vec3,
        u: Vec2,
        geometry: Option<&SceneGeometry>,
    ) -> Option<LightSample> {
        match self {
            Light::Point {
                position,
                intensity,
                shadows,
            } => {
                let d = *position - p;
                let dist2 = d.length_squared();
                if dist2 <= 0.0 {
                    return None;
                }
                Some(LightSample {
                    wi: d / dist2.sqrt(),
                    contribution: *intensity / dist2,
                    target: Some(point_target(*position)),
                    shadows: *shadows,
                    pdf: 0.0,
                })
            }
            Light::Spot {
                position,
                axis,
                cos_outer,
                cos_inner,
                beam_distribution,
                intensity,
                shadows,
            } => {
                let d = *position - p;
                let dist2 = d.length_squared();
                if dist2 <= 0.0 {
                    return None;
                }
                let wi = d / dist2.sqrt();
                let cos_angle = (-wi).dot(*axis);
                let falloff = spot_falloff(cos_angle, *cos_outer, *cos_inner, *beam_distribution);
                if falloff <= 0.0 {
                    return None;
                }
                Some(LightSample {
                    wi,
                    contribution: *intensity * (falloff / dist2),
                    target: Some(point_target(*position)),
                    shadows: *shadows,
                    pdf: 0.0,
                })
            }
            Light::Directional {
                direction,
                irradiance,
                shadows,
            } => Some(LightSample {
                wi: -*direction,
                contribution: *irradiance,
                target: None,
                shadows: *shadows,
                pdf: 0.0,
            }),
            Light::Rect {
                corner,
                edge_u,
                edge_v,
                normal,
                area,
                radiance,
                shadows,
                ..
            } => {
                let q = *corner + *edge_u * u.x + *edge_v * u.y;
                area_sample(p, q, *normal, false, *radiance, *area, *shadows, q_err(q))
            }
            Light::Mesh {
                prims,
                cdf,
                total_weight,
                ..
            } => {
                let geometry = geometry?;
                let k = cdf.partition_point(|&c| c <= u.x).clamp(1, prims.len()) - 1;
                let (c0, c1) = (cdf[k], cdf[k + 1]);
                let ux = if c1 > c0 {
                    ((u.x - c0) / (c1 - c0)).clamp(0.0, 1.0 - f32::EPSILON)
                } else {
                    0.5
                };
                let prim = prims[k];
                let material = geometry.material_of(prim);
                let tri = geometry.accel.triangle(prim);
                let e = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
                let tri_area = 0.5 * e.length();
                let weight = tri_area * material.emission.max_element();
                let prob = weight / total_weight;
                let (b1, b2) = crate::sampling::sample_triangle(Vec2::new(ux, u.y));
                let sp = geometry.accel.surface_point(&crate::accel::Hit {
                    t: 0.0,
                    prim,
                    b1,
                    b2,
                });
                // pdf in area measure is prob / tri_area; area_sample divides by (1/area).
                area_sample(
                    p,
                    sp.p,
                    sp.ng,
                    material.two_sided,
                    material.emission,
                    tri_area / prob,
                    true,
                    sp,
                )
            }
        }
    }
}

impl Light {
    /// Where a ray meets this light, if it is an area light that rays can hit (`Rect`, whose
    /// front face only is seen): the ray parameter, the emitted radiance, and the solid-angle
    /// pdf with which [`Light::sample`] would have chosen that direction from the ray origin.
    /// Emitting meshes are geometry: see [`LightSet::mesh_pdf`].
    pub fn hit(&self, ray: &Ray) -> Option<(f32, Vec3, f32)> {
        let Light::Rect {
            corner,
            edge_u,
            edge_v,
            normal,
            area,
            radiance,
            ..
        } = self
        else {
            return None;
        };
        let denom = ray.dir.dot(*normal);
        if denom.is_nan() || denom >= 0.0 {
            return None;
        }
        let t = (*corner - ray.origin).dot(*normal) / denom;
        if !(t > 0.0 && t < ray.t_max) {
            return None;
        }
        let q = ray.origin + ray.dir * t - *corner;
        // Coordinates of q in the (edge_u, edge_v) basis via the dual basis.
        let (uu, uv, vv) = (
            edge_u.dot(*edge_u),
            edge_u.dot(*edge_v),
            edge_v.dot(*edge_v),
        );
        let det = uu * vv - uv * uv;
        let (qu, qv) = (q.dot(*edge_u), q.dot(*edge_v));
        let s = (qu * vv - qv * uv) / det;
        let r = (qv * uu - qu * uv) / det;
        if !((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&r)) {
            return None;
        }
        let len = ray.dir.length();
        let dist = t * len;
        let cos_l = -denom / len;
        let pdf = dist * dist / (cos_l * area);
        (pdf.is_finite() && pdf > 0.0).then_some((t, *radiance, pdf))
    }
}

/// A shadow-ray target at an exactly known point (no error to account for).
fn point_target(q: Vec3) -> SurfacePoint {
    SurfacePoint {
        p: q,
        p_err: Vec3::ZERO,
        ng: Vec3::ZERO,
    }
}

/// Error bound of a point computed as `corner + u·edge_u + v·edge_v` (three roundings).
fn q_err(q: Vec3) -> SurfacePoint {
    let gamma = 4.0 * f32::EPSILON * 0.5 / (1.0 - 4.0 * f32::EPSILON * 0.5);
    SurfacePoint {
        p: q,
        p_err: q.abs() * gamma,
        ng: Vec3::ZERO,
    }
}

/// Converts an area-measure sample of an emitter at `q` into a solid-angle light sample.
/// `inv_pdf_area` is 1 / (pdf with respect to area).
#[allow(clippy::too_many_arguments)] // the terms of one radiometric conversion
fn area_sample(
    p: Vec3,
    q: Vec3,
    light_normal: Vec3,
    two_sided: bool,
    radiance: Vec3,
    inv_pdf_area: f32,
    shadows: bool,
    mut target: SurfacePoint,
) -> Option<LightSample> {
    let d = q - p;
    let dist2 = d.length_squared();
    if dist2.is_nan() || dist2 <= 0.0 {
        return None;
    }
    let wi = d / dist2.sqrt();
    let mut cos_l = light_normal.dot(-wi);
    if two_sided {
        cos_l = cos_l.abs();
    }
    if cos_l <= 0.0 {
        return None;
    }
    target.ng = light_normal;
    let contribution = radiance * (cos_l * inv_pdf_area / dist2);
    let pdf = dist2 / (cos_l * inv_pdf_area);
    if !(contribution.is_finite() && pdf > 0.0 && pdf.is_finite()) {
        return None;
    }
    Some(LightSample {
        wi,
        contribution,
        target: Some(target),
        shadows,
        pdf,
    })
}

/// RenderMan spotlight attenuation: `cos^beam · smoothstep(cos_outer, cos_inner, cos)`.
pub fn spot_falloff(cos_angle: f32, cos_outer: f32, cos_inner: f32, beam: f32) -> f32 {
    if cos_angle <= cos_outer {
        return 0.0;
    }
    let edge = if cos_inner > cos_outer {
        let t = ((cos_angle - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    } else {
        1.0
    };
    cos_angle.max(0.0).powf(beam) * edge
}

/// The lights of a scene, ready for sampling.
#[derive(Debug, Clone, Default)]
pub struct LightSet {
    /// Every light, emitters first (in entity order), then the emitting-mesh light.
    pub lights: Vec<Light>,
}

impl LightSet {
    /// Lights from scene emitters plus one light for all emitting triangles in `geometry`.
    pub fn new(emitters: &[Emitter], geometry: Option<&SceneGeometry>, mesh_samples: u32) -> Self {
        let mut lights: Vec<Light> = emitters.iter().map(Light::from_emitter).collect();
        if let Some(g) = geometry {
            let mut prims = Vec::new();
            let mut weights = Vec::new();
            for inst in &g.instances {
                let m = &g.materials[inst.material as usize];
                if !m.is_emissive() {
                    continue;
                }
                let lum = m.emission.max_element();
                for local in 0..inst.mesh.triangles.len() {
                    let prim = inst.first_triangle + local as u32;
                    let t = g.accel.triangle(prim);
                    let area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
                    if area > 0.0 && area.is_finite() {
                        prims.push(prim);
                        weights.push(area as f64 * lum as f64);
                    }
                }
            }
            let total: f64 = weights.iter().sum();
            if !prims.is_empty() && total > 0.0 {
                let mut cdf = Vec::with_capacity(prims.len() + 1);
                let mut acc = 0.0f64;
                cdf.push(0.0f32);
                for w in &weights {
                    acc += w;
                    cdf.push((acc / total) as f32);
                }
                *cdf.last_mut().expect("non-empty") = 1.0;
                lights.push(Light::Mesh {
                    prims,
                    cdf,
                    total_weight: total as f32,
                    samples: mesh_samples.max(1),
                });
            }
        }
        Self { lights }
    }

    /// Solid-angle pdf with which the emitting-mesh light samples the point `q` (geometric
    /// normal `ng`, emitted radiance `emission`, `two_sided` emission) from `p`; 0 when no
    /// mesh light exists or `q` faces away.
    pub fn mesh_pdf(&self, p: Vec3, q: Vec3, ng: Vec3, emission: Vec3, two_sided: bool) -> f32 {
        let Some(total) = self.lights.iter().find_map(|l| match l {
            Light::Mesh { total_weight, .. } => Some(*total_weight),
            _ => None,
        }) else {
            return 0.0;
        };
        let d = q - p;
        let dist2 = d.length_squared();
        let mut cos_l = ng.dot(-d) / dist2.sqrt();
        if two_sided {
            cos_l = cos_l.abs();
        }
        if cos_l.is_nan() || cos_l <= 0.0 || total <= 0.0 {
            return 0.0;
        }
        let pdf = emission.max_element() / total * dist2 / cos_l;
        if pdf.is_finite() {
            pdf
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_is_full_inside_and_zero_outside_the_cone() {
        let (outer, inner) = (30f32.to_radians().cos(), 25f32.to_radians().cos());
        assert_eq!(spot_falloff(1.0, outer, inner, 0.0), 1.0);
        assert_eq!(
            spot_falloff(31f32.to_radians().cos(), outer, inner, 0.0),
            0.0
        );
        let mid = spot_falloff(27.5f32.to_radians().cos(), outer, inner, 0.0);
        assert!(mid > 0.3 && mid < 0.7, "{mid}");
        // Beam distribution: cos² on the axis' neighbourhood.
        let c = 10f32.to_radians().cos();
        assert!((spot_falloff(c, outer, inner, 2.0) - c * c).abs() < 1e-6);
    }

    #[test]
    fn point_light_follows_inverse_square() {
        let l = Light::Point {
            position: Vec3::new(0.0, 0.0, 2.0),
            intensity: Vec3::splat(8.0),
            shadows: true,
        };
        let s = l.sample(Vec3::ZERO, Vec2::ZERO, None).unwrap();
        assert_eq!(s.contribution, Vec3::splat(2.0));
        assert_eq!(s.wi, Vec3::Z);
    }

    #[test]
    fn rect_light_is_one_sided() {
        let l = Light::from_emitter(&Emitter {
            shape: LightShape::Rect {
                corner: Vec3::new(-0.5, -0.5, 1.0),
                edge_u: Vec3::X,
                edge_v: Vec3::Y,
            },
            radiant: Vec3::ONE,
            shadows: true,
            samples: 4,
        });
        // Normal is +Z: a point below the light (z = 0) sees its back.
        assert!(l.sample(Vec3::ZERO, Vec2::splat(0.5), None).is_none());
        assert!(l
            .sample(Vec3::new(0.0, 0.0, 2.0), Vec2::splat(0.5), None)
            .is_some());
    }
}
