//! Irradiance at photon positions, which final-gather rays read with one nearest lookup
//! instead of a `gather`-photon density estimate each (Christensen, *Faster Photon Map Global
//! Illumination*, JGT 1999; the fast final gathering of Jensen's and mental ray's global
//! illumination).
//!
//! **What is stored.** At every [`STRIDE`]-th photon of the global map and of the caustic
//! map's gather view ([`super::coarse`]), in tree order, a site: the photon's position and
//! normal, and the irradiance the two maps estimate there (`Σ Φ / area` over the same gather,
//! radius, filter and normal test as the per-ray estimate; every pass of a progressive map).
//!
//! **Computed on first use.** The sites are placed when the maps are made (`trace_photons`);
//! a site's irradiance is computed the first time a lookup lands on it and kept
//! ([`OnceLock`]). It depends only on the maps and the site, so whichever thread computes it
//! first, in whatever order, it has the same bits: images are the same at any thread count,
//! and the same as computing every site up front (`lazy_values_are_the_eager_ones`). A render
//! computes only the sites its gather rays reach: the photon-heavy 8 × 6-pixel render of
//! `docs/ray-layer.md` (session 26) no longer spends 7 % of `trace_photons` on estimates it
//! never reads. In a closed room gather rays reach most sites from anywhere, so a full render
//! or a farm part computes most of them, now in `shade`. A site whose estimate is not finite
//! (an overflowing photon power) reads as zero.
//!
//! **How it is read.** A final-gather ray landing at `p` with normal `n` on a surface whose
//! non-delta lobes are all Lambertian takes the irradiance `E` of the nearest site within the
//! global map's gather radius whose normal passes the photon normal test against `n`, and
//! reflects `f·E` (`f` = the surface's Lambertian BSDF, ρ/π), or nothing when no site is that
//! close. Other surfaces (glossy, Phong, metallic-roughness lobes) keep the per-ray estimate,
//! which weighs each photon by the BSDF toward its direction.
//!
//! **Cost and error.** At most `N/STRIDE` estimates per render, each once; each gather ray
//! costs one nearest-neighbour search. The lookup adds a piecewise-constant blur (Voronoi
//! cells of the sites, a fraction of the gather disc) on top of the estimate's own; measured
//! in `tests/it/photon_final_gather.rs` and `docs/accuracy.md`.

use std::sync::OnceLock;

use glam::Vec3;

use super::point_grid::PointGrid;
use super::{GatherMap, Neighbour, Photon, PhotonMap};

/// One photon in how many carries an irradiance site (Christensen's "every fourth").
pub const STRIDE: usize = 4;

/// The maps whose irradiance the sites hold: the global map and the caustic map's gather
/// view, the ones [`IrradiancePoints::new`] was given.
#[derive(Debug, Clone, Copy)]
pub struct IrradianceMaps<'m> {
    /// The global map.
    pub global: &'m GatherMap,
    /// The caustic map's gather view ([`super::coarse`]), when there is one.
    pub caustics: Option<&'m GatherMap>,
}

/// Each map's photon count and gather-radius bits: global, then the caustic gather view.
type MapsFingerprint = ((usize, u32), Option<(usize, u32)>);

impl IrradianceMaps<'_> {
    /// What tells these maps apart from others a caller might pass by mistake: each map's
    /// photon count and gather radius (checked in debug builds, [`IrradiancePoints::at`]).
    fn fingerprint(&self) -> MapsFingerprint {
        let of = |m: &GatherMap| (m.map.len(), m.radius.to_bits());
        (of(self.global), self.caustics.map(of))
    }

    /// The irradiance both maps estimate at `p` (normal `n`).
    fn irradiance(&self, p: Vec3, n: Vec3, scratch: &mut Vec<Neighbour>) -> Vec3 {
        let mut e = self.global.density(p, n, scratch, |_| Vec3::ONE);
        if let Some(c) = self.caustics {
            e += c.density(p, n, scratch, |_| Vec3::ONE);
        }
        e
    }
}

/// Irradiance sites at a subset of photon positions, in a kd-tree (each site stored as a
/// [`Photon`] with its position and normal), and in a grid for the lookups when the sites
/// spread well enough for one ([`PointGrid::build`]; the same answers); each site's value
/// computed on first use.
#[derive(Debug, Clone)]
pub struct IrradiancePoints {
    points: PhotonMap,
    /// The maps the sites were made from ([`IrradianceMaps::fingerprint`]): the values are
    /// computed lazily from the maps each lookup passes, which must be these.
    made_from: MapsFingerprint,
    /// The irradiance at each site (W/m²), by tree index, once computed.
    values: Box<[OnceLock<Vec3>]>,
    grid: Option<Box<PointGrid>>,
    radius: f32,
}

impl IrradiancePoints {
    /// The sites of `maps`: every [`STRIDE`]-th photon of the global map and of the caustic
    /// gather view (values computed later, by [`IrradiancePoints::at`]).
    pub fn new(maps: IrradianceMaps<'_>) -> Self {
        let sites: Vec<Photon> = [Some(maps.global), maps.caustics]
            .into_iter()
            .flatten()
            .flat_map(|m| m.map.photons().iter().step_by(STRIDE))
            .map(|site| Photon {
                position: site.position,
                power: Vec3::ZERO,
                incoming: site.normal,
                normal: site.normal,
            })
            .collect();
        let points = PhotonMap::build(sites);
        Self {
            made_from: maps.fingerprint(),
            grid: PointGrid::build(points.photons()).map(Box::new),
            values: (0..points.len()).map(|_| OnceLock::new()).collect(),
            points,
            radius: maps.global.radius,
        }
    }

    /// The irradiance at `p` (normal `normal`): the nearest site's within the gather radius
    /// (computed from `maps`, the maps the sites were made from, if no lookup did it
    /// before), zero when no site is that close.
    pub fn at(
        &self,
        p: Vec3,
        normal: Vec3,
        maps: IrradianceMaps<'_>,
        scratch: &mut Vec<Neighbour>,
    ) -> Vec3 {
        debug_assert_eq!(
            self.made_from,
            maps.fingerprint(),
            "IrradiancePoints::at takes the maps its sites were made from"
        );
        let nearest = match &self.grid {
            Some(grid) => grid.nearest(p, normal, self.radius * self.radius),
            None => {
                self.points
                    .nearest(p, Some(normal), 1, self.radius, scratch);
                scratch.first().copied()
            }
        };
        nearest.map_or(Vec3::ZERO, |nb| {
            self.value(nb.index as usize, maps, scratch)
        })
    }

    /// Site `i`'s irradiance, computed now if no lookup did it before.
    fn value(&self, i: usize, maps: IrradianceMaps<'_>, scratch: &mut Vec<Neighbour>) -> Vec3 {
        *self.values[i].get_or_init(|| {
            let site = &self.points.photons()[i];
            let e = maps.irradiance(site.position, site.normal, scratch);
            if e.is_finite() {
                e
            } else {
                Vec3::ZERO
            }
        })
    }

    /// Number of sites.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when there is no site.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Sites whose irradiance has been computed so far.
    pub fn computed(&self) -> usize {
        self.values.iter().filter(|v| v.get().is_some()).count()
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

    /// Both maps of a test.
    fn both<'m>(global: &'m GatherMap, caustics: &'m GatherMap) -> IrradianceMaps<'m> {
        IrradianceMaps {
            global,
            caustics: Some(caustics),
        }
    }

    /// The global map alone.
    fn alone(global: &GatherMap) -> IrradianceMaps<'_> {
        IrradianceMaps {
            global,
            caustics: None,
        }
    }

    /// Sites looked up with maps other than their own would cache values of the wrong maps
    /// without a sound: debug builds stop there (a map missing, another map, another radius).
    #[test]
    #[cfg(debug_assertions)]
    fn lookups_with_other_maps_are_caught_in_debug_builds() {
        let global = disc(4000, 1e-3, 1.0);
        let caustics = disc(400, 1e-3, 0.2);
        let other = disc(3000, 1e-3, 1.0);
        let mut wider = disc(4000, 1e-3, 1.0);
        wider.radius = 0.2;
        let points = IrradiancePoints::new(both(&global, &caustics));
        let p = Vec3::new(0.05, 0.03, 0.0);
        let mut scratch = Vec::new();
        assert!(
            points
                .at(p, Vec3::Z, both(&global, &caustics), &mut scratch)
                .x
                > 0.0
        );
        for maps in [
            alone(&global),
            both(&other, &caustics),
            both(&wider, &caustics),
        ] {
            let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                points.at(p, Vec3::Z, maps, &mut Vec::new())
            }));
            let message = caught.expect_err("other maps are caught");
            let text = message
                .downcast_ref::<String>()
                .map(String::as_str)
                .unwrap_or_default();
            assert!(
                text.contains("takes the maps its sites were made from"),
                "{text}"
            );
        }
    }

    #[test]
    fn points_hold_the_estimate_of_both_maps_at_every_fourth_photon() {
        let global = disc(4000, 1e-3, 1.0);
        let caustics = disc(400, 1e-3, 0.2);
        let maps = both(&global, &caustics);
        let points = IrradiancePoints::new(maps);
        assert_eq!(points.len(), 1000 + 100);
        // Inside both discs: E = 4 W / π·1² + 0.4 W / π·0.2² (uniform discs), and the lookup
        // returns exactly the estimate at the nearest site.
        let expected = 4.0 / std::f32::consts::PI + 0.4 / (std::f32::consts::PI * 0.04);
        let mut scratch = Vec::new();
        let p = Vec3::new(0.05, 0.03, 0.0);
        let e = points.at(p, Vec3::Z, maps, &mut scratch).x;
        assert!((e / expected - 1.0).abs() < 0.15, "{e} vs {expected}");
        points
            .points
            .nearest(p, Some(Vec3::Z), 1, points.radius, &mut scratch);
        let nearest = points.points.photons()[scratch[0].index as usize].position;
        let direct = global.density(nearest, Vec3::Z, &mut scratch, |_| Vec3::ONE)
            + caustics.density(nearest, Vec3::Z, &mut scratch, |_| Vec3::ONE);
        assert_eq!(points.at(p, Vec3::Z, maps, &mut scratch), direct);
    }

    #[test]
    fn nothing_is_read_beyond_the_radius_or_across_a_normal() {
        let global = disc(4000, 1e-3, 1.0);
        let maps = alone(&global);
        let points = IrradiancePoints::new(maps);
        let mut scratch = Vec::new();
        assert_eq!(
            points.at(Vec3::new(1.2, 0.0, 0.0), Vec3::Z, maps, &mut scratch),
            Vec3::ZERO
        );
        assert_eq!(
            points.at(Vec3::ZERO, Vec3::X, maps, &mut scratch),
            Vec3::ZERO
        );
        assert!(points.at(Vec3::ZERO, Vec3::Z, maps, &mut scratch).x > 0.0);
    }

    /// The grid answers every lookup as the kd-tree does, bit for bit: inside and outside
    /// the discs, across the normal test, near and beyond the radius.
    #[test]
    fn grid_lookups_are_the_kd_tree_lookups() {
        let global = disc(4000, 1e-3, 1.0);
        let caustics = disc(400, 1e-3, 0.2);
        let maps = both(&global, &caustics);
        let with_grid = IrradiancePoints::new(maps);
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
            let e = with_grid.at(p, n, maps, &mut scratch);
            assert_eq!(e, tree_only.at(p, n, maps, &mut scratch), "at {p}");
            lit += usize::from(e != Vec3::ZERO);
        }
        assert!((2000..3200).contains(&lit), "{lit} lookups found a point");
    }

    /// The values computed on first use — in parallel, in scrambled orders, on one thread
    /// or many — are, bit for bit, the estimates computed for every site up front in tree
    /// order (what the precompute of earlier versions stored).
    #[test]
    fn lazy_values_are_the_eager_ones() {
        let global = disc(2000, 1e-3, 1.0);
        let caustics = disc(300, 1e-3, 0.2);
        let maps = both(&global, &caustics);
        let points = IrradiancePoints::new(maps);
        let mut scratch = Vec::new();
        let eager: Vec<Vec3> = points
            .points
            .photons()
            .iter()
            .map(|s| maps.irradiance(s.position, s.normal, &mut scratch))
            .collect();
        assert!(eager.iter().all(|e| e.x > 0.0));
        let n = points.len();
        // Every site looked up at its own position, in a scrambled order, on rayon's threads
        // and on one.
        let looked_up = |points: &IrradiancePoints| -> Vec<Vec3> {
            use rayon::prelude::*;
            (0..n)
                .into_par_iter()
                .map_init(Vec::new, |scratch, j| {
                    let i = (j * 7919) % n;
                    points.value(i, maps, scratch)
                })
                .collect::<Vec<_>>()
        };
        let many = IrradiancePoints::new(maps);
        let values = looked_up(&many);
        let one = IrradiancePoints::new(maps);
        let single = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| looked_up(&one));
        for j in 0..n {
            let i = (j * 7919) % n;
            assert_eq!(values[j], eager[i]);
            assert_eq!(single[j], eager[i]);
        }
        assert_eq!(many.computed(), n);
    }

    /// A lookup computes only the site it lands on: sites no gather ray reaches cost nothing.
    #[test]
    fn only_the_sites_looked_up_are_computed() {
        let global = disc(4000, 1e-3, 1.0);
        let maps = alone(&global);
        let points = IrradiancePoints::new(maps);
        assert_eq!(points.computed(), 0);
        let mut scratch = Vec::new();
        let p = Vec3::new(0.3, -0.2, 0.0);
        let e = points.at(p, Vec3::Z, maps, &mut scratch);
        assert!(e.x > 0.0);
        assert_eq!(points.computed(), 1);
        // The same site again: read, not computed again.
        assert_eq!(points.at(p, Vec3::Z, maps, &mut scratch), e);
        assert_eq!(points.computed(), 1);
        // Beyond the radius or across the normal test: nothing computed.
        points.at(Vec3::new(3.0, 0.0, 0.0), Vec3::Z, maps, &mut scratch);
        points.at(p, Vec3::X, maps, &mut scratch);
        assert_eq!(points.computed(), 1);
    }
}
