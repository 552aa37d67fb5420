//! Baked textures: a float RGB image with a validity mask, and its encodings (EXR f32,
//! PNG 8/16-bit).

use exr::prelude::*;
use glam::Vec3;

use crate::image_io::png_codec::{self, PngLayout};
use crate::image_io::srgb;

/// A baked texture: linear RGB per texel (row 0 at the top) and whether each texel holds a
/// baked (or dilated) value.
#[derive(Debug, Clone, PartialEq)]
pub struct TexelImage {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Values.
    pub texels: Vec<Vec3>,
    /// True where `texels` holds a value.
    pub valid: Vec<bool>,
}

impl TexelImage {
    /// An empty (all invalid, zero) image.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            texels: vec![Vec3::ZERO; n],
            valid: vec![false; n],
        }
    }

    /// The four texels a bilinear lookup at `uv` reads, with their weights, clamped to the
    /// image (texel centres at `((i + ½)/W, 1 − (j + ½)/H)`).
    pub fn bilinear_taps(&self, uv: glam::Vec2) -> [(usize, f32); 4] {
        let x = uv.x * self.width as f32 - 0.5;
        let y = (1.0 - uv.y) * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let clamp_x = |v: f32| (v.max(0.0) as usize).min(self.width as usize - 1);
        let clamp_y = |v: f32| (v.max(0.0) as usize).min(self.height as usize - 1);
        let (i0, i1) = (clamp_x(x0), clamp_x(x0 + 1.0));
        let (j0, j1) = (clamp_y(y0), clamp_y(y0 + 1.0));
        let w = self.width as usize;
        [
            (j0 * w + i0, (1.0 - fx) * (1.0 - fy)),
            (j0 * w + i1, fx * (1.0 - fy)),
            (j1 * w + i0, (1.0 - fx) * fy),
            (j1 * w + i1, fx * fy),
        ]
    }

    /// Bilinear lookup at `uv` (v up), as a renderer sampling the texture would do.
    pub fn bilinear(&self, uv: glam::Vec2) -> Vec3 {
        self.bilinear_taps(uv)
            .iter()
            .map(|&(i, w)| self.texels[i] * w)
            .sum()
    }

    /// Encodes as linear f32 RGB EXR.
    pub fn encode_exr(&self) -> std::result::Result<Vec<u8>, String> {
        let channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = [("R", 0usize), ("G", 1), ("B", 2)]
            .into_iter()
            .map(|(name, c)| {
                AnyChannel::new(
                    name,
                    FlatSamples::F32(self.texels.iter().map(|t| t[c]).collect()),
                )
            })
            .collect();
        let layer = Layer::new(
            (self.width as usize, self.height as usize),
            LayerAttributes::default(),
            Encoding::SMALL_LOSSLESS,
            AnyChannels::sort(channels),
        );
        let mut cursor = std::io::Cursor::new(Vec::new());
        Image::from_layer(layer)
            .write()
            .non_parallel()
            .to_buffered(&mut cursor)
            .map_err(|e| e.to_string())?;
        Ok(cursor.into_inner())
    }

    /// Encodes as PNG RGB, 8 or 16 bits; `srgb` applies the sRGB curve (colour data),
    /// otherwise values are stored linearly (clamped to [0, 1]).
    pub fn encode_png(
        &self,
        sixteen_bit: bool,
        srgb_encode: bool,
    ) -> std::result::Result<Vec<u8>, String> {
        let encode = |v: f32| -> f32 {
            if srgb_encode {
                srgb::encode(v)
            } else if v.is_nan() {
                0.0
            } else {
                v.clamp(0.0, 1.0)
            }
        };
        if sixteen_bit {
            let mut data = Vec::with_capacity(self.texels.len() * 6);
            for t in &self.texels {
                for c in 0..3 {
                    let v = (encode(t[c]) * 65535.0 + 0.5) as u16;
                    data.extend_from_slice(&v.to_be_bytes());
                }
            }
            png_codec::encode_png(&data, self.width, self.height, PngLayout::Rgb16)
        } else {
            let data: Vec<u8> = self
                .texels
                .iter()
                .flat_map(|t| [0, 1, 2].map(|c| (encode(t[c]) * 255.0 + 0.5) as u8))
                .collect();
            png_codec::encode_png(&data, self.width, self.height, PngLayout::Rgb8)
        }
    }

    /// The validity mask as an 8-bit grey PNG (255 valid, 0 empty).
    pub fn encode_mask_png(&self) -> std::result::Result<Vec<u8>, String> {
        let data: Vec<u8> = self
            .valid
            .iter()
            .map(|&v| if v { 255 } else { 0 })
            .collect();
        png_codec::encode_png(&data, self.width, self.height, PngLayout::Grey8)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::png_codec::{decode_png, Samples};

    /// A 16-bit PNG holds each linear value as round(v · 65535), big-endian as PNG requires
    /// (a reader gets 0x1234, not the byte-swapped 0x3412 an encoder expecting native-endian
    /// samples would write); 8-bit as round(v · 255); the mask as 255 and 0.
    #[test]
    fn png_bakes_store_the_quantised_values() {
        let mut img = TexelImage::new(2, 1);
        img.texels = vec![
            Vec3::new(0x1234 as f32 / 65535.0, 0.0, 1.0),
            Vec3::splat(0.5),
        ];
        img.valid = vec![true, false];
        let d = decode_png(&img.encode_png(true, false).unwrap()).unwrap();
        let want = vec![0x1234, 0, 65535, 32768, 32768, 32768];
        assert_eq!(
            (d.width, d.height, d.samples),
            (2, 1, Samples::Sixteen(want))
        );
        let d = decode_png(&img.encode_png(false, false).unwrap()).unwrap();
        assert_eq!(d.samples, Samples::Eight(vec![18, 0, 255, 128, 128, 128]));
        let d = decode_png(&img.encode_mask_png().unwrap()).unwrap();
        assert_eq!((d.channels, d.samples), (1, Samples::Eight(vec![255, 0])));
    }
}
