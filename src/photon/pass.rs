//! The photon pass for one map: `N` photons emitted and traced in parallel (rayon over
//! fixed ranges of photon indices, each range traced wide through batch intersections in
//! scenes of many triangles, one photon at a time in small ones: [`super::batch`]), each
//! photon from its own Sobol sequence `Sampler::for_item(seed ⊕ map, photon index, 0)`,
//! gathered in index order — so the map is the same at any thread count. Lights with their
//! own photon count (mental ray `caustic photons N` on a light) emit it in a pass of their
//! own ([`trace_map_by_light`]). A surface keeps only the photons of the lights its
//! material's light list names ([`super::light_lists`]).

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;

pub use super::batch::MapKind;
use super::batch::{shortcuts_pay, Chunk, Tracing};
use super::emit::Emission;
use super::kdtree::Photon;
use super::light_lists::ReceiverLights;
use super::parts::PhotonParts;
use crate::components::PhotonRole;
use crate::sampling::hash_combine;
use crate::shading::integrator::ShadeContext;

/// Photons per parallel work item.
const CHUNK: u64 = 4096;

/// Emits `photons` photons from `emission` into `ctx`'s scene and returns the ones the map
/// stores, powers divided by `photons`, as the work items' vectors ([`PhotonParts`]);
/// `roles[instance slot]` says which surfaces cast and receive (empty: all). `None` when
/// `cancel` was set.
pub fn trace_map(
    ctx: &ShadeContext<'_>,
    emission: &Emission,
    roles: &[PhotonRole],
    kind: MapKind,
    photons: u32,
    seed: u32,
    cancel: &AtomicBool,
) -> Option<PhotonParts> {
    let map = (ctx, emission, roles, kind);
    trace_parts_with(map, photons, seed, cancel, default_tracing(ctx))
}

/// Scenes of at least this many triangles trace their photons batched: measured on the
/// photon-heavy `caustics.ron` (18,052 triangles, 1 M caustic photons, issue 17 session 15),
/// batched was 1.01–1.05× faster than per photon; on the Cornell boxes (a few dozen
/// triangles, a cache-resident tree) the batch's bookkeeping does not pay (session 11).
const BATCHED_MIN_TRIANGLES: usize = 4096;

/// How [`trace_map`] traces in `ctx`'s scene: batched from [`BATCHED_MIN_TRIANGLES`]
/// triangles, else per photon; the environment variable `STAGELIGHT_PHOTON_TRACING`
/// (`batched` or `per_photon`) overrides it (a measuring knob: the same photons either way).
fn default_tracing(ctx: &ShadeContext<'_>) -> Tracing {
    static FORCED: std::sync::OnceLock<Option<Tracing>> = std::sync::OnceLock::new();
    let forced =
        FORCED.get_or_init(
            || match std::env::var("STAGELIGHT_PHOTON_TRACING").as_deref() {
                Ok("batched") => Some(Tracing::Batched),
                Ok("per_photon") => Some(Tracing::PerPhoton),
                _ => None,
            },
        );
    forced.unwrap_or(if ctx.geometry.triangle_count() >= BATCHED_MIN_TRIANGLES {
        Tracing::Batched
    } else {
        Tracing::PerPhoton
    })
}

/// [`trace_map`] (its `ctx`, `emission`, `roles`, `kind` in `map`) traced as `tracing`
/// says, in one vector: the same photons either way.
pub fn trace_map_with(
    map: (&ShadeContext<'_>, &Emission, &[PhotonRole], MapKind),
    photons: u32,
    seed: u32,
    cancel: &AtomicBool,
    tracing: Tracing,
) -> Option<Vec<Photon>> {
    trace_parts_with(map, photons, seed, cancel, tracing).map(PhotonParts::into_vec)
}

/// [`trace_map_with`] as the work items' vectors.
fn trace_parts_with(
    map: (&ShadeContext<'_>, &Emission, &[PhotonRole], MapKind),
    photons: u32,
    seed: u32,
    cancel: &AtomicBool,
    tracing: Tracing,
) -> Option<PhotonParts> {
    let (ctx, emission, roles, kind) = map;
    let n = u64::from(photons);
    let chunk = Chunk {
        ctx,
        emission,
        roles,
        kind,
        seed: hash_combine(&[seed, kind as u32, 0x9407]),
        scale: 1.0 / n.max(1) as f32,
        receivers: ReceiverLights::new(ctx.geometry),
        shortcuts: (tracing == Tracing::Batched && shortcuts_pay(ctx.geometry, n))
            .then(|| ctx.geometry.shortcuts()),
    };
    let chunks: Vec<Option<Vec<Photon>>> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            Some(chunk.trace(c * CHUNK..((c + 1) * CHUNK).min(n), tracing))
        })
        .collect();
    chunks.into_iter().collect()
}

/// [`trace_map`] where the lights in `counts` (`(light index, photons)`) each emit their own
/// number of photons, seeded apart, and the other lights share `photons` by power. Returns
/// the stored photons (shared pass first, then by light in `counts` order; the work items'
/// vectors) and the number emitted.
#[allow(clippy::too_many_arguments)] // reason: one pass's inputs, each used once
pub fn trace_map_by_light(
    ctx: &ShadeContext<'_>,
    emission: &Emission,
    roles: &[PhotonRole],
    kind: MapKind,
    photons: u32,
    counts: &[(usize, u32)],
    seed: u32,
    cancel: &AtomicBool,
) -> Option<(PhotonParts, u64)> {
    if counts.is_empty() {
        let all = trace_map(ctx, emission, roles, kind, photons, seed, cancel)?;
        return Some((all, u64::from(photons)));
    }
    let counted = |i: usize| counts.iter().any(|&(j, _)| j == i);
    let shared = emission.subset(|i| !counted(i));
    let (mut all, mut emitted) = (PhotonParts::new(), 0u64);
    if !shared.is_empty() {
        all = trace_map(ctx, &shared, roles, kind, photons, seed, cancel)?;
        emitted += u64::from(photons);
    }
    for &(light, n) in counts {
        let own = emission.subset(|i| i == light);
        if own.is_empty() || n == 0 {
            continue;
        }
        let light_seed = hash_combine(&[seed, light as u32 + 1, 0x117e]);
        all.append(trace_map(ctx, &own, roles, kind, n, light_seed, cancel)?);
        emitted += u64::from(n);
    }
    Some((all, emitted))
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
            .map(PhotonParts::into_vec)
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
