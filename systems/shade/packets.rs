//! A pixel's camera samples traced as common-origin packets: a pinhole's rays all leave the
//! camera's origin, and a pixel's samples cross one small patch of the scene, so the tree's
//! packet kernel ([`crate::accel::Accel::intersect_shared_origin_as`]) answers them for
//! about 0.6 of the per-ray cost at 16 samples (session 30, `docs/ray-layer.md`). Each
//! sample draws what the per-sample loop draws, in the same order, and gets the same hit bit
//! for bit, so the pixel's value is the same.

use glam::{DVec3, Vec2, Vec3};

use super::PixelShader;
use crate::accel::{Hit, Ray, RayKind};
use crate::adaptive::PixelSamples;
use crate::exact_sum::ExactSum;
use crate::sampling::Sampler;
use crate::shading::integrator::camera_hit_with;
use crate::shading::ShadeContext;

/// Samples traced in one call (the packet kernel's packet size).
const CHUNK: usize = 64;

impl PixelShader<'_> {
    /// [`PixelShader::take`] for a camera without a lens sample: samples `first..first +
    /// count` of `pixel` (centre `centre`), their rays traced [`CHUNK`] at a time.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn take_in_packets(
        &self,
        ctx: &ShadeContext<'_>,
        samples: &mut PixelSamples,
        mut sums: Option<&mut [DVec3; 6]>,
        mut missed: Option<&mut [ExactSum; 3]>,
        pixel: u64,
        centre: Vec2,
        first: u32,
        count: u32,
    ) {
        let unused = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::Z,
            t_max: 0.0,
        };
        let mut samplers: [Option<Sampler>; CHUNK] = [const { None }; CHUNK];
        let mut rays = [unused; CHUNK];
        let mut hits: [Option<Hit>; CHUNK] = [None; CHUNK];
        // Per sample of the chunk, its ray's place in `rays` (`usize::MAX`: no ray).
        let mut slot = [usize::MAX; CHUNK];
        let end = first + count;
        let mut start = first;
        while start < end {
            if self.cancel.load(std::sync::atomic::Ordering::Relaxed) {
                return;
            }
            let n = (end - start).min(CHUNK as u32) as usize;
            let mut traced = 0;
            for k in 0..n {
                let mut sampler = Sampler::for_item_primed(self.seed, pixel, start + k as u32);
                let film = centre + self.filter.sample(sampler.next_2d());
                slot[k] = usize::MAX;
                if let Some(ray) = self.rays.ray(film.x, film.y, Vec2::splat(0.5)) {
                    rays[traced] = ray;
                    slot[k] = traced;
                    traced += 1;
                }
                samplers[k] = Some(sampler);
            }
            ctx.geometry.accel.intersect_shared_origin_as(
                &rays[..traced],
                RayKind::Camera,
                &mut hits[..traced],
            );
            for k in 0..n {
                let Some(mut sampler) = samplers[k].take() else {
                    continue;
                };
                let hit = (slot[k] != usize::MAX).then(|| {
                    let ray = rays[slot[k]];
                    (ray, camera_hit_with(ctx, &ray, hits[slot[k]]))
                });
                let sums = sums.as_deref_mut();
                self.add_sample(ctx, hit, &mut sampler, samples, sums, missed.as_deref_mut());
            }
            start += n as u32;
        }
    }
}
