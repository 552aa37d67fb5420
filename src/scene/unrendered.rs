//! Warnings about what a scene asks for but a render never does: the outputs of a camera
//! other than the render camera (a render writes them only with `--camera NAME`), and an
//! instance that no group reachable from the render root lists (it is never placed). Both
//! are warnings, not errors: the scene renders, only not all of it.

use super::diagnostics::{Diagnostic, Sources};
use super::names::{Resolved, Target};
use super::syntax::{Helps, Syntax};
use super::validate::Merged;

/// Records both warnings (none of a kind whose render camera or root did not resolve: that
/// is an error of its own).
pub fn warn(src: &mut Sources, m: &Merged<'_>, r: &Resolved) {
    warn_other_cameras(src, m, r);
    warn_unplaced_instances(src, m, r);
}

/// A camera with outputs that is not the render camera.
fn warn_other_cameras(src: &mut Sources, m: &Merged<'_>, r: &Resolved) {
    let Some(render) = r.camera.and_then(|c| m.cameras.get(c)) else {
        return;
    };
    let render_name = &render.desc.name;
    let rendered: Vec<&str> = render
        .desc
        .outputs
        .iter()
        .map(|o| o.file.as_str())
        .collect();
    for (i, c) in m.cameras.iter().enumerate() {
        let name = &c.desc.name;
        // A second camera of the render camera's name is an error of its own; outputs the
        // render camera writes too (two `.mi` instances of one camera) are written.
        let written = c
            .desc
            .outputs
            .iter()
            .all(|o| rendered.contains(&o.file.as_str()));
        // A glTF file's cameras all get an output of their own: one of them is rendered,
        // the others are there to be chosen with `--camera`, not forgotten.
        let gltf = src.syntax(c.file) == Syntax::Gltf;
        if Some(i) == r.camera || written || name == render_name || gltf {
            continue;
        }
        let flag = format!("--camera {}", shell_word(name));
        let ron = format!(
            "`render {flag}` renders it; `render: (camera: \"{name}\")` makes it the scene's render camera"
        );
        let help = src.syntax(c.file).help_each(Helps {
            ron: &ron,
            mi: &format!(
                "`render {flag}` renders it; naming its instance in the `render` statement makes it the scene's render camera"
            ),
            rib: &format!("`render {flag}` renders it"),
            gltf: &format!("`render {flag}` renders it"),
        });
        let pos = src.pos(c.file, &c.at(".outputs[0].file"));
        let message = format!(
            "camera \"{name}\" has outputs, but the scene renders camera \"{render_name}\": a render writes them only with {flag}"
        );
        src.push_warning(c.file, Diagnostic::at(pos, message, Some(help)));
    }
}

/// An instance that no group reachable from the render root lists.
fn warn_unplaced_instances(src: &mut Sources, m: &Merged<'_>, r: &Resolved) {
    let (Some(root), Some(render)) = (r.root, m.render.as_ref()) else {
        return;
    };
    let placed = placed_instances(m, r, root);
    let root_name = &render.desc.root;
    for (i, it) in m.instances.iter().enumerate() {
        let name = &it.desc.name;
        // An empty or repeated name is an error of its own.
        let first = m.instances.iter().position(|o| &o.desc.name == name);
        if placed[i] || name.is_empty() || first != Some(i) {
            continue;
        }
        let help = src.syntax(it.file).help_each(Helps {
            ron: &format!(
                "add \"{name}\" to the `members` of group \"{root_name}\" (or of a group placed in it), or remove the instance"
            ),
            mi: &format!(
                "list \"{name}\" in the instgroup \"{root_name}\" (or in an instgroup placed in it), or remove the instance"
            ),
            rib: &format!("add \"{name}\" to a group placed in \"{root_name}\""),
            gltf: &format!("add node \"{name}\" to the scene's nodes or to a child list under them"),
        });
        let pos = src.pos(it.file, &it.at(".name"));
        let message = format!(
            "instance \"{name}\" is never placed: no group reachable from the render root \"{root_name}\" lists it"
        );
        src.push_warning(it.file, Diagnostic::at(pos, message, Some(help)));
    }
}

/// Which instances a group reachable from `root` lists.
fn placed_instances(m: &Merged<'_>, r: &Resolved, root: usize) -> Vec<bool> {
    let mut placed = vec![false; m.instances.len()];
    let mut seen = vec![false; m.groups.len()];
    let mut todo = vec![root];
    while let Some(g) = todo.pop() {
        if seen.get(g).is_none_or(|s| *s) {
            continue;
        }
        seen[g] = true;
        for &inst in r.group_members.get(g).into_iter().flatten() {
            placed[inst] = true;
            if let Some(Target::Group(child)) = r.instance_of[inst] {
                todo.push(child);
            }
        }
    }
    placed
}

/// `name` as one shell word: as it is when it needs no quoting, else in double quotes.
fn shell_word(name: &str) -> String {
    let plain = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-.+/:@".contains(c));
    if plain {
        name.to_string()
    } else {
        let mut quoted = String::from('"');
        for c in name.chars() {
            if matches!(c, '"' | '\\' | '$' | '`') {
                quoted.push('\\');
            }
            quoted.push(c);
        }
        quoted.push('"');
        quoted
    }
}
