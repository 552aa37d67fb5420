//! Anti-aliased rasterisation of contour lines into a premultiplied RGBA layer.
//!
//! A line covers the points within half its (linearly varying) width of it: round joins
//! and round caps. A pixel's coverage is the box-filtered coverage of its centre across the
//! line, `clamp(h + ½ − d, 0, min(1, 2h))` for distance `d` and half-width `h`, which sums
//! to exactly the width across a straight line. Each line takes, per pixel, the coverage
//! of its nearest segment (joints are not counted twice) and is composited `over` the lines
//! below it, in the stacking order of [`super::stacking`] (the one the SVG and EPS follow).

use glam::{Vec2, Vec4};

use super::stacking::layers;
use super::ContourLine;

/// The layer of `lines` on a `width × height` image (premultiplied RGBA, row-major).
pub fn rasterise(lines: &[ContourLine], width: u32, height: u32) -> Vec<Vec4> {
    let (w, h) = (width as usize, height as usize);
    let mut layer = vec![Vec4::ZERO; w * h];
    // Per-line scratch: coverage and colour of the best segment so far, and which pixels
    // this line touched.
    let mut best: Vec<(f32, Vec4)> = vec![(0.0, Vec4::ZERO); w * h];
    let mut touched: Vec<usize> = Vec::new();
    let stacked = layers(lines)
        .into_iter()
        .flat_map(|layer| &lines[layer.lines]);
    for line in stacked {
        let n = line.points.len();
        let segments = if line.closed { n } else { n - 1 };
        for k in 0..segments {
            let (p, q) = (line.points[k], line.points[(k + 1) % n]);
            let reach = 0.5 * p.width.max(q.width) + 1.0;
            let lo = p.pos.min(q.pos) - Vec2::splat(reach);
            let hi = p.pos.max(q.pos) + Vec2::splat(reach);
            let x0 = lo.x.floor().max(0.0) as usize;
            let y0 = lo.y.floor().max(0.0) as usize;
            let x1 = (hi.x.ceil().max(0.0) as usize).min(w);
            let y1 = (hi.y.ceil().max(0.0) as usize).min(h);
            let d = q.pos - p.pos;
            let len2 = d.length_squared();
            for y in y0..y1 {
                for x in x0..x1 {
                    let c = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                    let t = if len2 > 0.0 {
                        ((c - p.pos).dot(d) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let dist = (c - (p.pos + d * t)).length();
                    let half = 0.5 * (p.width + (q.width - p.width) * t);
                    let cover = (half + 0.5 - dist).min(1.0).min(2.0 * half);
                    if cover <= 0.0 {
                        continue;
                    }
                    let i = y * w + x;
                    if best[i].0 == 0.0 {
                        touched.push(i);
                    }
                    if cover > best[i].0 {
                        best[i] = (cover, p.color.lerp(q.color, t));
                    }
                }
            }
        }
        for &i in &touched {
            let (cover, color) = std::mem::replace(&mut best[i], (0.0, Vec4::ZERO));
            let a = color.w * cover;
            let src = (color.truncate() * a).extend(a);
            layer[i] = src + layer[i] * (1.0 - a);
        }
        touched.clear();
    }
    layer
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::ContourPoint;

    fn line(a: Vec2, b: Vec2, width: f32) -> ContourLine {
        let point = |pos| ContourPoint {
            pos,
            color: Vec4::new(1.0, 0.0, 0.0, 1.0),
            width,
        };
        ContourLine {
            material: 1,
            closed: false,
            points: vec![point(a), point(b)],
        }
    }

    #[test]
    fn coverage_across_a_line_sums_to_its_width() {
        for (width, offset) in [(3.0, 0.0), (3.0, 0.3), (1.7, 0.81), (0.4, 0.5)] {
            let x = 10.0 + offset;
            let layer = rasterise(
                &[line(Vec2::new(x, 2.0), Vec2::new(x, 18.0), width)],
                20,
                20,
            );
            let across: f32 = (0..20).map(|c| layer[10 * 20 + c].w).sum();
            assert!((across - width).abs() < 1e-4, "{width} at {x}: {across}");
        }
    }

    #[test]
    fn joints_are_not_counted_twice() {
        let mut l = line(Vec2::new(2.0, 10.0), Vec2::new(10.0, 10.0), 3.0);
        let mut end = l.points[1];
        end.pos = Vec2::new(18.0, 10.0);
        l.points.push(end);
        let layer = rasterise(&[l], 20, 20);
        let across: f32 = (0..20).map(|r| layer[r * 20 + 10].w).sum();
        assert!((across - 3.0).abs() < 1e-4, "{across}");
    }
}
