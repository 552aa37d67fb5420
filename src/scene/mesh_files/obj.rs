//! Wavefront OBJ reader: the geometry of an OBJ file (`v`, `vt`, `vn`, `f`) as a
//! [`MeshData`], read from bytes.
//!
//! OBJ is bytes, not text: only statement keywords and numbers must be ASCII. Comments may
//! hold any bytes; an object, group or material name that is not UTF-8 is an error at its
//! line. A line whose first word is not an OBJ statement (binary data, another format,
//! prose) is an error at that word, so a file that is not OBJ never loads as an empty mesh.
//!
//! The rules, as the loader applied them before this reader existed (through `tobj`):
//! - positions are f64 (`v x y z`, divided by `w` in `v x y z w`; a colour in
//!   `v x y z r g b` is read and ignored), normals and texture coordinates are rounded to
//!   f32; a position that is not finite (`nan`, `inf`) or lies beyond the f32 range is an
//!   error at the number (added by stagelight: `tobj` kept it);
//! - every object or group (`o`, `g`) is a model; within a model each distinct
//!   `v/vt/vn` triple becomes one vertex, numbered in order of first use, and the models
//!   are concatenated;
//! - a face `a b c d …` is fan-triangulated into `(a, b, c), (a, c, d), …`;
//! - normals (texture coordinates) are kept only when every face vertex names one; where some
//!   do and others do not, [`super::PartialAttributes`] says where the first one without is.
//!
//! A line ending in a backslash continues on the next one (the OBJ specification's line
//! continuation; [`super::obj_lines`]): errors still name the line and column where the
//! offending word was written.
//!
//! Indices count from 1, or back from −1 (the last element read so far); an index may
//! refer to an element written later in the file. An index of 0, one before the first
//! element, or past the last is an error at the face vertex that holds it, as is a `vt` or
//! `vn` index when the file has no such element. Points (`p`), lines (`l`), smoothing groups
//! and free-form geometry statements are valid and ignored.
//!
//! Materials: the `mtllib` files (each word one file, as written) and the material each
//! triangle was written under (`usemtl`, none before the first) are kept in
//! [`MeshData::materials`] when the file has either; reading the libraries is
//! [`crate::scene::obj_materials`]'s job.

use std::collections::HashMap;

use glam::{DVec3, Vec2, Vec3};

use super::obj_lines::{logical_lines, LogicalLine};
use super::{
    shown, FaceMaterials, MaterialLibrary, MeshData, MeshFileError, PartialAttributes, UsedMaterial,
};

/// Valid OBJ statements that carry nothing this reader uses (besides the names it checks).
const IGNORED: &[&[u8]] = &[
    b"vp",
    b"p",
    b"l",
    b"s",
    b"cstype",
    b"deg",
    b"bmat",
    b"step",
    b"curv",
    b"curv2",
    b"surf",
    b"parm",
    b"trim",
    b"hole",
    b"scrv",
    b"sp",
    b"end",
    b"con",
    b"mg",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"lod",
    b"shadow_obj",
    b"trace_obj",
    b"ctech",
    b"stech",
    b"maplib",
    b"usemap",
    b"call",
    b"csh",
];

/// Marks a face vertex without a texture coordinate or normal.
const NONE: u32 = u32::MAX;

/// Parses an OBJ file (see the module documentation for the rules).
pub fn parse(bytes: &[u8]) -> Result<MeshData, MeshFileError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let mut reader = Reader {
        current: NONE,
        ..Reader::default()
    };
    for line in logical_lines(bytes) {
        reader.statement(&line).map_err(|(offset, message)| {
            let (line, column) = line.at(offset);
            MeshFileError::at_line(line, column, message)
        })?;
    }
    reader.finish()
}

/// A face index that refers past the elements read so far, checked at the end of the file.
struct Forward {
    line: usize,
    column: usize,
    /// 0 for `v`, 1 for `vt`, 2 for `vn`.
    kind: usize,
    /// The index as written.
    written: i64,
    /// The 0-based element it names.
    index: u32,
}

/// What an OBJ file has said so far.
#[derive(Default)]
struct Reader {
    positions: Vec<DVec3>,
    uvs: Vec<Vec2>,
    normals: Vec<Vec3>,
    /// Output vertices as `[v, vt, vn]` element indices ([`NONE`] where absent).
    vertices: Vec<[u32; 3]>,
    /// Output vertex of each triple of the current model.
    model: HashMap<[u32; 3], u32>,
    triangles: Vec<[u32; 3]>,
    forward: Vec<Forward>,
    /// `mtllib` files in order.
    libraries: Vec<MaterialLibrary>,
    /// Materials named by `usemtl`, in order of first use.
    used: Vec<UsedMaterial>,
    /// Index into `used` of the current `usemtl` ([`NONE`] before the first).
    current: u32,
    /// The material of each triangle (index into `used`, or [`NONE`]).
    triangle_material: Vec<u32>,
    /// `(line, column)` of the first face vertex without `vt` (`[1]`) and without `vn`
    /// (`[2]`); `[0]` unused.
    first_without: [Option<(usize, usize)>; 3],
}

/// An error inside a line: byte offset in the line and message.
type LineError = (usize, String);

impl Reader {
    fn statement(&mut self, logical: &LogicalLine<'_>) -> Result<(), LineError> {
        let line: &[u8] = &logical.text;
        let words = words(line);
        let Some(&(at, keyword)) = words.first() else {
            return Ok(());
        };
        let args = &words[1..];
        match keyword {
            b"v" => self.position(args, at),
            b"vt" => {
                let n = numbers(
                    args,
                    at,
                    1..=3,
                    "a texture coordinate has 1 to 3 numbers (\"vt u v\")",
                )?;
                self.uvs.push(Vec2::new(
                    n[0] as f32,
                    n.get(1).copied().unwrap_or(0.0) as f32,
                ));
                Ok(())
            }
            b"vn" => {
                let n = numbers(args, at, 3..=3, "a normal needs 3 numbers (\"vn x y z\")")?;
                self.normals
                    .push(Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32));
                Ok(())
            }
            b"f" => self.face(logical, args, at),
            b"o" | b"g" => {
                let what = if keyword == b"o" { "object" } else { "group" };
                utf8_name(line, at + keyword.len(), what)?;
                self.model.clear();
                Ok(())
            }
            b"usemtl" => {
                let start = at + keyword.len();
                if words.len() < 2 {
                    return Err((start, "usemtl needs a material name".into()));
                }
                utf8_name(line, start, "material")?;
                let name = String::from_utf8_lossy(&line[words[1].0..])
                    .trim_end()
                    .to_string();
                self.current = match self.used.iter().position(|u| u.name == name) {
                    Some(k) => k as u32,
                    None => {
                        let (line, column) = logical.at(words[1].0);
                        self.used.push(UsedMaterial { name, line, column });
                        (self.used.len() - 1) as u32
                    }
                };
                Ok(())
            }
            b"mtllib" => {
                for &(offset, word) in args {
                    let file = std::str::from_utf8(word).map_err(|_| {
                        (offset, "the material library name is not UTF-8".to_string())
                    })?;
                    let (line, column) = logical.at(offset);
                    self.libraries.push(MaterialLibrary {
                        file: file.to_string(),
                        line,
                        column,
                    });
                }
                Ok(())
            }
            _ if keyword.starts_with(b"#") || IGNORED.contains(&keyword) => Ok(()),
            b"ply" if logical.first_line() == 1 => Err((
                at,
                "\"ply\" is not an OBJ statement: this is a PLY file (load it with Ply(file: …))"
                    .into(),
            )),
            _ => Err((
                at,
                format!("\"{}\" is not an OBJ statement", shown(keyword)),
            )),
        }
    }

    fn position(&mut self, args: &[(usize, &[u8])], at: usize) -> Result<(), LineError> {
        let n = numbers(args, at, 3..=6, "a position needs 3 numbers (\"v x y z\")")?;
        let position = match n.len() {
            3 | 6 => DVec3::new(n[0], n[1], n[2]),
            4 if n[3] == 0.0 => {
                return Err((
                    args[3].0,
                    "the weight w of a position must not be zero".into(),
                ))
            }
            4 => DVec3::new(n[0] / n[3], n[1] / n[3], n[2] / n[3]),
            count => {
                return Err((
                    args[count - 1].0,
                    format!(
                    "a position has 3 numbers, 4 with a weight or 6 with a colour, found {count}"
                ),
                ))
            }
        };
        for (k, x) in position.to_array().into_iter().enumerate() {
            let expected = if !x.is_finite() {
                "a vertex position must be a finite number"
            } else if x.abs() > f64::from(f32::MAX) {
                "a vertex position must lie within the f32 range (±3.4e38)"
            } else {
                continue;
            };
            let weighted = if n.len() == 4 { " (divided by w)" } else { "" };
            return Err((
                args[k].0,
                format!(
                    "position {} = {x:e}{weighted}: {expected}",
                    ["x", "y", "z"][k]
                ),
            ));
        }
        self.positions.push(position);
        Ok(())
    }

    fn face(
        &mut self,
        line: &LogicalLine<'_>,
        args: &[(usize, &[u8])],
        at: usize,
    ) -> Result<(), LineError> {
        if args.len() < 3 {
            return Err((
                at,
                format!("a face needs at least 3 vertices, found {}", args.len()),
            ));
        }
        let mut corners = Vec::with_capacity(args.len());
        for &(offset, word) in args {
            corners.push(self.face_vertex(line, offset, word)?);
        }
        for k in 1..corners.len() - 1 {
            let triangle = [corners[0], corners[k], corners[k + 1]].map(|c| self.vertex(c));
            self.triangles.push(triangle);
            self.triangle_material.push(self.current);
        }
        Ok(())
    }

    /// The `[v, vt, vn]` element indices of a face vertex `v`, `v/vt`, `v//vn` or `v/vt/vn`.
    fn face_vertex(
        &mut self,
        line: &LogicalLine<'_>,
        offset: usize,
        word: &[u8],
    ) -> Result<[u32; 3], LineError> {
        let bad = || {
            (
                offset,
                format!(
                    "\"{}\" is not a face vertex: write v, v/vt, v//vn or v/vt/vn with whole numbers",
                    shown(word)
                ),
            )
        };
        let parts: Vec<&[u8]> = word.split(|&b| b == b'/').collect();
        if parts.len() > 3 || parts[0].is_empty() {
            return Err(bad());
        }
        let mut out = [NONE; 3];
        for (kind, part) in parts.iter().enumerate() {
            if part.is_empty() {
                continue;
            }
            let written: i64 = std::str::from_utf8(part)
                .ok()
                .and_then(|s| s.parse().ok())
                .ok_or_else(bad)?;
            let count = [self.positions.len(), self.uvs.len(), self.normals.len()][kind] as i64;
            let index = match written {
                0 => {
                    return Err((
                        offset,
                        format!(
                        "{} index 0 is out of range: OBJ indices count from 1 (or back from -1)",
                        KINDS[kind].0
                    ),
                    ))
                }
                i if i < 0 => count + i,
                i => i - 1,
            };
            if index < 0 || index >= i64::from(NONE) {
                return Err((offset, out_of_range(kind, written, count as usize)));
            }
            if index >= count {
                let (line, column) = line.at(offset);
                self.forward.push(Forward {
                    line,
                    column,
                    kind,
                    written,
                    index: index as u32,
                });
            }
            out[kind] = index as u32;
        }
        for (index, first) in out.iter().zip(&mut self.first_without).skip(1) {
            if *index == NONE && first.is_none() {
                *first = Some(line.at(offset));
            }
        }
        Ok(out)
    }

    /// The output vertex of a `[v, vt, vn]` triple in the current model.
    fn vertex(&mut self, triple: [u32; 3]) -> u32 {
        let next = self.vertices.len() as u32;
        *self.model.entry(triple).or_insert_with(|| {
            self.vertices.push(triple);
            next
        })
    }

    fn finish(self) -> Result<MeshData, MeshFileError> {
        let counts = [self.positions.len(), self.uvs.len(), self.normals.len()];
        if let Some(f) = self
            .forward
            .iter()
            .find(|f| f.index as usize >= counts[f.kind])
        {
            return Err(MeshFileError::at_line(
                f.line,
                f.column,
                out_of_range(f.kind, f.written, counts[f.kind]),
            ));
        }
        let positions = self
            .vertices
            .iter()
            .map(|v| self.positions[v[0] as usize])
            .collect();
        let attribute = |kind: usize| {
            (!self.vertices.is_empty() && self.vertices.iter().all(|v| v[kind] != NONE))
                .then_some(())
        };
        // Dropped because some face vertices name it and others do not.
        let partial = |kind: usize| {
            self.first_without[kind].filter(|_| self.vertices.iter().any(|v| v[kind] != NONE))
        };
        let partial = PartialAttributes {
            uvs: partial(1),
            normals: partial(2),
        };
        let uvs = attribute(1).map(|()| {
            self.vertices
                .iter()
                .map(|v| self.uvs[v[1] as usize])
                .collect()
        });
        let normals = attribute(2).map(|()| {
            self.vertices
                .iter()
                .map(|v| self.normals[v[2] as usize])
                .collect()
        });
        let materials =
            (!self.libraries.is_empty() || !self.used.is_empty()).then_some(FaceMaterials {
                libraries: self.libraries,
                used: self.used,
                of_triangle: self.triangle_material,
            });
        Ok(MeshData {
            positions,
            normals,
            uvs,
            uvs1: None,
            colours: None,
            tangents: None,
            triangles: self.triangles,
            materials,
            partial,
        })
    }
}

/// What each face index names: for messages, and the statement that writes it.
const KINDS: [(&str, &str); 3] = [
    ("position", "v"),
    ("texture coordinate", "vt"),
    ("normal", "vn"),
];

fn out_of_range(kind: usize, written: i64, count: usize) -> String {
    let (what, keyword) = KINDS[kind];
    let has = match count {
        0 => format!("the file has no \"{keyword}\" lines"),
        1 => format!("the file has 1 {what}"),
        n => format!("the file has {n} {what}s"),
    };
    format!("{what} index {written} is out of range: {has}")
}

/// The words of a line with their byte offsets, up to a word that starts a comment (`#`)
/// unless that is the first.
pub(super) fn words(line: &[u8]) -> Vec<(usize, &[u8])> {
    let mut out = Vec::new();
    let mut start = None;
    for (k, &b) in line.iter().chain(std::iter::once(&b' ')).enumerate() {
        match (b.is_ascii_whitespace(), start) {
            (false, None) => start = Some(k),
            (true, Some(s)) => {
                let word = &line[s..k];
                if word.starts_with(b"#") && !out.is_empty() {
                    break;
                }
                out.push((s, word));
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// The numbers of a statement's arguments: each must parse as a number, and there must be
/// a count in `range` (`need` says what is expected).
pub(super) fn numbers(
    args: &[(usize, &[u8])],
    at: usize,
    range: std::ops::RangeInclusive<usize>,
    need: &str,
) -> Result<Vec<f64>, LineError> {
    let mut out = Vec::with_capacity(args.len());
    for &(offset, word) in args {
        let x = std::str::from_utf8(word)
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| (offset, format!("\"{}\" is not a number", shown(word))))?;
        out.push(x);
    }
    if out.len() < *range.start() {
        return Err((at, format!("{need}, found {}", out.len())));
    }
    if out.len() > *range.end() {
        let (offset, _) = args[*range.end()];
        return Err((offset, format!("{need}, found {}", out.len())));
    }
    Ok(out)
}

/// Checks that the rest of `line` from byte `start` (a name) is UTF-8.
fn utf8_name(line: &[u8], start: usize, what: &str) -> Result<(), LineError> {
    let rest = &line[start.min(line.len())..];
    match std::str::from_utf8(rest) {
        Ok(_) => Ok(()),
        Err(e) => Err((
            start + e.valid_up_to(),
            format!("the {what} name is not UTF-8"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::mesh_files::Location;

    fn error(bytes: &[u8]) -> (usize, usize, String) {
        match parse(bytes) {
            Err(MeshFileError::Parse {
                at: Location::Text { line, column },
                message,
            }) => (line, column, message),
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    const TRI: &[u8] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n";

    #[test]
    fn a_backslash_continues_a_statement_and_errors_keep_their_place() {
        let m = parse(b"v 0 0 0\nv 1 0 \\\r\n 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\n  3 4\n").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.positions[1], DVec3::new(1.0, 0.0, 0.0));
        // The bad index 9 is on line 5, column 5, inside the face begun on line 4.
        assert_eq!(
            error(&[TRI, b"f 1 2 \\\n    9\nv 0 0 1\n"].concat()),
            (
                5,
                5,
                "position index 9 is out of range: the file has 4 positions".into()
            )
        );
        // A word after the joined line is located too.
        assert_eq!(
            error(&[TRI, b"f 1 \\\n 2 x\n"].concat()),
            (
                5,
                4,
                "\"x\" is not a face vertex: write v, v/vt, v//vn or v/vt/vn with whole numbers"
                    .into()
            )
        );
    }

    #[test]
    fn quads_share_vertices_and_fan() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4 5\n";
        let m = parse(obj).unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
        assert_eq!(m.positions.len(), 5);
        assert_eq!((m.normals, m.uvs), (None, None));
    }

    #[test]
    fn triples_are_vertices_per_model() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\n\
                    f 1/1/1 2/2/1 3/1/1\nf 3/2/1 2/2/1 1/1/1\no second\nf -3/1/1 2/2/1 3/1/1\n";
        let m = parse(obj).unwrap();
        // 1/1, 2/2, 3/1, 3/2 in the first model; the second model numbers its own.
        assert_eq!(m.triangles, vec![[0, 1, 2], [3, 1, 0], [4, 5, 6]]);
        assert_eq!(m.positions[3], DVec3::new(0.0, 1.0, 0.0));
        assert_eq!(m.uvs.as_ref().unwrap()[3], Vec2::new(1.0, 0.0));
        assert_eq!(m.normals.unwrap().len(), 7);
    }

    #[test]
    fn weights_divide_and_colours_are_ignored() {
        let m = parse(b"v 2 4 6 2\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(m.positions[0], DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(m.positions[1], DVec3::new(1.0, 0.0, 0.0));
    }

    #[test]
    fn normals_are_kept_only_when_every_vertex_has_one() {
        let obj = [TRI, b"vn 0 0 1\nf 1//1 2//1 3\n"].concat();
        assert_eq!(parse(&obj).unwrap().normals, None);
    }

    #[test]
    fn comments_and_names_may_hold_any_bytes_but_names_must_be_utf8() {
        let ok = [
            b"# caf\xe9 \xff\xfe\n",
            TRI,
            b"o caf\xc3\xa9\nf 1 2 3 # \xff\n",
        ]
        .concat();
        assert_eq!(parse(&ok).unwrap().triangles, vec![[0, 1, 2]]);
        let bad = [TRI, b"g caf\xe9\nf 1 2 3\n"].concat();
        assert_eq!(error(&bad), (4, 6, "the group name is not UTF-8".into()));
        let bad = [TRI, b"usemtl  m\xff\n"].concat();
        assert_eq!(
            error(&bad),
            (4, 10, "the material name is not UTF-8".into())
        );
    }

    #[test]
    fn a_file_that_is_not_obj_is_an_error_at_its_first_word() {
        assert_eq!(
            error(b"ply\nformat ascii 1.0\n"),
            (
                1,
                1,
                "\"ply\" is not an OBJ statement: this is a PLY file (load it with Ply(file: …))"
                    .into()
            )
        );
        assert_eq!(
            error(b"# a note\n  The quick brown fox\n"),
            (2, 3, "\"The\" is not an OBJ statement".into())
        );
        assert_eq!(
            error(b"\x89PNG\r\n\x1a\n"),
            (1, 1, "\"\\x89PNG\" is not an OBJ statement".into())
        );
    }

    #[test]
    fn bad_statements_are_located_at_the_word() {
        assert_eq!(
            error(b"v 0 0 0\nv 0 l 0\n"),
            (2, 5, "\"l\" is not a number".into())
        );
        assert_eq!(
            error(b"v 0 0\n"),
            (
                1,
                1,
                "a position needs 3 numbers (\"v x y z\"), found 2".into()
            )
        );
        assert_eq!(
            error(b"v 0 0 0 1 1\n"),
            (
                1,
                11,
                "a position has 3 numbers, 4 with a weight or 6 with a colour, found 5".into()
            )
        );
        assert_eq!(
            error(b"v 0 0 0 0\n"),
            (1, 9, "the weight w of a position must not be zero".into())
        );
        assert_eq!(
            error(b"vn 0 0 1 1\n"),
            (
                1,
                10,
                "a normal needs 3 numbers (\"vn x y z\"), found 4".into()
            )
        );
        assert_eq!(
            error(&[TRI, b"f 1 2\n"].concat()),
            (4, 1, "a face needs at least 3 vertices, found 2".into())
        );
        assert_eq!(
            error(&[TRI, b"f 1 2 3/x\n"].concat()),
            (
                4,
                7,
                "\"3/x\" is not a face vertex: write v, v/vt, v//vn or v/vt/vn with whole numbers"
                    .into()
            )
        );
    }

    /// A position that is NaN, infinite or beyond the f32 range is an error at its number,
    /// even when no face uses it.
    #[test]
    fn non_finite_positions_are_located_at_the_number() {
        let finite = "a vertex position must be a finite number";
        assert_eq!(
            error(b"v 0 0 0\nv 1 nan 0\n"),
            (2, 5, format!("position y = NaN: {finite}"))
        );
        assert_eq!(
            error(b"v 0 0 0\nv  -inf 0 0 0.5 0.5 0.5\n"),
            (2, 4, format!("position x = -inf: {finite}"))
        );
        assert_eq!(
            error(b"v 0 0 1e39\n"),
            (
                1,
                7,
                "position z = 1e39: a vertex position must lie within the f32 range (±3.4e38)"
                    .into()
            )
        );
        assert_eq!(
            error(b"v 0 1e300 0 1e-300\n"),
            (
                1,
                5,
                "position y = inf (divided by w): a vertex position must be a finite number".into()
            )
        );
    }

    #[test]
    fn face_indices_must_name_elements() {
        assert_eq!(
            error(&[TRI, b"f 1 2 3\nf 1 2 9\no next\n"].concat()),
            (
                5,
                7,
                "position index 9 is out of range: the file has 3 positions".into()
            )
        );
        assert_eq!(
            error(&[TRI, b"f 1 2 0\n"].concat()),
            (
                4,
                7,
                "position index 0 is out of range: OBJ indices count from 1 (or back from -1)"
                    .into()
            )
        );
        assert_eq!(
            error(&[TRI, b"f 1 2 -4\n"].concat()),
            (
                4,
                7,
                "position index -4 is out of range: the file has 3 positions".into()
            )
        );
        assert_eq!(
            error(&[TRI, b"vt 0 0\nf 1/1 2/2 3/1\n"].concat()),
            (
                5,
                7,
                "texture coordinate index 2 is out of range: the file has 1 texture coordinate"
                    .into()
            )
        );
        assert_eq!(
            error(&[TRI, b"f 1//1 2//1 3//1\n"].concat()),
            (
                4,
                3,
                "normal index 1 is out of range: the file has no \"vn\" lines".into()
            )
        );
    }

    #[test]
    fn indices_may_refer_forward() {
        let m = parse(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        assert_eq!(m.positions[2], DVec3::new(0.0, 1.0, 0.0));
    }

    #[test]
    fn libraries_and_each_triangles_material_are_kept() {
        let obj = [
            TRI,
            b"mtllib a.mtl  sub/b.mtl\nf 1 2 3\nusemtl red\nf 1 2 3 1\nusemtl blue\nf 1 2 3\nusemtl red\nf 3 2 1\n",
        ]
        .concat();
        let mut m = parse(&obj).unwrap();
        let faces = m.materials.clone().unwrap();
        let files: Vec<(&str, usize, usize)> = faces
            .libraries
            .iter()
            .map(|l| (l.file.as_str(), l.line, l.column))
            .collect();
        assert_eq!(files, vec![("a.mtl", 4, 8), ("sub/b.mtl", 4, 15)]);
        let used: Vec<(&str, usize)> = faces
            .used
            .iter()
            .map(|u| (u.name.as_str(), u.line))
            .collect();
        assert_eq!(used, vec![("red", 6), ("blue", 8)]);
        assert_eq!(faces.of_triangle, vec![NONE, 0, 0, 1, 0]);
        // Only red's three triangles, over the vertices they use.
        m.keep_material("red").unwrap();
        assert_eq!(m.triangles.len(), 3);
        assert_eq!(m.positions.len(), 3);
        assert!(m.triangles.iter().flatten().all(|&i| i < 3));
        assert_eq!(
            parse(&obj).unwrap().keep_material("green").unwrap_err(),
            "no face uses material \"green\": it uses \"red\", \"blue\""
        );
        let mut before = parse(&obj).unwrap();
        before.keep_material("").unwrap();
        assert_eq!(before.triangles, vec![[0, 1, 2]]);
        assert_eq!(parse(TRI).unwrap().materials, None);
    }

    #[test]
    fn an_empty_file_is_an_empty_mesh() {
        assert_eq!(parse(b"").unwrap(), MeshData::default());
        assert_eq!(
            parse(b"\xEF\xBB\xBF# only a comment\r\n").unwrap(),
            MeshData::default()
        );
    }
}
