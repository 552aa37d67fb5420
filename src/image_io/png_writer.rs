//! PNG encoding of the beauty pass (8-bit sRGB, RGB or RGBA), or of the alpha pass alone
//! (8-bit grey, linear coverage).

use crate::components::Imager;
use crate::framebuffer::FrameBuffers;
use crate::image_io::png_codec::{self, PngLayout};
use crate::image_io::srgb::to_u8;

/// Encodes the beauty pass as PNG; with `alpha` the coverage goes into the alpha channel.
/// An imager (background, exposure, tone map, gamma) replaces the plain sRGB encoding.
pub fn encode_png(
    fb: &FrameBuffers,
    alpha: bool,
    imager: Option<&Imager>,
) -> Result<Vec<u8>, String> {
    let channels = if alpha { 4 } else { 3 };
    let mut data = Vec::with_capacity(fb.beauty.len() * channels);
    let quantize = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    for (i, c) in fb.beauty.iter().enumerate() {
        let a = match imager {
            Some(im) => {
                let (c, a) = im.composite(*c, fb.alpha[i]);
                data.extend_from_slice(&[c.x, c.y, c.z].map(|v| quantize(im.encode(v))));
                a
            }
            None => {
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

/// Encodes the alpha pass alone as a grey PNG: the pixel coverage, linear (0 empty, 255
/// covered), as RenderMan's `Display … "a"` writes it.
pub fn encode_alpha_png(fb: &FrameBuffers) -> Result<Vec<u8>, String> {
    let data: Vec<u8> = fb
        .alpha
        .iter()
        .map(|&a| (a.clamp(0.0, 1.0) * 255.0 + 0.5) as u8)
        .collect();
    png_codec::encode_png(&data, fb.width, fb.height, PngLayout::Grey8)
}
