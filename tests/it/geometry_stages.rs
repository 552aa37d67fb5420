//! The geometry stages on worlds built in code: run conditions and reasons, expansion into
//! instances that `build_accel` picks up, scatter, errors, determinism, and a ray-level leak
//! test of a displaced closed surface (HARDCASES H3/H13).

use crate::common;

use std::sync::Arc;

use glam::{Affine3A, Vec3};
use hecs::{Entity, World};
use stagelight::accel::{Accel, Ray};
use stagelight::components::{
    Approximation, DerivativeRequest, Displacement, DisplacementMode, GeneratedFrom, Grid,
    Instance, LengthSpace, MaterialRef, Name, Procedural, ScalarNode, Scatter, Shader, Sphere,
    Stairs, SurfaceDerivatives, Technique, Torus, TriMesh, UvAxis, WorldFromObject,
};
use stagelight::frame::Frame;
use stagelight::procedural::pending_instance;
use stagelight::procedural::scatter::hash01;
use stagelight::schedule::run_stages;
use stagelight::settings::{BvhQuality, RenderSettings};
use stagelight::systems::STAGES;

/// Runs only the two geometry stages.
fn geometry_stages(world: &mut World) -> Frame {
    let stages: Vec<_> = STAGES
        .iter()
        .copied()
        .filter(|s| s.name == "expand_geometry" || s.name == "tessellate")
        .collect();
    let mut frame = Frame::new(RenderSettings::default());
    run_stages(&stages, world, &mut frame).expect("geometry stages");
    frame
}

/// Spawns a generated object and one placed instance of it.
fn object(
    world: &mut World,
    name: &str,
    c: impl hecs::DynamicBundle,
    xf: Affine3A,
    m: Entity,
) -> Entity {
    let e = world.spawn(c);
    world.insert_one(e, Name(name.into())).unwrap();
    world.spawn((
        pending_instance(e),
        WorldFromObject(xf),
        MaterialRef(m),
        Name(format!("{name}_instance")),
    ));
    e
}

fn torus() -> Procedural {
    Procedural::Torus(Torus {
        r_major: 3.0,
        r_minor: 1.0,
        phi_min: 0.0,
        phi_max: 360.0,
        theta_max: 360.0,
    })
}

fn sine() -> Displacement {
    Displacement {
        shader: ScalarNode::Sine {
            amplitude: 0.01,
            factor: 50.0,
            axis: UvAxis::U,
        },
        bound: None,
        mode: DisplacementMode::True,
    }
}

#[test]
fn both_stages_skip_when_the_scene_does_not_ask_for_them() {
    let mut world = World::new();
    let m = common::material(&mut world, Shader::Lambert { albedo: Vec3::ONE });
    common::instance(&mut world, common::square(1.0), Affine3A::IDENTITY, m);
    let frame = geometry_stages(&mut world);
    let expand = frame.report.stage("expand_geometry").unwrap();
    assert!(!expand.ran);
    assert_eq!(expand.reason, "no procedural geometry");
    let tess = frame.report.stage("tessellate").unwrap();
    assert!(!tess.ran);
    assert_eq!(tess.reason, "no parametric surfaces or displacement");
    // Bump displacement alone needs no tessellation.
    let obj = world.spawn((
        Arc::new(common::square(1.0)),
        Displacement {
            mode: DisplacementMode::Bump,
            ..sine()
        },
    ));
    let frame = geometry_stages(&mut world);
    let tess = frame.report.stage("tessellate").unwrap();
    assert!(!tess.ran);
    assert_eq!(
        tess.reason,
        "no parametric surfaces or true displacement (1 bump displacement(s) are left to shading)"
    );
    assert!(
        world.get::<&Displacement>(obj).is_ok(),
        "bump data stays for shading"
    );
}

#[test]
fn geometry_shaders_expand_into_instances_that_build_accel_traces() {
    let mut world = World::new();
    let m = common::material(
        &mut world,
        Shader::Lambert {
            albedo: Vec3::splat(0.5),
        },
    );
    let t = object(
        &mut world,
        "torus",
        (torus(), Approximation::default(), DerivativeRequest),
        Affine3A::IDENTITY,
        m,
    );
    let s = object(
        &mut world,
        "stairs",
        (Procedural::Stairs(Stairs {
            steps: 10,
            width: 2.0,
            depth: 2.0,
            height: 2.0,
            closed: false,
        }),),
        Affine3A::from_translation(Vec3::new(6.0, 0.0, 0.0)),
        m,
    );
    common::camera(
        &mut world,
        Vec3::new(0.0, -12.0, 6.0),
        Vec3::ZERO,
        40.0,
        8,
        6,
    );
    let frame = common::render(
        &mut world,
        RenderSettings {
            spp: 1,
            ..RenderSettings::default()
        },
    );
    let expand = frame.report.stage("expand_geometry").unwrap();
    assert!(expand.ran);
    assert_eq!(expand.reason, "2 geometry shader(s), 0 scatter(s)");
    assert_eq!(expand.items, 40); // the stairs: 10 × (riser + tread) × 2 triangles
    let tess = frame.report.stage("tessellate").unwrap();
    assert!(
        tess.ran && tess.reason == "1 surface(s), 0 subdivision mesh(es), 0 true displacement(s)"
    );
    let torus_mesh = Arc::clone(&world.get::<&Arc<TriMesh>>(t).unwrap());
    assert_eq!(tess.items, torus_mesh.triangles.len() as u64);
    assert_eq!(
        *world.get::<&GeneratedFrom>(t).unwrap(),
        GeneratedFrom {
            source: t,
            generator: "torus"
        }
    );
    assert_eq!(
        world.get::<&SurfaceDerivatives>(t).unwrap().dpdu.len(),
        torus_mesh.positions.len()
    );
    assert!(
        world.get::<&Procedural>(s).is_err(),
        "the shader is consumed"
    );
    let build = frame.report.stage("build_accel").unwrap();
    assert!(build.ran);
    assert_eq!(build.items, tess.items + expand.items);
    // Both stages are now idle: running again changes nothing.
    let again = geometry_stages(&mut world);
    assert!(again.report.stages.iter().all(|s| !s.ran));
}

#[test]
fn scatter_places_seeded_copies_of_a_generated_prototype() {
    let build = || {
        let mut world = World::new();
        let m = common::material(&mut world, Shader::Lambert { albedo: Vec3::ONE });
        let ground = world.spawn((
            Name("ground".into()),
            Procedural::Grid(Grid {
                size_x: 10.0,
                size_y: 10.0,
                nx: 4,
                ny: 4,
            }),
        ));
        let pebble = world.spawn((
            Name("pebble".into()),
            Procedural::Sphere(Sphere {
                radius: 0.1,
                z_min: -0.1,
                z_max: 0.1,
                theta_max: 360.0,
            }),
            Approximation {
                technique: Technique::Parametric { u: 2, v: 2 },
                min_subdiv: 0,
                max_subdiv: 7,
            },
        ));
        let field = world.spawn((
            Name("field".into()),
            Scatter {
                prototype: pebble,
                surface: ground,
                count: 50,
                seed: 3,
                scale_min: 0.5,
                scale_max: 2.0,
                rotation_jitter: 180.0,
                align_to_normal: true,
            },
        ));
        world.spawn((
            pending_instance(field),
            WorldFromObject(Affine3A::from_translation(Vec3::Z)),
            MaterialRef(m),
            Name("field".into()),
        ));
        let frame = geometry_stages(&mut world);
        (world, frame, field)
    };
    let (world, frame, field) = build();
    let copies: Vec<(String, Arc<TriMesh>, Affine3A, GeneratedFrom)> = {
        let mut q = world.query::<(&Name, &Instance, &WorldFromObject, &GeneratedFrom)>();
        let mut v: Vec<_> = q
            .iter()
            .map(|(n, i, w, g)| (n.0.clone(), i.mesh.clone(), w.0, *g))
            .collect();
        v.sort_by(|a, b| a.0.cmp(&b.0));
        v
    };
    assert_eq!(copies.len(), 50);
    assert!(copies.iter().all(|c| c.3
        == GeneratedFrom {
            source: field,
            generator: "scatter"
        }));
    // The prototype was tessellated after expansion; its copies carry the final mesh.
    assert!(copies
        .iter()
        .all(|c| c.1.triangles.len() == 2 * 8 * 4 - 2 * 8));
    assert!(copies
        .iter()
        .all(|c| (c.2.translation.z - 1.0).abs() < 1e-6));
    assert_eq!(frame.report.stage("expand_geometry").unwrap().items, 2 * 16);
    let (world2, ..) = build();
    let mut q = world2.query::<(&Name, &WorldFromObject)>();
    let mut again: Vec<_> = q.iter().map(|(n, w)| (n.0.clone(), w.0)).collect();
    again.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(again.len(), 50);
    let placed: Vec<_> = again
        .into_iter()
        .filter(|(_, w)| w.translation.z != 0.0)
        .map(|x| x.1)
        .collect();
    assert_eq!(placed, copies.iter().map(|c| c.2).collect::<Vec<_>>());
}

#[test]
fn bad_parameters_and_missing_cameras_fail_with_the_object_name() {
    let mut world = World::new();
    let m = common::material(&mut world, Shader::Lambert { albedo: Vec3::ONE });
    object(
        &mut world,
        "donut",
        (Procedural::Torus(Torus {
            r_minor: -1.0,
            ..match torus() {
                Procedural::Torus(t) => t,
                _ => unreachable!(),
            }
        }),),
        Affine3A::IDENTITY,
        m,
    );
    let mut frame = Frame::new(RenderSettings::default());
    let err = stagelight::systems::run(&mut world, &mut frame).unwrap_err();
    assert_eq!(
        err.to_string(),
        "error: object \"donut\": torus: parameter `r_minor` = -1 is out of range (expected > 0)"
    );

    let mut world = World::new();
    let m = common::material(&mut world, Shader::Lambert { albedo: Vec3::ONE });
    let raster = Approximation {
        technique: Technique::Spatial {
            edge: 2.0,
            space: LengthSpace::Raster,
        },
        min_subdiv: 0,
        max_subdiv: 7,
    };
    object(&mut world, "ring", (torus(), raster), Affine3A::IDENTITY, m);
    let mut frame = Frame::new(RenderSettings::default());
    let err = stagelight::systems::run(&mut world, &mut frame).unwrap_err();
    assert_eq!(
        err.to_string(),
        "error: object \"ring\": the approximation measures edges in raster pixels but the scene has no render camera"
    );
}

#[test]
fn raster_approximation_is_view_dependent() {
    let triangles = |distance: f32| {
        let mut world = World::new();
        let m = common::material(&mut world, Shader::Lambert { albedo: Vec3::ONE });
        let raster = Approximation {
            technique: Technique::Spatial {
                edge: 4.0,
                space: LengthSpace::Raster,
            },
            min_subdiv: 0,
            max_subdiv: 9,
        };
        let t = object(&mut world, "ring", (torus(), raster), Affine3A::IDENTITY, m);
        common::camera(
            &mut world,
            Vec3::new(0.0, -distance, distance),
            Vec3::ZERO,
            40.0,
            320,
            240,
        );
        geometry_stages(&mut world);
        let n = world.get::<&Arc<TriMesh>>(t).unwrap().triangles.len();
        n
    };
    let (near, far) = (triangles(10.0), triangles(40.0));
    let ratio = near as f64 / far as f64;
    assert!(
        (8.0..25.0).contains(&ratio),
        "4× closer should give ≈ 16× the triangles: {near} / {far}"
    );
}

#[test]
fn displaced_closed_surface_does_not_leak_rays() {
    // A noise-displaced sphere, tessellated through the stage, traced from inside: every ray
    // aimed exactly at a vertex or at a point on an edge must hit the surface.
    let mut world = World::new();
    let m = common::material(&mut world, Shader::Lambert { albedo: Vec3::ONE });
    let noise = Displacement {
        shader: ScalarNode::Noise {
            amplitude: 0.08,
            frequency: 2.0,
            octaves: 3,
            lacunarity: 2.0,
            gain: 0.5,
            seed: 5,
        },
        bound: None,
        mode: DisplacementMode::True,
    };
    let approx = Approximation {
        technique: Technique::Curvature {
            distance: 2e-2,
            angle: 0.0,
        },
        min_subdiv: 0,
        max_subdiv: 7,
    };
    let ball = object(
        &mut world,
        "ball",
        (
            Procedural::Sphere(Sphere {
                radius: 1.0,
                z_min: -1.0,
                z_max: 1.0,
                theta_max: 360.0,
            }),
            noise,
            approx,
        ),
        Affine3A::IDENTITY,
        m,
    );
    geometry_stages(&mut world);
    let mesh = Arc::clone(&world.get::<&Arc<TriMesh>>(ball).unwrap());
    let tris: Vec<[Vec3; 3]> = (0..mesh.triangles.len())
        .map(|i| mesh.triangle(i))
        .collect();
    let accel = Accel::build(tris.clone(), BvhQuality::Medium);
    let rays_per_kind = 50_000u32;
    let mut leaks = [0u32; 2];
    for i in 0..rays_per_kind {
        let r = |d: u64| hash01(17, i as u64, d) as f32;
        // Origin uniform in the ball of radius 0.5 (rejection-free: cube root radius).
        let dir =
            Vec3::new(2.0 * r(0) - 1.0, 2.0 * r(1) - 1.0, 2.0 * r(2) - 1.0).normalize_or(Vec3::X);
        let origin = dir * 0.5 * r(3).cbrt();
        let tri = tris[(r(4) * tris.len() as f32) as usize % tris.len()];
        let vertex = tri[(r(5) * 3.0) as usize % 3];
        let k = (r(6) * 3.0) as usize % 3;
        let on_edge = tri[k].lerp(tri[(k + 1) % 3], r(7));
        for (kind, target) in [vertex, on_edge].into_iter().enumerate() {
            let ray = Ray {
                origin,
                dir: target - origin,
                t_max: f32::INFINITY,
            };
            if accel.intersect(&ray).is_none() {
                leaks[kind] += 1;
            }
        }
    }
    assert_eq!(
        leaks,
        [0, 0],
        "leaks (vertex-aimed, edge-aimed) of {rays_per_kind} rays each"
    );
}
