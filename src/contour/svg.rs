//! The SVG writer of contour lines: one `<g>` per layer of the stacking order
//! ([`super::stacking`], bottom to top as the PNG composite draws them; a layer is a run of
//! lines of one material: its name as `id`, `name-2`, … for its later layers, its first
//! line's colour as `fill`), each line a filled polygon outlining its varying width (the
//! shapes of [`super::outline`]), in pixel coordinates with the image size as `viewBox`.

use std::fmt::Write;

use glam::Vec4;

use super::outline::layer_groups;
use super::ContourImage;

/// The SVG document of `image`'s lines.
pub fn encode_svg(image: &ContourImage) -> String {
    let (w, h) = (image.width, image.height);
    let mut out = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n"
    );
    for group in layer_groups(image) {
        let id = escape(&group.id);
        let _ = writeln!(out, "<g id=\"{id}\" {}>", paint(group.color));
        for shape in &group.shapes {
            let own = if shape.color == group.color {
                String::new()
            } else {
                format!(" {}", paint(shape.color))
            };
            let mut points = String::new();
            for p in &shape.polygon {
                let _ = write!(points, "{:.3},{:.3} ", p.x, p.y);
            }
            let _ = writeln!(out, "<polygon{own} points=\"{}\"/>", points.trim_end());
        }
        out.push_str("</g>\n");
    }
    out.push_str("</svg>\n");
    out
}

/// `fill` and `fill-opacity` of a linear RGBA colour (sRGB-encoded).
fn paint(c: Vec4) -> String {
    let u8 = crate::image_io::srgb::to_u8;
    format!(
        "fill=\"#{:02x}{:02x}{:02x}\" fill-opacity=\"{:.3}\"",
        u8(c.x),
        u8(c.y),
        u8(c.z),
        c.w.clamp(0.0, 1.0)
    )
}

/// XML-escapes a name for an attribute.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
