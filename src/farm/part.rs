//! Which share of a render one farm part computes: `--part K/N` with `--split tiles|samples`.
//!
//! - **Tiles**: the image is cut into [`TILE`]×[`TILE`] pixel tiles in row-major order and
//!   tile `t` belongs to part `t mod N + 1` (interleaved, so every part gets a share of the
//!   expensive regions). A part computes every sample of the pixels it owns. Pixels depend
//!   only on (seed, pixel index, sample index), so the pixel filter needs no border: each
//!   sample lands in the pixel that drew it. With adaptive sampling a part also takes the
//!   first pass of the pixels next to its tiles, because refinement compares neighbours.
//! - **Samples**: every part computes every pixel, samples `spp·(K−1)/N .. spp·K/N` of it.
//!   Sums are exact ([`crate::exact_sum`]), so adding the parts gives the single render's
//!   bits. Adaptive sampling cannot be split this way (a pixel's second pass depends on all
//!   of its first-pass samples) and is refused.

use std::fmt;
use std::ops::Range;
use std::str::FromStr;

/// Side of a tile of the `tiles` split, in pixels.
pub const TILE: usize = 16;

/// How the work is divided between parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Split {
    /// Interleaved image tiles.
    Tiles,
    /// Ranges of the sample indices of every pixel.
    Samples,
}

impl Split {
    /// The name used on the command line and in part files.
    pub fn name(self) -> &'static str {
        match self {
            Split::Tiles => "tiles",
            Split::Samples => "samples",
        }
    }

    /// The split named `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "tiles" => Some(Split::Tiles),
            "samples" => Some(Split::Samples),
            _ => None,
        }
    }
}

impl fmt::Display for Split {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Part `index` (1-based) of `count`, divided by `split`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Part {
    /// 1-based part number `K`.
    pub index: u32,
    /// Number of parts `N`.
    pub count: u32,
    /// How the work is divided.
    pub split: Split,
}

/// The most parts a render may be split into.
pub const MAX_PARTS: u32 = 1_000_000;

/// `K/N` as written on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PartNumber {
    /// `K`.
    pub index: u32,
    /// `N`.
    pub count: u32,
}

impl FromStr for PartNumber {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let expected =
            || format!("expected K/N with 1 ≤ K ≤ N ≤ {MAX_PARTS}, e.g. 2/4; got \"{s}\"");
        let (k, n) = s.split_once('/').ok_or_else(expected)?;
        let k: u32 = k.trim().parse().map_err(|_| expected())?;
        let n: u32 = n.trim().parse().map_err(|_| expected())?;
        if k == 0 || k > n || n > MAX_PARTS {
            return Err(expected());
        }
        Ok(Self { index: k, count: n })
    }
}

impl Part {
    /// The whole render as one part.
    pub fn whole() -> Self {
        Self {
            index: 1,
            count: 1,
            split: Split::Tiles,
        }
    }

    /// The part that owns pixel `(x, y)` of a `width`-wide image (1-based), for the tiles
    /// split; every part shares every pixel under the samples split (then 1 is returned:
    /// part 1 carries the centre-sample passes).
    pub fn owner_of(split: Split, count: u32, x: usize, y: usize, width: usize) -> u32 {
        match split {
            Split::Samples => 1,
            Split::Tiles => {
                let tiles_x = width.div_ceil(TILE).max(1);
                let tile = (y / TILE) * tiles_x + x / TILE;
                (tile % count as usize) as u32 + 1
            }
        }
    }

    /// Whether this part computes the samples of pixel `(x, y)`.
    pub fn owns(&self, x: usize, y: usize, width: usize) -> bool {
        match self.split {
            Split::Samples => true,
            Split::Tiles => Self::owner_of(self.split, self.count, x, y, width) == self.index,
        }
    }

    /// Whether this part needs the first pass of pixel `(x, y)`: its own pixels and, when
    /// `neighbours` (adaptive refinement compares them), those next to one.
    pub fn needs_first_pass(
        &self,
        x: usize,
        y: usize,
        width: usize,
        height: usize,
        neighbours: bool,
    ) -> bool {
        if self.owns(x, y, width) {
            return true;
        }
        if !neighbours {
            return false;
        }
        (y.saturating_sub(1)..(y + 2).min(height))
            .any(|ny| (x.saturating_sub(1)..(x + 2).min(width)).any(|nx| self.owns(nx, ny, width)))
    }

    /// Whether this part traces the centre-sample passes (depth, normal, ids) of the pixels
    /// it computes: every part of a tiles split (of its own pixels), only part 1 of a samples
    /// split, whose merge takes them from part 1 alone; the other parts' files hold none
    /// (depth +∞, normal and ids zero).
    pub fn traces_centres(&self) -> bool {
        match self.split {
            Split::Tiles => true,
            Split::Samples => self.index == 1,
        }
    }

    /// The sample indices this part takes of a pixel with `spp` samples.
    pub fn samples(&self, spp: u32) -> Range<u32> {
        match self.split {
            Split::Tiles => 0..spp,
            Split::Samples => {
                let at = |k: u32| (u64::from(spp) * u64::from(k) / u64::from(self.count)) as u32;
                at(self.index - 1)..at(self.index)
            }
        }
    }
}

/// What one part computes of a `width`×`height` image with `spp` samples per pixel (the
/// adaptive minimum for the tiles split, where it does not matter).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Share {
    /// Samples of some pixels.
    Samples,
    /// No samples, only the centre-sample passes (depth, normal, ids), which the merge takes
    /// from part 1 of a samples split; the reason says why it takes no samples.
    CentresOnly(String),
    /// Nothing: its part file is empty. The reason says why.
    Nothing(String),
}

/// Number of [`TILE`]×[`TILE`] tiles of a `width`×`height` image.
pub fn tile_count(width: u32, height: u32) -> u64 {
    u64::from(width).div_ceil(TILE as u64) * u64::from(height).div_ceil(TILE as u64)
}

/// The most parts that each get work when `split` divides a `width`×`height` image with
/// `spp` samples per pixel: its tiles, or its samples per pixel.
pub fn useful_parts(split: Split, width: u32, height: u32, spp: u32) -> u64 {
    match split {
        Split::Tiles => tile_count(width, height),
        Split::Samples => u64::from(spp),
    }
}

impl Part {
    /// What this part computes of a `width`×`height` image with `spp` samples per pixel.
    pub fn share(&self, width: u32, height: u32, spp: u32) -> Share {
        let (k, n) = (self.index, self.count);
        match self.split {
            Split::Tiles => {
                let tiles = tile_count(width, height);
                if u64::from(k) <= tiles {
                    return Share::Samples;
                }
                Share::Nothing(format!(
                    "{self} owns no tile: the {width}×{height} image has {}",
                    plural(
                        tiles,
                        &format!("tile of {TILE}×{TILE} pixels"),
                        &format!("tiles of {TILE}×{TILE} pixels")
                    )
                ))
            }
            Split::Samples => {
                if !self.samples(spp).is_empty() {
                    return Share::Samples;
                }
                let why = format!(
                    "{self} takes no samples: {} per pixel, fewer than the {n} parts",
                    plural(u64::from(spp), "sample", "samples"),
                );
                if k == 1 {
                    Share::CentresOnly(why)
                } else {
                    Share::Nothing(why)
                }
            }
        }
    }
}

/// `n` and the noun for that many.
pub(crate) fn plural(n: u64, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "part {}/{} ({})", self.index, self.count, self.split)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn part_numbers_parse_and_refuse_nonsense() {
        assert_eq!(
            "2/4".parse::<PartNumber>(),
            Ok(PartNumber { index: 2, count: 4 })
        );
        for bad in ["0/4", "5/4", "4", "a/b", "1/0", "1/2000000"] {
            let e = bad.parse::<PartNumber>().unwrap_err();
            assert!(e.starts_with("expected K/N"), "{bad}: {e}");
        }
    }

    #[test]
    fn every_pixel_has_exactly_one_owner_and_sample_ranges_tile_the_spp() {
        let (w, h) = (37, 21);
        for n in [1, 2, 3, 7] {
            for y in 0..h {
                for x in 0..w {
                    let owners = (1..=n)
                        .filter(|&k| {
                            Part {
                                index: k,
                                count: n,
                                split: Split::Tiles,
                            }
                            .owns(x, y, w)
                        })
                        .count();
                    assert_eq!(owners, 1);
                }
            }
            let mut next = 0;
            for k in 1..=n {
                let r = Part {
                    index: k,
                    count: n,
                    split: Split::Samples,
                }
                .samples(10);
                assert_eq!(r.start, next);
                next = r.end;
            }
            assert_eq!(next, 10);
        }
    }
}
