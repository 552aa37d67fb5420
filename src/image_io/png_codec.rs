//! PNG files in and out, on the `png` crate: every reader and writer of PNG data in
//! stagelight (image textures, displacement maps, glTF images, beauty and bake outputs)
//! goes through here.
//!
//! * **Decoding**: any colour type and bit depth; palettes, bit depths below 8 and `tRNS`
//!   transparency are expanded, so an image is 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA)
//!   channels of 8- or 16-bit samples. An image may hold at most [`MAX_IMAGE_SAMPLES`]
//!   samples (pixels × channels once expanded, the limit of EXR inputs) and the decoder may
//!   allocate at most [`MAX_DECODED_BYTES`], so a small file that claims huge dimensions is
//!   refused from its header ([`read_header`]), not allocated. An indexed image's palette and
//!   indices are checked first ([`png_palette`](super::png_palette)): an index past the
//!   palette is an error, as the PNG specification says. [`DecodedPng::rgba`] and [`DecodedPng::luma`] give samples as `f32` in
//!   `[0, 1]` (`v / 255`, `v / 65535`); luma weighs RGB by Rec. 709's 0.2126, 0.7152,
//!   0.0722 in integers, truncated to the sample type before the division.
//! * **Encoding**: 8-bit grey, RGB and RGBA, and 16-bit RGB with big-endian samples (as PNG
//!   stores them); balanced deflate and adaptive filtering.

use std::io::Cursor;
use std::path::Path;

/// The most bytes the decoder allocates for one image (512 MiB: a 16-bit RGBA image of
/// 8,192 × 8,192 pixels, [`MAX_IMAGE_SAMPLES`] samples of two bytes).
pub const MAX_DECODED_BYTES: usize = 512 << 20;

pub use super::exr_limits::MAX_IMAGE_SAMPLES;

/// The eight bytes every PNG file starts with.
const SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a];

/// A decoded image: rows top to bottom, `channels` interleaved samples per pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct DecodedPng {
    /// Pixels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// 1 grey, 2 grey and alpha, 3 RGB, 4 RGBA.
    pub channels: usize,
    /// The samples.
    pub samples: Samples,
}

/// Samples of one bit depth.
#[derive(Debug, Clone, PartialEq)]
pub enum Samples {
    /// 8-bit samples (and palettes and bit depths below 8, expanded).
    Eight(Vec<u8>),
    /// 16-bit samples.
    Sixteen(Vec<u16>),
}

impl DecodedPng {
    /// Whether the image has an alpha channel (its own or from `tRNS`).
    pub fn has_alpha(&self) -> bool {
        matches!(self.channels, 2 | 4)
    }

    /// Pixels in the image.
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Sample `k` of pixel `p` as it is stored, and the largest value of its type.
    fn raw(&self, p: usize, k: usize) -> (u32, u32) {
        let i = p * self.channels + k;
        match &self.samples {
            Samples::Eight(s) => (u32::from(s[i]), 255),
            Samples::Sixteen(s) => (u32::from(s[i]), 65535),
        }
    }

    /// Pixel `p` (row-major from the top left) as RGBA in `[0, 1]`: grey fills R, G and B,
    /// and a missing alpha is 1.
    pub fn rgba(&self, p: usize) -> [f32; 4] {
        let f = |k: usize| {
            let (v, max) = self.raw(p, k);
            v as f32 / max as f32
        };
        match self.channels {
            1 => [f(0), f(0), f(0), 1.0],
            2 => [f(0), f(0), f(0), f(1)],
            3 => [f(0), f(1), f(2), 1.0],
            _ => [f(0), f(1), f(2), f(3)],
        }
    }

    /// Pixel `p`'s luma in `[0, 1]`: the grey sample, or Rec. 709's weighting of R, G and B
    /// in integers, truncated to the sample type.
    pub fn luma(&self, p: usize) -> f32 {
        let (v, max) = if self.channels <= 2 {
            self.raw(p, 0)
        } else {
            let [(r, max), (g, _), (b, _)] = [0, 1, 2].map(|k| self.raw(p, k));
            ((2126 * r + 7152 * g + 722 * b) / 10000, max)
        };
        v as f32 / max as f32
    }
}

/// What a PNG file's header says of the image [`decode_png`] makes of it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PngHeader {
    /// Pixels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Channels once expanded: 1 grey, 2 grey and alpha, 3 RGB, 4 RGBA.
    pub channels: usize,
    /// Bytes of the decoded samples.
    pub decoded_bytes: u64,
}

impl PngHeader {
    /// Pixels in the image.
    pub fn pixels(&self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }
}

fn decoder(bytes: &[u8]) -> Result<png::Decoder<Cursor<&[u8]>>, String> {
    if !bytes.starts_with(&SIGNATURE) {
        return Err("not a PNG file (it does not start with the PNG signature)".into());
    }
    let limits = png::Limits {
        bytes: MAX_DECODED_BYTES,
    };
    let mut decoder = png::Decoder::new_with_limits(Cursor::new(bytes), limits);
    decoder.set_transformations(png::Transformations::EXPAND);
    Ok(decoder)
}

/// The header of `reader`'s image, refused when it holds more than [`MAX_IMAGE_SAMPLES`]
/// samples or the decoder would allocate more than [`MAX_DECODED_BYTES`].
fn header_of(reader: &png::Reader<Cursor<&[u8]>>) -> Result<PngHeader, String> {
    let info = reader.info();
    super::png_palette::check_length(info)?;
    let (width, height) = (info.width, info.height);
    let channels = reader.output_color_type().0.samples();
    let samples = u64::from(width) * u64::from(height) * channels as u64;
    if samples > MAX_IMAGE_SAMPLES {
        return Err(format!(
            "a {width}×{height} image in {channels} channel(s): the file claims more than the \
             {MAX_IMAGE_SAMPLES} samples (pixels × channels) this input may hold"
        ));
    }
    let decoded_bytes = reader
        .output_buffer_size()
        .filter(|&n| n <= MAX_DECODED_BYTES)
        .ok_or_else(|| {
            format!(
                "a {width} × {height} PNG image is larger than the {} MiB a decoded image may take",
                MAX_DECODED_BYTES >> 20
            )
        })?;
    Ok(PngHeader {
        width,
        height,
        channels,
        decoded_bytes: decoded_bytes as u64,
    })
}

/// Reads a PNG file's header (the chunks before the image data) without decoding the image;
/// an image [`decode_png`] would refuse for its size is refused here.
pub fn read_header(bytes: &[u8]) -> Result<PngHeader, String> {
    let reader = decoder(bytes)?.read_info().map_err(|e| e.to_string())?;
    header_of(&reader)
}

/// Decodes a PNG file held in memory.
pub fn decode_png(bytes: &[u8]) -> Result<DecodedPng, String> {
    let mut reader = decoder(bytes)?.read_info().map_err(|e| e.to_string())?;
    let header = header_of(&reader)?;
    super::png_palette::check_indices(
        bytes,
        reader.info(),
        png::Limits {
            bytes: MAX_DECODED_BYTES,
        },
    )?;
    let mut buf = vec![0u8; header.decoded_bytes as usize];
    let frame = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    buf.truncate(frame.buffer_size());
    let channels = frame.color_type.samples();
    let samples = match frame.bit_depth {
        png::BitDepth::Sixteen => Samples::Sixteen(
            buf.chunks_exact(2)
                .map(|b| u16::from_be_bytes([b[0], b[1]]))
                .collect(),
        ),
        _ => Samples::Eight(buf),
    };
    Ok(DecodedPng {
        width: frame.width,
        height: frame.height,
        channels,
        samples,
    })
}

/// Reads and decodes the PNG file at `path` (a file that cannot be read gives the system's
/// message, as `std::io::Error` writes it).
pub fn read_png(path: &Path) -> Result<DecodedPng, String> {
    decode_png(&std::fs::read(path).map_err(|e| e.to_string())?)
}

/// The layouts [`encode_png`] writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PngLayout {
    /// 8-bit grey.
    Grey8,
    /// 8-bit RGB.
    Rgb8,
    /// 8-bit RGBA.
    Rgba8,
    /// 16-bit RGB, each sample two big-endian bytes.
    Rgb16,
}

/// Encodes `data` (rows top to bottom, samples as `layout` says) as a PNG file.
pub fn encode_png(
    data: &[u8],
    width: u32,
    height: u32,
    layout: PngLayout,
) -> Result<Vec<u8>, String> {
    let (color, depth, bytes_per_pixel) = match layout {
        PngLayout::Grey8 => (png::ColorType::Grayscale, png::BitDepth::Eight, 1),
        PngLayout::Rgb8 => (png::ColorType::Rgb, png::BitDepth::Eight, 3),
        PngLayout::Rgba8 => (png::ColorType::Rgba, png::BitDepth::Eight, 4),
        PngLayout::Rgb16 => (png::ColorType::Rgb, png::BitDepth::Sixteen, 6),
    };
    let want = width as usize * height as usize * bytes_per_pixel;
    if data.len() != want {
        return Err(format!(
            "{} bytes of samples for a {width} × {height} {layout:?} image, which needs {want}",
            data.len()
        ));
    }
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    encoder.set_compression(png::Compression::Balanced);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(data).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every layout round-trips: what is written decodes to the same samples, 16-bit ones
    /// big-endian in the file (a sample 0x1234 reads back as 0x1234, not 0x3412).
    #[test]
    fn encoded_images_decode_to_their_samples() {
        let grey: Vec<u8> = (0..12).map(|i| i * 20).collect();
        let d = decode_png(&encode_png(&grey, 4, 3, PngLayout::Grey8).unwrap()).unwrap();
        assert_eq!((d.width, d.height, d.channels), (4, 3, 1));
        assert_eq!(d.samples, Samples::Eight(grey));
        let rgba: Vec<u8> = (0..24).map(|i| 255 - i * 7).collect();
        let d = decode_png(&encode_png(&rgba, 3, 2, PngLayout::Rgba8).unwrap()).unwrap();
        assert_eq!((d.channels, d.has_alpha()), (4, true));
        assert_eq!(d.samples, Samples::Eight(rgba));
        let wide: Vec<u16> = vec![0x1234, 0, 65535, 1, 0x8000, 0x00ff];
        let bytes: Vec<u8> = wide.iter().flat_map(|v| v.to_be_bytes()).collect();
        let d = decode_png(&encode_png(&bytes, 2, 1, PngLayout::Rgb16).unwrap()).unwrap();
        assert_eq!((d.channels, d.has_alpha()), (3, false));
        assert_eq!(d.samples, Samples::Sixteen(wide));
        assert_eq!(d.rgba(0), [0x1234 as f32 / 65535.0, 0.0, 1.0, 1.0]);
    }

    /// Grey fills R, G and B; luma weighs RGB in integers and truncates (8-bit: (2126·200 +
    /// 7152·100 + 722·50) / 10000 = 117.65 → 117).
    #[test]
    fn rgba_and_luma_of_each_channel_count() {
        let rgb = decode_png(&encode_png(&[200, 100, 50], 1, 1, PngLayout::Rgb8).unwrap()).unwrap();
        assert_eq!(rgb.luma(0), 117.0 / 255.0);
        assert_eq!(
            rgb.rgba(0),
            [200.0 / 255.0, 100.0 / 255.0, 50.0 / 255.0, 1.0]
        );
        let grey = decode_png(&encode_png(&[51], 1, 1, PngLayout::Grey8).unwrap()).unwrap();
        assert_eq!(grey.rgba(0), [0.2, 0.2, 0.2, 1.0]);
        assert_eq!(grey.luma(0), 0.2);
    }

    /// Files that are not PNG, truncated files and wrong sample counts are errors, never
    /// panics; a header claiming more pixels than the decoder may allocate is refused
    /// before anything that large is allocated.
    #[test]
    fn bad_input_is_an_error() {
        assert_eq!(
            decode_png(b"garbage").unwrap_err(),
            "not a PNG file (it does not start with the PNG signature)"
        );
        let good = encode_png(&[1, 2, 3, 4], 2, 2, PngLayout::Grey8).unwrap();
        for cut in [8, 20, good.len() - 12] {
            assert!(decode_png(&good[..cut]).is_err(), "{cut} bytes");
        }
        // IHDR claiming 60,000 × 60,000 RGBA pixels (14.4 GB), CRC made valid.
        let mut huge = good[..8].to_vec();
        let mut ihdr = b"IHDR".to_vec();
        ihdr.extend_from_slice(&60_000u32.to_be_bytes());
        ihdr.extend_from_slice(&60_000u32.to_be_bytes());
        ihdr.extend_from_slice(&[8, 6, 0, 0, 0]);
        huge.extend_from_slice(&13u32.to_be_bytes());
        huge.extend_from_slice(&ihdr);
        huge.extend_from_slice(&crc32(&ihdr).to_be_bytes());
        huge.extend_from_slice(&good[33..]);
        let e = decode_png(&huge).unwrap_err();
        assert!(e.contains("60000") || e.contains("limit"), "{e}");
        assert!(encode_png(&[0; 5], 2, 2, PngLayout::Grey8).is_err());
        // Found by the `png` fuzz target (its CRCs made valid): a 2-bit indexed image whose
        // PLTE chunk holds 44 bytes (14 entries and 2 bytes); the png crate panicked
        // expanding it.
        assert_eq!(
            decode_png(include_bytes!("../../fuzz/corpus/png/bad_plte_length.png")).unwrap_err(),
            "the PLTE chunk holds 44 bytes: a palette is 1 to 256 RGB entries of 3 bytes each"
        );
    }

    /// An indexed image of `depth` bits with `palette` (RGB triples) and packed `rows`.
    fn indexed(depth: png::BitDepth, width: u32, palette: &[u8], rows: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let height = 2;
        let mut encoder = png::Encoder::new(&mut out, width, height);
        encoder.set_color(png::ColorType::Indexed);
        encoder.set_depth(depth);
        encoder.set_palette(palette.to_vec());
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(rows).unwrap();
        writer.finish().unwrap();
        out
    }

    /// An indexed-colour PNG without its `PLTE` chunk says the chunk is missing (it said
    /// "the PLTE chunk holds 0 entries (indices 0 to 0)").
    #[test]
    fn a_palette_image_without_its_palette_says_so() {
        let png = indexed(png::BitDepth::Eight, 2, &[0, 0, 0], &[0, 0, 0, 0]);
        let at = png.windows(4).position(|w| w == b"PLTE").unwrap() - 4;
        let len = u32::from_be_bytes(png[at..at + 4].try_into().unwrap()) as usize;
        let without: Vec<u8> = [&png[..at], &png[at + 12 + len..]].concat();
        assert_eq!(
            decode_png(&without).unwrap_err(),
            "the PLTE chunk is missing: an indexed-colour (palette) PNG needs its palette"
        );
    }

    /// An index past the palette's last entry is an error naming the first such pixel (the
    /// decoder would expand it to opaque black), at 8 bits and packed below 8 bits; indices
    /// within the palette decode to its colours.
    #[test]
    fn a_palette_index_past_the_palette_is_an_error() {
        let two = [0, 0, 0, 255, 128, 0];
        let bad = indexed(png::BitDepth::Eight, 4, &two, &[0, 1, 1, 0, 1, 0, 0, 5]);
        assert_eq!(
            decode_png(&bad).unwrap_err(),
            "pixel (3, 1) has palette index 5, but the PLTE chunk holds 2 entries (indices 0 to 1)"
        );
        // 4 bits: row 0 is 0x01 0x30 → indices 0, 1, 3, 0; three entries.
        let three = [0, 0, 0, 255, 128, 0, 10, 20, 30];
        let bad = indexed(png::BitDepth::Four, 4, &three, &[0x01, 0x30, 0x00, 0x00]);
        assert_eq!(
            decode_png(&bad).unwrap_err(),
            "pixel (2, 0) has palette index 3, but the PLTE chunk holds 3 entries (indices 0 to 2)"
        );
        let one = indexed(png::BitDepth::One, 3, &[7, 8, 9], &[0x00, 0x40]);
        assert_eq!(
            decode_png(&one).unwrap_err(),
            "pixel (1, 1) has palette index 1, but the PLTE chunk holds 1 entry (indices 0 to 0)"
        );
        let good = indexed(png::BitDepth::Four, 4, &three, &[0x01, 0x20, 0x22, 0x10]);
        let d = decode_png(&good).unwrap();
        assert_eq!(d.channels, 3);
        assert_eq!(
            d.samples,
            Samples::Eight(vec![
                0, 0, 0, 255, 128, 0, 10, 20, 30, 0, 0, 0, //
                10, 20, 30, 10, 20, 30, 255, 128, 0, 0, 0, 0
            ])
        );
    }

    /// The sample limit is the EXR inputs' (pixels × channels once expanded): a grey image
    /// of 16,384 × 16,384 pixels is within it, one row more is not; the header alone decides.
    #[test]
    fn the_header_is_refused_past_the_sample_limit() {
        let claiming = |width: u32, height: u32| {
            let good = encode_png(&[1, 2, 3, 4], 2, 2, PngLayout::Grey8).unwrap();
            let mut ihdr = b"IHDR".to_vec();
            ihdr.extend_from_slice(&width.to_be_bytes());
            ihdr.extend_from_slice(&height.to_be_bytes());
            ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
            let mut bytes = good[..8].to_vec();
            bytes.extend_from_slice(&13u32.to_be_bytes());
            bytes.extend_from_slice(&ihdr);
            bytes.extend_from_slice(&crc32(&ihdr).to_be_bytes());
            bytes.extend_from_slice(&good[33..]);
            bytes
        };
        assert_eq!(
            read_header(&claiming(16384, 16384)),
            Ok(PngHeader {
                width: 16384,
                height: 16384,
                channels: 1,
                decoded_bytes: 1 << 28
            })
        );
        assert_eq!(
            read_header(&claiming(16384, 16385)).unwrap_err(),
            "a 16384×16385 image in 1 channel(s): the file claims more than the 268435456 \
             samples (pixels × channels) this input may hold"
        );
        // Decoding refuses it the same way, before allocating.
        assert_eq!(
            decode_png(&claiming(23000, 23000)).unwrap_err(),
            "a 23000×23000 image in 1 channel(s): the file claims more than the 268435456 \
             samples (pixels × channels) this input may hold"
        );
    }

    /// CRC-32 (PNG's chunk checksum), for the hand-made header above.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xedb8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
}
