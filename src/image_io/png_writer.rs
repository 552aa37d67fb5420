//! PNG encoding of the beauty pass (8-bit sRGB, RGB or RGBA).

use crate::framebuffer::FrameBuffers;
use crate::image_io::srgb::to_u8;

/// Encodes the beauty pass as PNG; with `alpha` the coverage goes into the alpha channel.
pub fn encode_png(fb: &FrameBuffers, alpha: bool) -> Result<Vec<u8>, String> {
    let channels = if alpha { 4 } else { 3 };
    let mut data = Vec::with_capacity(fb.beauty.len() * channels);
    for (i, c) in fb.beauty.iter().enumerate() {
        data.extend_from_slice(&[to_u8(c.x), to_u8(c.y), to_u8(c.z)]);
        if alpha {
            data.push((fb.alpha[i].clamp(0.0, 1.0) * 255.0 + 0.5) as u8);
        }
    }
    let color = if alpha {
        image::ExtendedColorType::Rgba8
    } else {
        image::ExtendedColorType::Rgb8
    };
    let mut out = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut out);
    image::ImageEncoder::write_image(encoder, &data, fb.width, fb.height, color)
        .map_err(|e| e.to_string())?;
    Ok(out)
}
