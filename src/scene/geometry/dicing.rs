//! `approximation` and `displacement` of an object: checked, then validated by the
//! tessellator's own rules (rate context, `displace::validate`, the displacement bound).

use std::path::Path;
use std::sync::Arc;

use super::{height_map, num, report};
use crate::components::{
    Approximation, DecodedImage, Displacement, DisplacementMode, ImageContent, ImageMap,
    LengthSpace, ScalarNode, Technique, UvAxis,
};
use crate::scene::desc::{
    ApproximationDesc, AxisDesc, DisplacementDesc, DisplacementModeDesc, ScalarDesc, SpaceDesc,
};
use crate::scene::syntax::Syntax;
use crate::scene::validate::Checker;
use crate::tessellation::displace::{self, Displacer};
use crate::tessellation::rates::{RateContext, MAX_LEVEL};
use crate::tessellation::RasterView;

/// Checks an approximation and builds its component.
pub fn approximation(
    ck: &mut Checker<'_>,
    object: &str,
    path: &str,
    d: &ApproximationDesc,
) -> Option<Approximation> {
    let defaults = Approximation::default();
    let (variant, technique, levels) = match *d {
        ApproximationDesc::Parametric { u, v } => {
            ("Parametric", Technique::Parametric { u, v }, None)
        }
        ApproximationDesc::Regular { u, v } => ("Regular", Technique::Regular { u, v }, None),
        ApproximationDesc::Spatial {
            edge,
            space,
            min_subdiv,
            max_subdiv,
        } => {
            let edge = num(ck, &format!("{path}.Spatial.edge"), "edge", edge)?;
            let space = match space {
                SpaceDesc::Object => LengthSpace::Object,
                SpaceDesc::Raster => LengthSpace::Raster,
            };
            (
                "Spatial",
                Technique::Spatial { edge, space },
                Some((min_subdiv, max_subdiv)),
            )
        }
        ApproximationDesc::Curvature {
            distance,
            angle,
            min_subdiv,
            max_subdiv,
        } => {
            let dp = format!("{path}.Curvature.distance");
            let ap = format!("{path}.Curvature.angle");
            let (distance, angle) = (
                num(ck, &dp, "distance", distance),
                num(ck, &ap, "angle", angle),
            );
            let (distance, angle) = (distance?, angle?);
            if angle < 0.0 && distance >= 0.0 {
                ck.error(
                    &ap,
                    format!("object \"{object}\" (approximation): parameter `angle` = {angle} is out of range (expected ≥ 0)"),
                );
                return None;
            }
            (
                "Curvature",
                Technique::Curvature { distance, angle },
                Some((min_subdiv, max_subdiv)),
            )
        }
    };
    let at = format!("{path}.{variant}");
    let (min_subdiv, max_subdiv) = levels.unwrap_or((defaults.min_subdiv, defaults.max_subdiv));
    if levels.is_some() {
        for (field, level) in [("min_subdiv", min_subdiv), ("max_subdiv", max_subdiv)] {
            if level > MAX_LEVEL {
                ck.error(
                    &format!("{at}.{field}"),
                    format!("{field} must be at most {MAX_LEVEL}, found {level}"),
                );
                return None;
            }
        }
        if min_subdiv > max_subdiv {
            // `.mi` writes the two bounds last in its `approximate` technique.
            let message = if ck.src.syntax(ck.file) == Syntax::Mi {
                format!("the `approximate` statement's min subdivision ({min_subdiv}) must not exceed its max subdivision ({max_subdiv})")
            } else {
                format!("min_subdiv ({min_subdiv}) must not exceed max_subdiv ({max_subdiv})")
            };
            ck.error(&format!("{at}.min_subdiv"), message);
            return None;
        }
    }
    let approx = Approximation {
        technique,
        min_subdiv,
        max_subdiv,
    };
    // The render camera always exists (`render` is required), so a raster view is assumed.
    let view = RasterView {
        camera_from_object: Vec::new(),
        pixels_per_unit: 1.0,
    };
    if let Err(e) = RateContext::new(&approx, Some(&view), (1, 1)) {
        let field = match technique {
            Technique::Spatial { .. } => "edge",
            _ => "distance",
        };
        report(ck, object, "approximation", &at, Some(field), &e);
        return None;
    }
    Some(approx)
}

/// Checks a displacement and builds its component (image maps are read relative to `dir`).
pub fn displacement(
    ck: &mut Checker<'_>,
    dir: &Path,
    object: &str,
    path: &str,
    d: &DisplacementDesc,
) -> Option<Displacement> {
    let shader = scalar(ck, dir, &format!("{path}.shader"), &d.shader);
    let bound = match d.bound {
        Some(b) => Some(num(ck, &format!("{path}.bound"), "bound", b)?),
        None => None,
    };
    let shader = shader?;
    if let Err(e) = displace::validate(&shader) {
        report(
            ck,
            object,
            "displacement",
            &format!("{path}.shader"),
            None,
            &e,
        );
        return None;
    }
    let disp = Displacement {
        shader,
        bound,
        mode: match d.mode {
            DisplacementModeDesc::True => DisplacementMode::True,
            DisplacementModeDesc::Bump => DisplacementMode::Bump,
        },
    };
    if let Err(e) = Displacer::new(&disp) {
        report(ck, object, "displacement", path, Some("bound"), &e);
        return None;
    }
    Some(disp)
}

/// A scalar node tree (numbers checked at their paths; image files decoded).
fn scalar(ck: &mut Checker<'_>, dir: &Path, path: &str, d: &ScalarDesc) -> Option<ScalarNode> {
    match d {
        ScalarDesc::Constant(c) => Some(ScalarNode::Constant(num(
            ck,
            &format!("{path}.Constant[0]"),
            "constant",
            *c,
        )?)),
        ScalarDesc::Sine {
            amplitude,
            factor,
            axis,
        } => {
            let a = num(
                ck,
                &format!("{path}.Sine.amplitude"),
                "amplitude",
                *amplitude,
            );
            let f = num(ck, &format!("{path}.Sine.factor"), "factor", *factor);
            Some(ScalarNode::Sine {
                amplitude: a?,
                factor: f?,
                axis: match axis {
                    AxisDesc::U => UvAxis::U,
                    AxisDesc::V => UvAxis::V,
                },
            })
        }
        ScalarDesc::Noise {
            amplitude,
            frequency,
            octaves,
            lacunarity,
            gain,
            seed,
        } => {
            let mut f = |field: &str, x: f64| num(ck, &format!("{path}.Noise.{field}"), field, x);
            let (a, fr, l, g) = (
                f("amplitude", *amplitude),
                f("frequency", *frequency),
                f("lacunarity", *lacunarity),
                f("gain", *gain),
            );
            Some(ScalarNode::Noise {
                amplitude: a?,
                frequency: fr?,
                octaves: *octaves,
                lacunarity: l?,
                gain: g?,
                seed: *seed,
            })
        }
        ScalarDesc::Image {
            file,
            scale,
            offset,
        } => {
            let s = num(ck, &format!("{path}.Image.scale"), "scale", *scale);
            let o = num(ck, &format!("{path}.Image.offset"), "offset", *offset);
            let full = dir.join(file);
            let file_at = format!("{path}.Image.file");
            let exr = crate::shading::texture::image::is_exr(&full);
            let bytes = std::fs::read(&full).map_err(|e| crate::scene::message::io_reason(&e));
            // Counted against the budget from the header, before anything is decoded.
            let size = bytes
                .as_deref()
                .map_err(Clone::clone)
                .and_then(|b| height_map::footprint(b, exr));
            if let Ok((size, peak)) = size {
                if let Err((message, help)) =
                    ck.src.images.admit(file, size, ImageContent::Heights, peak)
                {
                    ck.src.error(ck.file, &file_at, message, Some(help));
                    return None;
                }
            }
            let read = size.and_then(|_| height_map::decode(&bytes.unwrap_or_default(), exr));
            let img = match read {
                Ok(img) => img,
                Err(e) => {
                    ck.src.error(
                        ck.file,
                        &file_at,
                        format!("cannot read image file \"{}\": {e}", full.display()),
                        Some(
                            "displacement images are PNG files (read as grey 0…1) or EXR files \
                             (heights as stored: Y, a single channel, or the luminance of R, G \
                             and B), relative to the scene file"
                                .into(),
                        ),
                    );
                    return None;
                }
            };
            let (w, h, texels) = (img.width, img.height, img.texels);
            let pos = ck.src.pos(ck.file, &file_at);
            let image = DecodedImage {
                width: w,
                height: h,
                bytes: height_map::held_bytes(w, h),
                content: ImageContent::Heights,
            };
            ck.src.images.list(file, pos, image);
            Some(ScalarNode::Image(ImageMap {
                width: w,
                height: h,
                texels: Arc::new(texels),
                scale: s?,
                offset: o?,
            }))
        }
        ScalarDesc::Sum(xs) | ScalarDesc::Product(xs) => {
            let variant = if matches!(d, ScalarDesc::Sum(_)) {
                "Sum"
            } else {
                "Product"
            };
            let nodes: Vec<Option<ScalarNode>> = xs
                .iter()
                .enumerate()
                .map(|(k, x)| scalar(ck, dir, &format!("{path}.{variant}[0][{k}]"), x))
                .collect();
            let nodes: Option<Vec<ScalarNode>> = nodes.into_iter().collect();
            let nodes = nodes?;
            Some(if variant == "Sum" {
                ScalarNode::Sum(nodes)
            } else {
                ScalarNode::Product(nodes)
            })
        }
    }
}
