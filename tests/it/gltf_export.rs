//! `bake scene.ron --write-gltf`: the standalone glTF of a scene that is not glTF — its
//! baked instances with their triangles as baked in world space, the bake's generated UVs
//! on `TEXCOORD_1`, the PNGs embedded and wired into their own materials — which stagelight
//! reads back and bakes to the same AO; `merge --write-gltf` of its bake parts writes the
//! same bytes, at any thread count. (`--write-gltf` refused every scene but glTF before.)

use std::path::Path;

use glam::{Vec2, Vec3};
use serde_json::Value;

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

/// A 1.5 × 1.5 floor moved to x = 3, baked on generated UVs (lightmap, then AO, as the
/// glTF reader's default request bakes them), and an unbaked box standing on it.
const SCENE: &str = r#"Scene(
    options: (seed: 7),
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (3, -4, 4), target: (3, 0, 0), up: (0, 0, 1)))],
    lights: [(name: "lamp", kind: Point(position: (3.5, -0.5, 2)), intensity: 2.0)],
    materials: [(name: "w", shader: Lambert(albedo: (0.8, 0.6, 0.4)))],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-0.75, -0.75, 0), (0.75, -0.75, 0), (0.75, 0.75, 0), (-0.75, 0.75, 0)],
            polygons: [[0, 1, 2, 3]]), material: "w"),
        (name: "box", mesh: Inline(
            vertices: [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                       (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],
            polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5],
                       [0, 4, 7, 3]]), material: "w"),
    ],
    instances: [(name: "f", of: "floor", transform: [Translate((3, 0, 0))],
                 bake: (resolution: (64, 64), uvs: Unwrap, outputs: [
                     (kind: Lightmap(indirect: true, samples: 64, max_depth: 2,
                                     store: IrradianceOverPi, scale: 0.5), format: Png8),
                     (kind: AmbientOcclusion(samples: 64), format: Png8)])),
                (name: "b", of: "box", transform: [Scale((0.3, 0.3, 0.3)), Translate((3, 0, 0.3))])],
    groups: [(name: "world", members: ["f", "b"])],
    render: (root: "world", camera: "cam"),
)
"#;

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// The JSON chunk of a GLB.
fn json_of(glb: &[u8]) -> Value {
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&glb[20..20 + len]).unwrap()
}

/// The floor's triangles as baked (world corners, in the world triangles' order) and its
/// bake's corner UVs (v up) in the same order, from the library's own stages.
fn baked_floor() -> (Vec<[Vec3; 3]>, Vec<[Vec2; 3]>) {
    let mut scene = stagelight::scene::load_scene_str(SCENE, Path::new("scene.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    let frame = crate::common::through_photons(&mut scene.world, settings);
    let geometry = frame.outputs.geometry.as_ref().unwrap();
    let prepared = stagelight::bake::request::prepare_bakes(&scene.world, Some(geometry)).unwrap();
    assert_eq!(prepared.len(), 1);
    let p = &prepared[0];
    let inst = &geometry.instances[p.slot];
    let triangles = (0..inst.mesh.triangles.len())
        .map(|t| {
            inst.corners(t).map(|i| {
                (inst
                    .world_from_object
                    .transform_point3(inst.mesh.positions[i])
                    .as_dvec3()
                    + geometry.origin)
                    .as_vec3()
            })
        })
        .collect();
    let uvs = p.uvs.iter().map(|c| inst.world_order(*c)).collect();
    (triangles, uvs)
}

/// The written file: one node per instance ("f" baked, the box as plain geometry), no
/// transforms, the floor's triangles and bake UVs exactly as baked (glTF's v down:
/// `1 − v`), POSITION bounds, its own material with the scene colour, the AO as
/// `occlusionTexture` and the lightmap as `MSFT_lightmap` (factor 2 = 1 / scale) on
/// `TEXCOORD_1`, both the PNG files byte for byte, and nothing left unused.
#[test]
fn a_ron_bake_writes_a_standalone_glb_of_its_baked_geometry() {
    let dir = scratch_dir("gltf-export-standalone");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "out",
            "--write-gltf",
            "--threads",
            "1",
        ],
    );
    assert_eq!(
        dir_names(&dir.join("out")),
        ["f_ao.png", "f_lightmap.png", "scene.glb"]
    );
    let bytes = std::fs::read(dir.join("out/scene.glb")).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    let json = json_of(&bytes);
    let names: Vec<_> = glb.nodes().map(|n| n.name().unwrap().to_string()).collect();
    assert_eq!(names, ["f", "world/b"]);
    for node in glb.nodes() {
        assert_eq!(
            node.transform().matrix(),
            glam::Mat4::IDENTITY.to_cols_array_2d()
        );
    }
    let floor = glb.nodes().next().unwrap().mesh().unwrap();
    let prim = floor.primitives().next().unwrap();
    let reader = prim.reader(|_| Some(&blob));
    let positions: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
    let uv1: Vec<Vec2> = reader
        .read_tex_coords(1)
        .unwrap()
        .into_f32()
        .map(Vec2::from)
        .collect();
    let normals: Vec<Vec3> = reader.read_normals().unwrap().map(Vec3::from).collect();
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    let (triangles, bake_uvs) = baked_floor();
    let written: Vec<[Vec3; 3]> = indices
        .chunks(3)
        .map(|t| [0, 1, 2].map(|k| positions[t[k] as usize]))
        .collect();
    assert_eq!(written, triangles, "the triangles as baked, in world space");
    let written_uvs: Vec<[Vec2; 3]> = indices
        .chunks(3)
        .map(|t| [0, 1, 2].map(|k| uv1[t[k] as usize]))
        .collect();
    let expected_uvs: Vec<[Vec2; 3]> = bake_uvs
        .iter()
        .map(|c| c.map(|uv| Vec2::new(uv.x, 1.0 - uv.y)))
        .collect();
    assert_eq!(
        written_uvs, expected_uvs,
        "TEXCOORD_1 is the bake's UVs, v down"
    );
    assert!(normals.iter().all(|n| *n == Vec3::Z), "{normals:?}");
    // Welded: no two vertices alike; POSITION's bounds are the vertices'.
    for a in 0..positions.len() {
        for b in a + 1..positions.len() {
            assert!(
                (positions[a], uv1[a]) != (positions[b], uv1[b]),
                "{a} and {b}"
            );
        }
    }
    let bounds = prim.bounding_box();
    assert_eq!(
        (bounds.min, bounds.max),
        ([2.25, -0.75, 0.0], [3.75, 0.75, 0.0])
    );
    // The material.
    let material = prim.material();
    assert_eq!(material.name(), Some("f_baked"));
    assert_eq!(
        material.pbr_metallic_roughness().base_color_factor(),
        [0.8, 0.6, 0.4, 1.0]
    );
    let view_bytes = |image: gltf::Image<'_>| -> Vec<u8> {
        let gltf::image::Source::View { view, mime_type } = image.source() else {
            panic!("the image is embedded");
        };
        assert_eq!(mime_type, "image/png");
        blob[view.offset()..view.offset() + view.length()].to_vec()
    };
    let occlusion = material.occlusion_texture().expect("occlusionTexture");
    assert_eq!(occlusion.tex_coord(), 1);
    assert!(
        view_bytes(occlusion.texture().source())
            == std::fs::read(dir.join("out/f_ao.png")).unwrap()
    );
    let m = &json["materials"][material.index().unwrap()];
    let lightmap = &m["extensions"]["MSFT_lightmap"];
    assert_eq!(
        lightmap["lightmapFactor"],
        serde_json::json!([2.0, 2.0, 2.0])
    );
    assert_eq!(lightmap["lightmapTexture"]["texCoord"], 1);
    let texture = glb
        .textures()
        .nth(lightmap["lightmapTexture"]["index"].as_u64().unwrap() as usize)
        .unwrap();
    assert!(view_bytes(texture.source()) == std::fs::read(dir.join("out/f_lightmap.png")).unwrap());
    assert_eq!(json["extensionsUsed"], serde_json::json!(["MSFT_lightmap"]));
    // The box: plain geometry with the scene material, no bake UVs.
    let boxed = glb.nodes().nth(1).unwrap().mesh().unwrap();
    let box_prim = boxed.primitives().next().unwrap();
    assert_eq!(box_prim.material().name(), Some("w"));
    assert!(box_prim.material().occlusion_texture().is_none());
    assert!(box_prim.get(&gltf::Semantic::TexCoords(1)).is_none());
    assert_eq!(box_prim.bounding_box().min, [2.7, -0.3, 0.0]);
    // Nothing unused: every mesh, material, accessor, image and texture is referenced.
    assert_eq!((glb.meshes().count(), glb.materials().count()), (2, 2));
    assert_eq!((glb.images().count(), glb.textures().count()), (2, 2));
    let mut used = std::collections::BTreeSet::new();
    for mesh in glb.meshes() {
        for p in mesh.primitives() {
            used.extend(p.attributes().map(|(_, a)| a.index()));
            used.extend(p.indices().map(|a| a.index()));
        }
    }
    assert_eq!(used.len(), glb.accessors().count());
    let _ = std::fs::remove_dir_all(&dir);
}

/// stagelight reads its own file back: the glTF reader gives the floor (it has
/// `TEXCOORD_1`) its default request — lightmap then AO, 64 rays, 4 positions per texel, on
/// `TEXCOORD_1` — which, at the RON request's size and seed, bakes the same AO bytes: the
/// same triangles, the same texels, the same random numbers.
#[test]
fn the_written_glb_bakes_again_to_the_same_ao() {
    let dir = scratch_dir("gltf-export-round-trip");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
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
    let first = crate::common::png::read(&dir.join("out/f_ao.png"));
    let again = crate::common::png::read(&dir.join("again/f_ao.png"));
    assert_eq!((again.width, again.height), (64, 64));
    assert!(
        std::fs::read(dir.join("out/f_ao.png")).unwrap()
            == std::fs::read(dir.join("again/f_ao.png")).unwrap(),
        "the AO of the re-read file differs ({}×{})",
        first.width,
        first.height
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two bake parts merged with `--write-gltf` write the single bake's files byte for byte
/// (the merge runs the geometry stages again and prepares the same UVs), and the single bake
/// writes the same bytes at 1 and 2 threads.
#[test]
fn merged_bake_parts_write_the_single_bakes_glb() {
    let dir = scratch_dir("gltf-export-merge");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "single",
            "--write-gltf",
            "--threads",
            "1",
        ],
    );
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "two",
            "--write-gltf",
            "--threads",
            "2",
        ],
    );
    for k in ["1/2", "2/2"] {
        ok(
            &dir,
            &[
                "bake",
                "scene.ron",
                "--part",
                k,
                "-o",
                "parts",
                "--threads",
                "1",
            ],
        );
    }
    ok(
        &dir,
        &[
            "merge",
            "parts/bake_part_2_of_2.exr",
            "parts/bake_part_1_of_2.exr",
            "-o",
            "merged",
            "--write-gltf",
        ],
    );
    for other in ["two", "merged"] {
        assert_eq!(dir_names(&dir.join(other)), dir_names(&dir.join("single")));
        for name in dir_names(&dir.join("single")) {
            assert!(
                std::fs::read(dir.join("single").join(&name)).unwrap()
                    == std::fs::read(dir.join(other).join(&name)).unwrap(),
                "{other}/{name} differs"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The output guard still refuses a glTF file that would overwrite an input: a RON scene
/// whose mesh is `mesh.glb`, baked with `--write-gltf` into its own directory (exit 2,
/// nothing written, the mesh file unchanged).
#[test]
fn a_standalone_glb_over_an_input_of_the_scene_is_refused() {
    let dir = scratch_dir("gltf-export-over-input");
    std::fs::write(dir.join("scene.ron"), SCENE).unwrap();
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "out",
            "--write-gltf",
            "--threads",
            "1",
        ],
    );
    std::fs::copy(dir.join("out/scene.glb"), dir.join("mesh.glb")).unwrap();
    let ron = r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (3, -4, 4), target: (3, 0, 0), up: (0, 0, 1)))],
    materials: [(name: "w", shader: Lambert(albedo: (0.8, 0.6, 0.4)))],
    objects: [(name: "floor", mesh: Gltf(file: "mesh.glb", mesh: "f"), material: "w")],
    instances: [(name: "f", of: "floor", bake: (resolution: (16, 16), uvs: Unwrap,
                 outputs: [(kind: AmbientOcclusion(samples: 4), format: Png8)]))],
    groups: [(name: "world", members: ["f"])],
    render: (root: "world", camera: "cam"),
)
"#;
    std::fs::write(dir.join("mesh.ron"), ron).unwrap();
    let before = dir_names(&dir);
    let o = run_in(&dir, &["bake", "mesh.ron", "--write-gltf"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "error: --write-gltf ./mesh.glb would overwrite an input of the scene mesh.glb\n  help: give every output its own file, and none the name of an input\n1 error in mesh.ron; nothing baked\n"
    );
    assert_eq!(dir_names(&dir), before);
    assert!(
        std::fs::read(dir.join("mesh.glb")).unwrap()
            == std::fs::read(dir.join("out/scene.glb")).unwrap()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A per-vertex bake of a RON scene becomes `COLOR_0` of its node: the floor under the box
/// bakes AO per vertex, and each written vertex carries the value of its mesh vertex — the
/// PLY's, in the same order of vertices (the floor's four corners, open to the sky but for
/// the box: below 1) — with no bake UVs or textures.
#[test]
fn a_per_vertex_bake_becomes_color_0() {
    let dir = scratch_dir("gltf-export-vertices");
    let scene = SCENE.replace(
        r#"bake: (resolution: (64, 64), uvs: Unwrap, outputs: ["#,
        r#"bake: (outputs: [(kind: AmbientOcclusion(samples: 64), target: Vertices)]), nobake: ("#,
    );
    let scene = scene.replace(
        r#", nobake: (
                     (kind: Lightmap(indirect: true, samples: 64, max_depth: 2,
                                     store: IrradianceOverPi, scale: 0.5), format: Png8),
                     (kind: AmbientOcclusion(samples: 64), format: Png8)]))"#,
        ")",
    );
    std::fs::write(dir.join("scene.ron"), &scene).unwrap();
    ok(
        &dir,
        &[
            "bake",
            "scene.ron",
            "-o",
            "out",
            "--write-gltf",
            "--threads",
            "1",
        ],
    );
    assert_eq!(dir_names(&dir.join("out")), ["f_ao.ply", "scene.glb"]);
    let bytes = std::fs::read(dir.join("out/scene.glb")).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    let prim = glb
        .nodes()
        .next()
        .unwrap()
        .mesh()
        .unwrap()
        .primitives()
        .next()
        .unwrap();
    assert_eq!(prim.material().name(), Some("f_baked"));
    assert!(prim.get(&gltf::Semantic::TexCoords(1)).is_none());
    assert_eq!(glb.images().count(), 0);
    let reader = prim.reader(|_| Some(&blob));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    let colors: Vec<[f32; 3]> = reader.read_colors(0).unwrap().into_rgb_f32().collect();
    let ply = crate::vertex_bake::BakedPly::read(&dir.join("out/f_ao.ply"));
    assert_eq!((positions.len(), ply.count), (4, 4));
    for (p, c) in positions.iter().zip(&colors) {
        // The PLY's vertex at this corner (the PLY may be in object space: x − 3).
        let v = (0..ply.count)
            .find(|&v| {
                let x = ply.float(v, "x");
                (x == p[0] || x + 3.0 == p[0])
                    && (ply.float(v, "y"), ply.float(v, "z")) == (p[1], p[2])
            })
            .unwrap_or_else(|| panic!("{p:?} is not a vertex of the PLY"));
        let ao = ply.float(v, "baked_r");
        assert_eq!(*c, [ao, ao, ao], "{p:?}");
        assert!(ao > 0.5 && ao < 1.0, "{ao}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
