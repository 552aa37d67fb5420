//! RIB geometric primitives as stagelight meshes: the quadrics (`Sphere`, `Cylinder`,
//! `Cone`, `Disk`, `Torus`; `Paraboloid` and `Hyperboloid` as NURBS, see [`super::revolve`]),
//! polygons (`Polygon`, `GeneralPolygon`, `PointsPolygons`,
//! `PointsGeneralPolygons`), patches (`Patch`, `PatchMesh` with the current `Basis`),
//! `NuPatch` and `SubdivisionMesh "catmull-clark"`, with the `P`, `Pw`, `N`, `st`/`s`/`t`
//! primitive variables. Each mesh comes with the positions of its values by path (relative
//! to `mesh`).

use super::super::located::{Pos, Problem};
use super::params::{Args, Declarations, Param};
use super::parse::{Arg, Request};
use super::primvars::{mesh_variables, FaceLayout};
use super::state::Attributes;
use super::surface_vars::{surface_variables, Shape};
use crate::scene::desc::{BasisDesc, MeshDesc, SurfaceVariablesDesc, V3};

/// Requests that make geometry.
pub const PRIMITIVES: &[&str] = &[
    "Sphere",
    "Cylinder",
    "Cone",
    "Disk",
    "Torus",
    "Paraboloid",
    "Hyperboloid",
    "Polygon",
    "GeneralPolygon",
    "PointsPolygons",
    "PointsGeneralPolygons",
    "Patch",
    "PatchMesh",
    "NuPatch",
    "SubdivisionMesh",
];

/// A primitive read: its mesh, value paths, and a constant `Cs`/`Os` it carries.
#[derive(Debug, Clone)]
pub struct Primitive {
    /// The mesh.
    pub mesh: MeshDesc,
    /// `(path below mesh, position)`.
    pub paths: Vec<(String, Pos)>,
    /// A constant or uniform `Cs` given on the primitive.
    pub color: Option<V3>,
    /// A constant or uniform `Os` given on the primitive.
    pub opacity: Option<V3>,
}

/// Reads the primitive `req` (one of [`PRIMITIVES`]).
pub fn primitive(
    req: &Request,
    attrs: &Attributes,
    decls: &Declarations,
    problems: &mut Vec<Problem>,
) -> Option<Primitive> {
    let mut a = Args::new(req);
    let mut paths = Vec::new();
    let mut nums = |a: &mut Args<'_>, names: &[&'static str], variant: &str| {
        let mut out = Vec::new();
        for n in names {
            let (v, pos) = a.num(n).map_err(|e| problems.push(e)).ok()?;
            paths.push((format!(".{variant}.{n}"), pos));
            out.push(v);
        }
        Some(out)
    };
    let mesh = match req.name.as_str() {
        "Sphere" => {
            let v = nums(&mut a, &["radius", "zmin", "zmax", "thetamax"], "Sphere")?;
            MeshDesc::Sphere {
                radius: v[0],
                z_min: Some(v[1]),
                z_max: Some(v[2]),
                theta_max: v[3],
            }
        }
        "Cylinder" => {
            let v = nums(&mut a, &["radius", "zmin", "zmax", "thetamax"], "Cylinder")?;
            MeshDesc::Cylinder {
                radius: v[0],
                z_min: v[1],
                z_max: v[2],
                theta_max: v[3],
            }
        }
        "Cone" => {
            let v = nums(&mut a, &["height", "radius", "thetamax"], "Cone")?;
            MeshDesc::Cone {
                height: v[0],
                radius: v[1],
                theta_max: v[2],
            }
        }
        "Disk" => {
            let v = nums(&mut a, &["height", "radius", "thetamax"], "Disk")?;
            MeshDesc::Disk {
                height: v[0],
                radius: v[1],
                theta_max: v[2],
            }
        }
        "Torus" => {
            let v = nums(
                &mut a,
                &["rmajor", "rminor", "phimin", "phimax", "thetamax"],
                "Torus",
            )?;
            for (i, field) in ["r_major", "r_minor", "phi_min", "phi_max", "theta_max"]
                .iter()
                .enumerate()
            {
                let at = paths.len() - 5 + i;
                paths[at].0 = format!(".Torus.{field}");
            }
            MeshDesc::Torus {
                r_major: v[0],
                r_minor: v[1],
                phi_min: v[2],
                phi_max: v[3],
                theta_max: v[4],
            }
        }
        "Paraboloid" => {
            let v = nums(&mut a, &["rmax", "zmin", "zmax", "thetamax"], "Nurbs")?;
            paths.clear();
            super::revolve::paraboloid(v[0], v[1], v[2], v[3])
                .map_err(|m| problems.push(Problem::error(req.pos, m)))
                .ok()?
        }
        "Hyperboloid" => {
            let v = nums(
                &mut a,
                &["x1", "y1", "z1", "x2", "y2", "z2", "thetamax"],
                "Nurbs",
            )?;
            paths.clear();
            super::revolve::hyperboloid((v[0], v[1], v[2]), (v[3], v[4], v[5]), v[6])
                .map_err(|m| problems.push(Problem::error(req.pos, m)))
                .ok()?
        }
        _ => return polygonal(req, a, attrs, decls, problems),
    };
    rename_quadric_paths(&mut paths);
    let params = a.params(decls, problems);
    let (color, opacity) = constant_colours(req, &params, problems, &[]);
    Some(Primitive {
        mesh,
        paths,
        color,
        opacity,
    })
}

/// Our field names for the RenderMan spellings of the quadrics.
fn rename_quadric_paths(paths: &mut [(String, Pos)]) {
    for (p, _) in paths {
        for (rib, ours) in [
            (".zmin", ".z_min"),
            (".zmax", ".z_max"),
            (".thetamax", ".theta_max"),
        ] {
            if let Some(stem) = p.strip_suffix(rib) {
                *p = format!("{stem}{ours}");
            }
        }
    }
}

/// `Cs`/`Os` with one value for the whole primitive; warnings for every other parameter
/// not in `used`.
fn constant_colours(
    req: &Request,
    params: &[Param],
    problems: &mut Vec<Problem>,
    used: &[&str],
) -> (Option<V3>, Option<V3>) {
    let (mut color, mut opacity) = (None, None);
    for p in params {
        match p.name.as_str() {
            "Cs" | "Os" if p.nums().len() == 3 => {
                let v = p.triple();
                let at = [0, 1, 2].map(|k| p.value.item(k));
                let what = format!("parameter \"{}\" of {}", p.name, req.name);
                match super::shaders::check_colour(&what, p.name == "Os", [v.0, v.1, v.2], at) {
                    Err(e) => problems.push(e),
                    Ok(()) if p.name == "Cs" => color = Some(v),
                    Ok(()) => opacity = Some(v),
                }
            }
            n if used.contains(&n) => {}
            n => problems.push(Problem::warning(
                p.name_pos,
                format!(
                    "ignored primitive variable \"{n}\" of {}{}",
                    req.name,
                    if matches!(n, "Cs" | "Os") {
                        " (per-vertex colours are not supported)"
                    } else {
                        ""
                    }
                ),
            )),
        }
    }
    (color, opacity)
}

fn find<'p>(params: &'p [Param], name: &str) -> Option<&'p Param> {
    params.iter().find(|p| p.name == name)
}

/// Points of a primitive: positions, where each was written, and the weights of `Pw`.
type PointList = (Vec<V3>, Vec<Pos>, Option<Vec<f64>>);
/// A patch's basis, its vertex counts in u and v, its periodicity in u and v, and where it was written.
type PatchShape = (BasisDesc, usize, usize, bool, bool, Pos);
/// Polygon faces (vertex indices), where each index was written, and where the faces lie
/// among the face-corner and per-face values.
type FaceList = (Vec<Vec<u32>>, Vec<Vec<Pos>>, FaceLayout);

/// The triples of `P` (or of `Pw` divided by w, when `homogeneous_ok` is false it must
/// have w = 1), with the position of each point.
fn points(req: &Request, params: &[Param], problems: &mut Vec<Problem>) -> Option<PointList> {
    if let Some(p) = find(params, "P") {
        let v = p.nums();
        let pts = v.chunks_exact(3).map(|c| (c[0], c[1], c[2])).collect();
        let pos = (0..v.len() / 3).map(|i| p.value.item(3 * i)).collect();
        return Some((pts, pos, None));
    }
    if let Some(p) = find(params, "Pw") {
        let v = p.nums();
        let mut pts = Vec::new();
        let mut w = Vec::new();
        for (i, c) in v.chunks_exact(4).enumerate() {
            if c[3] <= 0.0 || !c[3].is_finite() {
                problems.push(Problem::error(
                    p.value.item(4 * i + 3),
                    format!(
                        "the weight of point {i} of \"Pw\" must be > 0, found {}",
                        c[3]
                    ),
                ));
                return None;
            }
            pts.push((c[0] / c[3], c[1] / c[3], c[2] / c[3]));
            w.push(c[3]);
        }
        let pos = (0..v.len() / 4).map(|i| p.value.item(4 * i)).collect();
        return Some((pts, pos, Some(w)));
    }
    problems.push(Problem::error(
        req.pos,
        format!("{} needs the positions \"P\"", req.name),
    ));
    None
}

fn counts(a: &mut Args<'_>, what: &str, problems: &mut Vec<Problem>) -> Option<(Vec<u32>, Arg)> {
    let arr = a.array(what).map_err(|e| problems.push(e)).ok()?;
    let mut out = Vec::new();
    for (i, &v) in arr.value.nums().unwrap_or(&[]).iter().enumerate() {
        if v.fract() != 0.0 || !(0.0..=u32::MAX as f64).contains(&v) {
            problems.push(Problem::error(
                arr.item(i),
                format!("{what} must hold non-negative integers, found {v}"),
            ));
            return None;
        }
        out.push(v as u32);
    }
    Some((out, arr))
}

fn wrap(a: &mut Args<'_>, what: &str, problems: &mut Vec<Problem>) -> Option<bool> {
    let (w, pos) = a.string(what).map_err(|e| problems.push(e)).ok()?;
    match w.as_str() {
        "periodic" => Some(true),
        "nonperiodic" => Some(false),
        other => {
            problems.push(
                Problem::error(pos, format!("unknown wrap mode \"{other}\""))
                    .with_help("expected \"periodic\" or \"nonperiodic\""),
            );
            None
        }
    }
}

fn polygonal(
    req: &Request,
    mut a: Args<'_>,
    attrs: &Attributes,
    decls: &Declarations,
    problems: &mut Vec<Problem>,
) -> Option<Primitive> {
    let mut paths = Vec::new();
    let name = req.name.as_str();
    // Face structure first (positional), then the parameter list.
    let mut faces: Option<FaceList> = None;
    let mut patch: Option<PatchShape> = None;
    let mut nurbs = None;
    let mut subdiv_tags = None;
    // Polygons with holes, cut into triangles once the points are read: the loops of each
    // (`PointsGeneralPolygons`), or the loop sizes of a `GeneralPolygon`.
    let mut general: Option<(Vec<Vec<Loop>>, Pos)> = None;
    let mut general_sizes: Option<(Vec<u32>, Pos)> = None;
    match name {
        "Polygon" => {}
        "GeneralPolygon" => {
            let (loops, arr) = counts(&mut a, "nvertices", problems)?;
            general_sizes = Some((loops, arr.pos));
        }
        "PointsPolygons" | "PointsGeneralPolygons" | "SubdivisionMesh" => {
            if name == "SubdivisionMesh" {
                let (scheme, pos) = a.string("scheme").map_err(|e| problems.push(e)).ok()?;
                if scheme != "catmull-clark" {
                    problems.push(
                        Problem::error(pos, format!("unknown subdivision scheme \"{scheme}\""))
                            .with_help("expected \"catmull-clark\""),
                    );
                    return None;
                }
            }
            let loops = if name == "PointsGeneralPolygons" {
                Some(counts(&mut a, "nloops", problems)?)
            } else {
                None
            };
            let (nverts, narr) = counts(&mut a, "nvertices", problems)?;
            let (verts, varr) = counts(&mut a, "vertices", problems)?;
            let mut fv = Vec::new();
            let mut fp = Vec::new();
            let mut at = 0usize;
            let total: usize = nverts.iter().map(|&n| n as usize).sum();
            if total != verts.len() {
                problems.push(Problem::error(
                    varr.pos,
                    format!(
                        "{name} lists {} vertex indices, but nvertices adds up to {total}",
                        verts.len()
                    ),
                ));
                return None;
            }
            // The polygon (uniform value) each loop belongs to.
            let mut polygon_of: Vec<usize> = (0..nverts.len()).collect();
            if let Some((l, larr)) = &loops {
                let sum: usize = l.iter().map(|&n| n as usize).sum();
                if sum != nverts.len() {
                    problems.push(Problem::error(
                        narr.pos,
                        format!(
                            "{name} has {} loops, but nloops adds up to {sum}",
                            nverts.len()
                        ),
                    ));
                    return None;
                }
                general = Some((vec![Vec::new(); l.len()], larr.pos));
                polygon_of.clear();
                for (polygon, &n) in l.iter().enumerate() {
                    polygon_of.extend(std::iter::repeat_n(polygon, n as usize));
                }
            }
            let mut layout = FaceLayout {
                corners: verts.len(),
                faces: loops.as_ref().map_or(nverts.len(), |(l, _)| l.len()),
                ..FaceLayout::default()
            };
            for (f, &n) in nverts.iter().enumerate() {
                let n = n as usize;
                let polygon = polygon_of.get(f).copied().unwrap_or(0);
                let face = Loop {
                    points: verts[at..at + n].to_vec(),
                    at: (at..at + n).map(|i| varr.item(i)).collect(),
                    first_corner: at,
                };
                if let Some((polygons, _)) = &mut general {
                    polygons[polygon].push(face);
                } else {
                    fv.push(face.points);
                    fp.push(face.at);
                    layout.corners_of.push((at..at + n).collect());
                    layout.uniform.push(polygon);
                }
                at += n;
            }
            faces = Some((fv, fp, layout));
            if name == "SubdivisionMesh" && !a.done() && !a.peek_is_string() {
                // Tags, their argument counts, integer and float arguments.
                let tags = a.any("tags").map_err(|e| problems.push(e)).ok()?;
                if tags.value.strs().is_some_and(|t| !t.is_empty()) {
                    subdiv_tags = Some(tags.pos);
                }
                for what in ["nargs", "intargs", "floatargs"] {
                    a.array(what).map_err(|e| problems.push(e)).ok()?;
                }
            }
        }
        "Patch" => {
            let (ty, pos) = a.string("type").map_err(|e| problems.push(e)).ok()?;
            let basis = patch_type(&ty, pos, attrs, problems)?;
            let n = if basis == BasisDesc::Bilinear { 2 } else { 4 };
            patch = Some((basis, n, n, false, false, pos));
        }
        "PatchMesh" => {
            let (ty, pos) = a.string("type").map_err(|e| problems.push(e)).ok()?;
            let basis = patch_type(&ty, pos, attrs, problems)?;
            let (nu, nu_pos) = a.count("nu", 1).map_err(|e| problems.push(e)).ok()?;
            let uw = wrap(&mut a, "uwrap", problems)?;
            let (nv, nv_pos) = a.count("nv", 1).map_err(|e| problems.push(e)).ok()?;
            let vw = wrap(&mut a, "vwrap", problems)?;
            paths.push((".PatchMesh.nu".to_string(), nu_pos));
            paths.push((".PatchMesh.nv".to_string(), nv_pos));
            patch = Some((basis, nu, nv, uw, vw, pos));
        }
        "NuPatch" => {
            let mut dir = |a: &mut Args<'_>, d: &str| -> Option<(usize, usize, Vec<f64>, Pos)> {
                let (n, _) = a
                    .count(&format!("n{d}"), 1)
                    .map_err(|e| problems.push(e))
                    .ok()?;
                let (order, opos) = a
                    .count(&format!("{d}order"), 2)
                    .map_err(|e| problems.push(e))
                    .ok()?;
                let knots = a
                    .array(&format!("{d}knot"))
                    .map_err(|e| problems.push(e))
                    .ok()?;
                let kpos = knots.pos;
                let knots = knots.value.nums().unwrap_or(&[]).to_vec();
                let (lo, lpos) = a
                    .num(&format!("{d}min"))
                    .map_err(|e| problems.push(e))
                    .ok()?;
                let (hi, _) = a
                    .num(&format!("{d}max"))
                    .map_err(|e| problems.push(e))
                    .ok()?;
                let full = knots.len() == n + order && lo <= knots[order - 1] && hi >= knots[n];
                if !full && knots.len() == n + order {
                    problems.push(Problem::warning(
                        lpos,
                        format!("ignored the {d} range [{lo}, {hi}] of NuPatch: the whole surface is used"),
                    ));
                }
                let _ = opos;
                Some((n, order, knots, kpos))
            };
            let u = dir(&mut a, "u")?;
            let v = dir(&mut a, "v")?;
            nurbs = Some((u, v));
        }
        _ => unreachable!("only primitives reach here"),
    }
    let params = a.params(decls, problems);
    let (pts, ppos, weights) = points(req, &params, problems)?;
    if matches!(name, "Polygon" | "GeneralPolygon") && pts.len() < 3 {
        let at = find(&params, "P").or(find(&params, "Pw"));
        problems.push(Problem::error(
            at.map_or(req.pos, Param::pos),
            format!("{name} needs at least 3 vertices, found {}", pts.len()),
        ));
        return None;
    }
    if let Some((sizes, at)) = general_sizes {
        let total: usize = sizes.iter().map(|&s| s as usize).sum();
        if total != pts.len() {
            problems.push(Problem::error(
                at,
                format!(
                    "GeneralPolygon has {} points, but nvertices adds up to {total}",
                    pts.len()
                ),
            ));
            return None;
        }
        let mut loops = Vec::new();
        let mut first = 0;
        for &s in &sizes {
            let s = s as usize;
            loops.push(Loop {
                points: (first as u32..(first + s) as u32).collect(),
                at: ppos[first..first + s].to_vec(),
                first_corner: first,
            });
            first += s;
        }
        general = Some((vec![loops], at));
        faces = Some((
            Vec::new(),
            Vec::new(),
            FaceLayout {
                corners: total,
                faces: 1,
                ..FaceLayout::default()
            },
        ));
    }
    if let (Some((polygons, at)), Some((fv, fp, layout))) = (&general, &mut faces) {
        cut_holes(name, polygons, *at, &pts, (fv, fp, layout), problems);
    }
    let used = ["P", "Pw", "N", "st", "s", "t"];
    let (color, opacity) = constant_colours(req, &params, problems, &used);
    let n = pts.len();
    if let Some(tag_pos) = subdiv_tags {
        problems.push(Problem::warning(
            tag_pos,
            "ignored the tags of SubdivisionMesh (creases, corners, holes)",
        ));
    }
    let mesh = if let Some((basis, nu, nv, u_wrap, v_wrap, _)) = patch {
        if n != nu * nv {
            problems.push(Problem::error(
                find(&params, "P")
                    .or(find(&params, "Pw"))
                    .map_or(req.pos, Param::pos),
                format!("{name} needs nu × nv = {} points, found {n}", nu * nv),
            ));
            return None;
        }
        if weights
            .as_ref()
            .is_some_and(|w| w.iter().any(|&w| w != 1.0))
        {
            problems.push(Problem::error(
                req.pos,
                format!("rational patches (\"Pw\" with weights other than 1) are not supported in {name}"),
            ));
            return None;
        }
        push_points(&mut paths, ".PatchMesh.points", &ppos);
        let shape = Shape::Grid {
            control: n,
            patches: (
                patches_along(basis, nu, u_wrap),
                patches_along(basis, nv, v_wrap),
            ),
            wrap: (u_wrap, v_wrap),
        };
        let variables = variables(name, &params, &shape, ".PatchMesh", &mut paths, problems)?;
        MeshDesc::PatchMesh {
            basis,
            nu: nu as u32,
            nv: nv as u32,
            u_wrap,
            v_wrap,
            points: pts,
            variables,
        }
    } else if let Some(((nu, uo, ku, kupos), (nv, vo, kv, kvpos))) = nurbs {
        if n != nu * nv {
            problems.push(Problem::error(
                req.pos,
                format!("NuPatch needs nu × nv = {} points, found {n}", nu * nv),
            ));
            return None;
        }
        let w = weights.unwrap_or_else(|| vec![1.0; n]);
        push_points(&mut paths, ".Nurbs.points", &ppos);
        let shape = Shape::Grid {
            control: n,
            patches: ((nu + 1).saturating_sub(uo), (nv + 1).saturating_sub(vo)),
            wrap: (false, false),
        };
        let variables = variables(name, &params, &shape, ".Nurbs", &mut paths, problems)?;
        paths.push((".Nurbs.knots_u".into(), kupos));
        paths.push((".Nurbs.knots_v".into(), kvpos));
        MeshDesc::Nurbs {
            degree_u: uo as u32 - 1,
            degree_v: vo as u32 - 1,
            count_u: nu as u32,
            count_v: nv as u32,
            knots_u: ku,
            knots_v: kv,
            points: pts
                .iter()
                .zip(&w)
                .map(|(p, &w)| (p.0, p.1, p.2, w))
                .collect(),
            variables,
        }
    } else {
        let (polygons, fpos, layout) = faces.unwrap_or_else(|| {
            (
                vec![(0..n as u32).collect()],
                vec![ppos.clone()],
                FaceLayout::single(n),
            )
        });
        for (f, face) in fpos.iter().enumerate() {
            for (k, pos) in face.iter().enumerate() {
                let variant = if name == "SubdivisionMesh" {
                    "Subdiv"
                } else {
                    "Inline"
                };
                paths.push((format!(".{variant}.polygons[{f}][{k}]"), *pos));
            }
        }
        if name == "SubdivisionMesh" {
            push_points(&mut paths, ".Subdiv.vertices", &ppos);
            let shape = Shape::Mesh {
                control: n,
                faces: &polygons,
            };
            let variables = variables(name, &params, &shape, ".Subdiv", &mut paths, problems)?;
            MeshDesc::Subdiv {
                vertices: pts,
                polygons,
                variables,
            }
        } else {
            let vars = mesh_variables(name, &params, pts, ppos, polygons, &layout, problems)?;
            push_points(&mut paths, ".Inline.vertices", &vars.vertex_pos);
            paths.extend(
                vars.paths
                    .into_iter()
                    .map(|(p, pos)| (format!(".Inline{p}"), pos)),
            );
            MeshDesc::Inline {
                vertices: vars.vertices,
                polygons: vars.polygons,
                normals: vars.normals,
                uvs: vars.uvs,
                materials: None,
            }
        }
    };
    Some(Primitive {
        mesh,
        paths,
        color,
        opacity,
    })
}

/// One loop of a polygon: its point indices, where each was written, and the index of its
/// first corner among all corners written.
#[derive(Debug, Clone)]
struct Loop {
    points: Vec<u32>,
    at: Vec<Pos>,
    first_corner: usize,
}

/// Makes the faces of `polygons` (each its outline then its holes, all their corners
/// counted in `layout`): a polygon without holes is one face, one with holes the
/// triangles of [`super::holes::triangulate`]. A polygon the triangulation cannot cut
/// (degenerate) keeps its outline only, with a warning at `at`; one too intricate to cut
/// within the step limit is an error at `at`.
fn cut_holes(
    name: &str,
    polygons: &[Vec<Loop>],
    at: Pos,
    points: &[V3],
    (faces, face_pos, layout): (&mut Vec<Vec<u32>>, &mut Vec<Vec<Pos>>, &mut FaceLayout),
    problems: &mut Vec<Problem>,
) {
    for (polygon, loops) in polygons.iter().enumerate() {
        let Some(outline) = loops.first() else {
            continue;
        };
        let mut push = |corners: &[(usize, usize)]| {
            faces.push(corners.iter().map(|&(l, k)| loops[l].points[k]).collect());
            face_pos.push(corners.iter().map(|&(l, k)| loops[l].at[k]).collect());
            layout.corners_of.push(
                corners
                    .iter()
                    .map(|&(l, k)| loops[l].first_corner + k)
                    .collect(),
            );
            layout.uniform.push(polygon);
        };
        let whole: Vec<(usize, usize)> = (0..outline.points.len()).map(|k| (0, k)).collect();
        let in_range = loops
            .iter()
            .all(|l| l.points.iter().all(|&i| (i as usize) < points.len()));
        if loops.len() == 1 || !in_range {
            push(&whole); // out-of-range indices are reported by validation
            continue;
        }
        // Corner k of the concatenated loops → (loop, position in it).
        let local: Vec<(usize, usize)> = loops
            .iter()
            .enumerate()
            .flat_map(|(l, lp)| (0..lp.points.len()).map(move |k| (l, k)))
            .collect();
        let point_loops: Vec<Vec<u32>> = loops.iter().map(|l| l.points.clone()).collect();
        match super::holes::triangulate(points, &point_loops) {
            Ok(triangles) => {
                for t in triangles {
                    push(&t.map(|c| local[c]));
                }
            }
            Err(super::holes::Uncut::TooIntricate) => {
                problems.push(
                    Problem::error(
                        at,
                        format!(
                            "polygon {polygon} of {name} is too intricate to cut around its \
                             holes: its {} corners take more than {} steps",
                            local.len(),
                            super::holes::MAX_STEPS
                        ),
                    )
                    .with_help(
                        "split it into several polygons, each with its own holes \
                         (docs/rib.md, Holes)",
                    ),
                );
                push(&whole);
            }
            Err(super::holes::Uncut::Degenerate) => {
                problems.push(Problem::warning(
                    at,
                    format!(
                        "ignored the holes of polygon {polygon} of {name}: its loops do not \
                         make a polygon that can be cut into triangles"
                    ),
                ));
                push(&whole);
            }
        }
    }
}

/// The `N`, `st`, `s`, `t` of a surface (see [`super::surface_vars`]), with their paths
/// below `variant` pushed onto `paths`. `None` after a located error.
fn variables(
    name: &str,
    params: &[Param],
    shape: &Shape<'_>,
    variant: &str,
    paths: &mut Vec<(String, Pos)>,
    problems: &mut Vec<Problem>,
) -> Option<SurfaceVariablesDesc> {
    let (vars, vpaths) = surface_variables(name, params, shape, problems)?;
    paths.extend(
        vpaths
            .into_iter()
            .map(|(p, pos)| (format!("{variant}{p}"), pos)),
    );
    Some(vars)
}

/// Patches along one direction of `n` points in `basis` (RenderMan's count; 0 when `n` is
/// too small, which validation reports).
fn patches_along(basis: BasisDesc, n: usize, wrap: bool) -> usize {
    match (basis, wrap) {
        (BasisDesc::Bilinear, true) | (BasisDesc::BSpline | BasisDesc::CatmullRom, true) => n,
        (BasisDesc::Bilinear, false) => n.saturating_sub(1),
        (BasisDesc::Bezier, true) => n / 3,
        (BasisDesc::Bezier, false) => n.saturating_sub(1) / 3,
        (_, false) => n.saturating_sub(3),
    }
}

fn push_points(paths: &mut Vec<(String, Pos)>, field: &str, pos: &[Pos]) {
    paths.push((field.to_string(), pos.first().copied().unwrap_or_default()));
    for (i, p) in pos.iter().enumerate() {
        paths.push((format!("{field}[{i}]"), *p));
    }
}

/// The basis of a `Patch`/`PatchMesh` of type `ty` under the current `Basis`.
fn patch_type(
    ty: &str,
    pos: Pos,
    attrs: &Attributes,
    problems: &mut Vec<Problem>,
) -> Option<BasisDesc> {
    match ty {
        "bilinear" => Some(BasisDesc::Bilinear),
        "bicubic" => {
            let (u, v) = attrs.basis;
            if u.basis != v.basis || u.step != v.step {
                problems.push(
                    Problem::error(
                        v.pos.or(u.pos).unwrap_or(pos),
                        "different u and v bases are not supported",
                    )
                    .with_help("use the same basis and step in both directions"),
                );
                return None;
            }
            Some(u.basis)
        }
        other => {
            problems.push(
                Problem::error(pos, format!("unknown patch type \"{other}\""))
                    .with_help("expected \"bilinear\" or \"bicubic\""),
            );
            None
        }
    }
}

/// `Basis` by name with its step, or `Err` with the message.
pub fn basis(name: &str, step: usize) -> Result<BasisDesc, String> {
    let (b, natural) = match name {
        "bezier" => (BasisDesc::Bezier, 3),
        "b-spline" => (BasisDesc::BSpline, 1),
        "catmull-rom" => (BasisDesc::CatmullRom, 1),
        "hermite" | "power" => {
            return Err(format!(
                "the \"{name}\" basis is not supported: expected \"bezier\", \"b-spline\" or \
                 \"catmull-rom\""
            ))
        }
        other => {
            return Err(format!(
                "unknown basis \"{other}\": expected \"bezier\", \"b-spline\" or \"catmull-rom\""
            ))
        }
    };
    if step != natural {
        return Err(format!(
            "the \"{name}\" basis takes step {natural}, found {step}"
        ));
    }
    Ok(b)
}
