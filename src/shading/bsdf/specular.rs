//! Delta lobes: perfect mirror, smooth dielectric interface, straight pass-through.
//!
//! Their "BRDF" is a Dirac delta; a sample carries `f` with `f·|cosθi| / pdf` equal to the
//! throughput weight, as in pbrt. Their `eval` and `pdf` for arbitrary directions are 0.

use glam::Vec3;

use super::Transport;
use crate::shading::fresnel::{fresnel_dielectric_rt, refract};

/// One delta-lobe direction with the fraction of radiance it carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeltaBranch {
    /// Local direction toward the incident light.
    pub wi: Vec3,
    /// Radiance fraction carried along `wi` (`R`, or `T/η²` for refraction).
    pub weight: f32,
    /// Whether the branch crosses the surface.
    pub transmits: bool,
}

/// Mirror reflection of `wo`.
pub fn mirror(wo: Vec3) -> DeltaBranch {
    DeltaBranch {
        wi: Vec3::new(-wo.x, -wo.y, wo.z),
        weight: 1.0,
        transmits: false,
    }
}

/// Straight continuation through the surface.
pub fn pass_through(wo: Vec3) -> DeltaBranch {
    DeltaBranch {
        wi: -wo,
        weight: 1.0,
        transmits: true,
    }
}

/// The reflected and refracted branches of a smooth dielectric with relative index `eta`
/// (`η` behind the surface over `η` on the side of `wo`); `wo.z > 0`. Under total internal
/// reflection the refracted branch is `None` and the reflected one carries everything.
/// Radiance crossing into the denser side is scaled by `1/η²` (radiance, not importance).
pub fn dielectric(wo: Vec3, eta: f32) -> (DeltaBranch, Option<DeltaBranch>) {
    dielectric_transport(wo, eta, Transport::Radiance)
}

/// [`dielectric`] for the given transported quantity: the refracted branch carries `T/η²`
/// of radiance but `T` of importance (photon power), pbrt's `TransportMode`.
pub fn dielectric_transport(
    wo: Vec3,
    eta: f32,
    mode: Transport,
) -> (DeltaBranch, Option<DeltaBranch>) {
    let (r, t) = fresnel_dielectric_rt(wo.z, eta);
    let mut reflected = mirror(wo);
    let refracted = refract(wo, Vec3::Z, eta).and_then(|(wt, eta_t)| {
        (t > 0.0).then_some(DeltaBranch {
            wi: wt,
            weight: match mode {
                Transport::Radiance => t / (eta_t * eta_t),
                Transport::Importance => t,
            },
            transmits: true,
        })
    });
    reflected.weight = if refracted.is_some() { r } else { 1.0 };
    (reflected, refracted)
}

/// Probability of choosing the reflected branch of [`dielectric`] when sampling one branch.
pub fn dielectric_reflect_probability(wo: Vec3, eta: f32) -> f32 {
    let (r, t) = fresnel_dielectric_rt(wo.z, eta);
    if r + t > 0.0 {
        r / (r + t)
    } else {
        1.0
    }
}
