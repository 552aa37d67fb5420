//! mental ray's base texture shaders mapped onto shader-graph nodes
//! (`docs/scene-format.md`, *Shader graphs*): a material parameter written `= "lookup"`,
//! where `"lookup"` is a named `mib_texture_lookup` of a `color texture "name" "file"`,
//! becomes a `bind` of the parameter to `Image(file, uv: …)`.
//!
//! - `mib_texture_lookup` (`tex`, `coord`): `Image(file: the texture's file, uv: coord)`,
//!   `coord` default `Uv`.
//! - `mib_texture_vector` (`select`, `selspace`, `vertex`, `project`): `select` ≥ 0 is the
//!   texture space, `Uv` (one space: the `t` references of the polygons' vertices);
//!   `select −1` the point, `Position` (object space); `select −2` the normal, `Normal`.
//! - `mib_texture_remap` (`input`, `transform`, `repeat`, `offset`): mental ray computes
//!   `p · transform`, then `frac(p · repeat)` where a `repeat` component is non-zero, then
//!   adds `offset`: `Add(Repeat(uv: Mul(Add(Mul(input, scale), translation), repeat),
//!   scale: 1), offset)`. Only scale-and-translation transforms are mapped.

use std::collections::HashMap;

use super::super::located::{Located, Pos};
use super::cursor::{Cursor, Param, ShaderCall, Value};
use crate::scene::desc::{InputDesc, NodeDesc, V3};
use crate::scene::nodes_desc::WrapDesc;

/// Deepest chain of named texture shaders followed.
const MAX_CHAIN: usize = 8;

/// The named shaders and declared textures a texture chain resolves against.
pub struct Scope<'a> {
    /// `shader "name" …` calls.
    pub named: &'a HashMap<String, ShaderCall>,
    /// `color texture "name" "file"` declarations.
    pub textures: &'a HashMap<String, (String, Located)>,
}

/// The node graph of a colour parameter written `= "shader"` when that shader is a
/// `mib_texture_lookup`; `None` (nothing reported) for any other value, `Some(None)` after
/// a reported error.
pub fn colour_input(c: &mut Cursor, p: &Param, scope: &Scope<'_>) -> Option<Option<InputDesc>> {
    let Value::Ref(name) = &p.value else {
        return None;
    };
    let call = scope.named.get(name)?;
    if call.name != "mib_texture_lookup" {
        return None;
    }
    Some(lookup(c, call, scope, 0))
}

fn param<'a>(call: &'a ShaderCall, name: &str) -> Option<&'a Param> {
    call.params.iter().rev().find(|p| p.name == name)
}

fn node(n: NodeDesc) -> InputDesc {
    InputDesc::Node(Box::new(n))
}

fn lookup(c: &mut Cursor, call: &ShaderCall, scope: &Scope<'_>, depth: usize) -> Option<InputDesc> {
    let Some(tex) = param(call, "tex") else {
        c.error(
            call.pos,
            "mib_texture_lookup needs \"tex\", the name of a color texture",
        );
        return None;
    };
    let Value::Str(texture) = &tex.value else {
        c.error(
            tex.value_pos,
            "parameter \"tex\" of \"mib_texture_lookup\" takes a texture name (a string)",
        );
        return None;
    };
    let Some((file, _)) = scope.textures.get(texture) else {
        c.error(tex.value_pos, format!("unknown texture \"{texture}\""));
        return None;
    };
    let uv = match param(call, "coord") {
        Some(p) => coordinates(c, p, scope, depth + 1)?,
        None => node(NodeDesc::Uv),
    };
    Some(node(NodeDesc::Image {
        file: file.clone(),
        uv,
        wrap: WrapDesc::Repeat,
        color_space: None,
    }))
}

/// The coordinates a `coord`/`input` parameter gives: a constant vector or a chain of
/// `mib_texture_vector`/`mib_texture_remap`.
fn coordinates(c: &mut Cursor, p: &Param, scope: &Scope<'_>, depth: usize) -> Option<InputDesc> {
    match &p.value {
        Value::Nums(n) if n.len() == 3 => Some(InputDesc::Colour((n[0], n[1], n[2]))),
        Value::Ref(name) => {
            let Some(call) = scope.named.get(name) else {
                c.error(p.value_pos, format!("unknown shader \"{name}\""));
                return None;
            };
            if depth > MAX_CHAIN {
                c.error(
                    p.value_pos,
                    format!("texture shaders refer to each other more than {MAX_CHAIN} deep"),
                );
                return None;
            }
            match call.name.as_str() {
                "mib_texture_vector" => Some(vector(c, call)),
                "mib_texture_remap" => remap(c, call, scope, depth),
                other => {
                    c.error(
                        p.value_pos,
                        format!("\"{name}\" is a \"{other}\", not a texture coordinate shader"),
                    );
                    None
                }
            }
        }
        _ => {
            c.error(
                p.value_pos,
                format!(
                    "parameter \"{}\" takes a vector (3 numbers) or = \"shader\"",
                    p.name
                ),
            );
            None
        }
    }
}

fn number(p: Option<&Param>, default: f64) -> f64 {
    match p.map(|p| &p.value) {
        Some(Value::Nums(n)) if n.len() == 1 => n[0],
        _ => default,
    }
}

fn vector(c: &mut Cursor, call: &ShaderCall) -> InputDesc {
    let select = number(param(call, "select"), 0.0);
    for name in ["project", "vertex"] {
        if let Some(p) = param(call, name) {
            if number(Some(p), 0.0) != 0.0 {
                c.warn(
                    p.pos,
                    format!("parameter \"{name}\" of \"mib_texture_vector\" is not mapped"),
                );
            }
        }
    }
    if select >= 0.0 {
        if select > 0.0 {
            c.warn(
                call.pos,
                "one texture space is mapped: texture space 0 is used",
            );
        }
        return node(NodeDesc::Uv);
    }
    if select == -2.0 {
        return node(NodeDesc::Normal);
    }
    if select != -1.0 {
        c.warn(
            call.pos,
            format!("\"select\" {select} is not mapped: the point (select -1) is used"),
        );
    }
    let space = number(param(call, "selspace"), 1.0);
    if space != 1.0 {
        c.warn(
            call.pos,
            "the point is given in object space (\"selspace\" 1)",
        );
    }
    node(NodeDesc::Position)
}

fn triple(c: &mut Cursor, call: &ShaderCall, name: &str) -> Option<V3> {
    let p = param(call, name)?;
    match &p.value {
        Value::Nums(n) if n.len() == 3 => Some((n[0], n[1], n[2])),
        _ => {
            c.error(
                p.value_pos,
                format!("parameter \"{name}\" of \"mib_texture_remap\" takes a vector (3 numbers)"),
            );
            None
        }
    }
}

fn remap(c: &mut Cursor, call: &ShaderCall, scope: &Scope<'_>, depth: usize) -> Option<InputDesc> {
    let mut p = match param(call, "input") {
        Some(input) => coordinates(c, input, scope, depth + 1)?,
        None => node(NodeDesc::Uv),
    };
    if let Some(t) = param(call, "transform") {
        let m = match &t.value {
            Value::Nums(n) if n.len() == 16 => n.clone(),
            _ => {
                c.error(
                    t.value_pos,
                    "parameter \"transform\" of \"mib_texture_remap\" takes a matrix (16 numbers)",
                );
                return None;
            }
        };
        let off_diagonal = [1, 2, 4, 6, 8, 9, 3, 7, 11];
        if off_diagonal.iter().any(|&k| m[k] != 0.0) || m[15] != 1.0 {
            c.error(
                t.value_pos,
                "only scale-and-translation \"transform\" matrices of \"mib_texture_remap\" are mapped",
            );
            return None;
        }
        p = node(NodeDesc::Add(
            node(NodeDesc::Mul(p, InputDesc::Colour((m[0], m[5], m[10])))),
            InputDesc::Colour((m[12], m[13], m[14])),
        ));
    }
    if let Some(r) = triple(c, call, "repeat") {
        if r != (0.0, 0.0, 0.0) {
            let keep = |x: f64| if x == 0.0 { 1.0 } else { x };
            if r.0 == 0.0 || r.1 == 0.0 {
                warn_at(
                    c,
                    call,
                    "repeat",
                    "a zero \"repeat\" component is taken as 1",
                );
            }
            p = node(NodeDesc::Repeat {
                uv: node(NodeDesc::Mul(
                    p,
                    InputDesc::Colour((keep(r.0), keep(r.1), keep(r.2))),
                )),
                scale: InputDesc::Number(1.0),
            });
        }
    }
    if let Some(o) = triple(c, call, "offset") {
        if o != (0.0, 0.0, 0.0) {
            p = node(NodeDesc::Add(p, InputDesc::Colour(o)));
        }
    }
    for name in [
        "alt_x", "alt_y", "alt_z", "torus_x", "torus_y", "torus_z", "min", "max",
    ] {
        if param(call, name).is_some() {
            warn_at(
                c,
                call,
                name,
                &format!("parameter \"{name}\" of \"mib_texture_remap\" is not mapped"),
            );
        }
    }
    Some(p)
}

fn warn_at(c: &mut Cursor, call: &ShaderCall, name: &str, message: &str) {
    let at: Pos = param(call, name).map_or(call.pos, |p| p.pos);
    c.warn(at, message.to_string());
}
