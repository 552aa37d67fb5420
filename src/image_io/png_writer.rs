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
/// The frame buffer's colour is premultiplied by coverage (as in EXR) and, where camera
/// samples missed every surface, holds the environment they saw:
/// `c = surface·a + environment·(1 − a)`. PNG's alpha is straight (unassociated, PNG
/// specification §3.3 "alpha channel"), so with `alpha` a partly covered pixel is written
/// with its surfaces' own colour `(c − E) / a`, `E` its environment share
/// ([`FrameBuffers::environment`], zero where the buffers keep none) — the viewer composites
/// its own background behind it; dividing `c` alone would leave a halo of the environment's
/// colour around every silhouette, and not dividing, dark fringes. Pixels of alpha 0 (the
/// environment, nothing) keep their colour; opaque pixels are unchanged. An imager's
/// `background` replaces the environment the same way: it is composited behind `c − E`.
/// An imager's `pattern` replaces every pixel: its colour is written as display values
/// (RenderMan runs the imager after exposure, so gain, tone map and gamma do not apply) with
/// alpha 1.
pub fn encode_png(
    fb: &FrameBuffers,
    alpha: bool,
    imager: Option<&Imager>,
) -> Result<Vec<u8>, String> {
    let channels = if alpha { 4 } else { 3 };
    let mut data = Vec::with_capacity(fb.beauty.len() * channels);
    let quantize = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    let background = imager.and_then(|im| im.background).is_some();
    let environment = |i: usize| fb.environment.as_ref().map_or(Vec3::ZERO, |e| e[i]);
    for (i, c) in fb.beauty.iter().enumerate() {
        let straight = |c: Vec3, a: f32| if alpha { unpremultiply(c, a) } else { c };
        let a = fb.alpha[i];
        // What is composited over a background (the imager's, or the viewer's): the
        // surfaces' share, without the environment the missed samples saw.
        let over = |c: Vec3| {
            if background || (alpha && a > 0.0 && a < 1.0) {
                c - environment(i)
            } else {
                c
            }
        };
        let a = match imager {
            Some(Imager {
                pattern: Some(pattern),
                ..
            }) => {
                // The imager's pattern replaces the pixel: display values, alpha 1.
                let (x, y) = (i % fb.width as usize, i / fb.width as usize);
                let c = pattern.paint(x as u32, y as u32, fb.width, fb.height);
                data.extend_from_slice(&[c.x, c.y, c.z].map(quantize));
                1.0
            }
            Some(im) => {
                let (c, a) = im.composite(over(*c), a);
                let c = straight(c, a);
                data.extend_from_slice(&[c.x, c.y, c.z].map(|v| quantize(im.encode(v))));
                a
            }
            None => {
                let c = straight(over(*c), a);
                data.extend_from_slice(&[to_u8(c.x), to_u8(c.y), to_u8(c.z)]);
                a
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
    fn the_environment_share_is_left_out_of_a_partly_covered_pixels_straight_colour() {
        // A quarter of the pixel covered by a surface of 0.2, the rest sees an environment
        // of 1: c = 0.2·0.25 + 1·0.75, E = 0.75, straight colour 0.2 (not c / a = 3.2).
        let mut fb = one_pixel(Vec3::splat(0.8), 0.25);
        fb.environment = Some(vec![Vec3::splat(0.75)]);
        let (_, s) = bytes(encode_png(&fb, true, None).unwrap());
        assert_eq!(s, vec![to_u8(0.2), to_u8(0.2), to_u8(0.2), 64]);
        // Without an alpha channel the environment stays behind the surface.
        let (_, s) = bytes(encode_png(&fb, false, None).unwrap());
        assert_eq!(s, vec![to_u8(0.8); 3]);
        // An imager background replaces the environment: 0.05 + 0.75·0.4.
        let imager = Imager {
            background: Some(Vec3::splat(0.4)),
            gamma: Some(1.0),
            ..Imager::default()
        };
        let (_, s) = bytes(encode_png(&fb, true, Some(&imager)).unwrap());
        let v = (0.35f32 * 255.0 + 0.5) as u8;
        assert_eq!(s, vec![v, v, v, 255]);
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
    fn an_imager_pattern_replaces_every_pixel_with_display_values_and_alpha_one() {
        // 2 × 1, nothing covered: the disk of radius 0.3 around (0.25, 0.5) covers the
        // left pixel's centre (0.25, 0.5), not the right one's (0.75, 0.5).
        let fb = FrameBuffers::new(2, 1);
        let imager = Imager {
            gain: 4.0,
            gamma: Some(2.2),
            pattern: Some(crate::components::ImagerPattern::Disk {
                center: glam::Vec2::new(0.25, 0.5),
                radius: 0.3,
                fuzz: 0.0,
                inside: Vec3::new(1.0, 1.0, 0.0),
                outside: Vec3::new(0.5, 0.0, 0.0),
            }),
            ..Imager::default()
        };
        let (_, s) = bytes(encode_png(&fb, true, Some(&imager)).unwrap());
        assert_eq!(s, vec![255, 255, 0, 255, 128, 0, 0, 255]);
    }

    #[test]
    fn the_alpha_pass_alone_is_a_linear_grey_image() {
        let png = encode_alpha_png(&one_pixel(Vec3::ONE, 0.5)).unwrap();
        assert_eq!(bytes(png), (1, vec![128]));
    }
}
