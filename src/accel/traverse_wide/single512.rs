//! The AVX-512 single-ray kernels (x86-64 with AVX-512F and VL, picked at run time by
//! `traverse_wide.rs`): the single-ray closest-hit and occlusion loops of `traverse.rs` with
//! the block node step of `block.rs` ([`NodeRay8k`] packing with `vpcompressq`), which
//! stores the hit children as one block instead of pushing them in a loop over the hit mask
//! (A/B in `docs/ray-layer.md`, session 19). On AVX2 alone the single-ray kernels keep the
//! loop: the same step with the `vpermd` table measured 0.91–0.98× there (session 23).
//! * **Same answers**: the node test is `NodeRay8`'s, the leaf test `leaf_wide.rs`'s, so the
//!   children visited, their order, and the results are those of the AVX2 and SSE kernels bit
//!   for bit (`single_avx512_equals_avx2_and_sse` below).

use super::super::bvh::Bvh;
use super::super::traverse::{closest_in, occluded_in};
use super::super::{Hit, Ray};
use super::block::NodeRay8k;
use super::pack::Avx512Pack;

/// Closest hit with the AVX-512 node step (in octant order, unless sorted: `traverse.rs`).
///
/// # Safety
/// The CPU must support AVX2, AVX-512F, AVX-512VL and the bit operations of
/// [`super::have_bit_ops`].
#[target_feature(enable = "avx2,avx512f,avx512vl,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn closest_avx512(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
    closest_in::<NodeRay8k<Avx512Pack>>(bvh, ray)
}

/// Occlusion with the AVX-512 node step (in octant order, unless sorted).
///
/// # Safety
/// The CPU must support AVX2, AVX-512F, AVX-512VL and the bit operations of
/// [`super::have_bit_ops`].
#[target_feature(enable = "avx2,avx512f,avx512vl,popcnt,bmi1,bmi2,lzcnt")]
pub(super) unsafe fn occluded_avx512(bvh: &Bvh, ray: &Ray) -> bool {
    occluded_in::<NodeRay8k<Avx512Pack>>(bvh, ray)
}

#[cfg(test)]
mod tests {
    use super::super::super::bvh::build;
    use super::super::super::bvh::Node;
    use super::super::super::traverse::tests::{soup_and_nested, test_rays};
    use super::super::super::traverse::NodeTest;
    use super::super::super::traverse::{closest_ordered_in, BatchStack, NodeRay};
    use super::super::super::triangle::WoopRay;
    use super::super::tests::soup_and_rays;
    use super::super::NodeRay8;
    use super::*;
    use crate::settings::BvhQuality;
    use glam::Vec3;

    fn hit_bits(h: Option<Hit>) -> Option<[u32; 4]> {
        h.map(|h| [h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()])
    }

    fn have_avx512() -> bool {
        std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512vl")
            && super::super::have_bit_ops()
    }

    #[target_feature(enable = "avx2")]
    unsafe fn avx2(bvh: &Bvh, ray: &Ray) -> (Option<Hit>, bool) {
        (
            closest_ordered_in::<NodeRay8, true>(bvh, ray),
            occluded_in::<NodeRay8>(bvh, ray),
        )
    }

    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    unsafe fn avx512_sorted(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
        closest_ordered_in::<NodeRay8k<Avx512Pack>, false>(bvh, ray)
    }

    /// The AVX-512 single-ray kernels (when this CPU has AVX-512F/VL) give the AVX2 and SSE
    /// kernels' answers bit for bit (closest hit: t, prim, b1, b2; occlusion), on the traverse
    /// tests' soup and nested hierarchy (deeper than the array stack: the heap stack's block
    /// stores) with their rays, and on the wide tests' soup with axis-parallel, zero-component,
    /// on-plane and finite-`t_max` rays, for both BVH qualities.
    #[test]
    fn single_avx512_equals_avx2_and_sse() {
        if !have_avx512() {
            eprintln!("no AVX-512F/VL on this CPU: the AVX2 and SSE kernels run");
            return;
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x3c6e_f372_fe94_f82bu64);
        let [soup, nested] = soup_and_nested(&mut rnd);
        let mut rays = test_rays(&mut rnd, 3000);
        rays[5].dir = Vec3::ZERO;
        rays[17].origin.x = f32::NAN;
        rays[40].t_max = -1.0;
        let (wide_soup, wide_rays) = soup_and_rays();
        let (mut hits, mut occluded) = (0, 0);
        for (tris, rays) in [(soup, &rays), (nested, &rays), (wide_soup, &wide_rays)] {
            for q in [BvhQuality::Fast, BvhQuality::Medium] {
                let bvh = build(&tris, q);
                for (i, r) in rays.iter().enumerate() {
                    let sse = (
                        hit_bits(closest_ordered_in::<NodeRay, true>(&bvh, r)),
                        occluded_in::<NodeRay>(&bvh, r),
                    );
                    // SAFETY: AVX2, AVX-512F/VL and the bit operations were detected above.
                    let (a2, a2_occ) = unsafe { avx2(&bvh, r) };
                    assert_eq!((hit_bits(a2), a2_occ), sse, "ray {i}");
                    // SAFETY: as above.
                    let got = unsafe {
                        [
                            (closest_avx512(&bvh, r), occluded_avx512(&bvh, r)),
                            (avx512_sorted(&bvh, r), sse.1),
                        ]
                    };
                    for (hit, occ) in got {
                        assert_eq!((hit_bits(hit), occ), sse, "ray {i}");
                    }
                    hits += usize::from(sse.0.is_some());
                    occluded += usize::from(sse.1);
                }
            }
        }
        assert!(hits > 3000 && occluded > 3000, "{hits} {occluded}");
    }

    /// A node step's outcome: the child to visit next, and the stack's entries as
    /// `(reference, entry-distance bits)` from the bottom up.
    type Step = (Option<u32>, Vec<(u32, u32)>);

    /// The entries the block step and the generic step (the AVX2 node test, a loop) put on a
    /// stack that already holds three, as `(reference, entry-distance bits)` from the bottom
    /// up, with the child each returns to visit next.
    #[target_feature(enable = "avx2,avx512f,avx512vl")]
    unsafe fn steps(bvh: &Bvh, node: &Node, ray: &Ray, t_far: f32, order: u32) -> [Step; 2] {
        let woop = WoopRay::new(ray.origin, ray.dir);
        let block = <NodeRay8k<Avx512Pack> as NodeTest>::new(ray, &woop);
        let generic = <NodeRay8 as NodeTest>::new(ray, &woop);
        let mut stacks = [3, 3].map(BatchStack::with_entries);
        let next = [
            block.visit_ordered(bvh, node, t_far, order, &mut stacks[0]),
            generic.visit_ordered(bvh, node, t_far, order, &mut stacks[1]),
        ];
        let [a, b] = stacks.map(|s| s.entries().iter().map(|e| (e.r, e.t.to_bits())).collect());
        [(next[0], a), (next[1], b)]
    }

    /// The block node step pushes exactly the entries (references and entry-distance bits,
    /// same order) that the generic loop pushes, and returns the same child to visit next, for
    /// every node of a tree, every octant's order and two `t_far`.
    #[test]
    fn block_step_equals_generic_step() {
        if !have_avx512() {
            eprintln!("no AVX-512F/VL on this CPU: the AVX2 and SSE kernels run");
            return;
        }
        let (tris, rays) = soup_and_rays();
        let bvh = build(&tris, BvhQuality::Medium);
        let (mut pushed, mut visited) = (0, 0);
        for r in rays.iter().step_by(29) {
            for node in &bvh.nodes {
                for t_far in [r.t_max, 1.0] {
                    for &order in &node.order {
                        // SAFETY: AVX2 and AVX-512F/VL were detected above.
                        let [block, generic] = unsafe { steps(&bvh, node, r, t_far, order) };
                        assert_eq!(block, generic, "{r:?}");
                        pushed += block.1.len() - 3;
                        visited += usize::from(block.0.is_some());
                    }
                }
            }
        }
        assert!(pushed > 1000 && visited > 1000, "{pushed} {visited}");
    }
}
