//! Free-form surfaces of `.mi` objects, mapped onto NURBS surfaces (`docs/mi.md`,
//! *Free-form surfaces*):
//!
//! - `basis "name" [rational] bezier|bspline degree` in the object: a Bézier basis becomes
//!   a knot vector with the parameters as breakpoints (end knots `degree + 1` times, inner
//!   ones `degree` times), a B-spline basis takes its parameters as the knot vector
//!   (`count + degree + 1` values). `taylor`, `cardinal` and basis-`matrix` bases are
//!   located errors where a surface uses them.
//! - `surface "name" ["material"] "u_basis" umin umax u_params… "v_basis" vmin vmax
//!   v_params… control_points…` in the group: control points are `v` vertex indices of the
//!   group, u fastest, each with `w weight` when a basis is rational. The v parameters and
//!   the control points are told apart by their counts. Only whole surfaces are read: a
//!   range narrower than the parameters is an error.
//! - `approximate surface technique "name"…`: `parametric u v` (`u·degree` segments per
//!   patch), `regular parametric u v`, `spatial`/`length` (with `view`: pixels),
//!   `curvature d a`, `distance d`/`angle a`, then optional `min max` subdivision levels.
//!   Other techniques warn.

use std::collections::HashMap;

use super::super::located::{Pos, Problem};
use super::cursor::Cursor;
use super::lexer::Tok;
use super::model::{RawAxis, RawObject, RawSurface};
use crate::scene::desc::{ApproximationDesc, SpaceDesc};
use crate::scene::suggest::closest;

/// Largest degree the NURBS tessellation supports (mental ray goes to 21).
const MAX_DEGREE: u32 = 7;

/// The basis types of a `basis` declaration.
const BASIS_TYPES: &[&str] = &["bezier", "bspline", "taylor", "cardinal", "matrix"];

/// What a `basis` declaration is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BasisKind {
    /// `bezier degree`: piecewise Bézier, parameters at the patch boundaries.
    Bezier,
    /// `bspline degree`: the parameters are the knot vector.
    BSpline,
    /// `taylor`, `cardinal` or `matrix`: read, not mapped.
    Other(&'static str),
}

/// A `basis` declaration of an object.
#[derive(Debug, Clone, Copy)]
pub struct Basis {
    /// The type.
    pub kind: BasisKind,
    /// `rational`: control points carry weights.
    pub rational: bool,
    /// The degree (3 for `cardinal`).
    pub degree: u32,
}

/// The `basis` declarations of an object by name; `None`: declared with an error (already
/// reported, so surfaces using it stay quiet).
pub type Bases = HashMap<String, Option<Basis>>;

/// `basis "name" [rational] type …` (after the word `basis`). Returns false on an error.
pub fn basis(c: &mut Cursor, bases: &mut Bases) -> bool {
    let Some((name, _)) = c.string("the name of the basis") else {
        c.skip_arguments();
        return false;
    };
    bases.insert(name.clone(), None);
    let rational = c.eat_word("rational");
    let (pos, word) = match c.peek() {
        Some(t) => (t.pos, t.tok.clone()),
        None => (c.pos(), Tok::Punct(' ')),
    };
    let Tok::Word(w) = word else {
        let found = c
            .peek()
            .map_or("the end of the file".into(), |t| t.tok.describe());
        c.report(
            Problem::error(
                pos,
                format!("expected a basis type for basis \"{name}\", found {found}"),
            )
            .with_help("write bezier, bspline, taylor, cardinal or matrix"),
        );
        return false;
    };
    c.advance();
    let kind = match w.as_str() {
        "bezier" => BasisKind::Bezier,
        "bspline" => BasisKind::BSpline,
        "taylor" => BasisKind::Other("taylor"),
        "cardinal" => BasisKind::Other("cardinal"),
        "matrix" => BasisKind::Other("matrix"),
        other => {
            let mut p = Problem::error(pos, format!("unknown basis type \"{other}\""));
            p = match closest(other, BASIS_TYPES.iter().copied()) {
                Some(s) => p.with_help(format!("did you mean \"{s}\"?")),
                None => p.with_help("write bezier, bspline, taylor, cardinal or matrix"),
            };
            c.report(p);
            c.skip_arguments();
            return false;
        }
    };
    let degree = if w == "cardinal" {
        3
    } else {
        let at = c.pos();
        let Some(d) = c.count("the degree of the basis") else {
            c.skip_arguments();
            return false;
        };
        if kind != BasisKind::Other("matrix") && d == 0 {
            c.error(at, "the degree of a basis must be at least 1, found 0");
            return false;
        }
        d
    };
    // A basis matrix: the step size and the matrix.
    c.skip_arguments();
    bases.insert(
        name,
        Some(Basis {
            kind,
            rational,
            degree,
        }),
    );
    true
}

/// One value after a basis name: a number, maybe with `w weight`.
struct Item {
    value: f64,
    pos: Pos,
    weight: Option<(f64, Pos)>,
}

/// Reads numbers (each maybe followed by `w weight`) up to the next word, string or
/// punctuation.
fn items(c: &mut Cursor) -> Option<Vec<Item>> {
    let mut out = Vec::new();
    while c.at_number() {
        let pos = c.pos();
        let value = c.number("a value")?;
        let mut weight = None;
        if c.at_word("w") {
            let wpos = c.pos();
            c.advance();
            weight = Some((c.number("the weight of a control point")?, wpos));
        }
        out.push(Item { value, pos, weight });
    }
    Some(out)
}

/// A basis reference of a surface, resolved and checked.
fn resolve(c: &mut Cursor, bases: &Bases, name: &str, pos: Pos) -> Option<Basis> {
    let Some(&declared) = bases.get(name) else {
        let mut p = Problem::error(pos, format!("unknown basis \"{name}\""));
        p = match closest(name, bases.keys().map(String::as_str)) {
            Some(s) => p.with_help(format!("did you mean \"{s}\"?")),
            None => {
                p.with_help("declare it in the object before the group: basis \"name\" bezier 3")
            }
        };
        c.report(p);
        return None;
    };
    let b = declared?;
    if let BasisKind::Other(kind) = b.kind {
        c.report(
            Problem::error(
                pos,
                format!("basis \"{name}\" is a {kind} basis, which is not supported"),
            )
            .with_help("write the surface with a bezier or bspline basis"),
        );
        return None;
    }
    if b.degree > MAX_DEGREE {
        c.report(
            Problem::error(
                pos,
                format!(
                    "basis \"{name}\" has degree {}; surfaces up to degree {MAX_DEGREE} are supported",
                    b.degree
                ),
            )
            .with_help("raise the surface to degree 7 or less in the modeller, or write polygons"),
        );
        return None;
    }
    Some(b)
}

/// Control points along one direction made by `n` parameters of basis `b`, if any.
fn count_of(b: &Basis, n: usize) -> Option<usize> {
    let d = b.degree as usize;
    match b.kind {
        BasisKind::Bezier if n >= 2 => Some((n - 1) * d + 1),
        BasisKind::BSpline if n >= 2 * d + 2 => Some(n - d - 1),
        _ => None,
    }
}

/// The direction `dir` from basis `b`, its range and parameters.
fn axis(
    c: &mut Cursor,
    b: &Basis,
    basis_name: &str,
    range: (&Item, &Item),
    params: &[Item],
    dir: &str,
    surface: &str,
) -> Option<RawAxis> {
    let d = b.degree;
    let at = params.first().map_or(range.1.pos, |p| p.pos);
    let values: Vec<f64> = params.iter().map(|p| p.value).collect();
    let Some(count) = count_of(b, values.len()) else {
        let need = match b.kind {
            BasisKind::Bezier => "at least 2 parameters (the patch boundaries)".to_string(),
            _ => format!(
                "at least {} parameters (a knot vector of count + degree + 1 values)",
                2 * d + 2
            ),
        };
        c.error(
            at,
            format!(
                "surface \"{surface}\": the {dir} basis \"{basis_name}\" (degree {d}) needs {need}, found {}",
                values.len()
            ),
        );
        return None;
    };
    if let Some(bad) = params.iter().find(|p| p.weight.is_some()) {
        c.error(
            bad.weight.map_or(bad.pos, |w| w.1),
            format!("surface \"{surface}\": a weight belongs to a control point, not to a {dir} parameter"),
        );
        return None;
    }
    let strict = b.kind == BasisKind::Bezier;
    if let Some(i) = values
        .windows(2)
        .position(|w| if strict { w[1] <= w[0] } else { w[1] < w[0] })
    {
        let order = if strict { "increase" } else { "not decrease" };
        c.error(
            params[i + 1].pos,
            format!(
                "surface \"{surface}\": the {dir} parameters must {order}: {} follows {}",
                values[i + 1],
                values[i]
            ),
        );
        return None;
    }
    let du = d as usize;
    let (knots, lo, hi) = match b.kind {
        BasisKind::Bezier => {
            let mut k = Vec::with_capacity(count + du + 1);
            for (i, &t) in values.iter().enumerate() {
                let times = if i == 0 || i + 1 == values.len() {
                    du + 1
                } else {
                    du
                };
                k.extend(std::iter::repeat_n(t, times));
            }
            (k, values[0], values[values.len() - 1])
        }
        _ => (values.clone(), values[du], values[count]),
    };
    if hi <= lo {
        c.error(
            at,
            format!("surface \"{surface}\": the {dir} parameters span nothing ([{lo}, {hi}])"),
        );
        return None;
    }
    let (r0, r1) = (range.0.value, range.1.value);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()));
    if !close(r0, lo) || !close(r1, hi) {
        c.report(
            Problem::error(
                range.0.pos,
                format!(
                    "surface \"{surface}\": the {dir} range [{r0}, {r1}] is not the whole surface [{lo}, {hi}]; parts of surfaces are not supported"
                ),
            )
            .with_help(format!("write the range as {lo} {hi}")),
        );
        return None;
    }
    Some(RawAxis {
        degree: d,
        count: count as u32,
        knots,
    })
}

/// `surface "name" ["material"] …` in a group whose first vertex is `base` and which has
/// `vertex_count` vertices so far. Pushes the surface onto `obj`; on an error (reported)
/// the surface's name goes to `failed` instead and false is returned.
pub fn surface(
    c: &mut Cursor,
    obj: &mut RawObject,
    bases: &Bases,
    (base, vertex_count): (u32, u32),
    failed: &mut Vec<String>,
    at: Pos,
) -> bool {
    let Some((name, _)) = c.string("the name of the surface") else {
        return false;
    };
    let ok = read_surface(c, obj, bases, (base, vertex_count), name.clone(), at);
    if !ok {
        failed.push(name);
    }
    ok
}

fn read_surface(
    c: &mut Cursor,
    obj: &mut RawObject,
    bases: &Bases,
    (base, vertex_count): (u32, u32),
    name: String,
    at: Pos,
) -> bool {
    // `"material" "u_basis"` or just `"u_basis"`.
    let two_strings = matches!(
        c.peek2(),
        Some(super::lexer::Token {
            tok: Tok::Str(_),
            ..
        })
    );
    let (material, material_at) = if c.at_string() && two_strings {
        let Some((m, p)) = c.string("the material of the surface") else {
            return false;
        };
        (Some(m), Some(c.located(p)))
    } else {
        (None, None)
    };
    let Some((u_name, u_pos)) = c.string("the u basis of the surface") else {
        return false;
    };
    let Some(u_items) = items(c) else {
        return false;
    };
    let Some((v_name, v_pos)) = c.string("the v basis of the surface") else {
        return false;
    };
    let Some(rest) = items(c) else {
        return false;
    };
    let Some(ub) = resolve(c, bases, &u_name, u_pos) else {
        if v_name != u_name {
            let _ = resolve(c, bases, &v_name, v_pos);
        }
        return false;
    };
    let Some(vb) = resolve(c, bases, &v_name, v_pos) else {
        return false;
    };
    if u_items.len() < 2 {
        c.error(
            u_pos,
            format!("surface \"{name}\": expected the u range (min max) after the u basis"),
        );
        return false;
    }
    if rest.len() < 2 {
        c.error(
            v_pos,
            format!("surface \"{name}\": expected the v range (min max) after the v basis"),
        );
        return false;
    }
    let Some(u) = axis(
        c,
        &ub,
        &u_name,
        (&u_items[0], &u_items[1]),
        &u_items[2..],
        "u",
        &name,
    ) else {
        return false;
    };
    // Split what follows the v range into the v parameters and the control points.
    let tail = &rest[2..];
    let cu = u.count as usize;
    let split =
        (2..=tail.len()).find(|&k| count_of(&vb, k).is_some_and(|cv| k + cu * cv == tail.len()));
    let Some(k) = split else {
        let per = match vb.kind {
            BasisKind::Bezier => format!("(k − 1)·{} + 1", vb.degree),
            _ => format!("k − {}", vb.degree + 1),
        };
        c.report(
            Problem::error(
                v_pos,
                format!(
                    "surface \"{name}\": the {} values after the v range are not v parameters followed by control points",
                    tail.len()
                ),
            )
            .with_help(format!(
                "k v parameters of basis \"{v_name}\" take {cu} × ({per}) control points ({cu} along u from the u parameters)"
            )),
        );
        return false;
    };
    let Some(v) = axis(
        c,
        &vb,
        &v_name,
        (&rest[0], &rest[1]),
        &tail[..k],
        "v",
        &name,
    ) else {
        return false;
    };
    let rational = ub.rational || vb.rational;
    let mut points = Vec::with_capacity(tail.len() - k);
    let mut ok = true;
    for item in &tail[k..] {
        let i = item.value;
        if i < 0.0 || i.fract() != 0.0 || i >= f64::from(vertex_count) {
            c.error(
                item.pos,
                format!(
                    "vertex index {i} is out of range (the group has {vertex_count} vertices so far)"
                ),
            );
            ok = false;
            continue;
        }
        let w = match item.weight {
            Some((w, wpos)) if !rational => {
                c.report(
                    Problem::error(
                        wpos,
                        format!("surface \"{name}\": a weight on a control point of a non-rational surface"),
                    )
                    .with_help(if u_name == v_name {
                        format!("declare basis \"{u_name}\" rational")
                    } else {
                        format!("declare basis \"{u_name}\" or \"{v_name}\" rational")
                    }),
                );
                ok = false;
                w
            }
            Some((w, wpos)) if !(w > 0.0 && w.is_finite()) => {
                c.error(
                    wpos,
                    format!("surface \"{name}\": a control point weight must be > 0, found {w}"),
                );
                ok = false;
                1.0
            }
            Some((w, _)) => w,
            None => 1.0,
        };
        let (x, y, z) = obj.vertices[(base + i as u32) as usize];
        points.push((x, y, z, w));
    }
    if !ok {
        return false;
    }
    obj.surfaces.push(RawSurface {
        name,
        at: c.located(at),
        material,
        material_at,
        u,
        v,
        points,
        approximation: None,
    });
    true
}

/// A technique word of `approximate surface` and the numbers after it.
type Words = Vec<(String, Pos, Vec<f64>)>;

/// `approximate surface …` (after `approximate`, at `surface`) in a group: sets the
/// approximation of the named surfaces of `obj` (names in `failed` were reported).
pub fn approximate(c: &mut Cursor, obj: &mut RawObject, failed: &[String], at: Pos) {
    c.advance(); // `surface`
    let mut words: Words = Vec::new();
    while let Some(t) = c.peek().cloned() {
        match t.tok {
            Tok::Word(w) if w != "end" => words.push((w, t.pos, Vec::new())),
            // Numbers belong to the word before them.
            Tok::Num(v) if !words.is_empty() => {
                if let Some(last) = words.last_mut() {
                    last.2.push(v);
                }
            }
            _ => break,
        }
        c.advance();
    }
    let mut names = Vec::new();
    while c.at_string() {
        if let Some((n, p)) = c.string("a surface name") {
            names.push((n, p));
        }
    }
    if names.is_empty() {
        let (pos, found) = (
            c.pos(),
            c.peek()
                .map_or("the end of the file".into(), |t| t.tok.describe()),
        );
        c.error(
            pos,
            format!("expected the name of a surface after \"approximate surface\", found {found}"),
        );
        return;
    }
    let technique = technique(c, &words, at);
    for (n, p) in names {
        let Some(s) = obj.surfaces.iter_mut().find(|s| s.name == n) else {
            if failed.contains(&n) {
                continue;
            }
            let mut problem = Problem::error(p, format!("unknown surface \"{n}\""));
            problem = match closest(&n, obj.surfaces.iter().map(|s| s.name.as_str())) {
                Some(s) => problem.with_help(format!("did you mean \"{s}\"?")),
                None => {
                    problem.with_help("approximate names a surface written before it in the group")
                }
            };
            c.report(problem);
            continue;
        };
        s.approximation = technique.clone().map(|t| t.of(s.u.degree, s.v.degree));
    }
}

/// The words of an approximation technique.
const TECHNIQUE_WORDS: &[&str] = &[
    "view",
    "tree",
    "grid",
    "delaunay",
    "any",
    "regular",
    "parametric",
    "spatial",
    "length",
    "curvature",
    "distance",
    "angle",
    "fine",
    "sharp",
];

/// A polygon group's `approximate [displace] technique …` (after `approximate`): how the
/// object is diced when it is displaced (polygons without displacement are used as
/// written). `parametric u v` is `u × v` segments per patch (degree 1).
pub fn polygon_approximation(c: &mut Cursor, at: Pos) -> Option<ApproximationDesc> {
    c.eat_word("displace");
    let mut words: Words = Vec::new();
    while let Some(t) = c.peek().cloned() {
        match t.tok {
            Tok::Word(w) if TECHNIQUE_WORDS.contains(&w.as_str()) => {
                words.push((w, t.pos, Vec::new()))
            }
            Tok::Num(v) if !words.is_empty() => {
                if let Some(last) = words.last_mut() {
                    last.2.push(v);
                }
            }
            _ => break,
        }
        c.advance();
    }
    technique(c, &words, at).map(|t| t.of(1, 1))
}

/// A mapped approximation technique, before the surface's degrees are known.
#[derive(Debug, Clone)]
enum Technique {
    /// `parametric u v`: factors of the degree per patch.
    Parametric(f64, f64),
    /// Anything else: as it is.
    Fixed(ApproximationDesc),
}

impl Technique {
    fn of(self, du: u32, dv: u32) -> ApproximationDesc {
        match self {
            Technique::Parametric(u, v) => ApproximationDesc::Parametric {
                u: (u * f64::from(du)).round().max(1.0) as u32,
                v: (v * f64::from(dv)).round().max(1.0) as u32,
            },
            Technique::Fixed(a) => a,
        }
    }
}

/// Subdivision levels `min max` written after a technique's own numbers.
fn levels(nums: &[f64], own: usize) -> (u32, u32) {
    match nums.get(own..own + 2) {
        Some([lo, hi]) => (lo.clamp(0.0, 12.0) as u32, hi.clamp(0.0, 12.0) as u32),
        _ => (0, 7),
    }
}

fn technique(c: &mut Cursor, words: &Words, at: Pos) -> Option<Technique> {
    let find = |w: &str| words.iter().find(|(x, _, _)| x == w);
    let view = find("view").is_some();
    let first = |w: &str| find(w).and_then(|(_, _, n)| n.first().copied());
    let unmapped = |c: &mut Cursor, what: &str| {
        c.warn(
            at,
            format!("approximation \"{what}\" is not mapped; the default approximation is used"),
        );
        None
    };
    const KNOWN: &[&str] = TECHNIQUE_WORDS;
    if let Some((w, pos, _)) = words.iter().find(|(w, _, _)| !KNOWN.contains(&w.as_str())) {
        let mut p = Problem::error(*pos, format!("unknown approximation technique \"{w}\""));
        if let Some(s) = closest(w, KNOWN.iter().copied()) {
            p = p.with_help(format!("did you mean \"{s}\"?"));
        }
        c.report(p);
        return None;
    }
    if find("fine").is_some() {
        return unmapped(c, "fine");
    }
    if let Some((_, _, n)) = find("parametric") {
        let (u, v) = (
            n.first().copied().unwrap_or(1.0),
            n.get(1).copied().unwrap_or(1.0),
        );
        if find("regular").is_some() {
            return Some(Technique::Fixed(ApproximationDesc::Regular {
                u: u.round().max(1.0) as u32,
                v: v.round().max(1.0) as u32,
            }));
        }
        return Some(Technique::Parametric(u, v));
    }
    let space = if view {
        SpaceDesc::Raster
    } else {
        SpaceDesc::Object
    };
    if let Some((_, _, n)) = find("curvature") {
        let (min_subdiv, max_subdiv) = levels(n, 2);
        if view {
            c.warn(at, "\"view\" is not mapped for curvature approximations: distances are in object units");
        }
        return Some(Technique::Fixed(ApproximationDesc::Curvature {
            distance: n.first().copied().unwrap_or(0.01),
            angle: n.get(1).copied().unwrap_or(10.0),
            min_subdiv,
            max_subdiv,
        }));
    }
    let edge = find("spatial").or(find("length"));
    let curv = find("distance").is_some() || find("angle").is_some();
    if let Some((w, _, n)) = edge {
        if curv {
            c.warn(
                at,
                format!("combined approximation criteria are not mapped: only \"{w}\" is used"),
            );
        }
        let (min_subdiv, max_subdiv) = levels(n, 1);
        return Some(Technique::Fixed(ApproximationDesc::Spatial {
            edge: n.first().copied().unwrap_or(1.0),
            space,
            min_subdiv,
            max_subdiv,
        }));
    }
    if curv {
        let last = words
            .iter()
            .rev()
            .find(|(w, _, _)| w == "distance" || w == "angle")
            .map_or(&[][..], |(_, _, n)| n.as_slice());
        let (min_subdiv, max_subdiv) = levels(last, 1);
        if view {
            c.warn(at, "\"view\" is not mapped for curvature approximations: distances are in object units");
        }
        return Some(Technique::Fixed(ApproximationDesc::Curvature {
            distance: first("distance").unwrap_or(0.0),
            angle: first("angle").unwrap_or(0.0),
            min_subdiv,
            max_subdiv,
        }));
    }
    unmapped(c, "without a technique")
}
