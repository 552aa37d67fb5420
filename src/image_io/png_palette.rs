//! The checks an indexed PNG passes before it is expanded: a `PLTE` chunk of whole RGB
//! entries, and every pixel's index within it. The PNG specification makes an index past the
//! palette's last entry an error; the `png` crate would expand it to opaque black.

use std::io::Cursor;

/// Refuses an indexed image whose palette the decoder (png 0.18) would index past its end and
/// panic: a `PLTE` chunk whose length is not 3 to 768 bytes in whole RGB entries (which the
/// PNG specification forbids).
pub fn check_length(info: &png::Info) -> Result<(), String> {
    if info.color_type != png::ColorType::Indexed {
        return Ok(());
    }
    let Some(palette) = &info.palette else {
        return Ok(());
    };
    if palette.is_empty() || palette.len() % 3 != 0 || palette.len() > 768 {
        return Err(format!(
            "the PLTE chunk holds {} bytes: a palette is 1 to 256 RGB entries of 3 bytes each",
            palette.len()
        ));
    }
    Ok(())
}

/// Refuses an indexed image (`info`, read from `bytes`) with a pixel whose index is past the
/// last entry of its palette, naming the first such pixel (row-major from the top left). The
/// indices are decoded once more without expansion (at most one byte a pixel), only when the
/// palette has fewer entries than the bit depth can index.
pub fn check_indices(bytes: &[u8], info: &png::Info, limits: png::Limits) -> Result<(), String> {
    if info.color_type != png::ColorType::Indexed {
        return Ok(());
    }
    let Some(palette) = info.palette.as_ref() else {
        return Err(
            "the PLTE chunk is missing: an indexed-colour (palette) PNG needs its palette".into(),
        );
    };
    let entries = palette.len() / 3;
    let depth = info.bit_depth as usize;
    if entries >= 1 << depth {
        return Ok(());
    }
    let mut decoder = png::Decoder::new_with_limits(Cursor::new(bytes), limits);
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let size = reader
        .output_buffer_size()
        .ok_or("the image is too large to decode")?;
    let mut packed = vec![0u8; size];
    let frame = reader.next_frame(&mut packed).map_err(|e| e.to_string())?;
    let mask = (1u16 << depth) - 1;
    for (y, row) in packed
        .chunks_exact(frame.line_size)
        .take(frame.height as usize)
        .enumerate()
    {
        for x in 0..frame.width as usize {
            let bit = x * depth;
            let index = (u16::from(row[bit / 8]) >> (8 - depth - bit % 8)) & mask;
            if usize::from(index) >= entries {
                return Err(format!(
                    "pixel ({x}, {y}) has palette index {index}, but the PLTE chunk holds {entries} {} (indices 0 to {})",
                    if entries == 1 { "entry" } else { "entries" },
                    entries.saturating_sub(1)
                ));
            }
        }
    }
    Ok(())
}
