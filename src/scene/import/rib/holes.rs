//! Polygons with holes (`GeneralPolygon`, `PointsGeneralPolygons`) as triangles: the first
//! loop is the outline, every other loop a hole. The loops are projected onto the outline's
//! plane, each hole is joined to the outline by a bridge edge to a vertex it sees (Eberly's
//! method, rightmost hole first), and the resulting simple polygon is cut into ears (the
//! ear test looks only at reflex corners near the ear, in a grid). The triangles keep the
//! outline's winding (its front) and name face corners, so per-corner values follow them.
//! The work is bounded: a polygon whose cut would take more than [`MAX_STEPS`] steps is
//! refused ([`Uncut::TooIntricate`]) rather than taking minutes.

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
/// the outline. An error when the loops do not make a polygon or cutting it would take
/// more than [`MAX_STEPS`].
pub fn triangulate(points: &[V3], loops: &[Vec<u32>]) -> Result<Vec<[usize; 3]>, Uncut> {
    cut(points, loops, MAX_STEPS)
}

/// [`triangulate`] within `steps`.
fn cut(points: &[V3], loops: &[Vec<u32>], steps: usize) -> Result<Vec<[usize; 3]>, Uncut> {
    let mut budget = Budget { left: steps };
    let outline = loops.first().ok_or(Uncut::Degenerate)?;
    let point = |i: u32| points.get(i as usize).copied().ok_or(Uncut::Degenerate);
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
        return Err(Uncut::Degenerate);
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
        budget.spend(2 * polygon.len())?;
        polygon = bridge(polygon, &hole).ok_or(Uncut::Degenerate)?;
    }
    let mut triangles = ears(polygon, &mut budget)?;
    if flipped {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    Ok(triangles)
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

/// Ear clipping of a counter-clockwise polygon (bridge vertices may repeat). The corners
/// are a linked ring; after each cut the corner before is tried again (it may have become
/// an ear), else the walk goes on, and a whole round without an ear ends it. A corner is
/// an ear when no corner that is not strictly convex lies in its triangle (a convex one
/// inside would put a reflex one inside too); those are looked up in the cells of a grid
/// that the triangle crosses. Every ear test and corner looked at is a step of `budget`.
fn ears(polygon: Vec<Corner>, budget: &mut Budget) -> Result<Vec<[usize; 3]>, Uncut> {
    let n = polygon.len();
    let mut out = Vec::with_capacity(n.saturating_sub(2));
    if n < 3 {
        return Ok(out);
    }
    let mut ring = Ring {
        prev: (0..n).map(|i| (i + n - 1) % n).collect(),
        next: (0..n).map(|i| (i + 1) % n).collect(),
    };
    let mut reflex = ReflexGrid::new(&polygon);
    for k in 0..n {
        if ring.turn(&polygon, k) <= 0.0 {
            reflex.insert(k);
        }
    }
    let mut left = n;
    let mut k = 0;
    // Corners tried since the last cut.
    let mut tried = 0;
    while left > 3 {
        if tried >= left {
            // Only degenerate corners left: drop a collinear one (no triangle).
            let mut c = k;
            let collinear = (0..left)
                .find_map(|_| {
                    c = ring.next[c];
                    (ring.turn(&polygon, c) == 0.0).then_some(c)
                })
                .ok_or(Uncut::Degenerate)?;
            budget.spend(left)?;
            let (a, b) = (ring.prev[collinear], ring.next[collinear]);
            ring.unlink(collinear);
            reflex.remove(collinear);
            left -= 1;
            for v in [a, b] {
                reflex.update(v, ring.turn(&polygon, v));
            }
            (k, tried) = (b, 0);
            continue;
        }
        let (a, c) = (ring.prev[k], ring.next[k]);
        if is_ear(&polygon, &ring, &reflex, k, budget)? {
            out.push([polygon[a].index, polygon[k].index, polygon[c].index]);
            ring.unlink(k);
            reflex.remove(k);
            left -= 1;
            for v in [a, c] {
                reflex.update(v, ring.turn(&polygon, v));
            }
            (k, tried) = (a, 0);
        } else {
            (k, tried) = (c, tried + 1);
        }
    }
    let (a, c) = (ring.prev[k], ring.next[k]);
    if ring.turn(&polygon, k) > 0.0 {
        out.push([polygon[a].index, polygon[k].index, polygon[c].index]);
    }
    Ok(out)
}

/// The corners still in the polygon, as a doubly linked ring.
struct Ring {
    prev: Vec<usize>,
    next: Vec<usize>,
}

impl Ring {
    /// Twice the signed area of corner `k` with its neighbours: > 0 where it is convex.
    fn turn(&self, polygon: &[Corner], k: usize) -> f64 {
        cross(
            polygon[self.prev[k]].at,
            polygon[k].at,
            polygon[self.next[k]].at,
        )
    }

    fn unlink(&mut self, k: usize) {
        let (a, c) = (self.prev[k], self.next[k]);
        self.next[a] = c;
        self.prev[c] = a;
    }
}

/// Whether corner `k` (with its neighbours) is an ear: convex, and no corner that is not
/// strictly convex lies in its triangle (corners at the same place as one of its corners,
/// the two ends of a bridge, do not count).
fn is_ear(
    polygon: &[Corner],
    ring: &Ring,
    reflex: &ReflexGrid,
    k: usize,
    budget: &mut Budget,
) -> Result<bool, Uncut> {
    budget.spend(1)?;
    let (a, c) = (ring.prev[k], ring.next[k]);
    let (pa, pb, pc) = (polygon[a].at, polygon[k].at, polygon[c].at);
    if cross(pa, pb, pc) <= 0.0 {
        return Ok(false);
    }
    let (mut cells, mut looked) = (0, 0);
    let blocked = reflex.any_in([pa, pb, pc], &mut cells, |j| {
        looked += 1;
        let q = polygon[j].at;
        j != a && j != k && j != c && q != pa && q != pb && q != pc && in_triangle(q, pa, pb, pc)
    });
    budget.spend(cells + looked)?;
    Ok(!blocked)
}

/// The corners that are not strictly convex, in a uniform grid over the polygon's box
/// with about one cell a corner, cells about square (at most 2²⁰ cells).
struct ReflexGrid {
    points: Vec<(f64, f64)>,
    low: (f64, f64),
    cell: (f64, f64),
    size: (usize, usize),
    cells: Vec<Vec<usize>>,
    /// Per corner: its cell and place in it, while it is in the grid.
    slot: Vec<Option<(usize, usize)>>,
    /// Corners in the grid.
    count: usize,
}

impl ReflexGrid {
    fn new(polygon: &[Corner]) -> Self {
        let points: Vec<(f64, f64)> = polygon.iter().map(|c| c.at).collect();
        let (mut low, mut high) = ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN));
        for p in &points {
            low = (low.0.min(p.0), low.1.min(p.1));
            high = (high.0.max(p.0), high.1.max(p.1));
        }
        let (w, h) = (high.0 - low.0, high.1 - low.1);
        let cells = (points.len() as f64).clamp(1.0, (1 << 20) as f64);
        // Columns × rows ≈ cells, in the proportion of the box.
        let aspect = if w > 0.0 && h > 0.0 && (w / h).is_finite() {
            w / h
        } else {
            1.0
        };
        let columns = (cells * aspect).sqrt().clamp(1.0, cells).ceil() as usize;
        let rows = (cells / columns as f64).ceil().max(1.0) as usize;
        let extent = |e: f64, count: usize| {
            let e = e / count as f64;
            if e > 0.0 && e.is_finite() {
                e
            } else {
                1.0
            }
        };
        ReflexGrid {
            slot: vec![None; points.len()],
            points,
            low,
            cell: (extent(w, columns), extent(h, rows)),
            size: (columns, rows),
            cells: vec![Vec::new(); columns * rows],
            count: 0,
        }
    }

    /// The column (`axis` 0) or row (1) of coordinate `v`, clamped to the grid.
    fn index(&self, v: f64, axis: usize) -> usize {
        let (low, cell, size) = if axis == 0 {
            (self.low.0, self.cell.0, self.size.0)
        } else {
            (self.low.1, self.cell.1, self.size.1)
        };
        (((v - low) / cell).max(0.0) as usize).min(size - 1)
    }

    fn insert(&mut self, k: usize) {
        if self.slot[k].is_some() {
            return;
        }
        let p = self.points[k];
        let cell = self.index(p.1, 1) * self.size.0 + self.index(p.0, 0);
        self.slot[k] = Some((cell, self.cells[cell].len()));
        self.cells[cell].push(k);
        self.count += 1;
    }

    fn remove(&mut self, k: usize) {
        let Some((cell, place)) = self.slot[k].take() else {
            return;
        };
        self.cells[cell].swap_remove(place);
        if let Some(&moved) = self.cells[cell].get(place) {
            self.slot[moved] = Some((cell, place));
        }
        self.count -= 1;
    }

    /// Keeps corner `k` in the grid exactly while its `turn` is not strictly convex.
    fn update(&mut self, k: usize, turn: f64) {
        if turn > 0.0 {
            self.remove(k);
        } else {
            self.insert(k);
        }
    }

    /// Whether `test` holds for a corner in a cell that the triangle crosses: row by row,
    /// the columns between where its edges cross that row (widened by a millionth of a
    /// cell, for rounding). Counts the cells looked at in `cells`.
    fn any_in(
        &self,
        triangle: [(f64, f64); 3],
        cells: &mut usize,
        mut test: impl FnMut(usize) -> bool,
    ) -> bool {
        if self.count == 0 {
            return false;
        }
        let ys = triangle.map(|p| p.1);
        let row0 = self.index(ys.iter().copied().fold(f64::MAX, f64::min), 1);
        let row1 = self.index(ys.iter().copied().fold(f64::MIN, f64::max), 1);
        for row in row0..=row1 {
            let bottom = self.low.1 + row as f64 * self.cell.1;
            let top = bottom + self.cell.1;
            let (slack_x, slack_y) = (self.cell.0 * 1e-6, self.cell.1 * 1e-6);
            let (bottom, top) = (
                if row == 0 { f64::MIN } else { bottom - slack_y },
                if row + 1 == self.size.1 {
                    f64::MAX
                } else {
                    top + slack_y
                },
            );
            let (mut x0, mut x1) = (f64::MAX, f64::MIN);
            for e in 0..3 {
                let (p, q) = (triangle[e], triangle[(e + 1) % 3]);
                if let Some((a, b)) = clip_to_rows(p, q, bottom, top) {
                    x0 = x0.min(a.min(b));
                    x1 = x1.max(a.max(b));
                }
            }
            if x0 > x1 {
                continue;
            }
            let (c0, c1) = (self.index(x0 - slack_x, 0), self.index(x1 + slack_x, 0));
            // A row's edge clipping costs about four cells.
            *cells += c1 - c0 + 1 + 4;
            let row_cells = &self.cells[row * self.size.0 + c0..=row * self.size.0 + c1];
            if row_cells.iter().flatten().any(|&j| test(j)) {
                return true;
            }
        }
        false
    }
}

/// The x-coordinates of where segment `p`–`q` enters and leaves the rows
/// `bottom ≤ y ≤ top`, if it crosses them.
fn clip_to_rows(p: (f64, f64), q: (f64, f64), bottom: f64, top: f64) -> Option<(f64, f64)> {
    let (p, q) = if p.1 <= q.1 { (p, q) } else { (q, p) };
    if q.1 < bottom || p.1 > top {
        return None;
    }
    if p.1 == q.1 {
        return Some((p.0, q.0));
    }
    let x_at = |y: f64| p.0 + (y - p.1) * (q.0 - p.0) / (q.1 - p.1);
    let from = if p.1 >= bottom { p.0 } else { x_at(bottom) };
    let to = if q.1 <= top { q.0 } else { x_at(top) };
    Some((from, to))
}

/// Why a polygon was not cut into triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Uncut {
    /// Its loops do not make a polygon (degenerate outline, a hole no bridge reaches, no
    /// ear left).
    Degenerate,
    /// Cutting it would take more than [`MAX_STEPS`] steps.
    TooIntricate,
}

/// The most steps (ear tests, grid cells and reflex corners looked at, corners passed by
/// the bridges) that cutting one polygon may take: up to about two seconds of work. Only
/// polygons with tens of thousands of corners arranged so that most cuts look at many of
/// them reach it (a 40,000-corner comb with a hole along its back takes about 425 million);
/// a 100,000-corner star takes about 95 million, a 10,000-corner one 2.4 million.
pub const MAX_STEPS: usize = 200_000_000;

/// The steps left for one polygon.
struct Budget {
    left: usize,
}

impl Budget {
    fn spend(&mut self, steps: usize) -> Result<(), Uncut> {
        self.left = self.left.checked_sub(steps).ok_or(Uncut::TooIntricate)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Twice the signed area of loop `l` of `points`.
    fn loop_area(points: &[V3], l: &[u32]) -> f64 {
        area(
            &l.iter()
                .map(|&i| (points[i as usize].0, points[i as usize].1))
                .collect::<Vec<_>>(),
        )
    }

    /// Checks that `triangles` of `loops` cover the outline less the holes, each
    /// triangle wound as the outline: their count and their area.
    fn assert_cut(points: &[V3], loops: &[Vec<u32>], triangles: &[[usize; 3]]) {
        let corners: Vec<u32> = loops.concat();
        let outline = loop_area(points, &loops[0]);
        let holes: f64 = loops[1..].iter().map(|l| loop_area(points, l).abs()).sum();
        assert_eq!(triangles.len(), corners.len() + 2 * (loops.len() - 1) - 2);
        let mut total = 0.0;
        for t in triangles {
            let p = |k: usize| {
                let q = points[corners[t[k]] as usize];
                (q.0, q.1)
            };
            let a = cross(p(0), p(1), p(2));
            assert!(
                a * outline.signum() > 0.0,
                "{t:?} is wound against the outline"
            );
            total += a;
        }
        let expected = outline - holes * outline.signum();
        assert!(
            (total - expected).abs() <= 1e-9 * expected.abs(),
            "area {total}, expected {expected}"
        );
    }

    /// A spiral band of `2·n` corners (its inner edge out, its outer edge back: every
    /// corner of the inner edge is reflex) with a small square hole near its start.
    fn spiral(n: usize) -> (Vec<V3>, Vec<Vec<u32>>) {
        let arm = |i: usize, off: f64| {
            let a = i as f64 * 0.05;
            let r = 1.0 + 0.1 * a + off;
            (r * a.cos(), r * a.sin(), 0.0)
        };
        let mut points: Vec<V3> = (0..n).map(|i| arm(i, 0.0)).collect();
        points.extend((0..n).rev().map(|i| arm(i, 0.3)));
        let m = points.len() as u32;
        for (x, y) in [(1.1, 0.1), (1.2, 0.1), (1.2, 0.2), (1.1, 0.2)] {
            points.push((x, y, 0.0));
        }
        (points, vec![(0..m).collect(), (m..m + 4).collect()])
    }

    /// A comb of `teeth` teeth on a back 1 high, with a hole along its back.
    fn comb(teeth: usize) -> (Vec<V3>, Vec<Vec<u32>>) {
        let w = 2.0 * teeth as f64;
        let mut points = vec![(0.0, 0.0, 0.0), (w, 0.0, 0.0)];
        for t in (0..teeth).rev() {
            let x = 2.0 * t as f64;
            for p in [
                (x + 2.0, 1.0),
                (x + 1.5, 4.0),
                (x + 1.0, 4.0),
                (x + 1.0, 1.0),
            ] {
                points.push((p.0, p.1, 0.0));
            }
        }
        points.dedup();
        let m = points.len() as u32;
        for (x, y) in [(1.5, 0.25), (1.5, 0.75), (w - 0.5, 0.75), (w - 0.5, 0.25)] {
            points.push((x, y, 0.0));
        }
        (points, vec![(0..m).collect(), (m..m + 4).collect()])
    }

    #[test]
    fn a_square_with_a_square_hole_is_eight_triangles() {
        let points = [
            (0.0, 0.0, 0.0),
            (4.0, 0.0, 0.0),
            (4.0, 4.0, 0.0),
            (0.0, 4.0, 0.0),
            (1.0, 1.0, 0.0),
            (1.0, 3.0, 0.0),
            (3.0, 3.0, 0.0),
            (3.0, 1.0, 0.0),
        ];
        let loops = [vec![0, 1, 2, 3], vec![4, 5, 6, 7]];
        let triangles = triangulate(&points, &loops).unwrap();
        assert_cut(&points, &loops, &triangles);
        // Wound clockwise, the triangles are too.
        let loops = [vec![3, 2, 1, 0], vec![4, 5, 6, 7]];
        assert_cut(&points, &loops, &triangulate(&points, &loops).unwrap());
    }

    #[test]
    fn a_spiral_of_ten_thousand_reflex_heavy_corners_is_cut_in_milliseconds() {
        // The old ear clipping (every corner tested against every corner, the search
        // started again from the first corner after each cut) took 9 s on this spiral.
        let (points, loops) = spiral(5000);
        let start = std::time::Instant::now();
        let triangles = triangulate(&points, &loops).unwrap();
        let took = start.elapsed();
        assert_cut(&points, &loops, &triangles);
        assert!(took.as_secs_f64() < 1.0, "took {took:?}");
    }

    #[test]
    fn a_comb_with_a_hole_along_its_back_is_cut_or_refused_within_the_steps() {
        let (points, loops) = comb(2500);
        assert_cut(&points, &loops, &triangulate(&points, &loops).unwrap());
        // The same comb, given fewer steps than it needs, is refused rather than cut.
        assert_eq!(cut(&points, &loops, 1_000_000), Err(Uncut::TooIntricate));
        // A 10,000-corner star takes far fewer.
        let star: Vec<V3> = (0..10_000)
            .map(|i| {
                let a = i as f64 / 10_000.0 * std::f64::consts::TAU;
                let r = if i % 2 == 0 { 1.0 } else { 0.5 };
                (r * a.cos(), r * a.sin(), 0.0)
            })
            .collect();
        let loops = [(0..10_000).collect()];
        assert_cut(&star, &loops, &cut(&star, &loops, 5_000_000).unwrap());
    }
}
