//! The names a glTF scene's nodes get, which name their baked files: a node named like its
//! material (or a light) keeps its name — materials, lights, cameras, instances and
//! objects are separate namespaces, as in RON — and a made-up name (a primitive's
//! `<node>_<k>`) never takes a name the file gives to a node, so `x_1_ao.png` is the user's
//! node `x_1`'s whatever order the nodes come in. Checked on `bake` (the files written)
//! and `convert` (the instances of the RON).

use std::path::Path;

use serde_json::{json, Value};

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

/// A glTF file being built: its JSON and its one binary buffer.
pub(crate) struct Glb {
    pub(crate) json: Value,
    bin: Vec<u8>,
}

impl Glb {
    pub(crate) fn new() -> Glb {
        Glb {
            json: json!({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}],
                         "nodes": [], "meshes": [], "accessors": [], "bufferViews": []}),
            bin: Vec::new(),
        }
    }

    /// Adds `bytes` as a view and an accessor of `count` elements of `kind`; its index.
    fn accessor(&mut self, bytes: &[u8], count: usize, kind: &str, component: u32) -> usize {
        let view = self.json["bufferViews"].as_array().unwrap().len();
        self.json["bufferViews"]
            .as_array_mut()
            .unwrap()
            .push(json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()}));
        self.bin.extend_from_slice(bytes);
        let accessors = self.json["accessors"].as_array_mut().unwrap();
        accessors.push(json!({"bufferView": view, "componentType": component,
                              "count": count, "type": kind}));
        accessors.len() - 1
    }

    pub(crate) fn floats<const N: usize>(&mut self, values: &[[f32; N]], kind: &str) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        self.accessor(&bytes, values.len(), kind, 5126)
    }

    /// A primitive of a `side` × `side` quad in z = 0 at `x`, its UVs on `TEXCOORD_0` and
    /// (when `lightmap_uvs`) `TEXCOORD_1`.
    pub(crate) fn quad(&mut self, x: f32, side: f32, lightmap_uvs: bool) -> Value {
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0f32]];
        let position = self.floats(&corners.map(|[u, v]| [x + u * side, v * side, 0.0]), "VEC3");
        let accessors = self.json["accessors"].as_array_mut().unwrap();
        accessors[position]["min"] = json!([x, 0.0, 0.0]);
        accessors[position]["max"] = json!([x + side, side, 0.0]);
        let uv = self.floats(&corners, "VEC2");
        let indices: Vec<u8> = [0u32, 1, 2, 0, 2, 3]
            .iter()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        let indices = self.accessor(&indices, 6, "SCALAR", 5125);
        let mut attributes = json!({"POSITION": position, "TEXCOORD_0": uv});
        if lightmap_uvs {
            attributes["TEXCOORD_1"] = json!(uv);
        }
        json!({"attributes": attributes, "indices": indices})
    }

    /// Adds the mesh `name` of `primitives`; its index.
    pub(crate) fn mesh(&mut self, name: &str, primitives: Vec<Value>) -> usize {
        let meshes = self.json["meshes"].as_array_mut().unwrap();
        meshes.push(json!({"name": name, "primitives": primitives}));
        meshes.len() - 1
    }

    /// Adds `node` as a root node of the scene.
    pub(crate) fn root(&mut self, node: Value) {
        let nodes = self.json["nodes"].as_array_mut().unwrap();
        nodes.push(node);
        let index = nodes.len() - 1;
        self.json["scenes"][0]["nodes"]
            .as_array_mut()
            .unwrap()
            .push(json!(index));
    }

    /// The GLB file.
    pub(crate) fn write(&self, path: &Path) {
        let mut json = self.json.clone();
        json["buffers"] = json!([{"byteLength": self.bin.len()}]);
        let mut text = serde_json::to_vec(&json).unwrap();
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let total = 12 + 8 + text.len() + 8 + self.bin.len();
        let mut out = b"glTF".to_vec();
        for n in [2, total, text.len()] {
            out.extend((n as u32).to_le_bytes());
        }
        out.extend(b"JSON");
        out.extend(&text);
        out.extend((self.bin.len() as u32).to_le_bytes());
        out.extend(b"BIN\0");
        out.extend(&self.bin);
        std::fs::write(path, out).unwrap();
    }
}

/// The instance names of the RON that `stagelight convert` writes of `file` in `dir`.
fn converted_instances(dir: &Path, file: &str) -> Vec<String> {
    let o = run_in(dir, &["convert", file, "-o", "converted.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let ron = std::fs::read_to_string(dir.join("converted.ron")).unwrap();
    let instances =
        &ron[ron.find("\n    instances: [").unwrap()..ron.find("\n    groups: [").unwrap()];
    instances
        .lines()
        .filter_map(|l| l.trim().strip_prefix("name: \""))
        .map(|n| n.trim_end_matches("\",").to_string())
        .collect()
}

/// The files `stagelight bake file -o out` writes in `dir/out`.
fn baked_files(dir: &Path, file: &str) -> Vec<String> {
    let _ = std::fs::remove_dir_all(dir.join("out"));
    let o = run_in(dir, &["bake", file, "-o", "out", "--seed", "3"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    dir_names(&dir.join("out"))
}

/// Material `wall` on node `wall`, material `lamp` on node `lamp` beside a light `lamp`
/// (a Blender export names them alike): the nodes keep their names — instances `wall` and
/// `lamp`, baked as `wall_*.png` and `lamp_*.png` (were `wall_2`, `lamp_2`).
#[test]
fn a_node_named_like_its_material_or_a_light_keeps_its_name() {
    let dir = scratch_dir("gltf_names_namespaces");
    let mut g = Glb::new();
    g.json["materials"] = json!([{"name": "wall"}, {"name": "lamp"}]);
    for (k, name) in ["wall", "lamp"].into_iter().enumerate() {
        let mut prim = g.quad(k as f32, 0.25, true);
        prim["material"] = json!(k);
        let mesh = g.mesh("m", vec![prim]);
        g.root(json!({"name": name, "mesh": mesh}));
    }
    g.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    g.json["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"name": "lamp", "type": "point", "intensity": 100}]}});
    g.root(json!({"name": "bulb", "translation": [0, 0, 2],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}}));
    g.write(&dir.join("named.glb"));
    assert_eq!(converted_instances(&dir, "named.glb"), ["wall", "lamp"]);
    let ron = std::fs::read_to_string(dir.join("converted.ron")).unwrap();
    for kept in [
        "name: \"wall\",\n            shader",
        "name: \"lamp\",\n            shader",
        "name: \"lamp\",\n            kind",
    ] {
        assert!(ron.contains(kept), "{kept:?} not in\n{ron}");
    }
    assert_eq!(
        baked_files(&dir, "named.glb"),
        [
            "lamp_ao.png",
            "lamp_lightmap.png",
            "wall_ao.png",
            "wall_lightmap.png"
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Node `x` shows a mesh of two primitives (instances `x_0`, `x_1`…) beside the user's node
/// `x_1`: the user's node is `x_1` and the made-up name yields (`x_1_2`), whichever node
/// comes first, so `x_1_ao.png` is the user's node's (at x = 5).
#[test]
fn a_primitives_made_up_name_yields_to_a_node_of_that_name() {
    let dir = scratch_dir("gltf_names_primitives");
    for user_node_first in [false, true] {
        let mut g = Glb::new();
        let two = vec![g.quad(0.0, 0.25, true), g.quad(1.0, 0.25, true)];
        let two = g.mesh("two", two);
        let one = vec![g.quad(0.0, 0.25, true)];
        let one = g.mesh("one", one);
        let x = json!({"name": "x", "mesh": two});
        let x_1 = json!({"name": "x_1", "mesh": one, "translation": [5, 0, 0]});
        if user_node_first {
            g.root(x_1);
            g.root(x);
        } else {
            g.root(x);
            g.root(x_1);
        }
        g.write(&dir.join("clash.glb"));
        let mut names = converted_instances(&dir, "clash.glb");
        names.sort();
        assert_eq!(
            names,
            ["x_0", "x_1", "x_1_2", "x_node"],
            "{user_node_first}"
        );
        assert_eq!(
            baked_files(&dir, "clash.glb"),
            [
                "x_0_ao.png",
                "x_0_lightmap.png",
                "x_1_2_ao.png",
                "x_1_2_lightmap.png",
                "x_1_ao.png",
                "x_1_lightmap.png"
            ]
        );
        // Where each request bakes: `x_1` is the user's node, moved to x = 5.
        let scene =
            stagelight::scene::load_scene(&dir.join("clash.glb")).unwrap_or_else(|e| panic!("{e}"));
        let moved: Vec<(String, f32)> = scene
            .world
            .query::<(
                &stagelight::components::BakeRequest,
                &stagelight::components::WorldFromObject,
            )>()
            .iter()
            .map(|(r, m)| (r.name.clone(), m.0.translation.x))
            .filter(|(_, x)| *x == 5.0)
            .collect();
        assert_eq!(moved, [("x_1".to_string(), 5.0)], "{user_node_first}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
