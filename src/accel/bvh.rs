//! BVH construction: obvhs builds the binary hierarchy (PLOC, reinsertion), `collapse.rs`
//! collapses it in parallel into stagelight's own 8-wide node layout (the tree obvhs's CWBVH
//! collapse makes) with *exact* `f32` child boxes, and the triangles are copied into BVH order.
//!
//! Why convert: obvhs's CWBVH nodes store child boxes quantised to 8 bits, and its node test
//! clamps the entry distance to a hard-coded 1e-4 and ignores `tmin`; its traversal stack has
//! 32 fixed entries and silently overwrites the top when a degenerate hierarchy is deeper.
//! Our nodes hold the exact min/max of the child's triangles (so the pbrt-style conservative
//! slab test of `traverse.rs` is exact up to its own bounded rounding), and the traversal stack
//! is sized from the depth measured here.

use std::time::Instant;

use glam::{Vec3, Vec4};
use obvhs::{
    bvh2::{reinsertion::ReinsertionOptimizer, Bvh2},
    ploc::PlocBuilder,
    triangle::Triangle,
    BvhBuildParams,
};
use rayon::prelude::*;

use super::triangle::is_degenerate;
use crate::settings::BvhQuality;

mod collapse;

/// Child reference flag: the child is a leaf.
pub(crate) const LEAF_BIT: u32 = 1 << 31;
/// Leaf child references keep the triangle count (1..=3) in bits 29–30.
pub(crate) const COUNT_SHIFT: u32 = 29;
/// Leaf child references keep the first triangle (BVH order) in bits 0–28.
pub(crate) const FIRST_MASK: u32 = (1 << COUNT_SHIFT) - 1;
/// Reference of an empty child slot (its box is empty, so it is never entered).
pub(crate) const EMPTY_CHILD: u32 = u32::MAX;

/// An 8-wide node: one reference per child (node index, or leaf with `LEAF_BIT`), children
/// packed into the first slots, and the six bounding planes of every child in
/// structure-of-arrays form: `bounds[group][2·axis]` minima, `bounds[group][2·axis + 1]`
/// maxima, children 0–3 in group 0 and 4–7 in group 1. A node with at most four children is
/// tested from its first two cache lines only.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct Node {
    pub(crate) child: [u32; 8],
    pub(crate) bounds: [[Vec4; 6]; 2],
}

impl Node {
    pub(crate) const EMPTY: Node = Node {
        child: [EMPTY_CHILD; 8],
        bounds: [[
            Vec4::INFINITY,
            Vec4::NEG_INFINITY,
            Vec4::INFINITY,
            Vec4::NEG_INFINITY,
            Vec4::INFINITY,
            Vec4::NEG_INFINITY,
        ]; 2],
    };

    pub(crate) fn set_child(&mut self, slot: usize, reference: u32, lo: Vec3, hi: Vec3) {
        let (g, l) = (slot / 4, slot % 4);
        for axis in 0..3 {
            self.bounds[g][2 * axis][l] = lo[axis];
            self.bounds[g][2 * axis + 1][l] = hi[axis];
        }
        self.child[slot] = reference;
    }
}

/// The built hierarchy.
pub(crate) struct Bvh {
    /// Nodes; the root is node 0 (none when nothing can be hit).
    pub(crate) nodes: Vec<Node>,
    /// Triangles in BVH order (degenerate ones are left out).
    pub(crate) tris: Vec<[Vec3; 3]>,
    /// Original index of each triangle in BVH order.
    pub(crate) prim_ids: Vec<u32>,
    /// Number of node levels on the longest root-to-leaf path.
    pub(crate) depth: u32,
    /// SAH cost (`collapse::sah_cost`).
    pub(crate) sah_cost: f64,
    /// Wall-clock build time in seconds.
    pub(crate) build_seconds: f64,
}

/// obvhs build parameters for a quality level. Spatial pre-splits are turned off: they are
/// slow, and with them a triangle may appear in several leaves.
pub(crate) fn build_params(quality: BvhQuality) -> BvhBuildParams {
    let mut p = match quality {
        BvhQuality::Fast => BvhBuildParams::very_fast_build(),
        BvhQuality::Medium => BvhBuildParams::medium_build(),
        BvhQuality::High => BvhBuildParams::slow_build(),
    };
    p.pre_split = false;
    p
}

/// Builds the hierarchy over the non-degenerate triangles of `tris`.
pub(crate) fn build(tris: &[[Vec3; 3]], quality: BvhQuality) -> Bvh {
    let start = Instant::now();
    assert!(
        tris.len() <= FIRST_MASK as usize,
        "too many triangles for one BVH"
    );
    // Every pass goes wide: the gathers (order-preserving collects), PLOC and reinsertion
    // inside obvhs, and the collapse into 8-wide nodes (`collapse.rs`).
    let valid: Vec<u32> = (0..tris.len() as u32)
        .into_par_iter()
        .filter(|&i| !is_degenerate(&tris[i as usize]))
        .collect();
    if valid.is_empty() {
        return Bvh {
            nodes: Vec::new(),
            tris: Vec::new(),
            prim_ids: Vec::new(),
            depth: 0,
            sah_cost: 0.0,
            build_seconds: start.elapsed().as_secs_f64(),
        };
    }
    let ob_tris: Vec<Triangle> = valid
        .par_iter()
        .map(|&i| {
            let [v0, v1, v2] = tris[i as usize];
            Triangle {
                v0: v0.into(),
                v1: v1.into(),
                v2: v2.into(),
            }
        })
        .collect();
    let params = build_params(quality);
    let bvh2 = binary_hierarchy(&ob_tris, &params);
    drop(ob_tris);
    let collapsed = collapse::collapse(&bvh2, params.max_prims_per_leaf.clamp(1, 3), &|p| {
        tris[valid[p as usize] as usize]
    });
    drop(bvh2);
    let prim_ids: Vec<u32> = collapsed
        .order
        .par_iter()
        .map(|&i| valid[i as usize])
        .collect();
    let bvh_tris: Vec<[Vec3; 3]> = prim_ids.par_iter().map(|&i| tris[i as usize]).collect();
    let nodes = collapsed.nodes;
    let n = nodes.len();

    // Depth by a forward sweep (parents first).
    let mut level = vec![0u32; n];
    level[0] = 1;
    let mut depth = 1;
    for i in 0..n {
        for &c in &nodes[i].child {
            if c & LEAF_BIT == 0 {
                level[c as usize] = level[i] + 1;
                depth = depth.max(level[i] + 1);
            }
        }
    }

    let sah_cost = collapse::sah_cost(&nodes);
    Bvh {
        nodes,
        tris: bvh_tris,
        prim_ids,
        depth,
        sah_cost,
        build_seconds: start.elapsed().as_secs_f64(),
    }
}

/// obvhs's binary hierarchy (PLOC, then reinsertion), one triangle per leaf. The low-level
/// obvhs calls (not `build_cwbvh_from_tris`) skip its debug-build validation, which is slow
/// and would dominate debug-profile tests.
pub(crate) fn binary_hierarchy(ob_tris: &[Triangle], params: &BvhBuildParams) -> Bvh2 {
    let mut bvh2 = PlocBuilder::with_capacity(ob_tris.len()).build(
        params.ploc_search_distance,
        ob_tris,
        (0..ob_tris.len() as u32).collect(),
        params.sort_precision,
        params.search_depth_threshold,
    );
    ReinsertionOptimizer::default().run(&mut bvh2, params.reinsertion_batch_ratio, None);
    bvh2
}

#[cfg(test)]
mod tests {
    use super::*;

    fn soup(n: usize) -> Vec<[Vec3; 3]> {
        (0..n)
            .map(|i| {
                let f = i as f32;
                let c = Vec3::new((f * 0.37).sin(), (f * 0.11).cos(), (f * 0.05).sin()) * 10.0;
                [
                    c,
                    c + Vec3::new(0.3, 0.0, 0.1),
                    c + Vec3::new(0.0, 0.2, 0.3),
                ]
            })
            .collect()
    }

    #[test]
    fn every_valid_triangle_is_referenced_once_and_boxes_contain_children() {
        let mut tris = soup(500);
        tris[7] = [Vec3::ZERO; 3];
        for q in [BvhQuality::Fast, BvhQuality::Medium, BvhQuality::High] {
            let bvh = build(&tris, q);
            let mut seen = vec![0u32; tris.len()];
            for node in &bvh.nodes {
                for (slot, &c) in node.child.iter().enumerate() {
                    if c == EMPTY_CHILD || c & LEAF_BIT == 0 {
                        continue;
                    }
                    let first = (c & FIRST_MASK) as usize;
                    let count = ((c & !LEAF_BIT) >> COUNT_SHIFT) as usize;
                    for k in first..first + count {
                        seen[bvh.prim_ids[k] as usize] += 1;
                        for v in bvh.tris[k] {
                            for axis in 0..3 {
                                let (g, l) = (slot / 4, slot % 4);
                                assert!(node.bounds[g][2 * axis][l] <= v[axis]);
                                assert!(node.bounds[g][2 * axis + 1][l] >= v[axis]);
                            }
                        }
                    }
                }
            }
            assert_eq!(seen[7], 0);
            assert!(seen.iter().enumerate().all(|(i, &s)| i == 7 || s == 1));
            assert!(bvh.depth >= 2);
        }
    }

    #[test]
    fn tiny_and_empty_inputs() {
        assert!(build(&[], BvhQuality::Medium).nodes.is_empty());
        assert!(build(&[[Vec3::ZERO; 3]], BvhQuality::Medium)
            .nodes
            .is_empty());
        let one = build(&soup(1), BvhQuality::Medium);
        assert_eq!(one.tris.len(), 1);
        assert!(!one.nodes.is_empty());
    }
}
