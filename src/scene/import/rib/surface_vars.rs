//! The `N`, `st`, `s` and `t` primitive variables of patches (`Patch`, `PatchMesh`),
//! `NuPatch` and `SubdivisionMesh`, in every RenderMan class with its count for the
//! primitive: `vertex` (one per control point, interpolated like `P`), `varying` (one per
//! corner of the parametric grid; for a subdivision mesh one per point, linear over each
//! face), `facevarying` (four per patch, one per face corner), `uniform` (one per patch or
//! face) and `constant`. `s` and `t` are separate variables, each replacing its default
//! (the parametric coordinate) alone; `st` gives both. The declared class is used when the
//! count fits it, else the class whose count it fits; a count that fits none is a located
//! error naming the counts that would.

use super::super::located::{Pos, Problem};
use super::params::{Class, Param};
use crate::scene::desc::{SurfaceValuesDesc, SurfaceVariablesDesc, V3};

/// How a primitive's values are counted.
#[derive(Debug, Clone, Copy)]
pub enum Shape<'a> {
    /// A grid of patches: `control` points, `patches` `(u, v)` (a NURBS: every knot segment),
    /// wrapped (periodic) in u and v.
    Grid {
        /// Control points.
        control: usize,
        /// Patches along u and v.
        patches: (usize, usize),
        /// Periodic in u and v (the varying grid has no extra column or row there).
        wrap: (bool, bool),
    },
    /// A subdivision mesh: `control` points and its faces.
    Mesh {
        /// Control points.
        control: usize,
        /// The faces' point indices.
        faces: &'a [Vec<u32>],
    },
}

impl Shape<'_> {
    /// The number of values of `class`.
    fn count(&self, class: Class) -> usize {
        match (*self, class) {
            (_, Class::Constant) => 1,
            (Shape::Grid { control, .. }, Class::Vertex)
            | (Shape::Mesh { control, .. }, Class::Vertex | Class::Varying) => control,
            (Shape::Grid { patches, wrap, .. }, Class::Varying) => {
                (patches.0 + usize::from(!wrap.0)) * (patches.1 + usize::from(!wrap.1))
            }
            (Shape::Grid { patches, .. }, Class::Uniform) => patches.0 * patches.1,
            (Shape::Grid { patches, .. }, Class::FaceVarying) => 4 * patches.0 * patches.1,
            (Shape::Mesh { faces, .. }, Class::Uniform) => faces.len(),
            (Shape::Mesh { faces, .. }, Class::FaceVarying) => faces.iter().map(Vec::len).sum(),
        }
    }

    /// `values` (`width` numbers each, of `class`) as the description's values: one per
    /// control point for `vertex`, else at every patch or face corner.
    fn expand<T>(
        &self,
        class: Class,
        values: &[f64],
        width: usize,
        make: impl Fn(&[f64]) -> T,
    ) -> SurfaceValuesDesc<T> {
        let value = |i: usize| make(&values[i * width..(i + 1) * width]);
        let mut out = Vec::new();
        match (*self, class) {
            (_, Class::Vertex) => {
                return SurfaceValuesDesc::Control((0..values.len() / width).map(value).collect())
            }
            (Shape::Grid { patches, wrap, .. }, _) => {
                let cols = patches.0 + usize::from(!wrap.0);
                let rows = patches.1 + usize::from(!wrap.1);
                for j in 0..patches.1 {
                    for i in 0..patches.0 {
                        let patch = i + j * patches.0;
                        for (k, (du, dv)) in
                            [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate()
                        {
                            let at = match class {
                                Class::Constant => 0,
                                Class::Uniform => patch,
                                Class::FaceVarying => 4 * patch + k,
                                _ => (i + du) % cols + ((j + dv) % rows) * cols,
                            };
                            out.push(value(at));
                        }
                    }
                }
            }
            (Shape::Mesh { faces, .. }, _) => {
                let mut corner = 0;
                for (f, face) in faces.iter().enumerate() {
                    for &p in face {
                        let at = match class {
                            Class::Constant => 0,
                            Class::Uniform => f,
                            Class::FaceVarying => corner,
                            _ => p as usize,
                        };
                        out.push(value(at));
                        corner += 1;
                    }
                }
            }
        }
        SurfaceValuesDesc::Corners(out)
    }
}

/// The class `p` (`width` numbers per value) is read in on `shape`: its declared class when
/// its count fits, else the first that fits. `Err`: the located error naming the counts.
fn classify(p: &Param, width: usize, shape: &Shape<'_>, primitive: &str) -> Result<Class, Problem> {
    let n = p.nums().len();
    let order = [
        p.decl.class,
        Class::Vertex,
        Class::Varying,
        Class::FaceVarying,
        Class::Uniform,
        Class::Constant,
    ];
    if let Some(class) = order
        .into_iter()
        .find(|&c| shape.count(c) > 0 && n == width * shape.count(c))
    {
        return Ok(class);
    }
    let grid = matches!(shape, Shape::Grid { .. });
    let mut options: Vec<(usize, String)> = Vec::new();
    for (class, one, many) in [
        (Class::Vertex, "vertex", "vertices"),
        (Class::Varying, "parametric corner", "parametric corners"),
        if grid {
            (Class::FaceVarying, "patch corner", "patch corners")
        } else {
            (Class::FaceVarying, "face corner", "face corners")
        },
        if grid {
            (Class::Uniform, "patch", "patches")
        } else {
            (Class::Uniform, "face", "faces")
        },
    ] {
        let k = shape.count(class);
        if k == 0 || options.iter().any(|(c, _)| *c == width * k) {
            continue;
        }
        let things = if k == 1 { one } else { many };
        options.push((width * k, format!("{width} per {one}, {k} {things}")));
    }
    if !options.iter().any(|(c, _)| *c == width) {
        options.push((width, "constant".to_string()));
    }
    let list: Vec<String> = options.iter().map(|(c, w)| format!("{c} ({w})")).collect();
    let counts = match list.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    };
    Err(Problem::error(
        p.pos(),
        format!(
            "parameter \"{}\" of {primitive} takes {counts} numbers, found {n}",
            p.name
        ),
    ))
}

/// Reads `N`, `st`, `s` and `t` of the surface `primitive` counted as `shape`: the
/// description's variables and the `(path below its variant, position)` of each. `None`
/// after a located error.
pub fn surface_variables(
    primitive: &str,
    params: &[Param],
    shape: &Shape<'_>,
    problems: &mut Vec<Problem>,
) -> Option<(SurfaceVariablesDesc, Vec<(String, Pos)>)> {
    let find = |name: &str| params.iter().find(|p| p.name == name);
    let mut vars = SurfaceVariablesDesc::default();
    let mut paths = Vec::new();
    let mut failed = false;
    let mut read = |p: &Param, width: usize| -> Option<Class> {
        classify(p, width, shape, primitive)
            .map_err(|e| {
                problems.push(e);
                failed = true;
            })
            .ok()
    };
    let scalar = |v: &[f64]| v[0];
    if let Some(p) = find("N") {
        if let Some(class) = read(p, 3) {
            vars.normals = Some(shape.expand(class, p.nums(), 3, |v| -> V3 { (v[0], v[1], v[2]) }));
            paths.push((".variables.normals".to_string(), p.pos()));
        }
    }
    if let Some(p) = find("st") {
        if let Some(class) = read(p, 2) {
            vars.s = Some(shape.expand(class, p.nums(), 2, scalar));
            vars.t = Some(shape.expand(class, p.nums(), 2, |v| v[1]));
            paths.push((".variables.s".to_string(), p.pos()));
            paths.push((".variables.t".to_string(), p.pos()));
        }
    } else {
        for (name, slot) in [("s", &mut vars.s), ("t", &mut vars.t)] {
            if let Some(p) = find(name) {
                if let Some(class) = read(p, 1) {
                    *slot = Some(shape.expand(class, p.nums(), 1, scalar));
                    paths.push((format!(".variables.{name}"), p.pos()));
                }
            }
        }
    }
    (!failed).then_some((vars, paths))
}
