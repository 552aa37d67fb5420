//! The names a glTF scene's elements get in the description: one table per namespace of a
//! scene (materials, lights, cameras, instances, objects and groups together, as
//! `docs/scene-format.md` scopes them), so a node named like its material keeps its name.
//!
//! In each table the names the file gives (node, material, light and camera names, made
//! safe for a file name) are reserved for their elements: a name the reader makes up — an
//! unnamed element's `node3`, a primitive's `<node>_<k>`, a node's `<node>_node`, a
//! repeat's `_2`, `_3`, … — never takes one of them, so the user's node `x_1` is instance
//! `x_1` (and its baked textures `x_1_*.png`) beside node `x`'s second primitive, whatever
//! order the walk meets them in.

use std::collections::HashSet;

/// Unique, file-name-safe names of one namespace.
#[derive(Debug, Default)]
pub struct Names {
    used: HashSet<String>,
    /// The names the file gives to this namespace's elements (made safe): only a name the
    /// file gives takes one of them ([`Names::take_given`]).
    reserved: HashSet<String>,
}

/// The name tables of the namespaces a glTF scene fills.
#[derive(Debug, Default)]
pub struct SceneNames {
    /// Material names.
    pub materials: Names,
    /// Light names.
    pub lights: Names,
    /// Camera names.
    pub cameras: Names,
    /// Instance names (the nodes' names are these: a node's instance, and its baked files).
    pub instances: Names,
    /// Object and group names (one namespace).
    pub objects: Names,
}

impl SceneNames {
    /// The tables of `doc`, each reserving the names the file gives to its elements; the
    /// objects' the name of `scene` (the root group).
    pub fn of(doc: &gltf::Document, scene: &gltf::Scene<'_>) -> Self {
        let reserve = |names: Vec<Option<&str>>| {
            Names::reserving(names.into_iter().flatten().filter_map(|n| given(Some(n))))
        };
        Self {
            materials: reserve(doc.materials().map(|m| m.name()).collect()),
            lights: reserve(
                doc.lights()
                    .into_iter()
                    .flatten()
                    .map(|l| l.name())
                    .collect(),
            ),
            cameras: reserve(doc.cameras().map(|c| c.name()).collect()),
            instances: reserve(doc.nodes().map(|n| n.name()).collect()),
            objects: reserve(vec![scene.name()]),
        }
    }
}

/// `preferred` made safe for a file name: letters, digits, `_`, `-`, `.`; others become
/// `_`, and `_` goes before an empty name or one starting with `.`.
pub fn safe(preferred: &str) -> String {
    let mut base: String = preferred
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || matches!(c, '_' | '-' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if base.is_empty() || base.starts_with('.') {
        base.insert(0, '_');
    }
    base
}

/// An element's name from the file, `None` for none or an empty one (both get the
/// element's fallback name, such as `node3`).
pub fn given(name: Option<&str>) -> Option<&str> {
    name.filter(|n| !n.is_empty())
}

/// Every node's label, by index: its name, or `node<i>` for one without (or with an
/// empty name), which yields to the file's names: `node4` becomes `node4_2` when a node
/// of the file is named `node4`.
pub fn node_labels(doc: &gltf::Document) -> Vec<String> {
    let named: HashSet<String> = doc
        .nodes()
        .filter_map(|n| given(n.name()))
        .map(safe)
        .collect();
    doc.nodes()
        .map(|node| match given(node.name()) {
            Some(name) => name.to_string(),
            None => {
                let base = format!("node{}", node.index());
                let mut label = base.clone();
                let mut k = 2;
                while named.contains(&label) {
                    label = format!("{base}_{k}");
                    k += 1;
                }
                label
            }
        })
        .collect()
}

impl Names {
    /// Names that keep the `given` names (made safe) for the elements the file gives them to.
    pub fn reserving<'a>(given: impl IntoIterator<Item = &'a str>) -> Self {
        Self {
            used: HashSet::new(),
            reserved: given.into_iter().map(safe).collect(),
        }
    }

    /// A name the file gives to an element, made safe (letters, digits, `_`, `-`, `.`;
    /// others become `_`): as written unless an element of the file with the same name took
    /// it first, then unique with `_2`, `_3`, … appended, skipping the file's names.
    pub fn take_given(&mut self, given: &str) -> String {
        let base = safe(given);
        if self.used.insert(base.clone()) {
            return base;
        }
        self.suffixed(&base)
    }

    /// A name the reader makes up (`node3`, `box_1`, `box_node`), made safe and unique: as
    /// made up unless taken or a name the file gives, else with `_2`, `_3`, … appended,
    /// skipping the file's names.
    pub fn take(&mut self, made_up: &str) -> String {
        let base = safe(made_up);
        if !self.reserved.contains(&base) && self.used.insert(base.clone()) {
            return base;
        }
        self.suffixed(&base)
    }

    /// `base_2`, `base_3`, …: the first neither taken nor a name the file gives.
    fn suffixed(&mut self, base: &str) -> String {
        let mut k = 2;
        loop {
            let name = format!("{base}_{k}");
            if !self.reserved.contains(&name) && self.used.insert(name.clone()) {
                return name;
            }
            k += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_made_safe_and_unique() {
        let mut n = Names::default();
        assert_eq!(n.take("Cube"), "Cube");
        assert_eq!(n.take("Cube"), "Cube_2");
        assert_eq!(n.take_given("a/b c"), "a_b_c");
        assert_eq!(n.take(""), "_");
        assert_eq!(n.take("../x"), "_.._x");
    }

    /// A repeat's suffix skips the file's names: with nodes `box`, `box`, `box_2`, the
    /// second `box` is `box_3` whichever comes first (it took `box_2`, and the user's
    /// `box_2` became `box_2_2`).
    #[test]
    fn repeats_skip_the_files_names() {
        let reserved = || Names::reserving(["box", "box", "box_2"]);
        let mut n = reserved();
        assert_eq!(
            [
                n.take_given("box"),
                n.take_given("box"),
                n.take_given("box_2")
            ],
            ["box", "box_3", "box_2"]
        );
        let mut n = reserved();
        assert_eq!(
            [
                n.take_given("box_2"),
                n.take_given("box"),
                n.take_given("box")
            ],
            ["box_2", "box", "box_3"]
        );
    }

    /// A made-up name never takes a name the file gives, before or after the element it
    /// belongs to: node `x`'s second primitive beside the user's node `x_1`.
    #[test]
    fn made_up_names_never_take_the_files_names() {
        let mut n = Names::reserving(["x", "x_1"]);
        assert_eq!(
            [n.take("x_0"), n.take("x_1"), n.take_given("x_1")],
            ["x_0", "x_1_2", "x_1"]
        );
        let mut n = Names::reserving(["x", "x_1"]);
        assert_eq!(
            [n.take_given("x_1"), n.take("x_0"), n.take("x_1")],
            ["x_1", "x_0", "x_1_2"]
        );
    }
}
