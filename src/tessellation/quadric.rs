//! Analytic quadrics (RenderMan's parameterisations) as patch sources.
//!
//! The sweep about +Z is cut into patches of at most 90°, as is the second parameter range;
//! full sweeps wrap (the seam is one shared edge) and full spheres, cone apexes and disk
//! centres collapse to one shared corner. Texture coordinates are RenderMan's: `u` along the
//! sweep, `v` along the profile. Derivatives are per unit of (u, v).

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::{DVec2, DVec3};

use super::grid::GridTopology;
use super::{as_written, finite, positive, sweep, GeometryError, PatchSource, SurfaceSample};
use crate::components::Quadric;

/// Validated parameters (f64, radians).
#[derive(Debug, Clone, Copy)]
enum Shape {
    Sphere {
        r: f64,
        a0: f64,
        a1: f64,
    },
    Cylinder {
        r: f64,
        z0: f64,
        z1: f64,
    },
    Cone {
        h: f64,
        r: f64,
    },
    Disk {
        h: f64,
        r: f64,
    },
    Torus {
        big: f64,
        small: f64,
        p0: f64,
        p1: f64,
    },
}

/// A quadric ready to evaluate.
#[derive(Debug, Clone)]
pub struct QuadricSource {
    shape: Shape,
    theta_max: f64,
    topo: GridTopology,
}

/// Patches needed to cover `range` radians with pieces of at most 90°.
fn pieces(range: f64) -> usize {
    ((range / FRAC_PI_2) - 1e-9).ceil().max(1.0) as usize
}

impl QuadricSource {
    /// Validates the quadric's parameters.
    pub fn new(q: &Quadric) -> Result<Self, GeometryError> {
        let (shape, theta_deg, v_range, wrap_v, c0, c1) = match *q {
            Quadric::Sphere(s) => {
                let r = positive("radius", s.radius)?;
                let z0 = finite("z_min", s.z_min)?.clamp(-r, r);
                let z1 = finite("z_max", s.z_max)?.clamp(z0, r);
                if z1 <= z0 {
                    // Quote z_max as written, not clamped.
                    return Err(GeometryError::OutOfRange {
                        parameter: "z_max",
                        value: as_written(s.z_max),
                        expected: if s.z_max > s.z_min {
                            "> z_min, both clamped to [-radius, radius]"
                        } else {
                            "> z_min"
                        },
                    });
                }
                let (a0, a1) = ((z0 / r).asin(), (z1 / r).asin());
                let shape = Shape::Sphere { r, a0, a1 };
                (shape, s.theta_max, a1 - a0, false, z0 <= -r, z1 >= r)
            }
            Quadric::Cylinder(c) => {
                let r = positive("radius", c.radius)?;
                let (z0, z1) = (finite("z_min", c.z_min)?, finite("z_max", c.z_max)?);
                if z0 == z1 {
                    return Err(GeometryError::OutOfRange {
                        parameter: "z_max",
                        value: as_written(c.z_max),
                        expected: "≠ z_min",
                    });
                }
                (
                    Shape::Cylinder { r, z0, z1 },
                    c.theta_max,
                    0.0,
                    false,
                    false,
                    false,
                )
            }
            Quadric::Cone(c) => {
                let h = finite("height", c.height)?;
                if h == 0.0 {
                    return Err(GeometryError::OutOfRange {
                        parameter: "height",
                        value: as_written(c.height),
                        expected: "≠ 0",
                    });
                }
                let r = positive("radius", c.radius)?;
                (Shape::Cone { h, r }, c.theta_max, 0.0, false, false, true)
            }
            Quadric::Disk(d) => {
                let h = finite("height", d.height)?;
                let r = positive("radius", d.radius)?;
                (Shape::Disk { h, r }, d.theta_max, 0.0, false, false, true)
            }
            Quadric::Torus(t) => {
                let big = positive("r_major", t.r_major)?;
                let small = positive("r_minor", t.r_minor)?;
                let p0 = finite("phi_min", t.phi_min)?.to_radians();
                let p1 = finite("phi_max", t.phi_max)?.to_radians();
                let range = p1 - p0;
                if !(range > 0.0 && range <= TAU + 1e-12) {
                    return Err(GeometryError::OutOfRange {
                        parameter: "phi_max",
                        value: as_written(t.phi_max),
                        expected: "phi_min < phi_max ≤ phi_min + 360",
                    });
                }
                let wrap = (range - TAU).abs() < 1e-9;
                (
                    Shape::Torus { big, small, p0, p1 },
                    t.theta_max,
                    range,
                    wrap,
                    false,
                    false,
                )
            }
        };
        let theta_max = sweep("theta_max", theta_deg)?;
        let wrap_u = (theta_max - TAU).abs() < 1e-9;
        let nu = pieces(theta_max).max(if wrap_u { 4 } else { 1 });
        let mut nv = pieces(v_range).max(if wrap_v { 4 } else { 1 });
        if c0 && c1 {
            nv = nv.max(2);
        }
        Ok(Self {
            shape,
            theta_max,
            topo: GridTopology::new(nu, nv, wrap_u, wrap_v, c0, c1),
        })
    }

    /// Evaluates at global parameters (u, v) ∈ [0, 1]².
    pub fn eval_global(&self, u: f64, v: f64) -> SurfaceSample {
        let th = u * self.theta_max;
        let (st, ct) = th.sin_cos();
        let tm = self.theta_max;
        let (p, dpdu, dpdv, fallback) = match self.shape {
            Shape::Sphere { r, a0, a1 } => {
                let a = a0 + v * (a1 - a0);
                let (sa, ca) = a.sin_cos();
                let n = DVec3::new(ca * ct, ca * st, sa);
                let dpdu = DVec3::new(-st, ct, 0.0) * (r * ca * tm);
                let dpdv = DVec3::new(-sa * ct, -sa * st, ca) * (r * (a1 - a0));
                (n * r, dpdu, dpdv, n)
            }
            Shape::Cylinder { r, z0, z1 } => {
                let p = DVec3::new(r * ct, r * st, z0 + v * (z1 - z0));
                let dpdu = DVec3::new(-st, ct, 0.0) * (r * tm);
                let n = DVec3::new(ct, st, 0.0) * (z1 - z0).signum();
                (p, dpdu, DVec3::new(0.0, 0.0, z1 - z0), n)
            }
            Shape::Cone { h, r } => {
                let rr = (1.0 - v) * r;
                let p = DVec3::new(rr * ct, rr * st, v * h);
                let dpdu = DVec3::new(-st, ct, 0.0) * (rr * tm);
                let dpdv = DVec3::new(-r * ct, -r * st, h);
                let n = (DVec3::new(h * ct, h * st, r) * h.signum()).normalize();
                (p, dpdu, dpdv, n)
            }
            Shape::Disk { h, r } => {
                let rr = (1.0 - v) * r;
                let p = DVec3::new(rr * ct, rr * st, h);
                let dpdu = DVec3::new(-st, ct, 0.0) * (rr * tm);
                let dpdv = DVec3::new(-r * ct, -r * st, 0.0);
                (p, dpdu, dpdv, DVec3::Z)
            }
            Shape::Torus { big, small, p0, p1 } => {
                let ph = p0 + v * (p1 - p0);
                let (sp, cp) = ph.sin_cos();
                let ring = big + small * cp;
                let p = DVec3::new(ring * ct, ring * st, small * sp);
                let dpdu = DVec3::new(-st, ct, 0.0) * (ring * tm);
                let dpdv = DVec3::new(-sp * ct, -sp * st, cp) * (small * (p1 - p0));
                let n = DVec3::new(cp * ct, cp * st, sp) * ring.signum();
                (p, dpdu, dpdv, n)
            }
        };
        let n = dpdu.cross(dpdv).try_normalize().unwrap_or(fallback);
        SurfaceSample {
            p,
            dpdu,
            dpdv,
            n,
            uv: DVec2::new(u, v),
        }
    }
}

impl PatchSource for QuadricSource {
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
        self.eval_global(
            (i as f64 + u) / self.topo.nu as f64,
            (j as f64 + v) / self.topo.nv as f64,
        )
    }
    fn grid(&self) -> (usize, usize) {
        (self.topo.nu, self.topo.nv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::components::{Sphere, Torus};

    #[test]
    fn torus_points_lie_on_the_torus_with_outward_normals() {
        let q = QuadricSource::new(&Quadric::Torus(Torus {
            r_major: 3.0,
            r_minor: 1.0,
            phi_min: 0.0,
            phi_max: 360.0,
            theta_max: 360.0,
        }))
        .unwrap();
        assert_eq!(q.grid(), (4, 4));
        for k in 0..50 {
            let (u, v) = (k as f64 / 49.0, (k * 7 % 50) as f64 / 49.0);
            let s = q.eval_global(u, v);
            let ring = DVec3::new(s.p.x, s.p.y, 0.0).normalize() * 3.0;
            assert!(((s.p - ring).length() - 1.0).abs() < 1e-12);
            assert!((s.p - ring).normalize().dot(s.n) > 0.999_999);
        }
    }

    #[test]
    fn bad_parameters_are_errors_not_panics() {
        let bad = Quadric::Sphere(Sphere {
            radius: -1.0,
            z_min: -1.0,
            z_max: 1.0,
            theta_max: 360.0,
        });
        let e = QuadricSource::new(&bad).unwrap_err();
        assert_eq!(
            e.to_string(),
            "parameter `radius` = -1 is out of range (expected > 0)"
        );
        let nan = Quadric::Sphere(Sphere {
            radius: 1.0,
            z_min: -1.0,
            z_max: 1.0,
            theta_max: f32::NAN,
        });
        assert!(QuadricSource::new(&nan).is_err());
    }
}
