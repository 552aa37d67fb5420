//! Polygons with holes (`GeneralPolygon`, `PointsGeneralPolygons`) as triangles: the first
//! loop is the outline, every other loop a hole. The loops are projected onto the outline's
//! plane, each hole is joined to the outline by a bridge edge to a vertex it sees (Eberly's
//! method, rightmost hole first), and the resulting simple polygon is cut into ears. The
//! triangles keep the outline's winding (its front) and name face corners, so per-corner
//! values follow them.

use crate::scene::desc::V3;

/// A corner: its index among all corners written and its point in the plane.
#[derive(Debug, Clone, Copy)]
struct Corner {
    index: usize,
    at: (f64, f64),
}

/// Twice the signed area of a 2D loop.
fn area(points: &[(f64, f64)]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum()
}

fn cross(o: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

/// Whether `p` lies inside or on the counter-clockwise triangle `(a, b, c)`.
fn in_triangle(p: (f64, f64), a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> bool {
    cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0
}

/// Triangulates `loops` (point indices; the first the outline, the others holes) of
/// `points`: triangles of corner indices (positions in the concatenated loops), wound as
/// the outline. `None` when the loops do not make a polygon (degenerate outline, a hole
/// that no bridge reaches, no ear left).
pub fn triangulate(points: &[V3], loops: &[Vec<u32>]) -> Option<Vec<[usize; 3]>> {
    let outline = loops.first()?;
    let point = |i: u32| points.get(i as usize).copied();
    // Newell's normal of the outline: its dominant axis is dropped.
    let mut normal = (0.0, 0.0, 0.0);
    for k in 0..outline.len() {
        let (a, b) = (point(outline[k])?, point(outline[(k + 1) % outline.len()])?);
        normal.0 += (a.1 - b.1) * (a.2 + b.2);
        normal.1 += (a.2 - b.2) * (a.0 + b.0);
        normal.2 += (a.0 - b.0) * (a.1 + b.1);
    }
    let (ax, ay, az) = (normal.0.abs(), normal.1.abs(), normal.2.abs());
    let project = |p: V3| -> (f64, f64) {
        if az >= ax && az >= ay {
            (p.0, p.1)
        } else if ax >= ay {
            (p.1, p.2)
        } else {
            (p.2, p.0)
        }
    };
    let mut first = 0;
    let mut rings: Vec<Vec<Corner>> = Vec::new();
    for l in loops {
        let mut ring = Vec::with_capacity(l.len());
        for (k, &i) in l.iter().enumerate() {
            ring.push(Corner {
                index: first + k,
                at: project(point(i)?),
            });
        }
        first += l.len();
        rings.push(ring);
    }
    let signed = |r: &[Corner]| area(&r.iter().map(|c| c.at).collect::<Vec<_>>());
    let outline_area = signed(&rings[0]);
    if outline_area == 0.0 || !outline_area.is_finite() {
        return None;
    }
    // Work counter-clockwise; holes clockwise.
    let flipped = outline_area < 0.0;
    let mut polygon = rings[0].clone();
    if flipped {
        polygon.reverse();
    }
    let mut holes: Vec<Vec<Corner>> = rings[1..]
        .iter()
        .filter(|h| h.len() >= 3)
        .cloned()
        .map(|mut h| {
            if signed(&h) > 0.0 {
                h.reverse();
            }
            h
        })
        .collect();
    let rightmost = |h: &[Corner]| h.iter().map(|c| c.at.0).fold(f64::MIN, f64::max);
    holes.sort_by(|a, b| rightmost(b).total_cmp(&rightmost(a)));
    for hole in holes {
        polygon = bridge(polygon, &hole)?;
    }
    let mut triangles = ears(polygon)?;
    if flipped {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    Some(triangles)
}

/// Joins the clockwise `hole` to the counter-clockwise `polygon` at a vertex the hole's
/// rightmost vertex sees.
fn bridge(polygon: Vec<Corner>, hole: &[Corner]) -> Option<Vec<Corner>> {
    let (m_at, m) = hole
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.at.0.total_cmp(&b.1.at.0))?;
    let m = m.at;
    // The closest edge the ray from m towards +x crosses.
    let n = polygon.len();
    let mut best: Option<(f64, usize)> = None;
    for i in 0..n {
        let (a, b) = (polygon[i].at, polygon[(i + 1) % n].at);
        if a.1 == b.1 {
            continue;
        }
        let x = a.0 + (m.1 - a.1) * (b.0 - a.0) / (b.1 - a.1);
        let lo = a.1.min(b.1);
        let hi = a.1.max(b.1);
        if m.1 < lo || m.1 > hi || x < m.0 {
            continue;
        }
        if best.is_none_or(|(bx, _)| x < bx) {
            best = Some((x, i));
        }
    }
    let (x, edge) = best?;
    let hit = (x, m.1);
    // The edge's endpoint furthest along x, unless a reflex vertex inside the triangle
    // (m, hit, that endpoint) is closer in angle.
    let (a, b) = (edge, (edge + 1) % n);
    let mut p = if polygon[a].at.0 > polygon[b].at.0 {
        a
    } else {
        b
    };
    let tri = |q: (f64, f64)| {
        let (t0, t1, t2) = (m, hit, polygon[p].at);
        if cross(t0, t1, t2) >= 0.0 {
            in_triangle(q, t0, t1, t2)
        } else {
            in_triangle(q, t0, t2, t1)
        }
    };
    let mut best_angle = f64::INFINITY;
    let mut candidate = None;
    for k in 0..n {
        if k == p {
            continue;
        }
        let (prev, here, next) = (
            polygon[(k + n - 1) % n].at,
            polygon[k].at,
            polygon[(k + 1) % n].at,
        );
        let reflex = cross(prev, here, next) < 0.0;
        if reflex && tri(here) {
            let d = (here.0 - m.0, here.1 - m.1);
            let angle = (d.1.abs() / (d.0 * d.0 + d.1 * d.1).sqrt()).asin();
            if angle < best_angle {
                best_angle = angle;
                candidate = Some(k);
            }
        }
    }
    if let Some(k) = candidate {
        p = k;
    }
    let mut out = Vec::with_capacity(n + hole.len() + 2);
    out.extend_from_slice(&polygon[..=p]);
    for k in 0..=hole.len() {
        out.push(hole[(m_at + k) % hole.len()]);
    }
    out.push(polygon[p]);
    out.extend_from_slice(&polygon[p + 1..]);
    Some(out)
}

/// Ear clipping of a counter-clockwise polygon (bridge vertices may repeat).
fn ears(mut polygon: Vec<Corner>) -> Option<Vec<[usize; 3]>> {
    let mut out = Vec::with_capacity(polygon.len().saturating_sub(2));
    while polygon.len() > 3 {
        let n = polygon.len();
        let ear = (0..n).find(|&k| {
            let (a, b, c) = (
                polygon[(k + n - 1) % n].at,
                polygon[k].at,
                polygon[(k + 1) % n].at,
            );
            if cross(a, b, c) <= 0.0 {
                return false;
            }
            (0..n).all(|j| {
                let q = polygon[j].at;
                j == k
                    || j == (k + 1) % n
                    || j == (k + n - 1) % n
                    || q == a
                    || q == b
                    || q == c
                    || !in_triangle(q, a, b, c)
            })
        });
        // A polygon with only degenerate corners left: drop a collinear one.
        let k = match ear {
            Some(k) => k,
            None => (0..n).find(|&k| {
                let (a, b, c) = (
                    polygon[(k + n - 1) % n].at,
                    polygon[k].at,
                    polygon[(k + 1) % n].at,
                );
                cross(a, b, c) == 0.0
            })?,
        };
        let (a, b, c) = (polygon[(k + n - 1) % n], polygon[k], polygon[(k + 1) % n]);
        if ear.is_some() {
            out.push([a.index, b.index, c.index]);
        }
        polygon.remove(k);
    }
    if polygon.len() == 3 && cross(polygon[0].at, polygon[1].at, polygon[2].at) > 0.0 {
        out.push([polygon[0].index, polygon[1].index, polygon[2].index]);
    }
    Some(out)
}
