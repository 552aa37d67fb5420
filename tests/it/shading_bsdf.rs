//! BSDF hard cases of `HARDCASES.md` group C:
//! - H15: χ² goodness-of-fit of every sampled (non-delta) BSDF at normal, oblique and grazing
//!   `wo`, α = 0.01 with Šidák correction over every χ² test in this file; sample values equal
//!   `eval` and `pdf`; the smooth dielectric's reflection fraction matches Fresnel (η, 1/η).
//! - H17: energy — albedo ≤ 1 for every material over many `wo` (including cosθ = 0.01);
//!   the lossless dielectric reflects + transmits exactly 1; reciprocity of the reflection
//!   lobes.

use crate::common;

use common::chi2::{chi2_directions, sidak, Rng};
use glam::Vec3;
use stagelight::components::Shader;
use stagelight::shading::bsdf::Bsdf;
use stagelight::shading::fresnel::fr_dielectric;

const ALPHA: f64 = 0.01;
const CHI2_SAMPLES: usize = 250_000;

fn grey(x: f32) -> Vec3 {
    Vec3::splat(x)
}

/// Every light-integrating shader family with parameters that keep the lobes resolvable by
/// the χ² grid.
fn materials() -> Vec<(&'static str, Shader)> {
    vec![
        ("lambert", Shader::Lambert { albedo: grey(0.8) }),
        (
            "phong",
            Shader::Phong {
                ambient: Vec3::ZERO,
                diffuse: grey(0.3),
                specular: grey(0.6),
                spec_exp: 20.0,
            },
        ),
        (
            "blinn",
            Shader::Blinn {
                ambient: Vec3::ZERO,
                diffuse: grey(0.4),
                specular: grey(0.6),
                roughness: 0.3,
                ior: 1.5,
            },
        ),
        (
            "cook_torrance",
            Shader::CookTorrance {
                ambient: Vec3::ZERO,
                diffuse: grey(0.2),
                specular: grey(0.8),
                roughness: 0.5,
                ior: Vec3::new(1.3, 1.5, 2.0),
            },
        ),
        (
            "blong",
            Shader::Blong {
                ambient: Vec3::ZERO,
                diffuse: grey(0.5),
                specular: grey(0.5),
                spec_exp: 30.0,
            },
        ),
        (
            "fresnel_specular",
            Shader::FresnelSpecular {
                ambient: Vec3::ZERO,
                diffuse: grey(0.5),
                specular: grey(1.0),
                spec_exp: 10.0,
                ior_in: 1.5,
                ior_out: 1.0,
            },
        ),
        (
            "plastic",
            Shader::Plastic {
                ka: 1.0,
                kd: 0.5,
                ks: 0.5,
                roughness: 0.1,
                specular_color: Vec3::ONE,
                color: Vec3::new(0.8, 0.2, 0.1),
            },
        ),
        (
            "metal",
            Shader::Metal {
                ka: 1.0,
                ks: 1.0,
                roughness: 0.05,
                color: Vec3::new(0.9, 0.7, 0.3),
            },
        ),
        (
            "shinymetal",
            Shader::ShinyMetal {
                ka: 1.0,
                ks: 1.0,
                kr: 1.0,
                roughness: 0.1,
                color: Vec3::ONE,
            },
        ),
        (
            "dgs",
            Shader::Dgs {
                diffuse: grey(0.3),
                glossy: grey(0.3),
                specular: grey(0.3),
                shiny: 15.0,
            },
        ),
        (
            "opacity_plastic",
            Shader::Opacity {
                opacity: grey(0.6),
                input: Box::new(Shader::Plastic {
                    ka: 1.0,
                    kd: 0.5,
                    ks: 0.5,
                    roughness: 0.1,
                    specular_color: Vec3::ONE,
                    color: Vec3::ONE,
                }),
            },
        ),
    ]
}

fn wo_set() -> Vec<Vec3> {
    vec![
        Vec3::new(0.3, 0.1, 0.9).normalize(),
        Vec3::new(-0.6, 0.5, 0.5).normalize(),
        Vec3::new(0.8, 0.3, 0.05).normalize(),
    ]
}

/// H15: every sampled BSDF passes χ² at every `wo` (one Šidák family for the whole set).
#[test]
fn h15_chi2_every_sampled_bsdf() {
    let mats = materials();
    let wos = wo_set();
    let count = mats.len() * wos.len();
    let alpha = sidak(ALPHA, count);
    let mut failures = Vec::new();
    for (m, (name, shader)) in mats.iter().enumerate() {
        let bsdf = Bsdf::new(shader, true).unwrap();
        for (k, &wo) in wos.iter().enumerate() {
            let seed = 1000 + (m * 10 + k) as u64;
            let outcome = chi2_directions(
                |u| {
                    let s = bsdf.sample(wo, u)?;
                    (!s.delta).then_some(s.wi)
                },
                |wi| bsdf.pdf(wo, wi) as f64,
                CHI2_SAMPLES,
                seed,
            );
            match outcome {
                Ok(o) if o.p_value >= alpha => {}
                Ok(o) => failures.push(format!(
                    "{name} wo={wo}: p = {:.3e} < {alpha:.3e} ({o:?})",
                    o.p_value
                )),
                Err(e) => failures.push(format!("{name} wo={wo}: {e}")),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// H15 companion: a non-delta sample's `f` and `pdf` equal `eval` and `pdf` at its
/// direction, every weight is finite and non-negative, delta weights are the lobe weights.
#[test]
fn h15_sample_values_match_eval_and_pdf() {
    let mut rng = Rng(7);
    for (name, shader) in materials() {
        let bsdf = Bsdf::new(&shader, true).unwrap();
        for wo in wo_set()
            .into_iter()
            .chain([Vec3::new(0.0, 0.99995, 0.01).normalize()])
        {
            for _ in 0..20_000 {
                let Some(s) = bsdf.sample(wo, rng.next_vec3()) else {
                    continue;
                };
                let w = s.weight();
                assert!(
                    w.is_finite() && w.min_element() >= 0.0,
                    "{name}: weight {w}"
                );
                if s.delta {
                    continue;
                }
                let f = bsdf.eval(wo, s.wi);
                let p = bsdf.pdf(wo, s.wi);
                assert!(
                    (f - s.f).abs().max_element() <= 1e-4 * f.max_element().max(1e-6),
                    "{name}"
                );
                assert!(
                    (p - s.pdf).abs() <= 1e-4 * p,
                    "{name}: pdf {p} vs {}",
                    s.pdf
                );
            }
        }
    }
}

/// H15 (smooth dielectric): the fraction of reflection choices matches F(θ) within 4
/// binomial standard errors, for η = 1.5 and 1/1.5 (beyond the critical angle: always).
#[test]
fn h15_dielectric_branch_fractions_match_fresnel() {
    for eta_scene in [1.5f32, 1.0 / 1.5] {
        let shader = Shader::Dielectric {
            ior: eta_scene,
            ior_out: 1.0,
            col: Vec3::ONE,
        };
        let bsdf = Bsdf::new(&shader, true).unwrap();
        for cos in [1.0f32, 0.9, 0.7, 0.5, 0.3, 0.1, 0.01] {
            let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let f = fr_dielectric(cos, eta_scene) as f64;
            let n = 200_000;
            let mut rng = Rng(99 + (cos * 1000.0) as u64);
            let mut reflected = 0usize;
            for _ in 0..n {
                let s = bsdf.sample(wo, rng.next_vec3()).unwrap();
                assert!(s.delta);
                if s.wi.z > 0.0 {
                    reflected += 1;
                    assert!((s.wi - Vec3::new(-wo.x, -wo.y, wo.z)).length() < 1e-6);
                    assert!((s.weight() - Vec3::ONE).abs().max_element() < 1e-4);
                } else {
                    // Radiance crossing into the other medium is scaled by 1/η².
                    let expect = 1.0 / (eta_scene * eta_scene);
                    assert!((s.weight().x - expect).abs() < 1e-4 * expect.max(1.0));
                }
            }
            let frac = reflected as f64 / n as f64;
            let se = (f * (1.0 - f) / n as f64).sqrt();
            assert!(
                (frac - f).abs() <= 4.0 * se + 1e-9,
                "η = {eta_scene}, cos = {cos}: reflected {frac}, Fresnel {f}"
            );
        }
    }
}

/// Mean of the throughput weight `f·|cos|/pdf` over stratified samples: an unbiased estimate
/// of the directional albedo (delta lobes included).
fn albedo(bsdf: &Bsdf, wo: Vec3, n: u32, seed: u32) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for i in 0..n {
        let mut s = stagelight::sampling::Sampler::new(seed, i);
        let u = Vec3::new(s.next_1d(), s.next_1d(), s.next_1d());
        if let Some(smp) = bsdf.sample(wo, u) {
            sum += smp.weight();
        }
    }
    sum / n as f32
}

/// H17: no material reflects more than it receives — albedo ≤ 1 + 1 % over 32 `wo` from
/// normal to cosθ = 0.01, including shaders whose weights add up to more than 1 (clamped).
#[test]
fn h17_albedo_at_most_one() {
    let mut mats = materials();
    mats.push((
        "phong_white",
        Shader::Phong {
            ambient: Vec3::ZERO,
            diffuse: Vec3::ZERO,
            specular: Vec3::ONE,
            spec_exp: 1.0,
        },
    ));
    mats.push((
        "metal_rough",
        Shader::Metal {
            ka: 1.0,
            ks: 1.0,
            roughness: 1.0,
            color: Vec3::ONE,
        },
    ));
    mats.push((
        "cook_torrance_rough",
        Shader::CookTorrance {
            ambient: Vec3::ZERO,
            diffuse: Vec3::ZERO,
            specular: Vec3::ONE,
            roughness: 1.0,
            ior: Vec3::splat(20.0),
        },
    ));
    mats.push((
        "overfull_dgs",
        Shader::Dgs {
            diffuse: Vec3::ONE,
            glossy: Vec3::ONE,
            specular: Vec3::ONE,
            shiny: 2.0,
        },
    ));
    mats.push(("mirror", Shader::Mirror { color: Vec3::ONE }));
    for (name, shader) in mats {
        let bsdf = Bsdf::new(&shader, true).unwrap();
        for k in 0..32 {
            let cos = if k == 31 {
                0.01
            } else {
                1.0 - k as f32 / 31.0 * 0.98
            };
            let phi = k as f32 * 0.7;
            let sin = (1.0 - cos * cos).sqrt();
            let wo = Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
            let a = albedo(&bsdf, wo, 16_384, k);
            assert!(
                a.max_element() <= 1.01,
                "{name} at cosθ = {cos}: albedo {a}"
            );
        }
    }
}

/// H17: the lossless smooth dielectric reflects plus transmits exactly what it receives
/// (transmitted radiance weights × η² undo the radiance scaling), for η and 1/η.
#[test]
fn h17_lossless_dielectric_conserves_energy() {
    for ior in [1.5f32, 1.0 / 1.5] {
        let bsdf = Bsdf::new(
            &Shader::Dielectric {
                ior,
                ior_out: 1.0,
                col: Vec3::ONE,
            },
            true,
        )
        .unwrap();
        for cos in [1.0f32, 0.6, 0.2, 0.01] {
            let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let total: f32 = bsdf
                .delta_branches(wo)
                .map(|b| b.weight.x * if b.transmits { ior * ior } else { 1.0 })
                .sum();
            assert!((total - 1.0).abs() < 1e-5, "ior {ior} cos {cos}: {total}");
        }
    }
}

/// H17: reflection lobes are reciprocal, f(wo, wi) = f(wi, wo) within 1e-5 relative.
#[test]
fn h17_reflection_lobes_are_reciprocal() {
    let mut rng = Rng(3);
    let dir = |rng: &mut Rng| {
        let u = rng.next_vec3();
        stagelight::sampling::sample_cosine_hemisphere(glam::Vec2::new(u.x, u.y))
    };
    for (name, shader) in materials() {
        let bsdf = Bsdf::new(&shader, true).unwrap();
        for _ in 0..20_000 {
            let (a, b) = (dir(&mut rng), dir(&mut rng));
            if a.z <= 1e-3 || b.z <= 1e-3 {
                continue;
            }
            let (fab, fba) = (bsdf.eval(a, b), bsdf.eval(b, a));
            let scale = fab.max_element().max(fba.max_element()).max(1e-6);
            assert!(
                (fab - fba).abs().max_element() <= 1e-5 * scale + 1e-7,
                "{name}: {fab} vs {fba}"
            );
        }
    }
}
