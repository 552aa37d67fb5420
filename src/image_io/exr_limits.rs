//! The size check every EXR read from outside passes first: the file's headers are read, and
//! a file whose layers claim more samples than its reader allows is refused before the `exr`
//! crate allocates them. Its readers allocate every layer's samples from the header's data
//! window, so a 15 KB file claiming 60000×60000 pixels aborted the process with a 72 GB
//! allocation. A file whose blocks (tiles, or groups of scan lines) claim more than
//! [`MAX_BLOCK_BYTES`] is refused too: the crate reserves a chunk's declared size up to the
//! header's block size before it reads the chunk. And a file whose layers would decode to
//! more bytes than its own length can hold under its compression is refused: a 973-byte part
//! file claiming 2.1 G samples (inside the part budget) made the crate allocate 8.5 GB.

use std::path::Path;

use exr::meta::header::Header;
use exr::meta::{BlockDescription, MetaData};

/// The most samples (pixels × channels, all layers) an input image may hold: textures,
/// environment maps and sweep references (8192 × 8192 RGBA; 1 GiB as `f32`).
pub const MAX_IMAGE_SAMPLES: u64 = 1 << 28;

/// The most samples a farm part file may hold (16 GiB as `f32`, as photon map files).
pub const MAX_PART_SAMPLES: u64 = 1 << 32;

/// The largest block (one tile, or one compression group of scan lines) an input file may
/// declare, in bytes: 256 MiB, a 4096 × 4096 RGBA `f32` tile (a 32-line block of an 8192-pixel
/// RGBA `f32` image is 4 MiB). A 470-byte file whose header declared 4.3 GB blocks, inside
/// the sample budget, made the crate reserve 1.75 GB for its first chunk and ran the fuzzer
/// out of memory.
pub const MAX_BLOCK_BYTES: u64 = 256 << 20;

/// Reads the headers of the EXR file at `path` and refuses it when its layers hold more than
/// `max_samples` samples. A file whose headers cannot be read passes: the full read that
/// follows reports what is wrong with it.
pub fn check_file(path: &Path, max_samples: u64) -> Result<(), String> {
    let file_bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(u64::MAX);
    match MetaData::read_from_file(path, false) {
        Ok(meta) => check(&meta, max_samples, file_bytes),
        Err(_) => Ok(()),
    }
}

/// [`check_file`] for a file's bytes.
pub fn check_bytes(bytes: &[u8], max_samples: u64) -> Result<(), String> {
    match MetaData::read_from_buffered(std::io::Cursor::new(bytes), false) {
        Ok(meta) => check(&meta, max_samples, bytes.len() as u64),
        Err(_) => Ok(()),
    }
}

fn check(meta: &MetaData, max_samples: u64, file_bytes: u64) -> Result<(), String> {
    let mut decoded: u64 = 0;
    let mut samples: u64 = 0;
    for header in meta.headers.iter() {
        let size = header.layer_size;
        let pixels = (size.width() as u64).saturating_mul(size.height() as u64);
        let channels = header.channels.list.len() as u64;
        samples = samples.saturating_add(pixels.saturating_mul(channels));
        if samples > max_samples {
            return Err(format!(
                "a layer of {}×{} pixels in {channels} channels: the file claims more than the \
                 {max_samples} samples (pixels × channels) this input may hold",
                size.width(),
                size.height()
            ));
        }
        let block = block_bytes(header);
        if block > MAX_BLOCK_BYTES {
            return Err(format!(
                "blocks (tiles or groups of scan lines) of {block} bytes: more than the \
                 {MAX_BLOCK_BYTES} bytes one block of this input may hold"
            ));
        }
        decoded = decoded.saturating_add(decoded_bytes(header));
        let most = file_bytes.saturating_mul(largest_ratio(header.compression));
        if decoded > most {
            return Err(format!(
                "a layer of {}×{} pixels in {channels} channels ({decoded} bytes once decoded): \
                 more than a file of {file_bytes} bytes with {} can hold; the file may be \
                 truncated or its header damaged",
                size.width(),
                size.height(),
                header.compression
            ));
        }
    }
    Ok(())
}

/// The bytes `header`'s full-resolution layer holds once decoded, each channel at its sampling.
fn decoded_bytes(header: &Header) -> u64 {
    let (width, height) = (
        header.layer_size.width() as u64,
        header.layer_size.height() as u64,
    );
    header.channels.list.iter().fold(0u64, |sum, channel| {
        let (sx, sy) = (
            channel.sampling.x().max(1) as u64,
            channel.sampling.y().max(1) as u64,
        );
        let samples = width.div_ceil(sx).saturating_mul(height.div_ceil(sy));
        sum.saturating_add(samples.saturating_mul(channel.sample_type.bytes_per_sample() as u64))
    })
}

/// More than the most a file's bytes can expand by under `compression`: none for raw data,
/// 64:1 for run-length (2 bytes for 128), about 1032:1 for deflate (ZIP, and PXR24's 24-bit
/// floats after it), 10.7:1 for B44A's flat blocks; PIZ's Huffman runs reach about 410:1, and
/// 4096 bounds it and the DWA and HTJ2K codecs, which the `exr` crate does not decode.
fn largest_ratio(compression: exr::compression::Compression) -> u64 {
    use exr::compression::Compression::*;
    match compression {
        Uncompressed => 1,
        RLE => 64,
        ZIP1 | ZIP16 => 1040,
        PXR24 => 1400,
        B44 | B44A => 16,
        PIZ | DWAA(_) | DWAB(_) | HTJ2K32 | HTJ2K256 => 4096,
    }
}

/// The bytes of one of `header`'s blocks as its header declares them (what the `exr` crate
/// reserves for a chunk), without overflow.
fn block_bytes(header: &Header) -> u64 {
    let pixels = match header.blocks {
        BlockDescription::Tiles(tiles) => {
            (tiles.tile_size.width() as u64).saturating_mul(tiles.tile_size.height() as u64)
        }
        BlockDescription::ScanLines => (header.compression.scan_lines_per_block() as u64)
            .saturating_mul(header.layer_size.width() as u64),
    };
    pixels.saturating_mul(header.channels.bytes_per_pixel as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A real 2×2 EXR with its data and display windows patched to claim `size`².
    fn claiming(size: i32) -> Vec<u8> {
        use exr::prelude::*;
        let mut bytes = std::io::Cursor::new(Vec::new());
        Image::from_channels(
            (2, 2),
            SpecificChannels::rgba(|_pos: Vec2<usize>| (0.5_f32, 0.5_f32, 0.5_f32, 1.0_f32)),
        )
        .write()
        .to_buffered(&mut bytes)
        .unwrap();
        let mut d = bytes.into_inner();
        for name in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
            let at = d.windows(name.len()).position(|w| w == name).unwrap() + name.len() + 4;
            d[at + 8..at + 12].copy_from_slice(&(size - 1).to_le_bytes());
            d[at + 12..at + 16].copy_from_slice(&(size - 1).to_le_bytes());
        }
        d
    }

    /// [`check_bytes`] as if the file were long enough for what its header claims.
    fn check_claim(bytes: &[u8], max_samples: u64) -> Result<(), String> {
        let meta = MetaData::read_from_buffered(std::io::Cursor::new(bytes), false).unwrap();
        check(&meta, max_samples, u64::MAX)
    }

    #[test]
    fn a_small_file_claiming_a_huge_image_is_refused_from_its_header() {
        let e = check_bytes(&claiming(60000), MAX_IMAGE_SAMPLES).unwrap_err();
        assert_eq!(
            e,
            "a layer of 60000×60000 pixels in 4 channels: the file claims more than the \
             268435456 samples (pixels × channels) this input may hold"
        );
        // At the budget's edge the length bound is left out: a 2×2 file claims either.
        assert_eq!(check_claim(&claiming(8192), MAX_IMAGE_SAMPLES), Ok(()));
        assert!(check_claim(&claiming(8193), MAX_IMAGE_SAMPLES).is_err());
        assert_eq!(check_bytes(b"not an exr", MAX_IMAGE_SAMPLES), Ok(()));
    }

    /// CI's fuzzer's 973-byte part file claims 3 × 704,643,070 pixels, inside the part
    /// budget, with zip compression: refused from its length before the crate allocates the
    /// 8.5 GB. A real zip file of the same claim passes.
    #[test]
    fn a_small_file_claiming_more_than_its_compression_can_hold_is_refused() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/fuzz/corpus/part_file/claims_more_than_zip_can_hold.exr"
        );
        let e = check_file(Path::new(path), MAX_PART_SAMPLES).unwrap_err();
        assert_eq!(
            e,
            "a layer of 3×704643070 pixels in 2 channels (16911433680 bytes once decoded): \
             more than a file of 973 bytes with zip block compression can hold; the file may \
             be truncated or its header damaged"
        );
        // A constant 256² RGBA `f32` image (1 MiB decoded) compresses far, and still passes.
        use exr::prelude::*;
        let mut bytes = std::io::Cursor::new(Vec::new());
        let flat = |_pos: Vec2<usize>| (0.0_f32, 0.0_f32, 0.0_f32, 0.0_f32);
        let layer = Layer::new(
            (256, 256),
            LayerAttributes::default(),
            Encoding::SMALL_LOSSLESS,
            SpecificChannels::rgba(flat),
        );
        Image::from_layer(layer)
            .write()
            .to_buffered(&mut bytes)
            .unwrap();
        let bytes = bytes.into_inner();
        assert!(bytes.len() < 8192, "{} bytes", bytes.len());
        assert_eq!(check_bytes(&bytes, MAX_IMAGE_SAMPLES), Ok(()));
    }

    /// The fuzzer's 470-byte file: a layer within the sample budget whose scan-line blocks
    /// are declared at 4.3 GB each is refused from its header; ordinary blocks pass.
    #[test]
    fn a_file_declaring_huge_blocks_is_refused_from_its_header() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/fuzz/corpus/exr/huge_scan_line_blocks.exr"
        );
        let e = check_file(Path::new(path), MAX_IMAGE_SAMPLES).unwrap_err();
        assert_eq!(
            e,
            "blocks (tiles or groups of scan lines) of 4294966784 bytes: more than the \
             268435456 bytes one block of this input may hold"
        );
        // 8192 RGBA `f32` pixels in one scan-line block of the default compression.
        assert_eq!(check_claim(&claiming(8192), MAX_IMAGE_SAMPLES), Ok(()));
    }
}
