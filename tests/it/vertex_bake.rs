//! Per-vertex bakes (`outputs: [(kind: …, target: Vertices)]`): ambient occlusion per vertex
//! against closed forms beside a wall, the PLY they are written to, the same bytes at any
//! thread count and through farm parts, `COLOR_0` of a baked glTF copy, and the scene
//! errors of what a per-vertex output cannot be.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

/// A PLY written by a per-vertex bake: the header's vertex properties and the raw records.
pub(crate) struct BakedPly {
    pub(crate) count: usize,
    properties: Vec<(String, usize)>,
    records: Vec<u8>,
    stride: usize,
    faces: usize,
}

impl BakedPly {
    pub(crate) fn read(path: &Path) -> BakedPly {
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let end = b"end_header\n";
        let at = bytes.windows(end.len()).position(|w| w == end).unwrap() + end.len();
        let header = std::str::from_utf8(&bytes[..at]).unwrap();
        assert!(header.starts_with("ply\nformat binary_little_endian 1.0\n"));
        let mut count = 0;
        let mut faces = 0;
        let mut properties = Vec::new();
        let mut in_vertex = false;
        for line in header.lines() {
            let words: Vec<&str> = line.split_whitespace().collect();
            match words.as_slice() {
                ["element", "vertex", n] => {
                    count = n.parse().unwrap();
                    in_vertex = true;
                }
                ["element", "face", n] => {
                    faces = n.parse().unwrap();
                    in_vertex = false;
                }
                ["property", ty, name] if in_vertex => {
                    let size = match *ty {
                        "float" => 4,
                        "uchar" => 1,
                        other => panic!("unexpected type {other}"),
                    };
                    properties.push((name.to_string(), size));
                }
                _ => {}
            }
        }
        let stride = properties.iter().map(|p| p.1).sum();
        BakedPly {
            count,
            properties,
            records: bytes[at..at + count * stride].to_vec(),
            stride,
            faces,
        }
    }

    fn offset(&self, name: &str) -> usize {
        let mut o = 0;
        for (n, size) in &self.properties {
            if n == name {
                return o;
            }
            o += size;
        }
        panic!("no property {name}");
    }

    pub(crate) fn float(&self, v: usize, name: &str) -> f32 {
        let o = v * self.stride + self.offset(name);
        f32::from_le_bytes(self.records[o..o + 4].try_into().unwrap())
    }

    fn byte(&self, v: usize, name: &str) -> u8 {
        self.records[v * self.stride + self.offset(name)]
    }
}

/// The scene: a wall at x = 0 (facing −x, 200 × 100 units) and, on the floor z = 0 at
/// x < 0, the instances given.
fn scene(objects: &str, instances: &str, names: &str) -> String {
    format!(
        r#"Scene(
    options: (seed: 3),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (4, 4),
               placement: LookAt(eye: (-3, 0, 2), target: (0, 0, 0)),
               outputs: [(file: "view.png")])],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "wall", mesh: Inline(
            vertices: [(0, -100, 0), (0, 100, 0), (0, 100, 100), (0, -100, 100)],
            polygons: [[0, 3, 2, 1]]), material: "grey"),
        {objects}
    ],
    instances: [(name: "wall_1", of: "wall"), {instances}],
    groups: [(name: "world", members: ["wall_1", {names}])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

/// A floor strip beside the wall: x ∈ [−1, 0], y ∈ [−1, 1], 2 × 2 cells (9 vertices, three
/// of them on the wall's foot).
const STRIP: &str = r#"(name: "strip", mesh: Inline(
            vertices: [(-1, -1, 0), (-0.5, -1, 0), (0, -1, 0), (-1, 0, 0), (-0.5, 0, 0),
                       (0, 0, 0), (-1, 1, 0), (-0.5, 1, 0), (0, 1, 0)],
            polygons: [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]]),
            material: "grey"),"#;

fn bake(dir: &Path, text: &str, out: &str, extra: &[&str]) {
    std::fs::write(dir.join("scene.ron"), text).unwrap();
    let mut args = vec!["bake", "scene.ron", "-o", out];
    args.extend_from_slice(extra);
    let o = run_in(dir, &args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// Every vertex of a floor beside a (practically infinite) wall sees the wall cover half of
/// its cosine-weighted hemisphere: AO ½ within 4σ, the vertices on the wall's foot too.
#[test]
fn vertex_ao_beside_a_wall_is_one_half() {
    let dir = scratch_dir("vertex-bake-half");
    let samples = 1024;
    let text = scene(
        STRIP,
        &format!(
            r#"(name: "strip_1", of: "strip", bake: (outputs: [
                (kind: AmbientOcclusion(samples: {samples}), target: Vertices)]))"#
        ),
        r#""strip_1""#,
    );
    std::fs::write(dir.join("scene.ron"), &text).unwrap();
    let o = run_in(&dir, &["bake", "scene.ron", "-o", "out", "--stats"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let report = String::from_utf8_lossy(&o.stdout).into_owned() + &stderr_of(&o);
    // The rays are the stage's: the AO rays' occlusion queries (9 × samples) and the
    // inside probe's closest hits.
    let stage_rays: u64 = report
        .lines()
        .find(|l| l.starts_with("bake_lightmaps"))
        .and_then(|l| l.split_whitespace().nth(6))
        .and_then(|r| r.parse().ok())
        .unwrap_or_default();
    assert!(stage_rays >= 9 * samples, "{report}");
    assert!(
        report.contains(&format!(
            "bake strip_1: 9 vertices, 9 baked, 0 invalid, 0 filled from neighbours, {stage_rays} rays"
        )),
        "{report}"
    );
    assert_eq!(dir_names(&dir.join("out")), ["strip_1_ao.ply"]);
    let ply = BakedPly::read(&dir.join("out/strip_1_ao.ply"));
    assert_eq!((ply.count, ply.faces), (9, 8));
    let sigma = (0.25f64 / samples as f64).sqrt();
    let mut sum = 0.0;
    for v in 0..ply.count {
        let ao = ply.float(v, "baked_r") as f64;
        assert!((ao - 0.5).abs() < 4.0 * sigma, "vertex {v}: AO {ao}");
        assert_eq!(ply.float(v, "baked_g") as f64, ao);
        assert_eq!(ply.byte(v, "red"), (ao * 255.0 + 0.5) as u8);
        sum += ao;
    }
    let mean = sum / ply.count as f64;
    assert!((mean - 0.5).abs() < 4.0 * sigma / 3.0, "mean AO {mean}");
    // The positions are the mesh's.
    assert_eq!(
        (ply.float(2, "x"), ply.float(2, "y"), ply.float(2, "z")),
        (0.0, -1.0, 0.0)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--stats-json` reports a per-vertex bake in vertices: `vertices` (the mesh's), and the
/// baked, invalid and neighbour-filled vertices, without the texture fields (`width`,
/// `height`, `texels_per_unit`, `covered_texels`: the grid the vertices are laid out on);
/// the stage counts vertices when every request is per vertex and both units when a texture
/// bake runs beside it.
#[test]
fn stats_json_reports_a_per_vertex_bake_in_vertices() {
    let dir = scratch_dir("vertex-bake-json");
    let strip = r#"(name: "strip_1", of: "strip", bake: (outputs: [
                (kind: AmbientOcclusion(samples: 4), target: Vertices)]))"#;
    let tile = r#"(name: "tile", mesh: Inline(
            vertices: [(-3, -1, 0), (-2, -1, 0), (-2, 1, 0), (-3, 1, 0)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]),
            material: "grey"),"#;
    let tile_1 = r#"(name: "tile_1", of: "tile", bake: (resolution: (4, 4), uvs: Mesh,
                outputs: [(kind: AmbientOcclusion(samples: 4))]))"#;
    let stats = |text: &str, out: &str| {
        let json = format!("{out}.json");
        bake(&dir, text, out, &["--stats-json", &json]);
        let v: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join(&json)).unwrap()).unwrap();
        let stage = v["stages"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["stage"] == "bake_lightmaps")
            .cloned()
            .unwrap();
        (
            v["bakes"].clone(),
            (stage["items"].clone(), stage["unit"].clone()),
        )
    };
    let keys = |bake: &serde_json::Value| -> Vec<String> {
        let mut keys: Vec<String> = bake.as_object().unwrap().keys().cloned().collect();
        keys.sort();
        keys
    };
    let (bakes, stage) = stats(&scene(STRIP, strip, r#""strip_1""#), "alone");
    let strip_json = &bakes[0];
    assert_eq!(
        keys(strip_json),
        [
            "baked_vertices",
            "files",
            "filled_vertices",
            "invalid_vertices",
            "name",
            "rays",
            "rays_per_second",
            "seconds",
            "vertices"
        ]
    );
    assert_eq!(
        (
            &strip_json["vertices"],
            &strip_json["baked_vertices"],
            &strip_json["invalid_vertices"],
            &strip_json["filled_vertices"]
        ),
        (&9.into(), &9.into(), &0.into(), &0.into())
    );
    assert_eq!(stage, (9.into(), "vertices".into()));
    let (bakes, stage) = stats(
        &scene(
            &format!("{STRIP}\n        {tile}"),
            &format!("{strip}, {tile_1}"),
            r#""strip_1", "tile_1""#,
        ),
        "mixed",
    );
    assert_eq!(keys(&bakes[0]), keys(strip_json));
    let texture = &bakes[1];
    assert_eq!(
        (
            &texture["width"],
            &texture["height"],
            &texture["covered_texels"]
        ),
        (&4.into(), &4.into(), &16.into())
    );
    assert!(texture.get("vertices").is_none(), "{texture}");
    assert_eq!(stage, (25.into(), "texels+vertices".into()));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A fan of four triangles on the floor around a vertex at the wall's foot (and two more
/// vertices there, each on one triangle): at every point of the floor beside the 200 × 100
/// wall, within 1 of it, AO is ½ + ½ · x / √(x² + 100²) ∈ [½, 0.505], so each vertex's
/// dual cell averages to ½ within 4σ + 0.005 — at 1 and at 4 sample positions, the counts
/// at which a slot's stratum fell exactly on a boundary between the cell's pieces and
/// every position of the vertex collapsed onto the vertex itself, in the wall's plane, where
/// no ray meets the wall (AO 1).
#[test]
fn vertex_ao_at_the_foot_of_a_wall_is_one_half_at_any_sample_count() {
    let dir = scratch_dir("vertex-bake-foot");
    let fan = r#"(name: "fan", mesh: Inline(
            vertices: [(0, 0, 0), (0, 1, 0), (-1, 1, 0), (-1, 0, 0), (-1, -1, 0), (0, -1, 0)],
            polygons: [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]]),
            material: "grey"),"#;
    let samples = 1024;
    let sigma = (0.25f64 / samples as f64).sqrt();
    for texel_samples in [1, 4] {
        let text = scene(
            fan,
            &format!(
                r#"(name: "fan_1", of: "fan", bake: (texel_samples: {texel_samples}, outputs: [
                (kind: AmbientOcclusion(samples: {samples}), target: Vertices)]))"#
            ),
            r#""fan_1""#,
        );
        let out = format!("out{texel_samples}");
        bake(&dir, &text, &out, &[]);
        let ply = BakedPly::read(&dir.join(out).join("fan_1_ao.ply"));
        assert_eq!(ply.count, 6);
        for v in 0..ply.count {
            let ao = ply.float(v, "baked_r") as f64;
            assert!(
                (ao - 0.5).abs() < 4.0 * sigma + 0.005,
                "{texel_samples} sample positions: vertex {v}: AO {ao}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// With `max_distance: R`, a point at distance x from the wall is occluded by the directions
/// whose horizontal component toward the wall exceeds x/R: AO = 1 − (acos a − a√(1−a²))/π,
/// a = x/R. Tiny triangles (1 mm) at x = 0.1 … 0.9 make each vertex a point.
#[test]
fn vertex_ao_with_a_distance_limit_matches_the_closed_form() {
    let dir = scratch_dir("vertex-bake-limit");
    let xs = [0.1, 0.3, 0.5, 0.7, 0.9];
    let mut vertices = Vec::new();
    let mut polygons = Vec::new();
    for (k, x) in xs.iter().enumerate() {
        let x = -x;
        vertices.push(format!(
            "({x}, 0, 0), ({}, 0, 0), ({x}, 0.001, 0)",
            x + 0.001
        ));
        polygons.push(format!("[{}, {}, {}]", 3 * k, 3 * k + 1, 3 * k + 2));
    }
    let objects = format!(
        r#"(name: "dots", mesh: Inline(vertices: [{}], polygons: [{}]), material: "grey"),"#,
        vertices.join(", "),
        polygons.join(", ")
    );
    let samples = 2048;
    let text = scene(
        &objects,
        &format!(
            r#"(name: "dots_1", of: "dots", bake: (outputs: [
                (kind: AmbientOcclusion(samples: {samples}, max_distance: 1.0), target: Vertices)]))"#
        ),
        r#""dots_1""#,
    );
    bake(&dir, &text, "out", &[]);
    let ply = BakedPly::read(&dir.join("out/dots_1_ao.ply"));
    for (k, x) in xs.iter().enumerate() {
        let a: f64 = *x;
        let expected = 1.0 - (a.acos() - a * (1.0 - a * a).sqrt()) / PI;
        let sigma = (expected * (1.0 - expected) / samples as f64).sqrt();
        for v in 3 * k..3 * k + 3 {
            let ao = ply.float(v, "baked_r") as f64;
            assert!(
                (ao - expected).abs() < 4.0 * sigma + 2e-3,
                "x = {x}: vertex {v} AO {ao}, expected {expected} (σ {sigma})"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Per-vertex bakes are the same bytes at any thread count and through farm parts, beside a
/// texture bake of the same request (each keeps its own files).
#[test]
fn vertex_bakes_are_deterministic_and_merge_from_parts() {
    let dir = scratch_dir("vertex-bake-parts");
    let text = scene(
        STRIP,
        r#"(name: "strip_1", of: "strip", bake: (resolution: (8, 8), outputs: [
                (kind: AmbientOcclusion(samples: 8), target: Vertices),
                (kind: AmbientOcclusion(samples: 8)),
                (kind: Normals(), target: Vertices)]))"#,
        r#""strip_1""#,
    );
    bake(&dir, &text, "one", &["--threads", "1"]);
    bake(&dir, &text, "three", &["--threads", "3"]);
    let names = dir_names(&dir.join("one"));
    assert_eq!(
        names,
        ["strip_1_ao.exr", "strip_1_ao.ply", "strip_1_normals.ply"]
    );
    let read = |sub: &str, name: &str| std::fs::read(dir.join(sub).join(name)).unwrap();
    for name in &names {
        assert!(read("one", name) == read("three", name), "{name} differs");
    }
    for k in 1..=3 {
        let part = format!("{k}/3");
        bake(&dir, &text, "parts", &["--part", &part]);
    }
    let o = run_in(
        &dir,
        &[
            "merge",
            "parts/bake_part_1_of_3.exr",
            "parts/bake_part_2_of_3.exr",
            "parts/bake_part_3_of_3.exr",
            "-o",
            "merged",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    for name in &names {
        assert!(
            read("one", name) == read("merged", name),
            "{name} differs after merging"
        );
    }
    // World normals of the floor: straight up, shown as (128, 128, 255).
    let ply = BakedPly::read(&dir.join("one/strip_1_normals.ply"));
    assert_eq!(ply.float(4, "baked_b"), 1.0);
    assert_eq!(
        (
            ply.byte(4, "red"),
            ply.byte(4, "green"),
            ply.byte(4, "blue")
        ),
        (128, 128, 255)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A glTF primitive without `TEXCOORD_1` bakes AO per vertex by default, and `--write-gltf`
/// makes it the primitive's `COLOR_0` in the copy (one float RGB per vertex, the PLY's
/// values), each of the three nodes sharing the mesh with its own copy; the copy writes
/// no empty top-level array.
#[test]
fn a_baked_glb_carries_vertex_ao_as_color_0() {
    let dir = scratch_dir("vertex-bake-gltf");
    let source =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/gltf/hierarchy.glb");
    let o = run_in(
        &dir,
        &[
            "bake",
            source.to_str().unwrap(),
            "-o",
            "out",
            "--write-gltf",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let names = dir_names(&dir.join("out"));
    let plys: Vec<&String> = names.iter().filter(|n| n.ends_with("_ao.ply")).collect();
    assert_eq!(plys.len(), 3, "{names:?}");
    let bytes = std::fs::read(dir.join("out/hierarchy.glb")).unwrap();
    // glTF requires a defined array to hold at least one item (the Khronos validator's
    // EMPTY_ENTITY): no bake made a texture, so the copy has no `images` (nor `textures`).
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let empty: Vec<&String> = json
        .as_object()
        .unwrap()
        .iter()
        .filter(|(_, v)| v.as_array().is_some_and(|a| a.is_empty()))
        .map(|(k, _)| k)
        .collect();
    assert!(empty.is_empty(), "empty top-level arrays: {empty:?}");
    assert!(json.get("images").is_none() && json.get("textures").is_none());
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    let mut checked = 0;
    for ply_name in plys {
        let instance = ply_name.trim_end_matches("_ao.ply");
        let ply = BakedPly::read(&dir.join("out").join(ply_name));
        let node = glb
            .nodes()
            .find(|n| n.name() == Some(instance))
            .unwrap_or_else(|| panic!("a node for {instance}"));
        let prim = node.mesh().unwrap().primitives().next().unwrap();
        let colors = prim.get(&gltf::Semantic::Colors(0)).expect("COLOR_0");
        assert_eq!(colors.count(), ply.count);
        assert_eq!(colors.data_type(), gltf::accessor::DataType::F32);
        let view = colors.view().unwrap();
        let start = view.offset() + colors.offset();
        for v in 0..ply.count {
            let at = start + v * 12;
            let r = f32::from_le_bytes(blob[at..at + 4].try_into().unwrap());
            assert_eq!(r, ply.float(v, "baked_r").clamp(0.0, 1.0));
            checked += 1;
        }
    }
    assert!(checked > 0);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Vertices the bake cannot sample keep their place and get a value
/// (`tests/fixtures/gltf/loose_vertices.glb`, an L of two quads): vertex 8, at vertex 2's
/// position and used only by the degenerate triangle (8, 8, 1) the loader drops, gets
/// vertex 2's value; vertex 9, on no triangle, the value of the nearest vertex (6). The PLY
/// and the copy's `COLOR_0` keep the file's 10 vertices in its order (before, both got 0).
#[test]
fn loose_vertices_keep_their_place_and_take_the_nearest_value() {
    let dir = scratch_dir("vertex-bake-loose");
    let source =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/gltf/loose_vertices.glb");
    let o = run_in(
        &dir,
        &[
            "bake",
            source.to_str().unwrap(),
            "-o",
            "out",
            "--write-gltf",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let ply = BakedPly::read(&dir.join("out/L_ao.ply"));
    assert_eq!((ply.count, ply.faces), (10, 4));
    // The fixture's POSITION, in order (scripts/make_gltf_fixtures.py).
    let positions = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.0, 2.0, 0.0],
        [0.0, 2.0, 2.0],
        [0.0, 0.0, 2.0],
        [2.0, 2.0, 0.0],
        [0.1f32, 2.2, 2.3],
    ];
    for (v, p) in positions.iter().enumerate() {
        assert_eq!(
            [ply.float(v, "x"), ply.float(v, "y"), ply.float(v, "z")],
            *p
        );
    }
    let ao: Vec<f32> = (0..10).map(|v| ply.float(v, "baked_r")).collect();
    assert!(ao[..8].iter().all(|&a| a > 0.5 && a < 1.0), "{ao:?}");
    assert_eq!(ao[8], ao[2]);
    assert_eq!(ao[9], ao[6]);
    let copy = std::fs::read(dir.join("out/loose_vertices.glb")).unwrap();
    let glb = gltf::Gltf::from_slice(&copy).unwrap();
    let blob = glb.blob.clone().unwrap();
    let prim = glb.meshes().last().unwrap().primitives().next().unwrap();
    let colors = prim.get(&gltf::Semantic::Colors(0)).expect("COLOR_0");
    assert_eq!(colors.count(), 10);
    let start = colors.view().unwrap().offset() + colors.offset();
    for (v, a) in ao.iter().enumerate() {
        let at = start + v * 12;
        assert_eq!(f32::from_le_bytes(blob[at..at + 4].try_into().unwrap()), *a);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// What a per-vertex output cannot be is a located scene error.
#[test]
fn per_vertex_outputs_refuse_texture_only_settings() {
    let dir = scratch_dir("vertex-bake-errors");
    let cases = [
        (
            "(kind: AmbientOcclusion(), format: Png8, target: Vertices)",
            "`target: Vertices` writes a PLY with vertex colours; leave `format` out (or write `format: Ply`)",
        ),
        (
            "(kind: AmbientOcclusion(bent_normals: true), target: Vertices)",
            "bent normals are baked into a texture only; bake them in an output without `target: Vertices`",
        ),
        (
            "(kind: Normals(space: Tangent), target: Vertices)",
            "tangent-space normals need a texture's tangent frame; bake `space: World` per vertex",
        ),
        (
            "(kind: AmbientOcclusion(), format: Ply)",
            "`format: Ply` is the format of per-vertex bakes: add `target: Vertices`, or write the texture as Exr, Png8 or Png16",
        ),
    ];
    assert_refused(&dir, &cases);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Each bake's `outputs: [OUTPUT]` is refused with its message, located in scene.ron, and
/// nothing is written.
fn assert_refused(dir: &std::path::Path, cases: &[(&str, &str)]) {
    for &(output, message) in cases {
        let text = scene(
            STRIP,
            &format!(
                r#"(name: "strip_1", of: "strip", bake: (resolution: (4, 4), outputs: [{output}]))"#
            ),
            r#""strip_1""#,
        );
        std::fs::write(dir.join("scene.ron"), text).unwrap();
        let o = run_in(dir, &["bake", "scene.ron", "-o", "out"]);
        assert!(!o.status.success(), "{output}");
        let err = stderr_of(&o);
        // `scene.ron:LINE:COLUMN: error: …`, located at the output's field.
        let line = err
            .lines()
            .find(|l| l.ends_with(&format!(": error: {message}")))
            .unwrap_or_else(|| panic!("{output}:\n{err}"));
        let place: Vec<&str> = line.splitn(4, ':').collect();
        assert_eq!(place[0], "scene.ron", "{line}");
        assert!(
            place[1].parse::<u32>().is_ok() && place[2].parse::<u32>().is_ok(),
            "{line}"
        );
        assert!(!dir.join("out").exists(), "nothing is written");
    }
}

/// Texture outputs whose files would clash or lie about their format are located errors: a
/// second AO output with bent normals (both wrote one `_bent_normals.exr`, the first lost),
/// and a file whose extension is not its format's (EXR bytes in `ao.png`).
#[test]
fn texture_outputs_refuse_clashing_bent_normals_and_misnamed_files() {
    let dir = scratch_dir("bake-output-names");
    let cases = [
        (
            "(kind: AmbientOcclusion(bent_normals: true), file: \"a.exr\"), (kind: AmbientOcclusion(max_distance: 0.5, bent_normals: true), file: \"b.exr\")",
            "a second ambient-occlusion output with bent normals: both would write strip_1_bent_normals.exr",
        ),
        (
            "(kind: AmbientOcclusion(), file: \"ao.png\")",
            "file \"ao.png\" ends in .png, but this output is written as Exr (.exr)",
        ),
        (
            "(kind: Albedo, format: Png8, file: \"albedo.exr\")",
            "file \"albedo.exr\" ends in .exr, but this output is written as Png8 (.png)",
        ),
    ];
    assert_refused(&dir, &cases);
    let _ = std::fs::remove_dir_all(&dir);
}
