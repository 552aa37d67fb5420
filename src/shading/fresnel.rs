//! Fresnel equations and the reflection/refraction laws for smooth dielectric interfaces.
//!
//! Conventions: `eta` is the relative index `η_t / η_i` across the interface as seen from
//! the side the normal points to (outside → inside); directions point away from the surface.

use glam::Vec3;

/// Unpolarised Fresnel reflectance `R` of a dielectric interface for the cosine `cos_i` of
/// the incident direction with the normal and relative index `eta` (`η_inside/η_outside`).
/// A negative `cos_i` means the light arrives from the inside (η is inverted). Returns 1
/// under total internal reflection; never NaN for finite input.
pub fn fr_dielectric(cos_i: f32, eta: f32) -> f32 {
    fresnel_dielectric_rt(cos_i, eta).0
}

/// Reflectance and transmittance `(R, T)` of a dielectric interface, `T` computed from the
/// transmission amplitudes (not as `1 − R`), so `R + T = 1` is a property to test.
/// Arguments as for [`fr_dielectric`].
pub fn fresnel_dielectric_rt(cos_i: f32, eta: f32) -> (f32, f32) {
    let mut cos_i = cos_i.clamp(-1.0, 1.0);
    let mut eta = eta;
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    match fresnel_oriented(cos_i, eta) {
        Some((r, t, _)) => (r, t),
        None => (1.0, 0.0),
    }
}

/// `(R, T, cosθt)` for an oriented `cos_i ∈ [0, 1]` (the flip of `eta` already made), or
/// `None` where the interface only reflects — total internal reflection, or grazing incidence
/// on an index-matched interface (`cos_i = cos_t = 0`) — where `(R, T) = (1, 0)`. The one
/// Fresnel evaluation behind [`fresnel_dielectric_rt`] and the dielectric's branch sampling.
#[inline(always)]
pub(crate) fn fresnel_oriented(cos_i: f32, eta: f32) -> Option<(f32, f32, f32)> {
    let cos_t = cos_transmitted(cos_i, eta)?;
    let (ec_i, ec_t) = (eta * cos_i, eta * cos_t);
    let d_parl = ec_i + cos_t;
    let d_perp = cos_i + ec_t;
    if d_parl <= 0.0 || d_perp <= 0.0 {
        return None;
    }
    let r_parl = (ec_i - cos_t) / d_parl;
    let r_perp = (cos_i - ec_t) / d_perp;
    let r = 0.5 * (r_parl * r_parl + r_perp * r_perp);
    // Transmitted power: (η cosθt / cosθi) · |t|², written so that cos_i = 0 stays finite.
    let t_parl = 2.0 / d_parl;
    let t_perp = 2.0 / d_perp;
    let t = 0.5 * ec_t * cos_i * (t_parl * t_parl + t_perp * t_perp);
    Some((r, t, cos_t))
}

/// `cosθt` for `cosθi ∈ [0, 1]` and relative index `eta`, or `None` under total internal
/// reflection (`sin²θt ≥ 1`). Written as `√((η² − 1) + cos²θi) / η` with `η² − 1 =
/// (η − 1)(η + 1)`: exact for η = 1 and accurate at grazing angles, where `1 − sin²θt`
/// would cancel catastrophically.
#[inline]
fn cos_transmitted(cos_i: f32, eta: f32) -> Option<f32> {
    let k = (eta - 1.0) * (eta + 1.0) + cos_i * cos_i;
    if k == f32::INFINITY {
        // η² overflows f32 (η ≳ 1.8e19): sinθt ≤ 1/η < 2⁻⁶³, so cosθt rounds to 1 (the formula
        // would give ∞ here and NaN reflectances downstream).
        return Some(1.0);
    }
    (k > 0.0).then(|| k.sqrt() / eta)
}

/// Mirror direction of `wo` about `n`.
#[inline]
pub fn reflect(wo: Vec3, n: Vec3) -> Vec3 {
    -wo + 2.0 * wo.dot(n) * n
}

/// Refracted direction of `wi` (pointing away from the surface, on either side) through an
/// interface with normal `n` and relative index `eta` (`η` of the side `n` points away
/// from, over the side it points to). Returns the unit transmitted direction and the
/// relative index `η_t / η_i` actually crossed, or `None` under total internal reflection.
pub fn refract(wi: Vec3, n: Vec3, eta: f32) -> Option<(Vec3, f32)> {
    let mut cos_i = wi.dot(n).clamp(-1.0, 1.0);
    let (mut n, mut eta) = (n, eta);
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    let cos_t = cos_transmitted(cos_i, eta)?;
    let wt = -wi / eta + (cos_i / eta - cos_t) * n;
    Some((wt.normalize(), eta))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_index_whose_square_overflows_reflects_almost_everything() {
        for eta in [1.9e19_f32, 1e20, 1e30, f32::MAX] {
            for cos_i in [0.0_f32, 0.3, 1.0, -0.5, -1.0] {
                let (r, t) = fresnel_dielectric_rt(cos_i, eta);
                assert!(
                    r.is_finite() && t.is_finite(),
                    "η {eta} cos {cos_i}: {r} {t}"
                );
                assert!((0.999..=1.0).contains(&r), "η {eta} cos {cos_i}: R {r}");
                assert!(
                    (r + t - 1.0).abs() < 1e-6,
                    "η {eta} cos {cos_i}: R + T {}",
                    r + t
                );
            }
            assert_eq!(cos_transmitted(0.5, eta), Some(1.0));
        }
        // Just below the overflow the formula itself still answers.
        assert!(fr_dielectric(0.5, 1e19).is_finite());
    }

    #[test]
    fn mitsuba_reference_values() {
        assert!((fr_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        assert_eq!(fr_dielectric(0.0, 1.5), 1.0);
        let c45 = std::f32::consts::FRAC_1_SQRT_2;
        let expect = 0.5 * (0.092_013_363_f64.powi(2) + 0.303_337_045_3_f64.powi(2));
        assert!((f64::from(fr_dielectric(c45, 1.5)) - expect).abs() < 1e-6);
        assert_eq!(fr_dielectric(c45, 1.0 / 1.5), 1.0);
        let c10 = 10f32.to_radians().cos();
        let expect = 0.5 * (0.190_467_972_f64.powi(2) + 0.209_494_319_6_f64.powi(2));
        assert!((f64::from(fr_dielectric(c10, 1.0 / 1.5)) - expect).abs() < 1e-6);
    }

    #[test]
    fn refraction_angle_at_45_degrees() {
        let c45 = std::f32::consts::FRAC_1_SQRT_2;
        let wi = Vec3::new(c45, 0.0, c45);
        let (wt, eta) = refract(wi, Vec3::Z, 1.5).unwrap();
        assert_eq!(eta, 1.5);
        let theta_t = (-wt.z).acos().to_degrees();
        assert!((theta_t - 28.125_506).abs() < 1e-4, "{theta_t}");
    }
}
