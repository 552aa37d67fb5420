//! Colour spaces of the shading language's `color "space" (…)` table: RGB, HSV and HSL
//! (hue in [0, 1), as RenderMan writes it), and the sRGB transfer curve for decoding
//! 8-bit textures.

use glam::Vec3;

pub use crate::components::graph::ColourSpace;

/// Converts `c` from `from` to `to` (through RGB).
pub fn convert(c: Vec3, from: ColourSpace, to: ColourSpace) -> Vec3 {
    let rgb = match from {
        ColourSpace::Rgb => c,
        ColourSpace::Hsv => hsv_to_rgb(c),
        ColourSpace::Hsl => hsl_to_rgb(c),
    };
    match to {
        ColourSpace::Rgb => rgb,
        ColourSpace::Hsv => rgb_to_hsv(rgb),
        ColourSpace::Hsl => rgb_to_hsl(rgb),
    }
}

/// Hue in [0, 1) of an RGB colour with maximum `max` and range `d = max − min > 0`.
fn hue(c: Vec3, max: f32, d: f32) -> f32 {
    let h = if max == c.x {
        (c.y - c.z) / d
    } else if max == c.y {
        2.0 + (c.z - c.x) / d
    } else {
        4.0 + (c.x - c.y) / d
    };
    (h / 6.0).rem_euclid(1.0)
}

/// RGB → HSV.
pub fn rgb_to_hsv(c: Vec3) -> Vec3 {
    let max = c.max_element();
    let d = max - c.min_element();
    if d.is_nan() || d <= 0.0 {
        return Vec3::new(0.0, 0.0, max);
    }
    let s = if max > 0.0 { d / max } else { 0.0 };
    Vec3::new(hue(c, max, d), s, max)
}

/// The RGB colour of hue `h` (wrapped to [0, 1)) at full saturation and value.
fn pure_hue(h: f32) -> Vec3 {
    let h = if h.is_finite() {
        h.rem_euclid(1.0)
    } else {
        0.0
    } * 6.0;
    Vec3::new(
        ((h - 3.0).abs() - 1.0).clamp(0.0, 1.0),
        (2.0 - (h - 2.0).abs()).clamp(0.0, 1.0),
        (2.0 - (h - 4.0).abs()).clamp(0.0, 1.0),
    )
}

/// HSV → RGB.
pub fn hsv_to_rgb(c: Vec3) -> Vec3 {
    let (s, v) = (c.y.clamp(0.0, 1.0), c.z);
    v * (Vec3::ONE + s * (pure_hue(c.x) - Vec3::ONE))
}

/// RGB → HSL.
pub fn rgb_to_hsl(c: Vec3) -> Vec3 {
    let max = c.max_element();
    let min = c.min_element();
    let l = 0.5 * (max + min);
    let d = max - min;
    if d.is_nan() || d <= 0.0 {
        return Vec3::new(0.0, 0.0, l);
    }
    let s = d / (1.0 - (2.0 * l - 1.0).abs()).max(1e-12);
    Vec3::new(hue(c, max, d), s, l)
}

/// HSL → RGB.
pub fn hsl_to_rgb(c: Vec3) -> Vec3 {
    let (s, l) = (c.y.clamp(0.0, 1.0), c.z);
    let chroma = (1.0 - (2.0 * l - 1.0).abs()) * s;
    Vec3::splat(l) + chroma * (pure_hue(c.x) - Vec3::splat(0.5))
}

/// sRGB-encoded [0, 1] → linear (IEC 61966-2-1).
pub fn srgb_to_linear(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 {
        0.0
    } else if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x.min(1.0) + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn hsv_table_values() {
        assert!(close(hsv_to_rgb(Vec3::new(0.0, 1.0, 1.0)), Vec3::X));
        assert!(close(hsv_to_rgb(Vec3::new(1.0 / 3.0, 1.0, 1.0)), Vec3::Y));
        assert!(close(hsv_to_rgb(Vec3::new(2.0 / 3.0, 1.0, 1.0)), Vec3::Z));
        assert!(close(
            hsv_to_rgb(Vec3::new(1.0 / 6.0, 0.5, 0.8)),
            Vec3::new(0.8, 0.8, 0.4)
        ));
        assert!(close(
            hsv_to_rgb(Vec3::new(0.3, 0.0, 0.25)),
            Vec3::splat(0.25)
        ));
        // Hue wraps: the seed's `color "hsv" (cosangle*10, 1, 1)` goes round many times.
        assert!(close(
            hsv_to_rgb(Vec3::new(7.5, 1.0, 1.0)),
            Vec3::new(0.0, 1.0, 1.0)
        ));
    }

    #[test]
    fn hsl_table_values() {
        assert!(close(hsl_to_rgb(Vec3::new(0.0, 1.0, 0.5)), Vec3::X));
        assert!(close(
            hsl_to_rgb(Vec3::new(0.5, 1.0, 0.25)),
            Vec3::new(0.0, 0.5, 0.5)
        ));
        assert!(close(
            hsl_to_rgb(Vec3::new(0.9, 0.0, 0.7)),
            Vec3::splat(0.7)
        ));
        assert!(close(
            rgb_to_hsl(Vec3::new(0.75, 0.25, 0.25)),
            Vec3::new(0.0, 0.5, 0.5)
        ));
    }

    #[test]
    fn round_trips() {
        for i in 0..200 {
            let c = Vec3::new(
                (i as f32 * 0.137).fract(),
                (i as f32 * 0.311).fract(),
                (i as f32 * 0.577).fract(),
            );
            for space in [ColourSpace::Hsv, ColourSpace::Hsl] {
                let back = convert(convert(c, ColourSpace::Rgb, space), space, ColourSpace::Rgb);
                assert!(close(back, c), "{space:?} {c} → {back}");
            }
        }
    }

    #[test]
    fn srgb_decode_matches_the_standard() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(0.04045) - 0.04045 / 12.92).abs() < 1e-7);
        // 8-bit 188 is about 50 % linear.
        assert!((srgb_to_linear(188.0 / 255.0) - 0.5029).abs() < 1e-3);
        // Inverse of the encoder used for PNG output.
        for code in [1u8, 17, 64, 118, 200, 254] {
            let lin = srgb_to_linear(code as f32 / 255.0);
            assert_eq!(crate::image_io::srgb::to_u8(lin), code);
        }
    }
}
