//! The photon pass for one map: `N` photons emitted and traced in parallel (rayon over
//! fixed ranges of photon indices), each from its own Sobol sequence
//! `Sampler::for_item(seed ⊕ map, photon index, 0)`, gathered in index order — so the map is
//! the same at any thread count.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;

use super::emit::Emission;
use super::kdtree::Photon;
use super::trace::trace_photon_with_roles;
use crate::components::PhotonRole;
use crate::sampling::{hash_combine, Sampler};
use crate::shading::integrator::ShadeContext;

/// Photons per parallel work item.
const CHUNK: u64 = 4096;

/// Which map a pass fills.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapKind {
    /// Photons at diffuse surfaces after one or more specular bounces only; paths stop at
    /// their first diffuse scattering.
    Caustics,
    /// Photons at every diffuse hit.
    Global,
}

/// Emits `photons` photons from `emission` into `ctx`'s scene and returns the ones the map
/// stores, powers divided by `photons`; `roles[instance slot]` says which surfaces cast and
/// receive (empty: all). `None` when `cancel` was set.
pub fn trace_map(
    ctx: &ShadeContext<'_>,
    emission: &Emission,
    roles: &[PhotonRole],
    kind: MapKind,
    photons: u32,
    seed: u32,
    cancel: &AtomicBool,
) -> Option<Vec<Photon>> {
    let n = u64::from(photons);
    let scale = 1.0 / n.max(1) as f32;
    let seed = hash_combine(&[seed, kind as u32, 0x9407]);
    let chunks: Vec<Option<Vec<Photon>>> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            let mut out = Vec::new();
            for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                let mut sampler = Sampler::for_item(seed, i, 0);
                let u = [(); 5].map(|_| sampler.next_1d());
                let Some(emitted) = emission.sample(ctx.geometry, u) else {
                    continue;
                };
                let stop = kind == MapKind::Caustics;
                trace_photon_with_roles(
                    ctx,
                    roles,
                    emitted.ray,
                    emitted.power * scale,
                    &mut sampler,
                    stop,
                    |d| {
                        if kind == MapKind::Global || d.caustic {
                            out.push(d.photon);
                        }
                    },
                );
            }
            Some(out)
        })
        .collect();
    let mut all = Vec::new();
    for c in chunks {
        all.extend(c?);
    }
    Some(all)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::components::{Emitter, LightShape};
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture::{self, Object};
    use crate::shading::lights::LightSet;

    /// A point light of intensity 1 at height 1 over a large grey floor: 4π W, of which the
    /// half going down lands on the floor, and every bounce leaves the scene.
    fn photons(kind: MapKind, n: u32, threads: usize, cancel: bool) -> Option<Vec<Photon>> {
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::floor(1000.0, 0.0),
            material: fixture::lambert(0.5),
        }]);
        let position = Vec3::new(0.0, 0.0, 1.0);
        let e = Emitter::new(LightShape::Point { position }, Vec3::ONE);
        let lights = LightSet::new(&[e], None, 1);
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let emission = Emission::new(&lights, &geometry);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let flag = AtomicBool::new(cancel);
        pool.install(|| trace_map(&ctx, &emission, &[], kind, n, 3, &flag))
    }

    #[test]
    fn the_global_map_is_the_same_at_any_thread_count_with_exact_powers() {
        let n = 6000;
        let one = photons(MapKind::Global, n, 1, false).unwrap();
        let three = photons(MapKind::Global, n, 3, false).unwrap();
        assert_eq!(one, three);
        // First hits only (bounces escape), each carrying Φ / N.
        let each = Vec3::splat(4.0 * std::f32::consts::PI) * (1.0 / n as f32);
        assert!(one.iter().all(|p| p.power == each && p.normal == Vec3::Z));
        let fraction = one.len() as f64 / f64::from(n);
        println!("stored {} of {n} photons ({fraction})", one.len());
        assert!((fraction - 0.5).abs() < 0.03, "{fraction}");
    }

    #[test]
    fn the_caustic_map_is_empty_without_specular_surfaces_and_cancel_stops() {
        assert_eq!(photons(MapKind::Caustics, 2000, 2, false), Some(Vec::new()));
        assert_eq!(photons(MapKind::Global, 2000, 2, true), None);
    }
}
