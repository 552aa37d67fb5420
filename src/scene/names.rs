//! Name tables and name resolution.
//!
//! Names live in separate namespaces per kind: materials, lights, cameras, instances, and
//! one shared namespace for objects and groups (an instance's `of` may name either). A name
//! defined twice in its namespace is an error that points at the first definition. Every
//! reference is resolved to an index into the merged lists, or reported with a
//! "did you mean".

use std::collections::HashMap;

use super::diagnostics::{suggestion, Sources};
use super::suggest::closest;
use super::syntax::{Helps, Syntax};
use super::validate::{Item, Merged};

/// What an instance's `of` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// An object (index into `Merged::objects`).
    Object(usize),
    /// A group (index into `Merged::groups`).
    Group(usize),
}

/// Every reference of the scene resolved to indices (`None` where it did not resolve).
#[derive(Debug, Default)]
pub struct Resolved {
    /// Material of each object.
    pub object_material: Vec<Option<usize>>,
    /// Material override of each instance.
    pub instance_material: Vec<Option<usize>>,
    /// Per object, its inline mesh's polygon materials (`Some(None)` for `""`), when it
    /// names them; for an OBJ with per-material faces, the material of each of its
    /// `usemtl` groups.
    pub polygon_materials: Vec<Option<Vec<Option<usize>>>>,
    /// What each instance places.
    pub instance_of: Vec<Option<Target>>,
    /// Instances of each group (unresolved members left out).
    pub group_members: Vec<Vec<usize>>,
    /// The root group.
    pub root: Option<usize>,
    /// The render camera.
    pub camera: Option<usize>,
}

/// A namespace: name → index of its first definition.
struct Table<'a> {
    map: HashMap<&'a str, usize>,
    names: Vec<&'a str>,
    /// Whether some entry has an empty name (reported where it is).
    unnamed: bool,
}

impl<'a> Table<'a> {
    fn get(&self, name: &str) -> Option<usize> {
        self.map.get(name).copied()
    }

    /// Whether a reference to the unknown `name` is worth reporting: not when an entry of
    /// this kind has an empty name (it may be the one meant: its own error says so), unless
    /// a defined name is close enough to suggest.
    fn reports_unknown(&self, name: &str) -> bool {
        !self.unnamed || closest(name, self.names.iter().copied()).is_some()
    }
}

/// Builds a table, reporting empty and duplicate names. `entries` are
/// `(file, element path, name)` in load order.
fn table<'a>(src: &mut Sources, kind: &str, entries: &[(usize, &str, &'a str)]) -> Table<'a> {
    let mut map: HashMap<&'a str, usize> = HashMap::new();
    let mut names = Vec::new();
    let mut unnamed = false;
    for (i, &(file, path, name)) in entries.iter().enumerate() {
        let name_path = format!("{path}.name");
        if name.is_empty() {
            src.error(file, &name_path, format!("{kind} name is empty"), None);
            unnamed = true;
            continue;
        }
        match map.get(name) {
            Some(&first) => {
                let (ffile, fpath, _) = entries[first];
                let help = format!(
                    "first defined at {}",
                    src.where_is(ffile, &format!("{fpath}.name"))
                );
                src.error(
                    file,
                    &name_path,
                    format!("duplicate {kind} name \"{name}\""),
                    Some(help),
                );
            }
            None => {
                map.insert(name, i);
                names.push(name);
            }
        }
    }
    Table {
        map,
        names,
        unnamed,
    }
}

fn entries<'a, T>(
    list: &'a [Item<'a, T>],
    name: impl Fn(&'a T) -> &'a str,
) -> Vec<(usize, &'a str, &'a str)> {
    list.iter()
        .map(|it| (it.file, it.path.as_str(), name(it.desc)))
        .collect()
}

/// Checks names and resolves every reference.
pub fn resolve(src: &mut Sources, m: &Merged<'_>) -> Resolved {
    let materials = table(src, "material", &entries(&m.materials, |d| &d.name));
    table(src, "light", &entries(&m.lights, |d| &d.name));
    let cameras = table(src, "camera", &entries(&m.cameras, |d| &d.name));
    let instances = table(src, "instance", &entries(&m.instances, |d| &d.name));
    let mut shapes_entries = entries(&m.objects, |d| &d.name);
    shapes_entries.extend(entries(&m.groups, |d| &d.name));
    let shapes = table(src, "object or group", &shapes_entries);
    let n_objects = m.objects.len();
    let target = |i: usize| {
        if i < n_objects {
            Target::Object(i)
        } else {
            Target::Group(i - n_objects)
        }
    };

    let material_ref = |src: &mut Sources, file: usize, path: String, name: &Option<String>| {
        let name = name.as_deref()?;
        let found = materials.get(name);
        if found.is_none() && materials.reports_unknown(name) {
            src.error(
                file,
                &path,
                format!("unknown material \"{name}\""),
                suggestion(name, &materials.names, "materials"),
            );
        }
        found
    };
    let object_material = m
        .objects
        .iter()
        .map(|it| material_ref(src, it.file, it.at(".material"), &it.desc.material))
        .collect();
    let instance_material = m
        .instances
        .iter()
        .map(|it| material_ref(src, it.file, it.at(".material"), &it.desc.material))
        .collect();

    let polygon_materials = m
        .objects
        .iter()
        .map(|it| polygon_materials(src, it, &materials))
        .collect();

    let instance_of = m
        .instances
        .iter()
        .map(|it| {
            let name = it.desc.of.as_str();
            let found = shapes.get(name).map(target);
            if found.is_none() && shapes.reports_unknown(name) {
                src.error(
                    it.file,
                    &it.at(".of"),
                    format!("unknown object or group \"{name}\""),
                    suggestion(name, &shapes.names, "objects or groups"),
                );
            }
            found
        })
        .collect();

    let group_members = m
        .groups
        .iter()
        .map(|it| {
            let mut members: Vec<usize> = Vec::new();
            for (k, name) in it.desc.members.iter().enumerate() {
                let path = it.at(&format!(".members[{k}]"));
                match instances.get(name) {
                    Some(i) if members.contains(&i) => src.error(
                        it.file,
                        &path,
                        format!(
                            "instance \"{name}\" is listed twice in group \"{}\"",
                            it.desc.name
                        ),
                        Some(listed_twice_help(
                            src.syntax(it.file),
                            name,
                            &m.instances[i].desc.of,
                        )),
                    ),
                    Some(i) => members.push(i),
                    None if !instances.reports_unknown(name) => {}
                    None => {
                        let help = match shapes.get(name).map(target) {
                            Some(Target::Object(_)) => Some(format!(
                                "\"{name}\" is an object; groups list instances: add \
                                 `(name: \"{name}_1\", of: \"{name}\")` to `instances` and \
                                 list that"
                            )),
                            Some(Target::Group(_)) => Some(format!(
                                "\"{name}\" is a group; groups list instances: add \
                                 `(name: \"{name}_1\", of: \"{name}\")` to `instances` and \
                                 list that"
                            )),
                            None => suggestion(name, &instances.names, "instances"),
                        };
                        src.error(it.file, &path, format!("unknown instance \"{name}\""), help);
                    }
                }
            }
            members
        })
        .collect();

    let (mut root, mut camera) = (None, None);
    if let Some(r) = &m.render {
        let name = r.desc.root.as_str();
        match shapes.get(name).map(target) {
            Some(Target::Group(g)) => root = Some(g),
            Some(Target::Object(_)) => src.error(
                r.file,
                "render.root",
                format!("render root \"{name}\" is an object, not a group"),
                Some(format!(
                    "place it in a group: `instances: [(name: \"{name}_1\", of: \"{name}\")]`, \
                     `groups: [(name: \"world\", members: [\"{name}_1\"])]`"
                )),
            ),
            None if !shapes.reports_unknown(name) => {}
            None => {
                let groups: Vec<&str> = m.groups.iter().map(|g| g.desc.name.as_str()).collect();
                src.error(
                    r.file,
                    "render.root",
                    format!("unknown group \"{name}\""),
                    suggestion(name, &groups, "groups"),
                );
            }
        }
        let name = r.desc.camera.as_str();
        camera = cameras.get(name);
        if camera.is_none() && cameras.reports_unknown(name) {
            src.error(
                r.file,
                "render.camera",
                format!("unknown camera \"{name}\""),
                suggestion(name, &cameras.names, "cameras"),
            );
        }
    }

    Resolved {
        object_material,
        instance_material,
        polygon_materials,
        instance_of,
        group_members,
        root,
        camera,
    }
}

/// What to write instead of a group member listed twice: a group places each instance once,
/// so a second copy of `of` is a second instance of it.
fn listed_twice_help(syntax: Syntax, name: &str, of: &str) -> String {
    let neutral = format!(
        "a group places each of its instances once: remove this \"{name}\", or give \"{of}\" a second instance (with a transform of its own) and list that"
    );
    syntax.help_each(Helps {
        ron: &format!(
            "a group places each of its instances once: remove this \"{name}\", or add a second instance such as `(name: \"{name}_2\", of: \"{of}\", transform: [Translate((2, 0, 0))])` and list that"
        ),
        mi: &format!(
            "an instgroup places each of its instances once: remove this \"{name}\", or add a second `instance` of \"{of}\" with a `transform` of its own and list that"
        ),
        rib: &neutral,
        gltf: &neutral,
    })
}

/// Checks and resolves the `materials` of an inline mesh: one per polygon, `""` for the
/// instance's, each other name a material (an unknown name is reported once, at its first
/// polygon); not with true displacement, which re-tessellates the polygons.
fn polygon_materials(
    src: &mut Sources,
    it: &Item<'_, crate::scene::desc::ObjectDesc>,
    materials: &Table<'_>,
) -> Option<Vec<Option<usize>>> {
    if let crate::scene::desc::MeshDesc::Obj {
        materials: Some(slots),
        ..
    } = &it.desc.mesh
    {
        return Some(obj_face_materials(slots, materials));
    }
    let crate::scene::desc::MeshDesc::Inline {
        polygons,
        materials: Some(names),
        ..
    } = &it.desc.mesh
    else {
        return None;
    };
    let path = it.at(".mesh.Inline.materials");
    if names.len() != polygons.len() {
        src.error(
            it.file,
            &path,
            format!(
                "materials has {} entries but polygons has {}: give one material per polygon",
                names.len(),
                polygons.len()
            ),
            Some("write \"\" for a polygon that takes the object's material".into()),
        );
        return None;
    }
    let displaced = it
        .desc
        .displacement
        .as_ref()
        .is_some_and(|d| d.mode == crate::scene::desc_geometry::DisplacementModeDesc::True);
    if displaced {
        src.error(
            it.file,
            &path,
            "per-polygon materials cannot be combined with true displacement",
            Some("give the displaced polygons an object of their own, or use mode: Bump".into()),
        );
        return None;
    }
    let mut reported: Vec<&str> = Vec::new();
    let mut ok = true;
    let resolved = names
        .iter()
        .enumerate()
        .map(|(k, name)| {
            if name.is_empty() {
                return None;
            }
            let found = materials.get(name);
            if found.is_none()
                && !reported.contains(&name.as_str())
                && materials.reports_unknown(name)
            {
                reported.push(name);
                src.error(
                    it.file,
                    &format!("{path}[{k}]"),
                    format!("unknown material \"{name}\""),
                    suggestion(name, &materials.names, "materials"),
                );
            }
            ok &= found.is_some();
            found
        })
        .collect();
    ok.then_some(resolved)
}

/// The materials of an OBJ's `usemtl` groups, as [`crate::scene::obj_materials`] listed
/// them (it added every material it names), plus a last `None` for faces under a material
/// the list lacks.
fn obj_face_materials(slots: &[(String, String)], materials: &Table<'_>) -> Vec<Option<usize>> {
    slots
        .iter()
        .map(|(_, name)| materials.get(name))
        .chain([None])
        .collect()
}
