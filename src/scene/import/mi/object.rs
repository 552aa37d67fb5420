//! Geometry and the instance tree: `object … group … end group end object` (vector list,
//! `v` references, `p ["material"] i j k …` polygons, flags), `instance … end instance`
//! (`transform`, `material` override, flags) and `instgroup … end instgroup`.
//!
//! The `caustic`/`globillum` flags become the photon flags of the object or instance.
//! Vertex normals and derivative references and polygon `approximate` statements are read
//! and reported as not mapped; `basis` declarations, `surface` statements and their
//! `approximate surface` are read by [`super::surface`].

use super::super::located::{Pos, Problem};
use super::cursor::Cursor;
use super::lexer::Tok;
use super::model::{Flags, RawGroup, RawInstance, RawObject, RawPolygon};
use super::statements::Reader;
use super::surface::{self, Bases};
use crate::scene::suggest::closest;

const OBJECT: &[&str] = &[
    "visible",
    "shadow",
    "trace",
    "tag",
    "caustic",
    "globillum",
    "box",
    "max",
    "group",
    "basis",
    "hide",
    "end",
];

fn flag(c: &mut Cursor, w: &str, flags: &mut Flags) -> bool {
    match w {
        "visible" => flags.visible = Some(c.switch()),
        "trace" => flags.trace = Some(c.switch()),
        "shadow" => {
            if c.at_number() {
                let v = c.number("shadow").unwrap_or(1.0);
                flags.shadow = Some(v != 0.0);
            } else {
                flags.shadow = Some(c.switch());
            }
        }
        "caustic" | "globillum" => {
            let mode = photon_mode(c, w);
            if w == "caustic" {
                flags.caustic = mode;
            } else {
                flags.globillum = mode;
            }
        }
        "tag" => {
            c.eat_word("label");
            if let Some(label) = c.count("tag") {
                flags.label = Some(label);
            }
            c.skip_arguments();
        }
        _ => return false,
    }
    true
}

/// `caustic N` / `globillum N` (0 none, 1 casts, 2 receives, 3 both; `on` = 3, `off` = 0).
fn photon_mode(c: &mut Cursor, w: &str) -> Option<u8> {
    if !c.at_number() {
        return Some(if c.switch() { 3 } else { 0 });
    }
    let pos = c.pos();
    let v = c.number(w)?;
    if !(0.0..=3.0).contains(&v) || v.fract() != 0.0 {
        c.error(pos, format!("{w} must be 0, 1, 2 or 3, found {v}"));
        return None;
    }
    Some(v as u8)
}

/// `object "name" … end object`.
pub fn object(r: &mut Reader, c: &mut Cursor, open: Pos) {
    let Some((name, pos)) = c.string("the name of the object") else {
        c.skip_to_end("object", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    // An incremental object starts from the earlier one: flags not written keep their
    // values, and the geometry is kept unless the block writes a group (then its groups
    // replace the earlier geometry whole).
    let earlier = r.earlier.as_mut().and_then(|e| e.object.take());
    let mut keeps_earlier_geometry = earlier.is_some();
    let mut obj = RawObject {
        at: c.located(open),
        ..earlier.unwrap_or(RawObject {
            at: c.located(open),
            vertices: Vec::new(),
            uvs: Vec::new(),
            polygons: Vec::new(),
            surfaces: Vec::new(),
            approximation: None,
            flags: Flags::default(),
        })
    };
    let mut bases = Bases::new();
    let mut failed = false;
    loop {
        let Some(t) = c.block_token("object", open) else {
            return;
        };
        let Tok::Word(w) = &t.tok else {
            let found = t.tok.describe();
            c.error(t.pos, format!("unexpected {found} in object"));
            c.skip_to_end("object", open);
            return;
        };
        if w == "end" {
            break;
        }
        c.advance();
        if flag(c, w, &mut obj.flags) {
            continue;
        }
        match w.as_str() {
            "box" => {
                c.skip_arguments();
            }
            "max" => {
                c.eat_word("displace");
                c.skip_arguments();
            }
            "hide" => {
                if c.switch() {
                    obj.flags.visible = Some(false);
                }
            }
            "group" => {
                if std::mem::take(&mut keeps_earlier_geometry) {
                    obj.vertices.clear();
                    obj.uvs.clear();
                    obj.polygons.clear();
                    obj.surfaces.clear();
                    obj.approximation = None;
                }
                if !group(c, &mut obj, &bases, t.pos) {
                    failed = true;
                }
            }
            "basis" => {
                if !surface::basis(c, &mut bases) {
                    failed = true;
                }
            }
            "surface" | "curve" | "connect" => {
                c.report(
                    Problem::error(t.pos, format!("\"{w}\" belongs in a group"))
                        .with_help("write it between group and end group, after the vertices"),
                );
                c.skip_to_end("object", open);
                return;
            }
            other => {
                let mut p = Problem::error(t.pos, format!("unknown object statement \"{other}\""));
                if let Some(s) = closest(other, OBJECT.iter().copied()) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.report(p);
                c.skip_arguments();
            }
        }
    }
    c.expect_end("object", open);
    if failed {
        return;
    }
    if obj.polygons.is_empty() && obj.surfaces.is_empty() {
        c.error(
            open,
            format!("object \"{name}\" has no polygons or surfaces"),
        );
        return;
    }
    if fresh {
        r.raw.objects.push((name, obj));
    }
}

/// `group … end group`: appends its vertices and polygons to `obj`. False on an error.
fn group(c: &mut Cursor, obj: &mut RawObject, bases: &Bases, open: Pos) -> bool {
    if c.at_string() {
        // `group "merge" eps` and similar options.
        c.advance();
        c.skip_arguments();
    }
    let mut vectors: Vec<(f64, f64, f64)> = Vec::new();
    // Where each vector's three numbers are (a vertex's error points at its number).
    let mut vector_at: Vec<[Pos; 3]> = Vec::new();
    let base = obj.vertices.len() as u32;
    let mut vertex_count = 0u32;
    let mut material: Option<String> = None;
    let mut warned_refs = false;
    let mut failed_surfaces = Vec::new();
    let mut ok = true;
    // The vector list (an `$include` may hold some of it).
    loop {
        c.splice_includes();
        if !c.at_number() {
            break;
        }
        let mut v = [0.0; 3];
        let mut at = [Pos::default(); 3];
        for k in 0..3 {
            at[k] = c.pos();
            let Some(x) = c.number("a vector of the group") else {
                c.skip_to_end("group", open);
                return false;
            };
            v[k] = x;
        }
        vectors.push((v[0], v[1], v[2]));
        vector_at.push(at);
    }
    loop {
        let Some(t) = c.block_token("group", open) else {
            return false;
        };
        let Tok::Word(w) = &t.tok else {
            let found = t.tok.describe();
            c.error(
                t.pos,
                format!("unexpected {found} in group (expected v, p or end group)"),
            );
            c.skip_to_end("group", open);
            return false;
        };
        if w == "end" {
            break;
        }
        c.advance();
        match w.as_str() {
            "v" => {
                let at = c.pos();
                let Some(i) = c.count("the vector index of v") else {
                    ok = false;
                    continue;
                };
                obj.uvs.push(None);
                match vectors.get(i as usize) {
                    Some(p) => {
                        if !within_f32(c, *p, vector_at[i as usize]) {
                            ok = false;
                        }
                        obj.vertices.push(*p)
                    }
                    None => {
                        c.error(
                            at,
                            format!(
                                "vector index {i} is out of range (the group has {} vectors)",
                                vectors.len()
                            ),
                        );
                        ok = false;
                        obj.vertices.push((0.0, 0.0, 0.0));
                    }
                }
                vertex_count += 1;
                while c.at_word("n")
                    || c.at_word("t")
                    || c.at_word("d")
                    || c.at_word("m")
                    || c.at_word("u")
                {
                    let ref_at = c.pos();
                    let texture = c.at_word("t");
                    c.advance();
                    if texture && c.at_number() {
                        let at = c.pos();
                        if let Some(k) = c.count("the texture vector index of t") {
                            match vectors.get(k as usize) {
                                Some(&(u, v, _)) => {
                                    let last = obj.uvs.last_mut().expect("pushed with the vertex");
                                    last.get_or_insert((u, v));
                                }
                                None => {
                                    c.error(at, format!("vector index {k} is out of range (the group has {} vectors)", vectors.len()));
                                    ok = false;
                                }
                            }
                        }
                        // Further texture spaces: one is mapped.
                        while c.at_number() {
                            c.advance();
                        }
                        continue;
                    }
                    c.skip_arguments();
                    if !warned_refs {
                        c.warn(
                            ref_at,
                            "vertex normal and derivative references are not mapped",
                        );
                        warned_refs = true;
                    }
                }
            }
            "p" | "c" | "cp" => {
                if c.at_string() {
                    material = c.string("the polygon material").map(|s| s.0);
                }
                let mut indices = Vec::new();
                while c.at_number() {
                    let at = c.pos();
                    let Some(i) = c.count("a polygon vertex index") else {
                        ok = false;
                        break;
                    };
                    if i >= vertex_count {
                        c.error(at, format!("vertex index {i} is out of range (the group has {vertex_count} vertices so far)"));
                        ok = false;
                    }
                    indices.push(base + i);
                }
                if c.at_word("hole") {
                    let at = c.pos();
                    c.error(at, "polygons with holes are not supported");
                    c.advance();
                    c.skip_arguments();
                    ok = false;
                    continue;
                }
                if indices.len() < 3 {
                    c.error(
                        t.pos,
                        format!(
                            "a polygon needs at least 3 vertices, found {}",
                            indices.len()
                        ),
                    );
                    ok = false;
                    continue;
                }
                obj.polygons.push(RawPolygon {
                    material: material.clone(),
                    vertices: indices,
                    at: c.located(t.pos),
                });
            }
            "approximate" if c.at_word("surface") => {
                surface::approximate(c, obj, &failed_surfaces, t.pos)
            }
            "surface" => {
                let counts = (base, vertex_count);
                if !surface::surface(c, obj, bases, counts, &mut failed_surfaces, t.pos) {
                    ok = false;
                }
            }
            "curve" | "trim" | "hole" | "special" => {
                let what = if w == "curve" {
                    "free-form curves (\"curve\")".to_string()
                } else {
                    format!("\"{w}\" curves on surfaces")
                };
                c.report(
                    Problem::error(t.pos, format!("{what} are not supported")).with_help(
                        "only whole, untrimmed surfaces are read: remove the trimming curves",
                    ),
                );
                c.skip_arguments();
                ok = false;
            }
            "derivative" | "texture" | "vector" | "volume" | "connect" => {
                if w != "derivative" && w != "connect" {
                    c.eat_word("vector");
                    c.eat_word("texture");
                }
                c.skip_arguments();
                let what = match w.as_str() {
                    "derivative" => "surface derivative requests are not mapped",
                    "connect" => "surface connections are not mapped",
                    _ => "texture surfaces are not mapped (texture coordinates run 0…1 over the surface)",
                };
                c.warn(t.pos, what);
            }
            "approximate" => {
                obj.approximation = surface::polygon_approximation(c, t.pos);
            }
            other => {
                c.report(
                    Problem::error(t.pos, format!("unknown group statement \"{other}\""))
                        .with_help(
                            "a group holds vectors, then v, p, surface and approximate statements",
                        ),
                );
                c.skip_to_end("group", open);
                return false;
            }
        }
    }
    c.expect_end("group", open);
    ok
}

/// Whether each coordinate of the vertex `p` (its numbers at `at`) fits the f32 the
/// renderer keeps positions in; reports each that does not at its number.
fn within_f32(c: &mut Cursor, p: (f64, f64, f64), at: [Pos; 3]) -> bool {
    let mut ok = true;
    for (x, at) in [p.0, p.1, p.2].into_iter().zip(at) {
        if x.abs() > f64::from(f32::MAX) {
            c.error(at, format!("vertex {x:e} is beyond the f32 range"));
            ok = false;
        }
    }
    ok
}

/// `instance "name" "element" … end instance`.
pub fn instance(r: &mut Reader, c: &mut Cursor, open: Pos) {
    let Some((name, pos)) = c.string("the name of the instance") else {
        c.skip_to_end("instance", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    // An incremental instance starts from the earlier one: the element placed may be
    // left out, and what the block does not write keeps its value.
    let earlier = r.earlier.as_mut().and_then(|e| e.instance.take());
    let (of, of_at) = match earlier {
        Some(ref e) if !c.at_string() => (e.of.clone(), e.of_at.clone()),
        _ => {
            let Some((of, of_pos)) = c.string("the element the instance places") else {
                c.skip_to_end("instance", open);
                return;
            };
            (of, c.located(of_pos))
        }
    };
    let mut inst = RawInstance {
        at: c.located(open),
        of,
        of_at,
        ..earlier.unwrap_or(RawInstance {
            at: c.located(open),
            of: String::new(),
            of_at: c.located(open),
            transform: None,
            transform_at: None,
            material: None,
            flags: Flags::default(),
        })
    };
    loop {
        let Some(t) = c.block_token("instance", open) else {
            return;
        };
        let Tok::Word(w) = &t.tok else {
            let found = t.tok.describe();
            c.error(t.pos, format!("unexpected {found} in instance"));
            c.skip_to_end("instance", open);
            return;
        };
        if w == "end" {
            break;
        }
        c.advance();
        if flag(c, w, &mut inst.flags) {
            continue;
        }
        match w.as_str() {
            "transform" => {
                if c.at_number() {
                    let mut a = [0.0; 16];
                    let mut at = [Pos::default(); 16];
                    for k in 0..16 {
                        at[k] = c.pos();
                        let Some(x) = c.number("the transform (16 numbers)") else {
                            c.skip_to_end("instance", open);
                            return;
                        };
                        a[k] = x;
                    }
                    match super::transform::affine(&a, &at) {
                        Ok(a) => inst.transform = Some(a),
                        Err(problem) => c.report(problem),
                    }
                    // The matrix is the value: errors about it as a whole point at its
                    // first number.
                    inst.transform_at = Some(c.located(at[0]));
                }
            }
            "motion" => {
                c.eat_word("transform");
                c.eat_word("off");
                c.skip_arguments();
                c.warn(t.pos, "motion transforms are not mapped");
            }
            "material" => {
                if c.eat_punct('[') {
                    let first = c.string("a material name");
                    while c.peek().is_some() && !c.eat_punct(']') {
                        c.advance();
                    }
                    c.warn(
                        t.pos,
                        "a material list on an instance: its first material is used",
                    );
                    inst.material = first.map(|(s, p)| (s, c.located(p)));
                } else if let Some((m, p)) = c.string("the material of the instance") {
                    inst.material = Some((m, c.located(p)));
                }
            }
            "hide" => {
                if c.switch() {
                    inst.flags.visible = Some(false);
                }
            }
            other => {
                let mut p =
                    Problem::error(t.pos, format!("unknown instance statement \"{other}\""));
                let known = [
                    "transform",
                    "material",
                    "visible",
                    "shadow",
                    "trace",
                    "hide",
                    "tag",
                    "motion",
                ];
                if let Some(s) = closest(other, known) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.report(p);
                c.skip_arguments();
            }
        }
    }
    c.expect_end("instance", open);
    if fresh {
        r.raw.instances.push((name, inst));
    }
}

/// `instgroup "name" "member" … end instgroup`.
pub fn instgroup(r: &mut Reader, c: &mut Cursor, open: Pos) {
    let Some((name, pos)) = c.string("the name of the instgroup") else {
        c.skip_to_end("instgroup", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    let mut members = Vec::new();
    while c.at_string() {
        if let Some((m, p)) = c.string("a member") {
            members.push((m, c.located(p)));
        }
    }
    c.expect_end("instgroup", open);
    if fresh {
        r.raw.groups.push((
            name,
            RawGroup {
                at: c.located(open),
                members,
            },
        ));
    }
}
