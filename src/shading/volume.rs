//! Volume shaders along ray segments: fog as the camera's atmosphere and inside materials
//! (their `interior`), with transmittance `e^(−σt·d)` on every segment (height-bounded and
//! noisy densities: `shading::medium`) and single scattering of light into the segment; or
//! the camera's linear fade to a colour (`Fade`, mental ray's `mib_volume`).
//!
//! Which medium a segment crosses: the interior of the material whose **back face** ends the
//! segment (the ray is leaving that object), otherwise the atmosphere. There is no medium
//! stack: an object inside a fog-filled object is seen through the atmosphere. Following
//! mental ray (a volume shader sees `dist = 0` on rays of infinite length), segments that
//! leave the scene and shadow rays toward directional lights cross no medium.
//!
//! In-scattering `∫₀ᵈ T(t) σs Σ_lights p(θ) L_light(x(t)) T_light dt` is estimated with one
//! sample per light and segment: the distance is drawn by equiangular sampling about the
//! light's position (point, spot, rectangle centre) or from the transmittance for other
//! lights, the light then sampled from that point with a shadow ray. Shadow rays (from
//! surfaces too) pass through the shells of fog-filled materials and are attenuated by every
//! medium they cross. Only single scattering is computed: no path scatters twice inside a
//! medium.
//!
//! This module holds the media ([`Volumes`]) and the closed-form distance and phase
//! sampling; the integration along ray segments, which traces shadow rays through the scene,
//! is `shading::integrator::volume`.

use glam::Vec3;

use crate::accel::{Hit, Ray};
use crate::components::{Fade, Fog};
use crate::geometry::SceneGeometry;

/// The scene's media: the render camera's atmosphere and each material's interior.
#[derive(Debug, Clone, PartialEq)]
pub struct Volumes {
    /// The camera's atmosphere.
    pub atmosphere: Option<Fog>,
    /// Interior of each material, indexed like `SceneGeometry::materials`.
    pub interiors: Vec<Option<Fog>>,
    /// The camera's fade atmosphere (only without a fog `atmosphere`): segments that cross
    /// no fog blend toward its colour.
    pub fade: Option<Fade>,
}

impl Volumes {
    /// The media, or `None` when there is none (no volume work at all then).
    pub fn new(atmosphere: Option<Fog>, interiors: Vec<Option<Fog>>) -> Option<Self> {
        Self::with_fade(atmosphere, None, interiors)
    }

    /// [`Volumes::new`] with the camera's fade atmosphere.
    pub fn with_fade(
        atmosphere: Option<Fog>,
        fade: Option<Fade>,
        interiors: Vec<Option<Fog>>,
    ) -> Option<Self> {
        let any = atmosphere.is_some() || fade.is_some() || interiors.iter().any(Option::is_some);
        any.then_some(Self {
            atmosphere,
            interiors,
            fade,
        })
    }

    /// The medium the segment of `ray` ending at `hit` crosses.
    pub fn medium(&self, geometry: &SceneGeometry, ray: &Ray, hit: &Hit) -> Option<&Fog> {
        let material = geometry.material_slot(hit.prim) as usize;
        if let Some(Some(fog)) = self.interiors.get(material) {
            let ng = geometry.accel.surface_point(hit).ng;
            if ng.dot(ray.dir) > 0.0 {
                return Some(fog);
            }
        }
        self.atmosphere.as_ref()
    }
}

/// Equiangular sampling of `t ∈ [0, length]` about the point `c` (Kulla & Fajardo 2012):
/// `(t, pdf)`, or `None` when the ray passes (almost) through `c`.
pub fn equiangular(origin: Vec3, dir: Vec3, length: f32, c: Vec3, u: f32) -> Option<(f32, f32)> {
    let oc = c - origin;
    let delta = oc.dot(dir);
    let d = (oc - dir * delta).length();
    let far_enough = d > 1e-5 * (length + delta.abs()).max(1e-3);
    if !far_enough {
        return None;
    }
    let a = (-delta).atan2(d);
    let b = (length - delta).atan2(d);
    if b.is_nan() || a.is_nan() || b <= a {
        return None;
    }
    let theta = a + u * (b - a);
    let t = (delta + d * theta.tan()).clamp(0.0, length);
    let s = t - delta;
    Some((t, d / ((b - a) * (d * d + s * s))))
}

/// Distance sampling proportional to the mean extinction, truncated to `[0, length]`:
/// `(t, pdf)` (uniform when the segment is optically thin).
pub fn distance_sample(fog: &Fog, length: f32, u: f32) -> (f32, f32) {
    let s = fog.sigma_t().element_sum() / 3.0;
    if s * length < 1e-4 {
        return (u * length, 1.0 / length);
    }
    let norm = -(-s * length).exp_m1();
    let t = (-(-u * norm).ln_1p() / s).clamp(0.0, length);
    (t, s * (-s * t).exp() / norm)
}

/// Henyey–Greenstein phase function, 1/sr, for `cos_theta` between the direction toward the
/// light and the ray direction (light continuing forward has `cos_theta = 1`).
pub fn henyey_greenstein(g: f32, cos_theta: f32) -> f32 {
    let denom = 1.0 + g * g - 2.0 * g * cos_theta;
    (1.0 - g * g) / (4.0 * std::f32::consts::PI * denom * denom.max(1e-12).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inverse-CDF samples `t(u)` with pdf `p(t)`: `∫ dt` over the samples' spacing equals
    /// `∫ p dt = 1`, i.e. `dt/du = 1/p` everywhere.
    fn check_inverse_cdf(sample: impl Fn(f32) -> (f32, f32), length: f32) {
        let n = 2000;
        let mut total = 0.0f64;
        for k in 0..n {
            let u = (k as f32 + 0.5) / n as f32;
            let (t, pdf) = sample(u);
            assert!((0.0..=length).contains(&t) && pdf > 0.0, "{t} {pdf}");
            let (t2, _) = sample(u + 1e-4);
            let dtdu = (t2 - t) / 1e-4;
            assert!(
                (dtdu * pdf - 1.0).abs() < 2e-2,
                "u {u}: dt/du {dtdu} vs 1/pdf {}",
                1.0 / pdf
            );
            total += f64::from(1.0 / pdf) / n as f64;
        }
        // E_u[1/p] = length.
        assert!((total / f64::from(length) - 1.0).abs() < 1e-2, "{total}");
    }

    #[test]
    fn equiangular_pdf_matches_its_sampling() {
        let (o, d) = (Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0));
        check_inverse_cdf(
            |u| equiangular(o, d, 4.0, Vec3::new(0.5, 0.0, -1.0), u).unwrap(),
            4.0,
        );
        assert!(equiangular(o, d, 4.0, Vec3::new(0.0, 0.0, -2.0), 0.5).is_none());
    }

    #[test]
    fn distance_sampling_pdf_matches_its_sampling() {
        let fog = Fog {
            sigma_a: Vec3::splat(0.3),
            sigma_s: Vec3::new(0.2, 0.5, 0.8),
            g: 0.0,
            ..Default::default()
        };
        check_inverse_cdf(|u| distance_sample(&fog, 5.0, u), 5.0);
    }

    #[test]
    fn henyey_greenstein_integrates_to_one() {
        for g in [-0.9f32, -0.3, 0.0, 0.5, 0.95] {
            let n = 200_000;
            let sum: f64 = (0..n)
                .map(|k| {
                    let mu = -1.0 + 2.0 * (k as f64 + 0.5) / n as f64;
                    f64::from(henyey_greenstein(g, mu as f32))
                })
                .sum();
            // ∫ p dω = 2π ∫ p dμ.
            let integral = sum * 2.0 / n as f64 * std::f64::consts::TAU;
            assert!((integral - 1.0).abs() < 1e-3, "g {g}: {integral}");
        }
    }
}
