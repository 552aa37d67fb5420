//! A uniform grid over a photon map's points for the one-nearest lookup of final gathering
//! ([`super::irradiance`]): the same answer as [`PhotonMap::nearest`] with `k = 1`, found by
//! scanning the few grid rows around the query instead of descending a kd-tree.
//!
//! **Layout.** Points are counting-sorted by cell, cells in x-fastest order, so the points of
//! a run of cells along x are one contiguous slice: a search block of cells is one slice per
//! (y, z) row. Each entry carries the point's position, normal and map index (32 bytes), so
//! a scan reads nothing else.
//!
//! **Search.** The block of cells covering `p ± r`, starting with `r` the cell size (about the
//! spacing of surface points): the best point in it (least squared distance, then least
//! index) is the answer once it is nearer than every point outside the block can be (about
//! `r`: cell indices are monotone in the coordinate, see [`PointGrid::clearance`]), or when
//! nothing outside can be within the search radius. Otherwise `r` doubles, up to the whole
//! grid.
//!
//! **When there is no grid.** The cell size comes from the points' bounding volume and is
//! halved while cells stay within a budget of a few per point; if the points then still
//! crowd into few cells (a cluster far from the others), [`PointGrid::build`] declines and the
//! caller keeps the kd-tree.

use glam::Vec3;

use super::kdtree::{Neighbour, Photon, NORMAL_FILTER};

#[cfg(doc)]
use super::PhotonMap;

/// Fewer points than this are looked up in the kd-tree (a grid does not pay).
const MIN_POINTS: usize = 64;
/// Cells allowed per point (memory: 4 bytes per cell).
const CELLS_PER_POINT: usize = 16;
/// The cell size is halved while the points' mean cell occupancy (`Σ occupancy² / n`, what
/// a query at a point meets in its own cell) is above this.
const TARGET_OCCUPANCY: f64 = 2.0;
/// A grid whose mean occupancy is above this is declined.
const MAX_OCCUPANCY: f64 = 16.0;
/// Relative margin on a block's clearance: rounding in the clearance and in squared distances
/// cannot make a point outside the block look nearer than `clearance·(1 − MARGIN)`.
const MARGIN: f32 = 1e-5;

/// One point in cell order.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
struct Entry {
    position: Vec3,
    index: u32,
    normal: Vec3,
}

/// Points bucketed in a uniform grid (see the module header).
#[derive(Debug, Clone)]
pub struct PointGrid {
    origin: Vec3,
    cell: f32,
    inv_cell: f32,
    dims: [usize; 3],
    /// `starts[c]..starts[c + 1]`: the entries of cell `c`.
    starts: Vec<u32>,
    entries: Vec<Entry>,
}

impl PointGrid {
    /// A grid over `points` (indexed as given), or `None` when it would not pay: too few
    /// points, a non-finite position, or points too crowded for the cell budget.
    pub fn build(points: &[Photon]) -> Option<Self> {
        let n = points.len();
        if !(MIN_POINTS..u32::MAX as usize).contains(&n) {
            return None;
        }
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for p in points {
            if !p.position.is_finite() {
                return None;
            }
            lo = lo.min(p.position);
            hi = hi.max(p.position);
        }
        let extent = hi - lo;
        let largest = extent.max_element();
        if !(largest > 0.0 && largest.is_finite()) {
            return None;
        }
        // Flat axes count as a thousandth of the largest, so the volume is never zero.
        let volume = extent.max(Vec3::splat(largest * 1e-3));
        let mut cell = (volume.x as f64 * volume.y as f64 * volume.z as f64 / n as f64).cbrt();
        let budget = CELLS_PER_POINT * n;
        let mut grid = Self::with_cell(points, lo, extent, cell as f32, budget)?;
        while grid.occupancy() > TARGET_OCCUPANCY {
            cell *= 0.5;
            match Self::with_cell(points, lo, extent, cell as f32, budget) {
                Some(finer) => grid = finer,
                None => break,
            }
        }
        (grid.occupancy() <= MAX_OCCUPANCY).then_some(grid)
    }

    /// The grid of cell size `cell` over the box at `lo` of size `extent`, or `None` beyond
    /// `budget` cells.
    fn with_cell(
        points: &[Photon],
        lo: Vec3,
        extent: Vec3,
        cell: f32,
        budget: usize,
    ) -> Option<Self> {
        if !(cell > 0.0 && cell.is_finite()) {
            return None;
        }
        let inv_cell = 1.0 / cell;
        let dims = extent.to_array().map(|e| (e * inv_cell) as usize + 1);
        let cells = dims
            .iter()
            .try_fold(1usize, |acc, &d| acc.checked_mul(d))
            .filter(|&c| c <= budget)?;
        let mut grid = Self {
            origin: lo,
            cell,
            inv_cell,
            dims,
            starts: vec![0; cells + 1],
            entries: Vec::with_capacity(points.len()),
        };
        let slots: Vec<usize> = points.iter().map(|p| grid.slot(p.position)).collect();
        for &s in &slots {
            grid.starts[s + 1] += 1;
        }
        for c in 0..cells {
            grid.starts[c + 1] += grid.starts[c];
        }
        let mut next = grid.starts.clone();
        let empty = Entry {
            position: Vec3::ZERO,
            index: 0,
            normal: Vec3::ZERO,
        };
        grid.entries.resize(points.len(), empty);
        for (i, (p, &s)) in points.iter().zip(&slots).enumerate() {
            grid.entries[next[s] as usize] = Entry {
                position: p.position,
                index: i as u32,
                normal: p.normal,
            };
            next[s] += 1;
        }
        Some(grid)
    }

    /// Mean number of points in a point's own cell.
    fn occupancy(&self) -> f64 {
        let sum: f64 = self
            .starts
            .windows(2)
            .map(|w| f64::from(w[1] - w[0]).powi(2))
            .sum();
        sum / self.entries.len() as f64
    }

    /// The cell index along each axis of coordinate `x` (clamped to the grid): monotone in
    /// `x`, so a point whose cell is below the cell of `p_a − r` lies below `p_a − r`.
    #[inline(always)]
    fn cell_of(&self, x: Vec3) -> [usize; 3] {
        let t = ((x - self.origin) * self.inv_cell).to_array();
        std::array::from_fn(|a| {
            // `as usize` saturates: negative and NaN give 0.
            (t[a] as usize).min(self.dims[a] - 1)
        })
    }

    #[inline(always)]
    fn slot(&self, x: Vec3) -> usize {
        let [i, j, k] = self.cell_of(x);
        (k * self.dims[1] + j) * self.dims[0] + i
    }

    /// The cells covering `p ± r` on each axis (inclusive ranges), and whether they are the
    /// whole grid.
    #[inline(always)]
    fn block(&self, p: Vec3, r: f32) -> ([usize; 3], [usize; 3], bool) {
        let lo = self.cell_of(p - Vec3::splat(r));
        let hi = self.cell_of(p + Vec3::splat(r));
        let whole = (0..3).all(|a| lo[a] == 0 && hi[a] == self.dims[a] - 1);
        (lo, hi, whole)
    }

    /// The point nearest to `p` strictly within `sqrt(max_d2)` whose normal passes the photon
    /// normal test against `normal` (ties: the least index) — what
    /// [`PhotonMap::nearest`] returns for `k = 1` over the same points.
    pub fn nearest(&self, p: Vec3, normal: Vec3, max_d2: f32) -> Option<Neighbour> {
        if !p.is_finite() || max_d2.is_nan() || max_d2 <= 0.0 {
            return None;
        }
        let max_r = max_d2.sqrt();
        let mut r = self.cell.min(max_r);
        loop {
            let (lo, hi, whole) = self.block(p, r);
            let best = self.scan(p, normal, max_d2, lo, hi);
            if whole {
                return best;
            }
            let clear = self.clearance(p, r, lo, hi) * (1.0 - MARGIN);
            let clear2 = clear * clear;
            if best.is_some_and(|b| b.dist2 < clear2) || clear2 >= max_d2 {
                return best;
            }
            r *= 2.0;
        }
    }

    /// A distance below which no point outside the block `lo..=hi` of `p ± r` lies: on an
    /// axis where the block stops short of the grid's first cell, a point in a lower cell
    /// has its coordinate below `p − r` as computed (cell indices are monotone in the
    /// coordinate), so it is farther than that computed difference; likewise above.
    #[inline(always)]
    fn clearance(&self, p: Vec3, r: f32, lo: [usize; 3], hi: [usize; 3]) -> f32 {
        let (below, above) = (p - Vec3::splat(r), p + Vec3::splat(r));
        let mut clear = f32::INFINITY;
        for a in 0..3 {
            if lo[a] > 0 {
                clear = clear.min(p[a] - below[a]);
            }
            if hi[a] < self.dims[a] - 1 {
                clear = clear.min(above[a] - p[a]);
            }
        }
        clear
    }

    /// The best point of the block `lo..=hi`.
    #[inline(always)]
    fn scan(
        &self,
        p: Vec3,
        normal: Vec3,
        max_d2: f32,
        lo: [usize; 3],
        hi: [usize; 3],
    ) -> Option<Neighbour> {
        let mut best: Option<Neighbour> = None;
        let mut bound = max_d2;
        for k in lo[2]..=hi[2] {
            for j in lo[1]..=hi[1] {
                let row = (k * self.dims[1] + j) * self.dims[0];
                let from = self.starts[row + lo[0]] as usize;
                let to = self.starts[row + hi[0] + 1] as usize;
                for e in &self.entries[from..to] {
                    let d2 = (e.position - p).length_squared();
                    if d2 > bound || d2.is_nan() {
                        continue;
                    }
                    let better = match best {
                        Some(b) => d2 < b.dist2 || e.index < b.index,
                        None => d2 < max_d2,
                    };
                    if better && e.normal.dot(normal) > NORMAL_FILTER {
                        best = Some(Neighbour {
                            dist2: d2,
                            index: e.index,
                        });
                        bound = d2;
                    }
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn photon(position: Vec3, normal: Vec3) -> Photon {
        Photon {
            position,
            power: Vec3::ONE,
            incoming: normal,
            normal,
        }
    }

    /// The definition: least squared distance strictly within the radius among points that
    /// pass the normal test, ties to the least index.
    fn brute_force(points: &[Photon], p: Vec3, n: Vec3, max_d2: f32) -> Option<(f32, u32)> {
        points
            .iter()
            .enumerate()
            .map(|(i, ph)| ((ph.position - p).length_squared(), i as u32, ph))
            .filter(|(d2, _, ph)| *d2 < max_d2 && ph.normal.dot(n) > NORMAL_FILTER)
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .map(|(d2, i, _)| (d2, i))
    }

    fn xorshift(seed: u64) -> impl FnMut() -> f32 {
        let mut state = seed;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    /// Points on the five walls of a box (as a Cornell box's photons are), on a lattice so
    /// that exact ties occur, some repeated, normals facing into the box.
    fn box_walls(n: usize, seed: u64) -> Vec<Photon> {
        let mut rnd = xorshift(seed);
        let mut points = Vec::new();
        for i in 0..n {
            let (u, v) = ((rnd() * 64.0).floor() / 64.0, (rnd() * 64.0).floor() / 64.0);
            let (p, nrm) = match i % 5 {
                0 => (Vec3::new(u, v, 0.0), Vec3::Z),
                1 => (Vec3::new(u, v, 1.0), -Vec3::Z),
                2 => (Vec3::new(0.0, u, v), Vec3::X),
                3 => (Vec3::new(1.0, u, v), -Vec3::X),
                _ => (Vec3::new(u, 1.0, v), -Vec3::Y),
            };
            points.push(photon(p * 556.0, nrm));
            if i % 7 == 0 {
                points.push(photon(p * 556.0, nrm));
            }
        }
        points
    }

    #[test]
    fn nearest_is_the_brute_force_answer_with_ties_and_the_normal_filter() {
        let points = box_walls(6000, 3);
        let grid = PointGrid::build(&points).expect("a box's walls make a grid");
        let mut rnd = xorshift(4);
        let normals = [Vec3::Z, -Vec3::Z, Vec3::X, -Vec3::X, -Vec3::Y, Vec3::Y];
        let mut found = 0;
        let mut ties = 0;
        for q in 0..3000 {
            // On the walls (as final-gather hits are), inside the box, and outside it.
            let mut p = Vec3::new(rnd(), rnd(), rnd()) * 700.0 - 70.0;
            if q % 2 == 0 {
                p = points[q % points.len()].position + (Vec3::new(rnd(), rnd(), 0.0) - 0.5);
            }
            for r_max in [3.0f32, 20.0, 80.0, 2000.0, f32::INFINITY] {
                let n = normals[q % normals.len()];
                let want = brute_force(&points, p, n, r_max * r_max);
                let got = grid.nearest(p, n, r_max * r_max);
                assert_eq!(got.map(|b| (b.dist2, b.index)), want, "{p} {r_max}");
                found += usize::from(want.is_some());
                if let Some((d2, i)) = want {
                    let tied = points
                        .iter()
                        .enumerate()
                        .any(|(k, ph)| k as u32 != i && (ph.position - p).length_squared() == d2);
                    ties += usize::from(tied);
                }
            }
        }
        assert!(found > 5000, "only {found} lookups found a point");
        assert!(ties > 1000, "only {ties} lookups had a tie");
    }

    #[test]
    fn crowded_or_tiny_point_sets_get_no_grid() {
        // Too few points.
        let few: Vec<Photon> = (0..10)
            .map(|i| photon(Vec3::splat(i as f32), Vec3::Z))
            .collect();
        assert!(PointGrid::build(&few).is_none());
        // One tight cluster and one far point: any cell the budget allows holds the cluster.
        let mut rnd = xorshift(5);
        let mut crowded: Vec<Photon> = (0..5000)
            .map(|_| photon(Vec3::new(rnd(), rnd(), rnd()) * 1e-3, Vec3::Z))
            .collect();
        crowded.push(photon(Vec3::splat(1e6), Vec3::Z));
        assert!(PointGrid::build(&crowded).is_none());
        // A non-finite position.
        let mut bad = box_walls(200, 6);
        bad[17].position.y = f32::NAN;
        assert!(PointGrid::build(&bad).is_none());
        // Every point at one position: no extent.
        assert!(PointGrid::build(&vec![photon(Vec3::ONE, Vec3::Z); 100]).is_none());
    }
}
