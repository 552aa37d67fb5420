//! The `N` and `st` (or `s` and/or `t`) primitive variables of polygon meshes (`Polygon`,
//! `GeneralPolygon`, `PointsPolygons`, `PointsGeneralPolygons`): one value per vertex, per
//! face corner (`facevarying`) or, for `N`, per face (`uniform`) or one for all
//! (`constant`). stagelight meshes carry one normal and one uv per vertex, so a point whose
//! face corners disagree is split into one vertex per distinct value (points whose corners
//! agree stay shared). A value count that fits no class is a located error naming the
//! counts that would.

use std::collections::HashMap;

use super::super::located::{Pos, Problem};
use super::params::{Class, Param};
use crate::scene::desc::V3;

/// How a polygon mesh's faces lie in its face-corner and per-face value lists.
#[derive(Debug, Clone, Default)]
pub struct FaceLayout {
    /// For each face made, the index of each of its vertices among all corners written
    /// (the triangles of a polygon with holes name the corners of its loops).
    pub corners_of: Vec<Vec<usize>>,
    /// For each face made, the index of its value among the per-face (`uniform`) values.
    pub uniform: Vec<usize>,
    /// Number of face corners written (the length of the vertex index list).
    pub corners: usize,
    /// Number of faces written (`uniform` values).
    pub faces: usize,
}

impl FaceLayout {
    /// One face through every point (`Polygon`, `GeneralPolygon`).
    pub fn single(points: usize) -> Self {
        Self {
            corners_of: vec![(0..points).collect()],
            uniform: vec![0],
            corners: points,
            faces: 1,
        }
    }
}

/// A mesh with per-vertex normals and uvs.
#[derive(Debug, Clone)]
pub struct MeshVariables {
    /// The points, with a copy appended for each split corner value.
    pub vertices: Vec<V3>,
    /// Where each vertex was written (a copy: where its point was).
    pub vertex_pos: Vec<Pos>,
    /// The faces, indexing `vertices`.
    pub polygons: Vec<Vec<u32>>,
    /// One normal per vertex, when `N` is given.
    pub normals: Option<Vec<V3>>,
    /// One `(s, t)` per vertex, when `st` (or `s` and `t`) is given.
    pub uvs: Option<Vec<(f64, f64)>>,
    /// `(path below the mesh variant, position)` of the normals and uvs.
    pub paths: Vec<(String, Pos)>,
}

/// Which value a face corner takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Per {
    Vertex,
    Corner,
    Face,
    Whole,
}

/// One variable's values and how they are indexed.
struct Var<'a> {
    per: Per,
    data: &'a [f64],
    width: usize,
}

impl Var<'_> {
    /// The value at a face corner (`point`, `corner`, `face` indices), if there is one.
    fn at(&self, point: usize, corner: usize, face: usize) -> Option<&[f64]> {
        let i = match self.per {
            Per::Vertex => point,
            Per::Corner => corner,
            Per::Face => face,
            Per::Whole => 0,
        };
        self.data.get(i * self.width..(i + 1) * self.width)
    }
}

/// The class the count of `p` fits: its declared class first, then vertex, face corner and
/// (when `per_face` is allowed) face. `Err`: the located error naming the counts.
fn classify<'a>(
    p: &'a Param,
    width: usize,
    points: usize,
    layout: &FaceLayout,
    per_face: bool,
    primitive: &str,
) -> Result<Var<'a>, Problem> {
    let data = p.nums();
    let n = data.len();
    let fits = |count: usize| n == width * count;
    let declared = match p.decl.class {
        Class::Vertex | Class::Varying => Some(Per::Vertex),
        Class::FaceVarying => Some(Per::Corner),
        Class::Uniform if per_face => Some(Per::Face),
        Class::Constant if per_face => Some(Per::Whole),
        _ => None,
    };
    let count = |per: Per| match per {
        Per::Vertex => points,
        Per::Corner => layout.corners,
        Per::Face => layout.faces,
        Per::Whole => 1,
    };
    let mut order = vec![Per::Vertex, Per::Corner];
    if per_face {
        order.push(Per::Face);
    }
    let per = declared
        .filter(|&d| fits(count(d)))
        .or_else(|| order.iter().copied().find(|&c| fits(count(c))));
    match per {
        Some(per) => Ok(Var { per, data, width }),
        None => {
            let plural = |k: usize, one: &str, many: &str| {
                format!("{k} {}", if k == 1 { one } else { many })
            };
            let mut options = vec![(
                width * points,
                format!(
                    "{width} per vertex, {}",
                    plural(points, "vertex", "vertices")
                ),
            )];
            // One face through every point: its corners are its vertices.
            if layout.corners != points || layout.faces != 1 {
                options.push((
                    width * layout.corners,
                    format!(
                        "{width} per face corner, {}",
                        plural(layout.corners, "corner", "corners")
                    ),
                ));
            }
            if per_face {
                options.push((
                    width * layout.faces,
                    format!(
                        "{width} per face, {}",
                        plural(layout.faces, "face", "faces")
                    ),
                ));
            }
            let counts = match options.as_slice() {
                [(count, detail)] => format!("{count} numbers ({detail})"),
                [rest @ .., (count, detail)] => format!(
                    "{} or {count} ({detail}) numbers",
                    rest.iter()
                        .map(|(c, d)| format!("{c} ({d})"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                [] => String::new(),
            };
            Err(Problem::error(
                p.pos(),
                format!(
                    "parameter \"{}\" of {primitive} takes {counts}, found {n}",
                    p.name
                ),
            ))
        }
    }
}

/// Reads `N` and `st` (or `s` and `t`) of a polygon mesh with `points`/`point_pos` and
/// `polygons` laid out as `layout` says; splits points whose corners take different values.
/// `None` after a located error.
pub fn mesh_variables(
    primitive: &str,
    params: &[Param],
    points: Vec<V3>,
    point_pos: Vec<Pos>,
    polygons: Vec<Vec<u32>>,
    layout: &FaceLayout,
    problems: &mut Vec<Problem>,
) -> Option<MeshVariables> {
    let find = |name: &str| params.iter().find(|p| p.name == name);
    let n = points.len();
    fn read<'a>(
        p: &'a Param,
        (width, per_face): (usize, bool),
        (points, layout, primitive): (usize, &FaceLayout, &str),
        problems: &mut Vec<Problem>,
    ) -> Option<Var<'a>> {
        classify(p, width, points, layout, per_face, primitive)
            .map_err(|e| problems.push(e))
            .ok()
    }
    let mesh = (n, layout, primitive);
    let mut paths = Vec::new();
    let normal = match find("N") {
        Some(p) => {
            paths.push((".normals".to_string(), p.pos()));
            Some(read(p, (3, true), mesh, problems)?)
        }
        None => None,
    };
    // `st`, or `s` and `t` as two variables, each replacing its default alone: a polygon
    // has no parametric coordinates, so the one not given is 0 (as with neither given).
    const DEFAULT: Var<'static> = Var {
        per: Per::Whole,
        data: &[0.0],
        width: 1,
    };
    let mut uv: Vec<Var<'_>> = Vec::new();
    if let Some(p) = find("st") {
        paths.push((".uvs".to_string(), p.pos()));
        uv.push(read(p, (2, false), mesh, problems)?);
    } else if let Some(first) = find("s").or(find("t")) {
        paths.push((".uvs".to_string(), first.pos()));
        for name in ["s", "t"] {
            uv.push(match find(name) {
                Some(p) => read(p, (1, false), mesh, problems)?,
                None => DEFAULT,
            });
        }
    }
    let vars: Vec<&Var<'_>> = normal.iter().chain(&uv).collect();
    let width: usize = vars.iter().map(|v| v.width).sum();
    // The value of every variable at a face corner, one after the other.
    let value_at = |point: usize, corner: usize, face: usize| -> Vec<f64> {
        let mut out = Vec::with_capacity(width);
        for v in &vars {
            match v.at(point, corner, face) {
                Some(x) => out.extend_from_slice(x),
                None => out.extend(std::iter::repeat_n(0.0, v.width)),
            }
        }
        out
    };
    // A point no face uses keeps its per-vertex values (placeholders for the others).
    let mut values: Vec<Vec<f64>> = (0..n)
        .map(|p| {
            let mut out = Vec::with_capacity(width);
            for v in &vars {
                match v.at(p, 0, 0).filter(|_| v.per == Per::Vertex) {
                    Some(x) => out.extend_from_slice(x),
                    None if v.width == 3 => out.extend([0.0, 0.0, 1.0]),
                    None => out.extend(std::iter::repeat_n(0.0, v.width)),
                }
            }
            out
        })
        .collect();
    let mut vertices = points;
    let mut vertex_pos = point_pos;
    let mut polygons = polygons;
    if vars.iter().any(|v| v.per != Per::Vertex) {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        let mut assigned = vec![false; n];
        let mut copies: HashMap<(usize, Vec<u64>), u32> = HashMap::new();
        for (f, face) in polygons.iter_mut().enumerate() {
            let corners = layout.corners_of.get(f);
            let uniform = layout.uniform.get(f).copied().unwrap_or(0);
            for (k, index) in face.iter_mut().enumerate() {
                let p = *index as usize;
                if p >= n {
                    continue; // reported by validation, at the index
                }
                let corner = corners.and_then(|c| c.get(k)).copied().unwrap_or(k);
                let value = value_at(p, corner, uniform);
                if !assigned[p] {
                    assigned[p] = true;
                    values[p] = value;
                } else if bits(&values[p]) != bits(&value) {
                    *index = *copies.entry((p, bits(&value))).or_insert_with(|| {
                        vertices.push(vertices[p]);
                        vertex_pos.push(vertex_pos[p]);
                        values.push(value);
                        (vertices.len() - 1) as u32
                    });
                }
            }
        }
    }
    let column = |from: usize| values.iter().map(move |v| &v[from..]);
    let normals = normal
        .as_ref()
        .map(|_| column(0).map(|v| (v[0], v[1], v[2])).collect());
    let uv_from = if normal.is_some() { 3 } else { 0 };
    let uvs = (!uv.is_empty()).then(|| column(uv_from).map(|v| (v[0], v[1])).collect());
    Some(MeshVariables {
        vertices,
        vertex_pos,
        polygons,
        normals,
        uvs,
        paths,
    })
}
