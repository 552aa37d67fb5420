//! Building [`TriMesh`]es: inline polygons (checked, fan-triangulated) and mesh files (read
//! by [`super::mesh_files`], their errors reported as scene diagnostics).
//!
//! Positions are read in f64 and, when they lie far from the object origin, re-centred
//! before they are rounded to f32 ([`super::rebase::centre_positions`]); a triangle whose area is zero in f64 arithmetic on
//! those positions, or that touches a non-finite position, is dropped and counted; no vertex
//! is removed or reordered (the readers refuse non-finite positions). Shading
//! normals are normalised; a normal set with a non-finite or zero-length entry is dropped
//! whole, as is a non-finite UV set. Normals and UVs are kept only when every vertex has one.

use glam::{DVec3, Vec2, Vec3, Vec4};

use super::desc::{ObjectDesc, V3};
use super::diagnostics::{Diagnostic, Sources};
use super::mesh_files::{self, Location, MeshData, MeshFileError, MeshFormat, PartialAttributes};
use super::validate::{Checker, Item};
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
    /// Attributes the file gives some face vertices and not others, dropped (OBJ).
    pub partial: PartialAttributes,
    /// The mesh's second UV set (glTF `TEXCOORD_1`), one per vertex of `mesh`, for bakes
    /// with `uvs: MeshSet(1)`.
    pub uvs1: Option<Vec<Vec2>>,
    /// The mesh's vertex colours (linear RGB), one per vertex of `mesh`.
    pub colours: Option<Vec<Vec3>>,
    /// The mesh's tangents (glTF `TANGENT`, object space, `w` the handedness), one per
    /// vertex of `mesh`.
    pub tangents: Option<Vec<Vec4>>,
    /// Object-space point subtracted from every position before rounding to f32 (zero when
    /// the mesh lies near its object origin); the instance transforms add it back in f64.
    pub offset: DVec3,
    /// For inline meshes, the polygon each kept triangle comes from; for an OBJ file with
    /// per-material faces, the index of each kept triangle's material (empty otherwise).
    pub polygon_of: Vec<u32>,
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
    let mut polygon_of = Vec::new();
    for (p, poly) in polygons.iter().enumerate() {
        for k in 1..poly.len().saturating_sub(1) {
            triangles.push([poly[0], poly[k], poly[k + 1]]);
            polygon_of.push(p as u32);
        }
    }
    finish_with_polygons(
        vertices.iter().map(d3).collect(),
        normals.map(|n| n.iter().map(v3).collect()),
        [
            uvs.map(|u| {
                u.iter()
                    .map(|t| Vec2::new(t.0 as f32, t.1 as f32))
                    .collect()
            }),
            None,
        ],
        None,
        None,
        triangles,
        polygon_of,
    )
}

/// Drops degenerate and non-finite triangles and normalises normals; every vertex keeps its
/// index. Indices must be in range.
fn finish(data: MeshData) -> BuiltMesh {
    let partial = data.partial;
    BuiltMesh {
        partial,
        ..finish_with_polygons(
            data.positions,
            data.normals,
            [data.uvs, data.uvs1],
            data.colours,
            data.tangents,
            data.triangles,
            Vec::new(),
        )
    }
}

/// [`finish`], keeping `polygon_of` (one entry per triangle, or empty) in step with the kept
/// triangles.
fn finish_with_polygons(
    positions: Vec<DVec3>,
    normals: Option<Vec<Vec3>>,
    [uvs, uvs1]: [Option<Vec<Vec2>>; 2],
    colours: Option<Vec<Vec3>>,
    tangents: Option<Vec<Vec4>>,
    triangles: Vec<[u32; 3]>,
    polygon_of: Vec<u32>,
) -> BuiltMesh {
    let (positions, offset) = super::rebase::centre_positions(&positions);
    let before = triangles.len();
    let keep: Vec<bool> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| positions[i as usize].as_dvec3());
            a.is_finite() && b.is_finite() && c.is_finite() && (b - a).cross(c - a) != DVec3::ZERO
        })
        .collect();
    let polygon_of: Vec<u32> = polygon_of
        .into_iter()
        .zip(&keep)
        .filter_map(|(p, &k)| k.then_some(p))
        .collect();
    let triangles: Vec<[u32; 3]> = triangles
        .into_iter()
        .zip(&keep)
        .filter_map(|(t, &k)| k.then_some(t))
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
    let uvs1 = uvs1.filter(|u| u.len() == positions.len() && u.iter().all(|t| t.is_finite()));
    let colours = colours.filter(|c| c.len() == positions.len() && c.iter().all(|v| v.is_finite()));
    let tangents =
        tangents.filter(|t| t.len() == positions.len() && t.iter().all(|v| v.is_finite()));
    // The readers refuse non-finite positions and those beyond the f32 range; should the
    // rounding after re-centring still make one infinite, its triangles were dropped above
    // and it moves to the origin, so every vertex keeps its index (per-vertex bakes and
    // the baked glTF copy map values back by index).
    let positions = positions
        .into_iter()
        .map(|p| if p.is_finite() { p } else { Vec3::ZERO })
        .collect();
    let mesh = TriMesh {
        positions,
        normals,
        uvs,
        triangles,
    };
    BuiltMesh {
        mesh,
        dropped,
        dropped_normals: bad_normals,
        partial: PartialAttributes::default(),
        uvs1,
        colours,
        tangents,
        offset,
        polygon_of,
    }
}

/// Builds the mesh a mesh file describes (see [`finish`] for what is dropped).
pub fn from_data(data: MeshData) -> BuiltMesh {
    finish(data)
}

/// [`from_data`], but an OBJ with per-material faces (`Obj { materials: Some(…) }`, set
/// by [`super::obj_materials`]) gets its triangles grouped by material, each triangle's
/// material index in `polygon_of` (see [`MeshData::group_by_material`]).
fn from_data_grouped(mut data: MeshData, mesh: &super::desc::MeshDesc) -> BuiltMesh {
    let super::desc::MeshDesc::Obj {
        materials: Some(slots),
        ..
    } = mesh
    else {
        return from_data(data);
    };
    let order: Vec<String> = slots.iter().map(|(usemtl, _)| usemtl.clone()).collect();
    let polygon_of = data.group_by_material(&order);
    BuiltMesh {
        partial: data.partial,
        ..finish_with_polygons(
            data.positions,
            data.normals,
            [data.uvs, data.uvs1],
            data.colours,
            data.tangents,
            data.triangles,
            polygon_of,
        )
    }
}

/// The faces of one `usemtl` material when an `Obj(…, usemtl: …)` mesh asks for them.
fn obj_faces(mut data: MeshData, mesh: &super::desc::MeshDesc) -> Result<MeshData, MeshFileError> {
    if let super::desc::MeshDesc::Obj {
        usemtl: Some(name), ..
    } = mesh
    {
        data.keep_material(name)
            .map_err(|message| MeshFileError::Element {
                path: "usemtl".to_string(),
                message,
            })?;
    }
    Ok(data)
}

/// Loads the mesh file that object `it` names, or only checks that it exists when the
/// object is not `reachable`. Errors are recorded in `src`: an unreadable file at the file
/// name in the scene; a parse error at its place in the mesh file (line and column), or, for
/// a binary position, at the file name with the byte offset in the message; the help names
/// the object and the scene position that loads the file.
pub fn load_file(
    src: &mut Sources,
    it: &Item<'_, ObjectDesc>,
    format: MeshFormat,
    file: &str,
    reachable: bool,
) -> Option<BuiltMesh> {
    let path = src.files[it.file].dir().join(file);
    let at = it.at(&format!(".mesh.{}.file", format.variant()));
    let result = if reachable {
        mesh_files::read(format, &path, &mesh_files::gltf_pick(&it.desc.mesh))
            .and_then(|data| obj_faces(data, &it.desc.mesh))
            .map(|data| Some(from_data_grouped(data, &it.desc.mesh)))
    } else {
        std::fs::metadata(&path)
            .map(|_| None)
            .map_err(|e| MeshFileError::Read {
                reason: super::include::io_reason(&e),
            })
    };
    let kind = format.name();
    match result {
        Ok(b) => b,
        Err(MeshFileError::Read { reason }) => {
            let help = super::missing_file::help_if_missing(file, &path, &src.files[it.file].path);
            src.error(
                it.file,
                &at,
                format!("cannot read {kind} file \"{}\": {reason}", path.display()),
                help,
            );
            None
        }
        Err(MeshFileError::Element {
            path: element,
            message,
        }) => {
            let referrer = src.where_is(it.file, &at);
            src.error(
                it.file,
                &at,
                format!(
                    "invalid {kind} file \"{}\": {element}: {message}",
                    path.display()
                ),
                Some(format!(
                    "loaded for object \"{}\" at {referrer}",
                    it.desc.name
                )),
            );
            None
        }
        Err(MeshFileError::Parse {
            at: location,
            message,
        }) => {
            let pos = src.pos(it.file, &at);
            let referrer = src.where_is(it.file, &at);
            let (file, line, column, message) = match location {
                Location::Text { line, column } => (path.clone(), line, column, message),
                Location::Byte(offset) => (
                    src.files[it.file].path.clone(),
                    pos.line,
                    pos.column,
                    format!("at byte {offset}: {message}"),
                ),
            };
            src.push(
                it.file,
                pos,
                Diagnostic {
                    file,
                    line,
                    column,
                    message: format!("invalid {kind} file \"{}\": {message}", path.display()),
                    help: Some(format!(
                        "loaded for object \"{}\" at {referrer}",
                        it.desc.name
                    )),
                },
            );
            None
        }
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

    /// Vertices keep their index whatever is dropped: unused vertices, vertices of dropped
    /// degenerate triangles and (should one reach here) non-finite positions, which move to
    /// the origin.
    #[test]
    fn every_vertex_keeps_its_index() {
        let data = MeshData {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(f64::NAN, 0.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::new(5.0, 5.0, 5.0),
                DVec3::new(2.0, 0.0, 0.0),
            ],
            colours: Some(vec![Vec3::ONE; 6]),
            triangles: vec![[0, 2, 1], [0, 1, 3], [5, 5, 0]],
            ..MeshData::default()
        };
        let built = from_data(data);
        assert_eq!(built.dropped, 2);
        assert_eq!(built.mesh.triangles, vec![[0, 1, 3]]);
        assert_eq!(
            built.mesh.positions,
            [
                Vec3::ZERO,
                Vec3::X,
                Vec3::ZERO,
                Vec3::Y,
                Vec3::splat(5.0),
                Vec3::new(2.0, 0.0, 0.0)
            ]
        );
        assert_eq!(built.colours.map(|c| c.len()), Some(6));
    }
}
