//! Bilinear and bicubic patch meshes (RenderMan `Patch` / `PatchMesh`) as patch sources.

use glam::{DVec2, DVec3};

use super::grid::GridTopology;
use super::{GeometryError, PatchSource, SurfaceSample};
use crate::components::{CubicBasis, PatchKind, PatchMesh};

/// Basis functions of a cubic basis and their derivatives at `t`.
fn cubic(basis: CubicBasis, t: f64) -> ([f64; 4], [f64; 4]) {
    let (t2, t3) = (t * t, t * t * t);
    let s = 1.0 - t;
    match basis {
        CubicBasis::Bezier => (
            [s * s * s, 3.0 * t * s * s, 3.0 * t2 * s, t3],
            [
                -3.0 * s * s,
                3.0 * s * s - 6.0 * t * s,
                6.0 * t * s - 3.0 * t2,
                3.0 * t2,
            ],
        ),
        CubicBasis::BSpline => (
            [
                s * s * s / 6.0,
                (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0,
                (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0,
                t3 / 6.0,
            ],
            [
                -s * s / 2.0,
                (9.0 * t2 - 12.0 * t) / 6.0,
                (-9.0 * t2 + 6.0 * t + 3.0) / 6.0,
                t2 / 2.0,
            ],
        ),
        CubicBasis::CatmullRom => (
            [
                0.5 * (-t3 + 2.0 * t2 - t),
                0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
                0.5 * (-3.0 * t3 + 4.0 * t2 + t),
                0.5 * (t3 - t2),
            ],
            [
                0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
                0.5 * (9.0 * t2 - 10.0 * t),
                0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
                0.5 * (3.0 * t2 - 2.0 * t),
            ],
        ),
    }
}

/// Normal from derivatives, falling back to derivatives just inside the patch (degenerate
/// corners of collapsed patches), then to +Z.
pub(crate) fn normal_with_fallback(
    dpdu: DVec3,
    dpdv: DVec3,
    u: f64,
    v: f64,
    derivs_at: impl Fn(f64, f64) -> (DVec3, DVec3),
) -> DVec3 {
    if let Some(n) = dpdu.cross(dpdv).try_normalize() {
        return n;
    }
    for eps in [1e-6, 1e-3, 1e-1] {
        let (a, b) = derivs_at(u + (0.5 - u) * eps, v + (0.5 - v) * eps);
        if let Some(n) = a.cross(b).try_normalize() {
            return n;
        }
    }
    DVec3::Z
}

/// A validated patch mesh.
#[derive(Debug, Clone)]
pub struct PatchMeshSource {
    kind: PatchKind,
    nu: usize,
    points: Vec<DVec3>,
    /// Control points per patch row/column: 2 (bilinear) or 4 (bicubic); step between patches.
    order: usize,
    step: usize,
    topo: GridTopology,
}

/// Patches along one direction for `n` points: `(count, step)`.
fn patches_along(
    kind: PatchKind,
    n: usize,
    wrap: bool,
    dir: &'static str,
) -> Result<(usize, usize), GeometryError> {
    let bad = |why: String| GeometryError::BadCount {
        message: format!("patch mesh: {dir}: {why}"),
    };
    let (count, step) = match kind {
        PatchKind::Bilinear if n >= 2 => (if wrap { n } else { n - 1 }, 1),
        PatchKind::Bilinear => return Err(bad(format!("need at least 2 points, found {n}"))),
        PatchKind::Bicubic(_) if n < 4 && !(wrap && n >= 3) => {
            return Err(bad(format!("need at least 4 points, found {n}")))
        }
        PatchKind::Bicubic(CubicBasis::Bezier) => {
            if wrap && n.is_multiple_of(3) {
                (n / 3, 3)
            } else if !wrap && (n - 1).is_multiple_of(3) {
                ((n - 1) / 3, 3)
            } else {
                let rule = if wrap { "a multiple of 3" } else { "3·k + 1" };
                return Err(bad(format!(
                    "Bézier patch meshes need {rule} points, found {n}"
                )));
            }
        }
        PatchKind::Bicubic(_) => (if wrap { n } else { n - 3 }, 1),
    };
    if wrap && count < 3 {
        return Err(bad(format!(
            "a periodic direction needs at least 3 patches, found {count}"
        )));
    }
    Ok((count, step))
}

impl PatchMeshSource {
    /// Validates counts and points.
    pub fn new(m: &PatchMesh) -> Result<Self, GeometryError> {
        let (nu, nv) = (m.nu as usize, m.nv as usize);
        if m.points.len() != nu * nv {
            return Err(GeometryError::BadCount {
                message: format!(
                    "patch mesh: expected nu × nv = {} points, found {}",
                    nu * nv,
                    m.points.len()
                ),
            });
        }
        if m.points.iter().any(|p| !p.is_finite()) {
            return Err(GeometryError::NotFinite {
                parameter: "points",
            });
        }
        let (pu, step) = patches_along(m.kind, nu, m.u_wrap, "u")?;
        let (pv, _) = patches_along(m.kind, nv, m.v_wrap, "v")?;
        let order = if m.kind == PatchKind::Bilinear { 2 } else { 4 };
        Ok(Self {
            kind: m.kind,
            nu,
            points: m.points.iter().map(|p| p.as_dvec3()).collect(),
            order,
            step,
            topo: GridTopology::new(pu, pv, m.u_wrap, m.v_wrap, false, false),
        })
    }

    fn nv(&self) -> usize {
        self.points.len() / self.nu
    }

    /// Position and derivatives (per unit local parameter) of patch `(i, j)` at (u, v).
    fn local(&self, i: usize, j: usize, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let (bu, du, bv, dv) = match self.kind {
            PatchKind::Bilinear => {
                let (a, b) = ([1.0 - u, u, 0.0, 0.0], [-1.0, 1.0, 0.0, 0.0]);
                let (c, d) = ([1.0 - v, v, 0.0, 0.0], [-1.0, 1.0, 0.0, 0.0]);
                (a, b, c, d)
            }
            PatchKind::Bicubic(basis) => {
                let (a, b) = cubic(basis, u);
                let (c, d) = cubic(basis, v);
                (a, b, c, d)
            }
        };
        let nv = self.nv();
        let (mut p, mut pu, mut pv) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for b in 0..self.order {
            let row = (j * self.step + b) % nv;
            let (mut rp, mut ru) = (DVec3::ZERO, DVec3::ZERO);
            for a in 0..self.order {
                let q = self.points[row * self.nu + (i * self.step + a) % self.nu];
                rp += q * bu[a];
                ru += q * du[a];
            }
            p += rp * bv[b];
            pu += ru * bv[b];
            pv += rp * dv[b];
        }
        (p, pu, pv)
    }
}

impl PatchSource for PatchMeshSource {
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
        let (p, pu, pv) = self.local(i, j, u, v);
        let n = normal_with_fallback(pu, pv, u, v, |a, b| {
            let (_, x, y) = self.local(i, j, a, b);
            (x, y)
        });
        let (su, sv) = (self.topo.nu as f64, self.topo.nv as f64);
        SurfaceSample {
            p,
            dpdu: pu * su,
            dpdv: pv * sv,
            n,
            uv: DVec2::new((i as f64 + u) / su, (j as f64 + v) / sv),
        }
    }
    fn grid(&self) -> (usize, usize) {
        (self.topo.nu, self.topo.nv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn bases_are_partitions_of_unity_with_zero_sum_derivatives() {
        for basis in [
            CubicBasis::Bezier,
            CubicBasis::BSpline,
            CubicBasis::CatmullRom,
        ] {
            for k in 0..=10 {
                let (b, d) = cubic(basis, k as f64 / 10.0);
                assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-12);
                assert!(d.iter().sum::<f64>().abs() < 1e-12);
            }
        }
    }

    #[test]
    fn bilinear_patch_corners_and_counts() {
        let m = PatchMesh::bilinear([
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ]);
        let s = PatchMeshSource::new(&m).unwrap();
        assert_eq!(s.eval(0, 1.0, 1.0).p, DVec3::new(1.0, 1.0, 0.0));
        assert_eq!(s.eval(0, 0.5, 0.5).n, DVec3::Z);
        let bad = PatchMesh {
            kind: PatchKind::Bicubic(CubicBasis::Bezier),
            nu: 5,
            nv: 4,
            points: vec![Vec3::ZERO; 20],
            ..m
        };
        assert!(PatchMeshSource::new(&bad).is_err());
    }
}
