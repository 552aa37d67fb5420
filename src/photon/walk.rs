//! One photon's walk as a state machine: [`Walk::step`] takes the hit of the walk's current
//! ray (traced by the caller, alone or in a batch) and performs one surface interaction —
//! absorption along the segment, the deposit, roles, scattering, Russian roulette — exactly
//! as [`super::trace`] documents. [`super::trace::trace_photon_with_roles`] steps one walk
//! with one intersection per call; [`super::batch`] steps many with the accelerator's batch
//! intersection, with the same results bit for bit.

use glam::Vec3;

use super::depth::PathDepth;
use super::emit::Falloff;
use super::kdtree::Photon;
use crate::accel::{Accel, Hit, Ray, MAX_PASSED};
use crate::components::PhotonRole;
use crate::geometry::ShadingPoint;
use crate::sampling::Sampler;
use crate::shading::bsdf::{Bsdf, Scatter, TransportMode};
use crate::shading::integrator::ShadeContext;
use crate::shading::photon_vertex::PhotonVertex;
use crate::shading::shadow::shader_transmits_shadows;

/// Most surface interactions of one photon.
pub const MAX_BOUNCES: u32 = 64;

/// A photon at a diffuse (non-delta) surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deposit {
    /// The photon as a map stores it.
    pub photon: Photon,
    /// Scattering events before this hit (0 = straight from the light).
    pub bounces: u32,
    /// Whether every one of those events was specular (delta) and there was at least one:
    /// an `L S+ D` path, what the caustic map stores.
    pub caustic: bool,
    /// The world triangle it landed on (its material's light list filters it).
    pub prim: u32,
}

/// How a photon's path ended and where its power went, W.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Fate {
    /// Power absorbed by surfaces and dielectric media (Russian roulette included).
    pub absorbed: Vec3,
    /// Power that left the scene.
    pub escaped: Vec3,
    /// Direction of the escaping photon (zero when none escaped).
    pub escape_dir: Vec3,
    /// Power dropped at [`MAX_BOUNCES`], by `stop_after_diffuse` or at the photon trace
    /// depth.
    pub truncated: Vec3,
    /// Where the last hit was (the absorbing surface's triangle), if any.
    pub last_prim: Option<u32>,
}

/// A photon on its way: its next ray, its power and what happened to it so far.
#[derive(Debug, Clone)]
pub struct Walk {
    ray: Ray,
    power: Vec3,
    fate: Fate,
    specular_only: bool,
    specular_events: u32,
    bounces: u32,
    depth: PathDepth,
    live: bool,
    /// Whether [`Walk::fate`] is kept complete (see [`Walk::without_fate`]).
    keep_fate: bool,
    /// Culled back faces (`face: Cull`) passed since the last interaction.
    passed: u32,
    /// The triangle [`Walk::ray`] leaves (`u32::MAX`: the light), and the cosine between
    /// the ray's direction and that triangle's geometric normal.
    left: u32,
    left_cos: f32,
    /// The light's distance terms, still to be applied at the first hit, and where the
    /// photon left the light ([`Walk::with_falloff`]).
    falloff: Option<(Falloff, Vec3)>,
}

impl Walk {
    /// A photon leaving along `ray` with `power`, stopped at the photon trace depth
    /// `ctx.photon_depth`.
    pub fn new(ctx: &ShadeContext<'_>, ray: Ray, power: Vec3) -> Self {
        Self {
            ray,
            power,
            fate: Fate::default(),
            specular_only: true,
            specular_events: 0,
            bounces: 0,
            depth: PathDepth::new(ctx.photon_depth),
            live: true,
            keep_fate: true,
            passed: 0,
            left: u32::MAX,
            left_cos: 0.0,
            falloff: None,
        }
    }

    /// The walk of a photon whose light has distance terms beyond 1/d² (`falloff`): its
    /// power is multiplied by their factor at the distance of its first hit from the ray's
    /// origin, where it left the light.
    pub fn with_falloff(mut self, falloff: Option<Falloff>) -> Self {
        self.falloff = falloff.map(|f| (f, self.ray.origin));
        self
    }

    /// The walk for a caller that never reads [`Walk::fate`] (a batch keeps only the
    /// deposits). Its fate is left incomplete: the terms booked at every interaction (the
    /// segment's absorption, the part survival does not carry on, the escape, the last
    /// triangle) are skipped. With `stop_after_diffuse` it also ends at a surface whose BSDF
    /// has no delta lobe right after the deposit, without drawing the scattering that would
    /// end it anyway (the sampled lobe is non-delta, so the path is no longer specular-only;
    /// or it is absorbed). The deposits and the walk's end are the same.
    pub fn without_fate(mut self) -> Self {
        self.keep_fate = false;
        self
    }

    /// Whether the walk goes on: its [`Walk::ray`] is to be traced and passed to
    /// [`Walk::step`].
    pub fn live(&self) -> bool {
        self.live
    }

    /// The ray the walk follows next.
    pub fn ray(&self) -> &Ray {
        &self.ray
    }

    /// The triangle [`Walk::ray`] leaves and the cosine between the ray's direction and
    /// that triangle's geometric normal (`(v₁ − v₀) × (v₂ − v₀)`, unflipped); `None`: the
    /// photon comes from the light.
    pub fn left(&self) -> Option<(u32, f32)> {
        (self.left != u32::MAX).then_some((self.left, self.left_cos))
    }

    /// The power the photon carries along [`Walk::ray`].
    pub fn power(&self) -> Vec3 {
        self.power
    }

    /// Where the photon's power went (complete once the walk is no longer live, unless it
    /// was made [`Walk::without_fate`]).
    pub fn fate(&self) -> Fate {
        self.fate
    }

    /// One interaction at `hit`, the closest hit of [`Walk::ray`] (`None`: it left the
    /// scene). Draws from `sampler`; calls `deposit` when the photon is stored. With
    /// `stop_after_diffuse` the walk ends after its first non-specular scattering.
    pub fn step(
        &mut self,
        ctx: &ShadeContext<'_>,
        roles: &[PhotonRole],
        hit: Option<Hit>,
        sampler: &mut Sampler,
        stop_after_diffuse: bool,
        deposit: &mut impl FnMut(Deposit),
    ) {
        if !self.live {
            return;
        }
        let at = hit.map(|h| (h, PhotonVertex::shading_point(ctx, &h)));
        self.step_at(
            ctx,
            roles,
            at.as_ref().map(|(h, sp)| (h, sp)),
            sampler,
            stop_after_diffuse,
            deposit,
        );
    }

    /// [`Walk::step`] at a hit whose shading point the caller computed
    /// ([`PhotonVertex::shading_point`] of the hit): the same interaction, bit for bit.
    #[inline(always)]
    pub fn step_at(
        &mut self,
        ctx: &ShadeContext<'_>,
        roles: &[PhotonRole],
        hit: Option<(&Hit, &ShadingPoint)>,
        sampler: &mut Sampler,
        stop_after_diffuse: bool,
        deposit: &mut impl FnMut(Deposit),
    ) {
        if !self.live {
            return;
        }
        self.live = false;
        let fate = &mut self.fate;
        let ray = self.ray;
        // The account every interaction keeps (the exits below book their one term each):
        // left out where no caller reads it (a batch's walks, `Walk::without_fate`).
        let keep = self.keep_fate;
        let Some((hit, sp)) = hit else {
            if keep {
                fate.escaped = self.power;
                fate.escape_dir = ray.dir.normalize_or_zero();
            }
            return;
        };
        // A culled back face (`face: Cull`) is not there for photons either: the photon goes
        // on along the same line, power and path untouched (at most `MAX_PASSED` in a row).
        let accel = &ctx.geometry.accel;
        if accel.culls_back(hit.prim) && !accel.meets_front(hit.prim, ray.dir) {
            match Accel::beyond(&ray, &sp.surface) {
                Some(next) if self.passed < MAX_PASSED => {
                    self.passed += 1;
                    self.ray = next;
                    // The shortcut past a convex part assumes a scattered ray: trace in full.
                    self.left = u32::MAX;
                    self.live = true;
                }
                _ => fate.truncated += self.power,
            }
            return;
        }
        self.passed = 0;
        if let Some((falloff, from)) = self.falloff.take() {
            self.power *= falloff.factor(sp.surface.p.distance(from));
            // d² beyond f32 (a surface ~1e19 from a light without 1/d²): no estimate to
            // make, and no infinity or NaN carried into the map.
            if !self.power.is_finite() {
                self.power = Vec3::ZERO;
            }
        }
        let v = PhotonVertex::new(ctx, &ray, hit, *sp);
        let through = self.power * v.transmittance;
        if keep {
            fate.last_prim = Some(hit.prim);
            fate.absorbed += self.power - through;
        }
        let power = through;
        let mut scratch = None;
        let photon_bsdf;
        // A material's photon shader replaces what its surface shader implies for photons.
        // One that refracts is an interface: photons inside meet its back faces, one-sided
        // surface shader or not (they would otherwise die inside a closed object).
        let (bsdf, stores, interface) = match &ctx.geometry.materials[v.sp.material as usize].photon
        {
            Some(p) => {
                photon_bsdf = Bsdf::for_photons(p, v.front);
                (&photon_bsdf, p.stores(), p.refraction.max_element() > 0.0)
            }
            None => {
                let b = v.bsdf_ref(ctx, &mut scratch);
                (b, b.has_non_delta(), false)
            }
        };
        if !((bsdf.reflects() || stores) && (v.visible || interface)) {
            fate.absorbed += power;
            return;
        }
        let incoming = Vec3::from(v.wo_world);
        let role = roles
            .get(v.sp.instance as usize)
            .copied()
            .unwrap_or(PhotonRole::BOTH);
        if stores && role.receives() {
            deposit(Deposit {
                photon: Photon {
                    position: v.sp.surface.p,
                    power,
                    incoming,
                    normal: v.ng,
                },
                bounces: self.bounces,
                caustic: self.specular_events > 0 && self.specular_only,
                prim: hit.prim,
            });
        }
        if stop_after_diffuse && !self.keep_fate && !bsdf.has_delta() {
            return;
        }
        if !(role.casts() && bsdf.reflects()) {
            fate.absorbed += power;
            return;
        }
        let u = Vec3::new(sampler.next_1d(), sampler.next_1d(), sampler.next_1d());
        let u_rr = sampler.next_1d();
        let Some(s) = bsdf.sample_transport(v.wo, u, TransportMode::Importance) else {
            fate.absorbed += power;
            return;
        };
        let wi = v.frame.to_world(s.wi);
        // Adjoint BSDF with shading normals (Veach 1997, §5.3).
        let ns = v.frame.n;
        let correction =
            (incoming.dot(ns) * wi.dot(v.ng)).abs() / (incoming.dot(v.ng) * wi.dot(ns)).abs();
        let weight = s.weight() * correction;
        if !weight.is_finite() {
            fate.absorbed += power;
            return;
        }
        let q = weight.max_element().min(1.0);
        if q.is_nan() || u_rr >= q {
            fate.absorbed += power;
            return;
        }
        if !s.delta {
            self.specular_only = false;
        } else if !(s.wi == -v.wo && shader_transmits_shadows(&v.shader)) {
            self.specular_events += 1;
        }
        let next_power = power * (weight / q);
        // What survival does not carry on (a colour-dependent weight) is absorbed; a weight
        // above 1 (shading-normal correction) makes this negative, keeping the account exact.
        if keep {
            fate.absorbed += power - next_power;
        }
        if stop_after_diffuse && !self.specular_only {
            fate.truncated += next_power;
            return;
        }
        if !self.depth.scatter(s.scatter == Scatter::Transmission) {
            fate.truncated += next_power;
            return;
        }
        let Some(next) = v.spawn(s.wi, s.scatter == Scatter::Transmission) else {
            fate.absorbed += next_power;
            return;
        };
        self.power = next_power;
        self.ray = next;
        self.left = hit.prim;
        self.left_cos = wi.dot(v.sp.surface.ng);
        self.bounces += 1;
        if self.bounces >= MAX_BOUNCES {
            fate.truncated += next_power;
            return;
        }
        self.live = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture;
    use crate::shading::lights::LightSet;

    /// `face: Cull`: a photon meeting the back of a one-sided sheet goes on untouched to
    /// the floor behind it (no bounce), where without the culling it is absorbed.
    #[test]
    fn a_photon_passes_a_culled_back_face_untouched() {
        use crate::components::{ALL_RAYS, FRONT_ONLY};
        // A sheet at z = 1 facing down over a floor at z = 0 facing up.
        let sheet: Vec<[Vec3; 3]> = fixture::floor(1.0, 1.0)
            .into_iter()
            .map(|[a, b, c]| [a, c, b])
            .collect();
        let floor = fixture::floor(3.0, 0.0);
        let first_sheet = floor.len();
        let mut geometry = fixture::geometry(vec![
            fixture::Object {
                triangles: floor,
                material: fixture::lambert(0.5),
            },
            fixture::Object {
                triangles: sheet,
                material: fixture::lambert(0.5),
            },
        ]);
        let mut masks = vec![ALL_RAYS; geometry.accel.len()];
        for m in &mut masks[first_sheet..] {
            *m |= FRONT_ONLY;
        }
        let lights = LightSet::default();
        let s = RenderSettings::default();
        for culled in [false, true] {
            if culled {
                geometry.accel.set_ray_masks(masks.clone());
            }
            let ctx = ShadeContext::new(&geometry, &lights, &s);
            let ray = Ray {
                origin: Vec3::new(0.1, 0.2, 2.0),
                dir: Vec3::NEG_Z,
                t_max: f32::INFINITY,
            };
            let mut walk = Walk::new(&ctx, ray, Vec3::ONE);
            let mut sampler = Sampler::new(1, 0);
            let mut deposits = Vec::new();
            while walk.live() {
                let hit = ctx.geometry.accel.intersect(walk.ray());
                walk.step(&ctx, &[], hit, &mut sampler, true, &mut |d| {
                    deposits.push(d)
                });
            }
            if culled {
                assert_eq!(deposits.len(), 1);
                let d = deposits[0];
                assert!(d.photon.position.z.abs() < 1e-4, "{d:?}");
                assert_eq!((d.photon.power, d.bounces), (Vec3::ONE, 0));
                assert!((d.prim as usize) < first_sheet);
            } else {
                assert!(deposits.is_empty());
                assert_eq!(walk.fate().absorbed, Vec3::ONE);
            }
        }
    }

    /// A light without 1/d² (`Falloff`): the first hit's power is times d², and times the
    /// attenuation ramp; a d² past f32 gives no infinite or NaN photon.
    #[test]
    fn the_first_hit_takes_the_lights_distance_terms() {
        use crate::photon::emit::Falloff;
        let geometry = fixture::geometry(vec![fixture::Object {
            triangles: fixture::floor(100.0, 0.0),
            material: fixture::lambert(0.5),
        }]);
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let first_deposit = |height: f32, falloff: Falloff| {
            let ray = Ray {
                origin: Vec3::new(0.0, 0.0, height),
                dir: Vec3::NEG_Z,
                t_max: f32::INFINITY,
            };
            let mut walk = Walk::new(&ctx, ray, Vec3::splat(1e10)).with_falloff(Some(falloff));
            let hit = ctx.geometry.accel.intersect(walk.ray());
            let mut got = None;
            walk.step(&ctx, &[], hit, &mut Sampler::new(1, 0), true, &mut |d| {
                got.get_or_insert(d.photon.power);
            });
            got
        };
        let no_falloff = Falloff {
            inverse_square: false,
            attenuation: None,
        };
        let d3 = first_deposit(3.0, no_falloff).expect("a deposit on the floor");
        assert!((d3.x / 9e10 - 1.0).abs() < 1e-5, "{d3}");
        let ramp = Falloff {
            inverse_square: true,
            attenuation: Some((2.0, 4.0)),
        };
        let r3 = first_deposit(3.0, ramp).expect("a deposit on the floor");
        assert!((r3.x / 5e9 - 1.0).abs() < 1e-5, "{r3}");
        // 1e15 away: d² × 1e10 is past f32; stored with no power, never infinite.
        let far = first_deposit(1e15, no_falloff);
        assert_eq!(far, Some(Vec3::ZERO));
    }

    /// A walk without its fate deposits what a full walk deposits and ends at the same
    /// interaction; at a caustic deposit on a surface with no delta lobe it ends without
    /// drawing the scattering.
    #[test]
    fn a_walk_without_fate_ends_at_the_caustic_deposit_without_drawing() {
        // Mirror ceiling at z = 1 facing down, grey floor at z = 0.
        let geometry = fixture::mirror_over_floor();
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let (mut shortened, mut global_steps) = (0, 0);
        for i in 0..64u32 {
            let a = i as f32 * 0.41;
            let dir = Vec3::new(
                0.3 * a.cos(),
                0.3 * a.sin(),
                if i % 4 == 0 { -1.0 } else { 1.0 },
            );
            let ray = Ray {
                origin: Vec3::new(0.2, 0.1, 0.5),
                dir,
                t_max: f32::INFINITY,
            };
            for stop in [true, false] {
                let mut full = Walk::new(&ctx, ray, Vec3::splat(0.5));
                let mut lean = full.clone().without_fate();
                let (mut s_full, mut s_lean) = (Sampler::new(i, 0), Sampler::new(i, 0));
                let (mut d_full, mut d_lean) = (Vec::new(), Vec::new());
                while full.live() {
                    assert!(lean.live());
                    assert_eq!(full.ray(), lean.ray());
                    let hit = ctx.geometry.accel.intersect(full.ray());
                    let before = s_lean.clone();
                    let n = d_lean.len();
                    full.step(&ctx, &[], hit, &mut s_full, stop, &mut |d| d_full.push(d));
                    lean.step(&ctx, &[], hit, &mut s_lean, stop, &mut |d| d_lean.push(d));
                    if stop && d_lean.len() > n {
                        // A deposit on the Lambert floor: the lean walk drew nothing.
                        assert!(!lean.live() && !full.live());
                        assert_eq!(before.clone().next_1d(), s_lean.clone().next_1d());
                        assert_ne!(before.clone().next_1d(), s_full.clone().next_1d());
                        shortened += 1;
                    }
                    global_steps += usize::from(!stop);
                }
                assert!(!lean.live());
                assert_eq!(d_full, d_lean, "photon {i}, stop {stop}");
            }
        }
        assert!(shortened > 32, "{shortened}");
        assert!(global_steps > 64, "{global_steps}");
    }
}
