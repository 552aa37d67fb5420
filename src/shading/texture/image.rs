//! Image textures: PNG or EXR files decoded once at scene load into linear RGB texels and
//! sampled bilinearly at the surface uv, each axis wrapped as its [`Wrap`] says.
//!
//! Conventions: texel `(x, y)` covers `u ∈ [x/w, (x+1)/w)`, `v ∈ [y/h, (y+1)/h)` with its
//! centre at `((x + ½)/w, (y + ½)/h)`; `v = 0` is the **bottom** row of the image file (as in
//! OBJ and RenderMan `t` flipped), so a texture shows upright on a quad whose uv (0, 0) is
//! its lower-left corner. 8-bit PNG codes are decoded with the sRGB curve unless the node says
//! `Linear`; EXR values are taken as linear unless it says `Srgb`. An EXR file's R, G and B
//! are read, else its Y, else its one colour channel (grey); see [`exr_channels`].
//!
//! A file's [`footprint`] is read from its header before it is decoded (the scene loader
//! counts it against the run's memory budget), and decoding fills the texture's texel and
//! alpha arrays straight from the decoder's samples, with no larger intermediate.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::colour::srgb_to_linear;
use super::exr_channels;
pub use crate::components::graph::{Texture, UvWrap, Wrap};
use crate::image_io::png_codec::{self, DecodedPng};

/// How the stored numbers relate to linear RGB.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// sRGB-encoded (decoded with the IEC 61966-2-1 curve).
    Srgb,
    /// Already linear.
    Linear,
}

impl Texture {
    /// The four texels around `uv` and their bilinear weights (weights sum to 1).
    pub fn taps(&self, uv: Vec2) -> [(usize, f32); 4] {
        let (w, h) = (self.width as i64, self.height as i64);
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        let (x, y) = (
            if x.is_finite() { x } else { 0.0 },
            if y.is_finite() { y } else { 0.0 },
        );
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let index = |xi: i64, yi: i64| {
            let (xi, yi) = (
                wrap_texel(self.wrap.u, xi, w),
                wrap_texel(self.wrap.v, yi, h),
            );
            (yi * w + xi) as usize
        };
        // Large but finite coordinates saturate in the cast; wrapping keeps them in range.
        let (x0, y0) = (x0 as i64, y0 as i64);
        [
            (index(x0, y0), (1.0 - fx) * (1.0 - fy)),
            (index(x0.saturating_add(1), y0), fx * (1.0 - fy)),
            (index(x0, y0.saturating_add(1)), (1.0 - fx) * fy),
            (index(x0.saturating_add(1), y0.saturating_add(1)), fx * fy),
        ]
    }

    /// Bilinear lookup of the alpha channel at `uv` (1 when the image has none).
    pub fn sample_alpha(&self, uv: Vec2) -> f32 {
        if self.alpha.is_empty() {
            return 1.0;
        }
        self.taps(uv)
            .iter()
            .fold(0.0, |s, &(i, w)| s + self.alpha[i] * w)
    }

    /// Bilinear lookup at `uv`.
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        if self.texels.is_empty() {
            return Vec3::ZERO;
        }
        self.taps(uv)
            .iter()
            .fold(Vec3::ZERO, |s, &(i, w)| s + self.texels[i] * w)
    }
}

/// The texel of an axis of `n` texels that texel index `i` (any integer, outside the
/// image too) reads under `wrap`. Wrapping whole texels keeps every bilinear footprint
/// right across an edge: `Mirror` extends the image by its reflection (texel `n` reads
/// `n − 1`, texel `−1` reads `0`), so the filter there blends mirrored texels.
fn wrap_texel(wrap: Wrap, i: i64, n: i64) -> i64 {
    match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::Clamp => i.clamp(0, n - 1),
        Wrap::Mirror => {
            // `2n` cannot overflow: a texture's side is a `u32`.
            let m = i.rem_euclid(2 * n);
            if m < n {
                m
            } else {
                2 * n - 1 - m
            }
        }
    }
}

/// Whether a file name is read as EXR (by extension, case-insensitive).
pub fn is_exr(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// What a texture file takes once decoded, read from its header alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Footprint {
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Peak bytes of reading it: the file, the decoder's samples (PNG) and the texture's
    /// texels (12 bytes each) and alpha (4 bytes each, when the image has alpha).
    pub bytes: u64,
}

/// Bytes of one texel's colour (`Vec3`) and of its alpha.
const TEXEL_BYTES: u64 = 12;
const ALPHA_BYTES: u64 = 4;

/// Bytes of a decoded texture's texels and alpha (what it keeps for the run, without the
/// file and the decoder's samples its [`Footprint`] adds while it is read).
pub fn decoded_bytes(texture: &Texture) -> u64 {
    (texture.texels.len() as u64)
        .saturating_mul(TEXEL_BYTES)
        .saturating_add((texture.alpha.len() as u64).saturating_mul(ALPHA_BYTES))
}

/// The [`Footprint`] of a PNG or EXR file's bytes (`exr`: read as EXR), from its header; a
/// file its reader refuses for its size or channels is refused here, before decoding.
pub fn footprint(bytes: &[u8], exr: bool) -> Result<Footprint, String> {
    let (width, height, decoded, alpha) = if exr {
        let layer = exr_channels::choose(bytes)?;
        (layer.width, layer.height, 0, layer.alpha)
    } else {
        let h = png_codec::read_header(bytes)?;
        (
            h.width,
            h.height,
            h.decoded_bytes,
            matches!(h.channels, 2 | 4),
        )
    };
    let pixels = u64::from(width) * u64::from(height);
    let per_texel = TEXEL_BYTES + if alpha { ALPHA_BYTES } else { 0 };
    Ok(Footprint {
        width,
        height,
        bytes: (bytes.len() as u64)
            .saturating_add(decoded)
            .saturating_add(pixels.saturating_mul(per_texel)),
    })
}

/// Reads a PNG or EXR file (chosen by extension) into a texture wrapped as `wrap` (one
/// [`Wrap`] for both axes, or a [`UvWrap`]). `encoding: None` picks the
/// file kind's default (PNG: sRGB, EXR: linear). Non-finite or negative EXR values become 0.
pub fn load(
    path: &Path,
    encoding: Option<Encoding>,
    wrap: impl Into<UvWrap>,
) -> Result<Texture, String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    decode_file(&bytes, is_exr(path), encoding, wrap)
}

/// [`load`] for a file's bytes (`exr`: read as EXR, else PNG).
pub fn decode_file(
    bytes: &[u8],
    exr: bool,
    encoding: Option<Encoding>,
    wrap: impl Into<UvWrap>,
) -> Result<Texture, String> {
    if exr {
        let (width, height, texels, alpha) = decode_exr(bytes)?;
        let encoding = encoding.unwrap_or(Encoding::Linear);
        texture(width, height, texels, alpha, encoding, wrap.into())
    } else {
        decode(bytes, encoding, wrap)
    }
}

/// Decodes an image file held in memory (a PNG inside a glTF file) into a texture;
/// `encoding` and `wrap` as for [`load`] (default sRGB).
pub fn decode(
    bytes: &[u8],
    encoding: Option<Encoding>,
    wrap: impl Into<UvWrap>,
) -> Result<Texture, String> {
    let img = png_codec::decode_png(bytes)?;
    let (texels, alpha) = png_texels(&img);
    drop(img);
    let encoding = encoding.unwrap_or(Encoding::Srgb);
    texture(texels.0, texels.1, texels.2, alpha, encoding, wrap.into())
}

/// Width, height and the bottom-up colours of a decoded PNG, and its bottom-up alpha (empty
/// when the image has none): the texture's arrays, filled straight from the samples.
fn png_texels(img: &DecodedPng) -> ((u32, u32, Vec<Vec3>), Vec<f32>) {
    let w = img.width as usize;
    let bottom_up = || {
        (0..img.height as usize)
            .rev()
            .flat_map(move |y| y * w..(y + 1) * w)
    };
    let texels = bottom_up()
        .map(|p| {
            let [r, g, b, _] = img.rgba(p);
            Vec3::new(r, g, b)
        })
        .collect();
    let alpha = if img.has_alpha() {
        bottom_up().map(|p| img.rgba(p)[3]).collect()
    } else {
        Vec::new()
    };
    ((img.width, img.height, texels), alpha)
}

/// A texture from bottom-up colours as stored and bottom-up alpha (empty: none; alpha is
/// linear whatever the encoding): colours are decoded in place (negative or non-finite ones
/// become 0), alpha clamped to `[0, 1]` (non-finite: 1).
fn texture(
    width: u32,
    height: u32,
    mut texels: Vec<Vec3>,
    mut alpha: Vec<f32>,
    encoding: Encoding,
    wrap: UvWrap,
) -> Result<Texture, String> {
    if width == 0 || height == 0 {
        return Err("the image is empty".into());
    }
    for c in &mut texels {
        let v = Vec3::select(c.cmpge(Vec3::ZERO) & c.is_finite_mask(), *c, Vec3::ZERO);
        *c = match encoding {
            Encoding::Linear => v,
            Encoding::Srgb => Vec3::new(
                srgb_to_linear(v.x),
                srgb_to_linear(v.y),
                srgb_to_linear(v.z),
            ),
        };
    }
    for a in &mut alpha {
        *a = if a.is_finite() {
            a.clamp(0.0, 1.0)
        } else {
            1.0
        };
    }
    Ok(Texture {
        width,
        height,
        texels,
        alpha,
        wrap,
    })
}

/// Width, height, bottom-up colours and bottom-up alpha (empty when the layer has none) of an
/// EXR file's bytes: the first layer with R, G and B, else the first with Y, else the first
/// with one colour channel (grey fills R, G and B; see [`exr_channels`]). Its size is checked
/// from the headers first ([`exr_limits`](crate::image_io::exr_limits)), so a small file
/// claiming a huge image is refused before anything is allocated for it.
pub fn decode_exr(bytes: &[u8]) -> Result<(u32, u32, Vec<Vec3>, Vec<f32>), String> {
    let layer = exr_channels::choose(bytes)?;
    let texels = exr_channels::read_layer(bytes, &layer)?;
    Ok((layer.width, layer.height, texels.colours, texels.alpha))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tex(wrap: impl Into<UvWrap>) -> Texture {
        // 2×2: bottom row (v = 0) red, green; top row blue, white.
        Texture {
            width: 2,
            height: 2,
            texels: vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE],
            alpha: Vec::new(),
            wrap: wrap.into(),
        }
    }

    /// 4×2 texels whose value is `x + 10·y` (a grey), so a lookup names what it read.
    fn ramp(wrap: UvWrap) -> Texture {
        Texture {
            width: 4,
            height: 2,
            texels: (0..8)
                .map(|i| Vec3::splat((i % 4) as f32 + 10.0 * (i / 4) as f32))
                .collect(),
            alpha: Vec::new(),
            wrap,
        }
    }

    fn grey(t: &Texture, u: f32, v: f32) -> f32 {
        let c = t.sample(Vec2::new(u, v));
        assert!(c.x == c.y && c.y == c.z, "{c}");
        c.x
    }

    /// glTF's mirrored repeat of a coordinate into `[0, 1]`: `u` for an even period,
    /// `1 − frac(u)` for an odd one.
    fn mirrored(u: f32) -> f32 {
        let period = u.floor();
        let f = u - period;
        if (period as i64).rem_euclid(2) == 0 {
            f
        } else {
            1.0 - f
        }
    }

    #[test]
    fn mirror_reads_the_reflected_coordinate() {
        let t = ramp(UvWrap::both(Wrap::Mirror));
        let near = |a: f32, b: f32| (a - b).abs() < 1e-5;
        // Texel centres are at u = 0.125, 0.375, 0.625, 0.875 (texels 0 … 3).
        for (u, want) in [
            (0.875, 3.0),
            (1.125, 3.0),
            (1.375, 2.0),
            (1.875, 0.0),
            (2.125, 0.0),
            (-0.125, 0.0),
            (-0.375, 1.0),
            (-1.125, 3.0),
        ] {
            assert!(near(grey(&t, u, 0.25), want), "u = {u}");
        }
        // Between centres, the filter reads mirrored texels: u = 1.25 is u = 0.75 (half
        // texel 2, half texel 3); u = −0.25 is u = 0.25 (texels 0 and 1).
        assert!(near(grey(&t, 1.25, 0.25), 2.5));
        assert!(near(grey(&t, 1.25, 0.25), grey(&t, 0.75, 0.25)));
        assert!(near(grey(&t, -0.25, 0.25), 0.5));
        assert!(near(grey(&t, -0.25, 0.25), grey(&t, 0.25, 0.25)));
        // Continuous at whole numbers: the edge texel on both sides of u = 1 and u = 0
        // (repeat blends in the far edge there).
        assert!(near(grey(&t, 1.0, 0.25), 3.0));
        assert!(near(grey(&t, 0.0, 0.25), 0.0));
        assert!(near(
            grey(&ramp(UvWrap::both(Wrap::Repeat)), 1.0, 0.25),
            1.5
        ));
        // Everywhere: the clamped lookup at the mirrored coordinate, on both axes.
        let clamp = ramp(UvWrap::both(Wrap::Clamp));
        for i in -300..300 {
            let u = i as f32 / 37.0;
            let v = 0.3 - i as f32 / 53.0;
            let (a, b) = (grey(&t, u, v), grey(&clamp, mirrored(u), mirrored(v)));
            assert!((a - b).abs() < 1e-3, "({u}, {v}): {a} vs {b}");
        }
    }

    #[test]
    fn each_axis_wraps_its_own_way() {
        let t = ramp(UvWrap {
            u: Wrap::Mirror,
            v: Wrap::Clamp,
        });
        // v clamps: below the image the bottom row, above it the top row (values + 10).
        assert!((grey(&t, 1.125, -0.7) - 3.0).abs() < 1e-5);
        assert!((grey(&t, 1.125, 5.3) - 13.0).abs() < 1e-5);
        assert!((grey(&t, -0.375, 1.75) - 11.0).abs() < 1e-5);
        // The other way round: u clamps, v mirrors (rows 0, 1 | 1, 0 | 0, 1 …).
        let t = ramp(UvWrap {
            u: Wrap::Clamp,
            v: Wrap::Mirror,
        });
        assert!((grey(&t, -2.0, 1.25) - 10.0).abs() < 1e-5);
        assert!((grey(&t, 7.0, 1.75) - 3.0).abs() < 1e-5);
        assert!((grey(&t, 7.0, 2.25) - 3.0).abs() < 1e-5);
        assert!((grey(&t, 0.125, -0.25) - 0.0).abs() < 1e-5);
        // Repeat on u, mirror on v.
        let t = ramp(UvWrap {
            u: Wrap::Repeat,
            v: Wrap::Mirror,
        });
        assert!((grey(&t, 1.125, 1.25) - 10.0).abs() < 1e-5);
        assert!((grey(&t, -0.125, 1.25) - 13.0).abs() < 1e-5);
    }

    #[test]
    fn texel_centres_return_texels() {
        let t = tex(Wrap::Clamp);
        assert_eq!(t.sample(Vec2::new(0.25, 0.25)), Vec3::X);
        assert_eq!(t.sample(Vec2::new(0.75, 0.25)), Vec3::Y);
        assert_eq!(t.sample(Vec2::new(0.25, 0.75)), Vec3::Z);
        assert_eq!(t.sample(Vec2::new(0.75, 0.75)), Vec3::ONE);
    }

    #[test]
    fn bilinear_between_centres() {
        let t = tex(Wrap::Clamp);
        let c = t.sample(Vec2::new(0.5, 0.5));
        assert!(
            (c - Vec3::new(0.5, 0.5, 0.5)).abs().max_element() < 1e-6,
            "{c}"
        );
        let c = t.sample(Vec2::new(0.375, 0.25));
        assert!(
            (c - Vec3::new(0.75, 0.25, 0.0)).abs().max_element() < 1e-6,
            "{c}"
        );
    }

    #[test]
    fn wrap_and_clamp_differ_at_the_border() {
        // At u = 0 (left edge) on the bottom row: clamp gives red, repeat blends red with
        // the right-hand texel (green) half and half.
        let c = tex(Wrap::Clamp).sample(Vec2::new(0.0, 0.25));
        assert!((c - Vec3::X).abs().max_element() < 1e-6, "{c}");
        let r = tex(Wrap::Repeat).sample(Vec2::new(0.0, 0.25));
        assert!(
            (r - Vec3::new(0.5, 0.5, 0.0)).abs().max_element() < 1e-6,
            "{r}"
        );
        // Repeat tiles: one period away gives the same value.
        let a = tex(Wrap::Repeat).sample(Vec2::new(0.3, 0.6));
        let b = tex(Wrap::Repeat).sample(Vec2::new(-1.7, 3.6));
        assert!((a - b).abs().max_element() < 1e-5);
        // Hostile coordinates stay finite.
        for uv in [
            Vec2::splat(f32::NAN),
            Vec2::splat(1e30),
            Vec2::splat(-f32::MAX),
        ] {
            for wrap in [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror] {
                assert!(tex(wrap).sample(uv).is_finite());
            }
        }
    }
}
