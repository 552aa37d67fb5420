//! Delta lobes: perfect mirror, smooth dielectric interface, straight pass-through.
//!
//! Their "BRDF" is a Dirac delta; a sample carries `f` with `f·|cosθi| / pdf` equal to the
//! throughput weight, as in pbrt. Their `eval` and `pdf` for arbitrary directions are 0.

use glam::Vec3;

use crate::shading::fresnel::{fresnel_dielectric_rt, fresnel_oriented, refract};

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

/// One branch of a smooth dielectric drawn with `uc ∈ [0,1)`, and the probability of
/// drawing it: the refracted branch of [`dielectric_in_mode`] when there is one and
/// `uc ≥` [`dielectric_reflect_probability`], else the reflected one (probability 1 when
/// nothing is refracted). The same bits as those functions, from one Fresnel evaluation
/// (`fresnel_oriented`, which `fresnel_dielectric_rt` runs) and one `cosθt`: they computed the Fresnel
/// terms twice and `cosθt` three times, and normalised the refracted direction also when the
/// reflected branch was drawn (`dielectric_sample_is_the_two_calls_bit_for_bit`).
#[inline(always)]
pub fn dielectric_sample(wo: Vec3, eta: f32, mode: TransportMode, uc: f32) -> (DeltaBranch, f32) {
    // `fresnel_dielectric_rt(wo.z, eta)` and `refract(wo, Vec3::Z, eta)`, which flip the
    // same way and share `cos_transmitted`.
    let mut cos_i = wo.z.clamp(-1.0, 1.0);
    let (mut eta, mut n) = (eta, Vec3::Z);
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    let mut reflected = mirror(wo);
    let Some((r, t, cos_t)) = fresnel_oriented(cos_i, eta) else {
        // Total internal reflection (or grazing on a matched interface): (R, T) = (1, 0).
        return (reflected, 1.0);
    };
    // `refract`'s cosine is `wo·Z`, NaN when `wo.x` or `wo.y` is not finite (then nothing
    // is refracted); otherwise it is `wo.z`, which is not zero here.
    if !(t > 0.0 && wo.x.is_finite() && wo.y.is_finite()) {
        return (reflected, 1.0);
    }
    let pr = if r + t > 0.0 { r / (r + t) } else { 1.0 };
    if uc >= pr {
        let wt = -wo / eta + (cos_i / eta - cos_t) * n;
        let refracted = DeltaBranch {
            wi: wt.normalize(),
            weight: match mode {
                TransportMode::Radiance => t / (eta * eta),
                TransportMode::Importance => t,
            },
            transmits: true,
        };
        return (refracted, 1.0 - pr);
    }
    reflected.weight = r;
    (reflected, pr)
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

    /// The branch and probability `Bsdf::sample_transport` took from
    /// [`dielectric_reflect_probability`] and [`dielectric_in_mode`] before
    /// [`dielectric_sample`].
    fn two_calls(wo: Vec3, eta: f32, mode: TransportMode, uc: f32) -> (DeltaBranch, f32) {
        let pr = dielectric_reflect_probability(wo, eta);
        let (r, t) = dielectric_in_mode(wo, eta, mode);
        match t {
            Some(t) if uc >= pr => (t, 1.0 - pr),
            _ => (r, if t.is_some() { pr } else { 1.0 }),
        }
    }

    #[test]
    fn dielectric_sample_is_the_two_calls_bit_for_bit() {
        let bits = |(b, p): (DeltaBranch, f32)| {
            (
                b.wi.to_array().map(f32::to_bits),
                b.weight.to_bits(),
                b.transmits,
                p.to_bits(),
            )
        };
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let etas = [1.5, 1.0 / 1.5, 1.0, 1.33, 2.4, 0.5, 1.0 + 1e-7, 1e-3, 1e3];
        let special = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.0, -0.0, 0.0),
            Vec3::new(1.0, 0.0, 1e-30),
            Vec3::new(1.0, 0.0, -1e-30),
            Vec3::new(0.6, 0.0, 0.8) * 1.0001,
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(0.3, 0.1, f32::NAN),
            Vec3::new(f32::INFINITY, 0.0, 0.5),
        ];
        let mut checked = 0;
        for mode in [TransportMode::Radiance, TransportMode::Importance] {
            for &eta in &etas {
                let random: Vec<Vec3> = (0..2000)
                    .map(|_| {
                        let v =
                            Vec3::new(2.0 * next() - 1.0, 2.0 * next() - 1.0, 2.0 * next() - 1.0);
                        v.normalize_or(Vec3::Z)
                    })
                    .collect();
                for wo in special.into_iter().chain(random) {
                    for uc in [0.0, 0.02, 0.04, next(), 0.5, 0.999, 1.0 - f32::EPSILON] {
                        let want = two_calls(wo, eta, mode, uc);
                        let got = dielectric_sample(wo, eta, mode, uc);
                        assert_eq!(
                            bits(got),
                            bits(want),
                            "wo {wo:?} eta {eta} {mode:?} uc {uc}"
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 200_000);
    }

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
