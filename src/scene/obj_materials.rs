//! OBJ materials in scenes: before validation, every object whose mesh is an `Obj(file: …)`
//! with `mtllib`/`usemtl` and that names no `material` of its own gets the OBJ's materials,
//! read from its MTL files ([`super::mesh_files::mtl`]) and added to the scene as ordinary
//! materials named `<object>.<mtl name>`.
//!
//! - Faces under one material: the object's `material` becomes it.
//! - Faces under several: the object stays one object; its mesh gets the material of each
//!   `usemtl` group (`Obj { materials: Some(…) }`), which the loader turns into per-triangle
//!   material slots (`FaceMaterials`), its triangles grouped by material in order of first
//!   use (faces written before any `usemtl` first, with the instance's material). So one
//!   instance places the whole file and can be baked; an instance's `material` replaces the
//!   MTL materials on every face. A truly displaced object (re-tessellated, so it cannot
//!   keep per-triangle slots) is instead split into a group of the same name holding one
//!   object and one instance per material, `<object>.<mtl name>`, each `Obj(file: …,
//!   usemtl: "<mtl name>")` (faces before any `usemtl`: `<object>.default`).
//! - An object that writes `material: "…"` keeps it on every face; its MTL files are not read.
//! - `usemtl` in a file without `mtllib` is a warning at the first `usemtl`.
//! - A `mtllib` file that cannot be read is a warning at the `mtllib` line naming the file; a
//!   `usemtl` name no library defines (when every library was read) is a warning at its
//!   first `usemtl`; their faces get the default material (when no face gets an MTL
//!   material the object stays whole). A malformed MTL file, or a map naming a file that
//!   does not exist, is an error at its line and column in the MTL file.
//!
//! MTL → material: `Kd` (default 0.8 grey) → `Lambert(albedo)`, or `Phong(diffuse: Kd,
//! specular: Ks, spec_exp: Ns (default 10))` when `Ks` is above zero; `illum` 4, 6, 7 or 9
//! (refraction) → `Dielectric(ior: Ni, default 1.5)`; `d < 1` (or `Tr > 0`) wraps the shader
//! in `Opacity`; `Ke` → `emission`; `map_Kd` → the diffuse colour bound to the image (sRGB)
//! times `Kd`; `map_Bump`/`bump` → `bump` with the image's red channel as height times `-bm`
//! (object units). Map files are relative to the MTL file, which is relative to the OBJ
//! file.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::desc::{
    GroupDesc, InstanceDesc, MaterialDesc, MeshDesc, ObjectDesc, SceneDesc, ShaderDesc,
};
use super::desc_geometry::DisplacementModeDesc;
use super::diagnostics::{Diagnostic, Sources};
use super::mesh_files::mtl::{self, MapRef, MtlMaterial};
use super::mesh_files::{obj, FaceMaterials, Location, MeshFileError};
use super::message::io_reason;
use super::nodes_desc::{BumpDesc, EncodingDesc, InputDesc, NodeDesc, WrapDesc};
use crate::limits::{read_file, MAX_MESH_FILE_BYTES, MAX_SCENE_FILE_BYTES};

/// `Kd` when a material does not write it (the MTL specification's default).
const DEFAULT_DIFFUSE: [f64; 3] = [0.8, 0.8, 0.8];
/// `Ns` when a material with a specular colour does not write it.
const DEFAULT_EXPONENT: f64 = 10.0;

/// Gives the objects of every parsed scene their OBJ materials (see the module docs).
/// Errors and warnings are recorded in `src`; `read` collects the MTL files read (inputs of
/// the scene).
pub fn expand(src: &mut Sources, scenes: &mut [Option<SceneDesc>], read: &mut Vec<PathBuf>) {
    for (file, scene) in scenes.iter_mut().enumerate() {
        let Some(desc) = scene else { continue };
        for i in 0..desc.objects.len() {
            expand_object(src, file, desc, i, read);
        }
    }
}

/// One material an OBJ's faces use: its scene name and description (`None`: default).
type Piece = (String, Option<MaterialDesc>);

fn expand_object(
    src: &mut Sources,
    file: usize,
    desc: &mut SceneDesc,
    i: usize,
    read: &mut Vec<PathBuf>,
) {
    let object = &desc.objects[i];
    let MeshDesc::Obj {
        file: obj_file,
        usemtl: None,
        materials: None,
    } = &object.mesh
    else {
        return;
    };
    if object.material.is_some() {
        return;
    }
    let obj_path = src.files[file].dir().join(obj_file);
    // Errors in the OBJ itself are the mesh loader's to report.
    let Ok(bytes) = read_file(&obj_path, MAX_MESH_FILE_BYTES, "mesh file") else {
        return;
    };
    let Ok(data) = obj::parse(&bytes) else {
        return;
    };
    let Some(faces) = data.materials else { return };
    if faces.libraries.is_empty() {
        // `usemtl` names a material of a library the file never loads: said once, at the
        // first `usemtl`, since its faces quietly get the default material.
        if let Some(first) = faces.used.first() {
            src.push_warning(
                file,
                Diagnostic {
                    file: obj_path.clone(),
                    line: first.line,
                    column: first.column,
                    message: format!(
                        "usemtl \"{}\" but the file loads no material library (mtllib); its faces use the default material",
                        first.name
                    ),
                    help: Some(format!(
                        "add `mtllib FILE.mtl` to the OBJ, or give object \"{}\" a `material`",
                        object.name
                    )),
                },
            );
        }
        return;
    }
    let at = format!("objects[{i}].mesh.Obj.file");
    let name = object.name.clone();
    let Some((library, all_read)) = read_libraries(src, file, &at, &obj_path, &faces, &name, read)
    else {
        return;
    };
    let obj_dir = Path::new(obj_file).parent().unwrap_or(Path::new(""));
    let mut pieces: Vec<(String, Piece)> = Vec::new();
    if faces.of_triangle.contains(&u32::MAX) {
        pieces.push((String::new(), (format!("{name}.default"), None)));
    }
    for (k, used) in faces.used.iter().enumerate() {
        if !faces.of_triangle.contains(&(k as u32)) {
            continue;
        }
        let piece_name = format!("{name}.{}", used.name);
        let material = match library.iter().find(|(m, _)| m.name == used.name) {
            Some((m, lib_dir)) => Some(material(m, &piece_name, &obj_dir.join(lib_dir))),
            // A library that could not be read may have held it (warned already).
            None if !all_read => None,
            None => {
                let files: Vec<&str> = faces.libraries.iter().map(|l| l.file.as_str()).collect();
                src.push_warning(
                    file,
                    Diagnostic {
                        file: obj_path.clone(),
                        line: used.line,
                        column: used.column,
                        message: format!(
                            "material \"{}\" is in none of the material libraries ({}); its faces use the default material",
                            used.name,
                            files.join(", ")
                        ),
                        help: None,
                    },
                );
                None
            }
        };
        pieces.push((used.name.clone(), (piece_name, material)));
    }
    if pieces.iter().all(|(_, (_, m))| m.is_none()) {
        // Nothing to give the faces: the object stays whole, with the default material.
        return;
    }
    let mut added: Vec<MaterialDesc> = Vec::new();
    for (mtl_name, (_, m)) in &pieces {
        let Some(m) = m else { continue };
        // A name the scene's own materials hold: said here, at the object, naming the MTL
        // material (the duplicate-name check would point at the scene's material twice).
        match desc.materials.iter().position(|d| d.name == m.name) {
            Some(k) => src.error(
                file,
                &at,
                format!(
                    "material \"{mtl_name}\" of {} would be named \"{}\", a name already in use",
                    obj_file,
                    m.name
                ),
                Some(format!(
                    "the material at {} has it; rename that material, or give object \"{name}\" a `material`",
                    src.where_is(file, &format!("materials[{k}].name"))
                )),
            ),
            None => added.push(m.clone()),
        }
    }
    desc.materials.extend(added);
    if let [(_, (_, material))] = &pieces[..] {
        desc.objects[i].material = material.as_ref().map(|m| m.name.clone());
        return;
    }
    let displaced = desc.objects[i]
        .displacement
        .as_ref()
        .is_some_and(|d| d.mode == DisplacementModeDesc::True);
    if !displaced {
        let slots = pieces
            .into_iter()
            .map(|(usemtl, (_, material))| (usemtl, material.map(|m| m.name).unwrap_or_default()))
            .collect();
        desc.objects[i].mesh = MeshDesc::Obj {
            file: obj_file_of(&desc.objects[i]),
            usemtl: None,
            materials: Some(slots),
        };
        return;
    }
    split(desc, i, pieces);
}

/// Replaces object `i` (truly displaced, so its triangles are re-tessellated and cannot keep
/// per-triangle materials) by a group of one object and instance per piece.
fn split(desc: &mut SceneDesc, i: usize, pieces: Vec<(String, Piece)>) {
    let whole = desc.objects[i].clone();
    let mut members = Vec::new();
    for (k, (usemtl, (piece_name, material))) in pieces.into_iter().enumerate() {
        let piece = ObjectDesc {
            name: piece_name.clone(),
            mesh: MeshDesc::Obj {
                file: obj_file_of(&whole),
                usemtl: Some(usemtl),
                materials: None,
            },
            material: material.map(|m| m.name),
            ..whole.clone()
        };
        if k == 0 {
            desc.objects[i] = piece;
        } else {
            desc.objects.push(piece);
        }
        desc.instances
            .push(InstanceDesc::plain(&piece_name, &piece_name, Vec::new()));
        members.push(piece_name);
    }
    desc.groups.push(GroupDesc {
        name: whole.name,
        members,
    });
}

fn obj_file_of(object: &ObjectDesc) -> String {
    match &object.mesh {
        MeshDesc::Obj { file, .. } => file.clone(),
        _ => String::new(),
    }
}

/// Reads every library of an OBJ: its materials with the library's directory (relative to
/// the OBJ's) and whether every library could be read, or `None` when one is malformed (the
/// error is recorded).
fn read_libraries(
    src: &mut Sources,
    file: usize,
    at: &str,
    obj_path: &Path,
    faces: &FaceMaterials,
    object: &str,
    read: &mut Vec<PathBuf>,
) -> Option<(Vec<(MtlMaterial, PathBuf)>, bool)> {
    let referrer = src.where_is(file, at);
    let mut all_read = true;
    let dir = obj_path.parent().unwrap_or(Path::new(""));
    let mut out = Vec::new();
    for lib in &faces.libraries {
        let path = dir.join(&lib.file);
        let bytes = match read_file(&path, MAX_SCENE_FILE_BYTES, "material library") {
            Ok(bytes) => bytes,
            Err(e) => {
                src.push_warning(
                    file,
                    Diagnostic {
                        file: obj_path.to_path_buf(),
                        line: lib.line,
                        column: lib.column,
                        message: format!(
                            "cannot read material library \"{}\": {}; faces using its materials use the default material",
                            path.display(),
                            io_reason(&e)
                        ),
                        help: None,
                    },
                );
                all_read = false;
                continue;
            }
        };
        read.push(path.clone());
        match mtl::parse(&bytes) {
            Ok(materials) => {
                let help = format!(
                    "material library of \"{}\", loaded for object \"{object}\" at {referrer}",
                    obj_path.display()
                );
                let mut missing = false;
                for m in &materials {
                    for map in [&m.diffuse_map, &m.bump_map].into_iter().flatten() {
                        let texture = path
                            .parent()
                            .unwrap_or(Path::new(""))
                            .join(map.file.replace('\\', "/"));
                        if texture.is_file() {
                            continue;
                        }
                        let pos = src.pos(file, at);
                        src.push(
                            file,
                            pos,
                            Diagnostic {
                                file: path.clone(),
                                line: map.line,
                                column: map.column,
                                message: format!(
                                    "material \"{}\": cannot read texture \"{}\": file not found",
                                    m.name,
                                    texture.display()
                                ),
                                help: Some(help.clone()),
                            },
                        );
                        missing = true;
                    }
                }
                if missing {
                    return None;
                }
                let lib_dir = Path::new(&lib.file)
                    .parent()
                    .unwrap_or(Path::new(""))
                    .to_path_buf();
                out.extend(materials.into_iter().map(|m| (m, lib_dir.clone())));
            }
            Err(e) => {
                let (line, column, message) = match e {
                    MeshFileError::Parse {
                        at: Location::Text { line, column },
                        message,
                    } => (line, column, message),
                    other => (1, 1, other.to_string()),
                };
                let pos = src.pos(file, at);
                src.push(
                    file,
                    pos,
                    Diagnostic {
                        file: path.clone(),
                        line,
                        column,
                        message: format!("invalid MTL file \"{}\": {message}", path.display()),
                        help: Some(format!(
                            "material library of \"{}\", loaded for object \"{object}\" at {referrer}",
                            obj_path.display()
                        )),
                    },
                );
                return None;
            }
        }
    }
    Some((out, all_read))
}

/// The scene material of an MTL material; `dir` is the MTL file's directory relative to
/// the scene file.
fn material(m: &MtlMaterial, name: &str, dir: &Path) -> MaterialDesc {
    let v3 = |c: [f64; 3]| (c[0], c[1], c[2]);
    let diffuse = m.diffuse.unwrap_or(DEFAULT_DIFFUSE);
    let diffuse = diffuse.map(|x| x.min(1.0));
    let specular = m.specular.unwrap_or([0.0; 3]).map(|x| x.min(1.0));
    let refracts = matches!(m.illum, Some(4 | 6 | 7 | 9));
    let (mut shader, diffuse_key) = if refracts {
        let shader = ShaderDesc::Dielectric {
            ior: m.ior.unwrap_or(1.5),
            ior_out: 1.0,
            col: (1.0, 1.0, 1.0),
        };
        (shader, None)
    } else if specular.iter().any(|&x| x > 0.0) {
        let shader = ShaderDesc::Phong {
            ambient: (0.0, 0.0, 0.0),
            diffuse: v3(diffuse),
            specular: v3(specular),
            spec_exp: m.exponent.unwrap_or(DEFAULT_EXPONENT),
        };
        (shader, Some("diffuse"))
    } else {
        (
            ShaderDesc::Lambert {
                albedo: v3(diffuse),
            },
            Some("albedo"),
        )
    };
    let mut bind = BTreeMap::new();
    if let (Some(map), Some(key)) = (&m.diffuse_map, diffuse_key) {
        let image = image(map, dir, EncodingDesc::Srgb);
        let tinted = NodeDesc::Mul(image, InputDesc::Colour(v3(diffuse)));
        bind.insert(key.to_string(), InputDesc::Node(Box::new(tinted)));
    }
    let opacity = m.opacity.unwrap_or(1.0);
    if opacity < 1.0 {
        shader = ShaderDesc::Opacity {
            opacity: (opacity, opacity, opacity),
            input: Box::new(shader),
        };
        bind = bind
            .into_iter()
            .map(|(k, v)| (format!("input.{k}"), v))
            .collect();
    }
    let bump = m.bump_map.as_ref().map(|map| BumpDesc {
        height: Some(InputDesc::Node(Box::new(NodeDesc::Channel(
            image(map, dir, EncodingDesc::Linear),
            0,
        )))),
        normal_map: None,
        object_normal: None,
        scale: map.bump_multiplier,
    });
    MaterialDesc {
        name: name.to_string(),
        shader,
        two_sided: false,
        emission: v3(m.emission.unwrap_or([0.0; 3])),
        bind,
        bump,
        interior: None,
        contour: None,
        lights: None,
        shadow: None,
        environment: None,
        photon: None,
    }
}

/// The image node of a map, its file made relative to the scene file.
fn image(map: &MapRef, dir: &Path, encoding: EncodingDesc) -> InputDesc {
    let file = dir.join(map.file.replace('\\', "/"));
    InputDesc::Node(Box::new(NodeDesc::Image {
        file: file.to_string_lossy().into_owned(),
        uv: InputDesc::Node(Box::new(NodeDesc::Uv)),
        wrap: if map.clamp {
            WrapDesc::Clamp
        } else {
            WrapDesc::Repeat
        },
        color_space: Some(encoding),
    }))
}
