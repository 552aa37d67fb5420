//! Approximation techniques as segment counts: "how many equal parameter steps does this
//! curve need?" A curve is given by samples at equal parameter steps (its positions, already
//! displaced, and the surface normals there); the answer depends on nothing else.

use glam::DVec3;

use super::{finite, GeometryError, RasterView};
use crate::components::{Approximation, LengthSpace, Technique};

/// Largest segment count of the fixed (parametric, regular) techniques.
pub const MAX_FIXED_RATE: u32 = 4096;
/// Largest subdivision level.
pub const MAX_LEVEL: u32 = 12;

/// Whether a curve runs along u or v of its patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Along u.
    U,
    /// Along v.
    V,
}

/// A validated approximation, ready to rate curves.
#[derive(Debug, Clone)]
pub struct RateContext<'a> {
    technique: Technique,
    min_rate: u32,
    max_rate: u32,
    view: Option<&'a RasterView>,
    grid: (usize, usize),
}

impl<'a> RateContext<'a> {
    /// Validates `approx` (errors on non-finite or negative tolerances; clamps levels).
    pub fn new(
        approx: &Approximation,
        view: Option<&'a RasterView>,
        grid: (usize, usize),
    ) -> Result<Self, GeometryError> {
        match approx.technique {
            Technique::Spatial { edge, space } => {
                super::positive("edge", edge)?;
                if space == LengthSpace::Raster && view.is_none() {
                    return Err(GeometryError::NoCamera);
                }
            }
            Technique::Curvature { distance, angle } => {
                let d = finite("distance", distance)?;
                let a = finite("angle", angle)?;
                if d < 0.0 || a < 0.0 || (d == 0.0 && a == 0.0) {
                    return Err(GeometryError::OutOfRange {
                        parameter: "distance",
                        value: d,
                        expected: "distance ≥ 0 and angle ≥ 0, not both 0",
                    });
                }
            }
            Technique::Parametric { .. } | Technique::Regular { .. } => {}
        }
        let min_level = approx.min_subdiv.min(MAX_LEVEL);
        let max_level = approx.max_subdiv.clamp(min_level, MAX_LEVEL);
        Ok(Self {
            technique: approx.technique,
            min_rate: 1 << min_level,
            max_rate: 1 << max_level,
            view,
            grid: (grid.0.max(1), grid.1.max(1)),
        })
    }

    /// True for spatial and curvature (rates depend on the geometry).
    pub fn is_adaptive(&self) -> bool {
        matches!(
            self.technique,
            Technique::Spatial { .. } | Technique::Curvature { .. }
        )
    }

    /// The rate of the fixed techniques along `dir` (1 for adaptive ones).
    pub fn fixed_rate(&self, dir: Direction) -> u32 {
        let pick = |u: u32, v: u32| if dir == Direction::U { u } else { v };
        match self.technique {
            Technique::Parametric { u, v } => pick(u, v).clamp(1, MAX_FIXED_RATE),
            Technique::Regular { u, v } => {
                let per = if dir == Direction::U {
                    self.grid.0
                } else {
                    self.grid.1
                } as u32;
                pick(u, v).div_ceil(per).clamp(1, MAX_FIXED_RATE)
            }
            _ => 1,
        }
    }

    /// Segments for a curve sampled at equal parameter steps (`points.len() ≥ 2`).
    pub fn rate(&self, points: &[DVec3], normals: &[DVec3], dir: Direction) -> u32 {
        let wanted = match self.technique {
            Technique::Parametric { .. } | Technique::Regular { .. } => {
                return self.fixed_rate(dir)
            }
            Technique::Spatial { edge, space } => {
                let len = match space {
                    LengthSpace::Object => polyline_length(points),
                    LengthSpace::Raster => match self.view {
                        Some(view) => raster_length(points, view),
                        None => f64::INFINITY,
                    },
                };
                len / edge as f64
            }
            Technique::Curvature { distance, angle } => curvature_segments(
                points,
                normals,
                distance as f64,
                (angle as f64).to_radians(),
            ),
        };
        clamp_rate(wanted, self.min_rate, self.max_rate)
    }
}

/// Rounds a wanted (real) segment count up and clamps it; NaN and infinity give `max`.
fn clamp_rate(wanted: f64, min: u32, max: u32) -> u32 {
    if !wanted.is_finite() {
        return max;
    }
    (wanted.ceil().max(1.0).min(max as f64) as u32).max(min)
}

/// Length of the polyline through `points`.
pub fn polyline_length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// Largest projected length in pixels over the view's instances; infinite when a point is
/// at or behind the camera plane.
fn raster_length(points: &[DVec3], view: &RasterView) -> f64 {
    let mut best: f64 = 0.0;
    for xf in &view.camera_from_object {
        let mut len = 0.0;
        let mut prev: Option<(f64, f64)> = None;
        for p in points {
            let c = xf.transform_point3(*p);
            let depth = -c.z;
            if depth <= 1e-9 {
                return f64::INFINITY;
            }
            let s = (c.x / depth, c.y / depth);
            if let Some(q) = prev {
                len += ((s.0 - q.0).powi(2) + (s.1 - q.1).powi(2)).sqrt();
            }
            prev = Some(s);
        }
        best = best.max(len * view.pixels_per_unit);
    }
    best
}

/// Segments so that every chord stays within `distance / 2` of the curve (half the budget:
/// a triangle spans two directions) and turns by at most `angle` radians (0 disables).
///
/// The chord error of a segment of parameter length h is ≈ |P''| h² / 8; |P''| comes from
/// second differences of the samples. The turn is measured on the sample normals and on the
/// tangents of the sampled (possibly displaced) polyline.
fn curvature_segments(points: &[DVec3], normals: &[DVec3], distance: f64, angle: f64) -> f64 {
    let n = points.len() - 1;
    let h = 1.0 / n as f64;
    let mut wanted: f64 = 1.0;
    if distance > 0.0 {
        let mut max_second: f64 = 0.0;
        for w in points.windows(3) {
            max_second = max_second.max((w[0] - 2.0 * w[1] + w[2]).length() / (h * h));
        }
        wanted = wanted.max((max_second / (4.0 * distance)).sqrt());
    }
    if angle > 0.0 {
        let mut max_turn: f64 = 0.0;
        for w in normals.windows(2) {
            max_turn = max_turn.max(angle_between(w[0], w[1]) / h);
        }
        for w in points.windows(3) {
            max_turn = max_turn.max(angle_between(w[1] - w[0], w[2] - w[1]) / h);
        }
        wanted = wanted.max(max_turn / angle);
    }
    wanted
}

/// Angle between two vectors, 0 when either is zero.
fn angle_between(a: DVec3, b: DVec3) -> f64 {
    let d = a.length() * b.length();
    if d <= 0.0 || !d.is_finite() {
        return 0.0;
    }
    (a.dot(b) / d).clamp(-1.0, 1.0).acos()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arc(r: f64, sweep: f64, n: usize) -> (Vec<DVec3>, Vec<DVec3>) {
        (0..=n)
            .map(|k| {
                let a = sweep * k as f64 / n as f64;
                let d = DVec3::new(a.cos(), a.sin(), 0.0);
                (d * r, d)
            })
            .unzip()
    }

    fn ctx(technique: Technique) -> RateContext<'static> {
        RateContext::new(
            &Approximation {
                technique,
                min_subdiv: 0,
                max_subdiv: 12,
            },
            None,
            (4, 2),
        )
        .unwrap()
    }

    #[test]
    fn curvature_rate_meets_the_chord_tolerance() {
        let (p, n) = arc(1.0, std::f64::consts::FRAC_PI_2, 16);
        for tol in [1e-1, 1e-2, 1e-3, 1e-4] {
            let c = ctx(Technique::Curvature {
                distance: tol as f32,
                angle: 0.0,
            });
            let segs = c.rate(&p, &n, Direction::U) as f64;
            let step = std::f64::consts::FRAC_PI_2 / segs;
            let sagitta = 1.0 - (step / 2.0).cos();
            assert!(
                sagitta <= tol / 2.0 * 1.01,
                "tol {tol}: {segs} segments, {sagitta}"
            );
        }
    }

    #[test]
    fn spatial_and_fixed_rates() {
        let (p, n) = arc(1.0, std::f64::consts::FRAC_PI_2, 16);
        let c = ctx(Technique::Spatial {
            edge: 0.1,
            space: LengthSpace::Object,
        });
        assert_eq!(c.rate(&p, &n, Direction::U), 16); // length ≈ 1.5703
        let r = ctx(Technique::Regular { u: 16, v: 5 });
        assert_eq!(
            (r.fixed_rate(Direction::U), r.fixed_rate(Direction::V)),
            (4, 3)
        );
    }

    #[test]
    fn bad_tolerances_are_errors() {
        let a = Approximation {
            technique: Technique::Curvature {
                distance: 0.0,
                angle: 0.0,
            },
            ..Approximation::default()
        };
        assert!(RateContext::new(&a, None, (1, 1)).is_err());
        let a = Approximation {
            technique: Technique::Spatial {
                edge: 1.0,
                space: LengthSpace::Raster,
            },
            ..Approximation::default()
        };
        assert_eq!(
            RateContext::new(&a, None, (1, 1)).unwrap_err(),
            GeometryError::NoCamera
        );
    }
}
