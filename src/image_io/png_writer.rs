//! PNG encoding of the beauty pass (8-bit sRGB, RGB or RGBA with straight alpha) and of the
//! alpha pass alone (8-bit grey).

use glam::Vec3;

use crate::components::Imager;
use crate::framebuffer::FrameBuffers;
use crate::image_io::png_codec::{self, PngLayout};
use crate::image_io::srgb::to_u8;

/// Encodes the beauty pass as PNG; with `alpha` the coverage goes into the alpha channel.
/// An imager (background, exposure, tone map, gamma) replaces the plain sRGB encoding.
///
/// The frame buffer's colour is premultiplied by coverage (as in EXR); PNG's alpha is
/// straight (unassociated, PNG specification §3.3 "alpha channel"), so with `alpha` a partly
/// covered pixel's colour is divided by its alpha before it is encoded — otherwise every
/// viewer composites dark fringes. Pixels of alpha 0 (the environment, nothing) keep their
/// colour; opaque pixels are unchanged.
pub fn encode_png(
    fb: &FrameBuffers,
    alpha: bool,
    imager: Option<&Imager>,
) -> Result<Vec<u8>, String> {
    let channels = if alpha { 4 } else { 3 };
    let mut data = Vec::with_capacity(fb.beauty.len() * channels);
    let quantize = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    for (i, c) in fb.beauty.iter().enumerate() {
        let straight = |c: Vec3, a: f32| if alpha { unpremultiply(c, a) } else { c };
        let a = match imager {
            Some(im) => {
                let (c, a) = im.composite(*c, fb.alpha[i]);
                let c = straight(c, a);
                data.extend_from_slice(&[c.x, c.y, c.z].map(|v| quantize(im.encode(v))));
                a
            }
            None => {
                let c = straight(*c, fb.alpha[i]);
                data.extend_from_slice(&[to_u8(c.x), to_u8(c.y), to_u8(c.z)]);
                fb.alpha[i]
            }
        };
        if alpha {
            data.push(quantize(a));
        }
    }
    let layout = if alpha {
        PngLayout::Rgba8
    } else {
        PngLayout::Rgb8
    };
    png_codec::encode_png(&data, fb.width, fb.height, layout)
}

/// Encodes the alpha pass alone as an 8-bit grey PNG (coverage 0…1 → 0…255, linear: alpha is
/// not a colour and is never sRGB-encoded).
pub fn encode_alpha_png(fb: &FrameBuffers) -> Result<Vec<u8>, String> {
    let data: Vec<u8> = fb
        .alpha
        .iter()
        .map(|a| (a.clamp(0.0, 1.0) * 255.0 + 0.5) as u8)
        .collect();
    png_codec::encode_png(&data, fb.width, fb.height, PngLayout::Grey8)
}

/// The straight colour of a premultiplied pixel of coverage `a`: `c / a` for `0 < a < 1`,
/// `c` otherwise.
fn unpremultiply(c: Vec3, a: f32) -> Vec3 {
    if a > 0.0 && a < 1.0 {
        c / a
    } else {
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::png_codec::{decode_png, Samples};

    fn one_pixel(c: Vec3, a: f32) -> FrameBuffers {
        let mut fb = FrameBuffers::new(1, 1);
        fb.beauty[0] = c;
        fb.alpha[0] = a;
        fb
    }

    fn bytes(png: Vec<u8>) -> (usize, Vec<u8>) {
        let d = decode_png(&png).unwrap();
        match d.samples {
            Samples::Eight(s) => (d.channels, s),
            Samples::Sixteen(_) => panic!("16-bit"),
        }
    }

    #[test]
    fn a_half_covered_pixel_is_written_with_its_straight_colour() {
        // Half of the pixel covered by a surface of linear 0.5: premultiplied 0.25.
        let fb = one_pixel(Vec3::splat(0.25), 0.5);
        let half = to_u8(0.5);
        assert_eq!(
            bytes(encode_png(&fb, true, None).unwrap()),
            (4, vec![half, half, half, 128])
        );
        // Without an alpha channel the pixel is what a black background shows.
        let quarter = to_u8(0.25);
        assert_eq!(
            bytes(encode_png(&fb, false, None).unwrap()),
            (3, vec![quarter; 3])
        );
    }

    #[test]
    fn uncovered_and_opaque_pixels_keep_their_colour() {
        let c = Vec3::new(0.2, 0.3, 0.4);
        for a in [0.0, 1.0] {
            let (_, s) = bytes(encode_png(&one_pixel(c, a), true, None).unwrap());
            assert_eq!(s[..3], [to_u8(0.2), to_u8(0.3), to_u8(0.4)]);
        }
    }

    #[test]
    fn the_alpha_pass_alone_is_a_linear_grey_image() {
        let png = encode_alpha_png(&one_pixel(Vec3::ONE, 0.5)).unwrap();
        assert_eq!(bytes(png), (1, vec![128]));
    }
}
