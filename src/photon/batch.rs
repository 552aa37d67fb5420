//! Photons traced wide: one work item's photons (a fixed range of photon indices) advance
//! together, one interaction per round, and each round's rays go through the accelerator's
//! batch intersection ([`crate::accel::Accel::intersect_batch`], interleaved traversal: the
//! memory latency of one ray overlaps the others' work). Each photon keeps its own sampler
//! (`Sampler::for_item(seed, index, 0)`) and [`Walk`], and its deposits are put back in
//! photon-index order, so a batch stores the same photons in the same order, bit for bit, as
//! tracing the photons one by one ([`Tracing::PerPhoton`]).
//!
//! **Which one runs**: [`super::pass`] picks batched tracing in scenes of many triangles
//! and per-photon tracing in small ones. `benches/photons.rs` measured batched tracing 5–8 %
//! slower on `caustics.ron` in session 11 (1 thread, 3 × 41 alternating rounds, median ratio
//! batched/per-photon 0.95 global, 0.92 caustic; load 12–15 on 2 cores): at the few thousand
//! triangles of the Cornell boxes the traversal fits in cache and there is no memory latency
//! to hide, while the batch pays for the bookkeeping of its rounds. Since the AVX-512 batch
//! kernels (session 14) the photon-heavy `caustics.ron` render (1 M caustic photons into an
//! 18,048-triangle glass ball) is 1.01–1.05× faster batched (session 15,
//! `docs/ray-layer.md`). Both store the same bytes
//! (`batched_photons_are_the_per_photon_ones_bit_for_bit`).
//!
//! A walk's ray that starts on a convex, isolated instance (a glass ball) is traced from a
//! later origin past that instance's own triangles ([`crate::accel::Shortcuts`]); its hit is
//! then turned back into the full query's answer, or the ray is traced again in full (a
//! second batch), so the photons stay those of [`Tracing::PerPhoton`].
//!
//! After each round's batch intersection the walks step in blocks of [`BLOCK`]: the block's
//! shading points (the hit triangle's vertices, its instance, indices and vertex normals, all
//! loads that miss the cache in a large scene) are computed first in one tight loop, where
//! their loads overlap, then each walk steps from its point
//! ([`Walk::step_at`](super::walk::Walk::step_at), [`PhotonVertex`]).

use std::ops::Range;

use super::emit::Emission;
use super::kdtree::Photon;
use super::light_lists::ReceiverLights;
use super::trace::walk_to_end;
use super::walk::Walk;
use crate::accel::{Hit, Ray, Shortcut, Shortcuts};
use crate::components::PhotonRole;
use crate::geometry::ShadingPoint;
use crate::sampling::Sampler;
use crate::shading::integrator::ShadeContext;
use crate::shading::photon_vertex::PhotonVertex;

/// Walks whose hits' shading points are computed together before they step.
const BLOCK: usize = 16;

/// Which map a pass fills.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapKind {
    /// Photons at diffuse surfaces after one or more specular bounces only; paths stop at
    /// their first diffuse scattering.
    Caustics,
    /// Photons at every diffuse hit except caustic ones (`L S+ D`, the caustic map's): a
    /// final-gather ray that meets a caustic would read a few very bright photons, the
    /// speckles of a caustic seen through one diffuse bounce (`L S+ D D E`, not computed).
    Global,
}

/// How a pass traces its photons (the same photons either way).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tracing {
    /// A work item's photons advance together through batch intersections.
    Batched,
    /// One photon after the other, one intersection call per ray (the default; the photon
    /// pass itself picks batched tracing in large scenes, see the module header).
    #[default]
    PerPhoton,
}

/// What one work item of a pass traces: the photons `range` of the pass seeded `seed`, each
/// emitted from `emission` with its power times `scale`, stored for the map `kind`.
#[derive(Clone, Copy)]
pub struct Chunk<'a> {
    /// Scene, lights and settings.
    pub ctx: &'a ShadeContext<'a>,
    /// Where photons are emitted.
    pub emission: &'a Emission,
    /// Each instance's caster/receiver role (empty: all cast and receive).
    pub roles: &'a [PhotonRole],
    /// The map the photons are stored for.
    pub kind: MapKind,
    /// The pass's seed.
    pub seed: u32,
    /// Power factor (1 / photons in the pass).
    pub scale: f32,
    /// Which surfaces keep photons of which lights (material light lists).
    pub receivers: ReceiverLights<'a>,
    /// Shortcuts past convex parts for batched rays, where the pass is long enough to repay
    /// making them ([`shortcuts_pay`]).
    pub shortcuts: Option<&'a Shortcuts>,
}

/// Whether a pass of `photons` photons in `geometry` repays making the accelerator's
/// shortcuts (`accel/shortcut.rs`): making them costs about a microsecond per triangle of a
/// convex part (the convexity check) and saves about 0.3 µs per photon that crosses one
/// (measured on a glass ball, session 31), so a pass of fewer than 8 photons per triangle
/// goes without (unless they were made already: a second pass uses them for nothing). The
/// environment variable `STAGELIGHT_SHORTCUTS` (`on` or `off`) overrides it (a measuring
/// knob: the same photons either way).
pub fn shortcuts_pay(geometry: &crate::geometry::SceneGeometry, photons: u64) -> bool {
    static FORCED: std::sync::OnceLock<Option<bool>> = std::sync::OnceLock::new();
    let forced = FORCED.get_or_init(|| match std::env::var("STAGELIGHT_SHORTCUTS").as_deref() {
        Ok("on") => Some(true),
        Ok("off") => Some(false),
        _ => None,
    });
    forced.unwrap_or(
        geometry.accel.has_shortcuts() || photons >= 8 * geometry.triangle_count() as u64,
    )
}

impl Chunk<'_> {
    /// The photons the map stores from photon indices `range`, in index order (each photon's
    /// deposits in the order it made them).
    pub fn trace(&self, range: Range<u64>, tracing: Tracing) -> Vec<Photon> {
        match tracing {
            Tracing::Batched => self.batched(range),
            Tracing::PerPhoton => self.per_photon(range),
        }
    }

    /// Whether the map stores a deposit of a photon from light `light`: caustic photons go
    /// to the caustic map only (see [`MapKind::Global`]), and a surface keeps only the lights
    /// its material's light list names.
    fn keeps(&self, d: &super::walk::Deposit, light: usize) -> bool {
        (self.kind == MapKind::Caustics) == d.caustic && self.receivers.admits(d.prim, light)
    }

    /// The sampler of each photon of `range` in turn (`Sampler::for_item(seed, i, 0)`), each
    /// made one photon ahead ([`Sampler::for_item_primed`]: its seed hash, index scramble and
    /// first eight Sobol dimensions, integer chains that then run beside the previous
    /// photon's emission and tracing instead of heading its own; the same stream).
    fn samplers(&self, range: Range<u64>) -> impl Iterator<Item = Sampler> + '_ {
        let mut next = Sampler::for_item_primed(self.seed, range.start, 0);
        range.map(move |i| {
            std::mem::replace(&mut next, Sampler::for_item_primed(self.seed, i + 1, 0))
        })
    }

    /// Photon `sampler`'s sampler, after drawing its emission, its first ray and power, and
    /// the index of the light that emitted it.
    #[inline(always)]
    fn emit(&self, mut sampler: Sampler) -> (Sampler, Option<(Walk, usize)>) {
        let u = [(); 5].map(|_| sampler.next_1d());
        let walk = match (
            self.emission.sample(self.ctx.geometry, u),
            self.emission.light_index(u[0]),
        ) {
            (Some(e), Some(light)) => Some((
                Walk::new(self.ctx, e.ray, e.power * self.scale).with_falloff(e.falloff),
                light,
            )),
            _ => None,
        };
        (sampler, walk)
    }

    fn stop_after_diffuse(&self) -> bool {
        self.kind == MapKind::Caustics
    }

    fn per_photon(&self, range: Range<u64>) -> Vec<Photon> {
        let mut out = Vec::new();
        for sampler in self.samplers(range) {
            let (mut sampler, Some((walk, light))) = self.emit(sampler) else {
                continue;
            };
            walk_to_end(
                self.ctx,
                self.roles,
                walk,
                &mut sampler,
                self.stop_after_diffuse(),
                |d| {
                    if self.keeps(&d, light) {
                        out.push(d.photon);
                    }
                },
            );
        }
        out
    }

    fn batched(&self, range: Range<u64>) -> Vec<Photon> {
        let mut walks: Vec<(Sampler, Walk, usize)> =
            Vec::with_capacity((range.end - range.start) as usize);
        for sampler in self.samplers(range) {
            if let (sampler, Some((walk, light))) = self.emit(sampler) {
                walks.push((sampler, walk.without_fate(), light));
            }
        }
        let mut live: Vec<usize> = (0..walks.len()).collect();
        let (mut rays, mut hits) = (Vec::new(), Vec::<Option<Hit>>::new());
        let accel = &self.ctx.geometry.accel;
        let no_shortcuts = Shortcuts::default();
        let shortcuts = self.shortcuts.unwrap_or(&no_shortcuts);
        // Rays traced from a later origin (`Shortcuts`): their index in the round's rays.
        let mut shortened: Vec<u32> = Vec::new();
        let (mut retrace, mut again) = (Vec::<(u32, Ray)>::new(), Vec::<Option<Hit>>::new());
        // (walk, photon) in the order made; walks are in photon-index order, so
        // [`in_walk_order`] puts them back in photon-index order.
        let mut stored: Vec<(u32, Photon)> = Vec::new();
        let mut points: Vec<Option<ShadingPoint>> = Vec::with_capacity(BLOCK);
        let stop = self.stop_after_diffuse();
        while !live.is_empty() {
            rays.clear();
            shortened.clear();
            for (i, &w) in live.iter().enumerate() {
                let walk = &walks[w].1;
                let ray = walk.ray();
                let shortcut = walk
                    .left()
                    .map(|(from, cos)| shortcuts.shortcut(ray, from, cos));
                rays.push(match shortcut {
                    Some(Shortcut::From(later)) => {
                        shortened.push(i as u32);
                        later
                    }
                    _ => *ray,
                });
            }
            hits.clear();
            hits.resize(rays.len(), None);
            accel.intersect_batch(&rays, &mut hits);
            // The shortened rays' hits as the full queries', or those rays again in full.
            retrace.clear();
            for &i in &shortened {
                let ray = walks[live[i as usize]].1.ray();
                match Shortcuts::confirm(accel, ray, hits[i as usize]) {
                    Some(hit) => hits[i as usize] = Some(hit),
                    None => retrace.push((i, *ray)),
                }
            }
            if !retrace.is_empty() {
                rays.clear();
                rays.extend(retrace.iter().map(|&(_, ray)| ray));
                again.clear();
                again.resize(rays.len(), None);
                accel.intersect_batch(&rays, &mut again);
                for (&(i, _), &hit) in retrace.iter().zip(&again) {
                    hits[i as usize] = hit;
                }
            }
            for (ws, hs) in live.chunks(BLOCK).zip(hits.chunks(BLOCK)) {
                // The block's shading points first: their loads (the hit triangle, its
                // indices and normals) overlap here instead of stalling each interaction.
                points.clear();
                points.extend(
                    hs.iter()
                        .map(|h| h.as_ref().map(|h| PhotonVertex::shading_point(self.ctx, h))),
                );
                for ((&w, hit), sp) in ws.iter().zip(hs).zip(&points) {
                    let (sampler, walk, light) = &mut walks[w];
                    let light = *light;
                    let at = hit.as_ref().zip(sp.as_ref());
                    walk.step_at(self.ctx, self.roles, at, sampler, stop, &mut |d| {
                        if self.keeps(&d, light) {
                            stored.push((w as u32, d.photon));
                        }
                    });
                }
            }
            live.retain(|&w| walks[w].1.live());
        }
        in_walk_order(&stored, walks.len())
    }
}

/// The photons of `stored` (walk index below `walks`, photon) ordered by walk, each walk's
/// in the order given: what a stable sort by walk gives, by counting (a walk deposits at
/// most once per round, so `stored` is one sorted run per round, up to [`super::walk::MAX_BOUNCES`]).
fn in_walk_order(stored: &[(u32, Photon)], walks: usize) -> Vec<Photon> {
    let mut next = vec![0u32; walks + 1];
    for &(w, _) in stored {
        next[w as usize + 1] += 1;
    }
    for w in 1..next.len() {
        next[w] += next[w - 1];
    }
    let zero = Photon {
        position: glam::Vec3::ZERO,
        power: glam::Vec3::ZERO,
        incoming: glam::Vec3::ZERO,
        normal: glam::Vec3::ZERO,
    };
    let mut out = vec![zero; stored.len()];
    for &(w, p) in stored {
        let at = &mut next[w as usize];
        out[*at as usize] = p;
        *at += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::AtomicBool;

    use glam::Vec3;

    use super::*;
    use crate::components::{Emitter, LightShape, Shader};
    use crate::geometry::SceneGeometry;
    use crate::photon::trace_map_with;
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture::{self, Object};
    use crate::shading::lights::LightSet;

    /// Counting places the deposits as the stable sort by walk did.
    #[test]
    fn walk_order_is_the_stable_sort_by_walk() {
        let photon = |x: f32| Photon {
            position: Vec3::new(x, -x, 0.5 * x),
            power: Vec3::splat(x),
            incoming: Vec3::Z,
            normal: Vec3::Y,
        };
        for (n, walks) in [(0usize, 0usize), (1, 1), (7, 3), (500, 40), (3000, 4096)] {
            let stored: Vec<(u32, Photon)> = (0..n)
                .map(|i| (((i * 7919) % walks.max(1)) as u32, photon(i as f32)))
                .collect();
            let mut sorted = stored.clone();
            sorted.sort_by_key(|&(w, _)| w);
            let want: Vec<Photon> = sorted.into_iter().map(|(_, p)| p).collect();
            assert_eq!(
                in_walk_order(&stored, walks),
                want,
                "{n} deposits, {walks} walks"
            );
        }
    }

    #[test]
    fn batched_photons_are_the_per_photon_ones_bit_for_bit() {
        // A grey box with a mirror floor patch and a glass-like ceiling patch around a point
        // light: photons bounce many times (global) and make caustics (mirror).
        let geometry = fixture::geometry(vec![
            Object {
                triangles: fixture::inward_cube(1.0),
                material: fixture::lambert(0.7),
            },
            Object {
                triangles: fixture::quad(
                    Vec3::new(-0.5, -0.5, -0.99),
                    Vec3::new(1.0, 0.0, 0.0),
                    Vec3::new(0.0, 1.0, 0.0),
                ),
                material: fixture::material(Shader::Mirror { color: Vec3::ONE }),
            },
        ]);
        batched_equal_per_photon(&geometry, Vec3::new(0.1, 0.2, 0.3), 5000, 100);
    }

    /// Both maps of `photons` photons from a point light at `position`, batched and one by
    /// one, store the same photons (at least `least` of each).
    fn batched_equal_per_photon(
        geometry: &SceneGeometry,
        position: Vec3,
        photons: u32,
        least: usize,
    ) {
        let e = Emitter::new(LightShape::Point { position }, Vec3::ONE);
        let lights = LightSet::new(&[e], None, 1);
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(geometry, &lights, &s);
        let emission = Emission::new(&lights, geometry);
        let cancel = AtomicBool::new(false);
        for kind in [MapKind::Global, MapKind::Caustics] {
            let map = (&ctx, &emission, &[][..], kind);
            let batched = trace_map_with(map, photons, 7, &cancel, Tracing::Batched).unwrap();
            let single = trace_map_with(map, photons, 7, &cancel, Tracing::PerPhoton).unwrap();
            println!("{kind:?}: {} photons stored", batched.len());
            assert!(batched.len() > least, "{}", batched.len());
            assert_eq!(batched, single, "{kind:?}");
        }
    }

    /// A glass ball in a grey box: batched photons take the accelerator's shortcuts past the
    /// ball (leaving it and crossing it) and store what photons traced one by one store.
    #[test]
    fn batched_photons_through_shortcuts_are_the_per_photon_ones_bit_for_bit() {
        let ball = crate::accel::test_random::uv_sphere(Vec3::new(0.1, 0.0, -0.3), 0.5, 12, 24);
        let geometry = fixture::geometry(vec![
            Object {
                triangles: fixture::inward_cube(1.0),
                material: fixture::lambert(0.7),
            },
            Object {
                triangles: ball,
                material: fixture::material(Shader::Dielectric {
                    ior: 1.5,
                    ior_out: 1.0,
                    col: Vec3::ONE,
                }),
            },
        ]);
        assert!(!geometry.accel.has_shortcuts());
        let photons = 8 * geometry.triangle_count() as u32;
        batched_equal_per_photon(&geometry, Vec3::new(0.1, 0.2, 0.6), photons, 200);
        assert!(geometry.accel.has_shortcuts());
        assert_eq!(geometry.shortcuts().parts(), 1, "the ball");
    }
}
