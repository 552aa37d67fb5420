//! PNG files for the tests: written and read through stagelight's own codec.

use std::path::Path;

use stagelight::image_io::png_codec::{encode_png, read_png, DecodedPng, PngLayout};

/// Writes an 8-bit RGB PNG of `width` × `height` pixels (rows top to bottom).
pub fn write_rgb(path: &Path, width: u32, height: u32, pixels: &[[u8; 3]]) {
    let data: Vec<u8> = pixels.iter().flatten().copied().collect();
    std::fs::write(
        path,
        encode_png(&data, width, height, PngLayout::Rgb8).unwrap(),
    )
    .unwrap();
}

/// Reads a PNG file, panicking with its path.
pub fn read(path: &Path) -> DecodedPng {
    read_png(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Pixel (`x`, `y`) of an 8-bit image as its first three samples (grey repeated).
pub fn rgb8(img: &DecodedPng, x: u32, y: u32) -> [u8; 3] {
    let p = (y * img.width + x) as usize;
    img.rgba(p).map(|v| (v * 255.0).round() as u8)[..3]
        .try_into()
        .unwrap()
}
