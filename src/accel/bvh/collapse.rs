//! Parallel collapse of obvhs's binary hierarchy (one triangle per leaf) into stagelight's
//! 8-wide nodes, and the SAH cost of the result.
//!
//! The tree is the one obvhs 0.4's `bvh2_to_cwbvh` makes (same SAH dynamic programme after
//! Ylitie et al. 2017, same leaf cost, same greedy octant assignment of children, same
//! triangle order inside a leaf; `bvh::tests` compares the two trees node by node), but:
//!
//! * every pass runs over the rayon pool: the decision table bottom-up with `rayon::join` over
//!   the two subtrees of the upper levels (costs and 8-wide node counts travel up the
//!   recursion by value; a binary node keeps 16 bytes: its seven decisions, a byte each, and
//!   its sizes), then the emission top-down over disjoint slices of the output
//!   (`split_at_mut`), so no `unsafe` and no locks;
//! * it writes our nodes with exact `f32` child boxes directly (no 8-bit quantisation, hence
//!   no index-out-of-bounds on finite geometry around 1e19 as in obvhs's quantiser);
//! * the layout is depth-first: a node, then the subtrees of its inner children in slot order.
//!   Children still follow their parent, which `bvh.rs` relies on for the depth sweep.

use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

use glam::{Vec3, Vec3A};
use obvhs::bvh2::Bvh2;

use super::{Node, COUNT_SHIFT, LEAF_BIT};

/// SAH cost of one triangle test relative to one node visit (obvhs's `PRIM_COST`).
pub(crate) const PRIM_COST: f32 = 0.3;

/// Binary subtrees above this depth are costed in parallel (`rayon::join`).
const PARALLEL_DEPTH: u32 = 12;

/// Subtrees with more triangles than this are counted and emitted in parallel.
const PARALLEL_PRIMS: u32 = 4096;

/// No child in this slot.
const INVALID: u32 = u32::MAX;

/// What a binary node becomes when its parent hands it `i + 1` child slots.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    Leaf = 0,
    Internal = 1,
    Distribute = 2,
}

/// One entry of the decision table: the kind, and the slot budgets (index = slots − 1) of
/// the left and right child. Packed into one byte, seven per binary node.
#[derive(Clone, Copy, Debug)]
struct Decision {
    kind: Kind,
    left: u8,
    right: u8,
}

impl Decision {
    fn pack(self) -> u64 {
        u64::from(self.kind as u8 | self.left << 2 | self.right << 5)
    }

    fn unpack(v: u8) -> Self {
        let kind = match v & 3 {
            0 => Kind::Leaf,
            1 => Kind::Internal,
            _ => Kind::Distribute,
        };
        Self {
            kind,
            left: v >> 2 & 7,
            right: v >> 5,
        }
    }
}

/// What the cost pass hands a parent about a binary subtree.
struct Subtree {
    /// SAH cost when the subtree gets `i + 1` slots.
    cost: [f32; 7],
    /// 8-wide nodes the subtree contributes when it gets `i + 1` slots.
    nodes8: [u32; 7],
    /// Triangles under it.
    prims: u32,
}

/// The passes' shared state. The tables are atomics used with relaxed ordering: every entry is
/// written by exactly one task and read after `rayon::join`/the pass that wrote it returned,
/// which orders the accesses; on x86 these are plain loads and stores.
struct Collapser<'a> {
    bvh2: &'a Bvh2,
    max_prims_per_leaf: u32,
    /// Per binary node (one 16-byte entry, one cache miss): its seven decisions (`i + 1`
    /// slots for `i` in 0..7), a byte each; and its triangle count (low half) and the 8-wide
    /// nodes of its subtree when it becomes an 8-wide node (high half).
    table: Vec<[AtomicU64; 2]>,
}

/// Result of [`collapse`].
pub(crate) struct Collapsed {
    /// 8-wide nodes, root first; children follow their parent.
    pub(crate) nodes: Vec<Node>,
    /// Triangle order: `order[k]` is the binary hierarchy's primitive index of the `k`-th
    /// triangle in leaf order.
    pub(crate) order: Vec<u32>,
}

/// Collapses `bvh2` (non-empty, one triangle per leaf, boxes exact: the min/max of the
/// triangles' vertices, as obvhs computes them) into 8-wide nodes with leaves of at most
/// `max_prims_per_leaf` triangles. A leaf's box is its binary node's box, an inner node's box
/// the union of its children's.
pub(crate) fn collapse(bvh2: &Bvh2, max_prims_per_leaf: u32) -> Collapsed {
    let n = bvh2.nodes.len();
    let c = Collapser {
        bvh2,
        max_prims_per_leaf,
        // Zeroed pages from the allocator, not a 16-byte store per binary node (a temporary:
        // 4 KiB pages, see `huge_pages.rs`).
        table: bytemuck::zeroed_vec(n),
    };
    let root = c.cost(0, 0);
    let total_nodes = c.nodes8(0);
    let mut nodes = crate::accel::huge_pages::with_capacity(total_nodes as usize);
    nodes.resize(total_nodes as usize, Node::EMPTY);
    let mut order = vec![0u32; root.prims as usize];
    c.emit(0, &mut nodes, &mut order, 0, 0);
    Collapsed { nodes, order }
}

impl Collapser<'_> {
    fn decision(&self, node: usize, i: usize) -> Decision {
        Decision::unpack((self.table[node][0].load(Relaxed) >> (8 * i)) as u8)
    }

    /// Triangles under binary node `node`.
    fn prims(&self, node: usize) -> u32 {
        self.table[node][1].load(Relaxed) as u32
    }

    /// 8-wide nodes in the subtree of binary node `node` when it becomes an 8-wide node.
    fn nodes8(&self, node: usize) -> u32 {
        (self.table[node][1].load(Relaxed) >> 32) as u32
    }

    fn half_area(&self, node: usize) -> f32 {
        self.bvh2.nodes[node].aabb().half_area()
    }

    /// Fills the decision table of the subtree at `node` bottom-up (the SAH dynamic programme)
    /// and its sizes; returns what the parent needs.
    fn cost(&self, node: usize, depth: u32) -> Subtree {
        let bn = &self.bvh2.nodes[node];
        let half_area = self.half_area(node);
        if bn.prim_count != 0 {
            // Leaf decisions are all zero bits: nothing to store.
            self.table[node][1].store(u64::from(bn.prim_count) | 1 << 32, Relaxed);
            return Subtree {
                cost: [half_area * bn.prim_count as f32 * PRIM_COST; 7],
                nodes8: [0; 7],
                prims: bn.prim_count,
            };
        }
        let (l, r) = (bn.first_index as usize, bn.first_index as usize + 1);
        let (ls, rs) = if depth < PARALLEL_DEPTH {
            rayon::join(|| self.cost(l, depth + 1), || self.cost(r, depth + 1))
        } else {
            (self.cost(l, depth + 1), self.cost(r, depth + 1))
        };
        let prims = ls.prims + rs.prims;
        // One slot: a leaf, or an inner node whose 8 slots go to the two children.
        let cost_leaf = if prims <= self.max_prims_per_leaf {
            prims as f32 * half_area * PRIM_COST
        } else {
            f32::INFINITY
        };
        // obvhs starts from "no split" and panics when no cost is finite (half areas
        // overflow `f32` around extents of 1e19); starting from the even split gives the
        // same choice whenever one is finite, and a valid one otherwise.
        let (mut best, mut left, mut right) = (f32::INFINITY, 3, 3);
        for k in 0..7 {
            let c = ls.cost[k] + rs.cost[6 - k];
            if c < best {
                (best, left, right) = (c, k, 6 - k);
            }
        }
        let cost_internal = best + half_area;
        let own_nodes8 = 1 + ls.nodes8[left] + rs.nodes8[right];
        let kind = if cost_leaf < cost_internal {
            Kind::Leaf
        } else {
            Kind::Internal
        };
        let first = Decision {
            kind,
            left: left as u8,
            right: right as u8,
        };
        let mut out = Subtree {
            cost: [0.0; 7],
            nodes8: [0; 7],
            prims,
        };
        if kind == Kind::Internal {
            out.cost[0] = cost_internal;
            out.nodes8[0] = own_nodes8;
        } else {
            out.cost[0] = cost_leaf;
        }
        let mut packed = first.pack();
        // `i + 1` slots: as with `i` slots, or distributed over the two children.
        let mut prev = first;
        for i in 1..7 {
            let (mut best, mut left, mut right) = (out.cost[i - 1], usize::MAX, usize::MAX);
            for k in 0..i {
                let c = ls.cost[k] + rs.cost[i - k - 1];
                if c < best {
                    (best, left, right) = (c, k, i - k - 1);
                }
            }
            if left != usize::MAX {
                prev = Decision {
                    kind: Kind::Distribute,
                    left: left as u8,
                    right: right as u8,
                };
                out.nodes8[i] = ls.nodes8[left] + rs.nodes8[right];
            } else {
                out.nodes8[i] = out.nodes8[i - 1];
            }
            out.cost[i] = best;
            packed |= prev.pack() << (8 * i);
        }
        self.table[node][0].store(packed, Relaxed);
        self.table[node][1].store(u64::from(prims) | u64::from(own_nodes8) << 32, Relaxed);
        out
    }

    /// The binary nodes that become the children of the 8-wide node made of `node`, in the
    /// order obvhs gives them (`get_children`).
    fn gather(&self, node: usize, i: usize, out: &mut [u32; 8], len: &mut usize) {
        let bn = &self.bvh2.nodes[node];
        if bn.prim_count != 0 {
            out[*len] = node as u32;
            *len += 1;
            return;
        }
        let d = self.decision(node, i);
        for (child, k) in [
            (bn.first_index as usize, d.left),
            (bn.first_index as usize + 1, d.right),
        ] {
            if self.decision(child, k as usize).kind == Kind::Distribute {
                self.gather(child, k as usize, out, len);
            } else {
                out[*len] = child as u32;
                *len += 1;
            }
        }
    }

    /// Children of the 8-wide node made of `node`, assigned to octant slots (`INVALID` where
    /// empty) by obvhs's greedy `order_children`.
    fn children(&self, node: usize) -> [u32; 8] {
        let mut list = [INVALID; 8];
        let mut len = 0;
        self.gather(node, 0, &mut list, &mut len);
        let centre = |n: u32| self.bvh2.nodes[n as usize].aabb().center();
        let p = centre(node as u32);
        let list = &list[..len];
        // cost[c][s]: centroid of child `c` projected on the direction of octant `s`.
        let mut cost = [[f32::MAX; 8]; 8];
        for (row, &c) in cost.iter_mut().zip(list) {
            let v = centre(c) - p;
            *row = std::array::from_fn(|s| {
                let d = Vec3A::new(
                    if s & 0b100 != 0 { -1.0 } else { 1.0 },
                    if s & 0b010 != 0 { -1.0 } else { 1.0 },
                    if s & 0b001 != 0 { -1.0 } else { 1.0 },
                );
                d.dot(v)
            });
        }
        // Greedy: repeatedly the least cost over free (child, slot) pairs, the first in
        // (child, slot) order on ties; only costs below `f32::MAX` are taken (not NaN). Each
        // row keeps its least free entry (first slot on ties), so a pick is the first row
        // with the least entry; after it only the rows whose entry sat in the taken slot look
        // again.
        let row_min = |row: &[f32; 8], filled: &[bool; 8]| -> (f32, usize) {
            let (mut min_cost, mut min_slot) = (f32::MAX, usize::MAX);
            for (s, (&v, &f)) in row.iter().zip(filled).enumerate() {
                let less = v < min_cost && !f;
                min_cost = if less { v } else { min_cost };
                min_slot = if less { s } else { min_slot };
            }
            (min_cost, min_slot)
        };
        let mut assignment = [usize::MAX; 8];
        let mut filled = [false; 8];
        let mut best = [(f32::MAX, usize::MAX); 8];
        for (b, row) in best.iter_mut().zip(&cost[..list.len()]) {
            *b = row_min(row, &filled);
        }
        for _ in 0..list.len() {
            let (mut min_cost, mut min_child) = (f32::MAX, usize::MAX);
            for (c, &(v, _)) in best.iter().enumerate().take(list.len()) {
                let less = v < min_cost;
                min_cost = if less { v } else { min_cost };
                min_child = if less { c } else { min_child };
            }
            if min_child == usize::MAX {
                break;
            }
            let min_slot = best[min_child].1;
            filled[min_slot] = true;
            assignment[min_child] = min_slot;
            best[min_child] = (f32::MAX, usize::MAX);
            for (b, row) in best.iter_mut().zip(&cost[..list.len()]) {
                if b.1 == min_slot {
                    *b = row_min(row, &filled);
                }
            }
        }
        // Children whose costs are not below `f32::MAX` (infinite or NaN centres of huge
        // boxes) are left unassigned by the greedy loop (obvhs then indexes out of bounds):
        // they take the free slots in order.
        let mut slots = [INVALID; 8];
        for slot in assignment.iter_mut().take(list.len()) {
            if *slot == usize::MAX {
                let free = filled.iter().position(|&f| !f).unwrap_or(0);
                filled[free] = true;
                *slot = free;
            }
        }
        for (&child, &slot) in list.iter().zip(&assignment) {
            slots[slot] = child;
        }
        slots
    }

    /// Whether child `c` of an 8-wide node is an inner node (else a leaf).
    fn is_inner(&self, c: u32) -> bool {
        self.decision(c as usize, 0).kind == Kind::Internal
    }

    /// The binary leaves under `c` (in left-first order) into `out`.
    fn leaf_prims(&self, c: usize, out: &mut [u32], at: &mut usize) {
        let bn = &self.bvh2.nodes[c];
        if bn.prim_count != 0 {
            for k in 0..bn.prim_count {
                out[*at] = self.bvh2.primitive_indices[(bn.first_index + k) as usize];
                *at += 1;
            }
            return;
        }
        self.leaf_prims(bn.first_index as usize, out, at);
        self.leaf_prims(bn.first_index as usize + 1, out, at);
    }

    /// Writes the 8-wide subtree of `node` into `nodes` (its first entry is `node`'s, at global
    /// index `node_base`) and its triangle order into `order` (global offset `prim_base`);
    /// returns the subtree's exact box.
    fn emit(
        &self,
        node: usize,
        nodes: &mut [Node],
        order: &mut [u32],
        node_base: u32,
        prim_base: u32,
    ) -> (Vec3, Vec3) {
        let slots = self.children(node);
        let (head, mut rest_nodes) = nodes.split_at_mut(1);
        let mut rest_order = order;
        // Leaves first, in slot order: their triangles open the subtree's range.
        let mut at = 0;
        let mut refs = [None; 8];
        for (s, &c) in slots.iter().enumerate() {
            if c == INVALID || self.is_inner(c) {
                continue;
            }
            let start = at;
            self.leaf_prims(c as usize, rest_order, &mut at);
            // The binary node's box is the exact min/max of its triangles' vertices.
            let b = self.bvh2.nodes[c as usize].aabb();
            let (lo, hi) = (Vec3::from(b.min), Vec3::from(b.max));
            let count = (at - start) as u32;
            refs[s] = Some((
                LEAF_BIT | (count << COUNT_SHIFT) | (prim_base + start as u32),
                lo,
                hi,
            ));
        }
        rest_order = &mut rest_order[at..];
        // Then the inner children's subtrees, each in its own slices.
        let mut node_at = node_base + 1;
        let mut prim_at = prim_base + at as u32;
        let mut jobs = Vec::new();
        for (s, &c) in slots.iter().enumerate() {
            if c == INVALID || !self.is_inner(c) {
                continue;
            }
            let nn = self.nodes8(c as usize) as usize;
            let np = self.prims(c as usize) as usize;
            let (sub_nodes, more_nodes) = std::mem::take(&mut rest_nodes).split_at_mut(nn);
            let (sub_order, more_order) = std::mem::take(&mut rest_order).split_at_mut(np);
            rest_nodes = more_nodes;
            rest_order = more_order;
            jobs.push((s, c, sub_nodes, sub_order, node_at, prim_at));
            node_at += nn as u32;
            prim_at += np as u32;
        }
        let run = |(s, c, sub_nodes, sub_order, nb, pb): (
            usize,
            u32,
            &mut [Node],
            &mut [u32],
            u32,
            u32,
        )| {
            let (lo, hi) = self.emit(c as usize, sub_nodes, sub_order, nb, pb);
            (s, nb, lo, hi)
        };
        let done: Vec<(usize, u32, Vec3, Vec3)> = if self.prims(node) > PARALLEL_PRIMS {
            use rayon::prelude::*;
            jobs.into_par_iter().map(run).collect()
        } else {
            jobs.into_iter().map(run).collect()
        };
        for (s, nb, lo, hi) in done {
            refs[s] = Some((nb, lo, hi));
        }
        // Children packed into the first slots, in slot order; the box is their union.
        let (mut nlo, mut nhi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for (packed, (reference, lo, hi)) in refs.into_iter().flatten().enumerate() {
            head[0].set_child(packed, reference, lo, hi);
            nlo = nlo.min(lo);
            nhi = nhi.max(hi);
        }
        (nlo, nhi)
    }
}

/// SAH cost of the hierarchy, in units of one node visit by a ray that hits the root box:
/// `Σ_inner A(child)/A(root) + PRIM_COST · Σ_leaf n·A(leaf)/A(root)`, plus 1 for the root,
/// with `A` the half surface area. Serial and in node order, so the same tree gives the same
/// number bit for bit.
pub(crate) fn sah_cost(nodes: &[Node]) -> f64 {
    let Some(root) = nodes.first() else {
        return 0.0;
    };
    let half_area = |node: &Node, slot: usize| -> f64 {
        let (g, l) = (slot / 4, slot % 4);
        let d = [0, 1, 2]
            .map(|a| f64::from(node.bounds[2 * a + 1][g][l]) - f64::from(node.bounds[2 * a][g][l]));
        (d[0] + d[1]) * d[2] + d[0] * d[1]
    };
    let mut root_area = 0.0f64;
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for (slot, &c) in root.child.iter().enumerate() {
        if c == super::EMPTY_CHILD {
            continue;
        }
        let (g, l) = (slot / 4, slot % 4);
        let b = |k: usize| root.bounds[k][g][l];
        lo = lo.min(Vec3::new(b(0), b(2), b(4)));
        hi = hi.max(Vec3::new(b(1), b(3), b(5)));
    }
    let d = (hi - lo).as_dvec3();
    root_area += (d.x + d.y) * d.z + d.x * d.y;
    if root_area <= 0.0 || !root_area.is_finite() {
        return 1.0;
    }
    let mut sum = 0.0f64;
    for node in nodes {
        for (slot, &c) in node.child.iter().enumerate() {
            if c == super::EMPTY_CHILD {
                continue;
            }
            let area = half_area(node, slot);
            if c & LEAF_BIT != 0 {
                let count = (c & !LEAF_BIT) >> COUNT_SHIFT;
                sum += f64::from(PRIM_COST) * f64::from(count) * area;
            } else {
                sum += area;
            }
        }
    }
    1.0 + sum / root_area
}

#[cfg(test)]
mod tests {
    use super::super::{binary_hierarchy, build, build_params, EMPTY_CHILD, FIRST_MASK};
    use super::*;
    use crate::settings::BvhQuality;
    use obvhs::{cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh, triangle::Triangle};

    fn soup(n: usize, seed: u64) -> Vec<[Vec3; 3]> {
        let mut rnd = crate::accel::test_random::signed_uniform(seed);
        (0..n)
            .map(|_| {
                let c = Vec3::new(rnd(), rnd() * 0.5, rnd() * 2.0) * 8.0;
                [
                    c,
                    c + Vec3::new(rnd(), rnd(), rnd()) * 0.4,
                    c + Vec3::new(rnd(), rnd(), rnd()) * 0.4,
                ]
            })
            .collect()
    }

    /// One 8-wide node in canonical form: per packed child, its box bits and either the
    /// triangles of a leaf (binary-hierarchy primitive indices, in order) or an inner node.
    type Canon = Vec<([u32; 6], Result<Vec<u32>, usize>)>;

    fn canon_ours(c: &Collapsed, node: usize) -> Canon {
        let n = &c.nodes[node];
        (0..8)
            .filter(|&s| n.child[s] != EMPTY_CHILD)
            .map(|s| {
                let (g, l) = (s / 4, s % 4);
                let b = [0, 1, 2, 3, 4, 5].map(|k| n.bounds[k][g][l].to_bits());
                let r = n.child[s];
                let what = if r & LEAF_BIT != 0 {
                    let first = (r & FIRST_MASK) as usize;
                    let count = ((r & !LEAF_BIT) >> COUNT_SHIFT) as usize;
                    Ok(c.order[first..first + count].to_vec())
                } else {
                    Err(r as usize)
                };
                (b, what)
            })
            .collect()
    }

    /// Walks our tree and obvhs's (`bvh2_to_cwbvh`, the converter this file replaces) side by
    /// side: same children in the same packed order, same leaves, and our leaf boxes are
    /// exactly the folds of the leaf triangles' vertices (obvhs's own boxes are quantised, so
    /// the boxes are checked against the triangles).
    fn assert_same_tree(tris: &[[Vec3; 3]], quality: BvhQuality) {
        let ob: Vec<Triangle> = tris
            .iter()
            .map(|t| Triangle {
                v0: t[0].into(),
                v1: t[1].into(),
                v2: t[2].into(),
            })
            .collect();
        let params = build_params(quality);
        let bvh2 = binary_hierarchy(&ob, &params);
        let leaf = params.max_prims_per_leaf.clamp(1, 3);
        let ours = collapse(&bvh2, leaf);
        let theirs = bvh2_to_cwbvh(&bvh2, leaf, true, false);
        assert_eq!(ours.nodes.len(), theirs.nodes.len());
        let mut stack = vec![(0usize, 0usize)];
        let mut visited = 0;
        while let Some((a, b)) = stack.pop() {
            visited += 1;
            let mine = canon_ours(&ours, a);
            let cn = &theirs.nodes[b];
            let slots: Vec<usize> = (0..8).filter(|&s| !cn.is_child_empty(s)).collect();
            assert_eq!(mine.len(), slots.len(), "node {a}/{b}");
            for ((bits, what), s) in mine.into_iter().zip(slots) {
                let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
                match what {
                    Ok(prims) => {
                        assert!(cn.is_leaf(s));
                        let (first, count) = cn.child_primitives(s);
                        assert_eq!(
                            prims,
                            theirs.primitive_indices[first as usize..(first + count) as usize]
                        );
                        for p in prims {
                            let t = tris[p as usize];
                            lo = lo.min(t[0]).min(t[1]).min(t[2]);
                            hi = hi.max(t[0]).max(t[1]).max(t[2]);
                        }
                        // Equal as numbers (a zero's sign may differ: obvhs's SSE `min`
                        // and `f32::min` pick different zeros; the slab test sees no
                        // difference).
                        let want = [lo.x, hi.x, lo.y, hi.y, lo.z, hi.z];
                        assert_eq!(bits.map(f32::from_bits), want);
                    }
                    Err(child) => {
                        assert!(!cn.is_leaf(s));
                        stack.push((child, cn.child_node_index(s) as usize));
                    }
                }
            }
        }
        assert_eq!(visited, ours.nodes.len());
    }

    #[test]
    fn same_tree_as_obvhs_serial_collapse() {
        for (n, seed) in [(1, 3), (2, 5), (3, 7), (40, 11), (3000, 13)] {
            for q in [BvhQuality::Fast, BvhQuality::Medium, BvhQuality::High] {
                assert_same_tree(&soup(n, seed), q);
            }
        }
    }

    #[test]
    fn same_tree_at_every_thread_count() {
        let tris = soup(20_000, 17);
        let at = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| build(&tris, BvhQuality::Medium))
        };
        let (one, three) = (at(1), at(3));
        assert_eq!(one.tris, three.tris);
        assert_eq!(one.nodes.len(), three.nodes.len());
        for (a, b) in one.nodes.iter().zip(&three.nodes) {
            assert_eq!(a.child, b.child);
            assert_eq!(format!("{:?}", a.bounds), format!("{:?}", b.bounds));
        }
        assert_eq!(one.sah_cost.to_bits(), three.sah_cost.to_bits());
    }

    /// obvhs's collapse indexes out of bounds on finite geometry whose half areas overflow
    /// `f32` (extents around 1e19 and beyond: every cost is infinite); ours builds, and the
    /// hierarchy answers rays as brute force does.
    #[test]
    fn extreme_finite_extents_build() {
        for big in [1e19f32, 1e30, 1.5e38] {
            let mut tris = soup(200, 23);
            tris.push([
                Vec3::new(-big, -big, 0.0),
                Vec3::new(big, -big, 0.0),
                Vec3::new(0.0, big, big),
            ]);
            tris.push([
                Vec3::new(-big, 0.0, -big),
                Vec3::new(big, 0.0, -big),
                Vec3::Z,
            ]);
            let ob: Vec<Triangle> = tris
                .iter()
                .map(|t| Triangle {
                    v0: t[0].into(),
                    v1: t[1].into(),
                    v2: t[2].into(),
                })
                .collect();
            let bvh2 = binary_hierarchy(&ob, &build_params(BvhQuality::Medium));
            let theirs = std::panic::catch_unwind(|| bvh2_to_cwbvh(&bvh2, 3, true, false));
            eprintln!("{big:e}: obvhs collapse panics: {}", theirs.is_err());
            let accel = crate::accel::Accel::build(tris.clone(), BvhQuality::Medium);
            let s = accel.stats();
            assert_eq!(s.bvh_triangles, tris.len());
            for i in 0..200 {
                let f = i as f32;
                let ray = crate::accel::Ray {
                    origin: Vec3::new((f * 0.7).sin(), (f * 0.3).cos(), 9.0) * 8.0,
                    dir: Vec3::new((f * 1.3).sin(), (f * 0.9).cos(), -3.0),
                    t_max: f32::INFINITY,
                };
                let want = crate::accel::brute_force_intersect(&tris, &ray);
                assert_eq!(accel.intersect(&ray), want, "{big:e} ray {i}");
            }
        }
    }

    /// Closed form: one triangle gives one leaf covering the root box, so the cost is the root
    /// visit plus one triangle test.
    #[test]
    fn sah_cost_of_a_single_triangle() {
        let bvh = build(
            &[[Vec3::ZERO, Vec3::X, Vec3::Y + Vec3::Z]],
            BvhQuality::Medium,
        );
        assert_eq!(bvh.sah_cost, 1.0 + f64::from(PRIM_COST));
    }
}
