//! Mesh files: one reader per format ([`obj`], [`ply`], [`gltf_file`]), each turning a file's bytes into the same
//! [`MeshData`] or a located [`MeshFileError`]. This module owns the format list
//! ([`MeshFormat`]), the shared description and error, and the dispatch; it knows nothing
//! of scenes or diagnostics ([`super::mesh_load`] turns the results into meshes and
//! messages).
//!
//! Adding a format is one reader file here, one [`MeshFormat`] arm and its `MeshDesc`
//! variant.

pub mod gltf_file;
pub mod mtl;
pub mod obj;
mod obj_lines;
pub mod ply;

use std::fmt;
use std::path::Path;

use glam::{DVec3, Vec2, Vec3, Vec4};

use super::desc::MeshDesc;

/// A mesh file's format, chosen by the `MeshDesc` variant that names the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (`Obj(file: …)`), read by [`obj`].
    Obj,
    /// PLY, ASCII or binary (`Ply(file: …)`), read by [`ply`].
    Ply,
    /// glTF 2.0, `.gltf` or `.glb` (`Gltf(file: …, mesh: …)`), read by [`gltf_file`].
    Gltf,
}

impl MeshFormat {
    /// The format's name in messages (`"OBJ"`).
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::Obj => "OBJ",
            MeshFormat::Ply => "PLY",
            MeshFormat::Gltf => "glTF",
        }
    }

    /// The scene format's variant that names such a file (`"Obj"` for `Obj(file: …)`).
    pub fn variant(self) -> &'static str {
        match self {
            MeshFormat::Obj => "Obj",
            MeshFormat::Ply => "Ply",
            MeshFormat::Gltf => "Gltf",
        }
    }

    /// Reads a file of this format from its bytes (a glTF file: its only mesh, and only
    /// buffers inside the file).
    pub fn parse(self, bytes: &[u8]) -> Result<MeshData, MeshFileError> {
        match self {
            MeshFormat::Obj => obj::parse(bytes),
            MeshFormat::Ply => ply::parse(bytes),
            MeshFormat::Gltf => gltf_file::parse(bytes, None, &gltf_file::MeshPick::default()),
        }
    }
}

/// The mesh file an object's mesh names, if it names one: its format and path (as written,
/// relative to the declaring scene file).
pub fn mesh_file(mesh: &MeshDesc) -> Option<(MeshFormat, &str)> {
    match mesh {
        MeshDesc::Obj { file, .. } => Some((MeshFormat::Obj, file)),
        MeshDesc::Ply { file } => Some((MeshFormat::Ply, file)),
        MeshDesc::Gltf { file, .. } => Some((MeshFormat::Gltf, file)),
        _ => None,
    }
}

/// The part of a glTF file a `Gltf(…)` mesh names (the default for other meshes).
pub fn gltf_pick(mesh: &MeshDesc) -> gltf_file::MeshPick {
    match mesh {
        MeshDesc::Gltf {
            mesh, primitive, ..
        } => gltf_file::MeshPick {
            mesh: mesh.clone(),
            primitive: *primitive,
        },
        _ => gltf_file::MeshPick::default(),
    }
}

/// Reads and parses the mesh file at `path` (for glTF, the part `pick` names; external
/// buffers are read beside the file).
pub fn read(
    format: MeshFormat,
    path: &Path,
    pick: &gltf_file::MeshPick,
) -> Result<MeshData, MeshFileError> {
    use crate::limits::{read_file, MAX_MESH_FILE_BYTES};
    let bytes =
        read_file(path, MAX_MESH_FILE_BYTES, "mesh file").map_err(|e| MeshFileError::Read {
            reason: super::message::io_reason(&e),
        })?;
    match format {
        MeshFormat::Gltf => gltf_file::parse(&bytes, path.parent(), pick),
        _ => format.parse(&bytes),
    }
}

/// A mesh as a file describes it, whatever the format: f64 positions, optional per-vertex
/// normals and texture coordinates, triangles (polygons already fan-triangulated).
///
/// Invariants every reader keeps: `normals` and `uvs`, when present, have one entry per
/// position; every triangle index is below `positions.len()`; every position is finite and
/// within the f32 range (a reader refuses others with a located error). Other values are
/// as written (they may be non-finite or degenerate; [`super::mesh_load`] drops what cannot
/// be rendered).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions in object space, as written (f64).
    pub positions: Vec<DVec3>,
    /// Per-vertex shading normals, when every vertex has one.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates, when every vertex has one.
    pub uvs: Option<Vec<Vec2>>,
    /// A second set of per-vertex texture coordinates (glTF `TEXCOORD_1`, for lightmaps),
    /// when every vertex has one.
    pub uvs1: Option<Vec<Vec2>>,
    /// Per-vertex colours (linear RGB; PLY `red green blue`, glTF `COLOR_0`), when every
    /// vertex has one.
    pub colours: Option<Vec<Vec3>>,
    /// Per-vertex tangents (glTF `TANGENT`: object-space unit `xyz`, handedness `w` = ±1),
    /// when every vertex has one.
    pub tangents: Option<Vec<Vec4>>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// OBJ material libraries and per-triangle materials, when the file names either.
    pub materials: Option<FaceMaterials>,
    /// Attributes some face vertices name and others do not (OBJ), so the mesh has none.
    pub partial: PartialAttributes,
}

/// Where an OBJ file first leaves out an attribute that other face vertices name (`v//vn`
/// beside `v/vt/vn`): `(line, column)` of that face vertex, 1-based, for texture
/// coordinates and normals. The attribute is dropped for the whole mesh (a mesh keeps one
/// only when every vertex has one); the loader warns there.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PartialAttributes {
    /// The first face vertex without `vt`, when others have one.
    pub uvs: Option<(usize, usize)>,
    /// The first face vertex without `vn`, when others have one.
    pub normals: Option<(usize, usize)>,
}

/// A `mtllib` file an OBJ file names, and where.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MaterialLibrary {
    /// The file as written (relative to the OBJ file).
    pub file: String,
    /// 1-based line of the `mtllib` statement.
    pub line: usize,
    /// 1-based column of the file name.
    pub column: usize,
}

/// A material an OBJ file's `usemtl` names, and where it is first named.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UsedMaterial {
    /// The material name.
    pub name: String,
    /// 1-based line of its first `usemtl`.
    pub line: usize,
    /// 1-based column of the name there.
    pub column: usize,
}

/// The materials of an OBJ file's faces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceMaterials {
    /// `mtllib` files, in order.
    pub libraries: Vec<MaterialLibrary>,
    /// Materials named by `usemtl`, in order of first use.
    pub used: Vec<UsedMaterial>,
    /// Per triangle: index into `used`, or `u32::MAX` for a triangle written before any
    /// `usemtl`.
    pub of_triangle: Vec<u32>,
}

impl MeshData {
    /// Keeps only the triangles written under `usemtl name` (`""`: those written before any
    /// `usemtl`) and the vertices they use; an error names the file's materials when no
    /// triangle matches.
    pub fn keep_material(&mut self, name: &str) -> Result<(), String> {
        let used = self.materials.as_ref().map_or(&[][..], |m| &m.used[..]);
        let wanted = if name.is_empty() {
            u32::MAX
        } else {
            match used.iter().position(|u| u.name == name) {
                Some(k) => k as u32,
                None => {
                    let names: Vec<String> =
                        used.iter().map(|u| format!("\"{}\"", u.name)).collect();
                    let has = if names.is_empty() {
                        "the file has no usemtl statements".to_string()
                    } else {
                        format!("it uses {}", names.join(", "))
                    };
                    return Err(format!("no face uses material \"{name}\": {has}"));
                }
            }
        };
        let of_triangle = self
            .materials
            .as_ref()
            .map(|m| m.of_triangle.clone())
            .unwrap_or_else(|| vec![u32::MAX; self.triangles.len()]);
        let mut remap = vec![u32::MAX; self.positions.len()];
        let mut kept = Vec::new();
        let mut triangles = Vec::new();
        for (t, m) in self.triangles.iter().zip(&of_triangle) {
            if *m != wanted {
                continue;
            }
            triangles.push(t.map(|i| {
                let old = i as usize;
                if remap[old] == u32::MAX {
                    remap[old] = kept.len() as u32;
                    kept.push(old);
                }
                remap[old]
            }));
        }
        if triangles.is_empty() {
            return Err(format!("no face uses material \"{name}\""));
        }
        fn pick<T: Copy>(v: &[T], kept: &[usize]) -> Vec<T> {
            kept.iter().map(|&i| v[i]).collect()
        }
        self.positions = pick(&self.positions, &kept);
        self.normals = self.normals.as_ref().map(|n| pick(n, &kept));
        self.uvs = self.uvs.as_ref().map(|u| pick(u, &kept));
        self.uvs1 = self.uvs1.as_ref().map(|u| pick(u, &kept));
        self.colours = self.colours.as_ref().map(|c| pick(c, &kept));
        self.tangents = self.tangents.as_ref().map(|t| pick(t, &kept));
        if let Some(m) = &mut self.materials {
            m.of_triangle = vec![wanted; triangles.len()];
        }
        self.triangles = triangles;
        Ok(())
    }

    /// Orders the triangles by their `usemtl` material as `order` lists them (`""`: the
    /// faces written before any `usemtl`), each material's triangles in file order, and
    /// returns each triangle's index in `order` (`order.len()` for a material `order` does
    /// not list). Grouping keeps the triangle order the pieces of a split file had.
    pub fn group_by_material(&mut self, order: &[String]) -> Vec<u32> {
        let slot_of_used: Vec<u32> = self.materials.as_ref().map_or(Vec::new(), |m| {
            m.used
                .iter()
                .map(|u| position_or_end(order, &u.name))
                .collect()
        });
        let before = position_or_end(order, "");
        let of_triangle = self
            .materials
            .as_ref()
            .map_or(&[][..], |m| &m.of_triangle[..]);
        let slots: Vec<u32> = (0..self.triangles.len())
            .map(|t| {
                of_triangle
                    .get(t)
                    .and_then(|&k| slot_of_used.get(k as usize))
                    .copied()
                    .unwrap_or(before)
            })
            .collect();
        let mut by_slot: Vec<usize> = (0..self.triangles.len()).collect();
        by_slot.sort_by_key(|&t| slots[t]);
        self.triangles = by_slot.iter().map(|&t| self.triangles[t]).collect();
        if let Some(m) = &mut self.materials {
            if m.of_triangle.len() == by_slot.len() {
                m.of_triangle = by_slot.iter().map(|&t| m.of_triangle[t]).collect();
            }
        }
        by_slot.iter().map(|&t| slots[t]).collect()
    }
}

/// The index of `name` in `order`, or `order.len()`.
fn position_or_end(order: &[String], name: &str) -> u32 {
    order.iter().position(|o| o == name).unwrap_or(order.len()) as u32
}

/// Where in a mesh file a problem is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// A text position: 1-based line, and 1-based column in characters (a byte that is not
    /// UTF-8 counts as one).
    Text {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
    },
    /// An offset in binary data, in bytes from the start of the file.
    Byte(u64),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Text { line, column } => write!(f, "line {line}, column {column}"),
            Location::Byte(offset) => write!(f, "byte {offset}"),
        }
    }
}

/// Why a mesh file did not load.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MeshFileError {
    /// The file could not be read.
    Read {
        /// Why, for a message (`"file not found"`).
        reason: String,
    },
    /// The file was read but its content is not a valid file of the format.
    Parse {
        /// Where the first problem is.
        at: Location,
        /// What is wrong, for a message.
        message: String,
    },
    /// An element of a structured file (glTF) is wrong.
    Element {
        /// The element's path in the file (`meshes[0].primitives[1]`, `accessors[3]`).
        path: String,
        /// What is wrong, for a message.
        message: String,
    },
}

impl MeshFileError {
    /// A parse error at a text position.
    pub fn at_line(line: usize, column: usize, message: impl Into<String>) -> Self {
        MeshFileError::Parse {
            at: Location::Text { line, column },
            message: message.into(),
        }
    }
}

impl fmt::Display for MeshFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshFileError::Read { reason } => write!(f, "cannot read the file: {reason}"),
            MeshFileError::Parse { at, message } => write!(f, "{at}: {message}"),
            MeshFileError::Element { path, message } => write!(f, "{path}: {message}"),
        }
    }
}

impl std::error::Error for MeshFileError {}

/// `word` for a message: the text (escaped) when it is UTF-8, else its bytes escaped
/// (`\xff`); at most 24 characters, then `…`.
pub fn shown(word: &[u8]) -> String {
    let escaped: String = match std::str::from_utf8(word) {
        Ok(text) => text.escape_debug().collect(),
        Err(_) => word.escape_ascii().to_string(),
    };
    let mut chars = escaped.chars();
    let head: String = chars.by_ref().take(24).collect();
    if chars.next().is_some() {
        format!("{head}…")
    } else {
        head
    }
}

/// 1-based column of byte `offset` of `line` (characters before it, a byte that is not UTF-8
/// counting as one, plus one).
pub fn column(line: &[u8], offset: usize) -> usize {
    let prefix = &line[..offset.min(line.len())];
    String::from_utf8_lossy(prefix).chars().count() + 1
}
