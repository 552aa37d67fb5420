//! A material's `shadow` and `environment` shaders (`docs/mi.md`, *Shadow and environment
//! shaders*): `mib_shadow_transparency` becomes the material's `shadow:` transmittance,
//! an environment shader (what the camera's `environment` takes) its `environment:`.
//!
//! `mib_shadow_transparency` ("color" RGBA, "transp" RGB, "mode", "light"): mental ray
//! multiplies the transparency by the colour's alpha and the light passing through by the
//! colour, and an alpha below 1 lets light through too. We read that as the per-channel
//! transmittance `(1 − α) + α · color · transp`: `transp 0` with alpha 1 blocks, `transp 1`
//! tints by `color`, alpha 0 lets everything through. A 3-number colour has alpha 1; absent
//! parameters are mental ray's zero. The light list (`mode` 1 inclusive, 2 exclusive)
//! cannot be mapped: the shadow shader then applies to every light (warned).

use std::collections::HashMap;

use super::super::located::Problem;
use super::cursor::{Cursor, Param, ShaderCall, Value};
use super::shaders::{self, builtin, Role};
use crate::scene::desc::{MaterialEnvironmentDesc, ShadowDesc};

/// Follows named shaders (`shadow = "name"`, phenomenon roots) to the built-in call.
fn resolve(call: &ShaderCall, named: &HashMap<String, ShaderCall>) -> ShaderCall {
    let mut call = call.clone();
    for _ in 0..8 {
        match named.get(&call.name) {
            Some(inner) if builtin(&call.name).is_none() => call = inner.clone(),
            _ => break,
        }
    }
    call
}

/// The numbers of `p` if it holds between `min` and `max` of them; else reported.
fn numbers<'a>(c: &mut Cursor, shader: &str, p: &'a Param, counts: &[usize]) -> Option<&'a [f64]> {
    match &p.value {
        Value::Nums(n) if counts.contains(&n.len()) => Some(n),
        other => {
            let found = match other {
                Value::Nums(n) => format!("{} numbers", n.len()),
                v => v.kind().to_string(),
            };
            let want = if counts.len() == 1 && counts[0] == 1 {
                "a number".to_string()
            } else {
                "a colour (r g b or r g b a)".to_string()
            };
            c.error(
                p.value_pos,
                format!(
                    "parameter \"{}\" of \"{shader}\" takes {want}, found {found}",
                    p.name
                ),
            );
            None
        }
    }
}

/// The material's `shadow:` from its shadow shader `call`, or `None` (reported: an error for
/// bad parameters, a warning for a shader that is not built in).
pub fn shadow(
    c: &mut Cursor,
    call: &ShaderCall,
    named: &HashMap<String, ShaderCall>,
) -> Option<ShadowDesc> {
    let call = resolve(call, named);
    // A material shader as its own shadow shader (Maya's exporter writes `shadow =
    // "sh1"` beside `= "sh1"`): shadows follow the material shader, stagelight's rule
    // without a shadow shader.
    if builtin(&call.name).is_some_and(|b| b.role == shaders::Role::Material) {
        c.warn(
            call.pos,
            format!(
                "material shader \"{}\" as the shadow shader: shadows follow the material shader, as without one (an opaque surface blocks the light)",
                call.name
            ),
        );
        return None;
    }
    if builtin(&call.name).is_none() {
        c.report(
            Problem::warning(
                call.pos,
                format!(
                    "shadow shader \"{}\" is not mapped: shadows follow the material shader \
                     (mib_opacity lets 1 − opacity through, every other shader blocks)",
                    call.name
                ),
            )
            .with_help("mib_shadow_transparency maps onto the material's shadow transparency"),
        );
        return None;
    }
    let b = shaders::check(c, &call, Role::Shadow, "shadow")?;
    let get = |name: &str| call.params.iter().rev().find(|p| p.name == name);
    let mut ok = true;
    let mut rgba = [0.0, 0.0, 0.0, 0.0];
    if let Some(p) = get("color") {
        match numbers(c, b.name, p, &[3, 4]) {
            Some(n) => {
                rgba = [n[0], n[1], n[2], n.get(3).copied().unwrap_or(1.0)];
            }
            None => ok = false,
        }
    }
    let mut transp = [0.0; 3];
    if let Some(p) = get("transp") {
        match numbers(c, b.name, p, &[1, 3, 4]) {
            Some([t]) => transp = [*t; 3],
            Some(n) => transp = [n[0], n[1], n[2]],
            None => ok = false,
        }
    }
    let mut mode = 0.0;
    if let Some(p) = get("mode") {
        match numbers(c, b.name, p, &[1]) {
            Some([m]) if [0.0, 1.0, 2.0, 3.0].contains(m) => mode = *m,
            Some([m]) => {
                c.report(
                    Problem::error(
                        p.value_pos,
                        format!("\"mode\" of \"mib_shadow_transparency\" must be 0, 1, 2 or 3, found {m}"),
                    )
                    .with_help("0: every light, 1: the listed lights, 2: all but the listed, 3: no light list"),
                );
                ok = false;
            }
            _ => ok = false,
        }
    }
    let list = get("light").or_else(|| get("lights"));
    if let (Some(p), true) = (list, mode == 1.0 || mode == 2.0) {
        c.warn(
            p.pos,
            "the light list of \"mib_shadow_transparency\" is not mapped: its shadow \
             transparency applies to every light",
        );
    }
    let alpha = rgba[3];
    let t: Vec<f64> = (0..3)
        .map(|k| (1.0 - alpha) + alpha * rgba[k] * transp[k])
        .collect();
    if let Some(bad) = t.iter().find(|x| !(0.0..=1.0).contains(*x)) {
        let at = get("transp")
            .or_else(|| get("color"))
            .map_or(call.pos, |p| p.pos);
        c.report(
            Problem::error(
                at,
                format!(
                    "\"mib_shadow_transparency\" would let {bad} of the light through \
                     ((1 − alpha) + alpha · color · transp must lie in [0, 1])"
                ),
            )
            .with_help("colour, alpha and transp are each between 0 and 1"),
        );
        ok = false;
    }
    ok.then_some(if t.iter().all(|x| *x == 0.0) {
        ShadowDesc::Opaque
    } else {
        ShadowDesc::Transparency {
            color: (t[0], t[1], t[2]),
        }
    })
}

/// The material's `environment:` from its environment shader `call` (mapped as the camera's
/// environment is, the tutorial's `myEnvironment` included once `linked`), or `None`
/// (reported).
pub fn environment(
    c: &mut Cursor,
    call: &ShaderCall,
    named: &HashMap<String, ShaderCall>,
    linked: &[String],
) -> Option<MaterialEnvironmentDesc> {
    let env = super::tutorial::environment(c, call, linked)
        .unwrap_or_else(|| shaders::environment(c, call, named))?;
    Some(MaterialEnvironmentDesc {
        shader: env.shader,
        intensity: env.intensity,
        depth_exceeded: env.depth_exceeded,
    })
}
