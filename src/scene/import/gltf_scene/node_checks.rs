//! Node values glTF 2.0 forbids and the `gltf` crate accepts: a `rotation` that is not a unit
//! quaternion, a `translation`, `scale` or `matrix` that is not finite, a `matrix` beside
//! `translation`/`rotation`/`scale` (the validator's NODE_MATRIX_TRS), and a node listed as
//! the child of two parents. Each is one error naming the node (at the value's line and
//! column in a `.gltf`, at the start of a `.glb`), never repaired in silence; a rotation
//! whose length is within [`ROTATION_TOLERANCE`] of 1 (written with few digits) is
//! normalised by [`local_matrix`].
//!
//! A node whose transform flattens space (`"scale": [0, 0, 0]`, glTF's way to hide an
//! instance) is valid glTF but cannot be placed: [`hidden`] says so, and the walk skips the
//! node and everything under it with a warning.

use glam::{DMat3, DMat4};

use super::json_positions::{value_position, Step};
use super::{at_file, Walk};
use crate::scene::desc_values::is_singular;
use crate::scene::message::Diagnostic;

/// How far from 1 a rotation quaternion's length may be: closer, it is normalised (exporters
/// that write 4 to 6 digits stay well inside); farther, it is an error.
pub const ROTATION_TOLERANCE: f64 = 1e-3;

/// The node's label for messages: `nodes[3] ("arm")`, or `nodes[3]` without a name.
pub fn label(node: &gltf::Node<'_>) -> String {
    match node.name() {
        Some(n) => format!("nodes[{}] (\"{n}\")", node.index()),
        None => format!("nodes[{}]", node.index()),
    }
}

/// The length of a rotation `[x, y, z, w]`, in f64.
fn length(r: [f32; 4]) -> f64 {
    r.iter().map(|&c| f64::from(c).powi(2)).sum::<f64>().sqrt()
}

/// The node's local matrix (column-major, f64). A `rotation` whose length is off 1 by more
/// than f32 rounding is normalised first (one outside [`ROTATION_TOLERANCE`] was refused by
/// [`check`]); others are used as written, so unit rotations give the crate's matrix.
pub fn local_matrix(node: &gltf::Node<'_>) -> DMat4 {
    let mut transform = node.transform();
    if let gltf::scene::Transform::Decomposed { rotation, .. } = &mut transform {
        let len = length(*rotation);
        if len.is_finite() && len > 0.0 && (len - 1.0).abs() > 1e-6 {
            *rotation = rotation.map(|c| (f64::from(c) / len) as f32);
        }
    }
    DMat4::from_cols_array_2d(&transform.matrix().map(|c| c.map(f64::from)))
}

/// The first component of `values` that is not finite, with its index.
fn not_finite(values: &[f32]) -> Option<(usize, f32)> {
    values
        .iter()
        .copied()
        .enumerate()
        .find(|(_, v)| !v.is_finite())
}

/// The error for a node with both `matrix` and TRS properties, or with a `translation`,
/// `scale` or `matrix` that is not finite (one per node: the first found).
fn transform_error(w: &Walk<'_>, node: &gltf::Node<'_>) -> Option<Diagnostic> {
    let json = &w.file.doc.as_json().nodes[node.index()];
    let trs: Vec<&str> = [
        ("translation", json.translation.is_some()),
        ("rotation", json.rotation.is_some()),
        ("scale", json.scale.is_some()),
    ]
    .into_iter()
    .filter_map(|(key, present)| present.then_some(key))
    .collect();
    if json.matrix.is_some() && !trs.is_empty() {
        let list = trs
            .iter()
            .map(|k| format!("\"{k}\""))
            .collect::<Vec<_>>()
            .join(", ");
        return Some(located(
            w,
            node.index(),
            "matrix",
            format!(
                "{}: has both \"matrix\" and {list}: a glTF node's transform is a matrix or translation/rotation/scale, not both",
                label(node)
            ),
            "keep one of the two: the matrix, or the translation, rotation and scale it is made of",
        ));
    }
    let help = "write finite numbers: glTF's are 32-bit floats, so a value beyond ±3.4e38 reads as infinite";
    if let Some(m) = json.matrix {
        if let Some((k, v)) = not_finite(&m) {
            return Some(located(
                w,
                node.index(),
                "matrix",
                format!(
                    "{}: \"matrix\" element {k} is {v}: a transform must be finite",
                    label(node)
                ),
                help,
            ));
        }
    }
    for (key, values) in [("translation", json.translation), ("scale", json.scale)] {
        let Some(values) = values else { continue };
        if not_finite(&values).is_some() {
            let [x, y, z] = values;
            return Some(located(
                w,
                node.index(),
                key,
                format!(
                    "{}: \"{key}\" [{x}, {y}, {z}] is not finite: a transform must be finite",
                    label(node)
                ),
                help,
            ));
        }
    }
    None
}

/// Why `node` cannot be placed although it is valid glTF: its local transform flattens
/// space (a zero scale hides an instance), as the JSON key to locate and a warning; `None`
/// for a placeable node.
pub fn hidden(node: &gltf::Node<'_>) -> Option<(&'static str, String)> {
    let m = local_matrix(node);
    if !m.is_finite() || !is_singular(&DMat3::from_mat4(m)) {
        return None;
    }
    let (key, what) = match node.transform() {
        gltf::scene::Transform::Decomposed {
            scale: [x, y, z], ..
        } => ("scale", format!("\"scale\" [{x}, {y}, {z}]")),
        gltf::scene::Transform::Matrix { .. } => (
            "matrix",
            format!("\"matrix\" (determinant {})", m.determinant()),
        ),
    };
    Some((
        key,
        format!(
            "{}: skipped it and the nodes under it: its {what} flattens space (a hidden instance), and a flat transform cannot be rendered",
            label(node)
        ),
    ))
}

/// Errors for every node of the file with a rotation that is not a unit quaternion, a
/// transform that is not finite or is both a matrix and TRS, or with a second parent, in
/// node order.
pub fn check(w: &mut Walk<'_>) {
    let file = w.file;
    let doc = &file.doc;
    let mut parent: Vec<Option<usize>> = vec![None; doc.nodes().count()];
    let mut errors = Vec::new();
    for node in doc.nodes() {
        if let Some(error) = transform_error(w, &node) {
            errors.push(error);
        } else if let gltf::scene::Transform::Decomposed { rotation, .. } = node.transform() {
            let len = length(rotation);
            if !len.is_finite() || (len - 1.0).abs() > ROTATION_TOLERANCE {
                let [x, y, z, q] = rotation;
                let message = format!(
                    "{}: \"rotation\" [{x}, {y}, {z}, {q}] has length {}: a rotation must be a unit quaternion (length within {ROTATION_TOLERANCE} of 1)",
                    label(&node),
                    len as f32
                );
                let help = if len > 0.0 && len.is_finite() {
                    "write the rotation normalised (divide each component by the length); a scale belongs in \"scale\""
                } else {
                    "write a unit quaternion [x, y, z, w]; no rotation is [0, 0, 0, 1]"
                };
                errors.push(located(w, node.index(), "rotation", message, help));
            }
        }
        for child in node.children() {
            let Some(slot) = parent.get_mut(child.index()) else {
                continue;
            };
            match *slot {
                Some(first) if first != node.index() => errors.push(located(
                    w,
                    node.index(),
                    "children",
                    format!(
                        "{} is a child of nodes[{first}] and of nodes[{}]: a glTF node has at most one parent",
                        label(&child),
                        node.index()
                    ),
                    "list the node under one parent; to show a mesh twice, give it to two nodes",
                )),
                Some(_) => errors.push(located(
                    w,
                    node.index(),
                    "children",
                    format!(
                        "{} is listed twice in the children of nodes[{}]: a node's children are unique",
                        label(&child),
                        node.index()
                    ),
                    "list each child once; to show a mesh twice, give it to two nodes",
                )),
                None => *slot = Some(node.index()),
            }
        }
    }
    w.errors.extend(errors);
}

/// An error for each node listed twice among the roots of `scene` (the specification's
/// `uniqueItems`; it made two coincident instances, `box` and `box_2`).
pub fn check_roots(w: &mut Walk<'_>, scene: &gltf::Scene<'_>) {
    let mut seen = std::collections::HashSet::new();
    let mut errors = Vec::new();
    for node in scene.nodes() {
        if seen.insert(node.index()) {
            continue;
        }
        let path = [
            Step::Key("scenes"),
            Step::Index(scene.index()),
            Step::Key("nodes"),
        ];
        let mut d = at_file(
            w.path,
            format!(
                "{} is listed twice in the nodes of scenes[{}]: a scene's root nodes are unique",
                label(&node),
                scene.index()
            ),
        );
        if let Some((line, column)) = w.json.and_then(|json| value_position(json, &path)) {
            (d.line, d.column) = (line, column);
        }
        d.help =
            Some("list each root node once; to show a mesh twice, give it to two nodes".into());
        errors.push(d);
    }
    w.errors.extend(errors);
}

/// A diagnostic at `nodes[index].<key>` in a `.gltf`, else at the start of the file.
pub fn located(w: &Walk<'_>, index: usize, key: &str, message: String, help: &str) -> Diagnostic {
    let path = [Step::Key("nodes"), Step::Index(index), Step::Key(key)];
    let mut d = at_file(w.path, message);
    if let Some((line, column)) = w.json.and_then(|json| value_position(json, &path)) {
        d.line = line;
        d.column = column;
    }
    d.help = Some(help.into());
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_are_taken_in_f64() {
        assert_eq!(length([0.0, 0.0, 2.0, 0.0]), 2.0);
        assert_eq!(length([0.0; 4]), 0.0);
        assert!((length([0.5; 4]) - 1.0).abs() < 1e-15);
    }
}
