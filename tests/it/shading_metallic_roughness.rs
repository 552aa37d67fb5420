//! The glTF metallic-roughness BSDF (`Shader::MetallicRoughness`): χ² goodness of fit of its
//! sampling at several roughness/metallic values and `wo` (one Šidák family), sample values
//! equal to `eval`/`pdf`, albedo ≤ 1 (furnace) down to grazing `wo`, reciprocity, the smooth
//! metal equal to our mirror, and the rough dielectric close to Lambert.

use crate::common;

use common::chi2::{chi2_directions, sidak, Rng};
use glam::Vec3;
use stagelight::components::Shader;
use stagelight::shading::bsdf::Bsdf;

fn mr(base: f32, metallic: f32, roughness: f32) -> Shader {
    Shader::MetallicRoughness {
        base_color: Vec3::splat(base),
        metallic,
        roughness,
    }
}

fn materials() -> Vec<(&'static str, Shader)> {
    vec![
        ("dielectric_rough", mr(0.8, 0.0, 1.0)),
        ("dielectric_mid", mr(0.5, 0.0, 0.5)),
        ("half_metal", mr(0.9, 0.5, 0.5)),
        ("metal_mid", mr(0.9, 1.0, 0.6)),
    ]
}

fn wo_set() -> Vec<Vec3> {
    vec![
        Vec3::new(0.3, 0.1, 0.9).normalize(),
        Vec3::new(-0.6, 0.5, 0.5).normalize(),
        Vec3::new(0.8, 0.3, 0.05).normalize(),
    ]
}

/// χ² of the sampled directions against `pdf` for every material and `wo`.
#[test]
fn chi2_of_the_metallic_roughness_sampler() {
    let mats = materials();
    let wos = wo_set();
    let alpha = sidak(0.01, mats.len() * wos.len());
    let mut failures = Vec::new();
    for (m, (name, shader)) in mats.iter().enumerate() {
        let bsdf = Bsdf::new(shader, true).unwrap();
        for (k, &wo) in wos.iter().enumerate() {
            let outcome = chi2_directions(
                |u| {
                    let s = bsdf.sample(wo, u)?;
                    (!s.delta).then_some(s.wi)
                },
                |wi| bsdf.pdf(wo, wi) as f64,
                200_000,
                5000 + (m * 10 + k) as u64,
            );
            match outcome {
                Ok(o) if o.p_value >= alpha => {}
                Ok(o) => failures.push(format!("{name} wo={wo}: p = {:.3e} ({o:?})", o.p_value)),
                Err(e) => failures.push(format!("{name} wo={wo}: {e}")),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A sample's `f` and `pdf` are `eval` and `pdf` at its direction; `eval` is reciprocal.
#[test]
fn samples_match_eval_and_pdf_and_eval_is_reciprocal() {
    let mut rng = Rng(11);
    for (name, shader) in materials() {
        let bsdf = Bsdf::new(&shader, true).unwrap();
        for &wo in &wo_set() {
            for _ in 0..200 {
                let Some(s) = bsdf.sample(wo, rng.next_vec3()) else {
                    continue;
                };
                let f = bsdf.eval(wo, s.wi);
                let p = bsdf.pdf(wo, s.wi);
                assert!(
                    (s.f - f).abs().max_element() <= 1e-5 * f.max_element().max(1.0),
                    "{name}"
                );
                assert!((s.pdf - p).abs() <= 1e-4 * p.max(1.0), "{name}");
                assert!(
                    s.weight().is_finite() && s.weight().min_element() >= 0.0,
                    "{name}"
                );
                let back = bsdf.eval(s.wi, wo);
                assert!(
                    (back - f).abs().max_element() <= 1e-4 * f.max_element().max(1e-3),
                    "{name}: {f} vs {back}"
                );
            }
        }
    }
}

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

/// Furnace: no setting reflects more than it receives (1 % tolerance), from normal incidence
/// to cosθ = 0.01; a white rough metal loses little at normal incidence (≥ 0.9).
#[test]
fn albedo_at_most_one() {
    let mut mats = materials();
    mats.push(("white_metal_rough", mr(1.0, 1.0, 1.0)));
    mats.push(("white_metal_smoothish", mr(1.0, 1.0, 0.05)));
    mats.push(("white_dielectric_smoothish", mr(1.0, 0.0, 0.05)));
    mats.push(("white_dielectric_rough", mr(1.0, 0.0, 1.0)));
    mats.push(("grazing_half_metal", mr(0.9, 0.5, 0.4)));
    for (name, shader) in mats {
        let bsdf = Bsdf::new(&shader, true).unwrap();
        for k in 0..16 {
            let cos = if k == 15 {
                0.01
            } else {
                1.0 - k as f32 / 15.0 * 0.98
            };
            let sin = (1.0 - cos * cos).sqrt();
            let wo = Vec3::new(sin * (k as f32).cos(), sin * (k as f32).sin(), cos);
            let a = albedo(&bsdf, wo, 16_384, k);
            assert!(
                a.max_element() <= 1.01,
                "{name} at cosθ = {cos}: albedo {a}"
            );
        }
    }
    let metal = Bsdf::new(&mr(1.0, 1.0, 0.3), true).unwrap();
    let a = albedo(&metal, Vec3::Z, 16_384, 3);
    assert!(
        a.min_element() >= 0.9,
        "white metal at normal incidence: {a}"
    );
}

/// metallic = 1, roughness = 0 is our mirror (same lobes, same weights); a white
/// dielectric with roughness 0 is 96 % Lambert plus a 4 % mirror.
#[test]
fn the_smooth_metal_is_the_mirror() {
    let metal = Bsdf::new(&mr(1.0, 1.0, 0.0), true).unwrap();
    let mirror = Bsdf::new(&Shader::Mirror { color: Vec3::ONE }, true).unwrap();
    assert_eq!(metal, mirror);
    let dielectric = Bsdf::new(&mr(1.0, 0.0, 0.0), true).unwrap();
    let weights: Vec<Vec3> = dielectric.lobes().iter().map(|(w, _)| *w).collect();
    assert_eq!(weights, [Vec3::splat(0.96), Vec3::splat(0.04)]);
}

/// metallic = 0, roughness = 1: within 15 % of Lambert with the same base colour at every
/// pair of directions up to 60° (the documented difference: the Fresnel layer moves up to
/// 10 % from the diffuse to the specular term there).
#[test]
fn the_rough_dielectric_is_close_to_lambert() {
    let mrb = Bsdf::new(&mr(0.5, 0.0, 1.0), true).unwrap();
    let lambert = 0.5 / std::f32::consts::PI;
    let mut rng = Rng(3);
    for _ in 0..500 {
        let dir = |r: &mut Rng| {
            let cos = 0.5 + 0.5 * r.next_f32();
            let phi = std::f32::consts::TAU * r.next_f32();
            let sin = (1.0 - cos * cos).sqrt();
            Vec3::new(sin * phi.cos(), sin * phi.sin(), cos)
        };
        let (wo, wi) = (dir(&mut rng), dir(&mut rng));
        let f = mrb.eval(wo, wi).x;
        assert!(
            (f - lambert).abs() <= 0.15 * lambert,
            "{wo} {wi}: {f} vs {lambert}"
        );
    }
}

/// Just above the mirror threshold (roughness 0.05, α = 0.0025) a white metal behaves as the
/// mirror within noise: 95 % of the sampled directions lie within 2° of the mirror
/// direction (GGX: 98 % of half-vectors within 1° at this α) and the mean throughput weight
/// is within 3 % of the mirror's 1.
#[test]
fn a_nearly_smooth_metal_is_the_mirror_within_noise() {
    let bsdf = Bsdf::new(&mr(1.0, 1.0, 0.05), true).unwrap();
    for wo in [Vec3::Z, Vec3::new(0.6, 0.0, 0.8)] {
        let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
        let mut rng = Rng(21);
        let (mut sum, mut n, mut near) = (Vec3::ZERO, 0, 0);
        for _ in 0..20_000 {
            let Some(s) = bsdf.sample(wo, rng.next_vec3()) else {
                continue;
            };
            near += usize::from(s.wi.dot(mirror) > 2f32.to_radians().cos());
            sum += s.weight();
            n += 1;
        }
        assert!(
            near as f64 >= 0.95 * n as f64,
            "{wo}: {near} of {n} within 2°"
        );
        let mean = sum / n as f32;
        assert!(
            (mean - Vec3::ONE).abs().max_element() < 0.03,
            "{wo}: {mean}"
        );
    }
}
