//! The photon pass for one map: `N` photons emitted and traced in parallel (rayon over
//! fixed ranges of photon indices), each from its own Sobol sequence
//! `Sampler::for_item(seed ⊕ map, photon index, 0)`, gathered in index order — so the map is
//! the same at any thread count.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;

use super::emit::Emission;
use super::kdtree::Photon;
use super::trace::trace_photon;
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
/// stores, powers divided by `photons`. `None` when `cancel` was set.
pub fn trace_map(
    ctx: &ShadeContext<'_>,
    emission: &Emission,
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
                trace_photon(
                    ctx,
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
