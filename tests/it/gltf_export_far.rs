//! `bake scene.ron --write-gltf` of a scene far from the origin: a 1 cm patch floating over a
//! 1 m floor at x = 10⁶, where f32 steps by 1/16. The renderer rebases the scene (origin
//! (10⁶, 0, 0)) and bakes it in render space; the `.glb` keeps that shape by translating each
//! node by the scene origin and writing the traced render-space vertices
//! (`src/bake/gltf_translation.rs`). Before, every vertex was written in world space, the
//! patch's corners all rounded to x = 10⁶, and baking the written file failed (`the instance
//! has no triangles`).

use std::path::Path;

use glam::{DVec3, Vec3};

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// The scene: both instances bake what the glTF reader's default request bakes (lightmap
/// then AO, 64 rays, 4 positions per texel, on generated UVs here), the floor at the 64²
/// that default's 32 texels per unit gives it, so baking the written file again at the same
/// seed bakes the floor's AO bytes again. (The patch, 16² here, gets 1² from that density.)
const SCENE: &str = r#"Scene(
    options: (seed: 7),
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (1000000, -4, 4), target: (1000000, 0, 0), up: (0, 0, 1)))],
    lights: [(name: "lamp", kind: Point(position: (1000000.25, -0.25, 2)), intensity: 2.0)],
    materials: [(name: "w", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [
        (name: "patch", mesh: Inline(
            vertices: [(-0.005, -0.005, 0), (0.005, -0.005, 0), (0.005, 0.005, 0), (-0.005, 0.005, 0)],
            polygons: [[0, 1, 2, 3]]), material: "w"),
        (name: "floor", mesh: Inline(
            vertices: [(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0), (-0.5, 0.5, 0)],
            polygons: [[0, 1, 2, 3]]), material: "w"),
    ],
    instances: [
        (name: "p", of: "patch", transform: [Translate((1000000, 0, 0.004))],
         bake: (resolution: (16, 16), BAKE),
        (name: "f", of: "floor", transform: [Translate((1000000, 0, 0))],
         bake: (resolution: (64, 64), BAKE),
    ],
    groups: [(name: "world", members: ["p", "f"])],
    render: (root: "world", camera: "cam"),
)
"#;

/// The outputs of the glTF reader's default request, in RON.
const BAKE: &str = "uvs: Unwrap, outputs: [
            (kind: Lightmap(indirect: true, samples: 64, max_depth: 2,
                            store: IrradianceOverPi, scale: 0.5), format: Png8),
            (kind: AmbientOcclusion(samples: 64), format: Png8)])";

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// A scratch directory with the scene baked into `out/` (`out/scene.glb` written).
fn baked(name: &str) -> std::path::PathBuf {
    let dir = scratch_dir(name);
    std::fs::write(dir.join("scene.ron"), SCENE.replace("BAKE", BAKE)).unwrap();
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "out",
            "--write-gltf",
            "--threads",
            "2",
        ],
    );
    dir
}

/// Per node of the `.glb`: its name, its `translation` and its triangles as written
/// (corners in index order), with POSITION's `min` and `max`.
struct Node {
    name: String,
    translation: [f32; 3],
    triangles: Vec<[Vec3; 3]>,
    bounds: ([f32; 3], [f32; 3]),
}

fn nodes(path: &Path) -> Vec<Node> {
    let bytes = std::fs::read(path).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    glb.nodes()
        .map(|node| {
            let gltf::scene::Transform::Decomposed {
                translation,
                rotation,
                scale,
            } = node.transform()
            else {
                panic!("a translation, not a matrix");
            };
            assert_eq!((rotation, scale), ([0.0, 0.0, 0.0, 1.0], [1.0; 3]));
            let prim = node.mesh().unwrap().primitives().next().unwrap();
            let reader = prim.reader(|_| Some(&blob));
            let p: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
            let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            let box_ = prim.bounding_box();
            Node {
                name: node.name().unwrap().to_string(),
                translation,
                triangles: indices
                    .chunks(3)
                    .map(|t| [0, 1, 2].map(|k| p[t[k] as usize]))
                    .collect(),
                bounds: (box_.min, box_.max),
            }
        })
        .collect()
}

/// Both nodes are translated by the scene origin (10⁶, 0, 0); the patch's mesh is its
/// render-space corners (±0.005, ±0.005, 0.004), so translation + vertex (in f64) is each
/// world corner within f32's precision at the local coordinates (a few 10⁻¹⁰), where the
/// old file had all four at x = 10⁶ and y rounded to ±0.005 (2 degenerate triangles).
#[test]
fn a_centimetre_patch_far_from_the_origin_keeps_its_shape() {
    let dir = baked("gltf-export-far-patch");
    let nodes = nodes(&dir.join("out/scene.glb"));
    let names: Vec<&str> = nodes.iter().map(|n| n.name.as_str()).collect();
    assert_eq!(names, ["p", "f"]);
    for n in &nodes {
        assert_eq!(n.translation, [1000000.0, 0.0, 0.0], "{}", n.name);
    }
    let patch = &nodes[0];
    assert_eq!(patch.triangles.len(), 2);
    let t = DVec3::from(patch.translation.map(f64::from));
    let world = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, y)| DVec3::new(1000000.0 + 0.005 * x, 0.005 * y, 0.004));
    let mut matched = [false; 4];
    for corner in patch.triangles.iter().flatten() {
        let composed = t + corner.as_dvec3();
        let k = world
            .iter()
            .position(|w| {
                let local = *w - t;
                let error = (composed - *w).abs();
                (0..3).all(|a| error[a] <= local[a].abs() * 2f64.powi(-23))
            })
            .unwrap_or_else(|| panic!("{composed:?} is no corner of the patch"));
        matched[k] = true;
    }
    assert_eq!(matched, [true; 4], "every corner is written");
    let area: f64 = patch
        .triangles
        .iter()
        .map(|[a, b, c]| {
            let [a, b, c] = [a, b, c].map(|p| p.as_dvec3());
            (b - a).cross(c - a).length() / 2.0
        })
        .sum();
    assert!(
        (area - 1e-4).abs() < 1e-10,
        "the patch's area is 1 cm²: {area}"
    );
    assert_eq!(
        patch.bounds,
        ([-0.005, -0.005, 0.004], [0.005, 0.005, 0.004])
    );
    assert_eq!(nodes[1].bounds, ([-0.5, -0.5, 0.0], [0.5, 0.5, 0.0]));
    let _ = std::fs::remove_dir_all(&dir);
}

/// stagelight reads the written file back — its glTF reader composes node translation and
/// vertices in f64 and rebases the scene again — and bakes it (before: `error: bake request
/// on instance "p": the instance has no triangles`): the floor's AO, which the patch
/// shades, the same bytes as the RON bake; the patch's at the default request's 1×1.
#[test]
fn the_far_glb_bakes_again_to_the_same_ao() {
    let dir = baked("gltf-export-far-round-trip");
    ok(
        &dir,
        &[
            "bake",
            "out/scene.glb",
            "-o",
            "again",
            "--seed",
            "7",
            "--threads",
            "2",
        ],
    );
    assert!(
        std::fs::read(dir.join("out/f_ao.png")).unwrap()
            == std::fs::read(dir.join("again/f_ao.png")).unwrap(),
        "the floor's AO differs"
    );
    let floor = crate::common::png::read(&dir.join("out/f_ao.png"));
    assert!(
        (0..(floor.width * floor.height) as usize).any(|p| floor.rgba(p)[0] < 0.9),
        "the patch darkens the floor under it"
    );
    let patch = crate::common::png::read(&dir.join("again/p_ao.png"));
    assert_eq!((patch.width, patch.height), (1, 1));
    let _ = std::fs::remove_dir_all(&dir);
}
