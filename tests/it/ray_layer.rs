//! Ray-layer integration tests: watertightness through the full BVH (H3), BVH vs brute force
//! (H4), degenerate input (H6), invalid rays (H8), coincident faces (H9), and the obvhs
//! pitfalls (tmin clamp, fixed 32-entry stack, no instancing). Names follow
//! `/work/shared/HARDCASES.md`.

use crate::common;

use common::{
    height_field, mismatches, mismatches_all_qualities, soup, transform, triangles, uv_sphere, Rng,
};
use glam::{Affine3A, DVec3, Vec3};
use stagelight::accel::{brute_force_intersect, Accel, Ray};
use stagelight::settings::BvhQuality;

const QUALITIES: [BvhQuality; 3] = [BvhQuality::Fast, BvhQuality::Medium, BvhQuality::High];

fn ray(origin: Vec3, dir: Vec3) -> Ray {
    Ray {
        origin,
        dir,
        t_max: f32::INFINITY,
    }
}

/// Rays from inside a closed mesh: random direction, aimed exactly at a vertex, aimed at a
/// point on an edge. Returns the misses per kind.
fn leak_misses(verts: &[Vec3], idx: &[[u32; 3]], centre: DVec3, n: usize, seed: u64) -> [usize; 3] {
    let accel = Accel::build(triangles(verts, idx), BvhQuality::Medium);
    let mut rng = Rng::new(seed);
    let mut misses = [0; 3];
    for _ in 0..n {
        for (kind, miss) in misses.iter_mut().enumerate() {
            let o = (centre + rng.ball(0.5)).as_vec3();
            let target = match kind {
                0 => o + rng.sphere().as_vec3(),
                1 => verts[rng.below(verts.len())],
                _ => {
                    let t = idx[rng.below(idx.len())];
                    let e = rng.below(3);
                    let (a, b) = (verts[t[e] as usize], verts[t[(e + 1) % 3] as usize]);
                    a + (b - a) * rng.f64() as f32
                }
            };
            let r = ray(o, target - o);
            match accel.intersect(&r) {
                Some(h) if h.t > 0.0 && accel.occluded(&r) => {}
                _ => *miss += 1,
            }
        }
    }
    misses
}

#[test]
fn h03_leak_rate_uv_sphere_vertices_and_edges_zero_misses() {
    let mut rng = Rng::new(3);
    for centre in [
        DVec3::ZERO,
        DVec3::splat(1e5),
        DVec3::new(148376.0, 1234.0, -223423.0),
    ] {
        for (nu, nv, jitter, n) in [(64, 32, 0.0, 100_000), (256, 128, 0.3, 30_000)] {
            let (verts, idx) = uv_sphere(nu, nv, centre, 2.0, jitter, &mut rng);
            let misses = leak_misses(&verts, &idx, centre, n, nu as u64);
            assert_eq!(
                misses,
                [0, 0, 0],
                "centre {centre}, {nu}x{nv}, jitter {jitter}"
            );
        }
    }
}

#[test]
fn h03_leak_rate_micro_triangles_zero_misses() {
    // H7's variant: a 512×1024 sphere of radius 1e-3 (micro-triangles).
    let mut rng = Rng::new(7);
    let (verts, idx) = uv_sphere(1024, 512, DVec3::ZERO, 1e-3, 0.0, &mut rng);
    let accel = Accel::build(triangles(&verts, &idx), BvhQuality::Fast);
    let mut misses = 0;
    for _ in 0..20_000 {
        let o = rng.ball(2.5e-4).as_vec3();
        let target = verts[rng.below(verts.len())];
        misses += usize::from(accel.intersect(&ray(o, target - o)).is_none());
    }
    assert_eq!(misses, 0);
}

#[test]
fn h04_bvh_matches_brute_force_random_soup() {
    let mut rng = Rng::new(4);
    for offset in [0.0, 1e3, 1e5] {
        let c = Vec3::splat(offset);
        let tris = soup(2000, c, 10.0, 1.5, &mut rng);
        let mut rays = Vec::new();
        for _ in 0..2500 {
            let o = c + rng.ball(14.0).as_vec3();
            rays.push(ray(o, rng.sphere().as_vec3()));
            // Axis-aligned, with either sign of zero.
            let axis = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z][rng.below(6)];
            rays.push(ray(o, axis));
            rays.push(ray(o, axis * Vec3::new(1.0, -1.0, 1.0) + Vec3::splat(-0.0)));
            // Short segments.
            rays.push(Ray {
                origin: o,
                dir: rng.sphere().as_vec3(),
                t_max: 3.0,
            });
        }
        assert_eq!(mismatches_all_qualities(&tris, &rays), 0, "offset {offset}");
    }
}

#[test]
fn h04_bvh_matches_brute_force_height_field_on_node_boundaries() {
    // Vertices on a 0.25 grid, rays straight down through grid coordinates (node boundaries),
    // one ulp beside them, near-axis, and horizontal axis-aligned rays along grid lines.
    let mut rng = Rng::new(44);
    let n = 32;
    for offset in [0.0, 1e3, 1e5] {
        let off = Vec3::new(offset, offset, offset);
        let tris = height_field(n, 0.25, off);
        let mut rays = Vec::new();
        let mut down = Vec::new();
        let top = off.y + 10.0;
        for _ in 0..1500 {
            let (i, j) = (rng.below(n + 1), rng.below(n + 1));
            let (x, z) = (off.x + i as f32 * 0.25, off.z + j as f32 * 0.25);
            for (x, z) in [(x, z), (x.next_up(), z), (x, z.next_down()), (x + 0.125, z)] {
                for d in [
                    -Vec3::Y,
                    Vec3::new(1e-9, -1.0, 1e-9),
                    Vec3::new(-0.0, -1.0, 0.0),
                ] {
                    rays.push(ray(Vec3::new(x, top, z), d));
                    if i < n && j > 0 && j < n {
                        down.push(ray(Vec3::new(x, top, z), d));
                    }
                }
            }
            let y = off.y + rng.range(-1.5, 1.5) as f32;
            rays.push(ray(Vec3::new(off.x - 1.0, y, z), Vec3::X));
            rays.push(ray(Vec3::new(off.x + 9.0, y, z), -Vec3::X));
            rays.push(ray(Vec3::new(x, y, off.z - 1.0), Vec3::Z));
            rays.push(ray(Vec3::new(x, y, off.z + 9.0), -Vec3::Z));
        }
        assert_eq!(mismatches_all_qualities(&tris, &rays), 0, "offset {offset}");
        for q in QUALITIES {
            let accel = Accel::build(tris.clone(), q);
            // Straight down inside the field always hits (no gaps along node boundaries).
            for r in &down {
                assert!(accel.intersect(r).is_some(), "{r:?}");
            }
        }
    }
}

#[test]
fn h04_axis_aligned_flat_quads_zero_extent_boxes() {
    // Quads in the planes x = k, y = k, z = k: every leaf box has zero extent on one axis.
    let mut tris = Vec::new();
    for k in 0..8 {
        let k = k as f32 * 0.5;
        for (a, b, c, d) in [
            (
                Vec3::new(k, 0.0, 0.0),
                Vec3::new(k, 4.0, 0.0),
                Vec3::new(k, 4.0, 4.0),
                Vec3::new(k, 0.0, 4.0),
            ),
            (
                Vec3::new(0.0, k, 0.0),
                Vec3::new(4.0, k, 0.0),
                Vec3::new(4.0, k, 4.0),
                Vec3::new(0.0, k, 4.0),
            ),
            (
                Vec3::new(0.0, 0.0, k),
                Vec3::new(4.0, 0.0, k),
                Vec3::new(4.0, 4.0, k),
                Vec3::new(0.0, 4.0, k),
            ),
        ] {
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    let mut rng = Rng::new(5);
    let mut rays = Vec::new();
    for _ in 0..5000 {
        let grid = |rng: &mut Rng| rng.below(17) as f32 * 0.25;
        let o = Vec3::new(grid(&mut rng), grid(&mut rng), grid(&mut rng));
        for d in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
            rays.push(ray(o - d * 5.0, d));
            rays.push(ray(o, d));
        }
    }
    assert_eq!(mismatches_all_qualities(&tris, &rays), 0);
}

#[test]
fn h06_degenerate_and_nan_triangles_are_never_hit() {
    let mut rng = Rng::new(6);
    let (verts, idx) = uv_sphere(32, 16, DVec3::ZERO, 1.0, 0.0, &mut rng);
    let good = triangles(&verts, &idx);
    let mut tris = good.clone();
    let bad = [
        [Vec3::splat(0.1); 3],
        [
            Vec3::ZERO,
            Vec3::new(0.5, 0.5, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ],
        [Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X, Vec3::Y],
        [Vec3::new(0.0, f32::INFINITY, 0.0), Vec3::X, Vec3::Y],
        [
            Vec3::new(0.0, f32::NEG_INFINITY, 0.0),
            Vec3::new(f32::INFINITY, 0.0, 0.0),
            Vec3::Z,
        ],
    ];
    let first_bad = tris.len() as u32;
    tris.extend(bad);
    tris.push(good[3]); // a duplicate
    let accel = Accel::build(tris.clone(), BvhQuality::Medium);
    let reference = Accel::build(good.clone(), BvhQuality::Medium);
    assert_eq!(accel.stats().bvh_triangles, good.len() + 1);
    for _ in 0..100_000 {
        let r = ray(rng.ball(3.0).as_vec3(), rng.sphere().as_vec3());
        let h = accel.intersect(&r);
        if let Some(h) = h {
            assert!(!(first_bad..first_bad + bad.len() as u32).contains(&h.prim));
            assert!(h.t.is_finite() && h.b1.is_finite() && h.b2.is_finite());
        }
        // Same t as the scene without the bad triangles; the duplicate never wins (ties go
        // to the smaller index).
        assert_eq!(
            h.map(|h| (h.t, h.prim)),
            reference.intersect(&r).map(|h| (h.t, h.prim))
        );
    }
}

#[test]
fn h08_invalid_rays_return_no_hit() {
    let mut rng = Rng::new(8);
    let tris = soup(500, Vec3::ZERO, 2.0, 0.5, &mut rng);
    let accel = Accel::build(tris, BvhQuality::Fast);
    let specials = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        1e-40,
        f32::MAX,
        -1.0,
    ];
    for &a in &specials {
        for &b in &specials {
            for r in [
                Ray {
                    origin: Vec3::new(a, 0.0, b),
                    dir: Vec3::X,
                    t_max: f32::INFINITY,
                },
                Ray {
                    origin: Vec3::ZERO,
                    dir: Vec3::new(a, b, 0.0),
                    t_max: f32::INFINITY,
                },
                Ray {
                    origin: Vec3::ZERO,
                    dir: Vec3::new(1.0, a, 0.3),
                    t_max: b,
                },
            ] {
                if let Some(h) = accel.intersect(&r) {
                    assert!(h.t > 0.0 && h.t < r.t_max && h.t.is_finite(), "{r:?} {h:?}");
                }
                let _ = accel.occluded(&r);
            }
        }
    }
}

#[test]
fn h09_coincident_faces_resolve_to_smallest_index_for_every_quality() {
    let mut rng = Rng::new(9);
    let quad = [
        [
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 1.0),
        ],
        [
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(-1.0, 0.0, 1.0),
        ],
    ];
    let mut tris = soup(300, Vec3::new(0.0, 3.0, 0.0), 1.0, 0.3, &mut rng);
    tris.extend(quad);
    tris.extend(quad);
    tris.extend(quad.map(|t| [t[0], t[2], t[1]])); // opposite winding, same plane
    let rays: Vec<Ray> = (0..5000)
        .map(|_| {
            let o = Vec3::new(
                rng.range(-1.0, 1.0) as f32,
                -1.0,
                rng.range(-1.0, 1.0) as f32,
            );
            ray(o, Vec3::new(rng.range(-0.2, 0.2) as f32, 1.0, 0.0))
        })
        .collect();
    for q in QUALITIES {
        let accel = Accel::build(tris.clone(), q);
        assert_eq!(mismatches(&accel, &tris, &rays), 0, "{q:?}");
        for r in &rays {
            if let Some(h) = accel.intersect(r) {
                assert!(h.prim == 300 || h.prim == 301, "{h:?}");
            }
        }
    }
}

#[test]
fn obvhs_pitfall_tmin_hit_at_1e5_in_millimetre_scene() {
    // A millimetre-scale soup plus a triangle 1e-5 in front of the ray origin: obvhs's CWBVH
    // node test would cull that leaf (entry distance clamped at 1e-4).
    let mut rng = Rng::new(10);
    let mut tris = soup(400, Vec3::ZERO, 1e-3, 2e-4, &mut rng);
    let near = tris.len() as u32;
    tris.push([
        Vec3::new(-1e-4, -1e-4, 1e-5),
        Vec3::new(1e-4, -1e-4, 1e-5),
        Vec3::new(0.0, 1e-4, 1e-5),
    ]);
    for q in QUALITIES {
        let accel = Accel::build(tris.clone(), q);
        let r = ray(Vec3::ZERO, Vec3::Z);
        let h = accel.intersect(&r).expect("hit at t = 1e-5");
        assert_eq!(h.prim, near);
        assert!((h.t - 1e-5).abs() < 1e-11);
        assert!(accel.occluded(&Ray { t_max: 2e-5, ..r }));
        assert_eq!(accel.intersect(&r), brute_force_intersect(&tris, &r));
    }
}

#[test]
fn obvhs_pitfall_canary_own_cwbvh_traversal_misses_the_1e5_hit() {
    // Documents why the ray layer has its own kernel: obvhs 0.4's CWBVH traversal (with the
    // exact reciprocal already set) culls the one-triangle leaf at t = 1e-5. If this starts
    // failing, obvhs fixed the clamp; the own kernel stays correct either way.
    use obvhs::{
        cwbvh::builder::build_cwbvh_from_tris, ray::RayHit, triangle::Triangle, BvhBuildParams,
    };
    let mut rng = Rng::new(10);
    let mut tris = soup(400, Vec3::ZERO, 1e-3, 2e-4, &mut rng);
    tris.push([
        Vec3::new(-1e-4, -1e-4, 1e-5),
        Vec3::new(1e-4, -1e-4, 1e-5),
        Vec3::new(0.0, 1e-4, 1e-5),
    ]);
    let ot: Vec<Triangle> = tris
        .iter()
        .map(|t| Triangle {
            v0: t[0].into(),
            v1: t[1].into(),
            v2: t[2].into(),
        })
        .collect();
    let bvh = build_cwbvh_from_tris(
        &ot,
        BvhBuildParams::fastest_build(),
        &mut Default::default(),
    );
    let mut oray = obvhs::ray::Ray::new_inf(glam::Vec3A::ZERO, glam::Vec3A::Z);
    oray.inv_direction = glam::Vec3A::ONE / oray.direction;
    let mut hit = RayHit::none();
    bvh.ray_traverse(oray, &mut hit, |r, id| {
        ot[bvh.primitive_indices[id] as usize].intersect(r)
    });
    assert!(hit.t > 1e-4, "obvhs now finds the hit at {}", hit.t);
    let accel = Accel::build(tris, BvhQuality::Fast);
    assert!(accel
        .intersect(&ray(Vec3::ZERO, Vec3::Z))
        .is_some_and(|h| h.t < 2e-5));
}

/// Thousands of nested triangles around one point (every box contains the next) and thousands
/// of coincident ones: a hierarchy far deeper than obvhs's 32-entry traversal stack.
fn deep_scene() -> Vec<[Vec3; 3]> {
    let mut tris = Vec::new();
    for k in 0..3000 {
        let s = 1.003f32.powi(k);
        let z = k as f32 * 1e-3;
        tris.push([
            Vec3::new(-s, -s, z),
            Vec3::new(s, -s * 0.5, z),
            Vec3::new(0.0, s, z + s * 0.01),
        ]);
    }
    for _ in 0..2000 {
        tris.push([
            Vec3::new(-0.5, -0.5, 5.0),
            Vec3::new(0.5, -0.5, 5.0),
            Vec3::new(0.0, 0.5, 5.0),
        ]);
    }
    tris
}

#[test]
fn obvhs_pitfall_deep_hierarchy_neither_crashes_nor_loses_hits() {
    let tris = deep_scene();
    let mut rng = Rng::new(11);
    let mut rays = Vec::new();
    for _ in 0..1500 {
        let o = Vec3::new(
            rng.range(-3.0, 3.0) as f32,
            rng.range(-3.0, 3.0) as f32,
            -1.0,
        );
        rays.push(ray(
            o,
            Vec3::new(
                rng.range(-0.2, 0.2) as f32,
                rng.range(-0.2, 0.2) as f32,
                1.0,
            ),
        ));
        rays.push(ray(o + Vec3::Z * 8.0, rng.sphere().as_vec3()));
    }
    // PLOC (`Fast`, `High`) nests these boxes hundreds of levels deep; the binned-SAH
    // builder of `Medium` splits nested boxes by centroid and stays shallow. The heap stack
    // must be exercised by at least one quality, and every quality must answer exactly.
    let mut deepest = 0;
    for q in QUALITIES {
        let accel = Accel::build(tris.clone(), q);
        let depth = accel.stats().depth;
        eprintln!("{q:?}: depth {depth}, {} nodes", accel.stats().nodes);
        deepest = deepest.max(depth);
        assert_eq!(mismatches(&accel, &tris, &rays), 0, "{q:?}, depth {depth}");
    }
    assert!(
        deepest > 16,
        "scene not deep enough to exercise the heap stack: {deepest}"
    );
}

#[test]
fn obvhs_pitfall_no_instancing_flattened_instances_hit_exactly() {
    // The caller flattens instances into world space; the ray layer must trace the
    // transformed triangles exactly like brute force does.
    let mut rng = Rng::new(12);
    let (verts, idx) = uv_sphere(48, 24, DVec3::ZERO, 1.0, 0.2, &mut rng);
    let mesh = triangles(&verts, &idx);
    let mut world = Vec::new();
    let mut centres = Vec::new();
    for k in 0..6 {
        let scale = 10f32.powf(rng.range(-2.0, 2.0) as f32);
        let t = Vec3::new(k as f32 * 300.0, 1e4, -2e3) + rng.ball(50.0).as_vec3();
        let m = Affine3A::from_scale_rotation_translation(Vec3::splat(scale), rng.rotation(), t);
        world.extend(transform(&mesh, &m));
        centres.push((t, scale));
    }
    let accel = Accel::build(world.clone(), BvhQuality::Medium);
    let mut rays = Vec::new();
    for _ in 0..3000 {
        let (c, s) = centres[rng.below(centres.len())];
        // From inside an instance (must hit it), and from outside toward it.
        rays.push(ray(
            c + rng.ball(f64::from(s) * 0.5).as_vec3(),
            rng.sphere().as_vec3(),
        ));
        let o = c + rng.sphere().as_vec3() * s * 5.0;
        rays.push(ray(o, c + rng.ball(f64::from(s)).as_vec3() - o));
    }
    assert_eq!(mismatches(&accel, &world, &rays), 0);
    for r in rays.iter().step_by(2) {
        assert!(
            accel.intersect(r).is_some(),
            "ray from inside an instance escaped: {r:?}"
        );
    }
}

#[test]
fn build_stats_and_send_sync_tracing_from_threads() {
    let mut rng = Rng::new(13);
    let tris = soup(5000, Vec3::ZERO, 5.0, 0.5, &mut rng);
    let accel = Accel::build(tris.clone(), BvhQuality::Medium);
    let s = accel.stats();
    assert_eq!((s.triangles, s.bvh_triangles), (5000, 5000));
    assert!(s.nodes > 0 && s.build_seconds >= 0.0 && accel.build_seconds() == s.build_seconds);
    let rays: Vec<Ray> = (0..2000)
        .map(|_| ray(rng.ball(6.0).as_vec3(), rng.sphere().as_vec3()))
        .collect();
    let serial: Vec<_> = rays.iter().map(|r| accel.intersect(r)).collect();
    let parallel: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = rays
            .chunks(500)
            .map(|c| s.spawn(|| c.iter().map(|r| accel.intersect(r)).collect::<Vec<_>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    assert_eq!(serial, parallel);
}
