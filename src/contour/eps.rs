//! The Encapsulated PostScript writer of contour lines (mental ray's "Contour PS"): the
//! same filled polygons as the SVG ([`super::outline`]), one `fill` per line, coloured per
//! layer and drawn in the stacking order of [`super::stacking`] (as the SVG and the PNG
//! composite), with the image size as `%%BoundingBox` (1 unit = 1 pixel, y up as PostScript
//! wants it). PostScript has no transparency: colours are drawn opaque (alpha ignored).

use std::fmt::Write;

use glam::Vec4;

use super::outline::layer_groups;
use super::ContourImage;

/// Polygon points written per text line (keeps lines under DSC's 255 characters).
const POINTS_PER_LINE: usize = 8;

/// The EPS document of `image`'s lines.
pub fn encode_eps(image: &ContourImage) -> String {
    let (w, h) = (image.width, image.height);
    let mut out = format!(
        "%!PS-Adobe-3.0 EPSF-3.0\n%%Creator: stagelight\n%%Title: contour lines\n\
         %%BoundingBox: 0 0 {w} {h}\n%%LanguageLevel: 1\n%%EndComments\n\
         %%BeginProlog\n/m {{ moveto }} bind def\n/l {{ lineto }} bind def\n\
         /f {{ closepath fill }} bind def\n%%EndProlog\n"
    );
    let height = h as f32;
    for group in layer_groups(image) {
        let _ = writeln!(out, "% material {}", comment_safe(&group.name));
        let _ = writeln!(out, "gsave {} setrgbcolor", rgb(group.color));
        for shape in &group.shapes {
            let own = shape.color != group.color;
            if own {
                let _ = writeln!(out, "gsave {} setrgbcolor", rgb(shape.color));
            }
            for (k, p) in shape.polygon.iter().enumerate() {
                let op = if k == 0 { "m" } else { "l" };
                let sep = if (k + 1) % POINTS_PER_LINE == 0 {
                    '\n'
                } else {
                    ' '
                };
                let _ = write!(out, "{:.3} {:.3} {op}{sep}", p.x, height - p.y);
            }
            out.push_str("f\n");
            if own {
                out.push_str("grestore\n");
            }
        }
        out.push_str("grestore\n");
    }
    out.push_str("showpage\n%%EOF\n");
    out
}

/// `r g b` (0–1) of a linear colour, sRGB-encoded as the PNG and SVG are.
fn rgb(c: Vec4) -> String {
    let u8 = crate::image_io::srgb::to_u8;
    let k = |v: f32| f32::from(u8(v)) / 255.0;
    format!("{:.4} {:.4} {:.4}", k(c.x), k(c.y), k(c.z))
}

/// A name fit for a PostScript comment line (no line breaks or other control characters).
fn comment_safe(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::{ContourLine, ContourPoint};
    use glam::Vec2;

    fn point(x: f32, y: f32) -> ContourPoint {
        ContourPoint {
            pos: Vec2::new(x, y),
            color: Vec4::new(1.0, 0.0, 0.0, 1.0),
            width: 2.0,
        }
    }

    #[test]
    fn one_fill_per_line_with_flipped_y_and_the_image_as_bounding_box() {
        let image = ContourImage {
            width: 20,
            height: 10,
            lines: vec![
                ContourLine {
                    material: 1,
                    closed: false,
                    points: vec![point(2.0, 5.0), point(18.0, 5.0)],
                },
                ContourLine {
                    material: 2,
                    closed: false,
                    points: vec![point(10.0, 1.0), point(10.0, 9.0)],
                },
            ],
            material_names: vec!["ink\nred".into(), "b".into()],
            layer: vec![Vec4::ZERO; 200],
        };
        let eps = encode_eps(&image);
        assert!(eps.starts_with("%!PS-Adobe-3.0 EPSF-3.0\n"));
        assert!(eps.contains("\n%%BoundingBox: 0 0 20 10\n"));
        assert!(eps.ends_with("showpage\n%%EOF\n"));
        assert_eq!(eps.split_whitespace().filter(|t| *t == "f").count(), 2);
        assert!(eps.contains("% material ink?red\n"), "{eps}");
        assert!(eps.contains("gsave 1.0000 0.0000 0.0000 setrgbcolor\n"));
        // The horizontal line at y = 5 (down) of width 2 spans y 4..6 → PostScript 4..6.
        let first = eps
            .lines()
            .find(|l| l.ends_with(" m") || l.contains(" m "))
            .unwrap();
        let mut nums = first.split_whitespace();
        let (x, y): (f32, f32) = (
            nums.next().unwrap().parse().unwrap(),
            nums.next().unwrap().parse().unwrap(),
        );
        assert_eq!(
            (x, y),
            (2.0, 6.0),
            "start point's left side, y flipped: {first}"
        );
        assert!(eps.lines().all(|l| l.len() <= 255));
    }
}
