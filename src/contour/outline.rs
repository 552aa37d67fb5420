//! The vector shape of contour lines, shared by the SVG and EPS writers: each line as one
//! filled polygon outlining its varying width (round caps and joins as the raster layer
//! draws them, mitred where the turn is gentle), grouped in the layers of the stacking order
//! ([`super::stacking`]) that the raster layer follows too.

use std::collections::HashSet;

use glam::{Vec2, Vec4};

use super::stacking::layers;
use super::{ContourImage, ContourLine};

/// Points of a half circle (cap) or of a round join.
const ARC_STEPS: usize = 8;

/// One line as a filled shape.
#[derive(Debug, Clone, PartialEq)]
pub struct LineShape {
    /// The line's mean colour (linear RGBA, straight alpha).
    pub color: Vec4,
    /// The outline, pixel coordinates (y down), to fill with the non-zero rule.
    pub polygon: Vec<Vec2>,
}

/// One layer of lines ([`super::stacking::Layer`]): consecutive lines of one material.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerGroup {
    /// The material's name (`material-N` when unnamed).
    pub name: String,
    /// A name for this group alone: the material's name for its first layer, then
    /// `name-2`, `name-3`, … (any name already given gets the next free number), so that
    /// SVG `id`s stay unique when a material's lines lie in several layers.
    pub id: String,
    /// The colour of its first line.
    pub color: Vec4,
    /// Its lines, in the image's line order.
    pub shapes: Vec<LineShape>,
}

/// The image's lines in stacking order ([`super::stacking::layers`], bottom to top), one
/// group per layer, each line as its shape.
pub fn layer_groups(image: &ContourImage) -> Vec<LayerGroup> {
    let mut used: HashSet<String> = HashSet::new();
    layers(&image.lines)
        .into_iter()
        .map(|layer| {
            let m = layer.material;
            let shapes: Vec<LineShape> = image.lines[layer.lines]
                .iter()
                .map(|l| LineShape {
                    color: mean_color(l),
                    polygon: outline(l),
                })
                .collect();
            let name = image
                .material_names
                .get(m as usize - 1)
                .cloned()
                .unwrap_or_else(|| format!("material-{m}"));
            let mut id = name.clone();
            let mut k = 1;
            while !used.insert(id.clone()) {
                k += 1;
                id = format!("{name}-{k}");
            }
            LayerGroup {
                name,
                id,
                color: shapes[0].color,
                shapes,
            }
        })
        .collect()
}

/// The mean colour of a line's points.
fn mean_color(line: &ContourLine) -> Vec4 {
    line.points.iter().map(|p| p.color).sum::<Vec4>() / line.points.len() as f32
}

/// The polygon around `line`: its left side forward, the end cap, its right side back and
/// the start cap (an open line), or the left side then the right side as two rings joined
/// where they start (a closed line).
pub fn outline(line: &ContourLine) -> Vec<Vec2> {
    let pts = &line.points;
    let n = pts.len();
    let dir = |a: Vec2, b: Vec2| (b - a).try_normalize().unwrap_or(Vec2::X);
    let left_of = |d: Vec2| Vec2::new(d.y, -d.x);
    let segments = if line.closed { n } else { n - 1 };
    let seg_dir: Vec<Vec2> = (0..segments)
        .map(|k| dir(pts[k].pos, pts[(k + 1) % n].pos))
        .collect();
    // One side: offset points at each vertex (sign +1 left, −1 right), with round joins
    // on the outside of sharp turns.
    let side = |sign: f32| -> Vec<Vec2> {
        let mut out = Vec::new();
        for k in 0..n {
            let half = 0.5 * pts[k].width * sign;
            let before = if k > 0 || line.closed {
                Some(seg_dir[(k + segments - 1) % segments])
            } else {
                None
            };
            let after = if k < segments { Some(seg_dir[k]) } else { None };
            match (before, after) {
                (Some(a), Some(b)) => {
                    let miter = (left_of(a) + left_of(b)).normalize_or_zero();
                    let cos = miter.dot(left_of(a));
                    if cos > 0.7 {
                        out.push(pts[k].pos + miter * (half / cos));
                    } else {
                        arc(&mut out, pts[k].pos, left_of(a) * half, left_of(b) * half);
                    }
                }
                (Some(d), None) | (None, Some(d)) => out.push(pts[k].pos + left_of(d) * half),
                (None, None) => {}
            }
        }
        out
    };
    let mut left = side(1.0);
    let mut right = side(-1.0);
    right.reverse();
    if line.closed {
        // Both rings, the inner one reversed: with the non-zero fill rule the band between
        // them is filled and the inside stays empty.
        left.push(left[0]);
        right.push(right[0]);
        left.extend(right);
        return left;
    }
    let end = pts[n - 1];
    let start = pts[0];
    let end_left = left_of(seg_dir[segments - 1]) * 0.5 * end.width;
    let start_left = left_of(seg_dir[0]) * 0.5 * start.width;
    let mut out = left;
    cap(&mut out, end.pos, end_left);
    out.extend(right);
    cap(&mut out, start.pos, -start_left);
    out
}

/// Points of the arc from offset `from` to offset `to` around `centre` (inner points only).
fn arc(out: &mut Vec<Vec2>, centre: Vec2, from: Vec2, to: Vec2) {
    let (a0, a1) = (from.y.atan2(from.x), to.y.atan2(to.x));
    let mut sweep = a1 - a0;
    while sweep > std::f32::consts::PI {
        sweep -= std::f32::consts::TAU;
    }
    while sweep < -std::f32::consts::PI {
        sweep += std::f32::consts::TAU;
    }
    let r = from.length();
    for i in 0..=ARC_STEPS {
        let a = a0 + sweep * i as f32 / ARC_STEPS as f32;
        out.push(centre + Vec2::new(a.cos(), a.sin()) * r);
    }
}

/// A half circle cap around `centre` from offset `from` to `−from`, turning away from the
/// line (from the left side over the end to the right side).
fn cap(out: &mut Vec<Vec2>, centre: Vec2, from: Vec2) {
    let a0 = from.y.atan2(from.x);
    let r = from.length();
    for i in 1..ARC_STEPS {
        let a = a0 + std::f32::consts::PI * i as f32 / ARC_STEPS as f32;
        out.push(centre + Vec2::new(a.cos(), a.sin()) * r);
    }
}
