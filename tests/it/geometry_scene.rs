//! Geometry from RON scenes: every new mesh kind, approximation, displacement and scatter
//! loads into the components the geometry stages consume and generates the expected
//! triangles; bad parameters are located diagnostics; the stages run or skip with their
//! reasons through the CLI; a scatter renders identically at one and two threads.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Arc;

use glam::{Vec3, Vec4};
use hecs::{Entity, World};
use stagelight::components::{
    Approximation, DerivativeRequest, Displacement, DisplacementMode, GeneratedFrom, Grid,
    Instance, LengthSpace, MaterialRef, Name, NurbsSurface, Procedural, ScalarNode, Scatter,
    SourceLink, Sphere, Stairs, SubdivMesh, Surface, Technique, Torus, TriMesh, UvAxis,
    WorldFromObject,
};
use stagelight::frame::Frame;
use stagelight::scene::{load_scene, load_scene_str, LoadedScene};
use stagelight::schedule::run_stages;
use stagelight::settings::RenderSettings;
use stagelight::systems::STAGES;

/// A scene around `objects`, `instances` and the members of the root group `world`.
fn scene(objects: &str, instances: &str, members: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (16, 12),
               placement: LookAt(eye: (0, -6, 3), target: (0, 0, 0), up: (0, 0, 1)),
               outputs: [(file: "out.png")])],
    lights: [(name: "key", kind: Point(position: (2, -4, 5)), intensity: 30.0)],
    materials: [(name: "red", shader: Lambert(albedo: (0.8, 0.1, 0.1))),
                (name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [{objects}],
    instances: [{instances}],
    groups: [(name: "world", members: [{members}])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

fn load(text: &str) -> LoadedScene {
    load_scene_str(text, Path::new("inline.ron")).unwrap_or_else(|e| panic!("{e}"))
}

fn named(world: &World, name: &str) -> Entity {
    world
        .query::<(Entity, &Name)>()
        .iter()
        .find(|(_, n)| n.0 == name)
        .map(|(e, _)| e)
        .unwrap_or_else(|| panic!("no entity named {name}"))
}

/// Runs the two geometry stages and returns the frame (with its report).
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

/// Triangles of the object named `name` (after the stages).
fn triangles(world: &World, name: &str) -> usize {
    world
        .get::<&Arc<TriMesh>>(named(world, name))
        .map(|m| m.triangles.len())
        .unwrap_or_else(|_| panic!("{name} has no mesh"))
}

#[test]
fn geometry_shaders_load_as_components_with_pending_leaves() {
    let s = load(&scene(
        r#"(name: "donut", mesh: Torus(rmajor: 3, rminor: 1, phimin: -90, phimax: 180, thetamax: 270), material: "red"),
           (name: "ball", mesh: Sphere(radius: 2)),
           (name: "steps", mesh: Stairs(steps: 5, closed: true)),
           (name: "floor", mesh: Grid(size_x: 4, size_y: 2, nx: 8, ny: 4))"#,
        r#"(name: "d", of: "donut", transform: [Translate((1, 2, 3))]), (name: "b", of: "ball", material: "grey"),
           (name: "s", of: "steps"), (name: "f", of: "floor")"#,
        r#""d", "b", "s", "f""#,
    ));
    let w = &s.world;
    let proc = |name: &str| *w.get::<&Procedural>(named(w, name)).unwrap();
    assert_eq!(
        proc("donut"),
        Procedural::Torus(Torus {
            r_major: 3.0,
            r_minor: 1.0,
            phi_min: -90.0,
            phi_max: 180.0,
            theta_max: 270.0
        })
    );
    assert_eq!(
        proc("ball"),
        Procedural::Sphere(Sphere {
            radius: 2.0,
            z_min: -2.0,
            z_max: 2.0,
            theta_max: 360.0
        })
    );
    assert_eq!(
        proc("steps"),
        Procedural::Stairs(Stairs {
            steps: 5,
            width: 2.0,
            depth: 2.0,
            height: 2.0,
            closed: true
        })
    );
    assert_eq!(
        proc("floor"),
        Procedural::Grid(Grid {
            size_x: 4.0,
            size_y: 2.0,
            nx: 8,
            ny: 4
        })
    );
    let donut = named(w, "donut");
    assert_eq!(w.get::<&SourceLink>(donut).unwrap().line, 8);
    // The leaf: like a mesh instance, with an empty mesh until the stages fill it.
    let leaf = named(w, "world/d");
    let inst = w.get::<&Instance>(leaf).unwrap();
    assert_eq!(inst.object, donut);
    assert!(inst.mesh.triangles.is_empty());
    let xf = w.get::<&WorldFromObject>(leaf).unwrap().0;
    assert_eq!(xf.translation, Vec3::new(1.0, 2.0, 3.0).into());
    let material = w.get::<&MaterialRef>(leaf).unwrap().0;
    assert_eq!(w.get::<&Name>(material).unwrap().0, "red");
    assert!(w.get::<&SourceLink>(leaf).is_ok());
    let material = w.get::<&MaterialRef>(named(w, "world/b")).unwrap().0;
    assert_eq!(w.get::<&Name>(material).unwrap().0, "grey");
}

#[test]
fn stages_generate_the_expected_triangles_from_ron() {
    let mut s = load(&scene(
        r#"(name: "floor", mesh: Grid(nx: 3, ny: 2)),
           (name: "steps", mesh: Stairs(steps: 10)),
           (name: "quad", mesh: PatchMesh(nu: 2, nv: 2, points: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]),
            approximation: Parametric(u: 3, v: 2)),
           (name: "bspline", mesh: PatchMesh(basis: BSpline, nu: 5, nv: 4, points: [
               (0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0), (4, 0, 0),
               (0, 1, 0), (1, 1, 1), (2, 1, 1), (3, 1, 1), (4, 1, 0),
               (0, 2, 0), (1, 2, 1), (2, 2, 1), (3, 2, 1), (4, 2, 0),
               (0, 3, 0), (1, 3, 0), (2, 3, 0), (3, 3, 0), (4, 3, 0)]),
            approximation: Regular(u: 4, v: 2)),
           (name: "sheet", mesh: Nurbs(degree_u: 1, degree_v: 1, count_u: 2, count_v: 2,
               knots_u: [0, 0, 1, 1], knots_v: [0, 0, 1, 1],
               points: [(0, 0, 0, 1), (1, 0, 0, 1), (0, 1, 0, 1), (1, 1, 0, 2)]),
            approximation: Parametric(u: 2, v: 2)),
           (name: "cube", mesh: Subdiv(vertices: [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                                                  (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],
               polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [0, 4, 7, 3], [1, 2, 6, 5]]),
            approximation: Parametric(u: 1, v: 1))"#,
        r#"(name: "f", of: "floor"), (name: "s", of: "steps"), (name: "q", of: "quad"),
           (name: "b", of: "bspline"), (name: "n", of: "sheet"), (name: "c", of: "cube")"#,
        r#""f", "s", "q", "b", "n", "c""#,
    ));
    let w = &mut s.world;
    assert!(w.get::<&Surface>(named(w, "quad")).is_ok());
    assert!(w.get::<&SubdivMesh>(named(w, "cube")).is_ok());
    let nurbs: Surface = (*w.get::<&Surface>(named(w, "sheet")).unwrap()).clone();
    let Surface::Nurbs(NurbsSurface { points, .. }) = nurbs else {
        panic!("not a NURBS surface: {nurbs:?}");
    };
    assert_eq!(points[3], Vec4::new(1.0, 1.0, 0.0, 2.0));
    let frame = geometry_stages(w);
    let expand = frame.report.stage("expand_geometry").unwrap();
    assert_eq!(expand.reason, "2 geometry shader(s), 0 scatter(s)");
    let tess = frame.report.stage("tessellate").unwrap();
    assert_eq!(
        tess.reason,
        "3 surface(s), 1 subdivision mesh(es), 0 true displacement(s)"
    );
    assert_eq!(triangles(w, "floor"), 3 * 2 * 2);
    assert_eq!(triangles(w, "steps"), 10 * 2 * 2);
    assert_eq!(triangles(w, "quad"), 3 * 2 * 2);
    // 2 × 1 B-spline patches, regular 4 × 2 over the whole mesh: 2 × 2 segments each.
    assert_eq!(triangles(w, "bspline"), 2 * 2 * 2 * 2);
    assert_eq!(triangles(w, "sheet"), 2 * 2 * 2);
    // One Catmull-Clark level: 24 quads, each diced 1 × 1.
    assert_eq!(triangles(w, "cube"), 24 * 2);
    // Every leaf now carries its object's mesh, and the generator is recorded.
    for (leaf, object) in [("world/f", "floor"), ("world/c", "cube")] {
        let inst = w.get::<&Instance>(named(w, leaf)).unwrap();
        assert_eq!(inst.mesh.triangles.len(), triangles(w, object));
    }
    let gen = *w.get::<&GeneratedFrom>(named(w, "cube")).unwrap();
    assert_eq!(gen.generator, "subdiv");
}

#[test]
fn approximation_displacement_and_derivatives_become_components() {
    let mut s = load(&scene(
        r#"(name: "tube", mesh: Cylinder(radius: 0.5, z_min: 0, z_max: 2),
            approximation: Spatial(edge: 4, space: Raster, max_subdiv: 5),
            displacement: (shader: Sine(amplitude: 0.01, factor: 50), bound: 0.02),
            derivatives: true),
           (name: "tri", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]),
            approximation: Parametric(u: 2, v: 2),
            displacement: (shader: Sum([Constant(0.1), Noise(amplitude: 0.05, seed: 4)]))),
           (name: "bumpy", mesh: Inline(vertices: [(0, 0, 1), (1, 0, 1), (0, 1, 1)], polygons: [[0, 1, 2]]),
            displacement: (shader: Sine(amplitude: 0.01, factor: 20, axis: V), mode: Bump))"#,
        r#"(name: "t", of: "tube"), (name: "i", of: "tri"), (name: "b", of: "bumpy")"#,
        r#""t", "i", "b""#,
    ));
    let w = &mut s.world;
    let tube = named(w, "tube");
    assert_eq!(
        *w.get::<&Approximation>(tube).unwrap(),
        Approximation {
            technique: Technique::Spatial {
                edge: 4.0,
                space: LengthSpace::Raster
            },
            min_subdiv: 0,
            max_subdiv: 5
        }
    );
    assert_eq!(
        *w.get::<&Displacement>(tube).unwrap(),
        Displacement {
            shader: ScalarNode::Sine {
                amplitude: 0.01,
                factor: 50.0,
                axis: UvAxis::U
            },
            bound: Some(0.02),
            mode: DisplacementMode::True
        }
    );
    assert!(w.get::<&DerivativeRequest>(tube).is_ok());
    let tri = named(w, "tri");
    assert_eq!(
        w.get::<&Displacement>(tri).unwrap().shader,
        ScalarNode::Sum(vec![
            ScalarNode::Constant(0.1),
            ScalarNode::Noise {
                amplitude: 0.05,
                frequency: 1.0,
                octaves: 4,
                lacunarity: 2.0,
                gain: 0.5,
                seed: 4
            }
        ])
    );
    // The loaded triangle keeps its mesh until `tessellate` displaces it.
    assert_eq!(triangles(w, "tri"), 1);
    let frame = geometry_stages(w);
    assert_eq!(
        frame.report.stage("tessellate").unwrap().reason,
        "1 surface(s), 0 subdivision mesh(es), 2 true displacement(s)"
    );
    // Three bilinear quads, each diced 2 × 2.
    assert_eq!(triangles(w, "tri"), 3 * 2 * 2 * 2);
    assert!(
        w.get::<&Displacement>(tri).is_err(),
        "true displacement is consumed"
    );
    assert!(
        w.get::<&Displacement>(named(w, "bumpy")).is_ok(),
        "bump stays"
    );
    assert_eq!(triangles(w, "bumpy"), 1);
    assert!(w
        .get::<&stagelight::components::SurfaceDerivatives>(tube)
        .is_ok());
    assert!(s.located_warnings.is_empty(), "{:?}", s.located_warnings);
}

#[test]
fn scatter_copies_take_the_prototype_material_and_names() {
    let mut s = load(&scene(
        r#"(name: "pebble", mesh: Sphere(radius: 0.1), material: "red", approximation: Parametric(u: 2, v: 2)),
           (name: "ground", mesh: Grid(size_x: 2, size_y: 2, nx: 2, ny: 2), material: "grey"),
           (name: "pebbles", mesh: Scatter(prototype: "pebble", surface: "ground", count: 5, seed: 3,
                                           scale: (0.5, 2), rotation_jitter: 90, align_to_normal: false))"#,
        r#"(name: "g", of: "ground"), (name: "p", of: "pebbles", transform: [Translate((0, 0, 1))])"#,
        r#""g", "p""#,
    ));
    let w = &mut s.world;
    let (pebble, ground) = (named(w, "pebble"), named(w, "ground"));
    let scatter = *w.get::<&Scatter>(named(w, "pebbles")).unwrap();
    assert_eq!(
        scatter,
        Scatter {
            prototype: pebble,
            surface: ground,
            count: 5,
            seed: 3,
            scale_min: 0.5,
            scale_max: 2.0,
            rotation_jitter: 90.0,
            align_to_normal: false
        }
    );
    geometry_stages(w);
    let mut copies: Vec<(String, Entity, Entity)> = w
        .query::<(&Name, &Instance, &MaterialRef, &GeneratedFrom)>()
        .iter()
        .map(|(n, i, m, _)| (n.0.clone(), i.object, m.0))
        .collect();
    copies.sort();
    let names: Vec<&str> = copies.iter().map(|c| c.0.as_str()).collect();
    assert_eq!(
        names,
        [
            "world/p/0",
            "world/p/1",
            "world/p/2",
            "world/p/3",
            "world/p/4"
        ]
    );
    for (_, object, material) in &copies {
        assert_eq!(*object, pebble);
        assert_eq!(w.get::<&Name>(*material).unwrap().0, "red");
    }
    // The copies share the prototype's tessellated mesh.
    let n = triangles(w, "pebble");
    assert!(n > 0);
    for (i,) in w.query::<(&Instance,)>().iter() {
        if i.object == pebble {
            assert_eq!(i.mesh.triangles.len(), n);
        }
    }
}

// --- Located errors ---------------------------------------------------------------------

/// Asserts the full report of a fixture in `tests/fixtures/scenes/bad/geometry/`.
fn check(name: &str, expected: &[&str]) {
    let path = format!("tests/fixtures/scenes/bad/geometry/{name}");
    let errors = match load_scene(Path::new(&path)) {
        Ok(_) => panic!("{name} loaded without errors"),
        Err(e) => e,
    };
    let got: Vec<String> = errors.0.iter().map(ToString::to_string).collect();
    let expected: Vec<String> = expected
        .iter()
        .map(|e| format!("tests/fixtures/scenes/bad/geometry/{e}"))
        .collect();
    assert_eq!(got, expected, "\n--- {name} reported:\n{errors}\n");
}

#[test]
fn bad_torus_radius() {
    check(
        "torus_radius.ron",
        &["torus_radius.ron:4:58: error: object \"donut\" (torus): parameter `r_minor` = -1 is out of range (expected > 0)"],
    );
}

#[test]
fn unknown_approximation_variant_is_suggested() {
    check(
        "approximation_variant.ron",
        &["approximation_variant.ron:4:64: error: unknown variant \"Curvatur\" of Approximation\n  help: did you mean \"Curvature\"?"],
    );
}

#[test]
fn dangling_scatter_prototype_is_suggested() {
    check(
        "scatter_prototype.ron",
        &["scatter_prototype.ron:6:52: error: unknown prototype object \"pebbel\"\n  help: did you mean \"pebble\"?"],
    );
}

#[test]
fn negative_displacement_bound() {
    check(
        "displacement_bound.ron",
        &["displacement_bound.ron:5:75: error: object \"column\" (displacement): parameter `bound` = -0.02 is out of range (expected ≥ 0)"],
    );
}

/// A bad radius is reported once: not again through the `z_min`/`z_max` the user never wrote
/// (their defaults follow the radius).
#[test]
fn nan_sphere_radius_is_reported_once() {
    check(
        "sphere_nan_radius.ron",
        &["sphere_nan_radius.ron:4:45: error: radius must be a finite number, found NaN"],
    );
}

#[test]
fn nan_in_a_patch_control_point() {
    check(
        "patch_nan.ron",
        &["patch_nan.ron:5:55: error: control point must be a finite number, found NaN"],
    );
}

#[test]
fn scatter_over_a_surface_without_a_mesh() {
    check(
        "scatter_surface.ron",
        &["scatter_surface.ron:6:71: error: surface \"planet\" is a sphere: a scatter needs a polygon mesh (Obj, Ply, Inline, Grid or Stairs)"],
    );
}

#[test]
fn every_geometry_error_of_a_file_is_reported() {
    check(
        "several.ron",
        &[
            "several.ron:5:61: error: object \"bezier\" (patch mesh): u: Bézier patch meshes need 3·k + 1 points, found 5",
            "several.ron:12:45: error: object \"sheet\" (nurbs): v: expected 4 knots (count + degree + 1), found 3",
            "several.ron:14:58: error: object \"ball\" (sphere): parameter `theta_max` = 400 is out of range (expected (0, 360] degrees)",
            "several.ron:15:39: error: object \"ball\" (approximation): parameter `edge` = 0 is out of range (expected > 0)",
            "several.ron:17:23: error: object \"cube\" (subdiv): edge 0–1 is shared by more than two faces",
            "several.ron:18:63: error: min_subdiv (6) must not exceed max_subdiv (3)",
            "several.ron:19:55: error: object \"steps\" (stairs): parameter `width` = 0 is out of range (expected > 0)",
            "several.ron:20:100: error: amplitude must be a finite number, found inf",
            "several.ron:21:89: error: object \"pebbles\" (scatter): parameter `scale_max` = 1 is out of range (expected ≥ scale_min)",
            "several.ron:22:24: error: a scatter has no surface of its own to displace: displace the prototype",
        ],
    );
}

#[test]
fn a_scatter_cannot_be_baked() {
    let text = scene(
        r#"(name: "pebble", mesh: Sphere(radius: 0.1)),
           (name: "ground", mesh: Grid()),
           (name: "pebbles", mesh: Scatter(prototype: "pebble", surface: "ground"))"#,
        r#"(name: "p", of: "pebbles", bake: (resolution: (8, 8), outputs: [(kind: Positions)]))"#,
        r#""p""#,
    );
    let errors = load_scene_str(&text, Path::new("inline.ron"))
        .err()
        .unwrap();
    assert_eq!(
        errors.to_string(),
        "inline.ron:11:50: error: instance \"p\" places the scatter \"pebbles\", which has no surface of its own to bake\n  help: bake the scatter's surface object instead"
    );
}

// --- Through the CLI --------------------------------------------------------------------

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name)
}

fn scratch(test: &str) -> PathBuf {
    let dir =
        crate::common::scratch_root().join(format!("stagelight-geo-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn ok(o: Output) -> Output {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

/// `(ran, reason)` of the two geometry stages of a render with `--stats-json`.
fn geometry_reasons(scene: &Path, dir: &Path) -> [(bool, String); 2] {
    let json = dir.join("stats.json");
    ok(bin()
        .arg("render")
        .arg(scene)
        .arg("-o")
        .arg(dir.join("x.png"))
        .args(["--spp", "1", "--stats-json"])
        .arg(&json)
        .output()
        .unwrap());
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let stage = |name: &str| {
        let s = v["stages"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["stage"] == name)
            .unwrap();
        (
            s["ran"].as_bool().unwrap(),
            s["reason"].as_str().unwrap().to_string(),
        )
    };
    [stage("expand_geometry"), stage("tessellate")]
}

#[test]
fn stages_run_and_skip_with_their_reasons_from_ron_scenes() {
    let dir = scratch("reasons");
    let r = |ran: bool, reason: &str| (ran, reason.to_string());
    assert_eq!(
        geometry_reasons(&asset("stairs.ron"), &dir),
        [
            r(true, "4 geometry shader(s), 0 scatter(s)"),
            r(
                true,
                "1 surface(s), 0 subdivision mesh(es), 0 true displacement(s)"
            )
        ]
    );
    let grid = dir.join("grid.ron");
    std::fs::write(
        &grid,
        scene(
            r#"(name: "g", mesh: Grid(nx: 4, ny: 4))"#,
            r#"(name: "g1", of: "g")"#,
            r#""g1""#,
        ),
    )
    .unwrap();
    assert_eq!(
        geometry_reasons(&grid, &dir),
        [
            r(true, "1 geometry shader(s), 0 scatter(s)"),
            r(false, "no parametric surfaces or displacement")
        ]
    );
    let bump = dir.join("bump.ron");
    std::fs::write(
        &bump,
        scene(
            r#"(name: "t", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]),
                displacement: (shader: Constant(0.1), mode: Bump))"#,
            r#"(name: "t1", of: "t")"#,
            r#""t1""#,
        ),
    )
    .unwrap();
    assert_eq!(
        geometry_reasons(&bump, &dir),
        [
            r(false, "no procedural geometry"),
            r(
                false,
                "no parametric surfaces or true displacement (1 bump displacement(s) are left to shading)"
            )
        ]
    );
}

#[test]
fn scatter_scene_renders_identically_at_one_and_two_threads() {
    let dir = scratch("threads");
    let path = dir.join("scatter.ron");
    std::fs::write(
        &path,
        scene(
            r#"(name: "pebble", mesh: Sphere(radius: 0.2), material: "red", approximation: Curvature(distance: 0.005)),
               (name: "ground", mesh: Grid(size_x: 3, size_y: 3, nx: 3, ny: 3), material: "grey"),
               (name: "pebbles", mesh: Scatter(prototype: "pebble", surface: "ground", count: 40, seed: 11, scale: (0.5, 1.5)))"#,
            r#"(name: "g", of: "ground"), (name: "p", of: "pebbles")"#,
            r#""g", "p""#,
        ),
    )
    .unwrap();
    let mut files = Vec::new();
    for threads in ["1", "2"] {
        let out = dir.join(format!("scatter_{threads}.exr"));
        ok(bin()
            .arg("render")
            .arg(&path)
            .arg("-o")
            .arg(&out)
            .args(["--spp", "2", "--threads", threads])
            .output()
            .unwrap());
        files.push(std::fs::read(&out).unwrap());
    }
    assert!(files[0] == files[1], "EXR differs between thread counts");
}

#[test]
fn check_accepts_the_geometry_examples() {
    for name in [
        "stairs.ron",
        "displaced_cylinder.ron",
        "procedural_shapes.ron",
        "bake_ao.ron",
    ] {
        ok(bin().arg("check").arg(asset(name)).output().unwrap());
    }
}

/// An approximation that does nothing is a located warning at the setting, in the
/// documented `file:line:column: warning:` style ("a inline mesh" before, unlocated).
#[test]
fn an_approximation_without_effect_is_a_located_warning() {
    let dir = crate::common::scratch_dir("approx-warning");
    let object = r#"(name: "flat", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0)], polygons: [[0, 1, 2]]), material: "grey", approximation: Parametric(u: 4, v: 4)),"#;
    let scene = crate::common::small_scene(object, r#"(name: "f", of: "flat")"#, "", "");
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = crate::common::run_in(&dir, &["check", "scene.ron"]);
    assert!(o.status.success(), "{}", crate::common::stderr_of(&o));
    assert_eq!(
        crate::common::stderr_of(&o),
        "scene.ron:5:142: warning: object \"flat\": the approximation has no effect on an inline mesh without true displacement\n  help: leave `approximation` out: a polygon mesh is diced only for `displacement: (…, mode: True)`\n"
    );
}
