//! One light's samples at a shading point with their shadow rays traced together: the light
//! loop of [`super::gather_with`] for a light sampled `n` times from its own sequences (the
//! `Direct` integrator's area lights, `samples: 8` and more), where the shadow rays all leave
//! from the point's one offset origin. The samples are drawn first, their rays answered by
//! the common-origin packet kernel ([`crate::accel::Accel::occluded_shared_origin_as`]),
//! then summed in sample order with the per-sample loop's arithmetic: the same sums, bit for
//! bit (`tests::packets_give_the_per_sample_sums_bit_for_bit`).
//!
//! Taken only where the plain any-hit answer is the shadow (no fog, no transmissive
//! shadows), the geometry packs rays ([`crate::accel::Accel::packs_shared_origin`]: a tree,
//! no ray masks, at least eight rays) and the tree is large enough for packets to pay
//! ([`PACKET_MIN_TRIANGLES`]); otherwise the loop traces one ray per sample.

use std::sync::OnceLock;

use glam::Vec3;

use super::{ShadeContext, Share, Vertex};
use crate::accel::{Ray, RayKind, PACKET_MIN_RAYS};
use crate::geometry::SceneGeometry;
use crate::sampling::Sampler;
use crate::shading::lights::{Light, LightSample, LightSet};
use crate::shading::shadow::shadow_ray;
use crate::shading::volume::Volumes;

/// Samples drawn, and rays traced, per round: light sample counts are 8–16 where the
/// packets pay; a round of 64 spent more on filling its arrays than it saved.
const ROUND: usize = 16;

/// The fewest triangles for which the packets pay: a smaller tree stays in the first cache
/// levels, where one query per ray is as fast and the two passes cost more than they save
/// (measured, `Direct` integrator, 1 thread: 1,924 triangles 0.92× with the packets forced,
/// 18,052 1.09–1.10×, 55,494 1.15×; `docs/ray-layer.md`, session 32).
const PACKET_MIN_TRIANGLES: usize = 8192;

/// Whether the light loop without MIS takes [`gather`] for `geometry` lit by `lights`
/// through `volumes`: where the packets give the per-sample answers (no fog, no transmissive
/// shadows, the tree without ray masks) and pay (at least [`PACKET_MIN_TRIANGLES`], some
/// light sampled often enough for a packet). The environment variable
/// `STAGELIGHT_SHADOW_PACKETS` (`on` or `off`, read once) overrides whether they pay, for A/B
/// runs: `on` takes them wherever they give the same answers.
pub(super) fn pays(geometry: &SceneGeometry, lights: &LightSet, volumes: Option<&Volumes>) -> bool {
    static FORCED: OnceLock<Option<bool>> = OnceLock::new();
    let forced =
        FORCED.get_or_init(
            || match std::env::var("STAGELIGHT_SHADOW_PACKETS").as_deref() {
                Ok("on") => Some(true),
                Ok("off") => Some(false),
                _ => None,
            },
        );
    let exact = volumes.is_none()
        && !lights.transmissive_shadows
        && geometry.accel.packs_shared_origin(PACKET_MIN_RAYS);
    exact
        && forced.unwrap_or_else(|| {
            geometry.accel.len() >= PACKET_MIN_TRIANGLES
                && lights
                    .lights
                    .iter()
                    .any(|l| l.sample_count() as usize >= PACKET_MIN_RAYS)
        })
}

/// The light loop of `gather_with` without MIS (every light sampled its own number of
/// times from a child sequence of `sampler`), each light's shadow rays traced together:
/// the same radiance and share, bit for bit, as the per-sample loop. Out of line, so that
/// the per-sample loop's function stays as it was (inlined, it slowed that loop 5 %).
#[inline(never)]
pub(super) fn gather(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    sampler: &mut Sampler,
    response: &impl Fn(Vec3, Vec3) -> Vec3,
    cosine: bool,
    mut share: Option<Share<'_, '_>>,
) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    for (i, light) in ctx.lights.lights.iter().enumerate() {
        if matches!(light, Light::Ambient { .. }) || !v.material.sees_light(i) {
            continue;
        }
        let n = light.sample_count();
        let seed = sampler.child_seed();
        let (sum, shared) =
            light_samples_in_packets(ctx, v, light, n, seed, response, cosine, share.as_ref());
        radiance += sum / n as f32;
        if let Some((_, target)) = &mut share {
            **target += shared / n as f32;
        }
    }
    radiance
}

/// What the sum needs of a sample that passed the loop's tests before its shadow ray: its
/// contribution, world and local directions, the response there, the light's shadow factor,
/// and whether it has a shadow ray (the next one of the round, in sample order).
#[derive(Clone, Copy, Default)]
struct Drawn {
    contribution: Vec3,
    wi_world: Vec3,
    wi: Vec3,
    f: Vec3,
    shadow_factor: f32,
    traced: bool,
}

/// The sum over `n` samples of `light` at `v` (sample `j` from `Sampler::new(seed, j)`) of
/// `response · contribution · shadow · c` (`c` = `wi.z` when `cosine`, else 1), and of the
/// `share` response the same way: what the per-sample loop of `gather_with` adds up for
/// this light without MIS, in the same order, with the shadow rays traced in packets.
#[allow(clippy::too_many_arguments)] // The loop's own inputs, passed through.
fn light_samples_in_packets(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    light: &Light,
    n: u32,
    seed: u32,
    response: &impl Fn(Vec3, Vec3) -> Vec3,
    cosine: bool,
    share: Option<&Share<'_, '_>>,
) -> (Vec3, Vec3) {
    let mut sum = Vec3::ZERO;
    let mut shared = Vec3::ZERO;
    // The per-sample loop's sum step without MIS (weight 1), in its product order.
    let mut add = |d: &Drawn, blocked: bool| {
        let shadow = if d.traced {
            LightSample::lighten_by(
                d.shadow_factor,
                if blocked { Vec3::ZERO } else { Vec3::ONE },
            )
        } else {
            Vec3::ONE
        };
        if shadow == Vec3::ZERO {
            return;
        }
        let w = 1.0;
        let c = if cosine { d.wi.z * w } else { w };
        sum += d.f * d.contribution * shadow * c;
        if let Some((g, _)) = share {
            shared += g(d.wi, d.wi_world) * d.contribution * shadow * c;
        }
    };
    if (n as usize) < PACKET_MIN_RAYS {
        // Too few rays for a packet (point lights, few samples): one query per sample.
        for j in 0..n {
            if let Some((d, ray)) = draw(ctx, v, light, seed, j, response) {
                let blocked =
                    ray.is_some_and(|r| ctx.geometry.accel.occluded_as(&r, RayKind::Shadow));
                add(&d, blocked);
            }
        }
        return (sum, shared);
    }
    let mut drawn = [Drawn::default(); ROUND];
    let mut rays = [Ray {
        origin: Vec3::ZERO,
        dir: Vec3::ZERO,
        t_max: 0.0,
    }; ROUND];
    let mut occluded = [false; ROUND];
    for first in (0..n).step_by(ROUND) {
        let count = (n - first).min(ROUND as u32);
        let (mut kept, mut traced) = (0, 0);
        for j in first..first + count {
            let Some((d, ray)) = draw(ctx, v, light, seed, j, response) else {
                continue;
            };
            if let Some(r) = ray {
                rays[traced] = r;
                traced += 1;
            }
            drawn[kept] = d;
            kept += 1;
        }
        ctx.geometry.accel.occluded_shared_origin_as(
            &rays[..traced],
            RayKind::Shadow,
            &mut occluded[..traced],
        );
        let mut answers = occluded[..traced].iter();
        for d in &drawn[..kept] {
            let blocked = d.traced && answers.next().is_some_and(|&o| o);
            add(d, blocked);
        }
    }
    (sum, shared)
}

/// Sample `j` of `light` at `v` as the sum needs it, with its shadow ray (none when the
/// light casts no shadows); `None` where the per-sample loop skips it before its shadow ray
/// (no sample, below the horizon or the geometric surface, zero response).
#[inline(always)]
fn draw(
    ctx: &ShadeContext<'_>,
    v: &Vertex<'_>,
    light: &Light,
    seed: u32,
    j: u32,
    response: &impl Fn(Vec3, Vec3) -> Vec3,
) -> Option<(Drawn, Option<Ray>)> {
    let u = Sampler::new(seed, j).next_2d();
    // `Light::sample` for every kind (the per-sample loop calls a mesh light's sampler
    // directly; the same sample).
    let ls = light.sample(v.sp.surface.p, u, Some(ctx.geometry))?;
    let wi = v.frame.to_local(ls.wi);
    if wi.z <= 0.0 || v.ng.dot(ls.wi) <= 0.0 {
        return None;
    }
    let f = response(wi, ls.wi);
    if f == Vec3::ZERO {
        return None;
    }
    let ray = ls
        .shadows
        .then(|| shadow_ray(&v.sp.surface, ls.wi, ls.target.as_ref()));
    let d = Drawn {
        contribution: ls.contribution,
        wi_world: ls.wi,
        wi,
        f,
        shadow_factor: ls.shadow_factor,
        traced: ls.shadows,
    };
    Some((d, ray))
}

#[cfg(test)]
mod tests {
    use super::super::fixture::{self, Object};
    use super::super::{light_loop_in_packets, light_loop_split};
    use super::*;
    use crate::components::{Emitter, LightShape};
    use crate::settings::RenderSettings;

    /// Shading points on a floor under rectangular lights (8, 13, 40 and 3 samples: one
    /// round, a short last round, several rounds, too few for a packet; full shadows and a
    /// shadow factor), with a cloud of 9,000 small triangles between them casting partial
    /// shadows: the light loop with the packets gives the per-sample loop's radiance and
    /// diffuse share (`light_loop_split` without MIS), bit for bit, and draws the same
    /// sequences after it.
    #[test]
    fn packets_give_the_per_sample_sums_bit_for_bit() {
        let mut rnd = crate::accel::test_random::signed_uniform(0x5eed_1234_abcd_0001);
        let cloud: Vec<[Vec3; 3]> = (0..9000)
            .map(|_| {
                let c = Vec3::new(2.0 * rnd(), 2.0 * rnd(), 1.5 + 0.5 * rnd());
                [
                    c,
                    c + 0.08 * Vec3::new(rnd(), rnd(), rnd()),
                    c + 0.08 * Vec3::new(rnd(), rnd(), rnd()),
                ]
            })
            .collect();
        let geometry = fixture::geometry(vec![
            Object {
                triangles: fixture::floor(4.0, 0.0),
                material: fixture::lambert(0.6),
            },
            Object {
                triangles: cloud,
                material: fixture::lambert(0.3),
            },
        ]);
        let rect = |samples: u32, factor: f32| {
            let mut e = Emitter::new(
                LightShape::Rect {
                    corner: Vec3::new(-1.0, -1.0, 3.0),
                    edge_u: Vec3::new(0.0, 2.0, 0.0),
                    edge_v: Vec3::new(2.0, 0.0, 0.0),
                },
                Vec3::splat(5.0),
            );
            e.samples = samples;
            e.shadow_factor = factor;
            e
        };
        let lights = LightSet::new(
            &[rect(8, 0.0), rect(13, 0.25), rect(40, 0.0), rect(3, 0.0)],
            None,
            1,
        );
        let settings = RenderSettings::default();
        let ctx = ShadeContext::new(&geometry, &lights, &settings);
        assert!(ctx.shadow_packets, "the packets are taken");
        let (mut points, mut partly) = (0, 0);
        for k in 0..32u32 {
            let at = Vec3::new(rnd() * 1.5, rnd() * 1.5, 0.9);
            let (ray, hit) = fixture::hit(&geometry, at, -Vec3::Z);
            if hit.prim >= 2 {
                continue; // landed on the cloud, not the floor
            }
            let v = Vertex::new(&ctx, &ray, &hit);
            let bsdf = v.bsdf().expect("a Lambert floor");
            let (mut a, mut b) = (Sampler::new(77, k), Sampler::new(77, k));
            let (mut share_a, mut share_b) = (Vec3::ZERO, Vec3::ZERO);
            let want = light_loop_split(&ctx, &v, &bsdf, &mut a, false, Some(&mut share_a));
            let got = light_loop_in_packets(&ctx, &v, &bsdf, &mut b, Some(&mut share_b));
            let bits = |x: Vec3| x.to_array().map(f32::to_bits);
            assert_eq!(bits(got), bits(want), "point {at}");
            assert_eq!(bits(share_b), bits(share_a), "point {at}");
            assert_eq!(a.next_1d().to_bits(), b.next_1d().to_bits(), "point {at}");
            points += 1;
            // Partly shadowed: among the first light's sample rays some are blocked, some not.
            let response = |wi: Vec3, _: Vec3| bsdf.eval(v.wo, wi);
            let blocked: Vec<bool> = (0..8)
                .filter_map(|j| draw(&ctx, &v, &lights.lights[0], 5, j, &response))
                .filter_map(|(_, ray)| ray)
                .map(|r| ctx.geometry.accel.occluded(&r))
                .collect();
            partly += u32::from(blocked.contains(&true) && blocked.contains(&false));
        }
        assert!(points >= 20, "{points} floor points");
        assert!(partly >= 5, "only {partly} points partly in shadow");
    }
}
