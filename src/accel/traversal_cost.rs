//! What one closest-hit query costs the hierarchy, for the BVH diagnostic view (mental ray
//! `diagnostic bsp depth|size`; see [`crate::diagnostic_view`]): the nodes it tests, the
//! triangles it tests and the deepest level it enters.
//!
//! The walk is the SSE closest-hit kernel's (`traverse.rs`: the same slab test, children in
//! the ray's octant order, the same culling against the closest hit so far), written once more
//! with a level kept beside each stack entry, so the hot kernels carry no counters. It finds
//! the same hit as [`super::Accel::intersect`]; a test holds it to that.

use super::bvh::{Bvh, LEAF_BIT};
use super::traverse::{leaf_range, octant, NodeRay, NodeTest, FAR_SCALE_FACTOR as FAR_SCALE};
use super::triangle::{ray_is_valid, WoopRay};
use super::{Hit, Ray};

/// The work of one closest-hit query.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TraversalCost {
    /// Inner nodes whose children were tested (the root counts once the ray is valid).
    pub nodes: u32,
    /// Triangles tested in the leaves entered.
    pub triangles: u32,
    /// The deepest level entered, the root being level 0 and a child one level below its
    /// parent (leaves included): 0 when the ray enters no child of the root, at most the
    /// tree's depth (its number of inner-node levels, `AccelStats::depth`).
    pub deepest: u32,
}

/// The closest hit of `ray` (as the kernels find it) and what finding it cost.
pub(crate) fn closest_with_cost(bvh: &Bvh, ray: &Ray) -> (Option<Hit>, TraversalCost) {
    let mut cost = TraversalCost::default();
    if bvh.nodes.is_empty() || !ray_is_valid(ray) {
        return (None, cost);
    }
    let woop = WoopRay::new(ray.origin, ray.dir);
    let nr = NodeRay::new(ray);
    let octant = octant(ray);
    let mut best: Option<(usize, f32, f32)> = None;
    let mut best_t = ray.t_max;
    let mut cull = best_t * FAR_SCALE;
    // (reference, entry distance, level); the root is entered unconditionally, as the kernels do.
    let mut stack: Vec<(u32, f32, u32)> = vec![(0, 0.0, 0)];
    while let Some((cur, t, level)) = stack.pop() {
        if t > cull {
            continue;
        }
        cost.deepest = cost.deepest.max(level);
        if cur & LEAF_BIT != 0 {
            for k in leaf_range(cur) {
                cost.triangles += 1;
                if let Some((t, b1, b2)) = woop.intersect(&bvh.tris[k].v) {
                    let better = t < best_t
                        || (t == best_t
                            && best.is_some_and(|(bk, _, _)| bvh.tris[k].prim < bvh.tris[bk].prim));
                    if better {
                        best = Some((k, b1, b2));
                        best_t = t;
                        cull = t * FAR_SCALE;
                    }
                }
            }
            continue;
        }
        cost.nodes += 1;
        let node = &bvh.nodes[cur as usize];
        let (mut mask, tn, child) = nr.intersect_ordered(node, best_t, node.order[octant]);
        // Farthest pushed first, so the nearest (in octant order) is entered next.
        while mask != 0 {
            let i = 31 - mask.leading_zeros() as usize;
            mask ^= 1 << i;
            stack.push((child[i], tn[i], level + 1));
        }
    }
    let hit = best.map(|(k, b1, b2)| Hit {
        t: best_t,
        prim: bvh.tris[k].prim,
        b1,
        b2,
    });
    (hit, cost)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::accel::Accel;
    use crate::settings::BvhQuality;

    /// A deterministic stream in [0, 1).
    fn uniform(state: &mut u64) -> f32 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 40) as f32 / (1u64 << 24) as f32
    }

    fn soup(n: usize, seed: u64) -> Vec<[Vec3; 3]> {
        let mut s = seed;
        let p = |s: &mut u64| Vec3::new(uniform(s), uniform(s), uniform(s)) * 10.0;
        (0..n)
            .map(|_| {
                let c = p(&mut s);
                let e = |s: &mut u64| (Vec3::new(uniform(s), uniform(s), uniform(s)) - 0.5) * 0.8;
                [c, c + e(&mut s), c + e(&mut s)]
            })
            .collect()
    }

    #[test]
    fn the_walk_finds_the_kernels_hit_and_stays_within_the_tree() {
        let accel = Accel::build(soup(5000, 7), BvhQuality::Medium);
        let depth = accel.stats().depth;
        let mut s = 99u64;
        let (mut hits, mut reached_bottom) = (0, false);
        for _ in 0..4000 {
            let o = Vec3::new(uniform(&mut s), uniform(&mut s), uniform(&mut s)) * 14.0 - 2.0;
            let d = Vec3::new(uniform(&mut s), uniform(&mut s), uniform(&mut s)) - 0.5;
            let ray = Ray {
                origin: o,
                dir: d,
                t_max: f32::INFINITY,
            };
            let (hit, cost) = accel.intersect_with_cost(&ray);
            assert_eq!(hit, accel.intersect(&ray), "ray {ray:?}");
            assert!(cost.deepest <= depth, "{cost:?} deeper than {depth}");
            assert!(cost.nodes >= 1);
            if hit.is_some() {
                hits += 1;
                assert!(cost.triangles >= 1 && cost.deepest >= 1, "{cost:?}");
            }
            reached_bottom |= cost.deepest == depth;
        }
        assert!(hits > 500, "{hits} hits");
        assert!(reached_bottom, "no ray reached level {depth}");
    }

    #[test]
    fn a_ray_that_misses_every_box_enters_nothing() {
        let accel = Accel::build(soup(200, 3), BvhQuality::Medium);
        let away = Ray {
            origin: Vec3::new(50.0, 50.0, 50.0),
            dir: Vec3::X,
            t_max: f32::INFINITY,
        };
        assert_eq!(
            accel.intersect_with_cost(&away),
            (
                None,
                TraversalCost {
                    nodes: 1,
                    triangles: 0,
                    deepest: 0
                }
            )
        );
        let empty = Accel::build(Vec::new(), BvhQuality::Medium);
        assert_eq!(
            empty.intersect_with_cost(&away),
            (None, TraversalCost::default())
        );
    }
}
