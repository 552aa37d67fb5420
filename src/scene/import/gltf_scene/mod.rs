//! The glTF 2.0 scene reader (`.gltf`, `.glb`): a whole file → the format-neutral
//! [`SceneDesc`], so `stagelight render|check|bake|plan|convert model.glb` work like on RON.
//!
//! Mapping (documented in `docs/gltf.md`):
//! - every primitive of every mesh is an object whose mesh is `Gltf(file: <this file>, mesh:
//!   …, primitive: …)`, so geometry is read once by the shared mesh loader and shared by all
//!   nodes that use the mesh;
//! - the node hierarchy of the default scene (or the first) becomes instances and groups: a
//!   node with one primitive and no children is an instance of that object carrying the
//!   node's local matrix; any other node is a group (`<node>_group`) placed by an instance
//!   (`<node>_node`) with the node's matrix, holding one instance per primitive (`<node>` or
//!   `<node>_<k>`) and the instances of its children; the root is the group `scene`;
//! - materials ([`materials`]), cameras (their values checked by [`camera_values`]) and
//!   `KHR_lights_punctual` lights ([`view`]);
//! - node values the specification forbids (a rotation that is not a unit quaternion, a
//!   transform that is not finite or is both a matrix and TRS, a second parent) are errors
//!   ([`node_checks`]); a node whose transform flattens space (a zero scale: a hidden
//!   instance) is skipped with everything under it, with a warning;
//! - light values outside `KHR_lights_punctual`'s ranges are errors ([`light_values`]);
//!   skins, morph targets, animations and unread material extensions are warnings;
//! - every instance of a primitive with `TEXCOORD_1` carries the default bake request
//!   ([`bakes`]), so `stagelight bake model.glb` bakes lightmaps and ambient occlusion.
//!
//! Names come from the file (node, mesh, material, light and camera names; `node3` and the
//! like for unnamed or empty-named ones), made unique per namespace with `_2`, `_3`, … and
//! stripped of characters that could not be part of a file name; a made-up name never
//! takes one the file gives ([`names`]). Messages name the glTF element by its JSON path (`nodes[3]`,
//! `extensions.KHR_lights_punctual.lights[0]`); in a `.gltf` they are placed at that
//! element's line and column ([`json_positions`]), in a `.glb` (no lines) at the start of the
//! file. An image file that cannot be read is reported at its `uri`, and so are the image
//! errors the shared loader finds in the bindings that use it.

pub mod bakes;
pub mod camera_values;
pub mod json_positions;
pub mod light_values;
pub mod materials;
pub mod names;
pub mod node_checks;
pub mod texture_transform;
pub mod view;

use std::collections::HashMap;
use std::path::Path;

use glam::{DMat4, DVec3};

use super::{PathTable, ReadFailure, ReadScene, SourcePos};
use crate::scene::desc::{
    GroupDesc, InstanceDesc, MeshDesc, ObjectDesc, RenderDesc, SceneDesc, TransformDesc, M4,
};
use crate::scene::mesh_files::gltf_file::{self, GltfFile};
use crate::scene::mesh_files::MeshFileError;
use crate::scene::message::Diagnostic;
use json_positions::Step;
pub use names::given;
use names::{node_labels, SceneNames};
use node_checks::local_matrix;

/// Deepest node hierarchy read (deeper is refused, as a cycle would be).
const MAX_NODE_DEPTH: usize = 64;

/// A diagnostic at the start of `path` (glTF files are located by element, not by line).
pub fn at_file(path: &Path, message: impl Into<String>) -> Diagnostic {
    Diagnostic::at(SourcePos::start(path), message, None)
}

/// A diagnostic at the JSON element `path` (`nodes[2].skin`) in a `.gltf`, or at the
/// nearest enclosing element that is there; at the start of a `.glb`.
pub fn at_element(w: &Walk<'_>, path: &[Step<'_>], message: impl Into<String>) -> Diagnostic {
    let mut d = at_file(w.path, message);
    if let Some(json) = w.json {
        if let Some((line, column)) = (1..=path.len())
            .rev()
            .find_map(|n| json_positions::value_position(json, &path[..n]))
        {
            (d.line, d.column) = (line, column);
        }
    }
    d
}

/// `[1, 0.5]`: numbers as a JSON file writes them.
fn numbers(values: &[f32]) -> String {
    let list: Vec<String> = values.iter().map(f32::to_string).collect();
    format!("[{}]", list.join(", "))
}

/// Pushes warning `d` unless the same message was given already (an element met twice).
pub fn warn_once(w: &mut Walk<'_>, d: Diagnostic) {
    if !w.warnings.iter().any(|x| x.message == d.message) {
        w.warnings.push(d);
    }
}

/// The diagnostic for a container or mesh error of the file at `path`: at the line and
/// column of the element it names in a `.gltf` (`json`: its text), else at the start.
pub fn file_error(path: &Path, e: &MeshFileError, json: Option<&[u8]>) -> Diagnostic {
    use crate::scene::mesh_files::Location;
    match e {
        MeshFileError::Parse {
            at: Location::Text { line, column },
            message,
        } => Diagnostic {
            file: path.to_path_buf(),
            line: *line,
            column: *column,
            message: format!("invalid glTF file: {message}"),
            help: None,
        },
        other => {
            let mut d = at_file(path, format!("invalid glTF file: {other}"));
            if let (MeshFileError::Element { path, .. }, Some(json)) = (other, json) {
                if let Some((line, column)) = json_positions::element_position(json, path) {
                    (d.line, d.column) = (line, column);
                }
            }
            d
        }
    }
}

/// The name of the glTF format in `import::FORMATS`.
pub const FORMAT_NAME: &str = "glTF";

/// Makes a glTF scene a part of the scene that includes it (`include: ["level.glb"]` in
/// RON): its materials, objects, instances, groups (the root group, named after the glTF
/// scene, for the includer to place), cameras, lights and bakes come in; what the file
/// chose for a scene of its own — the render entry and the white default environment of a
/// file without lights — does not.
pub fn as_include(desc: &mut SceneDesc) {
    desc.render = None;
    desc.environment = None;
}

/// Reads a glTF scene (the reader in `import::FORMATS`).
pub fn read(path: &Path, bytes: &[u8]) -> Result<ReadScene, ReadFailure> {
    let dir = path.parent().unwrap_or(Path::new(""));
    let json = (!bytes.starts_with(b"glTF")).then_some(bytes);
    let file = gltf_file::open(bytes, Some(dir)).map_err(|e| vec![file_error(path, &e, json)])?;
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let (desc, warnings, _) = build(path, &file_name, &file, json)?;
    let mut table = PathTable::default();
    table.insert("", SourcePos::start(path));
    if let Some(json) = json {
        for (at, pos) in materials::image_positions(&desc, &file, path, json) {
            table.insert(at, pos);
        }
    }
    Ok(ReadScene {
        desc,
        map: table.into_map(path),
        warnings,
        read_files: Vec::new(),
    })
}

/// Row-major matrix of the description from a glam matrix.
pub fn m4(m: &DMat4) -> M4 {
    let c = m.to_cols_array_2d();
    [0, 1, 2, 3].map(|r| [0, 1, 2, 3].map(|k| c[k][r]))
}

/// What the node walk collects besides the hierarchy.
pub struct Walk<'a> {
    /// The file.
    pub file: &'a GltfFile,
    /// Element names, one table per namespace.
    pub names: &'a mut SceneNames,
    /// The scene being built.
    pub desc: &'a mut SceneDesc,
    /// Located warnings.
    pub warnings: Vec<Diagnostic>,
    /// The file's path as the user named it.
    pub path: &'a Path,
    /// Object names of each (mesh, primitive).
    objects: HashMap<(usize, usize), String>,
    /// Material name of each glTF material (`None`: the default material).
    materials: HashMap<Option<usize>, String>,
    /// Group of each node already built (`None`: nothing to place under it).
    groups: HashMap<usize, Option<String>>,
    /// World-space bounds of the placed meshes (min, max).
    pub bounds: Option<(DVec3, DVec3)>,
    /// Every perspective camera met, in walk order: (node, world matrix).
    pub cameras: Vec<(usize, DMat4)>,
    /// Every instance of a primitive: (instance name, node, primitive index).
    pub leaves: Vec<(String, usize, usize)>,
    errors: Vec<Diagnostic>,
    /// The JSON text of a `.gltf` file (for positions in messages); `None` for a `.glb`.
    json: Option<&'a [u8]>,
    /// Each node's label (`node_labels`).
    node_labels: Vec<String>,
}

/// What places a node under its parent: an instance of an object or a group, with the
/// node's matrix.
fn place(w: &mut Walk<'_>, name: String, of: String, local: &DMat4) -> String {
    let transform = if *local == DMat4::IDENTITY {
        Vec::new()
    } else {
        vec![TransformDesc::Matrix(m4(local))]
    };
    w.desc
        .instances
        .push(InstanceDesc::plain(&name, of, transform));
    name
}

impl Walk<'_> {
    /// The label of `node` (its name, or its fallback name).
    fn node_label(&self, node: &gltf::Node<'_>) -> String {
        self.node_labels[node.index()].clone()
    }

    /// The instance name of node `index` labelled `label` (the node's own name, which only
    /// a node of that name takes, or its made-up `node3`).
    fn node_instance(&mut self, index: usize, label: &str) -> String {
        let named = self
            .file
            .doc
            .nodes()
            .nth(index)
            .is_some_and(|n| given(n.name()).is_some());
        if named {
            self.names.instances.take_given(label)
        } else {
            self.names.instances.take(label)
        }
    }

    /// Warnings for what of `node` and its mesh is not read: its skin, its morph weights,
    /// and the mesh's morph targets (once per mesh).
    fn warn_unread_animation(&mut self, node: &gltf::Node<'_>) {
        let i = node.index();
        if node.skin().is_some() {
            let path = [Step::Key("nodes"), Step::Index(i), Step::Key("skin")];
            let d = at_element(
                self,
                &path,
                format!("nodes[{i}]: ignored its skin (the mesh is read in its bind pose)"),
            );
            warn_once(self, d);
        }
        if let Some(weights) = node.weights() {
            let path = [Step::Key("nodes"), Step::Index(i), Step::Key("weights")];
            let d = at_element(
                self,
                &path,
                format!(
                    "nodes[{i}]: ignored its morph weights {} (the mesh is read in its base shape, without its morph targets)",
                    numbers(weights)
                ),
            );
            warn_once(self, d);
        }
        let Some(mesh) = node.mesh() else { return };
        let Some(p) = mesh.primitives().position(|p| p.morph_targets().len() > 0) else {
            return;
        };
        let m = mesh.index();
        let label = match given(mesh.name()) {
            Some(n) => format!("meshes[{m}] (\"{n}\")"),
            None => format!("meshes[{m}]"),
        };
        let weights = match mesh.weights() {
            Some(w) if w.iter().any(|&x| x != 0.0) => {
                format!("; its default weights {} are not applied", numbers(w))
            }
            _ => String::new(),
        };
        let path = [
            Step::Key("meshes"),
            Step::Index(m),
            Step::Key("primitives"),
            Step::Index(p),
            Step::Key("targets"),
        ];
        let d = at_element(
            self,
            &path,
            format!(
                "{label}: ignored its morph targets (the mesh is read in its base shape, without them){weights}"
            ),
        );
        warn_once(self, d);
    }

    /// The file refused: its errors with the warnings found so far.
    fn refusal(&mut self) -> ReadFailure {
        ReadFailure {
            errors: std::mem::take(&mut self.errors),
            warnings: std::mem::take(&mut self.warnings),
        }
    }

    fn object(&mut self, mesh: &gltf::Mesh<'_>, p: usize, material: String) -> String {
        if let Some(name) = self.objects.get(&(mesh.index(), p)) {
            return name.clone();
        }
        let label = given(mesh.name())
            .map(str::to_string)
            .unwrap_or_else(|| format!("mesh{}", mesh.index()));
        let count = mesh.primitives().count();
        let name = self.names.objects.take(&if count > 1 {
            format!("{label}_mesh_{p}")
        } else {
            format!("{label}_mesh")
        });
        let unique = self
            .file
            .doc
            .meshes()
            .filter(|m| m.name() == mesh.name())
            .count()
            == 1;
        let selector = match mesh.name() {
            Some(n) if unique => n.to_string(),
            _ => format!("#{}", mesh.index()),
        };
        self.desc.objects.push(ObjectDesc {
            name: name.clone(),
            mesh: MeshDesc::Gltf {
                file: file_name_of(self.path),
                mesh: Some(selector),
                primitive: (count > 1).then_some(p as u32),
            },
            material: Some(material),
            approximation: None,
            displacement: None,
            derivatives: false,
            reverse_orientation: false,
            caustic: None,
            globillum: None,
            visible: None,
            shadow: None,
            trace: None,
            label: None,
        });
        self.objects.insert((mesh.index(), p), name.clone());
        name
    }

    fn grow_bounds(&mut self, prim: &gltf::Primitive<'_>, world: &DMat4) {
        let Some(pos) = prim.get(&gltf::Semantic::Positions) else {
            return;
        };
        let read = |v: Option<gltf::json::Value>| -> Option<[f64; 3]> {
            let list = v?.as_array()?.clone();
            let x: Vec<f64> = list.iter().filter_map(|x| x.as_f64()).collect();
            (x.len() == 3).then(|| [x[0], x[1], x[2]])
        };
        let (Some(lo), Some(hi)) = (read(pos.min()), read(pos.max())) else {
            return;
        };
        for k in 0..8 {
            let corner = DVec3::new(
                if k & 1 == 0 { lo[0] } else { hi[0] },
                if k & 2 == 0 { lo[1] } else { hi[1] },
                if k & 4 == 0 { lo[2] } else { hi[2] },
            );
            let p = world.transform_point3(corner);
            if !p.is_finite() {
                continue;
            }
            self.bounds = Some(match self.bounds {
                Some((a, b)) => (a.min(p), b.max(p)),
                None => (p, p),
            });
        }
    }

    /// Walks `node` placed at `world`; returns what its parent places (an object for a
    /// lone primitive, or the node's group), `None` when nothing lies under it.
    fn walk(
        &mut self,
        node: gltf::Node<'_>,
        world: DMat4,
        stack: &mut Vec<usize>,
    ) -> Option<String> {
        if stack.contains(&node.index()) || stack.len() >= MAX_NODE_DEPTH {
            let why = if stack.contains(&node.index()) {
                "the node hierarchy has a cycle (a node is its own ancestor)".to_string()
            } else {
                format!("the node hierarchy is deeper than {MAX_NODE_DEPTH} levels")
            };
            let path = [Step::Key("nodes"), Step::Index(node.index())];
            let d = at_element(self, &path, format!("nodes[{}]: {why}", node.index()));
            self.errors.push(d);
            return None;
        }
        if let Some((key, message)) = node_checks::hidden(&node) {
            let path = [
                Step::Key("nodes"),
                Step::Index(node.index()),
                Step::Key(key),
            ];
            let d = at_element(self, &path, message);
            warn_once(self, d);
            return None;
        }
        stack.push(node.index());
        if let Some(camera) = node.camera() {
            if matches!(
                camera.projection(),
                gltf::camera::Projection::Perspective(_)
            ) {
                self.cameras.push((node.index(), world));
            } else {
                let path = [Step::Key("cameras"), Step::Index(camera.index())];
                let d = at_element(
                    self,
                    &path,
                    format!(
                        "cameras[{}]: ignored an orthographic camera (only perspective cameras are read)",
                        camera.index()
                    ),
                );
                warn_once(self, d);
            }
        }
        if let Some(light) = node.light() {
            view::light(self, &light, &world);
        }
        self.warn_unread_animation(&node);
        let mut result = None;
        let memo = self.groups.get(&node.index()).cloned();
        let label = self.node_label(&node);
        let mut members = Vec::new();
        if let Some(mesh) = node.mesh() {
            let prims: Vec<gltf::Primitive<'_>> = mesh.primitives().collect();
            for prim in &prims {
                self.grow_bounds(prim, &world);
            }
            if memo.is_none() {
                let lone = prims.len() == 1 && node.children().count() == 0;
                for (p, prim) in prims.iter().enumerate() {
                    let material = materials::material_name(self, prim.material().index());
                    let object = self.object(&mesh, p, material);
                    if lone {
                        result = Some(object);
                    } else {
                        let inst = if prims.len() > 1 {
                            self.names.instances.take(&format!("{label}_{p}"))
                        } else {
                            self.node_instance(node.index(), &label)
                        };
                        self.leaves.push((inst.clone(), node.index(), p));
                        members.push(place(self, inst, object, &DMat4::IDENTITY));
                    }
                }
            }
        }
        for child in node.children() {
            let local = local_matrix(&child);
            let child_label = self.node_label(&child);
            let child_index = child.index();
            let placed = self.walk(child, world * local, stack);
            if memo.is_some() {
                continue;
            }
            if let Some(of) = placed {
                let lone = self.objects.values().any(|o| *o == of);
                let name = if lone {
                    self.node_instance(child_index, &child_label)
                } else {
                    self.names.instances.take(&format!("{child_label}_node"))
                };
                if lone {
                    self.leaves.push((name.clone(), child_index, 0));
                }
                members.push(place(self, name, of, &local));
            }
        }
        stack.pop();
        if let Some(memo) = memo {
            return memo;
        }
        if result.is_none() && !members.is_empty() {
            let group = self.names.objects.take(&format!("{label}_group"));
            self.desc.groups.push(GroupDesc {
                name: group.clone(),
                members,
            });
            result = Some(group);
        }
        self.groups.insert(node.index(), result.clone());
        result
    }
}

/// The file name a scene's `Gltf(file: …)` meshes use (the meshes resolve beside the file).
fn file_name_of(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// What [`build`] returns: the description, warnings and the primitive instances.
type Built = (SceneDesc, Vec<Diagnostic>, Vec<(String, usize, usize)>);

fn build(
    path: &Path,
    _file_name: &str,
    file: &GltfFile,
    json: Option<&[u8]>,
) -> Result<Built, ReadFailure> {
    let doc = &file.doc;
    let Some(scene) = doc.default_scene().or_else(|| doc.scenes().next()) else {
        return Err(vec![at_file(
            path,
            "the glTF file holds no scene: nothing to render",
        )]
        .into());
    };
    let mut names = SceneNames::of(doc, &scene);
    let mut desc = SceneDesc::default();
    let mut w = Walk {
        file,
        names: &mut names,
        desc: &mut desc,
        warnings: Vec::new(),
        path,
        objects: HashMap::new(),
        materials: HashMap::new(),
        groups: HashMap::new(),
        bounds: None,
        cameras: Vec::new(),
        leaves: Vec::new(),
        errors: Vec::new(),
        json,
        node_labels: node_labels(doc),
    };
    materials::warn_unmapped(&mut w);
    node_checks::check(&mut w);
    node_checks::check_roots(&mut w, &scene);
    if !w.errors.is_empty() {
        return Err(w.refusal());
    }
    let mut members = Vec::new();
    for node in scene.nodes() {
        let local = local_matrix(&node);
        let label = w.node_label(&node);
        let index = node.index();
        if let Some(of) = w.walk(node, local, &mut Vec::new()) {
            let lone = w.objects.values().any(|o| *o == of);
            let name = if lone {
                w.node_instance(index, &label)
            } else {
                w.names.instances.take(&format!("{label}_node"))
            };
            if lone {
                w.leaves.push((name.clone(), index, 0));
            }
            members.push(place(&mut w, name, of, &local));
        }
    }
    if !w.errors.is_empty() {
        return Err(w.refusal());
    }
    if members.is_empty() {
        let at = [Step::Key("scenes"), Step::Index(scene.index())];
        let error = at_element(
            &w,
            &at,
            format!(
                "scenes[{}]: the scene places no mesh: nothing to render",
                scene.index()
            ),
        );
        return Err(ReadFailure {
            errors: vec![error],
            warnings: std::mem::take(&mut w.warnings),
        });
    }
    let root = match given(scene.name()) {
        Some(name) => w.names.objects.take_given(name),
        None => w.names.objects.take("scene"),
    };
    w.desc.groups.push(GroupDesc {
        name: root.clone(),
        members,
    });
    let camera = view::camera(&mut w);
    if !w.errors.is_empty() {
        return Err(w.refusal());
    }
    view::default_light(&mut w);
    bakes::default_bakes(&mut w);
    let warnings = std::mem::take(&mut w.warnings);
    let leaves = std::mem::take(&mut w.leaves);
    desc.render = Some(RenderDesc { root, camera });
    Ok((desc, warnings, leaves))
}

/// Every instance of a primitive in the glTF scene at `path`: (instance name, node index,
/// primitive index), as [`read`] names them (for writing baked textures back into the file).
pub fn primitive_instances(
    path: &Path,
    bytes: &[u8],
) -> Result<Vec<(String, usize, usize)>, Vec<Diagnostic>> {
    let dir = path.parent().unwrap_or(Path::new(""));
    let file = gltf_file::open(bytes, Some(dir)).map_err(|e| vec![file_error(path, &e, None)])?;
    build(path, "", &file, None)
        .map(|(_, _, leaves)| leaves)
        .map_err(|failure| failure.errors)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matrices_are_written_row_major() {
        let m = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0));
        let r = m4(&m);
        assert_eq!(r[0], [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(r[2], [0.0, 0.0, 1.0, 3.0]);
        assert_eq!(r[3], [0.0, 0.0, 0.0, 1.0]);
    }
}
