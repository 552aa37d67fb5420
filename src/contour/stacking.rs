//! The stacking order of contour lines, the one order every writer draws them in: the raster
//! layer (and so the PNG composite and the EXR contour layer) and the vector writers (SVG
//! groups, EPS fills). Bottom to top it is the image's line order — the deeper ray levels
//! first, so that the lines of the first hits lie over what mirrors and refractions show,
//! and within a level the order the lines were linked in. Consecutive lines of one material
//! make one layer; a material whose lines are interleaved with another's gets one layer per
//! run, so that where two lines overlap the later one is on top in every output.

use std::ops::Range;

use super::ContourLine;

/// A run of consecutive lines of one material: one group of the SVG, one colour block of
/// the EPS.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layer {
    /// 1 + the index of the material (as [`ContourLine::material`]).
    pub material: u32,
    /// The lines, as indices into the image's lines.
    pub lines: Range<usize>,
}

/// The layers of `lines`, bottom to top; each line is in exactly one, in line order.
pub fn layers(lines: &[ContourLine]) -> Vec<Layer> {
    let mut out: Vec<Layer> = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        match out.last_mut() {
            Some(layer) if layer.material == line.material => layer.lines.end = k + 1,
            _ => out.push(Layer {
                material: line.material,
                lines: k..k + 1,
            }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::ContourPoint;
    use glam::{Vec2, Vec4};

    fn line(material: u32) -> ContourLine {
        let p = ContourPoint {
            pos: Vec2::ZERO,
            color: Vec4::ONE,
            width: 1.0,
        };
        ContourLine {
            material,
            closed: false,
            points: vec![p, p],
        }
    }

    #[test]
    fn runs_of_one_material_in_line_order() {
        let lines: Vec<ContourLine> = [2, 2, 1, 2, 3, 3].map(line).to_vec();
        let got: Vec<(u32, Range<usize>)> = layers(&lines)
            .into_iter()
            .map(|l| (l.material, l.lines))
            .collect();
        assert_eq!(got, [(2, 0..2), (1, 2..3), (2, 3..4), (3, 4..6)]);
        assert!(layers(&[]).is_empty());
    }
}
