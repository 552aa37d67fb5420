//! Building [`TriMesh`]es: inline polygons (checked, fan-triangulated) and Wavefront OBJ
//! files (via `tobj`, every model merged into one mesh).
//!
//! Positions are read in f64 and, when they lie far from the object origin, re-centred
//! before they are rounded to f32 ([`super::rebase::centre_positions`]); a triangle whose area is zero in f64 arithmetic on
//! those positions, or that touches a non-finite position, is dropped and counted. Shading
//! normals are normalised; a normal set with a non-finite or zero-length entry is dropped
//! whole, as is a non-finite UV set. Normals and UVs are kept only when every vertex has one.

use std::io::{self, BufRead, Read};
use std::path::Path;

use glam::{DVec3, Vec2, Vec3};

use super::desc::V3;
use super::validate::Checker;
use crate::components::TriMesh;

/// A mesh and what was dropped while building it.
#[derive(Debug, Clone)]
pub struct BuiltMesh {
    /// The mesh (every invariant of [`TriMesh`] holds).
    pub mesh: TriMesh,
    /// Triangles dropped as degenerate or non-finite.
    pub dropped: usize,
    /// Whether a normal set was dropped because of a bad entry.
    pub dropped_normals: bool,
    /// Object-space point subtracted from every position before rounding to f32 (zero when
    /// the mesh lies near its object origin); the instance transforms add it back in f64.
    pub offset: DVec3,
}

impl BuiltMesh {
    /// Undoes the re-centring (for meshes whose object space others depend on, such as
    /// scatter surfaces and prototypes): positions are moved back by `offset`, rounded again.
    pub fn uncentre(&mut self) {
        if self.offset == DVec3::ZERO {
            return;
        }
        for p in &mut self.mesh.positions {
            *p = (p.as_dvec3() + self.offset).as_vec3();
        }
        self.offset = DVec3::ZERO;
    }
}

/// Why an OBJ file did not load.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ObjError {
    /// The file could not be read (reason for a message).
    Read(String),
    /// The file did not parse; `line` where known.
    Parse {
        /// 1-based line of the offending statement.
        line: Option<usize>,
        /// What `tobj` said.
        message: String,
    },
}

/// Checks an inline mesh, reporting at `path` (`objects[i].mesh.Inline`). Returns whether it
/// can be built.
pub fn check_inline(
    ck: &mut Checker<'_>,
    path: &str,
    vertices: &[V3],
    polygons: &[Vec<u32>],
    normals: Option<&[V3]>,
    uvs: Option<&[(f64, f64)]>,
) -> bool {
    let mut ok = true;
    for (k, v) in vertices.iter().enumerate() {
        ok &= ck
            .v3(&format!("{path}.vertices[{k}]"), "vertex", *v)
            .is_some();
    }
    let n = vertices.len();
    for (p, poly) in polygons.iter().enumerate() {
        if poly.len() < 3 {
            ck.error(
                &format!("{path}.polygons[{p}]"),
                format!(
                    "a polygon needs at least 3 vertex indices, found {}",
                    poly.len()
                ),
            );
            ok = false;
        }
        for (q, &index) in poly.iter().enumerate() {
            if index as usize >= n {
                let range = if n == 0 {
                    "the mesh has no vertices".to_string()
                } else {
                    format!("the mesh has {n} vertices, 0 to {}", n - 1)
                };
                ck.error(
                    &format!("{path}.polygons[{p}][{q}]"),
                    format!("vertex index {index} is out of range: {range}"),
                );
                ok = false;
            }
        }
    }
    if let Some(normals) = normals {
        if normals.len() != n {
            ck.error(
                &format!("{path}.normals"),
                format!(
                    "normals has {} entries but vertices has {n}: give one normal per vertex",
                    normals.len()
                ),
            );
            ok = false;
        }
        for (k, v) in normals.iter().enumerate() {
            let npath = format!("{path}.normals[{k}]");
            match ck.v3(&npath, "normal", *v) {
                Some(d) if d.length_squared() == 0.0 => {
                    ck.error(&npath, "a normal must not be zero");
                    ok = false;
                }
                Some(_) => {}
                None => ok = false,
            }
        }
    }
    if let Some(uvs) = uvs {
        if uvs.len() != n {
            ck.error(
                &format!("{path}.uvs"),
                format!(
                    "uvs has {} entries but vertices has {n}: give one uv per vertex",
                    uvs.len()
                ),
            );
            ok = false;
        }
        for (k, uv) in uvs.iter().enumerate() {
            for (c, x) in [uv.0, uv.1].into_iter().enumerate() {
                ok &= ck.finite(&format!("{path}.uvs[{k}][{c}]"), "uv", x);
            }
        }
    }
    ok
}

/// Builds a checked inline mesh, fan-triangulating each polygon `[a, b, c, d, …]` into
/// `(a, b, c), (a, c, d), …`.
pub fn build_inline(
    vertices: &[V3],
    polygons: &[Vec<u32>],
    normals: Option<&[V3]>,
    uvs: Option<&[(f64, f64)]>,
) -> BuiltMesh {
    let v3 = |v: &V3| Vec3::new(v.0 as f32, v.1 as f32, v.2 as f32);
    let d3 = |v: &V3| DVec3::new(v.0, v.1, v.2);
    let mut triangles = Vec::new();
    for poly in polygons {
        for k in 1..poly.len().saturating_sub(1) {
            triangles.push([poly[0], poly[k], poly[k + 1]]);
        }
    }
    finish(
        vertices.iter().map(d3).collect(),
        normals.map(|n| n.iter().map(v3).collect()),
        uvs.map(|u| {
            u.iter()
                .map(|t| Vec2::new(t.0 as f32, t.1 as f32))
                .collect()
        }),
        triangles,
    )
}

/// Drops degenerate and non-finite triangles, normalises normals and removes unused
/// non-finite positions. Indices must be in range.
fn finish(
    positions: Vec<DVec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    triangles: Vec<[u32; 3]>,
) -> BuiltMesh {
    let (positions, offset) = super::rebase::centre_positions(&positions);
    let before = triangles.len();
    let triangles: Vec<[u32; 3]> = triangles
        .into_iter()
        .filter(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize].as_dvec3());
            a.is_finite() && b.is_finite() && c.is_finite() && (b - a).cross(c - a) != DVec3::ZERO
        })
        .collect();
    let dropped = before - triangles.len();
    let normals = normals.filter(|n| n.len() == positions.len());
    let uvs = uvs.filter(|u| u.len() == positions.len());
    let bad_normals = normals.as_ref().is_some_and(|n| {
        n.iter()
            .any(|v| !v.is_finite() || v.length_squared() == 0.0)
    });
    let normals = if bad_normals {
        None
    } else {
        normals.map(|n| n.iter().map(|v| v.normalize()).collect::<Vec<_>>())
    };
    let normals = normals.filter(|n| n.iter().all(|v| v.is_finite()));
    let uvs = uvs.filter(|u| u.iter().all(|t| t.is_finite()));
    let mut mesh = TriMesh {
        positions,
        normals,
        uvs,
        triangles,
    };
    if mesh.positions.iter().any(|p| !p.is_finite()) {
        compact(&mut mesh);
    }
    BuiltMesh {
        mesh,
        dropped,
        dropped_normals: bad_normals,
        offset,
    }
}

/// Keeps only the vertices some triangle uses.
fn compact(mesh: &mut TriMesh) {
    let mut remap = vec![u32::MAX; mesh.positions.len()];
    let mut kept = Vec::new();
    for t in &mut mesh.triangles {
        for i in t.iter_mut() {
            let old = *i as usize;
            if remap[old] == u32::MAX {
                remap[old] = kept.len() as u32;
                kept.push(old);
            }
            *i = remap[old];
        }
    }
    mesh.positions = kept.iter().map(|&i| mesh.positions[i]).collect();
    if let Some(n) = &mut mesh.normals {
        *n = kept.iter().map(|&i| n[i]).collect();
    }
    if let Some(u) = &mut mesh.uvs {
        *u = kept.iter().map(|&i| u[i]).collect();
    }
}

/// Loads an OBJ file, merging all its models (materials and `mtllib` are ignored).
pub fn load_obj(path: &Path) -> Result<BuiltMesh, ObjError> {
    let bytes = std::fs::read(path).map_err(|e| ObjError::Read(super::include::io_reason(&e)))?;
    parse_obj(&bytes)
}

/// Parses OBJ text (see [`load_obj`]).
pub fn parse_obj(bytes: &[u8]) -> Result<BuiltMesh, ObjError> {
    let options = obj_options();
    let mut reader = LineCounter {
        inner: bytes,
        newlines: 0,
        ends_line: true,
    };
    let result = std::panic::catch_unwind(move || {
        let r = tobj::load_obj_buf(&mut reader, &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        });
        (r, reader.newlines, reader.ends_line)
    });
    let (result, newlines, ends_line) = result.map_err(|_| ObjError::Parse {
        line: None,
        message: "the OBJ parser failed on this file".into(),
    })?;
    let models = match result {
        Ok((models, _)) => models,
        Err(err) => {
            let line = match err {
                tobj::LoadError::FaceVertexOutOfBounds
                | tobj::LoadError::FaceTexCoordOutOfBounds
                | tobj::LoadError::FaceNormalOutOfBounds => bad_face_line(bytes),
                tobj::LoadError::ReadError => None,
                _ => Some(if ends_line { newlines } else { newlines + 1 }.max(1)),
            };
            return Err(ObjError::Parse {
                line,
                message: err.to_string(),
            });
        }
    };
    let mut positions = Vec::new();
    let mut normals = Some(Vec::new());
    let mut uvs = Some(Vec::new());
    let mut triangles = Vec::new();
    for model in &models {
        let m = &model.mesh;
        let base = positions.len() as u32;
        let count = m.positions.len() / 3;
        positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2])),
        );
        if m.normals.len() == count * 3 {
            if let Some(n) = &mut normals {
                n.extend(
                    m.normals
                        .chunks_exact(3)
                        .map(|p| Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32)),
                );
            }
        } else {
            normals = None;
        }
        if m.texcoords.len() == count * 2 {
            if let Some(u) = &mut uvs {
                u.extend(
                    m.texcoords
                        .chunks_exact(2)
                        .map(|p| Vec2::new(p[0] as f32, p[1] as f32)),
                );
            }
        } else {
            uvs = None;
        }
        for t in m.indices.chunks_exact(3) {
            let t = [t[0], t[1], t[2]];
            if t.iter().all(|&i| (i as usize) < count) {
                triangles.push(t.map(|i| base + i));
            }
        }
    }
    if positions.is_empty() {
        normals = None;
        uvs = None;
    }
    Ok(finish(positions, normals, uvs, triangles))
}

#[allow(
    clippy::field_reassign_with_default,
    reason = "the struct gains fields with tobj features; a literal would not compile then"
)]
fn obj_options() -> tobj::LoadOptions {
    let mut options = tobj::LoadOptions::default();
    options.single_index = true;
    options.triangulate = true;
    options.ignore_points = true;
    options.ignore_lines = true;
    options
}

/// The first `f` statement with an out-of-range `v`, `vt` or `vn` index.
fn bad_face_line(bytes: &[u8]) -> Option<usize> {
    let text = String::from_utf8_lossy(bytes);
    let (mut v, mut vt, mut vn) = (0i64, 0i64, 0i64);
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => v += 1,
            Some("vt") => vt += 1,
            Some("vn") => vn += 1,
            Some("f") => {
                for word in words {
                    for (k, part) in word.split('/').enumerate() {
                        let count = [v, vt, vn].get(k).copied().unwrap_or(0);
                        let Ok(i) = part.parse::<i64>() else { continue };
                        let resolved = if i < 0 { count + i } else { i - 1 };
                        if resolved < 0 || resolved >= count {
                            return Some(number + 1);
                        }
                    }
                }
            }
            _ => {}
        }
    }
    None
}

/// Counts the lines a `BufRead` consumer has taken.
struct LineCounter<'a> {
    inner: &'a [u8],
    newlines: usize,
    ends_line: bool,
}

impl LineCounter<'_> {
    fn count(&mut self, taken: &[u8]) {
        self.newlines += taken.iter().filter(|&&b| b == b'\n').count();
        if let Some(&last) = taken.last() {
            self.ends_line = last == b'\n';
        }
    }
}

impl Read for LineCounter<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.len().min(buf.len());
        buf[..n].copy_from_slice(&self.inner[..n]);
        let (taken, rest) = self.inner.split_at(n);
        self.count(taken);
        self.inner = rest;
        Ok(n)
    }
}

impl BufRead for LineCounter<'_> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        Ok(self.inner)
    }

    fn consume(&mut self, amt: usize) {
        let amt = amt.min(self.inner.len());
        let (taken, rest) = self.inner.split_at(amt);
        self.count(taken);
        self.inner = rest;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fan_triangulates_and_drops_degenerates() {
        let v = [
            (0.0, 0.0, 0.0),
            (1.0, 0.0, 0.0),
            (1.0, 1.0, 0.0),
            (0.0, 1.0, 0.0),
            (2.0, 0.0, 0.0),
        ];
        let built = build_inline(&v, &[vec![0, 1, 2, 3], vec![0, 1, 4]], None, None);
        assert_eq!(built.mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(built.dropped, 1);
    }

    #[test]
    fn obj_errors_have_lines() {
        let bad = b"v 0 0 0\nv 1 0 0\nv x 1 0\nf 1 2 3\n";
        assert_eq!(
            parse_obj(bad).unwrap_err(),
            ObjError::Parse {
                line: Some(3),
                message: "position parse error".into()
            }
        );
        let oob = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\no next\n";
        assert_eq!(
            parse_obj(oob).unwrap_err(),
            ObjError::Parse {
                line: Some(5),
                message: "face vertex index out of bounds".into()
            }
        );
    }

    #[test]
    fn obj_nan_vertices_are_dropped_and_compacted() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nf 1 2 3\nf 1 2 4\n";
        let built = parse_obj(obj).unwrap();
        assert_eq!(built.dropped, 1);
        assert_eq!(built.mesh.positions.len(), 3);
        assert!(built.mesh.positions.iter().all(|p| p.is_finite()));
    }
}
