//! What a glTF file may hold that the reader cannot use as written, on small `.gltf` files:
//! a hidden node (`"scale": [0, 0, 0]`, valid glTF) is skipped with a warning, a transform
//! that is not finite or is both a `matrix` and TRS is one error naming the node;
//! `KHR_lights_punctual` values outside the extension's ranges are errors naming the light
//! (never clamped), error paths use the file's names (`KHR_lights_punctual`); morph
//! targets, skins and material extensions the reader does not read are located warnings;
//! glTF 1.0, 3.0 and a newer `minVersion` are refused; a node listed twice as a root or a
//! child is an error; unnamed and empty-named nodes get
//! fallback names that yield to the file's; integer `TEXCOORD_n` must be normalised.

use std::path::Path;

use crate::common::cli::{run_in, scratch_dir, stderr_of};
use crate::gltf_spec::{one_node, quad, write, LIST, MATERIAL, PLAIN_UVS, PRIMITIVE};

/// `line:column` (1-based, columns in characters) just after the first `needle` in `text`:
/// where the value of a member written `"key": ` starts.
pub(crate) fn after(text: &str, needle: &str) -> String {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle} not in the file"))
        + needle.len();
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let column = before[before.rfind('\n').map_or(0, |p| p + 1)..]
        .chars()
        .count()
        + 1;
    format!("{line}:{column}")
}

/// The quad file with `nodes` placed as the scene's roots `roots`.
fn nodes(nodes: &str, roots: &str) -> String {
    quad(PLAIN_UVS, &LIST)
        .replace("PRIMITIVE", PRIMITIVE)
        .replace("MATERIALS", MATERIAL)
        .replace("NODES", nodes)
        .replace("ROOTS", roots)
}

/// The names of the scene's primitive instances (each carries a default per-vertex bake
/// named after it).
fn instance_names(path: &Path) -> Vec<String> {
    let scene = stagelight::scene::load_scene(path).unwrap_or_else(|e| panic!("{e}"));
    let mut names: Vec<String> = scene
        .world
        .query::<&stagelight::components::BakeRequest>()
        .iter()
        .map(|r| r.name.clone())
        .collect();
    names.sort();
    names
}

/// A second node of the mesh with `"scale": [0, 0, 0]` is skipped with a warning at its
/// scale (the file loads, with one instance); a scale of 1e39 (infinite in f32) is one
/// error at the node's scale; `matrix` beside `translation` is an error at the matrix.
#[test]
fn hidden_nodes_are_skipped_and_bad_transforms_are_one_error_each() {
    let dir = scratch_dir("gltf_validity_nodes");
    let text = nodes(
        "{\"name\": \"shown\", \"mesh\": 0},\n    {\"name\": \"hidden\", \"mesh\": 0, \"scale\": [0, 0, 0]}",
        "0, 1",
    );
    let hidden = write(&dir, "hidden.gltf", &text);
    let o = run_in(&dir, &["check", "hidden.gltf"]);
    assert_eq!(
        (o.status.code(), stderr_of(&o)),
        (
            Some(0),
            format!(
                "hidden.gltf:{}: warning: nodes[1] (\"hidden\"): skipped it and the nodes under it: its \"scale\" [0, 0, 0] flattens space (a hidden instance), and a flat transform cannot be rendered\n",
                after(&text, "\"scale\": ")
            )
        )
    );
    assert_eq!(instance_names(&hidden), ["shown"]);

    let text = nodes(
        "{\"name\": \"big\", \"mesh\": 0,\n     \"scale\": [1e39, 1, 1]}",
        "0",
    );
    write(&dir, "big.gltf", &text);
    let o = run_in(&dir, &["check", "big.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "big.gltf:{}: error: nodes[0] (\"big\"): \"scale\" [inf, 1, 1] is not finite: a transform must be finite\n\
             \x20 help: write finite numbers: glTF's are 32-bit floats, so a value beyond ±3.4e38 reads as infinite\n\
             1 error in big.gltf\n",
            after(&text, "\"scale\": ")
        )
    );

    let text = nodes(
        "{\"name\": \"both\", \"mesh\": 0, \"translation\": [1, 0, 0],\n     \"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}",
        "0",
    );
    write(&dir, "both.gltf", &text);
    let o = run_in(&dir, &["check", "both.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "both.gltf:{}: error: nodes[0] (\"both\"): has both \"matrix\" and \"translation\": a glTF node's transform is a matrix or translation/rotation/scale, not both\n\
             \x20 help: keep one of the two: the matrix, or the translation, rotation and scale it is made of\n\
             1 error in both.gltf\n",
            after(&text, "\"matrix\": ")
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Light values outside the `KHR_lights_punctual` ranges are errors at the value, once per
/// light however many nodes use it; an unknown light type is named by the JSON's path.
#[test]
fn punctual_light_values_outside_their_ranges_are_errors() {
    let dir = scratch_dir("gltf_validity_lights");
    let lights = r#""extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"name": "neg", "type": "point", "intensity": -10},
    {"name": "wide", "type": "spot", "spot": {"outerConeAngle": 2.0}},
    {"name": "inverted", "type": "spot", "spot": {"innerConeAngle": 0.7, "outerConeAngle": 0.5}},
    {"name": "shut", "type": "spot", "spot": {"outerConeAngle": 0}},
    {"type": "point", "color": [2, 1, 1], "range": -1}
  ]}},
  "nodes""#;
    let text = nodes(
        r#"{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"extensions": {"KHR_lights_punctual": {"light": 3}}},
    {"extensions": {"KHR_lights_punctual": {"light": 4}}},
    {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 0, 1]}"#,
        "0, 1, 2, 3, 4, 5, 6",
    )
    .replacen("\"nodes\"", lights, 1);
    write(&dir, "lights.gltf", &text);
    let o = run_in(&dir, &["check", "lights.gltf"]);
    let at = |needle: &str| after(&text, needle);
    let l = "extensions.KHR_lights_punctual.lights";
    let intensity = "  help: \"intensity\" is in candela for point and spot lights and in lux for directional ones; 0 switches the light off\n";
    let outer = "  help: \"outerConeAngle\" is the angle from the spot's axis to the edge of its cone, in radians: 0.785 is 45°\n";
    assert_eq!(
        stderr_of(&o),
        format!(
            "lights.gltf:{}: error: {l}[0] (\"neg\"): \"intensity\" must be a finite number of at least 0, found -10\n{intensity}\
             lights.gltf:{}: error: {l}[1] (\"wide\"): \"outerConeAngle\" must be greater than 0 and at most π/2 radians (90°), found 2\n{outer}\
             lights.gltf:{}: error: {l}[2] (\"inverted\"): \"innerConeAngle\" must be at least 0 and less than \"outerConeAngle\" (0.5), found 0.7\n\
             \x20 help: \"innerConeAngle\" is where the falloff toward the outer cone begins, in radians; 0 fades across the whole cone\n\
             lights.gltf:{}: error: {l}[3] (\"shut\"): \"outerConeAngle\" must be greater than 0 and at most π/2 radians (90°), found 0\n{outer}\
             lights.gltf:{}: error: {l}[4]: \"color\" [2, 1, 1] must have components from 0 to 1\n\
             \x20 help: \"color\" is the light's linear RGB tint; its brightness belongs in \"intensity\"\n\
             lights.gltf:{}: error: {l}[4]: \"range\" must be greater than 0, found -1\n\
             \x20 help: leave \"range\" out for a light without a cutoff (stagelight ignores the cutoff anyway)\n\
             6 errors in lights.gltf\n",
            at("\"intensity\": "),
            at("{\"outerConeAngle\": "),
            at("\"innerConeAngle\": "),
            at("\"shut\", \"type\": \"spot\", \"spot\": {\"outerConeAngle\": "),
            at("\"color\": "),
            at("\"range\": "),
        )
    );

    let text = nodes(
        r#"{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}"#,
        "0, 1",
    )
    .replacen(
        "\"nodes\"",
        "\"extensions\": {\"KHR_lights_punctual\": {\"lights\": [\n    {\"type\": \"area\"}]}},\n  \"nodes\"",
        1,
    );
    write(&dir, "area.gltf", &text);
    let o = run_in(&dir, &["check", "area.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "area.gltf:{}: error: invalid glTF file: extensions.KHR_lights_punctual.lights[0].type: invalid glTF: not a light type: expected \"directional\", \"point\" or \"spot\"\n\
             1 error in area.gltf\n",
            after(&text, "{\"type\": ")
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A skin, a node's morph weights and a mesh's morph targets are each a warning at their
/// member; with non-zero default weights the target warning says they are not applied.
#[test]
fn skins_and_morph_targets_are_located_warnings() {
    let dir = scratch_dir("gltf_validity_morph");
    let primitive = PRIMITIVE.replace(
        "\"indices\"",
        "\"targets\": [{\"POSITION\": 0}], \"indices\"",
    );
    let text = quad(PLAIN_UVS, &LIST)
        .replace(
            "\"primitives\": [PRIMITIVE]}",
            "\"primitives\": [PRIMITIVE], \"weights\": [1]}",
        )
        .replace("PRIMITIVE", &primitive)
        .replace("MATERIALS", MATERIAL)
        .replace(
            "NODES",
            "{\"name\": \"arm\", \"mesh\": 0, \"skin\": 0,\n     \"weights\": [0.5]}",
        )
        .replace("ROOTS", "0")
        .replacen(
            "\"nodes\"",
            "\"skins\": [{\"joints\": [0]}],\n  \"nodes\"",
            1,
        );
    write(&dir, "morph.gltf", &text);
    let o = run_in(&dir, &["check", "morph.gltf"]);
    assert_eq!(
        (o.status.code(), stderr_of(&o)),
        (
            Some(0),
            format!(
                "morph.gltf:{}: warning: meshes[0] (\"quad\"): ignored its morph targets (the mesh is read in its base shape, without them); its default weights [1] are not applied\n\
                 morph.gltf:{}: warning: nodes[0]: ignored its skin (the mesh is read in its bind pose)\n\
                 morph.gltf:{}: warning: nodes[0]: ignored its morph weights [0.5] (the mesh is read in its base shape, without its morph targets)\n",
                after(&text, "\"targets\": "),
                after(&text, "\"skin\": "),
                after(&text, "\n     \"weights\": "),
            )
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Each material extension the reader does not read is one warning naming it and the
/// materials that use it, at the first one's extension.
#[test]
fn unread_material_extensions_are_one_warning_each() {
    let dir = scratch_dir("gltf_validity_material_extensions");
    let materials = r#"{"name": "glass", "extensions": {
      "KHR_materials_transmission": {"transmissionFactor": 1},
      "KHR_materials_clearcoat": {"clearcoatFactor": 1}}},
    {"extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}}}"#;
    let text = quad(PLAIN_UVS, &LIST)
        .replace("PRIMITIVE", PRIMITIVE)
        .replace("MATERIALS", materials)
        .replace("NODES", "{\"mesh\": 0}")
        .replace("ROOTS", "0")
        .replacen(
            "\"buffers\"",
            "\"extensionsUsed\": [\"KHR_materials_transmission\", \"KHR_materials_clearcoat\"],\n  \"buffers\"",
            1,
        );
    write(&dir, "ext.gltf", &text);
    let o = run_in(&dir, &["check", "ext.gltf"]);
    assert_eq!(
        (o.status.code(), stderr_of(&o)),
        (
            Some(0),
            format!(
                "ext.gltf:{}: warning: ignored \"KHR_materials_transmission\" on materials[0] (\"glass\") and materials[1]: this reader does not support the extension, so the materials render without it\n\
                 ext.gltf:{}: warning: ignored \"KHR_materials_clearcoat\" on materials[0] (\"glass\"): this reader does not support the extension, so the material renders without it\n",
                after(&text, "\"KHR_materials_transmission\": "),
                after(&text, "\"KHR_materials_clearcoat\": "),
            )
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// glTF 1.0 (with its version, or known by its dictionaries), 3.0 and `minVersion` 2.1 are
/// refused at `asset.version` / `asset.minVersion`; 2.1 without a `minVersion` loads.
#[test]
fn other_gltf_versions_are_refused_at_their_version() {
    let dir = scratch_dir("gltf_validity_versions");
    let v1 = "{\"asset\": {\"version\": \"1.0\"}, \"scene\": \"defaultScene\",\n \"scenes\": {\"defaultScene\": {\"nodes\": [\"node_1\"]}},\n \"meshes\": {}}";
    write(&dir, "v1.gltf", v1);
    let o = run_in(&dir, &["check", "v1.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "v1.gltf:{}: error: invalid glTF file: asset.version: glTF 1.0 is not supported (asset.version \"1.0\"): only glTF 2.0 files are read; convert it to glTF 2.0 first (gltf-pipeline does)\n\
             1 error in v1.gltf\n",
            after(v1, "\"version\": ")
        )
    );
    write(
        &dir,
        "v1_bare.gltf",
        &v1.replace("\"asset\": {\"version\": \"1.0\"}, ", ""),
    );
    let o = run_in(&dir, &["check", "v1_bare.gltf"]);
    assert_eq!(
        stderr_of(&o),
        "v1_bare.gltf:3:12: error: invalid glTF file: meshes: glTF 1.0 is not supported (no asset.version, and \"meshes\" is an object keyed by id, as in glTF 1.0): only glTF 2.0 files are read; convert it to glTF 2.0 first (gltf-pipeline does)\n\
         1 error in v1_bare.gltf\n"
    );
    let text = one_node(PRIMITIVE, "{\"mesh\": 0}");
    write(&dir, "v3.gltf", &text.replace("\"2.0\"", "\"3.0\""));
    let o = run_in(&dir, &["check", "v3.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "v3.gltf:{}: error: invalid glTF file: asset.version: glTF 3.0 is not supported (asset.version \"3.0\"): a file of another major version than 2 is not loadable by a glTF 2.0 reader\n\
             1 error in v3.gltf\n",
            after(&text, "\"version\": ")
        )
    );
    let min = text.replace("\"2.0\"}", "\"2.1\", \"minVersion\": \"2.1\"}");
    write(&dir, "min.gltf", &min);
    let o = run_in(&dir, &["check", "min.gltf"]);
    assert_eq!(
        stderr_of(&o),
        format!(
            "min.gltf:{}: error: invalid glTF file: asset.minVersion: the file needs a glTF 2.1 reader (asset.minVersion \"2.1\"); this reader implements glTF 2.0\n\
             1 error in min.gltf\n",
            after(&min, "\"minVersion\": ")
        )
    );
    write(&dir, "v21.gltf", &text.replace("\"2.0\"", "\"2.1\""));
    let o = run_in(&dir, &["check", "v21.gltf"]);
    assert_eq!((o.status.code(), stderr_of(&o)), (Some(0), String::new()));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A node named "" gets the fallback name of an unnamed node (`node0`), and the fallback
/// of unnamed node 1 yields to the file's own node named `node1` (`node1_2`).
#[test]
fn fallback_node_names_yield_to_the_files_names() {
    let dir = scratch_dir("gltf_validity_names");
    let text = nodes(
        r#"{"name": "", "mesh": 0}, {"mesh": 0}, {"name": "node1", "mesh": 0}"#,
        "0, 1, 2",
    );
    let path = write(&dir, "names.gltf", &text);
    assert_eq!(instance_names(&path), ["node0", "node1", "node1_2"]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A repeated name's suffix skips the file's own node names: nodes `box`, `box`, `box_2` are
/// `box`, `box_3`, `box_2` (the second `box` took `box_2`, and the user's `box_2` became
/// `box_2_2`, so `box_2_lightmap.png` belonged to the wrong node), in either order.
#[test]
fn repeated_names_skip_the_files_node_names() {
    let dir = scratch_dir("gltf_validity_repeats");
    for (list, roots) in [
        (
            r#"{"name": "box", "mesh": 0}, {"name": "box", "mesh": 0}, {"name": "box_2", "mesh": 0, "translation": [5, 0, 0]}"#,
            "0, 1, 2",
        ),
        (
            r#"{"name": "box_2", "mesh": 0, "translation": [5, 0, 0]}, {"name": "box", "mesh": 0}, {"name": "box", "mesh": 0}"#,
            "0, 1, 2",
        ),
    ] {
        let path = write(&dir, "repeats.gltf", &nodes(list, roots));
        assert_eq!(instance_names(&path), ["box", "box_2", "box_3"], "{list}");
        // `box_2` is the user's node (the one moved to x = 5).
        let scene = stagelight::scene::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
        let moved: Vec<(String, f32)> = scene
            .world
            .query::<(
                &stagelight::components::BakeRequest,
                &stagelight::components::WorldFromObject,
            )>()
            .iter()
            .map(|(r, m)| (r.name.clone(), m.0.translation.x))
            .filter(|(_, x)| *x != 0.0)
            .collect();
        assert_eq!(moved, [("box_2".to_string(), 5.0)], "{list}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A node listed twice among the scene's roots or among one node's children is an error at
/// the list (the specification's `uniqueItems`): it made two coincident instances.
#[test]
fn repeated_roots_and_children_are_errors() {
    let dir = scratch_dir("gltf_validity_unique");
    let roots = nodes(
        r#"{"name": "box", "mesh": 0}, {"name": "lid", "mesh": 0}"#,
        "0, 1, 1",
    );
    write(&dir, "roots.gltf", &roots);
    let o = run_in(&dir, &["check", "roots.gltf"]);
    // At the scene's `nodes` list.
    let at = after(&roots, "{\"nodes\": ");
    assert_eq!(
        (o.status.code(), stderr_of(&o)),
        (
            Some(1),
            format!(
                "roots.gltf:{at}: error: nodes[1] (\"lid\") is listed twice in the nodes of scenes[0]: a scene's root nodes are unique\n\
                 \x20 help: list each root node once; to show a mesh twice, give it to two nodes\n\
                 1 error in roots.gltf\n"
            )
        )
    );
    let children = nodes(
        r#"{"name": "box", "mesh": 0}, {"name": "pair", "children": [0, 0]}"#,
        "1",
    );
    write(&dir, "children.gltf", &children);
    let o = run_in(&dir, &["check", "children.gltf"]);
    let at = after(&children, "\"children\": ");
    assert_eq!(
        (o.status.code(), stderr_of(&o)),
        (
            Some(1),
            format!(
                "children.gltf:{at}: error: nodes[0] (\"box\") is listed twice in the children of nodes[1]: a node's children are unique\n\
                 \x20 help: list each child once; to show a mesh twice, give it to two nodes\n\
                 1 error in children.gltf\n"
            )
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Integer `TEXCOORD_0` must be normalised (the specification's accessor types; raw integers
/// need `KHR_mesh_quantization`), like `COLOR_0`.
#[test]
fn unnormalised_integer_texture_coordinates_are_an_error() {
    let dir = scratch_dir("gltf_validity_texcoord");
    let u16_uvs = |normalized: &str| {
        one_node(
            &PRIMITIVE.replace("\"TEXCOORD_0\": 1", "\"TEXCOORD_0\": 4"),
            "{\"mesh\": 0}",
        )
        .replacen(
            "\"type\": \"SCALAR\"}\n  ]",
            &format!(
                "\"type\": \"SCALAR\"}},\n    {{\"bufferView\": 2, \"componentType\": 5123, \"count\": 4, \"type\": \"VEC2\"{normalized}}}\n  ]"
            ),
            1,
        )
    };
    write(&dir, "uv.gltf", &u16_uvs(""));
    let o = run_in(&dir, &["check", "uv.gltf"]);
    assert_eq!(
        stderr_of(&o),
        "uv.gltf:1:1: error: invalid glTF file \"uv.gltf\": accessors[4]: TEXCOORD_0: U16 components must be normalized (\"normalized\": true) to be texture coordinates (unnormalized integers need KHR_mesh_quantization)\n\
         \x20 help: loaded for object \"quad_mesh\" at uv.gltf:1:1\n\
         1 error in uv.gltf\n"
    );
    write(&dir, "uvn.gltf", &u16_uvs(", \"normalized\": true"));
    let o = run_in(&dir, &["check", "uvn.gltf"]);
    assert_eq!((o.status.code(), stderr_of(&o)), (Some(0), String::new()));
    let _ = std::fs::remove_dir_all(&dir);
}
