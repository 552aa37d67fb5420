//! H16 of `HARDCASES.md`: Fresnel at grazing angles, total internal reflection, η = 1 and
//! η < 1 — reference values, a sweep of 10⁶ angles (no NaN, R + T = 1 within 1e-6, Snell's
//! law, unit refracted directions, TIR exactly past the critical angle), and an index-matched
//! sphere that is invisible in a render.

use crate::common;

use glam::{Affine3A, Vec3};
use stagelight::components::Shader;
use stagelight::settings::{Integrator, RenderSettings};
use stagelight::shading::fresnel::{fr_dielectric, fresnel_dielectric_rt, refract};

#[test]
fn h16_reference_values() {
    assert!((fr_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
    assert_eq!(fr_dielectric(0.0, 1.5), 1.0);
    let c45 = std::f32::consts::FRAC_1_SQRT_2;
    let r45 = 0.5 * (0.092_013_363_f64.powi(2) + 0.303_337_045_3_f64.powi(2));
    assert!((f64::from(fr_dielectric(c45, 1.5)) - r45).abs() < 1e-6);
    assert_eq!(fr_dielectric(c45, 1.0 / 1.5), 1.0);
    let c10 = 10f32.to_radians().cos();
    let r10 = 0.5 * (0.190_467_972_f64.powi(2) + 0.209_494_319_6_f64.powi(2));
    assert!((f64::from(fr_dielectric(c10, 1.0 / 1.5)) - r10).abs() < 1e-6);
}

/// 10⁶ cosines in [−1, 1] plus the special values, for η = 1.5 and 1/1.5.
#[test]
fn h16_sweep_of_a_million_angles() {
    let n = 1_000_000;
    let mut cosines: Vec<f32> = (0..n)
        .map(|i| -1.0 + 2.0 * (i as f32 + 0.5) / n as f32)
        .collect();
    cosines.extend([
        0.0,
        -0.0,
        1.0,
        -1.0,
        1.0 + f32::EPSILON,
        -1.0 - f32::EPSILON,
        1e-30,
        -1e-30,
    ]);
    for eta in [1.5f32, 1.0 / 1.5] {
        let mut worst_rt = 0.0f32;
        for &c in &cosines {
            let (r, t) = fresnel_dielectric_rt(c, eta);
            assert!(
                r.is_finite() && t.is_finite(),
                "η {eta} cos {c}: R {r} T {t}"
            );
            assert!((0.0..=1.0).contains(&r) && t >= 0.0);
            worst_rt = worst_rt.max((r + t - 1.0).abs());
            let cc = f64::from(c.clamp(-1.0, 1.0));
            let e = if cc < 0.0 {
                1.0 / f64::from(eta)
            } else {
                f64::from(eta)
            };
            let sin2_i = 1.0 - cc * cc;
            let wi = Vec3::new(sin2_i.sqrt() as f32, 0.0, c.clamp(-1.0, 1.0));
            // η is η_t/η_i: TIR exactly when sin²θi > η² (sin θc = η_t/η_i).
            let tir_expected = sin2_i > e * e;
            let near_critical = (sin2_i / (e * e) - 1.0).abs() < 1e-5;
            match refract(wi, Vec3::Z, eta) {
                None => {
                    assert!(
                        tir_expected || near_critical,
                        "η {eta} cos {c}: unexpected TIR"
                    );
                    assert_eq!(r, 1.0);
                }
                Some((wt, eta_t)) => {
                    assert!(
                        !tir_expected || near_critical,
                        "η {eta} cos {c}: missed TIR"
                    );
                    assert!((wt.length() - 1.0).abs() < 1e-5);
                    assert!(wt.z * wi.z <= 0.0, "transmitted to the wrong side");
                    let sin_i = (wi.x as f64).abs();
                    let sin_t = (wt.x as f64).abs();
                    assert!(
                        (sin_i - f64::from(eta_t) * sin_t).abs() < 1e-5,
                        "Snell at cos {c}"
                    );
                }
            }
        }
        assert!(worst_rt <= 1e-6, "η {eta}: |R + T − 1| up to {worst_rt}");
    }
}

/// TIR begins exactly at θc = asin(1/η) seen from the dense side.
#[test]
fn h16_tir_onset_at_the_critical_angle() {
    for eta in [1.33f32, 1.5, 2.4] {
        let theta_c = (1.0 / eta as f64).asin();
        for (offset, tir) in [(-1e-3, false), (1e-3, true)] {
            let theta = theta_c + offset;
            let wi = Vec3::new(theta.sin() as f32, 0.0, theta.cos() as f32);
            // Inside looking out: relative index 1/η.
            assert_eq!(
                refract(wi, Vec3::Z, 1.0 / eta).is_none(),
                tir,
                "η {eta} θ {theta}"
            );
            assert_eq!(
                fr_dielectric(wi.z, 1.0 / eta) == 1.0,
                tir,
                "η {eta} θ {theta}"
            );
        }
    }
}

/// η = 1: no reflection at any angle, the ray goes straight on.
#[test]
fn h16_index_matched_interface_is_transparent() {
    for i in 0..=1000 {
        let c = 1e-3 + (1.0 - 1e-3) * i as f32 / 1000.0;
        assert!(fr_dielectric(c, 1.0) < 1e-6, "cos {c}");
        let wi = Vec3::new((1.0 - c * c).sqrt(), 0.0, c);
        let (wt, _) = refract(wi, Vec3::Z, 1.0).unwrap();
        assert!((wt + wi).length() < 1e-6, "cos {c}: {wt}");
    }
}

fn scene_with_sphere(sphere: Option<f32>, integrator: Integrator) -> Vec<Vec3> {
    let mut world = hecs::World::new();
    let wall = common::material(
        &mut world,
        Shader::DefaultSurface {
            ka: 0.1,
            kd: 0.9,
            color: Vec3::new(0.9, 0.6, 0.3),
        },
    );
    common::instance(&mut world, common::square(20.0), Affine3A::IDENTITY, wall);
    if let Some(ior) = sphere {
        let glass = common::material(
            &mut world,
            Shader::Dielectric {
                ior,
                ior_out: 1.0,
                col: Vec3::ONE,
            },
        );
        common::instance(
            &mut world,
            common::sphere_mesh(Vec3::new(0.0, 0.0, 1.5), 1.0, 10, 20),
            Affine3A::IDENTITY,
            glass,
        );
    }
    common::camera(
        &mut world,
        Vec3::new(0.3, -4.0, 4.0),
        Vec3::new(0.0, 0.0, 1.0),
        40.0,
        16,
        16,
    );
    let settings = RenderSettings {
        spp: 2,
        integrator,
        max_depth: 8,
        refraction_depth: 8,
        ..RenderSettings::default()
    };
    common::render(&mut world, settings)
        .outputs
        .image
        .unwrap()
        .beauty
}

/// An η = 1 glass sphere is invisible: every pixel equals the render without it, in both
/// integrators (the wall's shader depends only on the ray direction, which η = 1 keeps).
/// The same sphere with η = 1.5 changes the image, so the test can fail.
#[test]
fn h16_index_matched_sphere_is_invisible() {
    for integrator in [Integrator::Direct, Integrator::Path] {
        let without = scene_with_sphere(None, integrator);
        let matched = scene_with_sphere(Some(1.0), integrator);
        for (i, (a, b)) in without.iter().zip(&matched).enumerate() {
            assert!(
                (*a - *b).abs().max_element() <= 1e-4 * a.max_element().max(1e-3),
                "{integrator:?} pixel {i}: {a} vs {b}"
            );
        }
        let glass = scene_with_sphere(Some(1.5), integrator);
        let changed = without
            .iter()
            .zip(&glass)
            .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-2)
            .count();
        assert!(
            changed > 20,
            "{integrator:?}: the η = 1.5 sphere changed only {changed} pixels"
        );
    }
}
