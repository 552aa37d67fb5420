//! mental ray's contour library (`contour.so`) mapped onto the contour stage
//! (`docs/scene-format.md`, *Contours*): the options' `contour store` and `contour
//! contrast` functions become `options.contours`, a material's `contour` shader its
//! `contour:` shader, and a camera's `output "contour" "ps"|"eps" "file"` an `Eps` output of
//! the `Contours` pass.
//!
//! | `.mi` | RON |
//! | --- | --- |
//! | `contour store "contour_store_function" ()` | `contours: (…)` present |
//! | `contour contrast "contour_contrast_function_levels" (…)` | `contrast`: `ndelta` → `normal_angle` (degrees), `diff_mat` → `material`, `diff_label` → `object`, `diff_index` → `instance`, `max_level` → `ray_depth` (`max_level − 1`; outside 1 … 9 the nearest, with a warning) |
//! | `contour_shader_simple ("color", "width")` | `Simple(color, width)` |
//! | `contour_shader_depthfade ("near_z", "far_z", "near_color", "far_color", "near_width", "far_width")` | `DepthFade` (distances as positive numbers) |
//! | `contour_shader_curvature ("color", "min_width", "max_width")` | `Curvature` |
//! | `contour_shader_factorcolor ("factor", "width")` | `FactorColor` |
//! | `contour_shader_widthfromlight ("color", "min_width", "max_width")` | `WidthFromLight(dark_width: max_width, lit_width: min_width)` |
//! | `contour_shader_widthfromcolor ("color", "min_width", "max_width")` | `WidthFromLight(dark_width: max_width, lit_width: min_width)`: thick where the material's colour is dark |
//! | `contour_shader_silhouette ("color", "width")` | `Silhouette(color, width)`: the outline only |
//! | `contour_shader_layerthinner ("color", "width", "factor")` | `Layered(color, width, thinning: factor)` |
//! | `contour_shader_framefade ("frame1", "frame2", "color1", "color2", "width1", "width2")` | `Simple`, colour and width interpolated linearly at the render camera's `frame` (clamped to the two frames) |
//!
//! `zdelta` (an absolute depth step; ours is relative) warns and keeps the default.

use super::super::located::{Pos, Problem};
use super::cursor::{Cursor, ShaderCall, Value};
use super::lexer::{Tok, Token};
use super::model::FrameFade;
use super::value_positions::ValuePositions;
use crate::scene::desc::{ContourDesc, ContoursDesc, OptionsDesc};
use crate::scene::desc_contour::V4;
use crate::scene::suggest::closest;

const STORE: &[&str] = &["contour_store_function", "contour_store_function_simple"];
const CONTRAST: &[&str] = &[
    "contour_contrast_function_levels",
    "contour_contrast_function_simple",
];
const SHADERS: &[&str] = &[
    "contour_shader_simple",
    "contour_shader_depthfade",
    "contour_shader_curvature",
    "contour_shader_factorcolor",
    "contour_shader_widthfromlight",
    "contour_shader_widthfromcolor",
    "contour_shader_silhouette",
    "contour_shader_layerthinner",
    "contour_shader_framefade",
];

fn unknown(c: &mut Cursor, call: &ShaderCall, what: &str, known: &[&str]) {
    let mut p = Problem::error(call.pos, format!("unknown {what} \"{}\"", call.name));
    p = match closest(&call.name, known.iter().copied()) {
        Some(s) => p.with_help(format!("did you mean \"{s}\"?")),
        None => p.with_help(format!("built in: {}", known.join(", "))),
    };
    c.report(p);
}

fn number(c: &mut Cursor, call: &ShaderCall, name: &str, default: f64) -> f64 {
    let Some(p) = call.params.iter().rev().find(|p| p.name == name) else {
        return default;
    };
    match &p.value {
        Value::Nums(n) if n.len() == 1 => n[0],
        Value::Bool(b) => f64::from(u8::from(*b)),
        _ => {
            c.error(
                p.value_pos,
                format!("parameter \"{name}\" of \"{}\" takes a number", call.name),
            );
            default
        }
    }
}

fn colour(c: &mut Cursor, call: &ShaderCall, name: &str) -> V4 {
    let Some(p) = call.params.iter().rev().find(|p| p.name == name) else {
        return (0.0, 0.0, 0.0, 1.0);
    };
    match &p.value {
        Value::Nums(n) if n.len() == 4 => (n[0], n[1], n[2], n[3]),
        Value::Nums(n) if n.len() == 3 => (n[0], n[1], n[2], 1.0),
        _ => {
            c.error(
                p.value_pos,
                format!(
                    "parameter \"{name}\" of \"{}\" takes a color (4 numbers)",
                    call.name
                ),
            );
            (0.0, 0.0, 0.0, 1.0)
        }
    }
}

/// `contour store "function" (…)` or `contour contrast "function" (…)` in `options`; where
/// their values were written goes to `values` (below `options`).
pub fn option(c: &mut Cursor, at: Pos, desc: &mut OptionsDesc, values: &mut ValuePositions) {
    let store = c.eat_word("store");
    if !store && !c.eat_word("contrast") {
        let (pos, found) = match c.peek() {
            Some(t) => (t.pos, t.tok.describe()),
            None => (at, "the end of the file".to_string()),
        };
        let mut p = Problem::error(
            pos,
            format!("expected \"store\" or \"contrast\" after \"contour\", found {found}"),
        );
        if let Some(Token {
            tok: Tok::Word(w), ..
        }) = c.peek()
        {
            if let Some(s) = closest(w, ["store", "contrast"]) {
                p = p.with_help(format!("did you mean \"{s}\"?"));
            }
            c.advance();
            // The function that follows belongs to the misspelt statement.
            if c.at_string() {
                let _ = c.shader_call("the contour function");
            }
        }
        c.report(p);
        return;
    }
    let Some(call) = c.shader_call("the contour function") else {
        return;
    };
    let contours = desc.contours.get_or_insert_with(ContoursDesc::default);
    let whole = if store {
        ".contours"
    } else {
        ".contours.contrast"
    };
    if values.get(".contours").is_none() {
        values.record(".contours", c.located(call.pos));
    }
    super::param_paths::record(c, &call, Some(whole), values);
    if store {
        if !STORE.contains(&call.name.as_str()) {
            unknown(c, &call, "contour store function", STORE);
        }
        return;
    }
    if !CONTRAST.contains(&call.name.as_str()) {
        unknown(c, &call, "contour contrast function", CONTRAST);
        return;
    }
    let k = &mut contours.contrast;
    k.normal_angle = number(c, &call, "ndelta", k.normal_angle);
    k.material = number(c, &call, "diff_mat", f64::from(u8::from(k.material))) != 0.0;
    k.object = number(c, &call, "diff_label", f64::from(u8::from(k.object))) != 0.0;
    k.instance = number(c, &call, "diff_index", f64::from(u8::from(k.instance))) != 0.0;
    let levels = number(c, &call, "max_level", 1.0);
    let used = levels.clamp(1.0, 9.0).floor();
    if used != levels {
        if let Some(p) = call.params.iter().rev().find(|p| p.name == "max_level") {
            c.warn(
                p.value_pos,
                format!(
                    "\"max_level\" {levels} is read as {used}: contours follow 1 to 9 levels (the first hit and up to 8 mirror, refraction or transparency levels behind it; RON `ray_depth` 0 to 8)"
                ),
            );
        }
    }
    contours.ray_depth = (used - 1.0) as u32;
    if let Some(p) = call.params.iter().find(|p| p.name == "zdelta") {
        c.warn(
            p.pos,
            "\"zdelta\" is an absolute depth step; the relative depth threshold (0.25) is used",
        );
    }
}

/// A material's `contour "shader" (…)`.
pub fn material_shader(c: &mut Cursor, call: &ShaderCall) -> Option<ContourDesc> {
    let width = |c: &mut Cursor, name: &str, default: f64| number(c, call, name, default);
    Some(match call.name.as_str() {
        "contour_shader_simple" => ContourDesc::Simple {
            color: colour(c, call, "color"),
            width: width(c, "width", 0.5),
        },
        "contour_shader_depthfade" => ContourDesc::DepthFade {
            near: width(c, "near_z", 0.0).abs(),
            far: width(c, "far_z", 1.0).abs(),
            near_color: colour(c, call, "near_color"),
            far_color: colour(c, call, "far_color"),
            near_width: width(c, "near_width", 1.0),
            far_width: width(c, "far_width", 0.25),
        },
        "contour_shader_curvature" => ContourDesc::Curvature {
            color: colour(c, call, "color"),
            min_width: width(c, "min_width", 0.1),
            max_width: width(c, "max_width", 1.0),
        },
        "contour_shader_factorcolor" => ContourDesc::FactorColor {
            factor: width(c, "factor", 0.5),
            width: width(c, "width", 0.5),
        },
        "contour_shader_silhouette" => ContourDesc::Silhouette {
            color: colour(c, call, "color"),
            width: width(c, "width", 0.5),
        },
        "contour_shader_layerthinner" => ContourDesc::Layered {
            color: colour(c, call, "color"),
            width: width(c, "width", 0.5),
            thinning: width(c, "factor", 0.5),
        },
        "contour_shader_widthfromlight" | "contour_shader_widthfromcolor" => {
            ContourDesc::WidthFromLight {
                color: colour(c, call, "color"),
                dark_width: width(c, "max_width", 1.0),
                lit_width: width(c, "min_width", 0.25),
            }
        }
        _ => {
            unknown(c, call, "contour shader", SHADERS);
            return None;
        }
    })
}

/// A material's `contour "contour_shader_framefade" (…)`, kept until the render frame is
/// known; `None` for any other contour shader.
pub fn frame_fade(c: &mut Cursor, call: &ShaderCall) -> Option<FrameFade> {
    if call.name != "contour_shader_framefade" {
        return None;
    }
    let frame1 = number(c, call, "frame1", 0.0);
    let frame2 = number(c, call, "frame2", 0.0);
    Some(FrameFade {
        frame1,
        frame2,
        color1: colour(c, call, "color1"),
        color2: colour(c, call, "color2"),
        width1: number(c, call, "width1", 0.5),
        width2: number(c, call, "width2", 0.5),
    })
}

/// The `Simple` contour a frame fade draws at frame `frame`: `t = (frame − frame1) /
/// (frame2 − frame1)` clamped to [0, 1] (0 when the frames are equal), colour and width
/// linear in `t`.
pub fn faded(f: &FrameFade, frame: f64) -> ContourDesc {
    let span = f.frame2 - f.frame1;
    let t = if span == 0.0 {
        0.0
    } else {
        ((frame - f.frame1) / span).clamp(0.0, 1.0)
    };
    let mix = |a: f64, b: f64| a + (b - a) * t;
    ContourDesc::Simple {
        color: (
            mix(f.color1.0, f.color2.0),
            mix(f.color1.1, f.color2.1),
            mix(f.color1.2, f.color2.2),
            mix(f.color1.3, f.color2.3),
        ),
        width: mix(f.width1, f.width2),
    }
}
