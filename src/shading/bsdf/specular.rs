//! Delta lobes: perfect mirror, smooth dielectric interface, straight pass-through.
//!
//! Their "BRDF" is a Dirac delta; a sample carries `f` with `f·|cosθi| / pdf` equal to the
//! throughput weight, as in pbrt. Their `eval` and `pdf` for arbitrary directions are 0.

use glam::Vec3;

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

/// What a path carries: the camera side traces radiance, the light side (photons) traces
/// importance. The two differ at refraction (hard case H14): radiance crossing an interface
/// is compressed into the narrower solid angle and scaled by `1/η²`; importance is not.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TransportMode {
    /// Camera paths: radiance flows from `wi` to `wo`.
    Radiance,
    /// Light paths (photons): importance flows from `wi` to `wo`, power is carried as is.
    Importance,
}

/// The reflected and refracted branches of a smooth dielectric with relative index `eta`
/// (`η` behind the surface over `η` on the side of `wo`); `wo.z > 0`. Under total internal
/// reflection the refracted branch is `None` and the reflected one carries everything.
/// Radiance crossing into the denser side is scaled by `1/η²` (radiance, not importance:
/// see [`dielectric_in_mode`]).
pub fn dielectric(wo: Vec3, eta: f32) -> (DeltaBranch, Option<DeltaBranch>) {
    dielectric_in_mode(wo, eta, TransportMode::Radiance)
}

/// [`dielectric`] for either transport mode: the refracted weight is `T/η²` for radiance and
/// `T` for importance (pbrt-v4 `DielectricBxDF`, Veach 1997 §5.2).
pub fn dielectric_in_mode(
    wo: Vec3,
    eta: f32,
    mode: TransportMode,
) -> (DeltaBranch, Option<DeltaBranch>) {
    let (r, t) = fresnel_dielectric_rt(wo.z, eta);
    let mut reflected = mirror(wo);
    let refracted = refract(wo, Vec3::Z, eta).and_then(|(wt, eta_t)| {
        (t > 0.0).then_some(DeltaBranch {
            wi: wt,
            weight: match mode {
                TransportMode::Radiance => t / (eta_t * eta_t),
                TransportMode::Importance => t,
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

#[cfg(test)]
mod tests {
    use super::*;

    /// H14(a): η = 1.5 at normal incidence, T = 1 − ((η−1)/(η+1))² = 0.96. Entering the
    /// glass (wo outside): radiance T/η², importance T; from inside (η → 1/η) radiance is
    /// T·η² and importance still T.
    #[test]
    fn h14_refraction_weight_depends_on_transport_mode() {
        let t = 1.0 - ((1.5f64 - 1.0) / (1.5 + 1.0)).powi(2);
        for (eta, radiance) in [(1.5f32, t / 2.25), (1.0 / 1.5, t * 2.25)] {
            let wo = Vec3::Z;
            let (_, rad) = dielectric_in_mode(wo, eta, TransportMode::Radiance);
            let (_, imp) = dielectric_in_mode(wo, eta, TransportMode::Importance);
            let (rad, imp) = (rad.unwrap(), imp.unwrap());
            assert_eq!(rad.wi, -Vec3::Z);
            assert!(
                (f64::from(rad.weight) / radiance - 1.0).abs() < 1e-6,
                "{rad:?}"
            );
            assert!((f64::from(imp.weight) / t - 1.0).abs() < 1e-6, "{imp:?}");
            assert_eq!(dielectric(wo, eta).1.unwrap(), rad);
        }
    }
}
