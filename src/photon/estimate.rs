//! Radiance from the photon maps at a diffuse shading point of the `Direct` integrator:
//! caustics by direct visualisation of the caustic map, indirect diffuse by one final-gather
//! bounce into the global map (see the module doc of [`crate::photon`] for the partition).

use glam::Vec3;

use super::gather_path::land;
use super::irradiance::{IrradianceMaps, IrradiancePoints};
use super::{GatherMap, Neighbour, PhotonMaps};
use crate::sampling::Sampler;
use crate::shading::bsdf::{Bsdf, Lobe};
use crate::shading::integrator::{PhotonRadiance, ShadeContext, Vertex};

impl PhotonRadiance for PhotonMaps {
    /// Caustic plus indirect diffuse radiance toward the viewer at `v` (zero without maps).
    /// Draws from `sampler` only when a global map exists.
    fn radiance(
        &self,
        ctx: &ShadeContext<'_>,
        v: &Vertex<'_>,
        bsdf: &Bsdf,
        sampler: &mut Sampler,
    ) -> Vec3 {
        let mut scratch = Vec::new();
        let mut radiance = Vec3::ZERO;
        if let Some(c) = &self.caustics {
            radiance += reflected(c, v, bsdf, &mut scratch);
        }
        if let Some(g) = &self.global {
            let landing = Landing {
                global: g,
                caustics: self.gather_caustics.as_ref(),
                irradiance: self.gather_irradiance.as_ref(),
            };
            radiance += final_gather(
                ctx,
                &landing,
                g.final_gather,
                v,
                bsdf,
                sampler,
                &mut scratch,
            );
        }
        radiance
    }

    fn caustic_irradiance(&self, v: &Vertex<'_>) -> Vec3 {
        let Some(c) = &self.caustics else {
            return Vec3::ZERO;
        };
        let mut scratch = Vec::new();
        let n = v.frame.n;
        c.density(v.sp.surface.p, v.ng, &mut scratch, |ph| {
            if ph.incoming.dot(n) > 0.0 {
                Vec3::ONE
            } else {
                Vec3::ZERO
            }
        })
    }
}

/// Density estimate of the light `map` reflects at `v` through `bsdf`.
pub fn reflected(
    map: &GatherMap,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    scratch: &mut Vec<Neighbour>,
) -> Vec3 {
    map.density(v.sp.surface.p, v.ng, scratch, |ph| {
        let wi = v.frame.to_local(ph.incoming);
        if wi.z <= 0.0 {
            Vec3::ZERO
        } else {
            bsdf.eval(v.wo, wi)
        }
    })
}

/// What a final-gather ray reads where it lands on a diffuse surface.
struct Landing<'m> {
    /// The global map.
    global: &'m GatherMap,
    /// The caustic map's gather view ([`super::coarse`]).
    caustics: Option<&'m GatherMap>,
    /// Both maps' irradiance at photon positions ([`super::irradiance`]).
    irradiance: Option<&'m IrradiancePoints>,
}

impl Landing<'_> {
    /// Radiance the maps give toward `w.wo` at the landing vertex `w` with BSDF `b`: one
    /// lookup of the irradiance at photon positions where every non-delta lobe is Lambertian, the
    /// per-ray density estimates of both maps otherwise.
    fn radiance(&self, w: &Vertex<'_>, b: &Bsdf, scratch: &mut Vec<Neighbour>) -> Vec3 {
        if let Some(points) = self.irradiance {
            if lambertian(b) {
                let maps = IrradianceMaps {
                    global: self.global,
                    caustics: self.caustics,
                };
                let e = points.at(w.sp.surface.p, w.ng, maps, scratch);
                return if e == Vec3::ZERO {
                    e
                } else {
                    b.eval(w.wo, Vec3::Z) * e
                };
            }
        }
        let mut incoming = reflected(self.global, w, b, scratch);
        if let Some(c) = self.caustics {
            incoming += reflected(c, w, b, scratch);
        }
        incoming
    }
}

/// Whether every non-delta lobe of `b` is Lambertian (its reflected radiance is `f·E`).
fn lambertian(b: &Bsdf) -> bool {
    b.lobes()
        .iter()
        .all(|(_, l)| l.is_delta() || matches!(l, Lobe::Lambert))
}

/// Indirect diffuse light at `v`: `n` BSDF-sampled rays, each reading the maps where it
/// lands on a diffuse surface, directly or through mirrors and glass
/// ([`super::gather_path`]).
fn final_gather(
    ctx: &ShadeContext<'_>,
    landing: &Landing<'_>,
    n: u32,
    v: &Vertex<'_>,
    bsdf: &Bsdf,
    sampler: &mut Sampler,
    scratch: &mut Vec<Neighbour>,
) -> Vec3 {
    let seed = sampler.child_seed();
    let n = n.max(1);
    let mut sum = Vec3::ZERO;
    for j in 0..n {
        let mut s = Sampler::new(seed, j);
        let u = Vec3::new(s.next_1d(), s.next_1d(), s.next_1d());
        let Some(bs) = bsdf.sample(v.wo, u) else {
            continue;
        };
        if bs.delta {
            continue;
        }
        let Some(ray) = v.spawn(bs.wi, false) else {
            continue;
        };
        let Some(to) = land(ctx, ray, &mut s) else {
            continue;
        };
        let incoming = landing.radiance(&to.vertex, &to.bsdf, scratch);
        sum += bs.weight() * to.throughput * incoming;
    }
    let l = sum / n as f32;
    if l.is_finite() {
        l
    } else {
        Vec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    use std::f32::consts::PI;

    use super::*;
    use crate::photon::{Photon, PhotonMap};
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture::{self, Object};
    use crate::shading::lights::LightSet;

    fn photon(x: f32, y: f32, power: f32, incoming: Vec3) -> Photon {
        Photon {
            position: Vec3::new(x, y, 0.0),
            power: Vec3::splat(power),
            incoming,
            normal: Vec3::Z,
        }
    }

    /// 8 photons at distance 0.5 of the origin, the 9th at 1, and 4 more at 2 (power 0.01).
    fn rings(incoming: Vec3) -> Vec<Photon> {
        let ring = |r: f32, n: usize, phase: f32| {
            (0..n).map(move |i| {
                let a = phase + i as f32 * std::f32::consts::TAU / n as f32;
                (r * a.cos(), r * a.sin())
            })
        };
        ring(0.5, 8, 0.1)
            .chain([(1.0, 0.0)])
            .chain(ring(2.0, 4, 0.3))
            .map(|(x, y)| photon(x, y, 0.01, incoming))
            .collect()
    }

    fn map(photons: Vec<Photon>, k: usize, radius: f32) -> GatherMap {
        GatherMap {
            map: PhotonMap::build(photons),
            gather: k,
            radius,
            final_gather: 0,
            emitted: 1000,
            filter: crate::photon::PhotonFilter::Box,
            progressive: None,
        }
    }

    #[test]
    fn the_estimate_of_known_photons_is_the_closed_form() {
        let rho = 0.6;
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::floor(10.0, 0.0),
            material: fixture::lambert(rho),
        }]);
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let (ray, hit) = fixture::hit(&geometry, Vec3::new(0.0, 0.0, 1.0), -Vec3::Z);
        let v = Vertex::new(&ctx, &ray, &hit);
        let bsdf = v.bsdf().unwrap();
        let mut scratch = Vec::new();
        let from_above = Vec3::new(0.6, 0.0, 0.8);
        // k = 9: the 8 nearest summed over π·r₉² (r₉ = 1), each reflecting f = ρ/π.
        let l = reflected(&map(rings(from_above), 9, 10.0), &v, &bsdf, &mut scratch);
        let expected = 8.0 * 0.01 * rho / PI / PI;
        assert!(
            (l - Vec3::splat(expected)).abs().max_element() < 1e-5 * expected,
            "{l}"
        );
        // Fewer than k within r_max = 1.5: the 9 inside, over π·1.5².
        let l = reflected(&map(rings(from_above), 20, 1.5), &v, &bsdf, &mut scratch);
        let expected = 9.0 * 0.01 * rho / PI / (PI * 2.25);
        assert!(
            (l - Vec3::splat(expected)).abs().max_element() < 1e-5 * expected,
            "{l}"
        );
        // Light arriving from below the surface reflects nothing.
        let l = reflected(&map(rings(-from_above), 9, 10.0), &v, &bsdf, &mut scratch);
        assert_eq!(l, Vec3::ZERO);
    }

    #[test]
    fn photon_maps_add_the_caustic_estimate_and_draw_nothing_without_a_global_map() {
        let geometry = fixture::geometry(vec![Object {
            triangles: fixture::floor(10.0, 0.0),
            material: fixture::lambert(0.5),
        }]);
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        let (ray, hit) = fixture::hit(&geometry, Vec3::new(0.0, 0.0, 1.0), -Vec3::Z);
        let v = Vertex::new(&ctx, &ray, &hit);
        let bsdf = v.bsdf().unwrap();
        let caustics = map(rings(Vec3::Z), 9, 10.0);
        let expected = reflected(&caustics, &v, &bsdf, &mut Vec::new());
        let maps = PhotonMaps {
            caustics: Some(caustics),
            global: None,
            gather_caustics: None,
            gather_irradiance: None,
        };
        let mut sampler = Sampler::new(4, 0);
        assert_eq!(maps.radiance(&ctx, &v, &bsdf, &mut sampler), expected);
        assert!(expected.x > 0.0);
        assert_eq!(sampler.next_1d(), Sampler::new(4, 0).next_1d());
        let none = PhotonMaps::default();
        assert_eq!(none.radiance(&ctx, &v, &bsdf, &mut sampler), Vec3::ZERO);
    }

    #[test]
    fn final_gather_reads_the_global_map_where_its_rays_land() {
        ceiling_over_a_lit_floor(false);
    }

    #[test]
    fn final_gather_reads_the_precomputed_irradiance_where_its_rays_land() {
        ceiling_over_a_lit_floor(true);
    }

    fn ceiling_over_a_lit_floor(precompute: bool) {
        // Seen from a grey ceiling (ρc, facing down, 1 above a floor covered by photons of
        // uniform irradiance E): the floor reflects ρf·E/π everywhere within the photons'
        // square, so the ceiling reflects ρc·ρf·E/π times the cosine-weighted fraction of
        // rays that land inside [−20, 20]² (> 0.998); rays that escape add nothing.
        let (rho_c, rho_f) = (0.5, 0.8);
        let geometry = fixture::geometry(vec![
            Object {
                triangles: fixture::floor(30.0, 0.0),
                material: fixture::lambert(rho_f),
            },
            Object {
                triangles: fixture::quad(
                    Vec3::new(-30.0, -30.0, 1.0),
                    Vec3::new(0.0, 60.0, 0.0),
                    Vec3::new(60.0, 0.0, 0.0),
                ),
                material: fixture::lambert(rho_c),
            },
        ]);
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &s);
        // A 401 × 401 grid of spacing 0.1 on [−20, 20]²: E = Φ / 0.01.
        let power = 1e-4;
        let photons: Vec<Photon> = (0..401 * 401)
            .map(|i| {
                let (x, y) = ((i % 401) as f32 * 0.1 - 20.0, (i / 401) as f32 * 0.1 - 20.0);
                photon(x, y, power, Vec3::Z)
            })
            .collect();
        let global = GatherMap {
            final_gather: 256,
            ..map(photons, 64, 1.0)
        };
        let gather_irradiance = precompute.then(|| {
            IrradiancePoints::new(IrradianceMaps {
                global: &global,
                caustics: None,
            })
        });
        let maps = PhotonMaps {
            caustics: None,
            global: Some(global),
            gather_caustics: None,
            gather_irradiance,
        };
        let (ray, hit) = fixture::hit(&geometry, Vec3::new(0.05, 0.0, 0.5), Vec3::Z);
        let v = Vertex::new(&ctx, &ray, &hit);
        let bsdf = v.bsdf().unwrap();
        let l = maps.radiance(&ctx, &v, &bsdf, &mut Sampler::new(2, 0));
        let expected = rho_c * rho_f * (power / 0.01) / PI;
        println!("final gather (precompute {precompute}): {l} (expected {expected})");
        assert!((l.x / expected - 1.0).abs() < 0.05, "{l} vs {expected}");
    }
}
