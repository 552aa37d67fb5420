//! What the glTF 2.0 specification allows and forbids, on small `.gltf` files written here:
//! application-specific attributes (`_BATCHID`) are read past and unknown attribute names
//! named; `KHR_texture_transform` maps the coordinates an image is read at; triangle strips
//! and fans are read; rotations that are not unit quaternions, a node with two parents and
//! a `byteStride` shorter than its elements are located errors; a mesh that fails to load
//! gets no follow-on UV error; a camera under a mirroring parent keeps its view and up; a
//! sampler's wrap modes apply per axis, mirrored repeat included.

use std::path::{Path, PathBuf};

use glam::{Vec3, Vec3A};
use stagelight::components::Camera;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// Standard base64 with padding.
pub(crate) fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (k, &b)| n | (b as u32) << (16 - 8 * k));
        for k in 0..4 {
            out.push(if k <= chunk.len() {
                A[(n >> (18 - 6 * k) & 63) as usize] as char
            } else {
                '='
            });
        }
    }
    out
}

/// A unit quad in z = 0 (corners (0,0), (1,0), (1,1), (0,1)) with `TEXCOORD_0` = `uvs`, the
/// indices `indices` (u16) and a float `_BATCHID` per vertex; `PRIMITIVE`, `MATERIALS`,
/// `NODES` and `ROOTS` are left for the caller to fill in.
pub(crate) fn quad(uvs: [[f32; 2]; 4], indices: &[u16]) -> String {
    let mut bytes = Vec::new();
    for p in [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ] {
        bytes.extend(p.iter().flat_map(|c| c.to_le_bytes()));
    }
    for uv in uvs {
        bytes.extend(uv.iter().flat_map(|c| c.to_le_bytes()));
    }
    for b in [7.0f32, 7.0, 8.0, 8.0] {
        bytes.extend(b.to_le_bytes());
    }
    let index_at = bytes.len();
    bytes.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{data}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 80, "byteLength": 16}},
    {{"buffer": 0, "byteOffset": {index_at}, "byteLength": {index_len}}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5126, "count": 4, "type": "SCALAR"}},
    {{"bufferView": 3, "componentType": 5123, "count": {count}, "type": "SCALAR"}}
  ],
  "meshes": [{{"name": "quad", "primitives": [PRIMITIVE]}}],
  "materials": [MATERIALS],
  "nodes": [NODES],
  "scenes": [{{"nodes": [ROOTS]}}]
}}"#,
        len = bytes.len(),
        data = base64(&bytes),
        index_len = indices.len() * 2,
        count = indices.len(),
    )
}

/// The quad's two triangles, counter-clockwise seen from +z.
pub(crate) const LIST: [u16; 6] = [0, 1, 2, 0, 2, 3];
pub(crate) const PLAIN_UVS: [[f32; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
pub(crate) const PRIMITIVE: &str = r#"{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "_BATCHID": 2}, "indices": 3, "material": 0}"#;
pub(crate) const MATERIAL: &str = r#"{"name": "m", "pbrMetallicRoughness": {"metallicFactor": 0}}"#;

/// The quad file with one node placing the mesh.
pub(crate) fn one_node(primitive: &str, node: &str) -> String {
    quad(PLAIN_UVS, &LIST)
        .replace("PRIMITIVE", primitive)
        .replace("MATERIALS", MATERIAL)
        .replace("NODES", node)
        .replace("ROOTS", "0")
}

pub(crate) fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// `_BATCHID` (an application-specific attribute: the specification allows names starting
/// with `_`) is read past; a name the specification does not allow is an error that names it.
#[test]
fn application_specific_attributes_are_read_past_and_unknown_names_named() {
    let dir = scratch_dir("gltf_spec_attributes");
    write(&dir, "batch.gltf", &one_node(PRIMITIVE, r#"{"mesh": 0}"#));
    let o = run_in(&dir, &["check", "batch.gltf"]);
    assert_eq!(
        (o.status.code(), stderr_of(&o)),
        (Some(0), String::new()),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let bad = PRIMITIVE.replace("_BATCHID", "BATCHID");
    let text = one_node(&bad, r#"{"mesh": 0}"#);
    write(&dir, "bad.gltf", &text);
    let o = run_in(&dir, &["check", "bad.gltf"]);
    assert_eq!(o.status.code(), Some(1));
    // At the attribute's value, where the name is.
    assert_eq!(
        stderr_of(&o),
        format!(
            "bad.gltf:{}: error: invalid glTF file: meshes[0].primitives[0].attributes[\"BATCHID\"]: invalid glTF: \"BATCHID\" is not an attribute name: expected POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n, JOINTS_n, WEIGHTS_n, or an application-specific name starting with \"_\"\n\
             1 error in bad.gltf\n",
            crate::gltf_validity::after(&text, "\"BATCHID\": ")
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The extension's map as its specification writes it (glTF coordinates, `v` down):
/// `T(offset) · R(rotation) · S(scale)`.
fn texture_transform(uv: [f32; 2], offset: [f64; 2], rotation: f64, scale: [f64; 2]) -> [f32; 2] {
    let (s, c) = rotation.sin_cos();
    let (u, v) = (uv[0] as f64 * scale[0], uv[1] as f64 * scale[1]);
    [
        (offset[0] + c * u + s * v) as f32,
        (offset[1] - s * u + c * v) as f32,
    ]
}

/// Renders `file` (a quad with a 4×4 texture of distinct texels) through a RON scene that
/// includes it, looking straight at the quad; returns the beauty.
fn render_included(dir: &Path, file: &str) -> Vec<Vec3> {
    let text = format!(
        r#"Scene(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 20, resolution: (12, 12),
               placement: LookAt(eye: (0.5, 0.5, 3), target: (0.5, 0.5, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0, 0, -1)), intensity: 3.14159265358979)],
    include: ["{file}"],
    instances: [(name: "placed", of: "scene")],
    groups: [(name: "top", members: ["placed"])],
    render: (root: "top", camera: "cam"),
)"#
    );
    let mut scene = stagelight::scene::load_scene_str(&text, &dir.join("view.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.located_warnings, Vec::<String>::new());
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("image").beauty
}

/// A base colour texture read through `KHR_texture_transform` (offset, rotation and
/// non-uniform scale) renders as the same texture without the extension on a quad whose
/// UVs are the transformed ones; without the transform the picture differs.
#[test]
fn a_texture_transform_maps_the_coordinates_the_image_reads() {
    let dir = scratch_dir("gltf_spec_texture_transform");
    let texels: Vec<[u8; 3]> = (0..16u8)
        .map(|k| [k * 16, 255 - k * 13, ((k as u32 * 97) % 251) as u8])
        .collect();
    crate::common::png::write_rgb(&dir.join("tex.png"), 4, 4, &texels);
    let (offset, rotation, scale) = ([0.25, 0.5], 0.5, [0.5, 0.75]);
    let textured = |transform: &str| {
        format!(
            r#"{{"name": "m", "pbrMetallicRoughness": {{"metallicFactor": 0, "baseColorTexture": {{"index": 0{transform}}}}}}}],
  "textures": [{{"source": 0}}],
  "images": [{{"uri": "tex.png"}}"#
        )
    };
    let file = |uvs: [[f32; 2]; 4], transform: &str| {
        quad(uvs, &LIST)
            .replace("PRIMITIVE", PRIMITIVE)
            .replace("MATERIALS", &textured(transform))
            .replace("NODES", r#"{"mesh": 0}"#)
            .replace("ROOTS", "0")
    };
    let extension = format!(
        r#", "extensions": {{"KHR_texture_transform": {{"offset": {offset:?}, "rotation": {rotation}, "scale": {scale:?}}}}}"#
    );
    write(&dir, "transformed.gltf", &file(PLAIN_UVS, &extension));
    let moved = PLAIN_UVS.map(|uv| texture_transform(uv, offset, rotation, scale));
    write(&dir, "moved.gltf", &file(moved, ""));
    write(&dir, "plain.gltf", &file(PLAIN_UVS, ""));
    let transformed = render_included(&dir, "transformed.gltf");
    let want = render_included(&dir, "moved.gltf");
    let plain = render_included(&dir, "plain.gltf");
    let largest = |a: &[Vec3], b: &[Vec3]| {
        a.iter()
            .zip(b)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0f32, f32::max)
    };
    assert!(
        largest(&transformed, &want) < 1e-4,
        "{}",
        largest(&transformed, &want)
    );
    assert!(
        largest(&plain, &want) > 0.05,
        "the transform changes the picture"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Triangle strips (mode 5) and fans (mode 6) become the specification's triangles; other
/// modes are still refused, and a mesh that fails to load gets no follow-on error about its
/// UVs (the default bake on `TEXCOORD_1` would otherwise say the set is missing).
#[test]
fn strips_and_fans_are_read_and_a_failed_mesh_gets_no_follow_on_error() {
    let dir = scratch_dir("gltf_spec_modes");
    let triangles = |indices: &[u16], mode: u32| {
        let primitive = format!(
            r#"{{"attributes": {{"POSITION": 0, "TEXCOORD_1": 1}}, "indices": 3, "mode": {mode}}}"#
        );
        let text = quad(PLAIN_UVS, indices)
            .replace("PRIMITIVE", &primitive)
            .replace("MATERIALS", MATERIAL)
            .replace("NODES", r#"{"name": "q", "mesh": 0}"#)
            .replace("ROOTS", "0");
        let path = write(&dir, &format!("mode{mode}.gltf"), &text);
        let pick = stagelight::scene::mesh_files::gltf_file::MeshPick::default();
        (
            stagelight::scene::mesh_files::gltf_file::parse(text.as_bytes(), Some(&dir), &pick)
                .map(|m| m.triangles),
            path,
        )
    };
    // The quad as a strip 1 2 0 3 and as a fan 0 1 2 3: both (1, 2, 0), (2, 3, 0).
    assert_eq!(
        triangles(&[1, 2, 0, 3], 5).0.unwrap(),
        [[1, 2, 0], [2, 3, 0]]
    );
    assert_eq!(
        triangles(&[0, 1, 2, 3], 6).0.unwrap(),
        [[1, 2, 0], [2, 3, 0]]
    );
    let o = run_in(&dir, &["check", "mode5.gltf"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr_of(&o));
    let (points, _) = triangles(&[0, 1, 2, 3], 0);
    assert_eq!(
        points.unwrap_err().to_string(),
        "meshes[0].primitives[0]: primitive mode Points is not supported: only triangles (mode 4, TRIANGLES; 5, TRIANGLE_STRIP; 6, TRIANGLE_FAN)"
    );
    let o = run_in(&dir, &["check", "mode0.gltf"]);
    assert_eq!(
        stderr_of(&o),
        "mode0.gltf:1:1: error: invalid glTF file \"mode0.gltf\": meshes[0].primitives[0]: primitive mode Points is not supported: only triangles (mode 4, TRIANGLES; 5, TRIANGLE_STRIP; 6, TRIANGLE_FAN)\n\
         \x20 help: loaded for object \"quad_mesh\" at mode0.gltf:1:1\n\
         1 error in mode0.gltf\n"
    );
    // The same for a PLY file that does not load under a bake on `uvs: Mesh`.
    write(
        &dir,
        "bad.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n",
    );
    write(
        &dir,
        "ply.ron",
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (8, 8), placement: LookAt(eye: (0, 0, 3), target: (0, 0, 0)))],
    materials: [(name: "m", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "o", mesh: Ply(file: "bad.ply"), material: "m")],
    instances: [(name: "o1", of: "o", bake: (resolution: (8, 8), uvs: Mesh, outputs: [(kind: AmbientOcclusion(samples: 4))]))],
    groups: [(name: "world", members: ["o1"])],
    render: (root: "world", camera: "cam"),
)"#,
    );
    let o = run_in(&dir, &["check", "ply.ron"]);
    let err = stderr_of(&o);
    assert_eq!(err.matches("error:").count(), 1, "{err}");
    assert!(err.contains("refers to vertex 9"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A rotation must be a unit quaternion: `[0, 0, 2, 0]` and `[0, 0, 0, 0]` are errors at
/// their line and column naming the node; a length within 0.001 of 1 is normalised. A node
/// listed under two parents, and a `byteStride` shorter than its accessor's elements, are
/// errors too.
#[test]
fn non_unit_rotations_second_parents_and_short_strides_are_errors() {
    let dir = scratch_dir("gltf_spec_nodes");
    let node = |rotation: &str| {
        format!(
            r#"{{"name": "spin", "mesh": 0,
    "rotation": {rotation}}}"#
        )
    };
    write(
        &dir,
        "long.gltf",
        &one_node(PRIMITIVE, &node("[0, 0, 2, 0]")),
    );
    write(
        &dir,
        "zero.gltf",
        &one_node(PRIMITIVE, &node("[0, 0, 0, 0]")),
    );
    // The text of the `nodes` line: the rotation stands on the line after it.
    let line = one_node(PRIMITIVE, &node("[0, 0, 0, 0]"))
        .lines()
        .position(|l| l.contains("\"spin\""))
        .unwrap()
        + 2;
    let o = run_in(&dir, &["check", "long.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "long.gltf:{line}:17: error: nodes[0] (\"spin\"): \"rotation\" [0, 0, 2, 0] has length 2: a rotation must be a unit quaternion (length within 0.001 of 1)\n\
             \x20 help: write the rotation normalised (divide each component by the length); a scale belongs in \"scale\"\n\
             1 error in long.gltf\n"
        )
    );
    let o = run_in(&dir, &["check", "zero.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "zero.gltf:{line}:17: error: nodes[0] (\"spin\"): \"rotation\" [0, 0, 0, 0] has length 0: a rotation must be a unit quaternion (length within 0.001 of 1)\n\
             \x20 help: write a unit quaternion [x, y, z, w]; no rotation is [0, 0, 0, 1]\n\
             1 error in zero.gltf\n"
        )
    );
    // 0.7072² + 0.7072² = 1.00026…: normalised, a rotation by 90° about z.
    let near = write(
        &dir,
        "near.gltf",
        &one_node(PRIMITIVE, &node("[0, 0, 0.7072, 0.7072]")),
    );
    let scene = stagelight::scene::load_scene(&near).unwrap_or_else(|e| panic!("{e}"));
    let placed: Vec<glam::Affine3A> = scene
        .world
        .query::<&stagelight::components::WorldFromObject>()
        .iter()
        .map(|w| w.0)
        .collect();
    assert_eq!(placed.len(), 1);
    let m = placed[0].matrix3;
    assert!((m.x_axis - Vec3A::Y).length() < 1e-6, "{m}");
    assert!((m.y_axis + Vec3A::X).length() < 1e-6, "{m}");

    let two = quad(PLAIN_UVS, &LIST)
        .replace("PRIMITIVE", PRIMITIVE)
        .replace("MATERIALS", MATERIAL)
        .replace(
            "NODES",
            r#"{"name": "leaf", "mesh": 0}, {"name": "a", "children": [0]}, {"name": "b", "children": [0]}"#,
        )
        .replace("ROOTS", "1, 2");
    write(&dir, "two.gltf", &two);
    let o = run_in(&dir, &["check", "two.gltf"]);
    let at = two.lines().position(|l| l.contains("\"leaf\"")).unwrap() + 1;
    // At b's `children`, the second parent's list.
    let column_b = two.lines().nth(at - 1).unwrap().rfind("[0]").unwrap() + 1;
    assert_eq!(
        stderr_of(&o),
        format!(
            "two.gltf:{at}:{column_b}: error: nodes[0] (\"leaf\") is a child of nodes[1] and of nodes[2]: a glTF node has at most one parent\n\
             \x20 help: list the node under one parent; to show a mesh twice, give it to two nodes\n\
             1 error in two.gltf\n"
        )
    );

    let strided = one_node(PRIMITIVE, r#"{"mesh": 0}"#).replace(
        r#""byteOffset": 0, "byteLength": 48}"#,
        r#""byteOffset": 0, "byteLength": 48, "byteStride": 8}"#,
    );
    write(&dir, "stride.gltf", &strided);
    let o = run_in(&dir, &["check", "stride.gltf"]);
    assert_eq!(
        stderr_of(&o),
        "stride.gltf:1:1: error: invalid glTF file \"stride.gltf\": bufferViews[0].byteStride: a stride of 8 bytes is less than the 12-byte elements of accessors[0] (POSITION): its elements would overlap\n\
         \x20 help: loaded for object \"quad_mesh\" at stride.gltf:1:1\n\
         1 error in stride.gltf\n"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A camera under a parent that mirrors one axis keeps the view (−Z) and the up (+Y) that
/// the world matrix gives it, in `convert`'s RON as when the file is the scene: under
/// `scale [-1, 1, 1]` it looks down −Z with +Y up (it was turned upside down before),
/// under `[1, -1, 1]` its up is −Y, where the mirror sends it.
#[test]
fn a_camera_under_a_mirroring_parent_keeps_its_view_and_up() {
    let dir = scratch_dir("gltf_spec_mirror_camera");
    for (name, scale, up) in [
        ("mirror_x", "[-1, 1, 1]", Vec3::Y),
        ("mirror_y", "[1, -1, 1]", Vec3::NEG_Y),
    ] {
        let text = one_node(PRIMITIVE, r#"{"mesh": 0}"#)
            .replace(
                r#""nodes": [{"mesh": 0}]"#,
                &format!(
                    r#""nodes": [{{"mesh": 0}}, {{"name": "rig", "scale": {scale}, "translation": [0.5, 0.5, 0], "children": [2]}}, {{"name": "eye", "camera": 0, "translation": [0, 0, 3]}}]"#
                ),
            )
            .replace(r#""nodes": [0]"#, r#""nodes": [0, 1]"#)
            .replace(
                r#""asset": {"version": "2.0"},"#,
                r#""asset": {"version": "2.0"},
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],"#,
            );
        let gltf = write(&dir, &format!("{name}.gltf"), &text);
        let ron = dir.join(format!("{name}.ron"));
        let o = run_in(
            &dir,
            &[
                "convert",
                gltf.to_str().unwrap(),
                "-o",
                ron.to_str().unwrap(),
            ],
        );
        assert!(o.status.success(), "{}", stderr_of(&o));
        let scene = stagelight::scene::load_scene(&ron).unwrap_or_else(|e| panic!("{e}"));
        let cameras: Vec<glam::Affine3A> = scene
            .world
            .query::<&Camera>()
            .iter()
            .map(|c| c.world_from_camera)
            .collect();
        let world = cameras[0];
        let view = world.transform_vector3(Vec3::NEG_Z);
        let y = world.transform_vector3(Vec3::Y);
        let eye = world.transform_point3(Vec3::ZERO);
        assert!((view - Vec3::NEG_Z).length() < 1e-6, "{name}: view {view}");
        assert!((y - up).length() < 1e-6, "{name}: up {y}");
        assert!(
            (eye - Vec3::new(0.5, 0.5, 3.0)).length() < 1e-5,
            "{name}: eye {eye}"
        );
        assert!(
            world.matrix3.determinant() > 0.0,
            "{name}: a rigid placement"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The quad file with a base colour texture `image` read through `sampler` (a
/// `"samplers"` entry, or `""` for glTF's default: repeat on both axes).
fn sampled_quad(uvs: [[f32; 2]; 4], image: &str, sampler: &str) -> String {
    let (samplers, reference) = if sampler.is_empty() {
        (String::new(), "")
    } else {
        (format!(r#""samplers": [{sampler}],"#), r#", "sampler": 0"#)
    };
    let material = format!(
        r#"{{"name": "m", "pbrMetallicRoughness": {{"metallicFactor": 0, "baseColorTexture": {{"index": 0}}}}}}],
  {samplers}
  "textures": [{{"source": 0{reference}}}],
  "images": [{{"uri": "{image}"}}"#
    );
    quad(uvs, &LIST)
        .replace("PRIMITIVE", PRIMITIVE)
        .replace("MATERIALS", &material)
        .replace("NODES", r#"{"mesh": 0}"#)
        .replace("ROOTS", "0")
}

/// A sampler with `wrapS` `MIRRORED_REPEAT` and `wrapT` `CLAMP_TO_EDGE` wraps each axis its
/// own way, without a warning: the image on u ∈ [0, 2] is the image beside its mirror image
/// (a texture twice as wide, clamped, on u ∈ [0, 1] renders the same pixels), t ∈ [−½, 1½]
/// clamps, and the loaded texture reads u = 1.25 as u = 0.75 and u = −0.25 as u = 0.25.
/// `convert` writes the wrap as `PerAxis(u: Mirror, v: Clamp)`, read back as the same
/// texture; a wrap mode glTF does not define is an error naming the modes.
#[test]
fn a_mirrored_and_clamped_sampler_wraps_each_axis_as_gltf_says() {
    use stagelight::components::graph::{Op, UvWrap, Wrap};
    let dir = scratch_dir("gltf_spec_sampler");
    let texels: Vec<[u8; 3]> = (0..16u8)
        .map(|k| [k * 16, 255 - k * 13, ((k as u32 * 97) % 251) as u8])
        .collect();
    crate::common::png::write_rgb(&dir.join("tex.png"), 4, 4, &texels);
    // Each row of the image followed by the same row reversed.
    let beside: Vec<[u8; 3]> = texels
        .chunks(4)
        .flat_map(|row| row.iter().chain(row.iter().rev()).copied())
        .collect();
    crate::common::png::write_rgb(&dir.join("beside.png"), 8, 4, &beside);
    let mirror_clamp = r#"{"wrapS": 33648, "wrapT": 33071}"#;
    let clamp = r#"{"wrapS": 33071, "wrapT": 33071}"#;
    let wide = [[0.0, -0.5], [2.0, -0.5], [2.0, 1.5], [0.0, 1.5]];
    let narrow = [[0.0, -0.5], [1.0, -0.5], [1.0, 1.5], [0.0, 1.5]];
    write(
        &dir,
        "mirror.gltf",
        &sampled_quad(wide, "tex.png", mirror_clamp),
    );
    write(
        &dir,
        "beside.gltf",
        &sampled_quad(narrow, "beside.png", clamp),
    );
    write(&dir, "repeat.gltf", &sampled_quad(wide, "tex.png", ""));

    let o = run_in(&dir, &["check", "mirror.gltf"]);
    assert_eq!((o.status.code(), stderr_of(&o)), (Some(0), String::new()));

    let mirrored = render_included(&dir, "mirror.gltf");
    let want = render_included(&dir, "beside.gltf");
    let repeated = render_included(&dir, "repeat.gltf");
    let largest = |a: &[Vec3], b: &[Vec3]| {
        a.iter()
            .zip(b)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0f32, f32::max)
    };
    assert!(
        largest(&mirrored, &want) < 1e-6,
        "{}",
        largest(&mirrored, &want)
    );
    assert!(
        largest(&repeated, &want) > 0.05,
        "the wrap changes the picture"
    );

    // A mode glTF does not define is the file's error, named by its JSON path.
    let bad = r#"{"wrapS": 33648, "wrapT": 12345}"#;
    let text = sampled_quad(wide, "tex.png", bad);
    write(&dir, "bad.gltf", &text);
    let o = run_in(&dir, &["check", "bad.gltf"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        format!(
            "bad.gltf:{}: error: invalid glTF file: samplers[0].wrapT: invalid glTF: not a wrap mode: expected 33071 (CLAMP_TO_EDGE), 33648 (MIRRORED_REPEAT) or 10497 (REPEAT)\n\
             1 error in bad.gltf\n",
            crate::gltf_validity::after(&text, "\"wrapT\": ")
        )
    );

    // The loaded texture: u mirrors, v clamps.
    let textures = |file: &str| -> Vec<_> {
        let scene =
            stagelight::scene::load_scene(&dir.join(file)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.located_warnings, Vec::<String>::new());
        let ops: Vec<Op> = scene
            .world
            .query::<&stagelight::components::Material>()
            .iter()
            .filter_map(|m| m.graph.clone())
            .flat_map(|g| g.program.ops.clone())
            .collect();
        ops.into_iter()
            .filter_map(|op| match op {
                Op::Image { texture, .. } => Some(texture),
                _ => None,
            })
            .collect()
    };
    let loaded = textures("mirror.gltf");
    assert_eq!(loaded.len(), 1);
    let t = &loaded[0];
    let mirror_clamp = UvWrap {
        u: Wrap::Mirror,
        v: Wrap::Clamp,
    };
    assert_eq!(t.wrap, mirror_clamp);
    let at = |u: f32, v: f32| t.sample(glam::Vec2::new(u, v));
    let same = |(u0, v0), (u1, v1)| {
        let (a, b) = (at(u0, v0), at(u1, v1));
        assert!(
            (a - b).abs().max_element() < 1e-6,
            "({u0}, {v0}): {a} vs ({u1}, {v1}): {b}"
        );
    };
    for v in [0.125, 0.6] {
        same((1.25, v), (0.75, v));
        same((-0.25, v), (0.25, v));
        same((1.875, v), (0.125, v));
    }
    same((0.375, -3.0), (0.375, 0.0));
    same((0.375, 7.0), (0.375, 1.0));

    // Converted to RON: the per-axis wrap is written, and read back as the same texture.
    let o = run_in(&dir, &["convert", "mirror.gltf", "-o", "mirror.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let ron = std::fs::read_to_string(dir.join("mirror.ron")).unwrap();
    let compact: String = ron.split_whitespace().collect();
    assert!(
        compact.contains("wrap:PerAxis(u:Mirror,v:Clamp,),"),
        "{ron}"
    );
    assert_eq!(textures("mirror.ron"), loaded);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The bake hint for a glTF file's overlapping `TEXCOORD_1` says how to get generated UVs
/// from a glTF file (which has no `uvs:` field).
#[test]
fn the_overlap_hint_of_a_gltf_bake_says_how_to_unwrap() {
    let dir = scratch_dir("gltf_spec_overlap_hint");
    // Both triangles on the same UV triangle.
    let text = quad([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 0.0]], &LIST)
        .replace(
            "PRIMITIVE",
            r#"{"attributes": {"POSITION": 0, "TEXCOORD_1": 1}, "indices": 3, "material": 0}"#,
        )
        .replace("MATERIALS", MATERIAL)
        .replace("NODES", r#"{"name": "q", "mesh": 0}"#)
        .replace("ROOTS", "0");
    write(&dir, "overlap.gltf", &text);
    let o = run_in(&dir, &["bake", "overlap.gltf", "-o", "out"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr_of(&o);
    assert!(
        err.contains(
            "overlap.gltf:1:1: error: bake request on instance \"q\": its UVs overlap (\
             "
        ) && err.contains(
            "\n  help: give TEXCOORD_1 unique lightmap UVs, or write the scene as RON (`stagelight convert overlap.gltf -o scene.ron`) and set `uvs: Unwrap` in the instance's bake there to generate lightmap UVs (a glTF file's bakes read its TEXCOORD_1); `stagelight bake scene.ron --write-gltf` then writes the glTF with them as TEXCOORD_1\n"
        ),
        "{err}"
    );
    assert!(!dir.join("out").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
