//! Linking edge crossings into polylines. Each cell of four neighbouring samples joins the
//! crossings on its sides: two crossings of one material make a segment; three or four (or
//! two of different materials) meet at a junction point, their mean. Every crossing lies on
//! the side shared by two cells, so each segment is made once. Chains then follow segments
//! through points where exactly two segments of one material meet; they end at line ends,
//! at junctions and where the material changes, and closed loops come back to their start.

use glam::Vec2;

use super::contrast::{Crossing, EdgeCrossings};

/// A point of a linked chain: its position and the crossing that styles it (a junction
/// takes the crossing its segment comes from).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainPoint {
    /// Film position, pixels.
    pub pos: Vec2,
    /// The crossing that styles this point.
    pub crossing: Crossing,
}

/// A chain of points of one material (the front material of its crossings).
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// 1 + material index.
    pub material: u32,
    /// Whether the last point joins back to the first (the first point is not repeated).
    pub closed: bool,
    /// The points, at least two.
    pub points: Vec<ChainPoint>,
}

/// A segment between two nodes, styled by the crossing at its crossing end.
struct Segment {
    ends: [usize; 2],
    material: u32,
    crossing: Crossing,
}

/// Links `crossings` into chains, in a deterministic order (cells row by row).
pub fn link(crossings: &EdgeCrossings) -> Vec<Chain> {
    let (w, h) = (crossings.width as usize, crossings.height as usize);
    if w < 2 || h < 2 {
        return Vec::new();
    }
    let horizontal = |x: usize, y: usize| crossings.horizontal[y * (w - 1) + x];
    let vertical = |x: usize, y: usize| crossings.vertical[y * w + x];
    // Nodes: crossings (numbered as met), then junctions.
    let mut node_of_h = vec![u32::MAX; crossings.horizontal.len()];
    let mut node_of_v = vec![u32::MAX; crossings.vertical.len()];
    let mut positions: Vec<Vec2> = Vec::new();
    let node = |slot: &mut u32, c: &Crossing, positions: &mut Vec<Vec2>| -> usize {
        if *slot == u32::MAX {
            *slot = positions.len() as u32;
            positions.push(c.pos);
        }
        *slot as usize
    };
    let mut segments: Vec<Segment> = Vec::new();
    // Junction nodes with the corner of their cell (film position of its first sample).
    let mut junctions: Vec<(usize, Vec2)> = Vec::new();
    for cy in 0..h - 1 {
        for cx in 0..w - 1 {
            let sides = [
                (horizontal(cx, cy), true, cy * (w - 1) + cx),
                (vertical(cx + 1, cy), false, cy * w + cx + 1),
                (horizontal(cx, cy + 1), true, (cy + 1) * (w - 1) + cx),
                (vertical(cx, cy), false, cy * w + cx),
            ];
            let mut found: Vec<(usize, Crossing)> = Vec::with_capacity(4);
            for (c, is_h, index) in sides {
                let Some(c) = c else { continue };
                let slot = if is_h {
                    &mut node_of_h[index]
                } else {
                    &mut node_of_v[index]
                };
                found.push((node(slot, &c, &mut positions), c));
            }
            match found.as_slice() {
                [] | [_] => {}
                [(a, ca), (b, _)] if ca.front.material == found[1].1.front.material => {
                    segments.push(Segment {
                        ends: [*a, *b],
                        material: ca.front.material,
                        crossing: *ca,
                    });
                }
                _ => {
                    let centre =
                        found.iter().map(|(_, c)| c.pos).sum::<Vec2>() / found.len() as f32;
                    let junction = positions.len();
                    positions.push(centre);
                    junctions.push((junction, Vec2::new(cx as f32, cy as f32) + 0.5));
                    for (n, c) in &found {
                        segments.push(Segment {
                            ends: [*n, junction],
                            material: c.front.material,
                            crossing: *c,
                        });
                    }
                }
            }
        }
    }
    place_junctions(&mut positions, &segments, &junctions);
    chains(&positions, &segments)
}

/// Moves each junction from the mean of its crossings to where the lines arriving at it
/// meet: the least-squares intersection of the lines through each of its crossings and the
/// node before that crossing (a corner may lie in the next cell, whose two crossings cut
/// it). It stays at the mean when the lines are near parallel or meet more than a pixel
/// outside its cell.
fn place_junctions(positions: &mut [Vec2], segments: &[Segment], junctions: &[(usize, Vec2)]) {
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); positions.len()];
    for (i, s) in segments.iter().enumerate() {
        incident[s.ends[0]].push(i);
        incident[s.ends[1]].push(i);
    }
    let other = |seg: usize, node: usize| {
        let e = segments[seg].ends;
        if e[0] == node {
            e[1]
        } else {
            e[0]
        }
    };
    for &(j, corner) in junctions {
        // Normal equations of Σ |(I − u uᵀ)(x − c)|² over the arriving lines.
        let (mut a11, mut a12, mut a22, mut b) = (0.0f32, 0.0f32, 0.0f32, Vec2::ZERO);
        for &seg in &incident[j] {
            let c = other(seg, j);
            let Some(&before) = incident[c].iter().find(|&&s| s != seg) else {
                continue;
            };
            let Some(u) = (positions[c] - positions[other(before, c)]).try_normalize() else {
                continue;
            };
            let (p11, p12, p22) = (1.0 - u.x * u.x, -u.x * u.y, 1.0 - u.y * u.y);
            let pc = positions[c];
            a11 += p11;
            a12 += p12;
            a22 += p22;
            b += Vec2::new(p11 * pc.x + p12 * pc.y, p12 * pc.x + p22 * pc.y);
        }
        let det = a11 * a22 - a12 * a12;
        if det < 0.05 {
            continue;
        }
        let x = Vec2::new(a22 * b.x - a12 * b.y, a11 * b.y - a12 * b.x) / det;
        let inside = x.cmpge(corner - 1.0).all() && x.cmple(corner + 2.0).all();
        if inside {
            positions[j] = x;
        }
    }
}

/// Follows the segments into chains.
fn chains(positions: &[Vec2], segments: &[Segment]) -> Vec<Chain> {
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); positions.len()];
    for (i, s) in segments.iter().enumerate() {
        incident[s.ends[0]].push(i);
        incident[s.ends[1]].push(i);
    }
    // The segment a chain arriving at `node` over `from` continues with, if any.
    let next = |node: usize, from: usize| -> Option<usize> {
        let [a, b] = incident[node][..] else {
            return None;
        };
        let other = if a == from { b } else { a };
        (segments[other].material == segments[from].material).then_some(other)
    };
    let mut used = vec![false; segments.len()];
    let mut out = Vec::new();
    let walk = |start: usize, first: usize, used: &mut Vec<bool>| -> Chain {
        let s = &segments[first];
        let mut points = vec![ChainPoint {
            pos: positions[start],
            crossing: s.crossing,
        }];
        let (mut node, mut seg) = (start, first);
        let closed = loop {
            used[seg] = true;
            let s = &segments[seg];
            node = if s.ends[0] == node {
                s.ends[1]
            } else {
                s.ends[0]
            };
            if node == start {
                break true;
            }
            points.push(ChainPoint {
                pos: positions[node],
                crossing: s.crossing,
            });
            match next(node, seg) {
                Some(n) if !used[n] => seg = n,
                _ => break false,
            }
        };
        Chain {
            material: s.material,
            closed,
            points,
        }
    };
    // Open chains start where they cannot continue backwards.
    for (i, s) in segments.iter().enumerate() {
        for end in s.ends {
            if !used[i] && next(end, i).is_none() {
                out.push(walk(end, i, &mut used));
            }
        }
    }
    // What is left are closed loops.
    for i in 0..segments.len() {
        if !used[i] {
            let start = segments[i].ends[0];
            out.push(walk(start, i, &mut used));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::store::ContourSample;

    fn grid(w: u32, h: u32) -> EdgeCrossings {
        EdgeCrossings {
            width: w,
            height: h,
            horizontal: vec![None; ((w - 1) * h) as usize],
            vertical: vec![None; (w * (h - 1)) as usize],
        }
    }

    fn at(x: f32, y: f32, material: u32) -> Option<Crossing> {
        let front = ContourSample {
            material,
            instance: 1,
            ..ContourSample::BACKGROUND
        };
        Some(Crossing {
            pos: Vec2::new(x, y),
            front,
            back: ContourSample::BACKGROUND,
        })
    }

    #[test]
    fn a_vertical_line_is_one_chain_without_duplicates() {
        // Crossings between columns 1 and 2 on every row of a 4×4 grid.
        let mut g = grid(4, 4);
        for y in 0..4 {
            g.horizontal[y * 3 + 1] = at(2.0, y as f32 + 0.5, 1);
        }
        let chains = link(&g);
        assert_eq!(chains.len(), 1);
        assert!(!chains[0].closed);
        let ys: Vec<f32> = chains[0].points.iter().map(|p| p.pos.y).collect();
        assert!(
            ys == [0.5, 1.5, 2.5, 3.5] || ys == [3.5, 2.5, 1.5, 0.5],
            "{ys:?}"
        );
    }

    #[test]
    fn a_square_ring_closes_and_a_t_junction_makes_three_chains() {
        // One sample inside a 3×3 grid differs from all its neighbours: a closed loop.
        let mut g = grid(3, 3);
        g.horizontal[2] = at(1.0, 1.5, 1);
        g.horizontal[3] = at(2.0, 1.5, 1);
        g.vertical[1] = at(1.5, 1.0, 1);
        g.vertical[4] = at(1.5, 2.0, 1);
        let chains = link(&g);
        assert_eq!(chains.len(), 1);
        assert!(chains[0].closed);
        assert_eq!(chains[0].points.len(), 4);

        // A horizontal line across a 3×3 grid with a branch going down in the middle.
        let mut g = grid(3, 3);
        g.vertical[0] = at(0.5, 1.0, 1);
        g.vertical[1] = at(1.5, 1.0, 1);
        g.vertical[2] = at(2.5, 1.0, 1);
        g.horizontal[2] = at(1.0, 1.5, 1);
        g.horizontal[4] = at(1.0, 2.5, 1);
        let chains = link(&g);
        let lengths: Vec<usize> = chains.iter().map(|c| c.points.len()).collect();
        assert_eq!(chains.len(), 3, "{lengths:?}");
        let segments: usize = chains.iter().map(|c| c.points.len() - 1).sum();
        assert_eq!(segments, 5, "each segment once");
    }
}
