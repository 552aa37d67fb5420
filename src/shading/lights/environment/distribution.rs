//! Piecewise-constant distributions in one and two dimensions (pbrt-v4 `PiecewiseConstant1D`
//! / `PiecewiseConstant2D`), for importance sampling a lat-long map.

use glam::Vec2;

/// Fraction of a cell at each edge that [`Distribution1D::sample`] leaves out.
const EDGE: f32 = 1e-4;

/// A piecewise-constant density over [0, 1) with `n` equal cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution1D {
    /// Non-negative cell values.
    func: Vec<f32>,
    /// Normalised CDF at cell boundaries (`n + 1` entries, last = 1).
    cdf: Vec<f32>,
    /// ∫ func over [0, 1).
    integral: f64,
}

impl Distribution1D {
    /// The distribution proportional to `func` (all ≥ 0); when it sums to zero it is uniform
    /// and [`Distribution1D::integral`] is 0.
    pub fn new(func: Vec<f32>) -> Self {
        let n = func.len().max(1);
        let mut cdf = Vec::with_capacity(n + 1);
        cdf.push(0.0f64);
        for (i, f) in func.iter().enumerate() {
            cdf.push(cdf[i] + f64::from(*f) / n as f64);
        }
        let integral = *cdf.last().expect("non-empty");
        let cdf = if integral > 0.0 {
            cdf.iter().map(|c| (c / integral) as f32).collect()
        } else {
            (0..=n).map(|i| i as f32 / n as f32).collect()
        };
        let mut d = Self {
            func,
            cdf,
            integral,
        };
        *d.cdf.last_mut().expect("non-empty") = 1.0;
        d
    }

    /// ∫ func over [0, 1).
    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// Bytes of its heap allocations (cells and CDF, by capacity).
    pub fn heap_bytes(&self) -> u64 {
        ((self.func.capacity() + self.cdf.capacity()) * std::mem::size_of::<f32>()) as u64
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.func.len()
    }

    /// Whether there are no cells.
    pub fn is_empty(&self) -> bool {
        self.func.is_empty()
    }

    /// Density at cell `i` (relative to the uniform density 1).
    pub fn pdf(&self, i: usize) -> f32 {
        if self.integral > 0.0 {
            (f64::from(self.func[i]) / self.integral) as f32
        } else {
            1.0
        }
    }

    /// A point `x ∈ [0, 1)` with density [`Distribution1D::pdf`] and its cell.
    pub fn sample(&self, u: f32) -> (f32, usize) {
        let n = self.func.len();
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, n) - 1;
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let du = if c1 > c0 { (u - c0) / (c1 - c0) } else { 0.5 };
        // Keep a hair's breadth from the cell's edges, so that rounding downstream (to a
        // direction and back) cannot move the point into a neighbouring cell.
        let x = (i as f32 + du.clamp(EDGE, 1.0 - EDGE)) / n as f32;
        (x, i)
    }
}

/// A piecewise-constant density over [0, 1)² on a `width × height` grid (rows along v).
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution2D {
    rows: Vec<Distribution1D>,
    marginal: Distribution1D,
}

impl Distribution2D {
    /// The density proportional to `func` (row-major, `width × height`, all ≥ 0).
    pub fn new(func: &[f32], width: usize, height: usize) -> Self {
        let rows: Vec<Distribution1D> = (0..height)
            .map(|y| Distribution1D::new(func[y * width..(y + 1) * width].to_vec()))
            .collect();
        let marginal = Distribution1D::new(rows.iter().map(|r| r.integral() as f32).collect());
        Self { rows, marginal }
    }

    /// ∫ func over the unit square.
    pub fn integral(&self) -> f64 {
        self.marginal.integral()
    }

    /// Bytes of its heap allocations: the rows (the `Distribution1D`s and their cells and
    /// CDFs, by capacity) and the marginal's cells and CDF.
    pub fn heap_bytes(&self) -> u64 {
        let row_structs = self.rows.capacity() * std::mem::size_of::<Distribution1D>();
        self.rows
            .iter()
            .fold(row_structs as u64 + self.marginal.heap_bytes(), |sum, r| {
                sum + r.heap_bytes()
            })
    }

    /// A point of the unit square (x along a row, y across rows) and its density.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (y, row) = self.marginal.sample(u.y);
        let (x, col) = self.rows[row].sample(u.x);
        (
            Vec2::new(x, y),
            self.marginal.pdf(row) * self.rows[row].pdf(col),
        )
    }

    /// Density at the point `p` of the unit square.
    pub fn pdf(&self, p: Vec2) -> f32 {
        let h = self.rows.len();
        let row = ((p.y * h as f32) as usize).min(h - 1);
        let w = self.rows[row].len();
        let col = ((p.x * w as f32) as usize).min(w - 1);
        self.marginal.pdf(row) * self.rows[row].pdf(col)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_dimensional_sampling_inverts_the_cdf() {
        let d = Distribution1D::new(vec![1.0, 3.0, 0.0, 4.0]);
        assert!((d.integral() - 2.0).abs() < 1e-12);
        assert_eq!(d.pdf(1), 1.5);
        let (x, i) = d.sample(0.5 / 8.0);
        assert_eq!(i, 0);
        assert!((x - 0.125).abs() < 1e-4);
        // Nothing lands in the empty cell.
        for k in 0..1000 {
            let (_, i) = d.sample(k as f32 / 1000.0);
            assert_ne!(i, 2);
        }
    }

    #[test]
    fn two_dimensional_pdf_matches_sampling() {
        let f = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let d = Distribution2D::new(&f, 3, 2);
        let (p, pdf) = d.sample(Vec2::new(0.7, 0.9));
        assert!((d.pdf(p) - pdf).abs() < 1e-6);
        assert!((pdf - f[5] / (15.0 / 6.0)).abs() < 1e-5, "{pdf}");
    }
}
