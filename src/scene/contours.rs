//! Checks contours in a scene: each material's `contour:` shader, the options' `contours:
//! (contrast: …)`, SVG outputs, and that contour shaders and contour outputs come together
//! (an SVG or `Contours` output without any contour shader is an error; a contour shader
//! that no output shows is a warning).

use std::path::PathBuf;

use glam::Vec4;

use super::checker::{Checker, Item};
use super::desc::{CameraDesc, MaterialDesc, OptionsDesc, OutputDesc, PassDesc};
use super::desc_contour::{ContourDesc, V4};
use super::diagnostics::{Diagnostic, Sources};
use super::syntax::Syntax;
use crate::components::{ContourContrast, ContourShader, ImageFormat, OutputSpec, Pass};

/// The contour shader of a material, if it has a valid one (errors recorded otherwise).
pub fn contour(src: &mut Sources, item: &Item<'_, MaterialDesc>) -> Option<ContourShader> {
    let d = item.desc.contour.as_ref()?;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let base = item.at(".contour");
    let colours_ok = std::cell::Cell::new(true);
    let colour = |ck: &mut Checker<'_>, variant: &str, name: &str, c: V4| -> Vec4 {
        let path = format!("{base}.{variant}.{name}");
        let v = [c.0, c.1, c.2, c.3];
        for (k, x) in v.iter().enumerate() {
            let p = format!("{path}[{k}]");
            if !ck.finite(&p, name, *x) {
                colours_ok.set(false);
            } else if *x < 0.0 || (k == 3 && *x > 1.0) {
                let range = if k == 3 { "in [0, 1]" } else { "non-negative" };
                ck.error(&p, format!("{name} must be {range}, found {x}"));
                colours_ok.set(false);
            }
        }
        Vec4::new(c.0 as f32, c.1 as f32, c.2 as f32, c.3 as f32)
    };
    let mut ok = true;
    // A `.mi` contour shader's own parameter names, for the messages about its values.
    let syntax = ck.src.syntax(ck.file);
    let (variant, shader) = match *d {
        ContourDesc::Simple { color, width } => (
            "Simple",
            ContourShader::Simple {
                color: colour(&mut ck, "Simple", "color", color),
                width: width as f32,
            },
        ),
        ContourDesc::Silhouette { color, width } => (
            "Silhouette",
            ContourShader::Silhouette {
                color: colour(&mut ck, "Silhouette", "color", color),
                width: width as f32,
            },
        ),
        ContourDesc::DepthFade {
            near,
            far,
            near_color,
            far_color,
            near_width,
            far_width,
        } => {
            let v = "DepthFade";
            let (near_name, far_name) = (
                syntax.named("near", "near_z", "near"),
                syntax.named("far", "far_z", "far"),
            );
            let mut distances_ok = ck
                .non_negative(&format!("{base}.{v}.near"), near_name, near)
                .is_some();
            distances_ok &= ck.finite(&format!("{base}.{v}.far"), far_name, far);
            if distances_ok && far <= near {
                // `.mi` depths are camera-space z (negative in front): compared as distances.
                let message = if syntax == Syntax::Mi {
                    format!("far_z must lie farther from the camera than near_z (distance {near}), found distance {far}")
                } else {
                    format!("far must be greater than near ({near}), found {far}")
                };
                ck.error(&format!("{base}.{v}.far"), message);
                distances_ok = false;
            }
            ok &= distances_ok;
            (
                v,
                ContourShader::DepthFade {
                    near: near as f32,
                    far: far as f32,
                    near_color: colour(&mut ck, v, "near_color", near_color),
                    far_color: colour(&mut ck, v, "far_color", far_color),
                    near_width: near_width as f32,
                    far_width: far_width as f32,
                },
            )
        }
        ContourDesc::Curvature {
            color,
            min_width,
            max_width,
        } => (
            "Curvature",
            ContourShader::Curvature {
                color: colour(&mut ck, "Curvature", "color", color),
                min_width: min_width as f32,
                max_width: max_width as f32,
            },
        ),
        ContourDesc::FactorColor { factor, width } => {
            let p = format!("{base}.FactorColor.factor");
            ok &= ck.non_negative(&p, "factor", factor).is_some();
            (
                "FactorColor",
                ContourShader::FactorColor {
                    factor: factor as f32,
                    width: width as f32,
                },
            )
        }
        ContourDesc::WidthFromLight {
            color,
            dark_width,
            lit_width,
        } => (
            "WidthFromLight",
            ContourShader::WidthFromLight {
                color: colour(&mut ck, "WidthFromLight", "color", color),
                dark_width: dark_width as f32,
                lit_width: lit_width as f32,
            },
        ),
        ContourDesc::Layered {
            color,
            width,
            thinning,
        } => {
            let p = format!("{base}.Layered.thinning");
            let name = syntax.named("thinning", "factor", "thinning");
            if ck.finite(&p, name, thinning) && !(thinning > 0.0 && thinning <= 1.0) {
                ck.error(&p, format!("{name} must be in (0, 1], found {thinning}"));
                ok = false;
            }
            (
                "Layered",
                ContourShader::Layered {
                    color: colour(&mut ck, "Layered", "color", color),
                    width: width as f32,
                    thinning: thinning as f32,
                },
            )
        }
    };
    let mut ok = colours_ok.get() && ok;
    for (field, mi, w) in width_fields(d) {
        let path = format!("{base}.{variant}.{field}");
        let name = syntax.named(field, mi, field);
        if !ck.finite(&path, name, w) {
            ok = false;
        } else if w <= 0.0 {
            let help = ck.src.syntax(ck.file).help(
                "widths are in percent of the smaller image dimension, e.g. `width: 0.5`; to draw no contours, leave out `contour`",
                "widths are in percent of the smaller image dimension, e.g. `\"width\" 0.5`; to draw no contours, leave out the material's `contour` shader",
            );
            ck.src.error(
                ck.file,
                &path,
                format!("contour {name} must be positive, found {w}"),
                Some(help),
            );
            ok = false;
        } else if w > 100.0 {
            ck.error(
                &path,
                format!("contour {name} must be at most 100 (percent), found {w}"),
            );
            ok = false;
        }
    }
    ok.then_some(shader)
}

/// The width fields of a contour shader: the field, the `.mi` shader parameter that sets it
/// (`contour_shader_widthfromlight`'s `"max_width"` is the width where it is dark) and
/// the value.
fn width_fields(d: &ContourDesc) -> Vec<(&'static str, &'static str, f64)> {
    match *d {
        ContourDesc::Simple { width, .. }
        | ContourDesc::Silhouette { width, .. }
        | ContourDesc::FactorColor { width, .. }
        | ContourDesc::Layered { width, .. } => vec![("width", "width", width)],
        ContourDesc::DepthFade {
            near_width,
            far_width,
            ..
        } => vec![
            ("near_width", "near_width", near_width),
            ("far_width", "far_width", far_width),
        ],
        ContourDesc::Curvature {
            min_width,
            max_width,
            ..
        } => vec![
            ("min_width", "min_width", min_width),
            ("max_width", "max_width", max_width),
        ],
        ContourDesc::WidthFromLight {
            dark_width,
            lit_width,
            ..
        } => vec![
            ("dark_width", "max_width", dark_width),
            ("lit_width", "min_width", lit_width),
        ],
    }
}

/// Most mirror/refraction levels contours are drawn through (`contours.ray_depth`).
pub const MAX_RAY_DEPTH: u32 = 8;

/// The contour contrast of `options` (defaults without them).
pub fn contrast(src: &mut Sources, options: Option<&Item<'_, OptionsDesc>>) -> ContourContrast {
    let Some((item, contours)) = options.and_then(|o| o.desc.contours.map(|c| (o, c))) else {
        return ContourContrast::default();
    };
    let c = contours.contrast;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let path = item.at(".contours.contrast");
    let angle = format!("{path}.normal_angle");
    let name = ck
        .src
        .syntax(ck.file)
        .named("normal_angle", "ndelta", "normal_angle");
    if ck.finite(&angle, name, c.normal_angle) && !(c.normal_angle > 0.0 && c.normal_angle <= 180.0)
    {
        ck.error(
            &angle,
            format!(
                "{name} must be in (0, 180] degrees, found {}",
                c.normal_angle
            ),
        );
    }
    let depth = format!("{path}.depth");
    if let Some(d) = c.depth {
        if ck.finite(&depth, "depth", d) && d <= 0.0 {
            ck.src.error(
                ck.file,
                &depth,
                format!("depth must be positive (a fraction of the nearer depth), found {d}"),
                Some("for no contours at depth jumps, write `depth: None`".into()),
            );
        }
    }
    if contours.ray_depth > MAX_RAY_DEPTH {
        ck.error(
            &item.at(".contours.ray_depth"),
            format!(
                "contour ray_depth must be at most {MAX_RAY_DEPTH}, found {}",
                contours.ray_depth
            ),
        );
    }
    ContourContrast {
        ray_depth: contours.ray_depth.min(MAX_RAY_DEPTH),
        instance: c.instance,
        object: c.object,
        material: c.material,
        normal_angle: c.normal_angle as f32,
        depth: c.depth.map(|d| d as f32),
        background: c.background,
    }
}

/// A contrast with every criterion off while some material has a contour shader: no line
/// can be drawn (`draw_contours` is skipped, contour-only outputs are not written), a
/// warning at `contours.contrast`.
pub fn check_contrast_off(
    src: &mut Sources,
    options: Option<&Item<'_, OptionsDesc>>,
    materials: &[Item<'_, MaterialDesc>],
    contrast: &ContourContrast,
) {
    let Some(item) = options.filter(|o| o.desc.contours.is_some()) else {
        return;
    };
    if contrast.any_on() || !materials.iter().any(|m| m.desc.contour.is_some()) {
        return;
    }
    let pos = src.pos(item.file, &item.at(".contours.contrast"));
    src.push_warning(
        item.file,
        Diagnostic::at(
            pos,
            "every contour contrast criterion is off: no contour lines are drawn, and SVG and EPS outputs are not written",
            Some("turn one on, e.g. `background: true`; to draw no contours, leave out the materials' `contour` shaders".into()),
        ),
    );
}

/// An SVG or EPS output (`format`): it holds the contour lines only (`passes`, if given, is
/// `[Contours]`).
pub fn vector_output(
    ck: &mut Checker<'_>,
    path: &str,
    o: &OutputDesc,
    format: ImageFormat,
) -> Option<OutputSpec> {
    if let Some(passes) = &o.passes {
        if passes.as_slice() != [PassDesc::Contours] {
            ck.src.error(
                ck.file,
                &format!("{path}.passes"),
                format!(
                    "an {} output holds only the contour lines",
                    if format == ImageFormat::Eps {
                        "EPS"
                    } else {
                        "SVG"
                    }
                ),
                Some("leave out `passes`, or write `passes: [Contours]`".into()),
            );
            return None;
        }
    }
    Some(OutputSpec {
        path: PathBuf::from(&o.file),
        format,
        passes: vec![Pass::Contours],
        beauty_alpha: true,
    })
}

/// Whether an output shows contours (an SVG or EPS, or a `Contours` pass).
fn shows_contours(o: &OutputDesc) -> bool {
    use super::desc::FormatDesc;
    let svg = matches!(o.format, Some(FormatDesc::Svg | FormatDesc::Eps))
        || (o.format.is_none()
            && std::path::Path::new(&o.file)
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("svg") || e.eq_ignore_ascii_case("eps")));
    svg || o
        .passes
        .as_ref()
        .is_some_and(|p| p.contains(&PassDesc::Contours))
}

/// Contour outputs need a contour shader (errors). Returns whether some output shows
/// contours, for [`warn_unshown_shaders`].
pub fn check_pairing(
    src: &mut Sources,
    cameras: &[Item<'_, CameraDesc>],
    materials: &[Item<'_, MaterialDesc>],
) -> bool {
    let shaders = materials.iter().any(|m| m.desc.contour.is_some());
    let mut shown = false;
    for c in cameras {
        for (k, o) in c.desc.outputs.iter().enumerate() {
            if !shows_contours(o) {
                continue;
            }
            shown = true;
            if !shaders {
                let help = src.syntax(c.file).help(
                    "give a material a contour shader, e.g. `contour: Simple(color: (0, 0, 0, 1), width: 0.5)`",
                    "give a material a contour shader, e.g. `contour \"contour_shader_simple\" (\"color\" 0 0 0 1, \"width\" 0.5)`",
                );
                src.error(
                    c.file,
                    &c.at(&format!(".outputs[{k}].file")),
                    format!(
                        "output \"{}\" shows contours, but no material has a contour shader",
                        o.file
                    ),
                    Some(help),
                );
            }
        }
    }
    shown
}

/// Contour shaders need an output that shows them: when none does (`shown` false), a
/// warning at each shader, saying why it draws nothing — its material placed by no instance
/// (`used[k]` false for material `k`), else no camera output showing contours.
pub fn warn_unshown_shaders(
    src: &mut Sources,
    materials: &[Item<'_, MaterialDesc>],
    shown: bool,
    used: &[bool],
) {
    if shown {
        return;
    }
    for (k, m) in materials.iter().enumerate() {
        if m.desc.contour.is_none() {
            continue;
        }
        let pos = src.pos(m.file, &m.at(".contour"));
        let name = &m.desc.name;
        let (message, help) = if used.get(k).copied().unwrap_or(true) {
            (
                format!(
                    "material \"{name}\" has a contour shader, but no camera output shows contours"
                ),
                src.syntax(m.file).help(
                    "add an output such as `(file: \"lines.svg\")` or a `Contours` pass",
                    "add a camera output such as `output \"contour\" \"ps\" \"lines.ps\"`",
                ),
            )
        } else {
            (
                format!("material \"{name}\" has a contour shader, but no instance uses the material: its contours are never drawn"),
                format!("contours are drawn around the objects placed with a material; place one with \"{name}\", or leave out its contour shader"),
            )
        };
        src.push_warning(m.file, Diagnostic::at(pos, message, Some(help)));
    }
}
