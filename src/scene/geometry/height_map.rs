//! Displacement images (`Image(file: …)` in a displacement shader): one height per texel,
//! rows flipped so that row 0 is v = 0 (the file's bottom row). A PNG reads as grey 0…1: its
//! grey sample, or the Rec. 709 luma of R, G and B, over the sample's maximum. An EXR reads
//! its heights as stored, 16- or 32-bit float, negative ones too: the channel an image
//! texture would read as grey (`Y`, else a layer's one channel), or the Rec. 709 luminance
//! of R, G and B; every height must be finite. What reading a file takes is known from its
//! header ([`footprint`]), so the loader counts it against the run's memory budget before
//! anything is decoded.

use std::mem::size_of;

use crate::image_io::png_codec;
use crate::shading::texture::exr_channels;

/// The heights of a displacement image, bottom row first.
#[derive(Debug, Clone, PartialEq)]
pub struct Heights {
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// `width × height` heights.
    pub texels: Vec<f32>,
}

/// Bytes the heights of a `width × height` image take once read (an `f32` each).
pub fn held_bytes(width: u32, height: u32) -> u64 {
    (u64::from(width) * u64::from(height)).saturating_mul(size_of::<f32>() as u64)
}

/// The size of the image in a file's bytes (`exr`: read as EXR, else PNG) and the peak bytes
/// of reading it: the file, the PNG decoder's samples, and the heights. A file whose header
/// cannot be read, or an EXR without the channels a displacement image reads, is refused.
pub fn footprint(bytes: &[u8], exr: bool) -> Result<((u32, u32), u64), String> {
    let (width, height, samples) = if exr {
        let layer = exr_channels::choose_for(bytes, "a displacement image")?;
        (layer.width, layer.height, 0)
    } else {
        let h = png_codec::read_header(bytes)?;
        (h.width, h.height, h.decoded_bytes)
    };
    let bytes = (bytes.len() as u64)
        .saturating_add(samples)
        .saturating_add(held_bytes(width, height));
    Ok(((width, height), bytes))
}

/// Reads a displacement image from a file's bytes (`exr`: read as EXR, else PNG).
pub fn decode(bytes: &[u8], exr: bool) -> Result<Heights, String> {
    if exr {
        let layer = exr_channels::choose_for(bytes, "a displacement image")?;
        let (w, h) = (layer.width as usize, layer.height as usize);
        let texels = exr_channels::read_grey(bytes, &layer)?;
        if let Some(i) = texels.iter().position(|t| !t.is_finite()) {
            // Reported in the file's own pixel coordinates (row 0 at the top).
            return Err(format!(
                "pixel ({}, {}) is {} (heights must be finite)",
                i % w,
                h - 1 - i / w,
                texels[i]
            ));
        }
        return Ok(Heights {
            width: layer.width,
            height: layer.height,
            texels,
        });
    }
    let img = png_codec::decode_png(bytes)?;
    let (w, h) = (img.width as usize, img.height as usize);
    let texels = (0..h)
        .rev()
        .flat_map(|y| y * w..(y + 1) * w)
        .map(|p| img.luma(p))
        .collect();
    Ok(Heights {
        width: img.width,
        height: img.height,
        texels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::png_codec::{encode_png, PngLayout};

    fn exr_bytes(width: usize, height: usize, channels: &[(&str, Vec<f32>)]) -> Vec<u8> {
        use exr::prelude::*;
        let list: Vec<AnyChannel<FlatSamples>> = channels
            .iter()
            .map(|(name, v)| AnyChannel::new(*name, FlatSamples::F32(v.clone())))
            .collect();
        let mut out = std::io::Cursor::new(Vec::new());
        Image::from_channels((width, height), AnyChannels::sort(list.into()))
            .write()
            .to_buffered(&mut out)
            .unwrap();
        out.into_inner()
    }

    /// Rows are flipped (row 0 is the file's bottom row) in both formats; an EXR keeps its
    /// values (negative too) and an RGB one reads as luminance; the heights take what
    /// [`held_bytes`] says.
    #[test]
    fn png_and_exr_read_bottom_up() {
        let png = encode_png(&[0, 51, 102, 255], 2, 2, PngLayout::Grey8).unwrap();
        let p = decode(&png, false).unwrap();
        assert_eq!(p.texels, vec![0.4, 1.0, 0.0, 0.2]);
        assert_eq!(footprint(&png, false).unwrap().0, (2, 2));
        let exr = exr_bytes(2, 2, &[("height", vec![-1.5, 0.25, 3.0, 1e-3])]);
        let e = decode(&exr, true).unwrap();
        assert_eq!(e.texels, vec![3.0, 1e-3, -1.5, 0.25]);
        assert_eq!(
            held_bytes(2, 2),
            (e.texels.capacity() * size_of::<f32>()) as u64
        );
        let (size, bytes) = footprint(&exr, true).unwrap();
        assert_eq!((size, bytes), ((2, 2), exr.len() as u64 + 16));
        let rgb = exr_bytes(
            1,
            1,
            &[("R", vec![1.0]), ("G", vec![2.0]), ("B", vec![4.0])],
        );
        let l = decode(&rgb, true).unwrap().texels[0];
        assert!(
            (l - (0.2126 + 2.0 * 0.7152 + 4.0 * 0.0722)).abs() < 1e-6,
            "{l}"
        );
    }

    /// A non-finite height is refused naming its pixel (from the top left); a file without a
    /// channel to read names the channels it has.
    #[test]
    fn bad_exr_heights_are_refused() {
        let nan = exr_bytes(2, 2, &[("Y", vec![0.0, 0.0, f32::NAN, 0.0])]);
        assert_eq!(
            decode(&nan, true).unwrap_err(),
            "pixel (0, 1) is NaN (heights must be finite)"
        );
        let uv = exr_bytes(1, 1, &[("U", vec![0.0]), ("V", vec![0.0])]);
        assert_eq!(
            footprint(&uv, true).unwrap_err(),
            "no layer has the channels a displacement image reads (R, G and B; or Y; or a \
             single channel, each with an optional A): the file has the channels U, V"
        );
    }
}
