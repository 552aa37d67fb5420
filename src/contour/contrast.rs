//! Contour contrast: which neighbouring store samples an edge runs between, and where
//! exactly (a bisection with extra probe rays places each edge crossing to 1/1024 pixel
//! along the line joining the two samples).

use glam::Vec2;
use rayon::prelude::*;

use super::store::{ContourSample, ContourStore, Probe};
use crate::components::ContourContrast;

/// Bisection steps placing a crossing: the crossing is within `2^-(STEPS+1)` of a sample
/// spacing (one pixel) of where the contrast changes.
pub const BISECTION_STEPS: u32 = 10;

/// The contrast test, with the normal-angle threshold as a cosine.
#[derive(Debug, Clone, Copy)]
pub struct Contrast {
    settings: ContourContrast,
    /// Normals whose dot product is below this differ (below −1: never).
    cos_angle: f32,
}

impl Contrast {
    /// The test for `settings`.
    pub fn new(settings: ContourContrast) -> Self {
        let cos_angle = if settings.normal_angle >= 180.0 {
            -2.0
        } else {
            settings.normal_angle.to_radians().cos()
        };
        Self {
            settings,
            cos_angle,
        }
    }

    /// Whether an edge runs between `a` and `b`.
    pub fn differs(&self, a: &ContourSample, b: &ContourSample) -> bool {
        let c = &self.settings;
        if a.is_absent() || b.is_absent() {
            return false;
        }
        match (a.is_background(), b.is_background()) {
            (true, true) => return false,
            (false, false) => {}
            _ => return c.background,
        }
        if (c.instance && a.instance != b.instance)
            || (c.object && a.object != b.object)
            || (c.material && a.material != b.material)
        {
            return true;
        }
        if a.normal.dot(b.normal) < self.cos_angle {
            return true;
        }
        let Some(fraction) = c.depth else {
            return false;
        };
        let near = a.depth.min(b.depth);
        (a.depth - b.depth).abs() > fraction * near
    }
}

/// An edge between two neighbouring samples: where it crosses the line joining them, and
/// the samples on its two sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Film position, pixels.
    pub pos: Vec2,
    /// The sample nearer the camera (a surface against the background), whose material
    /// styles the line.
    pub front: ContourSample,
    /// The other sample.
    pub back: ContourSample,
}

impl Crossing {
    /// Whether the edge is an outline: the back side is the background or another placed
    /// object — a different instance, so also another copy of the same object (mental ray's
    /// silhouette compares the instance tags its contour store keeps). Creases and material
    /// edges within one instance are not.
    pub fn is_outline(&self) -> bool {
        self.back.is_background() || self.back.instance != self.front.instance
    }
}

/// The crossings of a store's sample grid, by grid edge.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeCrossings {
    /// Samples per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Between samples `(x, y)` and `(x + 1, y)`, at `y·(width − 1) + x`.
    pub horizontal: Vec<Option<Crossing>>,
    /// Between samples `(x, y)` and `(x, y + 1)`, at `y·width + x`.
    pub vertical: Vec<Option<Crossing>>,
}

/// Finds every crossing of `store` whose front sample `keep` accepts (a material with a
/// contour shader), placing each by bisection with `probe`. Rows run in parallel; the result
/// does not depend on the thread count.
pub fn find_crossings(
    store: &ContourStore,
    probe: &Probe<'_>,
    contrast: &Contrast,
    keep: &(dyn Fn(&ContourSample) -> bool + Sync),
) -> EdgeCrossings {
    let (w, h) = (store.width, store.height);
    let crossing = |x0: u32, y0: u32, x1: u32, y1: u32| -> Option<Crossing> {
        let (a, b) = (store.at(x0, y0), store.at(x1, y1));
        if !contrast.differs(a, b) {
            return None;
        }
        let (front, back) = if b.depth < a.depth { (b, a) } else { (a, b) };
        if !keep(front) {
            return None;
        }
        let (pa, pb) = (
            ContourStore::position(x0, y0),
            ContourStore::position(x1, y1),
        );
        let (mut lo, mut hi) = (0.0f32, 1.0f32);
        for _ in 0..BISECTION_STEPS {
            let mid = 0.5 * (lo + hi);
            if contrast.differs(a, &probe.sample(pa.lerp(pb, mid))) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(Crossing {
            pos: pa.lerp(pb, 0.5 * (lo + hi)),
            front: *front,
            back: *back,
        })
    };
    // Per row: the crossings across to the right and down to the next row.
    type Row = (Vec<Option<Crossing>>, Vec<Option<Crossing>>);
    let rows: Vec<Row> = (0..h)
        .into_par_iter()
        .map(|y| {
            let across = (0..w.saturating_sub(1))
                .map(|x| crossing(x, y, x + 1, y))
                .collect();
            let down = if y + 1 < h {
                (0..w).map(|x| crossing(x, y, x, y + 1)).collect()
            } else {
                Vec::new()
            };
            (across, down)
        })
        .collect();
    let mut horizontal = Vec::with_capacity((w.saturating_sub(1) * h) as usize);
    let mut vertical = Vec::with_capacity((w * h.saturating_sub(1)) as usize);
    for (across, down) in rows {
        horizontal.extend(across);
        vertical.extend(down);
    }
    EdgeCrossings {
        width: w,
        height: h,
        horizontal,
        vertical,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn surface(instance: u32, material: u32, normal: Vec3, depth: f32) -> ContourSample {
        ContourSample {
            instance,
            object: instance,
            material,
            normal,
            depth,
            color: Vec3::ZERO,
        }
    }

    #[test]
    fn each_contrast_switch_decides_its_own_difference() {
        let all = Contrast::new(ContourContrast::default());
        let a = surface(1, 1, Vec3::Z, 2.0);
        assert!(!all.differs(&a, &a));
        assert!(all.differs(&a, &ContourSample::BACKGROUND));
        assert!(all.differs(&a, &surface(2, 1, Vec3::Z, 2.0)), "instance");
        assert!(all.differs(&a, &surface(1, 2, Vec3::Z, 2.0)), "material");
        assert!(all.differs(&a, &surface(1, 1, Vec3::X, 2.0)), "90° > 60°");
        assert!(!all.differs(
            &a,
            &surface(1, 1, Vec3::new(0.5, 0.0, 1.0).normalize(), 2.0)
        ));
        assert!(all.differs(&a, &surface(1, 1, Vec3::Z, 2.6)), "30 % > 25 %");
        assert!(!all.differs(&a, &surface(1, 1, Vec3::Z, 2.4)));
        let none = Contrast::new(ContourContrast {
            instance: false,
            object: false,
            material: false,
            normal_angle: 180.0,
            depth: None,
            background: false,
            ray_depth: 0,
        });
        for b in [ContourSample::BACKGROUND, surface(2, 2, -Vec3::Z, 9.0)] {
            assert!(!none.differs(&a, &b));
        }
    }

    #[test]
    fn depth_none_never_differs_by_depth_and_all_off_draws_nothing() {
        let no_depth = ContourContrast {
            depth: None,
            ..ContourContrast::default()
        };
        let a = surface(1, 1, Vec3::Z, 2.0);
        assert!(!Contrast::new(no_depth).differs(&a, &surface(1, 1, Vec3::Z, 90.0)));
        assert!(
            Contrast::new(ContourContrast::default()).differs(&a, &surface(1, 1, Vec3::Z, 90.0))
        );
        assert!(no_depth.any_on());
        let off = ContourContrast {
            instance: false,
            object: false,
            material: false,
            normal_angle: 180.0,
            depth: None,
            background: false,
            ray_depth: 2,
        };
        assert!(!off.any_on());
        for on in [
            ContourContrast {
                background: true,
                ..off
            },
            ContourContrast {
                normal_angle: 179.0,
                ..off
            },
            ContourContrast {
                depth: Some(0.25),
                ..off
            },
        ] {
            assert!(on.any_on(), "{on:?}");
        }
    }
}
