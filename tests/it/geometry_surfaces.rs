//! Tessellation accuracy, triangle counts, crack-freeness (bitwise edge maps) and
//! determinism, on surfaces built in code (HARDCASES H13).

use std::collections::HashMap;

use glam::{DVec3, Vec3};
use stagelight::components::{
    Approximation, CubicBasis, Displacement, DisplacementMode, LengthSpace, PatchKind, PatchMesh,
    Quadric, ScalarNode, Sphere, Stairs, SubdivMesh, Surface, Technique, Torus, TriMesh, UvAxis,
};
use stagelight::tessellation::{
    tessellate_mesh, tessellate_subdiv, tessellate_surface, Options, Tessellation,
};

fn approx(technique: Technique) -> Approximation {
    Approximation {
        technique,
        min_subdiv: 0,
        max_subdiv: 10,
    }
}

fn run(surface: &Surface, a: &Approximation, d: Option<&Displacement>) -> Tessellation {
    let opts = Options {
        approximation: a,
        displacement: d,
        view: None,
        derivatives: false,
        max_triangles: u64::MAX,
    };
    tessellate_surface(surface, &opts).expect("tessellates")
}

fn sphere(r: f32) -> Surface {
    Surface::Quadric(Quadric::Sphere(Sphere {
        radius: r,
        z_min: -r,
        z_max: r,
        theta_max: 360.0,
    }))
}

fn torus() -> Surface {
    Surface::Quadric(Quadric::Torus(Torus {
        r_major: 3.0,
        r_minor: 1.0,
        phi_min: 0.0,
        phi_max: 360.0,
        theta_max: 360.0,
    }))
}

/// Vertices, edge midpoints and centroids of every triangle (f64).
fn samples(m: &TriMesh) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(m.triangles.len() * 4);
    for i in 0..m.triangles.len() {
        let [a, b, c] = m.triangle(i).map(|p| p.as_dvec3());
        out.extend([
            a,
            (a + b) / 2.0,
            (b + c) / 2.0,
            (c + a) / 2.0,
            (a + b + c) / 3.0,
        ]);
    }
    out
}

fn max_distance(m: &TriMesh, dist: impl Fn(DVec3) -> f64) -> f64 {
    samples(m)
        .into_iter()
        .map(|p| dist(p).abs())
        .fold(0.0, f64::max)
}

fn sphere_distance(p: DVec3) -> f64 {
    p.length() - 1.0
}

fn torus_distance(p: DVec3) -> f64 {
    let ring = (p.x * p.x + p.y * p.y).sqrt() - 3.0;
    (ring * ring + p.z * p.z).sqrt() - 1.0
}

/// (edges used by one triangle only, edges used by more than two or unbalanced in
/// direction), keyed by bitwise vertex positions.
fn edge_defects(m: &TriMesh) -> (usize, usize) {
    let key = |p: Vec3| p.to_array().map(f32::to_bits);
    let mut edges: HashMap<([u32; 3], [u32; 3]), (u32, i32)> = HashMap::new();
    for i in 0..m.triangles.len() {
        let p = m.triangle(i);
        for k in 0..3 {
            let (a, b) = (key(p[k]), key(p[(k + 1) % 3]));
            let e = edges.entry((a.min(b), a.max(b))).or_default();
            e.0 += 1;
            e.1 += if a < b { 1 } else { -1 };
        }
    }
    let open = edges.values().filter(|e| e.0 == 1).count();
    let bad = edges
        .values()
        .filter(|e| e.0 > 2 || (e.0 == 2 && e.1 != 0))
        .count();
    (open, bad)
}

#[test]
fn sphere_and_torus_meet_the_curvature_tolerance() {
    for (surface, dist, size) in [
        (sphere(1.0), sphere_distance as fn(DVec3) -> f64, 1.0),
        (torus(), torus_distance as fn(DVec3) -> f64, 1.0),
    ] {
        for tol in [1e-1, 1e-2, 1e-3, 1e-4] {
            let a = approx(Technique::Curvature {
                distance: (tol * size) as f32,
                angle: 0.0,
            });
            let t = run(&surface, &a, None);
            let d = max_distance(&t.mesh, dist);
            assert!(
                d <= tol * size,
                "{}: tol {tol}: max distance {d}",
                surface.kind()
            );
        }
    }
}

#[test]
fn spatial_parametric_and_regular_meet_their_bounds() {
    // Spatial: edges ≤ L on a surface of largest curvature κ → distance ≤ κ·(√2·L)²/8.
    for (surface, dist, kappa) in [
        (sphere(1.0), sphere_distance as fn(DVec3) -> f64, 1.0),
        (torus(), torus_distance as fn(DVec3) -> f64, 1.0),
    ] {
        for edge in [0.4f64, 0.1, 0.025] {
            let a = approx(Technique::Spatial {
                edge: edge as f32,
                space: LengthSpace::Object,
            });
            let d = max_distance(&run(&surface, &a, None).mesh, dist);
            let bound = kappa * 2.0 * edge * edge / 8.0;
            assert!(d <= bound, "{}: edge {edge}: {d} > {bound}", surface.kind());
        }
    }
    // Parametric n per 90° patch and regular 4n over the sphere: the same mesh, with error
    // ≤ R·(1 − cos(√2·(π/2)/n / 2)) (half the cell diagonal angle).
    for n in [4u32, 16, 64] {
        let p = run(
            &sphere(1.0),
            &approx(Technique::Parametric { u: n, v: n }),
            None,
        );
        let r = run(
            &sphere(1.0),
            &approx(Technique::Regular { u: 4 * n, v: 2 * n }),
            None,
        );
        assert_eq!(p.mesh, r.mesh);
        let cell = std::f64::consts::FRAC_PI_2 / n as f64;
        let bound = 1.0 - (std::f64::consts::SQRT_2 * cell / 2.0).cos();
        let d = max_distance(&p.mesh, sphere_distance);
        let bound = bound + 1e-6; // f32 output positions
        assert!(d <= bound, "n {n}: {d} > {bound}");
        assert_eq!(
            p.mesh.triangles.len(),
            2 * (4 * n as usize) * (2 * n as usize) - 2 * 4 * n as usize
        );
    }
}

#[test]
fn triangle_count_grows_as_the_tolerance_predicts() {
    // Chord error ∝ h², so a quarter of the distance tolerance gives ≈ 4× the triangles, and
    // half the edge length ≈ 4× as well.
    let count = |t: Technique| run(&torus(), &approx(t), None).mesh.triangles.len() as f64;
    for tol in [1e-2f32, 1e-3] {
        let ratio = count(Technique::Curvature {
            distance: tol / 4.0,
            angle: 0.0,
        }) / count(Technique::Curvature {
            distance: tol,
            angle: 0.0,
        });
        assert!(
            (3.0..5.5).contains(&ratio),
            "curvature {tol}: ratio {ratio}"
        );
    }
    let ratio = count(Technique::Spatial {
        edge: 0.05,
        space: LengthSpace::Object,
    }) / count(Technique::Spatial {
        edge: 0.1,
        space: LengthSpace::Object,
    });
    assert!((3.0..5.5).contains(&ratio), "spatial: ratio {ratio}");
}

#[test]
fn adjacent_patches_of_different_rates_share_their_edge_bitwise() {
    // Two bicubic Bézier patches side by side (x < 0 and x > 0): the left one strongly bent,
    // the right one flat; they meet along x = 0 with a curved shared edge.
    let mut points = Vec::new();
    for j in 0..4 {
        let y = j as f32 / 3.0;
        for i in 0..7 {
            let x = (i as f32 - 3.0) / 3.0;
            let z = if i < 3 {
                ((i * 7 + j * 3) % 5) as f32 * 0.6
            } else {
                0.3 * y * y
            };
            points.push(Vec3::new(x, y, z));
        }
    }
    let mesh = Surface::Patches(PatchMesh {
        kind: PatchKind::Bicubic(CubicBasis::Bezier),
        nu: 7,
        nv: 4,
        u_wrap: false,
        v_wrap: false,
        points,
        vars: Default::default(),
    });
    let t = run(
        &mesh,
        &approx(Technique::Curvature {
            distance: 1e-3,
            angle: 0.0,
        }),
        None,
    )
    .mesh;
    let (left, right) = t.triangles.iter().fold((0, 0), |(l, r), tri| {
        let c: Vec3 = tri.iter().map(|&i| t.positions[i as usize]).sum::<Vec3>() / 3.0;
        if c.x < 0.0 {
            (l + 1, r)
        } else {
            (l, r + 1)
        }
    });
    assert!(
        left > 4 * right,
        "rates should differ: {left} vs {right} triangles"
    );
    // Every edge on the shared line x = 0 is used by exactly two triangles.
    let key = |p: Vec3| p.to_array().map(f32::to_bits);
    let mut shared: HashMap<_, u32> = HashMap::new();
    for i in 0..t.triangles.len() {
        let p = t.triangle(i);
        for k in 0..3 {
            let (a, b) = (p[k], p[(k + 1) % 3]);
            if a.x == 0.0 && b.x == 0.0 {
                *shared
                    .entry((key(a).min(key(b)), key(a).max(key(b))))
                    .or_default() += 1;
            }
        }
    }
    assert!(!shared.is_empty());
    assert!(
        shared.values().all(|&c| c == 2),
        "T-junctions on the shared edge"
    );
}

fn noise(amplitude: f32) -> Displacement {
    Displacement {
        shader: ScalarNode::Noise {
            amplitude,
            frequency: 3.0,
            octaves: 3,
            lacunarity: 2.0,
            gain: 0.5,
            seed: 11,
        },
        bound: None,
        mode: DisplacementMode::True,
    }
}

#[test]
fn closed_surfaces_stay_closed_after_tessellation_and_displacement() {
    let d = noise(0.05);
    for tol in [1e-1f32, 1e-2, 1e-3] {
        let a = approx(Technique::Curvature {
            distance: tol,
            angle: 0.0,
        });
        for (what, disp) in [("plain", None), ("displaced", Some(&d))] {
            for s in [sphere(1.0), torus()] {
                let m = run(&s, &a, disp).mesh;
                assert_eq!(edge_defects(&m), (0, 0), "{what} {} at {tol}", s.kind());
            }
        }
    }
    // Hard edges: closed stairs (split vertices per face) displaced with welded normals.
    let stairs = stagelight::procedural::stairs::stairs(&Stairs {
        steps: 4,
        width: 1.0,
        depth: 1.0,
        height: 1.0,
        closed: true,
    })
    .unwrap();
    let opts = Options {
        approximation: &approx(Technique::Spatial {
            edge: 0.05,
            space: LengthSpace::Object,
        }),
        displacement: Some(&d),
        view: None,
        derivatives: true,
        max_triangles: u64::MAX,
    };
    let m = tessellate_mesh(&stairs, &opts).unwrap();
    assert_eq!(edge_defects(&m.mesh), (0, 0), "displaced stairs");
    assert_eq!(m.derivatives.unwrap().dpdu.len(), m.mesh.positions.len());
    // Catmull-Clark cube, displaced.
    let m = tessellate_subdiv(&cube(), &opts).unwrap();
    assert_eq!(edge_defects(&m.mesh), (0, 0), "displaced subdivision cube");
}

fn cube() -> SubdivMesh {
    let positions = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32) - 0.5)
        .collect();
    let faces: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    SubdivMesh {
        positions,
        face_sizes: vec![4; 6],
        face_indices: faces.iter().flatten().copied().collect(),
        vars: Default::default(),
    }
}

#[test]
fn displaced_sphere_follows_the_analytic_surface() {
    // The seed's pattern over s on a sphere: the exact surface is r = 1 + a·sin(s·f·π).
    let d = Displacement {
        shader: ScalarNode::Sine {
            amplitude: 0.05,
            factor: 8.0,
            axis: UvAxis::U,
        },
        bound: None,
        mode: DisplacementMode::True,
    };
    let tol = 2e-3;
    let a = approx(Technique::Curvature {
        distance: tol as f32,
        angle: 0.0,
    });
    let m = run(&sphere(1.0), &a, Some(&d)).mesh;
    let plain = run(&sphere(1.0), &a, None).mesh;
    assert!(
        m.triangles.len() as f64 > 1.2 * plain.triangles.len() as f64,
        "displacement refines: {} vs {}",
        m.triangles.len(),
        plain.triangles.len()
    );
    let exact = |p: DVec3| {
        let s = p.y.atan2(p.x).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU;
        1.0 + 0.05 * (s * 8.0 * std::f64::consts::PI).sin()
    };
    // Away from the poles (where the pattern is singular), radial error ≤ tol.
    let err = samples(&m)
        .into_iter()
        .filter(|p| p.z.abs() < 0.9)
        .map(|p| (p.length() - exact(p)).abs())
        .fold(0.0, f64::max);
    assert!(err <= tol, "max radial error {err}");
    assert!(m
        .normals
        .as_ref()
        .unwrap()
        .iter()
        .all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-3));
}

#[test]
fn tessellation_is_deterministic_across_thread_counts() {
    let d = noise(0.05);
    let a = approx(Technique::Curvature {
        distance: 1e-3,
        angle: 5.0,
    });
    let go = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run(&torus(), &a, Some(&d)))
    };
    assert_eq!(go(1), go(2));
}
