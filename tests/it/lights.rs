//! Area lights (rectangle, disc, sphere, cylinder): χ² goodness-of-fit of every shape's
//! sampler against the pdf its ray crossing reports (α = 0.01 with Šidák correction over all
//! configurations, grazing ones included), irradiance against closed forms and against an
//! independent quadrature over the hemisphere, end-to-end renders through both integrators,
//! `visible` lights, near/far attenuation, and coloured shadows through transparent objects.

use crate::common;

use std::f64::consts::PI;

use glam::{Affine3A, Vec2, Vec3};
use stagelight::accel::Ray;
use stagelight::components::{Emitter, LightShape, Shader};
use stagelight::settings::{Integrator, RenderSettings};
use stagelight::shading::Light;

use common::chi2::{chi2_directions_fine, sidak, Rng};

fn light(shape: LightShape, radiance: f32) -> Light {
    Light::from_emitter(&Emitter::new(shape, Vec3::splat(radiance)))
}

fn hit_pdf(l: &Light, p: Vec3, w: Vec3) -> f64 {
    let ray = Ray {
        origin: p,
        dir: w,
        t_max: f32::INFINITY,
    };
    l.hit(&ray, false).map_or(0.0, |(_, _, pdf)| pdf as f64)
}

/// Configurations: (name, shape, shading point). Normals of one-sided shapes face `p`.
fn configurations() -> Vec<(&'static str, LightShape, Vec3)> {
    vec![
        (
            "rect",
            LightShape::Rect {
                corner: Vec3::new(-1.0, -1.0, 1.0),
                edge_u: Vec3::new(0.0, 2.0, 0.0),
                edge_v: Vec3::new(2.0, 0.0, 0.0),
            },
            Vec3::new(0.2, 0.1, 0.0),
        ),
        (
            "rect grazing",
            LightShape::Rect {
                corner: Vec3::new(-1.0, -1.0, 1.0),
                edge_u: Vec3::new(0.0, 2.0, 0.0),
                edge_v: Vec3::new(2.0, 0.0, 0.0),
            },
            Vec3::new(2.5, 0.3, 0.77),
        ),
        (
            "disc",
            LightShape::Disc {
                center: Vec3::new(0.0, 0.0, 1.0),
                normal: Vec3::new(0.0, 0.0, -1.0),
                radius: 1.2,
            },
            Vec3::new(0.3, -0.2, 0.0),
        ),
        (
            "disc grazing",
            LightShape::Disc {
                center: Vec3::new(0.0, 0.0, 1.0),
                normal: Vec3::new(0.3, 0.0, -1.0),
                radius: 1.0,
            },
            Vec3::new(2.2, 0.4, 0.6),
        ),
        (
            "sphere near",
            LightShape::Sphere {
                center: Vec3::new(0.0, 0.0, 1.5),
                radius: 1.0,
            },
            Vec3::ZERO,
        ),
        (
            "sphere far",
            LightShape::Sphere {
                center: Vec3::new(1.2, 0.3, 2.5),
                radius: 0.8,
            },
            Vec3::new(-0.2, 0.1, 0.0),
        ),
        (
            "cylinder",
            LightShape::Cylinder {
                start: Vec3::new(-2.0, 0.0, 1.0),
                end: Vec3::new(2.0, 0.0, 1.3),
                radius: 0.5,
            },
            Vec3::new(0.3, 0.2, 0.0),
        ),
        (
            "cylinder close",
            LightShape::Cylinder {
                start: Vec3::new(0.0, -1.5, 0.5),
                end: Vec3::new(0.2, 1.5, 0.5),
                radius: 0.3,
            },
            Vec3::new(0.1, 0.4, 0.0),
        ),
    ]
}

/// Every area-light sampler draws directions with exactly the density its ray crossing
/// reports (the density MIS uses): χ² at α = 0.01, Šidák-corrected over all configurations.
#[test]
fn area_light_samplers_pass_chi_square() {
    let configs = configurations();
    let alpha = sidak(0.01, configs.len());
    for (k, (name, shape, p)) in configs.into_iter().enumerate() {
        let l = light(shape, 1.0);
        let outcome = chi2_directions_fine(
            |u| l.sample(p, Vec2::new(u.x, u.y), None).map(|s| s.wi),
            |w| hit_pdf(&l, p, w),
            200_000,
            0x1197 + k as u64,
            64,
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            outcome.p_value > alpha,
            "{name}: p = {} (dof {}), threshold {alpha}",
            outcome.p_value,
            outcome.dof
        );
        assert!(outcome.valid_fraction > 0.999, "{name}: {outcome:?}");
    }
}

/// Irradiance at `p` (normal `n`) estimated from `count` light samples.
fn sampled_irradiance(l: &Light, p: Vec3, n: Vec3, count: usize) -> f64 {
    let mut rng = Rng(7);
    let mut sum = 0.0;
    for _ in 0..count {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        if let Some(s) = l.sample(p, u, None) {
            sum += s.contribution.x as f64 * n.dot(s.wi).max(0.0) as f64;
        }
    }
    sum / count as f64
}

/// Irradiance at `p` (normal `n`) by jittered quadrature over the hemisphere in (cosθ, φ)
/// (one point per cell, so shape edges along grid lines cause no bias), using only the
/// lights' ray crossings: independent of the samplers.
fn quadrature_irradiance(l: &Light, p: Vec3, n: Vec3) -> f64 {
    let frame = stagelight::shading::frame::ShadingFrame::from_normal(n);
    let (nc, np) = (600, 1200);
    let (dc, dp) = (1.0 / nc as f64, 2.0 * PI / np as f64);
    let mut rng = Rng(99);
    let mut sum = 0.0;
    for i in 0..nc {
        for j in 0..np {
            let c = (i as f64 + rng.next_f32() as f64) * dc;
            let s = (1.0 - c * c).sqrt();
            let phi = (j as f64 + rng.next_f32() as f64) * dp;
            let w = frame.to_world(Vec3::new(
                (s * phi.cos()) as f32,
                (s * phi.sin()) as f32,
                c as f32,
            ));
            let ray = Ray {
                origin: p,
                dir: w,
                t_max: f32::INFINITY,
            };
            if let Some((_, le, _)) = l.hit(&ray, false) {
                sum += le.x as f64 * c;
            }
        }
    }
    sum * dc * dp
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Closed forms: a sphere of radius r at distance d straight above a point gives
/// `E = π L (r/d)²`; a disc of radius r at height h on the axis gives `E = π L r²/(r²+h²)`.
/// Light sampling and hemisphere quadrature both reproduce them.
#[test]
fn sphere_and_disc_irradiance_match_closed_forms() {
    let sphere = light(
        LightShape::Sphere {
            center: Vec3::new(0.0, 0.0, 2.0),
            radius: 0.5,
        },
        3.0,
    );
    let e_sphere = PI * 3.0 * (0.5f64 / 2.0).powi(2);
    let disc = light(
        LightShape::Disc {
            center: Vec3::new(0.0, 0.0, 1.0),
            normal: Vec3::new(0.0, 0.0, -1.0),
            radius: 0.5,
        },
        2.0,
    );
    let e_disc = PI * 2.0 * 0.25 / (0.25 + 1.0);
    for (name, l, e) in [("sphere", &sphere, e_sphere), ("disc", &disc, e_disc)] {
        let s = sampled_irradiance(l, Vec3::ZERO, Vec3::Z, 200_000);
        let q = quadrature_irradiance(l, Vec3::ZERO, Vec3::Z);
        assert!(rel(s, e) < 0.01, "{name}: sampled {s} vs {e}");
        assert!(rel(q, e) < 0.005, "{name}: quadrature {q} vs {e}");
    }
}

/// Every shape in every configuration: the light-sampling estimate of irradiance equals the
/// hemisphere quadrature over the shape's ray crossings within 1 % (the cylinder's closed
/// form is unwieldy; this checks it, and the grazing cases, all the same).
#[test]
fn sampled_irradiance_matches_quadrature_for_every_shape() {
    for (name, shape, p) in configurations() {
        let l = light(shape, 1.0);
        let n = Vec3::new(0.1, -0.2, 1.0).normalize();
        let s = sampled_irradiance(&l, p, n, 200_000);
        let q = quadrature_irradiance(&l, p, n);
        assert!(rel(s, q) < 0.01, "{name}: sampled {s} vs quadrature {q}");
    }
}

fn lit_plane(shape: LightShape, settings: RenderSettings) -> Vec<Vec3> {
    let mut world = hecs::World::new();
    let m = common::material(
        &mut world,
        Shader::Lambert {
            albedo: Vec3::splat(0.5),
        },
    );
    common::instance(&mut world, common::square(10.0), Affine3A::IDENTITY, m);
    common::light(&mut world, shape, Vec3::splat(3.0), 16);
    common::camera(&mut world, Vec3::new(0.0, -3.0, 1.0), Vec3::ZERO, 0.5, 4, 4);
    common::render(&mut world, settings)
        .outputs
        .image
        .unwrap()
        .beauty
}

fn mean_red(image: &[Vec3]) -> f64 {
    image.iter().map(|c| c.x as f64).sum::<f64>() / image.len() as f64
}

/// End to end: a Lambert plane under a sphere, a disc and a cylinder light renders
/// `albedo/π · E` in the direct integrator and in the path tracer (MIS of light samples and
/// BSDF-sampled rays crossing the light), within 1 %.
#[test]
fn renders_of_each_shape_match_the_irradiance() {
    let shapes = [
        LightShape::Sphere {
            center: Vec3::new(0.0, 0.0, 2.0),
            radius: 0.5,
        },
        LightShape::Disc {
            center: Vec3::new(0.0, 0.0, 1.0),
            normal: Vec3::new(0.0, 0.0, -1.0),
            radius: 0.5,
        },
        LightShape::Cylinder {
            start: Vec3::new(-1.0, 0.5, 1.0),
            end: Vec3::new(1.0, 0.0, 1.2),
            radius: 0.25,
        },
    ];
    for shape in shapes {
        let l = light(shape.clone(), 3.0);
        let expected = 0.5 / PI * quadrature_irradiance(&l, Vec3::ZERO, Vec3::Z);
        let direct = lit_plane(
            shape.clone(),
            RenderSettings {
                spp: 64,
                ..RenderSettings::default()
            },
        );
        let path = lit_plane(
            shape.clone(),
            RenderSettings {
                spp: 1024,
                max_depth: 1,
                integrator: Integrator::Path,
                ..RenderSettings::default()
            },
        );
        for (name, image) in [("direct", direct), ("path", path)] {
            let m = mean_red(&image);
            assert!(
                rel(m, expected) < 0.01,
                "{shape:?} {name}: {m} vs {expected}"
            );
        }
    }
}

/// Scene with a small sphere light straight ahead of the camera (and a speck of geometry
/// out of view so that rays are traced at all).
fn look_at_sphere_light(visible: bool, mirror: bool, integrator: Integrator) -> (Vec3, f32) {
    let mut world = hecs::World::new();
    let m = common::material(
        &mut world,
        Shader::Mirror {
            color: Vec3::new(0.8, 0.6, 0.4),
        },
    );
    let (eye, target, centre) = if mirror {
        common::instance(&mut world, common::square(10.0), Affine3A::IDENTITY, m);
        (
            Vec3::new(0.0, -3.0, 1.0),
            Vec3::ZERO,
            Vec3::new(0.0, 6.0, 2.0),
        )
    } else {
        common::instance(
            &mut world,
            common::square(0.01),
            Affine3A::from_translation(Vec3::new(50.0, 50.0, 50.0)),
            m,
        );
        (Vec3::new(0.0, -3.0, 1.0), Vec3::ZERO, Vec3::ZERO)
    };
    let mut e = Emitter::new(
        LightShape::Sphere {
            center: centre,
            radius: 0.5,
        },
        Vec3::splat(2.0),
    );
    e.visible = visible;
    world.spawn((stagelight::components::Name("l".into()), e));
    common::camera(&mut world, eye, target, 0.5, 2, 2);
    let settings = RenderSettings {
        spp: 4,
        integrator,
        ..RenderSettings::default()
    };
    let fb = common::render(&mut world, settings).outputs.image.unwrap();
    (fb.beauty[0], fb.alpha[0])
}

/// `visible: true` area lights appear to camera rays (radiance L, alpha 1) and in perfect
/// mirrors (colour × L) in both integrators; invisible ones appear in neither.
#[test]
fn visible_area_lights_are_seen_by_camera_and_mirror_rays() {
    for integrator in [Integrator::Direct, Integrator::Path] {
        let (c, a) = look_at_sphere_light(true, false, integrator);
        assert!((c - Vec3::splat(2.0)).abs().max_element() < 1e-5, "{c}");
        assert_eq!(a, 1.0);
        let (c, a) = look_at_sphere_light(false, false, integrator);
        assert_eq!((c, a), (Vec3::ZERO, 0.0));
        let (c, _) = look_at_sphere_light(true, true, integrator);
        let want = Vec3::new(0.8, 0.6, 0.4) * 2.0;
        assert!(
            (c - want).abs().max_element() < 1e-5,
            "{integrator:?} mirror: {c}"
        );
        let (c, _) = look_at_sphere_light(false, true, integrator);
        assert_eq!(c, Vec3::ZERO, "{integrator:?}: invisible light in a mirror");
    }
}

/// Point light at height 4 over a white Lambert plane, with transparent coloured squares
/// (`Opacity`) at the given heights between them; the camera looks at the plane's origin.
fn tinted_shadow(squares: &[f32], look_at: Vec3, integrator: Integrator) -> Vec3 {
    tinted_shadow_in(squares, look_at, integrator, None)
}

fn tinted_shadow_in(
    squares: &[f32],
    look_at: Vec3,
    integrator: Integrator,
    fog: Option<stagelight::components::Fog>,
) -> Vec3 {
    let mut world = hecs::World::new();
    let white = common::material(
        &mut world,
        Shader::Lambert {
            albedo: Vec3::splat(0.8),
        },
    );
    common::instance(&mut world, common::square(10.0), Affine3A::IDENTITY, white);
    let sheet = common::material(
        &mut world,
        Shader::Opacity {
            opacity: Vec3::new(0.5, 0.8, 0.9),
            input: Box::new(Shader::Lambert {
                albedo: Vec3::new(0.8, 0.1, 0.1),
            }),
        },
    );
    for &z in squares {
        common::instance(
            &mut world,
            common::square(0.5),
            Affine3A::from_translation(Vec3::new(0.0, 0.0, z)),
            sheet,
        );
    }
    common::light(
        &mut world,
        LightShape::Point {
            position: Vec3::new(0.0, 0.0, 4.0),
        },
        Vec3::splat(10.0),
        1,
    );
    let cam = common::camera(
        &mut world,
        look_at + Vec3::new(3.0, 0.0, 1.0),
        look_at,
        0.2,
        2,
        2,
    );
    if let Some(f) = fog {
        world
            .insert_one(cam, stagelight::components::Atmosphere(f))
            .unwrap();
    }
    let settings = RenderSettings {
        spp: 4,
        max_depth: 1,
        integrator,
        ..RenderSettings::default()
    };
    let image = common::render(&mut world, settings)
        .outputs
        .image
        .unwrap()
        .beauty;
    image.iter().sum::<Vec3>() / image.len() as f32
}

/// Coloured shadow: a red sheet letting `1 − opacity = (0.5, 0.2, 0.1)` through tints the
/// shadow of a point light to exactly `albedo/π · I/d² · (0.5, 0.2, 0.1)`; two sheets
/// multiply; outside the shadow the plane is untinted.
#[test]
fn transparent_coloured_objects_tint_shadows() {
    let lit = 0.8 / std::f32::consts::PI * 10.0 / 16.0;
    let t = Vec3::new(0.5, 0.2, 0.1);
    for integrator in [Integrator::Direct, Integrator::Path] {
        let one = tinted_shadow(&[2.0], Vec3::ZERO, integrator);
        let want = t * lit;
        assert!(
            ((one - want) / want).abs().max_element() < 1e-3,
            "{integrator:?}: {one} vs {want}"
        );
        let two = tinted_shadow(&[2.0, 3.0], Vec3::ZERO, integrator);
        let want = t * t * lit;
        assert!(
            ((two - want) / want).abs().max_element() < 1e-3,
            "{integrator:?}: {two} vs {want}"
        );
        // Outside the shadow (|x| > 1 on the ground): full light at distance √(1.5² + 4²).
        let p = Vec3::new(1.5, 0.0, 0.0);
        let outside = tinted_shadow(&[2.0], p, integrator);
        let d2 = 1.5f32 * 1.5 + 16.0;
        let want = 0.8 / std::f32::consts::PI * 10.0 * (4.0 / d2.sqrt()) / d2;
        assert!(
            ((outside - Vec3::splat(want)) / want).abs().max_element() < 2e-3,
            "{integrator:?}: {outside} vs {want}"
        );
    }
}

/// H18 for the new shapes: a disc (on its axis, closed form `π L r²/(r²+h²)`) and a sphere
/// (straight below, `π L (r/d)²`) from near to very far: 10⁶ light samples within
/// 0.5 % + 3 standard errors, every weight finite; a point in the disc's plane outside it and a
/// point inside the sphere receive exactly 0.
#[test]
fn h18_disc_and_sphere_from_near_to_far() {
    let estimate = |l: &Light, p: Vec3| {
        let mut rng = Rng(17);
        let n = 1_000_000;
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            let v = l.sample(p, u, None).map_or(0.0, |s| {
                assert!(s.contribution.is_finite() && s.pdf.is_finite());
                s.contribution.x as f64 * s.wi.z.max(0.0) as f64
            });
            sum += v;
            sum2 += v * v;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
        (mean, se)
    };
    let r = 0.5f32;
    for h in [0.1f32, 1.0, 10.0, 1000.0] {
        let h = h * r;
        let disc = light(
            LightShape::Disc {
                center: Vec3::new(0.0, 0.0, h),
                normal: Vec3::NEG_Z,
                radius: r,
            },
            2.0,
        );
        let want = PI * 2.0 * (r * r) as f64 / (r as f64 * r as f64 + h as f64 * h as f64);
        let (e, se) = estimate(&disc, Vec3::ZERO);
        assert!(
            (e - want).abs() <= 0.005 * want + 3.0 * se,
            "disc h = {h}: {e} ± {se} vs {want}"
        );
    }
    for d in [1.001f32, 1.1, 10.0, 1000.0] {
        let d = d * r;
        let sphere = light(
            LightShape::Sphere {
                center: Vec3::new(0.0, 0.0, d),
                radius: r,
            },
            2.0,
        );
        let want = PI * 2.0 * (r as f64 / d as f64).powi(2);
        let (e, se) = estimate(&sphere, Vec3::ZERO);
        assert!(
            (e - want).abs() <= 0.005 * want + 3.0 * se,
            "sphere d = {d}: {e} ± {se} vs {want}"
        );
    }
    let disc = light(
        LightShape::Disc {
            center: Vec3::ZERO,
            normal: Vec3::NEG_Z,
            radius: r,
        },
        2.0,
    );
    assert!(disc
        .sample(Vec3::new(2.0, 0.0, 0.0), Vec2::splat(0.3), None)
        .is_none());
    let sphere = light(
        LightShape::Sphere {
            center: Vec3::ZERO,
            radius: r,
        },
        2.0,
    );
    assert!(sphere
        .sample(Vec3::new(0.1, 0.0, 0.0), Vec2::splat(0.3), None)
        .is_none());
}

/// Near/far attenuation from a scene: a spot light 4 above a plane with `attenuation:
/// (2, 6)` gives the plane point below it `I/16 · (6 − 4)/(6 − 2)`: half the physical value.
#[test]
fn spot_attenuation_halves_light_midway_through_the_ramp() {
    let text = r#"Scene(
    options: (samples: 4, max_depth: 1),
    cameras: [(name: "cam", fov_y: 0.5, resolution: (2, 2),
        placement: LookAt(eye: (3, 0, 1), target: (0, 0, 0), up: (0, 0, 1)))],
    lights: [(name: "spot", kind: Spot(position: (0, 0, 4), target: (0, 0, 0), cone_angle: 40),
              intensity: 16, attenuation: (2, 6))],
    materials: [(name: "m", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Inline(vertices: [(-5, -5, 0), (5, -5, 0), (5, 5, 0), (-5, 5, 0)],
               polygons: [[0, 1, 2, 3]]), material: "m")],
    instances: [(name: "f", of: "floor")],
    groups: [(name: "world", members: ["f"])],
    render: (root: "world", camera: "cam"),
)"#;
    let mut scene =
        stagelight::scene::load_scene_str(text, std::path::Path::new("att.ron")).unwrap();
    let mut frame = stagelight::frame::Frame::new(scene.settings.clone());
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame).unwrap();
    let image = frame.outputs.image.unwrap().beauty;
    let got = mean_red(&image);
    let want = 0.5 / PI * 16.0 / 16.0 * 0.5;
    assert!(rel(got, want) < 1e-3, "{got} vs {want}");
}

/// Tinted shadows inside an absorbing atmosphere: the shadow ray is attenuated by the fog
/// over its length and tinted by the sheet: `lit · T · e^(−σ·4) · e^(−σ·√10)` (the last
/// factor for the camera segment).
#[test]
fn tinted_shadows_through_fog() {
    let fog = stagelight::components::Fog {
        sigma_a: Vec3::splat(0.1),
        sigma_s: Vec3::ZERO,
        g: 0.0,
        ..Default::default()
    };
    let lit = 0.8 / std::f32::consts::PI * 10.0 / 16.0;
    let t = Vec3::new(0.5, 0.2, 0.1);
    let want = t * lit * (-0.1f32 * 4.0).exp() * (-0.1f32 * 10f32.sqrt()).exp();
    for integrator in [Integrator::Direct, Integrator::Path] {
        let got = tinted_shadow_in(&[2.0], Vec3::ZERO, integrator, Some(fog));
        assert!(
            ((got - want) / want).abs().max_element() < 2e-3,
            "{integrator:?}: {got} vs {want}"
        );
    }
}
