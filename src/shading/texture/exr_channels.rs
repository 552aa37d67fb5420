//! Which channels of an EXR file an image texture reads, and reading them: the first layer
//! with `R`, `G` and `B`; else the first with `Y` (luminance, as single-channel maps —
//! roughness, height — are often written); else the first layer with one colour channel,
//! whatever its name. A grey channel fills R, G and B. `A`, when the chosen layer has it, is
//! the alpha. A file with none of these is refused naming the channels it has.

use std::io::Cursor;

use exr::meta::MetaData;
use exr::prelude::{
    read, ChannelDescription, ReadChannels, ReadLayers, ReadSpecificChannel, RgbaChannels,
};
use glam::Vec3;

use crate::image_io::exr_limits;

/// The colour channels read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Colour {
    /// `R`, `G` and `B`.
    Rgb,
    /// One channel, by name, read as grey.
    Grey(String),
}

/// The layer a texture reads, from the file's headers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChosenLayer {
    /// Pixels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Its colour channels.
    pub colour: Colour,
    /// Whether it has an `A` channel.
    pub alpha: bool,
}

/// A layer's texels and alpha, bottom-up (alpha empty when the layer has none).
#[derive(Debug, Clone, PartialEq)]
pub struct Texels {
    /// Texels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Colours, bottom row first.
    pub colours: Vec<Vec3>,
    /// Alpha, bottom row first; empty without an `A` channel.
    pub alpha: Vec<f32>,
}

impl Texels {
    fn new(width: usize, height: usize, alpha: bool) -> Self {
        let n = width * height;
        Self {
            width,
            height,
            colours: vec![Vec3::ZERO; n],
            alpha: if alpha { vec![1.0; n] } else { Vec::new() },
        }
    }

    /// Stores the pixel at `(x, y)` from the top left.
    fn set(&mut self, x: usize, y: usize, colour: Vec3, alpha: f32) {
        let Some(row) = self.height.checked_sub(y + 1) else {
            return;
        };
        let i = row * self.width + x;
        if let Some(c) = self.colours.get_mut(i) {
            *c = colour;
        }
        if let Some(a) = self.alpha.get_mut(i) {
            *a = alpha;
        }
    }
}

/// Chooses the layer and channels a texture reads from an EXR file's headers, after the
/// size check every EXR input passes ([`exr_limits`]).
pub fn choose(bytes: &[u8]) -> Result<ChosenLayer, String> {
    choose_for(bytes, "an image texture")
}

/// [`choose`] for the input named `reader` in its refusal (`a displacement image`).
pub fn choose_for(bytes: &[u8], reader: &str) -> Result<ChosenLayer, String> {
    exr_limits::check_bytes(bytes, exr_limits::MAX_IMAGE_SAMPLES)?;
    let meta = MetaData::read_from_buffered(Cursor::new(bytes), false)
        .map_err(|e| format!("not a readable OpenEXR image ({e})"))?;
    let layers: Vec<Vec<String>> = meta
        .headers
        .iter()
        .map(|h| h.channels.list.iter().map(|c| c.name.to_string()).collect())
        .collect();
    let has = |layer: &[String], name: &str| layer.iter().any(|c| c == name);
    let rgb = layers
        .iter()
        .position(|l| ["R", "G", "B"].iter().all(|n| has(l, n)))
        .map(|i| (i, Colour::Rgb));
    let luminance = || {
        layers
            .iter()
            .position(|l| has(l, "Y"))
            .map(|i| (i, Colour::Grey("Y".into())))
    };
    let single = || {
        layers.iter().enumerate().find_map(|(i, l)| {
            let mut colour = l.iter().filter(|c| *c != "A");
            match (colour.next(), colour.next()) {
                (Some(c), None) => Some((i, Colour::Grey(c.clone()))),
                _ => None,
            }
        })
    };
    let Some((i, colour)) = rgb.or_else(luminance).or_else(single) else {
        let found: Vec<String> = layers.concat();
        return Err(format!(
            "no layer has the channels {reader} reads (R, G and B; or Y; or a single \
             channel, each with an optional A): the file has {}",
            if found.is_empty() {
                "no channels".to_string()
            } else {
                format!("the channels {}", found.join(", "))
            }
        ));
    };
    let size = meta.headers[i].layer_size;
    Ok(ChosenLayer {
        width: size.width() as u32,
        height: size.height() as u32,
        colour,
        alpha: has(&layers[i], "A"),
    })
}

/// Reads the chosen layer's texels (on the calling thread: exr's parallel decoding builds a
/// thread pool of its own per image, threads beyond `--threads`, left running when the call
/// returns).
pub fn read_layer(bytes: &[u8], layer: &ChosenLayer) -> Result<Texels, String> {
    let reader = read().no_deep_data().largest_resolution_level();
    let pixels = match &layer.colour {
        Colour::Rgb => {
            reader
                .rgba_channels(
                    |size, channels: &RgbaChannels| {
                        Texels::new(size.width(), size.height(), channels.3.is_some())
                    },
                    |t: &mut Texels, pos, (r, g, b, a): (f32, f32, f32, f32)| {
                        t.set(pos.x(), pos.y(), Vec3::new(r, g, b), a)
                    },
                )
                .first_valid_layer()
                .all_attributes()
                .non_parallel()
                .from_buffered(Cursor::new(bytes))
                .map_err(|e| e.to_string())?
                .layer_data
                .channel_data
                .pixels
        }
        Colour::Grey(name) => {
            reader
                .specific_channels()
                .required(name.as_str())
                .optional("A", 1.0_f32)
                .collect_pixels(
                    |size, (_, a): &(ChannelDescription, Option<ChannelDescription>)| {
                        Texels::new(size.width(), size.height(), a.is_some())
                    },
                    |t: &mut Texels, pos, (v, a): (f32, f32)| {
                        t.set(pos.x(), pos.y(), Vec3::splat(v), a)
                    },
                )
                .first_valid_layer()
                .all_attributes()
                .non_parallel()
                .from_buffered(Cursor::new(bytes))
                .map_err(|e| e.to_string())?
                .layer_data
                .channel_data
                .pixels
        }
    };
    Ok(pixels)
}

/// Rows of heights, filled bottom-up from pixels given from the top left.
struct Heights {
    width: usize,
    height: usize,
    values: Vec<f32>,
}

impl Heights {
    fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            values: vec![0.0; width * height],
        }
    }

    fn set(&mut self, x: usize, y: usize, value: f32) {
        let Some(row) = self.height.checked_sub(y + 1) else {
            return;
        };
        if let Some(v) = self.values.get_mut(row * self.width + x) {
            *v = value;
        }
    }
}

/// The refusal of a file the reader could not read (truncated, corrupt).
fn unreadable(e: exr::error::Error) -> String {
    format!("not a readable OpenEXR image ({e})")
}

/// Rec. 709 luminance of linear R, G and B.
fn luminance(r: f32, g: f32, b: f32) -> f32 {
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

/// Reads the chosen layer as one value per pixel, bottom row first (a displacement image's
/// heights): a grey channel's value, or the Rec. 709 luminance of R, G and B, as stored
/// (16- or 32-bit float; negative values kept). `A` is not read. On the calling thread, as
/// [`read_layer`].
pub fn read_grey(bytes: &[u8], layer: &ChosenLayer) -> Result<Vec<f32>, String> {
    let reader = read().no_deep_data().largest_resolution_level();
    let heights = match &layer.colour {
        Colour::Rgb => {
            reader
                .rgba_channels(
                    |size, _: &RgbaChannels| Heights::new(size.width(), size.height()),
                    |h: &mut Heights, pos, (r, g, b, _): (f32, f32, f32, f32)| {
                        h.set(pos.x(), pos.y(), luminance(r, g, b))
                    },
                )
                .first_valid_layer()
                .all_attributes()
                .non_parallel()
                .from_buffered(Cursor::new(bytes))
                .map_err(unreadable)?
                .layer_data
                .channel_data
                .pixels
        }
        Colour::Grey(name) => {
            reader
                .specific_channels()
                .required(name.as_str())
                .collect_pixels(
                    |size, _: &(ChannelDescription,)| Heights::new(size.width(), size.height()),
                    |h: &mut Heights, pos, (v,): (f32,)| h.set(pos.x(), pos.y(), v),
                )
                .first_valid_layer()
                .all_attributes()
                .non_parallel()
                .from_buffered(Cursor::new(bytes))
                .map_err(unreadable)?
                .layer_data
                .channel_data
                .pixels
        }
    };
    Ok(heights.values)
}
