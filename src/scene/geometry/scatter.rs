//! Scatter objects: their parameters, their `prototype` and `surface` names, what they make
//! reachable, the material of their copies, and what cannot be baked.

use std::collections::HashMap;

use glam::Vec3;
use hecs::Entity;

use super::{kind_name, num, report, Ctx};
use crate::components::{Scatter, TriMesh};
use crate::procedural::scatter::placements;
use crate::scene::dag::Leaf;
use crate::scene::desc::MeshDesc;
use crate::scene::diagnostics::{suggestion, Sources};
use crate::scene::validate::{Checker, Merged};
use crate::tessellation::GeometryError;

/// Checks a scatter's numbers (with the placement code's own rules) and builds its component
/// with dangling entities.
pub fn template(ck: &mut Checker<'_>, ctx: &Ctx<'_>, mesh: &MeshDesc) -> Option<Scatter> {
    let MeshDesc::Scatter {
        count,
        seed,
        scale,
        rotation_jitter,
        align_to_normal,
        ..
    } = mesh
    else {
        return None;
    };
    let at = format!("{}.Scatter", ctx.base);
    let smin = num(ck, &format!("{at}.scale[0]"), "scale", scale.0);
    let smax = num(ck, &format!("{at}.scale[1]"), "scale", scale.1);
    let jitter = num(
        ck,
        &format!("{at}.rotation_jitter"),
        "rotation_jitter",
        *rotation_jitter,
    );
    let s = Scatter {
        prototype: Entity::DANGLING,
        surface: Entity::DANGLING,
        count: *count,
        seed: *seed,
        scale_min: smin?,
        scale_max: smax?,
        rotation_jitter: jitter?,
        align_to_normal: *align_to_normal,
    };
    // The placement rules, on one triangle and no copies.
    let probe = TriMesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        normals: None,
        uvs: None,
        triangles: vec![[0, 1, 2]],
    };
    if let Err(e) = placements(&Scatter { count: 0, ..s }, &probe) {
        let field = match &e {
            GeometryError::OutOfRange { parameter, .. }
            | GeometryError::NotFinite { parameter } => match *parameter {
                "scale_min" => "scale[0]",
                "scale_max" => "scale[1]",
                other => other,
            },
            _ => "count",
        };
        report(ck, ctx.object, "scatter", &at, Some(field), &e);
        return None;
    }
    Some(s)
}

/// Resolves the `prototype` and `surface` of every scatter object to object indices
/// (`None` for other objects and for scatters with a bad reference, which are reported).
pub fn resolve(src: &mut Sources, m: &Merged<'_>) -> Vec<Option<(usize, usize)>> {
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, it) in m.objects.iter().enumerate() {
        index.entry(it.desc.name.as_str()).or_insert(i);
    }
    let names: Vec<&str> = m.objects.iter().map(|o| o.desc.name.as_str()).collect();
    let groups: Vec<&str> = m.groups.iter().map(|g| g.desc.name.as_str()).collect();
    m.objects
        .iter()
        .enumerate()
        .map(|(me, it)| {
            let MeshDesc::Scatter {
                prototype, surface, ..
            } = &it.desc.mesh
            else {
                return None;
            };
            let mut lookup = |field: &str, name: &str| -> Option<usize> {
                let path = it.at(&format!(".mesh.Scatter.{field}"));
                let Some(&i) = index.get(name) else {
                    let help = if groups.contains(&name) {
                        Some(format!(
                            "\"{name}\" is a group; a scatter's {field} is an object"
                        ))
                    } else {
                        suggestion(name, &names, "objects")
                    };
                    src.error(
                        it.file,
                        &path,
                        format!("unknown {field} object \"{name}\""),
                        help,
                    );
                    return None;
                };
                let target = &m.objects[i].desc.mesh;
                let problem = if i == me {
                    Some(format!("a scatter cannot use itself as its {field}"))
                } else if matches!(target, MeshDesc::Scatter { .. }) {
                    Some(format!(
                        "{field} \"{name}\" is a scatter: scatters cannot be nested"
                    ))
                } else if field == "surface"
                    && !super::is_loaded(target)
                    && !matches!(target, MeshDesc::Grid { .. } | MeshDesc::Stairs { .. })
                {
                    Some(format!(
                        "surface \"{name}\" is a {}: a scatter needs a polygon mesh \
                         (Obj, Ply, Inline, Grid or Stairs)",
                        kind_name(target)
                    ))
                } else {
                    None
                };
                match problem {
                    Some(message) => {
                        src.error(it.file, &path, message, None);
                        None
                    }
                    None => Some(i),
                }
            };
            let p = lookup("prototype", prototype);
            let s = lookup("surface", surface);
            Some((p?, s?))
        })
        .collect()
}

/// Marks the prototypes and surfaces of reachable scatters reachable.
pub fn extend_reachable(reachable: &mut [bool], scatters: &[Option<(usize, usize)>]) {
    loop {
        let mut changed = false;
        for (o, refs) in scatters.iter().enumerate() {
            if let (true, Some((p, s))) = (reachable[o], refs) {
                for t in [*p, *s] {
                    changed |= !std::mem::replace(&mut reachable[t], true);
                }
            }
        }
        if !changed {
            return;
        }
    }
}

/// Leaves of scatter objects with no material from an instance or the scatter itself take
/// the prototype's material.
pub fn copy_materials(
    leaves: &mut [Leaf],
    scatters: &[Option<(usize, usize)>],
    object_material: &[Option<usize>],
) {
    for leaf in leaves {
        if let (None, Some(Some((prototype, _)))) = (leaf.material, scatters.get(leaf.object)) {
            leaf.material = object_material.get(*prototype).copied().flatten();
        }
    }
}

/// A bake request on an instance that places a scatter is an error: the scattered copies
/// replace the placement when the scene expands.
pub fn check_bakes(src: &mut Sources, m: &Merged<'_>, leaves: &[Leaf]) {
    for (i, it) in m.instances.iter().enumerate() {
        if it.desc.bake.is_none() {
            continue;
        }
        let Some(leaf) = leaves.iter().find(|l| l.instance == i) else {
            continue;
        };
        let object = &m.objects[leaf.object].desc;
        if matches!(object.mesh, MeshDesc::Scatter { .. }) {
            src.error(
                it.file,
                &it.at(".bake"),
                format!(
                    "instance \"{}\" places the scatter \"{}\", which has no surface of its own to bake",
                    it.desc.name, object.name
                ),
                Some("bake the scatter's surface object instead".into()),
            );
        }
    }
}
