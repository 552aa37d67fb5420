//! Node values glTF 2.0 forbids and the `gltf` crate accepts: a `rotation` that is not a unit
//! quaternion, and a node listed as the child of two parents. Each is an error naming the
//! node (at the value's line and column in a `.gltf`, at the start of a `.glb`), never
//! repaired in silence; a rotation whose length is within [`ROTATION_TOLERANCE`] of 1
//! (written with few digits) is normalised by [`local_matrix`].

use glam::DMat4;

use super::json_positions::{value_position, Step};
use super::{at_file, Walk};
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

/// Errors for every node of the file with a rotation that is not a unit quaternion or with
/// a second parent, in node order.
pub fn check(w: &mut Walk<'_>) {
    let file = w.file;
    let doc = &file.doc;
    let mut parent: Vec<Option<usize>> = vec![None; doc.nodes().count()];
    let mut errors = Vec::new();
    for node in doc.nodes() {
        if let gltf::scene::Transform::Decomposed { rotation, .. } = node.transform() {
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
                Some(_) => {}
                None => *slot = Some(node.index()),
            }
        }
    }
    w.errors.extend(errors);
}

/// An error at `nodes[index].<key>` in a `.gltf`, else at the start of the file.
fn located(w: &Walk<'_>, index: usize, key: &str, message: String, help: &str) -> Diagnostic {
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
