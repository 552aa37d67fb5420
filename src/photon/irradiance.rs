//! Irradiance precomputed at photon positions, which final-gather rays read with one nearest
//! lookup instead of a `gather`-photon density estimate each (Christensen, *Faster Photon Map
//! Global Illumination*, JGT 1999; the fast final gathering of Jensen's and mental ray's
//! global illumination).
//!
//! **What is stored.** At every [`STRIDE`]-th photon of the global map and of the caustic
//! map's gather view ([`super::coarse`]), in tree order, the irradiance the two maps estimate
//! there (`Σ Φ / area` over the same gather, radius, filter and normal test as the per-ray
//! estimate; every pass of a progressive map), with the photon's position and normal.
//!
//! **How it is read.** A final-gather ray landing at `p` with normal `n` on a surface whose
//! non-delta lobes are all Lambertian takes the irradiance `E` of the nearest stored point
//! within the global map's gather radius whose normal passes the photon normal test against
//! `n`, and reflects `f·E` (`f` = the surface's Lambertian BSDF, ρ/π), or nothing when no point
//! is that close. Other surfaces (glossy, Phong, metallic-roughness lobes) keep the per-ray
//! estimate, which weighs each photon by the BSDF toward its direction.
//!
//! **Cost and error.** Precomputing is `N/STRIDE` estimates, once per render, in parallel and
//! deterministic (each point's value depends only on the maps); each gather ray then costs
//! one nearest-neighbour search. The lookup adds a piecewise-constant blur (Voronoi cells of
//! the stored points, a fraction of the gather disc) on top of the estimate's own; measured in
//! `tests/it/photon_final_gather.rs` and `docs/accuracy.md`.

use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use super::point_grid::PointGrid;
use super::{GatherMap, Neighbour, Photon, PhotonMap};

/// One photon in how many carries a precomputed irradiance (Christensen's "every fourth").
pub const STRIDE: usize = 4;

/// Irradiance at a subset of photon positions, in a kd-tree (each point is stored as a
/// [`Photon`] whose `power` is the irradiance, W/m²), and in a grid for the lookups when the
/// points spread well enough for one ([`PointGrid::build`]; the same answers).
#[derive(Debug, Clone)]
pub struct IrradiancePoints {
    points: PhotonMap,
    grid: Option<Box<PointGrid>>,
    radius: f32,
}

impl IrradiancePoints {
    /// Precomputes the irradiance of `global` plus `caustics` (the caustic map's gather view)
    /// at every [`STRIDE`]-th photon of each; `None` when `cancel` is raised on the way.
    pub fn precompute(
        global: &GatherMap,
        caustics: Option<&GatherMap>,
        cancel: &AtomicBool,
    ) -> Option<Self> {
        let sites: Vec<&Photon> = [Some(global), caustics]
            .into_iter()
            .flatten()
            .flat_map(|m| m.map.photons().iter().step_by(STRIDE))
            .collect();
        let irradiance = |scratch: &mut Vec<Neighbour>, site: &Photon| {
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            let (p, n) = (site.position, site.normal);
            let mut e = global.density(p, n, scratch, |_| Vec3::ONE);
            if let Some(c) = caustics {
                e += c.density(p, n, scratch, |_| Vec3::ONE);
            }
            Some(Photon {
                position: p,
                power: e,
                incoming: n,
                normal: n,
            })
        };
        let points: Option<Vec<Photon>> = sites
            .par_iter()
            .with_min_len(64)
            .map_init(Vec::new, |scratch, site| irradiance(scratch, site))
            .collect();
        let points = PhotonMap::build(points?);
        Some(Self {
            grid: PointGrid::build(points.photons()).map(Box::new),
            points,
            radius: global.radius,
        })
    }

    /// The irradiance at `p` (normal `normal`): the nearest stored point's within the gather
    /// radius, zero when none is that close.
    pub fn at(&self, p: Vec3, normal: Vec3, scratch: &mut Vec<Neighbour>) -> Vec3 {
        match &self.grid {
            Some(grid) => {
                scratch.clear();
                scratch.extend(grid.nearest(p, normal, self.radius * self.radius));
            }
            None => self
                .points
                .nearest(p, Some(normal), 1, self.radius, scratch),
        }
        scratch.first().map_or(Vec3::ZERO, |nb| {
            self.points.photons()[nb.index as usize].power
        })
    }

    /// Number of stored points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when no point is stored.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photon::PhotonFilter;

    /// `n` photons of power `power` on an even disc of radius `spread` in the plane z = 0.
    fn disc(n: usize, power: f32, spread: f32) -> GatherMap {
        let photons = (0..n)
            .map(|i| {
                let a = i as f32 * 2.399_963;
                let r = spread * ((i as f32 + 0.5) / n as f32).sqrt();
                Photon {
                    position: Vec3::new(r * a.cos(), r * a.sin(), 0.0),
                    power: Vec3::splat(power),
                    incoming: Vec3::Z,
                    normal: Vec3::Z,
                }
            })
            .collect();
        GatherMap {
            map: PhotonMap::build(photons),
            gather: 50,
            radius: 0.1,
            final_gather: 16,
            emitted: n as u64,
            filter: PhotonFilter::Box,
            progressive: None,
        }
    }

    #[test]
    fn points_hold_the_estimate_of_both_maps_at_every_fourth_photon() {
        let global = disc(4000, 1e-3, 1.0);
        let caustics = disc(400, 1e-3, 0.2);
        let none = AtomicBool::new(false);
        let points = IrradiancePoints::precompute(&global, Some(&caustics), &none).unwrap();
        assert_eq!(points.len(), 1000 + 100);
        // Inside both discs: E = 4 W / π·1² + 0.4 W / π·0.2² (uniform discs), and the lookup
        // returns exactly the estimate at the nearest stored point.
        let expected = 4.0 / std::f32::consts::PI + 0.4 / (std::f32::consts::PI * 0.04);
        let mut scratch = Vec::new();
        let p = Vec3::new(0.05, 0.03, 0.0);
        let e = points.at(p, Vec3::Z, &mut scratch).x;
        assert!((e / expected - 1.0).abs() < 0.15, "{e} vs {expected}");
        let nearest = points.points.photons()[scratch[0].index as usize].position;
        let direct = global.density(nearest, Vec3::Z, &mut scratch, |_| Vec3::ONE)
            + caustics.density(nearest, Vec3::Z, &mut scratch, |_| Vec3::ONE);
        assert_eq!(points.at(p, Vec3::Z, &mut scratch), direct);
    }

    #[test]
    fn nothing_is_read_beyond_the_radius_or_across_a_normal() {
        let global = disc(4000, 1e-3, 1.0);
        let none = AtomicBool::new(false);
        let points = IrradiancePoints::precompute(&global, None, &none).unwrap();
        let mut scratch = Vec::new();
        assert_eq!(
            points.at(Vec3::new(1.2, 0.0, 0.0), Vec3::Z, &mut scratch),
            Vec3::ZERO
        );
        assert_eq!(points.at(Vec3::ZERO, Vec3::X, &mut scratch), Vec3::ZERO);
        assert!(points.at(Vec3::ZERO, Vec3::Z, &mut scratch).x > 0.0);
    }

    /// The grid answers every lookup as the kd-tree does, bit for bit: inside and outside
    /// the discs, across the normal test, near and beyond the radius.
    #[test]
    fn grid_lookups_are_the_kd_tree_lookups() {
        let global = disc(4000, 1e-3, 1.0);
        let caustics = disc(400, 1e-3, 0.2);
        let none = AtomicBool::new(false);
        let with_grid = IrradiancePoints::precompute(&global, Some(&caustics), &none).unwrap();
        assert!(with_grid.grid.is_some());
        let tree_only = IrradiancePoints {
            grid: None,
            ..with_grid.clone()
        };
        let mut scratch = Vec::new();
        let mut lit = 0;
        for i in 0..4000 {
            let a = i as f32 * 0.618_034 * std::f32::consts::TAU;
            let r = 1.3 * (i as f32 / 4000.0).sqrt();
            let p = Vec3::new(r * a.cos(), r * a.sin(), (i % 3) as f32 * 0.02);
            let n = if i % 5 == 0 { Vec3::X } else { Vec3::Z };
            let e = with_grid.at(p, n, &mut scratch);
            assert_eq!(e, tree_only.at(p, n, &mut scratch), "at {p}");
            lit += usize::from(e != Vec3::ZERO);
        }
        assert!((2000..3200).contains(&lit), "{lit} lookups found a point");
    }

    #[test]
    fn precomputing_is_deterministic_and_stops_when_cancelled() {
        let global = disc(2000, 1e-3, 1.0);
        let none = AtomicBool::new(false);
        let a = IrradiancePoints::precompute(&global, None, &none).unwrap();
        let b = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| IrradiancePoints::precompute(&global, None, &none).unwrap());
        assert_eq!(a.points.photons(), b.points.photons());
        let raised = AtomicBool::new(true);
        assert!(IrradiancePoints::precompute(&global, None, &raised).is_none());
    }
}
