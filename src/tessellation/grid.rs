//! Corner ids of a `nu × nv` grid of patches, with optional wrap-around in u and v and rows
//! collapsed to a single point (poles, apexes, disk centres).

/// Topology of a patch grid. Patch `(i, j)` is patch index `i + j·nu`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GridTopology {
    /// Patches along u.
    pub nu: usize,
    /// Patches along v.
    pub nv: usize,
    wrap_u: bool,
    wrap_v: bool,
    /// Id of the first corner of each corner row (`nv + 1` rows, the last wraps onto the first
    /// when `wrap_v`), and whether the row is collapsed to one id.
    rows: Vec<(u32, bool)>,
    count: usize,
}

impl GridTopology {
    /// A grid; wrap directions are only honoured with at least 3 patches around (fewer would
    /// make two distinct edges join the same corners), and a row is collapsed only when
    /// `collapse_v0` / `collapse_v1` ask for it.
    pub fn new(
        nu: usize,
        nv: usize,
        wrap_u: bool,
        wrap_v: bool,
        collapse_v0: bool,
        collapse_v1: bool,
    ) -> Self {
        let (nu, nv) = (nu.max(1), nv.max(1));
        let wrap_u = wrap_u && nu >= 3;
        let wrap_v = wrap_v && nv >= 3;
        let cols = if wrap_u { nu } else { nu + 1 };
        let row_count = if wrap_v { nv } else { nv + 1 };
        let mut rows = Vec::with_capacity(row_count);
        let mut next = 0u32;
        for j in 0..row_count {
            let collapsed = (j == 0 && collapse_v0) || (j == nv && collapse_v1);
            rows.push((next, collapsed));
            next += if collapsed { 1 } else { cols as u32 };
        }
        Self {
            nu,
            nv,
            wrap_u,
            wrap_v,
            rows,
            count: next as usize,
        }
    }

    /// Number of patches.
    pub fn patch_count(&self) -> usize {
        self.nu * self.nv
    }

    /// Number of corner ids.
    pub fn corner_count(&self) -> usize {
        self.count
    }

    /// Id of grid corner `(i, j)`, `i ≤ nu`, `j ≤ nv`.
    pub fn corner(&self, i: usize, j: usize) -> u32 {
        let j = if self.wrap_v { j % self.nv } else { j };
        let i = if self.wrap_u { i % self.nu } else { i };
        let (first, collapsed) = self.rows[j];
        if collapsed {
            first
        } else {
            first + i as u32
        }
    }

    /// Corner ids of patch `p` in (0,0), (1,0), (1,1), (0,1) order.
    pub fn corners(&self, p: usize) -> [u32; 4] {
        let (i, j) = (p % self.nu, p / self.nu);
        [
            self.corner(i, j),
            self.corner(i + 1, j),
            self.corner(i + 1, j + 1),
            self.corner(i, j + 1),
        ]
    }

    /// Patch `(i, j)` of patch index `p`.
    pub fn cell(&self, p: usize) -> (usize, usize) {
        (p % self.nu, p / self.nu)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapped_grid_with_poles_shares_corners() {
        let g = GridTopology::new(4, 2, true, false, true, true);
        assert_eq!(g.corner_count(), 1 + 4 + 1);
        assert_eq!(g.corners(3), [0, 0, 1, 4]);
        assert_eq!(g.corners(7)[2], g.corners(7)[3]);
        // Too few patches to wrap: stays open.
        let g = GridTopology::new(2, 1, true, false, false, false);
        assert_eq!(g.corner_count(), 6);
    }
}
