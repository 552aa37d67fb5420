//! The geometry of `bake SCENE --write-gltf`'s standalone `.glb` is the scene's world
//! geometry with the renderer's front faces: scenes read from RIB and `.mi` (which ask for
//! no bakes: converted to RON, a bake added, as the `bake` help says), mirrored instances
//! (a negative-determinant transform baked into the vertices must reverse the corners, as
//! glTF's front is counter-clockwise under an identity node) and a scene far from the
//! origin, which the renderer rebases (the `.glb` translates its node by the scene origin
//! and holds the traced render-space vertices: together the true world coordinates).

use std::path::Path;

use glam::Vec3;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// A small AO bake request on generated UVs, as RON.
const BAKE: &str =
    "bake: (resolution: (8, 8), uvs: Unwrap, outputs: [(kind: AmbientOcclusion(samples: 4), format: Png8)]),";

/// What a written `.glb` holds: per node its name and its triangles (corners in index order).
struct Written {
    nodes: Vec<(String, Vec<[Vec3; 3]>)>,
    materials: Vec<String>,
    textures: usize,
    images: usize,
}

fn read_glb(path: &Path) -> Written {
    let bytes = std::fs::read(path).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    let nodes = glb
        .nodes()
        .map(|node| {
            assert_eq!(
                node.transform().matrix(),
                glam::Mat4::IDENTITY.to_cols_array_2d()
            );
            let prim = node.mesh().unwrap().primitives().next().unwrap();
            let reader = prim.reader(|_| Some(&blob));
            let p: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
            let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            let triangles = indices
                .chunks(3)
                .map(|t| [0, 1, 2].map(|k| p[t[k] as usize]))
                .collect();
            (node.name().unwrap().to_string(), triangles)
        })
        .collect();
    Written {
        nodes,
        materials: glb
            .materials()
            .map(|m| m.name().unwrap().to_string())
            .collect(),
        textures: glb.textures().count(),
        images: glb.images().count(),
    }
}

/// The world triangles of every placed instance of the scene at `path` as the renderer
/// traces them: the accelerator's triangles (in their winding: the geometric normal
/// `(b − a) × (c − a)` is the front the renderer and the bake use) plus the scene origin in
/// f64, rounded to f32.
fn traced_triangles(path: &Path) -> Vec<Vec<[Vec3; 3]>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut scene =
        stagelight::scene::load_scene_str(&text, path).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    let frame = crate::common::through_photons(&mut scene.world, settings);
    let geometry = frame.outputs.geometry.as_ref().unwrap();
    geometry
        .instances
        .iter()
        .map(|inst| {
            (0..inst.mesh.triangles.len() as u32)
                .map(|t| {
                    geometry
                        .accel
                        .triangle(inst.first_triangle + t)
                        .map(|p| (p.as_dvec3() + geometry.origin).as_vec3())
                })
                .collect()
        })
        .collect()
}

/// The front normal of a glTF triangle under an identity node: counter-clockwise.
fn ccw_normal([a, b, c]: [Vec3; 3]) -> Vec3 {
    (b - a).cross(c - a).normalize()
}

/// The sorted distinct corners of `triangles`.
fn corners(triangles: &[[Vec3; 3]]) -> Vec<[f32; 3]> {
    let mut v: Vec<[f32; 3]> = triangles.iter().flatten().map(|p| p.to_array()).collect();
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v.dedup();
    v
}

/// A RIB scene (left-handed: the reader flips z, so the floor is placed by a mirroring
/// matrix and the `Scale -1 1 1` wing by an unmirrored one), converted to RON and one
/// instance given a bake: the `.glb` has a node per instance, its triangles the RIB scene's
/// own traced triangles corner for corner (so the front is the renderer's, mirrored or not)
/// at the world positions the RIB transforms give.
#[test]
fn a_rib_scene_converted_and_baked_writes_its_world_triangles() {
    let dir = scratch_dir("gltf-export-rib");
    let rib = "Display \"out.png\" \"file\" \"rgb\"\nFormat 16 12 1\nProjection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nWorldBegin\nLightSource \"pointlight\" 1 \"from\" [0 2 -2] \"intensity\" 4\nAttributeBegin\nAttribute \"identifier\" \"name\" [\"floor\"]\nTranslate 3 0 0\nPolygon \"P\" [-1 0 -1  1 0 -1  1 0 1  -1 0 1]\nAttributeEnd\nAttributeBegin\nAttribute \"identifier\" \"name\" [\"wing\"]\nScale -1 1 1\nTranslate 2 0 0\nPolygon \"P\" [0 0 0  1 0 0  1 1 0]\nAttributeEnd\nWorldEnd\n";
    std::fs::write(dir.join("s.rib"), rib).unwrap();
    ok(&dir, &["convert", "s.rib", "-o", "s.ron"]);
    let ron = std::fs::read_to_string(dir.join("s.ron")).unwrap();
    assert_eq!(ron.matches("bake: None,").count(), 2);
    std::fs::write(dir.join("s.ron"), ron.replacen("bake: None,", BAKE, 1)).unwrap();
    ok(&dir, &["bake", "s.ron", "-o", "out", "--write-gltf"]);
    let written = read_glb(&dir.join("out/s.glb"));
    let names: Vec<&str> = written.nodes.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["floor", "world/wing"]);
    assert_eq!(written.materials, ["floor_baked", "defaultsurface_2"]);
    assert_eq!((written.textures, written.images), (1, 1));
    let traced = traced_triangles(&dir.join("s.rib"));
    for ((name, triangles), want) in written.nodes.iter().zip(&traced) {
        assert_eq!(triangles, want, "{name}: the RIB scene's traced triangles");
    }
    let floor = [
        [2.0, 0.0, -1.0],
        [2.0, 0.0, 1.0],
        [4.0, 0.0, -1.0],
        [4.0, 0.0, 1.0],
    ];
    assert_eq!(corners(&written.nodes[0].1), floor);
    let wing = [[-3.0, 0.0, 0.0], [-3.0, 1.0, 0.0], [-2.0, 0.0, 0.0]];
    assert_eq!(corners(&written.nodes[1].1), wing);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A `.mi` scene (instance transforms are world-to-object: the file's inverse places the
/// quad at x + 2 and mirrors the second instance in x), converted to RON and its first quad
/// baked: the `.glb`'s triangles are the `.mi` scene's traced triangles at those positions.
#[test]
fn a_mi_scene_converted_and_baked_writes_its_world_triangles() {
    let dir = scratch_dir("gltf-export-mi");
    let mi = r#"link "base.so"
$include <base.mi>
options "opt" samples 0 0 object space end options
camera "Cam" output "rgb" "png" "out.png" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "Cam_inst" "Cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 end instance
material "m" opaque "mib_illum_lambert" ("ambient" 1 1 1, "diffuse" 0.7 0.7 0.7) end material
object "Quad" group 0 0 0  1 0 0  1 1 0  0 1 0  v 0 v 1 v 2 v 3  p "m" 0 1 2 3 end group end object
instance "Quad_inst" "Quad" material "m" transform 1 0 0 0  0 1 0 0  0 0 1 0  -2 0 0 1 end instance
instance "Mirror_inst" "Quad" material "m" transform -1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1 end instance
instgroup "root" "Cam_inst" "Quad_inst" "Mirror_inst" end instgroup
render "root" "Cam_inst" "opt"
"#;
    std::fs::write(dir.join("c.mi"), mi).unwrap();
    ok(&dir, &["convert", "c.mi", "-o", "c.ron"]);
    let ron = std::fs::read_to_string(dir.join("c.ron")).unwrap();
    assert_eq!(ron.matches("bake: None,").count(), 2);
    std::fs::write(dir.join("c.ron"), ron.replacen("bake: None,", BAKE, 1)).unwrap();
    ok(&dir, &["bake", "c.ron", "-o", "out", "--write-gltf"]);
    let written = read_glb(&dir.join("out/c.glb"));
    let names: Vec<&str> = written.nodes.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["Quad_inst", "root/Mirror_inst"]);
    assert_eq!(written.materials, ["Quad_inst_baked", "m"]);
    assert_eq!((written.textures, written.images), (1, 1));
    let traced = traced_triangles(&dir.join("c.mi"));
    for ((name, triangles), want) in written.nodes.iter().zip(&traced) {
        assert_eq!(triangles, want, "{name}: the .mi scene's traced triangles");
    }
    let quad = [
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [3.0, 0.0, 0.0],
        [3.0, 1.0, 0.0],
    ];
    assert_eq!(corners(&written.nodes[0].1), quad);
    let mirrored = [
        [-1.0, 0.0, 0.0],
        [-1.0, 1.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    assert_eq!(corners(&written.nodes[1].1), mirrored);
    // Both instances face +z, the quad's counter-clockwise side: the mirrored one's corners
    // are reversed, or its glTF front would face −z.
    for (name, triangles) in &written.nodes {
        for t in triangles {
            assert_eq!(ccw_normal(*t), Vec3::Z, "{name}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A RON floor (counter-clockwise from +z) placed by `Scale((-1, 1, 1))` and baked: its
/// triangles in the `.glb` are counter-clockwise from +z (the mirrored corners reversed),
/// with `NORMAL` +z, at the mirrored positions; an unmirrored copy beside it is the same.
#[test]
fn a_mirrored_instance_keeps_its_front_face() {
    let dir = scratch_dir("gltf-export-mirror");
    let scene = format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (0, -4, 4), target: (0, 0, 0), up: (0, 0, 1)))],
    materials: [(name: "w", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [(name: "floor", mesh: Inline(
        vertices: [(1, 0, 0), (2, 0, 0), (2, 1, 0), (1, 1, 0)],
        polygons: [[0, 1, 2, 3]]), material: "w")],
    instances: [(name: "m", of: "floor", transform: [Scale((-1, 1, 1))], {BAKE}),
                (name: "u", of: "floor", {BAKE})],
    groups: [(name: "world", members: ["m", "u"])],
    render: (root: "world", camera: "cam"),
)
"#
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    ok(&dir, &["bake", "scene.ron", "-o", "out", "--write-gltf"]);
    let path = dir.join("out/scene.glb");
    let written = read_glb(&path);
    let names: Vec<&str> = written.nodes.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["m", "u"]);
    let mirrored = [
        [-2.0, 0.0, 0.0],
        [-2.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    assert_eq!(corners(&written.nodes[0].1), mirrored);
    for (name, triangles) in &written.nodes {
        assert_eq!(triangles.len(), 2);
        for t in triangles {
            assert_eq!(ccw_normal(*t), Vec3::Z, "{name}: {t:?}");
        }
    }
    let bytes = std::fs::read(&path).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = glb.blob.clone().unwrap();
    for mesh in glb.meshes() {
        let prim = mesh.primitives().next().unwrap();
        let normals: Vec<[f32; 3]> = prim
            .reader(|_| Some(&blob))
            .read_normals()
            .unwrap()
            .collect();
        assert!(normals.iter().all(|n| *n == [0.0, 0.0, 1.0]), "{normals:?}");
    }
    let traced = traced_triangles(&dir.join("scene.ron"));
    assert_eq!(written.nodes[0].1, traced[0]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A floor two million units from the origin (the loader rebases the scene: it is traced
/// within a unit of the render-space origin): its node is translated by the scene origin
/// (10⁶, −2·10⁶, 500), which f32 holds exactly, and its vertices are the traced render-space
/// ones, so translation + vertex, in f64 rounded once to f32 as a loader's f32 world space
/// would hold it, is each world corner (x = 1000000.3 ± 0.75, not representable:
/// 1000001.0625 and 999999.5625), and POSITION's bounds are the written vertices'.
#[test]
fn a_far_scene_is_written_at_its_world_coordinates() {
    let dir = scratch_dir("gltf-export-far");
    let scene = format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (1000000, -2000004, 504), target: (1000000, -2000000, 500), up: (0, 0, 1)))],
    materials: [(name: "w", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [(name: "floor", mesh: Inline(
        vertices: [(-0.75, -0.75, 0), (0.75, -0.75, 0), (0.75, 0.75, 0), (-0.75, 0.75, 0)],
        polygons: [[0, 1, 2, 3]]), material: "w")],
    instances: [(name: "f", of: "floor", transform: [Translate((1000000.3, -2000000, 500.25))], {BAKE})],
    groups: [(name: "world", members: ["f"])],
    render: (root: "world", camera: "cam"),
)
"#
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    ok(&dir, &["bake", "scene.ron", "-o", "out", "--write-gltf"]);
    let path = dir.join("out/scene.glb");
    let bytes = std::fs::read(&path).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = glb.blob.clone().unwrap();
    let node = glb.nodes().next().unwrap();
    let gltf::scene::Transform::Decomposed { translation, .. } = node.transform() else {
        panic!("a translation");
    };
    assert_eq!(translation, [1000000.0, -2000000.0, 500.0]);
    let prim = node.mesh().unwrap().primitives().next().unwrap();
    let local: Vec<Vec3> = prim
        .reader(|_| Some(&blob))
        .read_positions()
        .unwrap()
        .map(Vec3::from)
        .collect();
    let compose =
        |p: [f32; 3]| [0, 1, 2].map(|a| (f64::from(translation[a]) + f64::from(p[a])) as f32);
    let mut composed: Vec<[f32; 3]> = local.iter().map(|p| compose(p.to_array())).collect();
    composed.sort_by(|a, b| a.partial_cmp(b).unwrap());
    composed.dedup();
    let world = |x: f64, y: f64| [(1000000.3 + x) as f32, (-2000000.0 + y) as f32, 500.25f32];
    let mut want = vec![
        world(-0.75, -0.75),
        world(0.75, -0.75),
        world(0.75, 0.75),
        world(-0.75, 0.75),
    ];
    want.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(composed, want);
    assert_eq!(f64::from(want[0][0]), 999999.5625);
    assert_eq!(f64::from(want[3][0]), 1000001.0625);
    let bounds = prim.bounding_box();
    let lo = local.iter().fold(Vec3::INFINITY, |m, p| m.min(*p));
    let hi = local.iter().fold(Vec3::NEG_INFINITY, |m, p| m.max(*p));
    assert_eq!((bounds.min, bounds.max), (lo.to_array(), hi.to_array()));
    assert_eq!(
        (compose(bounds.min), compose(bounds.max)),
        (world(-0.75, -0.75), world(0.75, 0.75))
    );
    // The scene was rebased: the renderer traced it near the origin.
    let text = std::fs::read_to_string(dir.join("scene.ron")).unwrap();
    let mut loaded = stagelight::scene::load_scene_str(&text, &dir.join("scene.ron")).unwrap();
    let settings = loaded.settings.clone();
    let frame = crate::common::through_photons(&mut loaded.world, settings);
    let geometry = frame.outputs.geometry.as_ref().unwrap();
    assert_eq!(
        geometry.origin,
        glam::DVec3::new(1000000.0, -2000000.0, 500.0)
    );
    // The written vertices are the traced render-space corners, bit for bit.
    let indices: Vec<u32> = prim
        .reader(|_| Some(&blob))
        .read_indices()
        .unwrap()
        .into_u32()
        .collect();
    let written: Vec<[Vec3; 3]> = indices
        .chunks(3)
        .map(|t| [0, 1, 2].map(|k| local[t[k] as usize]))
        .collect();
    let traced: Vec<[Vec3; 3]> = (0..geometry.triangle_count() as u32)
        .map(|t| geometry.accel.triangle(t))
        .collect();
    assert_eq!(written, traced);
    let _ = std::fs::remove_dir_all(&dir);
}
