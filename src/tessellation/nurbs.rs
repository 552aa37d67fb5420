//! NURBS surfaces as patch sources: one patch per non-empty knot span pair.
//!
//! Not supported yet (see `docs/geometry.md`): trimming curves, and welding of closed
//! (periodic) surfaces across their seam — a closed NURBS is diced as an open one, so its
//! seam may show cracks. Rows of control points collapsed to one point in v (poles) are
//! detected and share a single corner.

use glam::{DVec2, DVec3, DVec4};

use super::grid::GridTopology;
use super::patch::normal_with_fallback;
use super::{GeometryError, PatchSource, SurfaceSample};
use crate::components::NurbsSurface;

/// Largest supported degree.
pub const MAX_DEGREE: usize = 7;

/// One parametric direction: degree, knots, and its non-empty spans.
#[derive(Debug, Clone)]
struct Axis {
    degree: usize,
    knots: Vec<f64>,
    /// (knot index k with knots[k] < knots[k+1], t0, t1).
    spans: Vec<(usize, f64, f64)>,
    t_min: f64,
    t_max: f64,
}

impl Axis {
    fn new(
        degree: u32,
        count: u32,
        knots: &[f32],
        dir: &'static str,
    ) -> Result<Self, GeometryError> {
        let (p, n) = (degree as usize, count as usize);
        let bad = |message: String| GeometryError::BadCount { message };
        if p == 0 || p > MAX_DEGREE {
            return Err(GeometryError::OutOfRange {
                parameter: if dir == "u" { "degree_u" } else { "degree_v" },
                value: degree as f64,
                expected: "1..=7",
            });
        }
        if n < p + 1 {
            return Err(bad(format!(
                "nurbs: {dir}: degree {p} needs at least {} control points, found {n}",
                p + 1
            )));
        }
        if knots.len() != n + p + 1 {
            return Err(bad(format!(
                "nurbs: {dir}: expected {} knots (count + degree + 1), found {}",
                n + p + 1,
                knots.len()
            )));
        }
        if knots.iter().any(|k| !k.is_finite()) {
            return Err(GeometryError::NotFinite { parameter: "knots" });
        }
        if knots.windows(2).any(|w| w[1] < w[0]) {
            return Err(bad(format!("nurbs: {dir}: knots must not decrease")));
        }
        let knots: Vec<f64> = knots.iter().map(|&k| k as f64).collect();
        let spans: Vec<_> = (p..n)
            .filter(|&k| knots[k + 1] > knots[k])
            .map(|k| (k, knots[k], knots[k + 1]))
            .collect();
        if spans.is_empty() {
            return Err(bad(format!("nurbs: {dir}: the parameter domain is empty")));
        }
        Ok(Self {
            degree: p,
            t_min: knots[p],
            t_max: knots[n],
            knots,
            spans,
        })
    }

    /// Basis functions `N_{k−p..=k, p}(t)` and their derivatives on knot span `k`.
    fn basis(&self, k: usize, t: f64) -> ([f64; MAX_DEGREE + 1], [f64; MAX_DEGREE + 1]) {
        let p = self.degree;
        let u = &self.knots;
        let funs = |deg: usize| {
            let mut n = [0.0; MAX_DEGREE + 1];
            let (mut left, mut right) = ([0.0; MAX_DEGREE + 1], [0.0; MAX_DEGREE + 1]);
            n[0] = 1.0;
            for j in 1..=deg {
                left[j] = t - u[k + 1 - j];
                right[j] = u[k + j] - t;
                let mut saved = 0.0;
                for r in 0..j {
                    let denom = right[r + 1] + left[j - r];
                    let temp = if denom != 0.0 { n[r] / denom } else { 0.0 };
                    n[r] = saved + right[r + 1] * temp;
                    saved = left[j - r] * temp;
                }
                n[j] = saved;
            }
            n
        };
        let n = funs(p);
        let lower = funs(p - 1); // N_{k−p+1..=k, p−1}
        let mut d = [0.0; MAX_DEGREE + 1];
        for (r, dr) in d.iter_mut().enumerate().take(p + 1) {
            let j = k + r - p; // function index
            let mut v = 0.0;
            if r >= 1 {
                let den = u[j + p] - u[j];
                if den != 0.0 {
                    v += p as f64 * lower[r - 1] / den;
                }
            }
            if r < p {
                let den = u[j + p + 1] - u[j + 1];
                if den != 0.0 {
                    v -= p as f64 * lower[r] / den;
                }
            }
            *dr = v;
        }
        (n, d)
    }
}

/// A validated NURBS surface.
#[derive(Debug, Clone)]
pub struct NurbsSource {
    u: Axis,
    v: Axis,
    count_u: usize,
    /// Homogeneous control points (w·x, w·y, w·z, w).
    points: Vec<DVec4>,
    topo: GridTopology,
}

impl NurbsSource {
    /// Validates degrees, knots, counts and weights.
    pub fn new(s: &NurbsSurface) -> Result<Self, GeometryError> {
        let u = Axis::new(s.degree_u, s.count_u, &s.knots_u, "u")?;
        let v = Axis::new(s.degree_v, s.count_v, &s.knots_v, "v")?;
        let (cu, cv) = (s.count_u as usize, s.count_v as usize);
        if s.points.len() != cu * cv {
            return Err(GeometryError::BadCount {
                message: format!(
                    "nurbs: expected count_u × count_v = {} points, found {}",
                    cu * cv,
                    s.points.len()
                ),
            });
        }
        if s.points.iter().any(|p| !p.is_finite()) {
            return Err(GeometryError::NotFinite {
                parameter: "points",
            });
        }
        if let Some(p) = s.points.iter().find(|p| p.w <= 0.0) {
            return Err(GeometryError::OutOfRange {
                parameter: "weight",
                value: p.w as f64,
                expected: "> 0",
            });
        }
        let row_collapsed = |j: usize| {
            let row = &s.points[j * cu..(j + 1) * cu];
            row.iter().all(|p| p.truncate() == row[0].truncate())
        };
        // A collapsed first/last row of a clamped knot vector is a pole of the surface.
        let clamped0 = v.knots[..=v.degree].iter().all(|&k| k == v.knots[0]);
        let clamped1 = v.knots[cv..].iter().all(|&k| k == v.knots[cv]);
        let topo = GridTopology::new(
            u.spans.len(),
            v.spans.len(),
            false,
            false,
            clamped0 && row_collapsed(0),
            clamped1 && row_collapsed(cv - 1),
        );
        Ok(Self {
            points: s
                .points
                .iter()
                .map(|p| {
                    DVec4::new(
                        p.x as f64 * p.w as f64,
                        p.y as f64 * p.w as f64,
                        p.z as f64 * p.w as f64,
                        p.w as f64,
                    )
                })
                .collect(),
            u,
            v,
            count_u: cu,
            topo,
        })
    }

    /// The knot segment of `patch` among all `(count_u − degree_u) × (count_v − degree_v)`
    /// segments, empty ones included, u fastest (RenderMan's uniform value index).
    pub fn segment(&self, patch: usize) -> usize {
        let (i, j) = self.topo.cell(patch);
        let (ku, kv) = (self.u.spans[i].0, self.v.spans[j].0);
        (ku - self.u.degree) + (kv - self.v.degree) * (self.count_u - self.u.degree)
    }

    /// The number of knot segments of `s`, empty ones included (see [`Self::segment`]).
    pub fn segments(s: &NurbsSurface) -> usize {
        let along = |count: u32, degree: u32| count.saturating_sub(degree) as usize;
        along(s.count_u, s.degree_u) * along(s.count_v, s.degree_v)
    }

    /// Position and derivatives per unit knot parameter on spans (`ku`, `kv`).
    fn local(&self, ku: usize, kv: usize, tu: f64, tv: f64) -> (DVec3, DVec3, DVec3) {
        let (nu, du) = self.u.basis(ku, tu);
        let (nv, dv) = self.v.basis(kv, tv);
        let (pu, pv) = (self.u.degree, self.v.degree);
        let (mut a, mut au, mut av) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for b in 0..=pv {
            let row = (kv - pv + b) * self.count_u;
            let (mut r, mut ru) = (DVec4::ZERO, DVec4::ZERO);
            for c in 0..=pu {
                let q = self.points[row + ku - pu + c];
                r += q * nu[c];
                ru += q * du[c];
            }
            a += r * nv[b];
            au += ru * nv[b];
            av += r * dv[b];
        }
        let w = a.w;
        let p = a.truncate() / w;
        let dpu = (au.truncate() - p * au.w) / w;
        let dpv = (av.truncate() - p * av.w) / w;
        (p, dpu, dpv)
    }
}

impl PatchSource for NurbsSource {
    fn patch_count(&self) -> usize {
        self.topo.patch_count()
    }
    fn corner_count(&self) -> usize {
        self.topo.corner_count()
    }
    fn corners(&self, patch: usize) -> [u32; 4] {
        self.topo.corners(patch)
    }
    fn eval(&self, patch: usize, u: f64, v: f64) -> SurfaceSample {
        let (i, j) = self.topo.cell(patch);
        let (ku, u0, u1) = self.u.spans[i];
        let (kv, v0, v1) = self.v.spans[j];
        let (tu, tv) = (u0 + u * (u1 - u0), v0 + v * (v1 - v0));
        let (p, pu, pv) = self.local(ku, kv, tu, tv);
        let n = normal_with_fallback(pu, pv, u, v, |a, b| {
            let (_, x, y) = self.local(ku, kv, u0 + a * (u1 - u0), v0 + b * (v1 - v0));
            (x, y)
        });
        let (ru, rv) = (self.u.t_max - self.u.t_min, self.v.t_max - self.v.t_min);
        SurfaceSample {
            p,
            dpdu: pu * ru,
            dpdv: pv * rv,
            n,
            uv: DVec2::new((tu - self.u.t_min) / ru, (tv - self.v.t_min) / rv),
        }
    }
    fn grid(&self) -> (usize, usize) {
        (self.topo.nu, self.topo.nv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    /// A quarter cylinder of radius 1 as an exact rational quadratic in u, linear in v.
    fn quarter_cylinder() -> NurbsSurface {
        let w = std::f32::consts::FRAC_1_SQRT_2;
        let ring = [
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(1.0, 1.0, 0.0, w),
            Vec4::new(0.0, 1.0, 0.0, 1.0),
        ];
        let mut points = ring.to_vec();
        points.extend(ring.iter().map(|p| Vec4::new(p.x, p.y, 2.0, p.w)));
        NurbsSurface {
            degree_u: 2,
            degree_v: 1,
            count_u: 3,
            count_v: 2,
            knots_u: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            knots_v: vec![0.0, 0.0, 1.0, 1.0],
            points,
            vars: Default::default(),
        }
    }

    #[test]
    fn rational_quadratic_is_an_exact_circle() {
        let s = NurbsSource::new(&quarter_cylinder()).unwrap();
        for k in 0..=20 {
            let smp = s.eval(0, k as f64 / 20.0, 0.3);
            let r = (smp.p.x * smp.p.x + smp.p.y * smp.p.y).sqrt();
            assert!((r - 1.0).abs() < 1e-6, "{r}");
            assert!((smp.p.z - 0.6).abs() < 1e-6);
            // Derivatives agree with finite differences.
            let h = 1e-6;
            let a = s.eval(0, (k as f64 / 20.0).min(1.0 - h), 0.3);
            let b = s.eval(0, (k as f64 / 20.0).min(1.0 - h) + h, 0.3);
            assert!(((b.p - a.p) / h - a.dpdu).length() < 1e-4);
        }
    }

    #[test]
    fn bad_knots_are_reported() {
        let mut n = quarter_cylinder();
        n.knots_u.pop();
        let e = NurbsSource::new(&n).unwrap_err();
        assert_eq!(
            e.to_string(),
            "nurbs: u: expected 6 knots (count + degree + 1), found 5"
        );
    }
}
