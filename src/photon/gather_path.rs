//! Where a final-gather ray lands: the first surface with a non-delta lobe along it, after
//! any chain of purely specular surfaces (mirrors, glass) it meets on the way — the `S*` of
//! `L … D S* D E` paths. At each purely specular surface one delta branch is sampled (glass:
//! reflection or refraction by Fresnel), its weight carried in the throughput.

use std::borrow::Cow;

use glam::Vec3;

use crate::accel::Ray;
use crate::sampling::Sampler;
use crate::shading::bsdf::{Bsdf, Scatter};
use crate::shading::integrator::{ShadeContext, Vertex};

/// Most purely specular surfaces a final-gather ray passes before it gives up (a glass ball
/// needs 2; total internal reflection a few more).
pub const MAX_SPECULAR_BOUNCES: u32 = 8;

/// A final-gather ray's landing point.
pub struct Landing<'a> {
    /// The surface it lands on (some lobe is not a delta).
    pub vertex: Vertex<'a>,
    /// Its BSDF: the material's kept one where the context keeps them and no texture drives
    /// the point's shader, else built for the point.
    pub bsdf: Cow<'a, Bsdf>,
    /// Weight of the specular chain before it, segment transmittances included.
    pub throughput: Vec3,
}

/// Follows `ray` through purely specular surfaces (delta branches sampled from `sampler`) to
/// the first surface that has a non-delta lobe; `None` when it leaves the scene, meets an
/// invisible face or a surface without a BSDF, or exceeds [`MAX_SPECULAR_BOUNCES`].
/// Inlined into its caller, the final gather: returned through memory, the landing (a
/// `Vertex` and a BSDF-sized `Cow`) was copied on its way.
#[inline(always)]
pub fn land<'a>(ctx: &ShadeContext<'a>, ray: Ray, sampler: &mut Sampler) -> Option<Landing<'a>> {
    let mut ray = ray;
    let mut throughput = Vec3::ONE;
    for _ in 0..=MAX_SPECULAR_BOUNCES {
        let hit = ctx
            .geometry
            .accel
            .intersect_as(&ray, crate::accel::RayKind::Secondary)?;
        let vertex = Vertex::new(ctx, &ray, &hit);
        if !vertex.visible {
            return None;
        }
        // As `Vertex::bsdf_ref`, but owned by the landing when built.
        let bsdf = match vertex.kept_bsdf(ctx) {
            Some(kept) => Cow::Borrowed(kept),
            None => Cow::Owned(vertex.bsdf().unwrap_or_else(Bsdf::empty)),
        };
        if !bsdf.reflects() {
            return None;
        }
        throughput *= vertex.transmittance;
        if bsdf.has_non_delta() {
            return Some(Landing {
                vertex,
                bsdf,
                throughput,
            });
        }
        let u = Vec3::new(sampler.next_1d(), sampler.next_1d(), sampler.next_1d());
        let s = bsdf.sample(vertex.wo, u)?;
        throughput *= s.weight();
        if !throughput.is_finite() || throughput.max_element() <= 0.0 {
            return None;
        }
        ray = vertex.spawn(s.wi, s.scatter == Scatter::Transmission)?;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::RenderSettings;
    use crate::shading::integrator::fixture;
    use crate::shading::integrator::material_bsdfs::MaterialBsdfs;
    use crate::shading::lights::LightSet;

    /// Landings read through the kept BSDFs are the built ones: the same surfaces (a grey
    /// room, a black panel that reflects nothing, a bumped panel whose BSDF is built, reached
    /// directly and through a glass floor), the same BSDFs, weights and draws.
    #[test]
    fn landings_through_kept_bsdfs_are_the_built_ones() {
        let mut g =
            fixture::room_with_panels(Vec3::ONE, [fixture::lambert(0.0), fixture::lambert(0.4)]);
        g.instances[3].bump = Some(fixture::sine_bump());
        let lights = LightSet::default();
        let s = RenderSettings::default();
        let bsdfs = MaterialBsdfs::new(&g);
        let built = ShadeContext::new(&g, &lights, &s);
        let kept = ShadeContext::new(&g, &lights, &s).with_bsdfs(Some(&bsdfs));
        let (mut borrowed, mut owned, mut none) = (0, 0, 0);
        for i in 0..3000 {
            let a = i as f32 * 0.37;
            let ray = Ray {
                origin: [Vec3::new(0.1, -0.2, 0.3), Vec3::new(-0.2, 0.3, -0.6)][i % 2],
                dir: Vec3::new(a.cos(), a.sin(), (i as f32 * 0.11).sin()),
                t_max: f32::INFINITY,
            };
            let (mut s_built, mut s_kept) = (Sampler::new(i as u32, 0), Sampler::new(i as u32, 0));
            let want = land(&built, ray, &mut s_built);
            let got = land(&kept, ray, &mut s_kept);
            assert_eq!(s_built.next_1d(), s_kept.next_1d(), "ray {i}: the draws");
            match (got, want) {
                (Some(got), Some(want)) => {
                    assert_eq!(*got.bsdf, *want.bsdf, "ray {i}");
                    assert_eq!(got.vertex.sp.prim, want.vertex.sp.prim, "ray {i}");
                    assert_eq!(
                        got.throughput.to_array().map(f32::to_bits),
                        want.throughput.to_array().map(f32::to_bits),
                        "ray {i}"
                    );
                    match got.bsdf {
                        Cow::Borrowed(_) => borrowed += 1,
                        Cow::Owned(_) => owned += 1,
                    }
                }
                (None, None) => none += 1,
                _ => panic!("ray {i}: a landing on one side only"),
            }
        }
        println!("{borrowed} kept, {owned} built, {none} none");
        assert!(
            borrowed > 500 && owned > 50 && none > 50,
            "{borrowed} {owned} {none}"
        );
    }
}
