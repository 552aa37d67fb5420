//! glTF 2.0 files (`.gltf` JSON with external or embedded buffers, and binary `.glb`): the
//! container and the mesh reader.
//!
//! [`open`] reads the container: the GLB header and chunks (checked here, so a truncated or
//! foreign file is reported at its byte offset), the glTF version ([`version`]), the JSON
//! (parsed and validated by the `gltf` crate; its error paths are given in the JSON's names,
//! [`json_names`]), and every buffer (the GLB `BIN` chunk, a base64 `data:` URI, or a file beside the
//! glTF file). [`mesh_data`] reads one mesh (or one of its primitives) into [`MeshData`]:
//! positions, normals, `TEXCOORD_0` and `TEXCOORD_1` (integers must be normalised unless
//! the file uses `KHR_mesh_quantization`), `TANGENT` (checked: `w` = ±1),
//! `COLOR_0` (vec3 or vec4, float or normalised u8/u16, linear; alpha not read; white for
//! the primitives of a mesh that lack it), indices, as triangle lists, strips or fans;
//! other attributes (`_BATCHID`, joints, …) are ignored. A non-finite position is an error
//! naming its accessor, primitive and vertex. Accessors are read here, not
//! by the crate's iterators: every accessor's byte range is checked against its buffer view
//! and every view against its buffer before a byte is read, and every index against the
//! vertex count, so no file can make the reader panic.
//!
//! glTF's texture coordinates have `v` growing downwards (the image's first row at `v = 0`);
//! stagelight's have `v` up (OBJ), so `v` is flipped on reading (`v' = 1 − v`, one f32
//! subtraction: exact whenever the result is an f32, e.g. every `v` in [½, 1]) and on
//! writing. The file holds the f32 nearest `1 − v`, so its UVs match an OBJ's or PLY's
//! only to within rounding (docs/gltf.md).

use std::path::Path;

use glam::{Vec2, Vec3, Vec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::{Location, MeshData, MeshFileError};

pub mod version;

/// GLB chunk type of the JSON chunk (`"JSON"` little-endian).
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// GLB chunk type of the binary chunk (`"BIN\0"` little-endian).
const CHUNK_BIN: u32 = 0x004E_4942;

/// A glTF file with every buffer loaded.
#[derive(Debug, Clone)]
pub struct GltfFile {
    /// The validated document.
    pub doc: gltf::Document,
    /// The bytes of each buffer, by index; each at least its declared `byteLength`.
    pub buffers: Vec<Vec<u8>>,
}

/// Which part of a file a `Gltf(…)` mesh names.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct MeshPick {
    /// The mesh's name (or `#index`); `None` when the file holds exactly one mesh.
    pub mesh: Option<String>,
    /// Only this primitive of the mesh; `None` for all of them.
    pub primitive: Option<u32>,
}

fn element(path: impl Into<String>, message: impl Into<String>) -> MeshFileError {
    MeshFileError::Element {
        path: path.into(),
        message: message.into(),
    }
}

fn at_byte(offset: u64, message: impl Into<String>) -> MeshFileError {
    MeshFileError::Parse {
        at: Location::Byte(offset),
        message: message.into(),
    }
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    bytes
        .get(at..at + 4)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Whether `bytes` are a binary glTF rather than JSON: they start with the GLB magic, or do
/// not start (after white space) with `{`.
fn is_binary(bytes: &[u8]) -> bool {
    bytes.starts_with(b"glTF")
        || bytes
            .iter()
            .find(|b| !b.is_ascii_whitespace())
            .is_some_and(|&b| b != b'{')
}

/// The JSON and `BIN` chunks of a GLB file, checked byte by byte.
fn glb_chunks(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), MeshFileError> {
    let len = bytes.len();
    if len < 12 {
        return Err(at_byte(
            len as u64,
            format!(
                "truncated binary glTF: the file ends after {len} bytes, inside the 12-byte header"
            ),
        ));
    }
    if &bytes[..4] != b"glTF" {
        return Err(at_byte(
            0,
            format!(
                "not a glTF file: it starts with \"{}\", expected the binary glTF magic \"glTF\" or a JSON object",
                bytes[..4].escape_ascii()
            ),
        ));
    }
    let version = u32_at(bytes, 4).unwrap_or(0);
    if version != 2 {
        return Err(at_byte(
            4,
            format!("binary glTF version {version} is not supported (only version 2)"),
        ));
    }
    let total = u32_at(bytes, 8).unwrap_or(0) as usize;
    if total > len {
        return Err(at_byte(
            8,
            format!("truncated binary glTF: the header gives a length of {total} bytes, the file has {len}"),
        ));
    }
    let mut chunks: Vec<(u32, &[u8], usize)> = Vec::new();
    let mut at = 12usize;
    while at < total {
        let (Some(chunk_len), Some(kind)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err(at_byte(
                at as u64,
                format!("truncated binary glTF: a chunk header at byte {at} runs past the end of the data ({total} bytes)"),
            ));
        };
        let start = at + 8;
        let end = start
            .checked_add(chunk_len as usize)
            .filter(|&e| e <= total);
        let Some(end) = end else {
            return Err(at_byte(
                at as u64,
                format!("truncated binary glTF: a chunk of {chunk_len} bytes at byte {start} runs past the end of the data ({total} bytes)"),
            ));
        };
        chunks.push((kind, &bytes[start..end], at));
        at = end;
    }
    let Some(&(kind, json, _)) = chunks.first() else {
        return Err(at_byte(
            12,
            "binary glTF without chunks: the JSON chunk is missing",
        ));
    };
    if kind != CHUNK_JSON {
        return Err(at_byte(
            16,
            "the first chunk of a binary glTF must be its JSON chunk",
        ));
    }
    let bin = chunks
        .get(1)
        .filter(|(kind, ..)| *kind == CHUNK_BIN)
        .map(|(_, data, _)| *data);
    Ok((json, bin))
}

/// Decodes standard base64 (padding optional, no white space).
fn base64(text: &str) -> Option<Vec<u8>> {
    let value = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return None,
        } as u32)
    };
    let body = text.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(body.len() * 3 / 4);
    for chunk in body.chunks(4) {
        if chunk.len() == 1 {
            return None;
        }
        let mut n = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            n |= value(c)? << (18 - 6 * k);
        }
        let bytes = n.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    Some(out)
}

/// Undoes `%XX` escapes of a relative URI (glTF URIs are percent-encoded).
pub fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        let hex = bytes
            .get(k + 1..k + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[k], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                k += 3;
            }
            (b, _) => {
                out.push(b);
                k += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The bytes a `uri` names: a base64 `data:` URI, or a file relative to `dir` (`None`: no
/// directory to read from, as for the fuzz target). `what` names the element in messages.
pub fn uri_bytes(uri: &str, dir: Option<&Path>, what: &str) -> Result<Vec<u8>, MeshFileError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_, data)) = rest.split_once(";base64,") else {
            return Err(element(
                format!("{what}.uri"),
                "a data URI must be base64 (\"data:<type>;base64,…\")",
            ));
        };
        return base64(data)
            .ok_or_else(|| element(format!("{what}.uri"), "the data URI is not valid base64"));
    }
    let name = percent_decode(uri);
    let Some(dir) = dir else {
        return Err(element(
            format!("{what}.uri"),
            format!("cannot read \"{name}\": no directory to read external files from"),
        ));
    };
    let path = dir.join(&name);
    crate::limits::read_file(
        &path,
        crate::limits::MAX_MESH_FILE_BYTES,
        "glTF buffer or image",
    )
    .map_err(|e| {
        element(
            format!("{what}.uri"),
            format!(
                "cannot read \"{}\": {}",
                path.display(),
                crate::scene::message::io_reason(&e)
            ),
        )
    })
}

/// Reads a glTF or GLB file from its bytes; external buffers are read relative to `dir`.
pub fn open(bytes: &[u8], dir: Option<&Path>) -> Result<GltfFile, MeshFileError> {
    let binary = is_binary(bytes);
    let (json, bin) = if binary {
        glb_chunks(bytes)?
    } else {
        (bytes, None)
    };
    let root: gltf::json::Root = match gltf::json::deserialize::from_slice(json) {
        Ok(root) => root,
        Err(e) => {
            if let Some(refusal) = serde_json::from_slice::<serde_json::Value>(json)
                .ok()
                .and_then(|root| version::refusal_of_value(&root))
            {
                return Err(refusal);
            }
            let message = format!("invalid glTF JSON: {e}");
            return Err(if binary {
                at_byte(20, message)
            } else {
                MeshFileError::at_line(e.line().max(1), e.column().max(1), message)
            });
        }
    };
    version::check(&root.asset)?;
    if let Some((path, message)) = what_the_validator_misses(&root) {
        return Err(element(path, format!("invalid glTF: {message}")));
    }
    let doc = match gltf::Document::from_json(root) {
        Ok(doc) => doc,
        Err(gltf::Error::Validation(errors)) => {
            let (path, error) = &errors[0];
            let more = match errors.len() {
                1 => String::new(),
                n => format!(" (and {} more problems)", n - 1),
            };
            let (path, text) = match invalid_semantic(json, path.as_str()) {
                Some(named) => named,
                None => {
                    let path = json_names(path.as_str());
                    let text = validation_text(&path, error);
                    (path, text)
                }
            };
            return Err(element(path, format!("invalid glTF: {text}{more}")));
        }
        Err(e) => return Err(at_byte(0, format!("invalid glTF: {e}"))),
    };
    let mut buffers = Vec::new();
    for buffer in doc.buffers() {
        let what = format!("buffers[{}]", buffer.index());
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => bin.map(<[u8]>::to_vec).ok_or_else(|| {
                element(
                    what.clone(),
                    "the buffer has no uri and the file has no BIN chunk",
                )
            })?,
            gltf::buffer::Source::Uri(uri) => uri_bytes(uri, dir, &what)?,
        };
        if data.len() < buffer.length() {
            return Err(element(
                format!("{what}.byteLength"),
                format!(
                    "the buffer declares {} bytes but its data has {}",
                    buffer.length(),
                    data.len()
                ),
            ));
        }
        buffers.push(data);
    }
    Ok(GltfFile { doc, buffers })
}

/// The first problem that the glTF crate (1.4) neither reports nor survives, as an element path
/// and a message: its validation reads a primitive's `POSITION` accessor without checking the
/// index, and `Image::source` unwraps an image's `uri`, or the `mimeType` beside its
/// `bufferView` — each a panic on such a file — so they are checked before either runs.
fn what_the_validator_misses(root: &gltf::json::Root) -> Option<(String, String)> {
    use gltf::json::validation::Checked;
    let positions = Checked::Valid(gltf::json::mesh::Semantic::Positions);
    let accessor = root.meshes.iter().enumerate().find_map(|(m, mesh)| {
        mesh.primitives
            .iter()
            .enumerate()
            .find_map(|(p, primitive)| {
                let index = primitive.attributes.get(&positions)?.value();
                (index >= root.accessors.len()).then(|| {
                    (
                        format!("meshes[{m}].primitives[{p}].attributes.POSITION"),
                        format!(
                            "accessor {index} is out of range: the file has {} accessors",
                            root.accessors.len()
                        ),
                    )
                })
            })
    });
    let image = || {
        root.images.iter().enumerate().find_map(|(i, image)| {
            let problem = match (&image.buffer_view, &image.mime_type, &image.uri) {
                (Some(_), None, _) => "an image in a bufferView needs its mimeType",
                (None, _, None) => "an image needs a uri or a bufferView",
                _ => return None,
            };
            Some((format!("images[{i}]"), problem.to_string()))
        })
    };
    accessor.or_else(image)
}

/// What the glTF crate writes for an attribute name it does not know (it keeps no name).
const INVALID_SEMANTIC: &str = "[\"<invalid semantic name>\"]";

/// For a validation error at an attribute name the crate could not read
/// (`meshes[0].primitives[0].attributes["<invalid semantic name>"]`): the path with the
/// name as written and a message saying what names are allowed. `None` for other paths.
fn invalid_semantic(json: &[u8], path: &str) -> Option<(String, String)> {
    use gltf::json::mesh::Semantic;
    use gltf::json::validation::Checked;
    let prefix = path.strip_suffix(INVALID_SEMANTIC)?;
    let root: serde_json::Value = serde_json::from_slice(json).ok()?;
    let mut at = &root;
    for part in prefix.split('.') {
        let (key, indices) = part.split_once('[').unwrap_or((part, ""));
        at = at.get(key)?;
        for index in indices.split('[').filter(|i| !i.is_empty()) {
            at = at.get(index.strip_suffix(']')?.parse::<usize>().ok()?)?;
        }
    }
    let name = at.as_object()?.keys().find(|k| {
        matches!(
            serde_json::from_value::<Checked<Semantic>>(serde_json::Value::String((*k).clone())),
            Ok(Checked::Invalid) | Err(_)
        )
    })?;
    Some((
        format!("{prefix}[\"{name}\"]"),
        format!(
            "\"{name}\" is not an attribute name: expected POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n, JOINTS_n, WEIGHTS_n, or an application-specific name starting with \"_\""
        ),
    ))
}

/// A validation path as the JSON spells it: the `gltf` crate names extension members by
/// its Rust fields in camel case (`extensions.khrLightsPunctual.lights[0]`), the file by
/// the extension's name (`extensions.KHR_lights_punctual.lights[0]`).
pub fn json_names(path: &str) -> String {
    path.split('.')
        .map(|part| {
            let (key, rest) = part.split_at(part.find('[').unwrap_or(part.len()));
            let Some(words) = key
                .strip_prefix("khr")
                .filter(|w| w.starts_with(|c: char| c.is_ascii_uppercase()))
            else {
                return part.to_string();
            };
            let mut name = String::from("KHR");
            for c in words.chars() {
                if c.is_ascii_uppercase() {
                    name.push('_');
                }
                name.push(c.to_ascii_lowercase());
            }
            name + rest
        })
        .collect::<Vec<_>>()
        .join(".")
}

/// What the validator's `error` at `path` (in the JSON's names) means; a sampler's wrap
/// mode and a light's type name the values allowed.
fn validation_text(path: &str, error: &gltf::json::validation::Error) -> String {
    use gltf::json::validation::Error as E;
    if matches!(error, E::Invalid) && (path.ends_with(".wrapS") || path.ends_with(".wrapT")) {
        return "not a wrap mode: expected 33071 (CLAMP_TO_EDGE), 33648 (MIRRORED_REPEAT) or 10497 (REPEAT)".into();
    }
    if matches!(error, E::Invalid)
        && path.starts_with("extensions.KHR_lights_punctual.lights[")
        && path.ends_with("].type")
    {
        return "not a light type: expected \"directional\", \"point\" or \"spot\"".into();
    }
    match error {
        E::IndexOutOfBounds => "an index is out of range",
        E::Invalid => "an invalid value",
        E::Missing => "a required value is missing",
        E::Oversize => "a size or offset is too large",
        E::Unsupported => "a required extension is not supported",
    }
    .into()
}

/// The checked bytes of an accessor: its view's slice, element offset, stride and size.
struct AccessorBytes<'a> {
    data: &'a [u8],
    stride: usize,
    count: usize,
    kind: DataType,
    normalized: bool,
}

impl AccessorBytes<'_> {
    /// Component `c` of element `i` as f32 (normalised integers mapped to [0, 1]).
    fn float(&self, i: usize, c: usize) -> f32 {
        let k = self.kind.size();
        let at = i * self.stride + c * k;
        let b = &self.data[at..at + k];
        match self.kind {
            DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            DataType::U8 if self.normalized => b[0] as f32 / 255.0,
            DataType::U16 if self.normalized => u16::from_le_bytes([b[0], b[1]]) as f32 / 65535.0,
            DataType::I8 if self.normalized => (b[0] as i8 as f32 / 127.0).max(-1.0),
            DataType::I16 if self.normalized => {
                (i16::from_le_bytes([b[0], b[1]]) as f32 / 32767.0).max(-1.0)
            }
            _ => self.index(i) as f32,
        }
    }

    /// Element `i` of an unsigned integer accessor.
    fn index(&self, i: usize) -> u32 {
        let at = i * self.stride;
        let b = &self.data[at..];
        match self.kind {
            DataType::U8 => b[0] as u32,
            DataType::U16 => u16::from_le_bytes([b[0], b[1]]) as u32,
            DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            DataType::I8 => b[0] as i8 as u32,
            DataType::I16 => i16::from_le_bytes([b[0], b[1]]) as u32,
            DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as u32,
        }
    }
}

/// Checks accessor `accessor` (used as `role`, for messages) against its view and buffer,
/// and that its type is one of `kinds` with `dims`.
fn accessor_bytes<'a>(
    file: &'a GltfFile,
    accessor: &gltf::Accessor<'_>,
    role: &str,
    kinds: &[DataType],
    dims: Dimensions,
) -> Result<AccessorBytes<'a>, MeshFileError> {
    let path = format!("accessors[{}]", accessor.index());
    if accessor.sparse().is_some() {
        return Err(element(
            path,
            format!("{role}: sparse accessors are not supported"),
        ));
    }
    let kind = accessor.data_type();
    if !kinds.contains(&kind) || accessor.dimensions() != dims {
        return Err(element(
            path,
            format!(
                "{role}: component type {:?} {:?} is not supported here (expected {:?} of {})",
                kind,
                accessor.dimensions(),
                dims,
                kinds
                    .iter()
                    .map(|k| format!("{k:?}"))
                    .collect::<Vec<_>>()
                    .join(" or ")
            ),
        ));
    }
    let Some(view) = accessor.view() else {
        return Err(element(
            path,
            format!("{role}: the accessor has no bufferView"),
        ));
    };
    let buffer = &file.buffers[view.buffer().index()];
    let view_end = view.offset().checked_add(view.length());
    let Some(view_data) = view_end.and_then(|end| buffer.get(view.offset()..end)) else {
        return Err(element(
            format!("bufferViews[{}]", view.index()),
            format!(
                "bytes {} to {} lie outside buffers[{}] ({} bytes)",
                view.offset(),
                view.offset() as u128 + view.length() as u128,
                view.buffer().index(),
                buffer.len()
            ),
        ));
    };
    let size = accessor.size();
    if let Some(stride) = view.stride().filter(|&s| s < size) {
        return Err(element(
            format!("bufferViews[{}].byteStride", view.index()),
            format!(
                "a stride of {stride} bytes is less than the {size}-byte elements of {path} ({role}): its elements would overlap"
            ),
        ));
    }
    let stride = view.stride().unwrap_or(size);
    let count = accessor.count();
    let end = match count {
        0 => Some(accessor.offset()),
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(size))
            .and_then(|x| x.checked_add(accessor.offset())),
    };
    let Some(data) = end.and_then(|end| view_data.get(accessor.offset()..end)) else {
        return Err(element(
            path,
            format!(
                "{role}: {count} elements of {size} bytes from byte {} (stride {stride}) run past the end of bufferViews[{}] ({} bytes)",
                accessor.offset(),
                view.index(),
                view.length()
            ),
        ));
    };
    Ok(AccessorBytes {
        data,
        stride,
        count,
        kind,
        normalized: accessor.normalized(),
    })
}

/// The index of the mesh `pick` names: by name (or `#index`), or the only mesh.
pub fn pick_mesh(doc: &gltf::Document, name: Option<&str>) -> Result<usize, MeshFileError> {
    let meshes: Vec<gltf::Mesh<'_>> = doc.meshes().collect();
    let label = |m: &gltf::Mesh<'_>| match m.name() {
        Some(n) => format!("\"{n}\""),
        None => format!("\"#{}\"", m.index()),
    };
    let Some(name) = name else {
        return match meshes.len() {
            1 => Ok(0),
            0 => Err(element("meshes", "the file holds no mesh")),
            n => Err(element(
                "meshes",
                format!(
                    "the file holds {n} meshes; name one with `mesh:` ({})",
                    meshes.iter().map(label).collect::<Vec<_>>().join(", ")
                ),
            )),
        };
    };
    let named: Vec<usize> = meshes
        .iter()
        .filter(|m| m.name() == Some(name))
        .map(|m| m.index())
        .collect();
    match named.as_slice() {
        [one] => return Ok(*one),
        [] => {}
        many => {
            return Err(element(
                "meshes",
                format!(
                    "{} meshes are named \"{name}\" ({}); name one by index (\"#{}\")",
                    many.len(),
                    many.iter()
                        .map(|i| format!("meshes[{i}]"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    many[0]
                ),
            ))
        }
    }
    let held = meshes.iter().map(label).collect::<Vec<_>>().join(", ");
    if let Some(index) = name.strip_prefix('#').and_then(|i| i.parse::<usize>().ok()) {
        if index < meshes.len() {
            return Ok(index);
        }
        let has = match meshes.len() {
            0 => "no meshes".to_string(),
            1 => format!("one mesh (\"#0\"): {held}"),
            n => format!("{n} meshes (\"#0\" to \"#{}\"): {held}", n - 1),
        };
        return Err(element(
            "meshes",
            format!("mesh \"{name}\" is out of range: the file has {has}"),
        ));
    }
    Err(element(
        "meshes",
        format!("no mesh named \"{name}\"; the file holds {held}"),
    ))
}

/// Reads the mesh (or primitive) `pick` names into one [`MeshData`], primitives appended in
/// order. Triangle lists, strips and fans are read (modes 4, 5, 6).
pub fn mesh_data(file: &GltfFile, pick: &MeshPick) -> Result<MeshData, MeshFileError> {
    let index = pick_mesh(&file.doc, pick.mesh.as_deref())?;
    let Some(mesh) = file.doc.meshes().nth(index) else {
        return Err(element("meshes", "the mesh vanished"));
    };
    let primitives: Vec<gltf::Primitive<'_>> = mesh.primitives().collect();
    let chosen: Vec<&gltf::Primitive<'_>> = match pick.primitive {
        None => primitives.iter().collect(),
        Some(p) => match primitives.get(p as usize) {
            Some(prim) => vec![prim],
            None => {
                return Err(element(
                    format!("meshes[{index}].primitives"),
                    format!(
                        "primitive {p} does not exist: the mesh has {} primitives",
                        primitives.len()
                    ),
                ))
            }
        },
    };
    let mut out = MeshData::default();
    let mut normals: Option<Vec<Vec3>> = Some(Vec::new());
    let mut uv0: Option<Vec<Vec2>> = Some(Vec::new());
    let mut uv1: Option<Vec<Vec2>> = Some(Vec::new());
    let mut tangents: Option<Vec<Vec4>> = Some(Vec::new());
    let mut colours: Vec<Vec3> = Vec::new();
    let mut any_colours = false;
    for prim in chosen {
        let path = format!("meshes[{index}].primitives[{}]", prim.index());
        let mode = prim.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            return Err(element(
                path,
                format!(
                    "primitive mode {mode:?} is not supported: only triangles (mode 4, TRIANGLES; 5, TRIANGLE_STRIP; 6, TRIANGLE_FAN)"
                ),
            ));
        }
        let Some(pos) = prim.get(&gltf::Semantic::Positions) else {
            return Err(element(
                format!("{path}.attributes"),
                "the primitive has no POSITION attribute",
            ));
        };
        let position_accessor = pos.index();
        let pos = accessor_bytes(file, &pos, "POSITION", &[DataType::F32], Dimensions::Vec3)?;
        let base = out.positions.len();
        let n = pos.count;
        for i in 0..n {
            let p = Vec3::from_array([0, 1, 2].map(|c| pos.float(i, c)));
            if !p.is_finite() {
                return Err(element(
                    format!("accessors[{position_accessor}]"),
                    format!(
                        "POSITION of {path}: vertex {i} is ({}, {}, {}): a vertex position must be a finite number",
                        p.x, p.y, p.z
                    ),
                ));
            }
            out.positions.push(p.as_dvec3());
        }
        let attr = |semantic: gltf::Semantic,
                    role: &str,
                    kinds: &[DataType],
                    dims: Dimensions|
         -> Result<Option<AccessorBytes<'_>>, MeshFileError> {
            let Some(a) = prim.get(&semantic) else {
                return Ok(None);
            };
            let bytes = accessor_bytes(file, &a, role, kinds, dims)?;
            if bytes.count != n {
                return Err(element(
                    format!("accessors[{}]", a.index()),
                    format!("{role} has {} elements but POSITION has {n}", bytes.count),
                ));
            }
            Ok(Some(bytes))
        };
        match attr(
            gltf::Semantic::Normals,
            "NORMAL",
            &[DataType::F32],
            Dimensions::Vec3,
        )? {
            Some(a) => {
                if let Some(list) = &mut normals {
                    list.extend((0..n).map(|i| Vec3::from_array([0, 1, 2].map(|c| a.float(i, c)))));
                }
            }
            None => normals = None,
        }
        let uv_kinds = [DataType::F32, DataType::U8, DataType::U16];
        let quantized = file
            .doc
            .extensions_used()
            .any(|e| e == "KHR_mesh_quantization");
        for (set, list) in [(0u32, &mut uv0), (1, &mut uv1)] {
            let role = format!("TEXCOORD_{set}");
            match attr(
                gltf::Semantic::TexCoords(set),
                &role,
                &uv_kinds,
                Dimensions::Vec2,
            )? {
                Some(a) => {
                    if a.kind != DataType::F32 && !a.normalized && !quantized {
                        let index = prim
                            .get(&gltf::Semantic::TexCoords(set))
                            .map_or(0, |c| c.index());
                        return Err(element(
                            format!("accessors[{index}]"),
                            format!(
                                "{role}: {:?} components must be normalized (\"normalized\": true) to be texture coordinates (unnormalized integers need KHR_mesh_quantization)",
                                a.kind
                            ),
                        ));
                    }
                    if let Some(list) = list {
                        list.extend((0..n).map(|i| Vec2::new(a.float(i, 0), 1.0 - a.float(i, 1))));
                    }
                }
                None => *list = None,
            }
        }
        match attr(
            gltf::Semantic::Tangents,
            "TANGENT",
            &[DataType::F32],
            Dimensions::Vec4,
        )? {
            Some(a) => {
                let read = read_tangents(&a, prim)?;
                if let Some(list) = &mut tangents {
                    list.extend(read);
                }
            }
            None => tangents = None,
        }
        let colour = prim.get(&gltf::Semantic::Colors(0));
        let dims = match colour.as_ref().map(|a| a.dimensions()) {
            Some(Dimensions::Vec4) => Dimensions::Vec4,
            _ => Dimensions::Vec3,
        };
        let colour_kinds = [DataType::F32, DataType::U8, DataType::U16];
        match attr(gltf::Semantic::Colors(0), "COLOR_0", &colour_kinds, dims)? {
            Some(a) => {
                if a.kind != DataType::F32 && !a.normalized {
                    return Err(element(
                        format!("accessors[{}]", colour.map_or(0, |c| c.index())),
                        format!(
                            "COLOR_0: {:?} components must be normalized (\"normalized\": true) to be colours in [0, 1]",
                            a.kind
                        ),
                    ));
                }
                any_colours = true;
                colours.extend((0..n).map(|i| Vec3::from_array([0, 1, 2].map(|c| a.float(i, c)))));
            }
            None => colours.extend(std::iter::repeat_n(Vec3::ONE, n)),
        }
        let corners: Vec<u32> = match prim.indices() {
            Some(acc) => {
                let a = accessor_bytes(
                    file,
                    &acc,
                    "indices",
                    &[DataType::U8, DataType::U16, DataType::U32],
                    Dimensions::Scalar,
                )?;
                let mut list = Vec::with_capacity(a.count);
                for i in 0..a.count {
                    let v = a.index(i);
                    if v as usize >= n {
                        return Err(element(
                            format!("accessors[{}]", acc.index()),
                            format!("index {v} (element {i}) is out of range: the primitive has {n} vertices"),
                        ));
                    }
                    list.push(v);
                }
                list
            }
            None => (0..n as u32).collect(),
        };
        if mode == Mode::Triangles && !corners.len().is_multiple_of(3) {
            return Err(element(
                path,
                format!(
                    "{} indices do not make whole triangles (a multiple of 3 is needed)",
                    corners.len()
                ),
            ));
        }
        out.triangles.extend(
            triangles(mode, &corners)
                .into_iter()
                .map(|t| t.map(|v| v + base as u32)),
        );
    }
    out.normals = normals.filter(|n| n.len() == out.positions.len());
    out.uvs = uv0.filter(|u| u.len() == out.positions.len());
    out.uvs1 = uv1.filter(|u| u.len() == out.positions.len());
    out.tangents = tangents.filter(|t| t.len() == out.positions.len());
    out.colours = Some(colours).filter(|c| any_colours && c.len() == out.positions.len());
    Ok(out)
}

/// The triangles of a primitive's corners (indices, or the vertices in order) as the
/// specification orders them: a list in threes; a strip's triangle `i` is
/// `(v[i], v[i + 1 + i % 2], v[i + 2 - i % 2])`, a fan's `(v[i + 1], v[i + 2], v[0])`.
/// Strip and fan triangles that repeat a vertex (the joins of restarted strips) are left
/// out; they have no area.
fn triangles(mode: Mode, c: &[u32]) -> Vec<[u32; 3]> {
    let joined = |i: usize| match mode {
        Mode::TriangleFan => [c[i + 1], c[i + 2], c[0]],
        _ => [c[i], c[i + 1 + i % 2], c[i + 2 - i % 2]],
    };
    match mode {
        Mode::TriangleStrip | Mode::TriangleFan => (0..c.len().saturating_sub(2))
            .map(joined)
            .filter(|[a, b, d]| a != b && b != d && a != d)
            .collect(),
        _ => c.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

/// The tangents of a `TANGENT` accessor: finite, a non-zero `xyz` and `w` = ±1 (the
/// bitangent's handedness) in every element, else an error naming the element.
fn read_tangents(
    a: &AccessorBytes<'_>,
    prim: &gltf::Primitive<'_>,
) -> Result<Vec<Vec4>, MeshFileError> {
    let index = prim.get(&gltf::Semantic::Tangents).map_or(0, |t| t.index());
    (0..a.count)
        .map(|i| {
            let t = Vec4::from_array([0, 1, 2, 3].map(|c| a.float(i, c)));
            let xyz = t.truncate();
            if !t.is_finite() || xyz.length_squared() == 0.0 || t.w.abs() != 1.0 {
                return Err(element(
                    format!("accessors[{index}]"),
                    format!(
                        "TANGENT element {i} is ({}, {}, {}, {}): expected a non-zero direction and w = 1 or -1 (the bitangent's sign)",
                        t.x, t.y, t.z, t.w
                    ),
                ));
            }
            Ok(xyz.normalize().extend(t.w))
        })
        .collect()
}

/// Reads the mesh `pick` names from a glTF file's bytes (external buffers relative to
/// `dir`).
pub fn parse(bytes: &[u8], dir: Option<&Path>, pick: &MeshPick) -> Result<MeshData, MeshFileError> {
    let file = open(bytes, dir)?;
    mesh_data(&file, pick)
}

/// Splits an image reference into a glTF file, `model.glb#images[3]` → `("model.glb", 3)`;
/// `None` for any other name.
pub fn image_reference(name: &str) -> Option<(&str, usize)> {
    let (file, fragment) = name.rsplit_once('#')?;
    let index = fragment.strip_prefix("images[")?.strip_suffix(']')?;
    Some((file, index.parse().ok()?))
}

/// Image `index` of the glTF file at `path` for messages: `images[3] ("bricks")`, or
/// `images[3]` when it has no name (or the file cannot be read).
pub fn image_label(path: &Path, index: usize) -> String {
    let name = crate::limits::read_file(path, crate::limits::MAX_MESH_FILE_BYTES, "glTF file")
        .ok()
        .and_then(|bytes| open(&bytes, None).ok())
        .and_then(|file| {
            let image = file.doc.images().nth(index)?;
            image.name().map(str::to_string)
        });
    match name {
        Some(n) => format!("images[{index}] (\"{n}\")"),
        None => format!("images[{index}]"),
    }
}

/// The encoded bytes (PNG, JPEG, …) of image `index` of the glTF file at `path`: a buffer
/// view, a `data:` URI or a file beside it.
pub fn image_bytes(path: &Path, index: usize) -> Result<Vec<u8>, String> {
    let bytes = crate::limits::read_file(path, crate::limits::MAX_MESH_FILE_BYTES, "glTF file")
        .map_err(|e| crate::scene::message::io_reason(&e))?;
    let dir = path.parent();
    let file = open(&bytes, dir).map_err(|e| e.to_string())?;
    let count = file.doc.images().count();
    let Some(image) = file.doc.images().nth(index) else {
        return Err(format!("the file has {count} images, no images[{index}]"));
    };
    match image.source() {
        gltf::image::Source::Uri { uri, .. } => {
            uri_bytes(uri, dir, &format!("images[{index}]")).map_err(|e| e.to_string())
        }
        gltf::image::Source::View { view, .. } => {
            let buffer = &file.buffers[view.buffer().index()];
            view.offset()
                .checked_add(view.length())
                .and_then(|end| buffer.get(view.offset()..end))
                .map(<[u8]>::to_vec)
                .ok_or_else(|| {
                    format!(
                        "bufferViews[{}]: the image's bytes lie outside buffers[{}]",
                        view.index(),
                        view.buffer().index()
                    )
                })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_with_and_without_padding() {
        assert_eq!(base64("TWFu").unwrap(), b"Man");
        assert_eq!(base64("TWE=").unwrap(), b"Ma");
        assert_eq!(base64("TQ").unwrap(), b"M");
        assert!(base64("T").is_none());
        assert!(base64("T*==").is_none());
    }

    #[test]
    fn glb_header_problems_are_located() {
        let e = open(b"glTF\x02\0\0", None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "byte 7: truncated binary glTF: the file ends after 7 bytes, inside the 12-byte header"
        );
        let e = open(b"PK\x03\x04\x02\0\0\0\x0c\0\0\0", None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "byte 0: not a glTF file: it starts with \"PK\\x03\\x04\", expected the binary glTF magic \"glTF\" or a JSON object"
        );
        let e = open(b"glTF\x02\0\0\0\xff\0\0\0", None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "byte 8: truncated binary glTF: the header gives a length of 255 bytes, the file has 12"
        );
    }

    #[test]
    fn image_references_name_a_file_and_an_index() {
        assert_eq!(image_reference("a.glb#images[3]"), Some(("a.glb", 3)));
        assert_eq!(image_reference("a.png"), None);
        assert_eq!(image_reference("a.glb#images[x]"), None);
    }

    #[test]
    fn strips_and_fans_become_triangles_in_the_specifications_order() {
        let c = [0, 1, 2, 3, 4];
        assert_eq!(
            triangles(Mode::TriangleStrip, &c),
            [[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            triangles(Mode::TriangleFan, &c),
            [[1, 2, 0], [2, 3, 0], [3, 4, 0]]
        );
        // A restarted strip's joining triangles repeat a vertex: left out.
        assert_eq!(
            triangles(Mode::TriangleStrip, &[0, 1, 2, 2, 5, 5, 6, 7]),
            [[0, 1, 2], [5, 7, 6]]
        );
        assert_eq!(
            triangles(Mode::TriangleStrip, &[0, 1]),
            Vec::<[u32; 3]>::new()
        );
        assert_eq!(triangles(Mode::Triangles, &[0, 1, 2]), [[0, 1, 2]]);
    }

    #[test]
    fn percent_escapes_are_decoded() {
        assert_eq!(percent_decode("a%20b.bin"), "a b.bin");
        assert_eq!(percent_decode("100%"), "100%");
    }
}
