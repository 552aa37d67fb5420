//! BVH construction: the binary hierarchy comes from our own parallel binned SAH
//! (`bvh/binned.rs`, the `Medium` preset) or from obvhs (PLOC + reinsertion: `Fast`, `High`);
//! `collapse.rs` collapses it in parallel into stagelight's own 8-wide node layout (the tree obvhs's CWBVH
//! collapse makes) with *exact* `f32` child boxes, and the triangles are copied into BVH order.
//! That copy is the only one the `Accel` keeps (the caller's vector is dropped): each copied
//! triangle carries its caller's index ([`LeafTri`], 40 bytes), and one index map back
//! (`slot_of`) answers lookups by the caller's index — 8 bytes per triangle instead of a
//! second 36-byte copy.
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
    ploc::{PlocBuilder, PlocSearchDistance},
    triangle::Triangle,
    BvhBuildParams,
};
use rayon::prelude::*;

use super::triangle::is_degenerate;
use crate::settings::BvhQuality;

mod binned;
mod collapse;
mod prepare;

/// Child reference flag: the child is a leaf.
pub(crate) const LEAF_BIT: u32 = 1 << 31;
/// Leaf child references keep the triangle count (1..=3) in bits 29–30.
pub(crate) const COUNT_SHIFT: u32 = 29;
/// Leaf child references keep the first triangle (BVH order) in bits 0–28.
pub(crate) const FIRST_MASK: u32 = (1 << COUNT_SHIFT) - 1;
/// Reference of an empty child slot (its box is empty, so it is never entered).
pub(crate) const EMPTY_CHILD: u32 = u32::MAX;

/// An 8-wide node (256 bytes, four cache lines): one reference per child (node index, or leaf
/// with `LEAF_BIT`), children packed into the first slots; the children's visiting order for
/// each ray octant (`order`, see [`Node::octant_orders`]); and the six bounding planes of
/// every child in structure-of-arrays form, plane-major: `bounds[2·axis][group]` minima,
/// `bounds[2·axis + 1][group]` maxima, children 0–3 in group 0 and 4–7 in group 1, so that
/// one plane of all eight children is 32 contiguous bytes (one 8-wide load; 32-byte aligned).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct Node {
    pub(crate) child: [u32; 8],
    /// `order[octant]`: the eight slots, nearest first for rays of that octant (bit `a` of
    /// the octant set when the direction's `a` component is negative), 3 bits each (`i`-th
    /// slot in bits `3i..3i + 3`); empty slots come last.
    pub(crate) order: [u32; 8],
    pub(crate) bounds: [[Vec4; 2]; 6],
}

impl Node {
    pub(crate) const EMPTY: Node = Node {
        child: [EMPTY_CHILD; 8],
        order: [IDENTITY_ORDER; 8],
        bounds: [
            [Vec4::INFINITY; 2],
            [Vec4::NEG_INFINITY; 2],
            [Vec4::INFINITY; 2],
            [Vec4::NEG_INFINITY; 2],
            [Vec4::INFINITY; 2],
            [Vec4::NEG_INFINITY; 2],
        ],
    };

    pub(crate) fn set_child(&mut self, slot: usize, reference: u32, lo: Vec3, hi: Vec3) {
        let (g, l) = (slot / 4, slot % 4);
        for axis in 0..3 {
            self.bounds[2 * axis][g][l] = lo[axis];
            self.bounds[2 * axis + 1][g][l] = hi[axis];
        }
        self.child[slot] = reference;
    }

    /// The visiting order of the children for each ray octant (Fuetterling et al. 2017, as
    /// tinybvh's `BVH8_CPU`): children sorted by the projection of their box centre on the
    /// octant's diagonal `(±1, ±1, ±1)`, ties by slot, empty slots last. Traversal pushes
    /// children in this order instead of sorting them by entry distance; the result does not
    /// depend on the order (ties go to the smallest triangle index).
    pub(crate) fn octant_orders(&self) -> [u32; 8] {
        // Doubled centres per slot, then each octant's keys once (not per comparison).
        let centre: [[f32; 3]; 8] = std::array::from_fn(|slot| {
            let (g, l) = (slot / 4, slot % 4);
            std::array::from_fn(|a| self.bounds[2 * a][g][l] + self.bounds[2 * a + 1][g][l])
        });
        std::array::from_fn(|octant| {
            let sign = |axis: usize| if octant >> axis & 1 == 0 { 1.0 } else { -1.0 };
            // A filled slot's key is NaN only where its centres overflow (extents near
            // `f32::MAX`); one NaN for all of them, whatever sign the arithmetic gave.
            let key: [f32; 8] = std::array::from_fn(|s| {
                let k: f32 = (0..3).map(|a| centre[s][a] * sign(a)).sum();
                if k.is_nan() {
                    f32::NAN
                } else {
                    k
                }
            });
            // Filled slots by key (ties by slot), then the empty ones in slot order: one
            // integer per slot ordered as (empty, key by `total_cmp`, slot), sorted. An empty
            // slot's key is left out: its box is (+∞, −∞), its centre NaN, and the sign of
            // `NaN · −1` is the compiler's choice (`mulss` keeps it, a negation flips it), so
            // the order of the empty slots changed with the build's codegen units.
            let sort_keys: [u64; 8] = std::array::from_fn(|s| {
                if self.child[s] == EMPTY_CHILD {
                    return 1 << 63 | s as u64;
                }
                let bits = key[s].to_bits() as i32;
                let total = (bits ^ (((bits >> 31) as u32) >> 1) as i32) as u32 ^ 1 << 31;
                u64::from(total) << 3 | s as u64
            });
            // The keys are distinct (the slot is in the low bits): each slot's rank is the
            // number of smaller keys, a branch-free sort of eight.
            let mut slots = [0usize; 8];
            for (s, &k) in sort_keys.iter().enumerate() {
                slots[sort_keys.iter().filter(|&&o| o < k).count()] = s;
            }
            pack_order(slots)
        })
    }
}

/// Packs eight slots into an order word (3 bits each, first in the low bits).
pub(crate) fn pack_order(slots: [usize; 8]) -> u32 {
    slots
        .iter()
        .enumerate()
        .fold(0, |w, (i, &s)| w | (s as u32) << (3 * i))
}

/// The order word of slots 0, 1, …, 7.
pub(crate) const IDENTITY_ORDER: u32 = 0o76543210;

/// A triangle of the hierarchy with its caller's index (`prim`), 40 bytes. The index lies in
/// the cache lines of the vertices the leaf test reads (and the traversal prefetches), so
/// answering a closest hit with it costs no extra miss; read from an array of its own, it
/// was a cache miss at the end of most incoherent queries (≈ 13 % of their time, session 36
/// in `docs/ray-layer.md`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(crate) struct LeafTri {
    /// The vertices, first in the struct (the leaf tests read them from its first byte).
    pub(crate) v: [Vec3; 3],
    /// The caller's index of the triangle.
    pub(crate) prim: u32,
}

impl LeafTri {
    /// `tris` in their own order, each numbered by its position.
    pub(crate) fn numbered(tris: &[[Vec3; 3]]) -> Vec<LeafTri> {
        (0u32..)
            .zip(tris)
            .map(|(prim, &v)| LeafTri { v, prim })
            .collect()
    }
}

/// The built hierarchy.
pub(crate) struct Bvh {
    /// Nodes; the root is node 0 (none when nothing can be hit).
    pub(crate) nodes: Vec<Node>,
    /// Every triangle given to [`build`], each with its caller's index: the first
    /// `hierarchy_triangles` in BVH order (leaf order), then the degenerate ones (never
    /// referenced by a leaf) in the caller's order.
    pub(crate) tris: Vec<LeafTri>,
    /// Triangles referenced by the leaves (the non-degenerate ones).
    pub(crate) hierarchy_triangles: usize,
    /// Position in `tris` of each original index: the inverse of the `prim` fields.
    pub(crate) slot_of: Vec<u32>,
    /// Number of node levels on the longest root-to-leaf path.
    pub(crate) depth: u32,
    /// SAH cost (`collapse::sah_cost`).
    pub(crate) sah_cost: f64,
    /// Wall-clock build time in seconds.
    pub(crate) build_seconds: f64,
    /// The same time by phase.
    pub(crate) phases: BuildPhases,
}

/// Wall-clock seconds of each phase of [`build`] (they add up to the build time).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BuildPhases {
    /// Degenerate-triangle filter and the builder's input (triangle boxes).
    pub prepare: f64,
    /// The binary hierarchy: our binned SAH (`binned.rs`, `Medium`) or obvhs's PLOC.
    pub hierarchy: f64,
    /// obvhs's reinsertion optimiser on a PLOC hierarchy (zero for `Medium`).
    pub reinsertion: f64,
    /// The collapse into 8-wide nodes with exact boxes (`collapse.rs`).
    pub collapse: f64,
    /// Triangles into BVH order, index maps, octant orders, depth and SAH cost.
    pub layout: f64,
}

/// obvhs build parameters for a quality level. Spatial pre-splits are turned off: they are
/// slow, and with them a triangle may appear in several leaves.
///
/// `Medium` is obvhs's `medium_build` with a shorter PLOC search (6 neighbours instead of 14,
/// distance 1 on the first two passes instead of three) and a smaller reinsertion batch (3 %
/// of the nodes instead of 5 %): on the 1,046,528-triangle anchor mesh the SAH cost is lower
/// (18.617 against 18.646) and reinsertion takes half the time; PLOC's time hardly depends on
/// the search distance (docs/ray-layer.md, session 9).
pub(crate) fn build_params(quality: BvhQuality) -> BvhBuildParams {
    let mut p = match quality {
        BvhQuality::Fast => BvhBuildParams::very_fast_build(),
        BvhQuality::Medium => BvhBuildParams {
            ploc_search_distance: PlocSearchDistance::Low,
            search_depth_threshold: 2,
            reinsertion_batch_ratio: 0.03,
            ..BvhBuildParams::medium_build()
        },
        BvhQuality::High => BvhBuildParams::slow_build(),
    };
    p.pre_split = false;
    p
}

/// Builds the hierarchy over the non-degenerate triangles of `tris` (and keeps all of them,
/// see [`Bvh::tris`]).
pub(crate) fn build(tris: &[[Vec3; 3]], quality: BvhQuality) -> Bvh {
    let start = Instant::now();
    let mut clock = PhaseClock::new(start);
    let mut phases = BuildPhases::default();
    assert!(
        tris.len() <= FIRST_MASK as usize,
        "too many triangles for one BVH"
    );
    // Every pass goes wide: the gathers (order-preserving collects), PLOC and reinsertion
    // inside obvhs, and the collapse into 8-wide nodes (`collapse.rs`).
    let params = build_params(quality);
    // `valid`: the caller's index of each triangle the hierarchy sees (`None`: all of them).
    let (bvh2, valid) = if quality == BvhQuality::Medium {
        let input = prepare::prepare(tris);
        phases.prepare = clock.lap();
        if input.refs.is_empty() {
            return unbuilt(tris, start, phases);
        }
        let bvh2 = binned::build_bounded(input.refs, input.bounds, input.centroids);
        phases.hierarchy = clock.lap();
        (bvh2, input.valid)
    } else {
        let valid: Vec<u32> = (0..tris.len() as u32)
            .into_par_iter()
            .filter(|&i| !is_degenerate(&tris[i as usize]))
            .collect();
        if valid.is_empty() {
            phases.prepare = clock.lap();
            return unbuilt(tris, start, phases);
        }
        let ob_tris = obvhs_triangles(tris, &valid);
        phases.prepare = clock.lap();
        let mut bvh2 = ploc(&ob_tris, &params);
        drop(ob_tris);
        phases.hierarchy = clock.lap();
        reinsert(&mut bvh2, &params);
        phases.reinsertion = clock.lap();
        (bvh2, Some(valid))
    };
    let collapsed = collapse::collapse(&bvh2, params.max_prims_per_leaf.clamp(1, 3));
    drop(bvh2);
    phases.collapse = clock.lap();
    let hierarchy_triangles = collapsed.order.len();
    let mut prim_ids: Vec<u32> = match valid {
        Some(valid) => collapsed
            .order
            .par_iter()
            .map(|&i| valid[i as usize])
            .collect(),
        None => collapsed.order,
    };
    if hierarchy_triangles < tris.len() {
        prim_ids.par_extend(
            (0..tris.len() as u32)
                .into_par_iter()
                .filter(|&i| is_degenerate(&tris[i as usize])),
        );
    }
    let mut bvh_tris: Vec<LeafTri> = super::huge_pages::with_capacity(prim_ids.len());
    bvh_tris.par_extend(prim_ids.par_iter().map(|&i| LeafTri {
        v: tris[i as usize],
        prim: i,
    }));
    let slot_of = inverse(&prim_ids);
    drop(prim_ids);
    let mut nodes = collapsed.nodes;
    nodes
        .par_iter_mut()
        .for_each(|node| node.order = node.octant_orders());
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
    phases.layout = clock.lap();
    Bvh {
        nodes,
        tris: bvh_tris,
        hierarchy_triangles,
        slot_of,
        depth,
        sah_cost,
        build_seconds: start.elapsed().as_secs_f64(),
        phases,
    }
}

/// Every triangle in the caller's order and no hierarchy over them, for a run that reads
/// triangles but traces no ray (a bake merge): nothing can be hit.
pub(crate) fn unindexed(tris: &[[Vec3; 3]]) -> Bvh {
    unbuilt(tris, Instant::now(), BuildPhases::default())
}

/// The hierarchy of a scene with no non-degenerate triangle: no nodes, every triangle kept
/// in the caller's order.
fn unbuilt(tris: &[[Vec3; 3]], start: Instant, phases: BuildPhases) -> Bvh {
    Bvh {
        nodes: Vec::new(),
        tris: LeafTri::numbered(tris),
        hierarchy_triangles: 0,
        slot_of: (0..tris.len() as u32).collect(),
        depth: 0,
        sah_cost: 0.0,
        build_seconds: start.elapsed().as_secs_f64(),
        phases,
    }
}

/// Seconds since the previous lap, for [`BuildPhases`].
struct PhaseClock(Instant);

impl PhaseClock {
    fn new(start: Instant) -> Self {
        Self(start)
    }

    fn lap(&mut self) -> f64 {
        let now = Instant::now();
        let seconds = now.duration_since(self.0).as_secs_f64();
        self.0 = now;
        seconds
    }
}

/// obvhs's input: the triangles `valid` names, in that order.
fn obvhs_triangles(tris: &[[Vec3; 3]], valid: &[u32]) -> Vec<Triangle> {
    valid
        .par_iter()
        .map(|&i| {
            let [v0, v1, v2] = tris[i as usize];
            Triangle {
                v0: v0.into(),
                v1: v1.into(),
                v2: v2.into(),
            }
        })
        .collect()
}

/// The inverse of a permutation of `0..n`: `inverse(p)[p[k]] = k` (one scattered pass; a
/// few milliseconds for a million triangles).
fn inverse(p: &[u32]) -> Vec<u32> {
    let mut out = vec![0u32; p.len()];
    for (k, &i) in p.iter().enumerate() {
        out[i as usize] = k as u32;
    }
    out
}

/// obvhs's binary hierarchy (PLOC, then reinsertion), one triangle per leaf. The low-level
/// obvhs calls (not `build_cwbvh_from_tris`) skip its debug-build validation, which is slow
/// and would dominate debug-profile tests.
#[cfg(test)]
pub(crate) fn binary_hierarchy(ob_tris: &[Triangle], params: &BvhBuildParams) -> Bvh2 {
    let mut bvh2 = ploc(ob_tris, params);
    reinsert(&mut bvh2, params);
    bvh2
}

/// obvhs's PLOC build, one triangle per leaf.
fn ploc(ob_tris: &[Triangle], params: &BvhBuildParams) -> Bvh2 {
    PlocBuilder::with_capacity(ob_tris.len()).build(
        params.ploc_search_distance,
        ob_tris,
        (0..ob_tris.len() as u32).collect(),
        params.sort_precision,
        params.search_depth_threshold,
    )
}

/// obvhs's reinsertion optimiser.
fn reinsert(bvh2: &mut Bvh2, params: &BvhBuildParams) {
    ReinsertionOptimizer::default().run(bvh2, params.reinsertion_batch_ratio, None);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node's planes are plane-major: plane `k` of all eight children is 32 contiguous,
    /// 32-byte aligned bytes (`bounds[k]`, children 0–7 in slot order), the one 8-wide load
    /// of the AVX2/AVX-512 node test; the node stays 256 bytes, 64-byte aligned.
    #[test]
    fn node_planes_are_contiguous_per_plane() {
        assert_eq!(std::mem::size_of::<Node>(), 256);
        assert_eq!(std::mem::align_of::<Node>(), 64);
        let mut node = Node::EMPTY;
        for slot in 0..8 {
            let s = slot as f32;
            node.set_child(
                slot,
                slot as u32,
                Vec3::new(s, 10.0 + s, 20.0 + s),
                Vec3::splat(40.0 + s),
            );
        }
        let base = std::ptr::from_ref(&node) as usize;
        for k in 0..6 {
            let plane = std::ptr::from_ref(&node.bounds[k]) as usize - base;
            assert_eq!(plane, 64 + 32 * k);
            // SAFETY: `bounds[k]` is two `Vec4`s: eight contiguous floats.
            let floats: [f32; 8] = unsafe { std::ptr::read(node.bounds[k].as_ptr().cast()) };
            let want: [f32; 8] = std::array::from_fn(|slot| {
                let s = slot as f32;
                [s, 40.0 + s, 10.0 + s, 40.0 + s, 20.0 + s, 40.0 + s][k]
            });
            assert_eq!(floats, want, "plane {k}");
        }
    }

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

    /// Every triangle of the copy carries its caller's index beside its vertices (40 bytes,
    /// the index in the last four, inside the lines a leaf's prefetch covers), and `slot_of`
    /// is the inverse of those indices — degenerate triangles and a scene of nothing but
    /// degenerate ones included.
    #[test]
    fn triangles_carry_their_caller_index() {
        assert_eq!(std::mem::size_of::<LeafTri>(), 40);
        assert_eq!(std::mem::offset_of!(LeafTri, prim), 36);
        let mut tris = soup(300);
        tris[5] = [Vec3::ZERO; 3];
        tris[77] = [Vec3::X; 3];
        let flat = vec![[Vec3::ONE; 3]; 4];
        for (tris, q) in [
            (&tris, BvhQuality::Fast),
            (&tris, BvhQuality::Medium),
            (&tris, BvhQuality::High),
            (&flat, BvhQuality::Medium),
        ] {
            let bvh = build(tris, q);
            assert_eq!(bvh.tris.len(), tris.len());
            for (slot, t) in bvh.tris.iter().enumerate() {
                assert_eq!(t.v, tris[t.prim as usize], "{q:?} slot {slot}");
                assert_eq!(bvh.slot_of[t.prim as usize] as usize, slot, "{q:?}");
            }
        }
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
                        seen[bvh.tris[k].prim as usize] += 1;
                        for v in bvh.tris[k].v {
                            for axis in 0..3 {
                                let (g, l) = (slot / 4, slot % 4);
                                assert!(node.bounds[2 * axis][g][l] <= v[axis]);
                                assert!(node.bounds[2 * axis + 1][g][l] >= v[axis]);
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

    /// Every node's order word, for every octant, is a permutation of the eight slots with the
    /// filled slots first, sorted by the box centre's projection on the octant's diagonal.
    #[test]
    fn octant_orders_sort_children_along_the_diagonal() {
        let bvh = build(&soup(3000), BvhQuality::Medium);
        let mut partial = 0;
        for node in &bvh.nodes {
            let filled = node.child.iter().filter(|&&c| c != EMPTY_CHILD).count();
            partial += usize::from(filled < 8);
            for (octant, &word) in node.order.iter().enumerate() {
                let slots: Vec<usize> = (0..8).map(|i| (word >> (3 * i) & 7) as usize).collect();
                let mut sorted = slots.clone();
                sorted.sort_unstable();
                assert_eq!(sorted, (0..8).collect::<Vec<_>>());
                assert!(slots[..filled]
                    .iter()
                    .all(|&s| node.child[s] != EMPTY_CHILD));
                let key = |s: usize| -> f32 {
                    let (g, l) = (s / 4, s % 4);
                    (0..3)
                        .map(|a| {
                            let c = node.bounds[2 * a][g][l] + node.bounds[2 * a + 1][g][l];
                            if octant >> a & 1 == 0 {
                                c
                            } else {
                                -c
                            }
                        })
                        .sum()
                };
                assert!(slots[..filled].windows(2).all(|w| key(w[0]) <= key(w[1])));
                // The same order as a comparison sort (ties by slot), the empty slots last in
                // slot order whatever their (NaN) keys.
                let mut want: Vec<usize> = (0..8).collect();
                want.sort_by(|&a, &b| {
                    let empty = |s: usize| node.child[s] == EMPTY_CHILD;
                    empty(a)
                        .cmp(&empty(b))
                        .then_with(|| match empty(a) {
                            true => std::cmp::Ordering::Equal,
                            false => key(a).total_cmp(&key(b)),
                        })
                        .then(a.cmp(&b))
                });
                assert_eq!(slots, want);
                assert!(slots[filled..].windows(2).all(|w| w[0] < w[1]));
            }
        }
        assert!(partial > 0 && bvh.nodes.len() > 10);
        assert_eq!(Node::EMPTY.order[5], pack_order(std::array::from_fn(|s| s)));
    }

    /// Empty slots follow the filled ones in slot order whatever NaN their (empty) boxes
    /// give as keys; before, they were sorted by the NaN's sign, which the compiler chose.
    #[test]
    fn empty_slots_come_last_in_slot_order_whatever_their_nan_keys() {
        let mut node = Node::EMPTY;
        node.set_child(0, 3, Vec3::splat(1.0), Vec3::splat(2.0));
        node.set_child(1, 4, Vec3::splat(-2.0), Vec3::splat(-1.0));
        let negative_nan = f32::from_bits(f32::NAN.to_bits() | 1 << 31);
        for (slot, nan) in [
            (2, f32::NAN),
            (3, negative_nan),
            (5, f32::NAN),
            (6, negative_nan),
        ] {
            node.bounds[0][slot / 4][slot % 4] = nan;
        }
        let orders = node.octant_orders();
        assert_eq!(orders[0], pack_order([1, 0, 2, 3, 4, 5, 6, 7]));
        assert_eq!(orders[7], pack_order([0, 1, 2, 3, 4, 5, 6, 7]));
    }

    /// The phases cover the build: each was timed, and together they are the build time up
    /// to the final `elapsed` call.
    #[test]
    fn build_phases_add_up_to_the_build_time() {
        let bvh = build(&soup(3000), BvhQuality::Medium);
        let p = bvh.phases;
        let parts = [p.prepare, p.hierarchy, p.reinsertion, p.collapse, p.layout];
        // `Medium` builds its own binned-SAH hierarchy: no reinsertion.
        assert!(
            parts.iter().all(|&t| t > 0.0) == (p.reinsertion > 0.0),
            "{p:?}"
        );
        assert_eq!(p.reinsertion, 0.0);
        let fast = build(&soup(3000), BvhQuality::Fast).phases;
        assert!(fast.hierarchy > 0.0 && fast.reinsertion > 0.0, "{fast:?}");
        let sum: f64 = parts.iter().sum();
        assert!(sum <= bvh.build_seconds, "{sum} > {}", bvh.build_seconds);
        let empty = build(&[[Vec3::ZERO; 3]], BvhQuality::Medium).phases;
        assert!(empty.prepare > 0.0 && empty.hierarchy == 0.0 && empty.layout == 0.0);
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
