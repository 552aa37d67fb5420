//! The caustic map as final-gather rays read it: thinned to the global map's photon power and
//! read with a fixed-radius estimate over the global map's gather radius, so a gather ray
//! that lands in a caustic sees it at the global map's resolution — as in Jensen's method,
//! where the single global map holds the caustic photons too and final gathering reads it
//! with a coarse estimate.
//!
//! Why: a final-gather ray from a diffuse point that lands, through a glass ball, in the
//! focus of a caustic reads the caustic map's sharp estimate there (tens of times the
//! surrounding radiance) with a small probability: unbiased, but one such ray in a pixel is a
//! firefly (`L S+ D S* D E` paths, measured on `scripts/glass_ball.ron`: one gather ray in
//! 8 000 made a pixel 15× too bright and 60 % of the caustic crop's error; a k-nearest
//! estimate on the thinned map still found the focus's core and only made it 23 % dimmer).
//! The fixed radius spreads the focus over the global map's gather disc: the landing
//! radiance is lower and met more often, the same flux (each caustic photon is kept with
//! probability `1/m`, its power times `m`), blurred by the gather radius where a second
//! diffuse bounce blurs anyway. Directly visible caustics still read the full map.
//!
//! Thinning is by a hash of the photon's index in the map (tree order, the same whether the
//! map was traced or loaded from a file), so it is deterministic at any thread count.

use super::{GatherMap, Photon, PhotonMap};
use crate::sampling::hash_combine;

/// Seed of the thinning hash.
const THIN_SEED: u32 = 0xC0A5;

/// The caustic map `caustics` as final-gather rays read it next to the global map `global`
/// (see the module doc): keeps one photon in `m`, `m` the ratio of the maps' mean photon
/// powers (at least 1), powers times `m`, read with every photon within `global`'s `radius`
/// (`gather` above the photon count) and `global`'s filter; a progressive caustic map
/// contributes its first pass. `None` when the caustic map is empty.
pub fn gather_view(caustics: &GatherMap, global: &GatherMap) -> Option<GatherMap> {
    let m = thinning(&caustics.map, &global.map)?;
    let photons: Vec<Photon> = caustics
        .map
        .photons()
        .iter()
        .enumerate()
        .filter(|&(i, _)| m == 1 || hash_combine(&[THIN_SEED, i as u32]).is_multiple_of(m))
        .map(|(_, p)| Photon {
            power: p.power * m as f32,
            ..*p
        })
        .collect();
    let kept = photons.len();
    Some(GatherMap {
        map: PhotonMap::build(photons),
        gather: kept + 1,
        radius: global.radius,
        final_gather: global.final_gather,
        emitted: caustics.emitted,
        filter: global.filter,
        progressive: None,
    })
}

/// One photon in how many the gather view keeps: the global map's mean photon power over the
/// caustic map's (largest channel of the summed powers), rounded, at least 1. `None` when
/// the caustic map is empty; 1 when the global map is.
fn thinning(caustics: &PhotonMap, global: &PhotonMap) -> Option<u32> {
    if caustics.is_empty() {
        return None;
    }
    if global.is_empty() {
        return Some(1);
    }
    let mean = |m: &PhotonMap| m.total_power().max_element() as f64 / m.len() as f64;
    let ratio = mean(global) / mean(caustics);
    if !ratio.is_finite() || ratio <= 1.0 {
        return Some(1);
    }
    Some(ratio.round().min(caustics.len() as f64).max(1.0) as u32)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::photon::PhotonFilter;

    fn map(n: usize, power: f32, spread: f32) -> GatherMap {
        let photons = (0..n)
            .map(|i| {
                let a = i as f32 * 2.399_963; // golden angle: an even disc
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
            radius: 0.01,
            final_gather: 0,
            emitted: n as u64,
            filter: PhotonFilter::Box,
            progressive: None,
        }
    }

    #[test]
    fn the_view_keeps_the_power_and_reads_the_global_radius() {
        // 40 000 caustic photons of power 1e-4 (4 W) in a disc of radius 0.1; the global map's
        // photons carry 1e-2: one in 100 is kept, at 100× the power.
        let caustics = map(40_000, 1e-4, 0.1);
        let mut global = map(500, 1e-2, 5.0);
        global.gather = 64;
        global.radius = 0.05;
        global.final_gather = 16;
        global.filter = PhotonFilter::Cone { k: 1.1 };
        let view = gather_view(&caustics, &global).unwrap();
        let kept = view.map.len();
        // Binomial(40 000, 1/100): 400 ± 20; 5σ.
        assert!((kept as i64 - 400).abs() < 100, "{kept}");
        assert!(view
            .map
            .photons()
            .iter()
            .all(|p| (p.power.x - 1e-2).abs() < 1e-7));
        let total = view.map.total_power().x;
        assert!((total - 4.0).abs() < 5.0 * 0.2, "{total}");
        assert_eq!((view.radius, view.final_gather), (0.05, 16));
        assert!(view.gather > kept, "a fixed-radius estimate");
        assert_eq!(view.filter, PhotonFilter::Cone { k: 1.1 });
        let again = gather_view(&caustics, &global).unwrap();
        assert_eq!(again.map.photons(), view.map.photons(), "deterministic");
    }

    #[test]
    fn the_view_estimates_the_same_irradiance_over_a_wider_disc() {
        // Inside the uniform disc (irradiance 4 W / π0.1² = 127.3) both estimates agree in
        // expectation: the map's over its 50 nearest photons (radius ≈ 0.0035), the view's
        // over every kept photon within 0.05 (≈ 100 photons); 4σ ≈ 0.4.
        let caustics = map(40_000, 1e-4, 0.1);
        let global = GatherMap {
            gather: 64,
            radius: 0.05,
            ..map(500, 1e-2, 5.0)
        };
        let view = gather_view(&caustics, &global).unwrap();
        let mut scratch = Vec::new();
        let expected = 4.0 / (std::f32::consts::PI * 0.01);
        for (g, tolerance) in [(&caustics, 0.3), (&view, 0.4)] {
            let p = Vec3::new(0.02, 0.0, 0.0);
            let e = g.density(p, Vec3::Z, &mut scratch, |_| Vec3::ONE).x;
            assert!((e / expected - 1.0).abs() < tolerance, "{e} vs {expected}");
        }
        // Outside the disc, within the view's radius of its edge: the view sees caustic light
        // there (the blur), the map does not.
        let p = Vec3::new(0.13, 0.0, 0.0);
        assert!(view.density(p, Vec3::Z, &mut scratch, |_| Vec3::ONE).x > 0.0);
    }

    #[test]
    fn no_thinning_when_caustic_photons_are_the_heavier_ones() {
        let caustics = map(100, 1.0, 0.1);
        let global = map(100, 1e-3, 1.0);
        let view = gather_view(&caustics, &global).unwrap();
        assert_eq!(view.map.photons(), caustics.map.photons());
        assert!(gather_view(&map(0, 1.0, 0.1), &global).is_none());
    }
}
