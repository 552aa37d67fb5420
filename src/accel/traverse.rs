//! The traversal kernels over our 8-wide nodes: closest hit and occlusion, one ray at a time
//! or a batch of rays interleaved.
//!
//! * **Slab test** (pbrt-v4 `Bounds3::IntersectP`, Ize 2013): `t = (plane − o) · (1/d)` with the
//!   exact IEEE reciprocal (±∞ for zero components, never clamped), far distances scaled by
//!   `1 + 2γ3`. The only NaN is `0 · ∞` (origin exactly on a plane of an axis the ray does not
//!   move along); the min/max chain is ordered so that such a slab is ignored, which is the
//!   conservative answer. The entry distance is clamped at 0 — not at obvhs's 1e-4.
//! * **Order**: the single-ray kernels (closest hit and occlusion) visit hit children in the
//!   node's precomputed order for the ray's octant (`Node::order`; no sort): the nearest is
//!   visited next (not pushed, not prefetched), the others are pushed farthest first. The
//!   block batch lanes (AVX-512 or AVX2) push them in the same order, farthest first, the
//!   nearest on top (`NodeTest::push_ordered`, one packed block store); the other batch lanes
//!   push them sorted by entry distance, nearest on top. `STAGELIGHT_TRAVERSAL=sorted` sorts in every kernel, and the
//!   single-ray occlusion kernel then visits the last slot hit first (for A/B runs).
//!   Popped entries farther than the current closest hit are skipped.
//! * **Prefetch**: every child pushed is prefetched whole (a node's four cache lines, a
//!   leaf's triangles), so its misses overlap the work on its siblings (+13–15 % incoherent);
//!   the addresses are selected without a branch on the leaf bit (`prefetch_lines`). The
//!   AVX-512 single-ray kernels (`traverse_wide/single512.rs`) push as one block store and
//!   prefetch only the child popped next. A leaf's prefetched lines hold its triangles'
//!   caller indices too ([`LeafTri`]), so answering the closest hit with one costs no miss.
//! * **Batches** (`closest_batch`, `occluded_batch`): 12 rays traversed interleaved, one node
//!   or leaf per ray in turn, each lane's next node or leaf prefetched (`prefetch_child`);
//!   identical results, 2.5–3× the single-ray throughput on incoherent rays.
//! * **Stack**: sized from the tree depth measured at build (a fixed array when that fits, a
//!   `Vec` otherwise), so it cannot overflow. The single-ray kernels' array is left
//!   uninitialised in their frame (`FrameStack`: no fill, no per-thread array).
//! * **Ties**: the closest hit is the smallest `(t, original index)`, so the result does not
//!   depend on traversal order (the brute-force reference gives the same answer).

use glam::Vec4;

use super::bvh::{Bvh, LeafTri, Node, COUNT_SHIFT, EMPTY_CHILD, FIRST_MASK, LEAF_BIT};
use super::triangle::{gamma, ray_is_valid, WoopRay};
use super::{Hit, Ray};
use crate::prefetch::prefetch_line;

/// Far slab distances are scaled by this to make the box test conservative.
const FAR_SCALE: f32 = 1.0 + 2.0 * gamma(3);

/// The 8-child slab test of one ray, in one instruction set: `intersect` returns the hit mask
/// (bit `i` for child slot `i`) and the entry distances. Every implementation returns the same
/// mask for the same ray and node, so the traversal (and the result) does not depend on it.
/// It also tests leaves (`leaf_hits`), with the scalar test's answers in every implementation.
pub(super) trait NodeTest {
    /// Whether the batch lanes push children in octant order ([`NodeTest::push_ordered`])
    /// rather than sorted by entry distance: only where the push is one block store (the
    /// block lanes, AVX-512 or AVX2); with a loop, octant order measured no better than the
    /// sort there.
    const BATCH_OCTANT: bool = false;

    /// Per-ray constants (`woop` is the ray's triangle-test constants, already made).
    fn new(ray: &Ray, woop: &WoopRay) -> Self;
    /// Tests the eight children against `[0, t_far]`.
    fn intersect(&self, node: &Node, t_far: f32) -> (u32, [f32; 8]);

    /// Reports the hits of a leaf's triangles `tris` (1 to 3, BVH order) with `t ≤ t_limit`
    /// to `f`, in triangle order, as `(j, (t, b1, b2))` with `j` the index in `tris`; each is
    /// exactly what `woop.intersect` answers for that triangle. Stops when `f` returns true.
    /// One triangle at a time here; the AVX2 kernels test the leaf in SIMD lanes.
    #[inline(always)]
    fn leaf_hits(
        &self,
        woop: &WoopRay,
        tris: &[LeafTri],
        t_limit: f32,
        mut f: impl FnMut(usize, (f32, f32, f32)) -> bool,
    ) {
        for (j, tri) in tris.iter().enumerate() {
            if let Some(hit) = woop.intersect(&tri.v) {
                if hit.0 <= t_limit && f(j, hit) {
                    return;
                }
            }
        }
    }

    /// The same test, answered in the visiting order `order` (a [`Node::order`] word):
    /// bit `i` of the mask, entry distance `i` and reference `i` are those of slot
    /// `order`'s `i`-th slot. Scalar permutation here; the wide kernels permute in registers.
    #[inline(always)]
    fn intersect_ordered(&self, node: &Node, t_far: f32, order: u32) -> (u32, [f32; 8], [u32; 8]) {
        let (mask, entry) = self.intersect(node, t_far);
        let mut ordered_mask = 0;
        let mut t = [0f32; 8];
        let mut r = [0u32; 8];
        for i in 0..8 {
            let slot = (order >> (3 * i) & 7) as usize;
            ordered_mask |= (mask >> slot & 1) << i;
            t[i] = entry[slot];
            r[i] = node.child[slot];
        }
        (ordered_mask, t, r)
    }

    /// The single-ray kernels' node step: of the children of `node` entered within
    /// `[0, t_far]`, in the visiting order `order` (a [`Node::order`] word), all but the
    /// nearest are pushed onto `stack` (with their entry distances), farthest first, and the
    /// nearest is returned, to be visited next; `None` when no child is entered. Here through
    /// [`NodeTest::intersect_ordered`] and a loop that prefetches each pushed child
    /// ([`push_all_but_nearest`]); the AVX-512 single-ray kernels store them as one block.
    #[inline(always)]
    fn visit_ordered<S: Stack>(
        &self,
        bvh: &Bvh,
        node: &Node,
        t_far: f32,
        order: u32,
        stack: &mut S,
    ) -> Option<u32> {
        let (mask, tn, child) = self.intersect_ordered(node, t_far, order);
        if mask == 0 {
            return None;
        }
        Some(push_all_but_nearest(bvh, stack, mask, &tn, &child))
    }

    /// Pushes the children of `node` entered within `[0, t_far]` onto `stack` in the visiting
    /// order `order` (a [`Node::order`] word), farthest first, so that the nearest is on top
    /// (the batch lanes). Here through [`NodeTest::intersect_ordered`] and a loop; the block
    /// kernels store all of them at once.
    #[inline(always)]
    fn push_ordered(&self, node: &Node, t_far: f32, order: u32, stack: &mut BatchStack) {
        let (mut mask, t, r) = self.intersect_ordered(node, t_far, order);
        while mask != 0 {
            let i = 31 - mask.leading_zeros() as usize;
            mask ^= 1 << i;
            stack.push(Entry { r: r[i], t: t[i] });
        }
    }

    /// Pushes the children of `node` entered within `[0, t_far]` onto `stack` in slot order
    /// (the last slot on top), with an unspecified entry distance (the occlusion lanes). A
    /// loop here; the block kernels (AVX-512 or AVX2) store them as one block.
    #[inline(always)]
    fn push_all(&self, node: &Node, t_far: f32, stack: &mut BatchStack) {
        let (mut mask, _) = self.intersect(node, t_far);
        while mask != 0 {
            let slot = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            stack.push(Entry {
                r: node.child[slot],
                t: 0.0,
            });
        }
    }
}

impl NodeTest for NodeRay {
    #[inline(always)]
    fn new(ray: &Ray, _: &WoopRay) -> Self {
        NodeRay::new(ray)
    }
    #[inline(always)]
    fn intersect(&self, node: &Node, t_far: f32) -> (u32, [f32; 8]) {
        let (mask, entry) = NodeRay::intersect(self, node, t_far);
        let (a, b) = (entry[0].to_array(), entry[1].to_array());
        (mask, [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]])
    }
}

/// Far slab distances are scaled by this (shared with the wide kernels).
pub(super) const FAR_SCALE_FACTOR: f32 = FAR_SCALE;

/// Per-ray constants of the slab test (SSE, four children at a time).
pub(super) struct NodeRay {
    o: [Vec4; 3],
    inv: [Vec4; 3],
    near: [usize; 3],
    far: [usize; 3],
}

impl NodeRay {
    #[inline]
    pub(super) fn new(ray: &Ray) -> Self {
        let inv = ray.dir.recip();
        let d = ray.dir.to_array();
        // The sign bit decides (−0.0 counts as negative, matching 1/−0 = −∞).
        let near_plane = |a: usize| 2 * a + usize::from(d[a].is_sign_negative());
        let near = [near_plane(0), near_plane(1), near_plane(2)];
        Self {
            o: [
                Vec4::splat(ray.origin.x),
                Vec4::splat(ray.origin.y),
                Vec4::splat(ray.origin.z),
            ],
            inv: [Vec4::splat(inv.x), Vec4::splat(inv.y), Vec4::splat(inv.z)],
            near,
            far: [near[0] ^ 1, near[1] ^ 1, near[2] ^ 1],
        }
    }

    /// Tests the eight children against `[0, t_far]`; returns the hit mask and entry distances.
    #[inline(always)]
    pub(super) fn intersect(&self, node: &Node, t_far: f32) -> (u32, [Vec4; 2]) {
        let t_far = Vec4::splat(t_far);
        let mut mask = 0;
        let mut entry = [Vec4::ZERO; 2];
        // Children are packed: an empty slot 4 means the second group is empty.
        let groups = if node.child[4] == EMPTY_CHILD { 1 } else { 2 };
        for (g, e) in entry.iter_mut().enumerate().take(groups) {
            // `a.max(acc)` is SSE `maxps(a, acc)`, which returns `acc` when either is NaN, and
            // `acc` never is: a NaN slab is ignored.
            let mut tn = Vec4::ZERO;
            let mut tf = t_far;
            for a in 0..3 {
                let n = (node.bounds[self.near[a]][g] - self.o[a]) * self.inv[a];
                let f = (node.bounds[self.far[a]][g] - self.o[a]) * self.inv[a];
                tn = n.max(tn);
                tf = f.min(tf);
            }
            let tf = tf * FAR_SCALE;
            mask |= tn.cmple(tf).bitmask() << (4 * g);
            *e = tn;
        }
        (mask, entry)
    }
}

/// A deferred child: its reference and entry distance (`repr(C)`: the AVX-512 kernels store
/// eight of them as one 64-byte vector of `(r, t)` pairs).
#[derive(Clone, Copy, Default)]
#[repr(C)]
pub(super) struct Entry {
    pub(super) r: u32,
    pub(super) t: f32,
}

/// The traversal stack interface (fixed array or heap). Every implementation keeps eight
/// slots beyond the traversal bound, so that a kernel may store a whole block of entries above
/// the top ([`Stack::top_block`]) and then count some of them as pushed ([`Stack::grow`]).
pub(super) trait Stack {
    fn push(&mut self, e: Entry);
    fn pop(&mut self) -> Option<Entry>;
    fn len(&self) -> usize;
    fn clear(&mut self);
    /// Sorts the entries from `from` to the top so that the smallest `t` is on top.
    fn sort_top(&mut self, from: usize);
    /// The first of the eight slots above the top (panics, never overwrites, when fewer are
    /// left). A raw pointer: the slots may be uninitialised ([`FrameStack`]); the caller
    /// writes entries there before it counts them with [`Stack::grow`], and reads back only
    /// slots it wrote.
    fn top_block(&mut self) -> *mut Entry;
    /// Counts `n ≤ 8` more entries, written through [`Stack::top_block`], as pushed.
    fn grow(&mut self, n: usize);
}

/// A stack in a fixed array; `push` past `N` panics (never silently overwrites), and `N` is
/// chosen from the measured tree depth so that it never happens.
pub(super) struct ArrayStack<const N: usize> {
    items: [Entry; N],
    len: usize,
}

impl<const N: usize> ArrayStack<N> {
    fn new() -> Self {
        Self {
            items: [Entry::default(); N],
            len: 0,
        }
    }

    /// The eight slots above the top, for a kernel that stores a whole block of entries and
    /// then [`ArrayStack::grow`]s by the number that count (right after). Panics (never
    /// overwrites) when fewer than eight slots are left; [`BatchStack`] keeps eight beyond
    /// the traversal bound for it.
    #[inline(always)]
    pub(super) fn block(&mut self) -> &mut [Entry; 8] {
        let len = self.len;
        (&mut self.items[len..len + 8])
            .try_into()
            .expect("eight slots")
    }

    /// Counts `n ≤ 8` more entries, written through [`ArrayStack::block`], as pushed.
    #[inline(always)]
    pub(super) fn grow(&mut self, n: usize) {
        debug_assert!(n <= 8);
        self.len += n;
    }

    /// A stack holding `n` marker entries (references `0..n`, distance −1), for tests.
    #[cfg(test)]
    pub(super) fn with_entries(n: usize) -> Self {
        let mut s = Self::new();
        for r in 0..n as u32 {
            s.push(Entry { r, t: -1.0 });
        }
        s
    }

    /// The entries, from the bottom up (for tests).
    #[cfg(test)]
    pub(super) fn entries(&self) -> &[Entry] {
        &self.items[..self.len]
    }
}

/// The batch lanes' stack: the deepest traversal an array stack allows, plus the eight slots
/// a block store writes above the top.
pub(super) type BatchStack = ArrayStack<{ ARRAY_STACK + 8 }>;

fn sort_descending(s: &mut [Entry]) {
    for i in 1..s.len() {
        let e = s[i];
        let mut j = i;
        while j > 0 && s[j - 1].t < e.t {
            s[j] = s[j - 1];
            j -= 1;
        }
        s[j] = e;
    }
}

impl<const N: usize> Stack for ArrayStack<N> {
    #[inline(always)]
    fn push(&mut self, e: Entry) {
        self.items[self.len] = e;
        self.len += 1;
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<Entry> {
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        Some(self.items[self.len])
    }
    #[inline(always)]
    fn len(&self) -> usize {
        self.len
    }
    #[inline(always)]
    fn clear(&mut self) {
        self.len = 0;
    }
    #[inline(always)]
    fn sort_top(&mut self, from: usize) {
        sort_descending(&mut self.items[from..self.len]);
    }
    #[inline(always)]
    fn top_block(&mut self) -> *mut Entry {
        self.block().as_mut_ptr()
    }
    #[inline(always)]
    fn grow(&mut self, n: usize) {
        ArrayStack::grow(self, n);
    }
}

/// A stack in an uninitialised array in the kernel's frame (the single-ray kernels' stack
/// for every tree within [`ARRAY_STACK`]): no zero fill per query (1 KiB) and no per-thread
/// array to take and put back (a TLS access and its `Option<Box>` tests, ~25 instructions per
/// ray). Slots below `len` are always initialised: [`Stack::push`] writes them, and a kernel
/// that [`Stack::grow`]s has written the slots it counts through [`Stack::top_block`].
pub(super) struct FrameStack<const N: usize> {
    items: [std::mem::MaybeUninit<Entry>; N],
    len: usize,
}

impl<const N: usize> FrameStack<N> {
    #[inline(always)]
    pub(super) fn new() -> Self {
        Self {
            items: [std::mem::MaybeUninit::uninit(); N],
            len: 0,
        }
    }

    /// The entries, from the bottom up (for tests).
    #[cfg(test)]
    pub(super) fn entries(&self) -> Vec<Entry> {
        // SAFETY: the slots below `len` are initialised (the type's invariant).
        self.items[..self.len]
            .iter()
            .map(|e| unsafe { e.assume_init() })
            .collect()
    }
}

impl<const N: usize> Stack for FrameStack<N> {
    #[inline(always)]
    fn push(&mut self, e: Entry) {
        self.items[self.len] = std::mem::MaybeUninit::new(e);
        self.len += 1;
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<Entry> {
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        // SAFETY: the slots below the old `len` are initialised (the type's invariant).
        Some(unsafe { self.items[self.len].assume_init() })
    }
    #[inline(always)]
    fn len(&self) -> usize {
        self.len
    }
    #[inline(always)]
    fn clear(&mut self) {
        self.len = 0;
    }
    #[inline(always)]
    fn sort_top(&mut self, from: usize) {
        let top = &mut self.items[from..self.len];
        // SAFETY: the slots below `len` are initialised (the type's invariant), and
        // `MaybeUninit<Entry>` has `Entry`'s layout.
        let top = unsafe { &mut *(std::ptr::from_mut(top) as *mut [Entry]) };
        sort_descending(top);
    }
    #[inline(always)]
    fn top_block(&mut self) -> *mut Entry {
        let len = self.len;
        self.items[len..len + 8].as_mut_ptr().cast()
    }
    #[inline(always)]
    fn grow(&mut self, n: usize) {
        debug_assert!(n <= 8);
        self.len += n;
    }
}

/// The single-ray kernels' frame stack: the deepest traversal an array stack allows, plus
/// the eight slots of a block store.
type SingleStack = FrameStack<{ ARRAY_STACK + 8 }>;

/// A stack on the heap, for trees too deep for the array stacks: `n` entries (the traversal
/// bound) plus the eight slots of a block store, allocated once per query.
struct HeapStack {
    items: Vec<Entry>,
    len: usize,
}

impl HeapStack {
    fn new(n: usize) -> Self {
        Self {
            items: vec![Entry::default(); n + 8],
            len: 0,
        }
    }
}

impl Stack for HeapStack {
    #[inline(always)]
    fn push(&mut self, e: Entry) {
        self.items[self.len] = e;
        self.len += 1;
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<Entry> {
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        Some(self.items[self.len])
    }
    #[inline(always)]
    fn len(&self) -> usize {
        self.len
    }
    #[inline(always)]
    fn clear(&mut self) {
        self.len = 0;
    }
    #[inline(always)]
    fn sort_top(&mut self, from: usize) {
        sort_descending(&mut self.items[from..self.len]);
    }
    #[inline(always)]
    fn top_block(&mut self) -> *mut Entry {
        let len = self.len;
        self.items[len..len + 8].as_mut_ptr()
    }
    #[inline(always)]
    fn grow(&mut self, n: usize) {
        debug_assert!(n <= 8);
        self.len += n;
    }
}

/// Largest number of entries a traversal of a tree with `depth` node levels can hold: each
/// level on the current path leaves at most 7 siblings, plus the 8 children just pushed.
fn stack_bound(depth: u32) -> usize {
    8 * depth as usize + 8
}

/// Array size used for shallow trees (every realistic scene; deeper ones use the heap); the
/// single-ray kernels keep it uninitialised in their frame ([`FrameStack`]).
const ARRAY_STACK: usize = 128;

/// Closest hit of `ray` with the SSE kernel (the fallback of `traverse_wide.rs`; `Accel`
/// picks the kernel).
pub(crate) fn closest(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
    closest_in::<NodeRay>(bvh, ray)
}

/// Whether anything is hit with `0 < t < ray.t_max`, with the SSE kernel.
pub(crate) fn occluded(bvh: &Bvh, ray: &Ray) -> bool {
    occluded_in::<NodeRay>(bvh, ray)
}

/// Whether the closest-hit kernel visits children in octant order (the default) rather than
/// sorted by entry distance: `STAGELIGHT_TRAVERSAL=sorted` (or `sse-sorted`) at the first
/// query turns the sort back on (and slot order in the single-ray occlusion kernel), for A/B
/// measurements. Both give the same hits.
pub(super) fn octant_order() -> bool {
    static CHOICE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *CHOICE
        .get_or_init(|| !std::env::var("STAGELIGHT_TRAVERSAL").is_ok_and(|v| v.ends_with("sorted")))
}

/// Closest hit of `ray` with the node test `N` (SSE: `NodeRay`, the fallback).
#[inline(always)]
pub(super) fn closest_in<N: NodeTest>(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
    if octant_order() {
        closest_ordered_in::<N, true>(bvh, ray)
    } else {
        closest_ordered_in::<N, false>(bvh, ray)
    }
}

/// [`closest_in`] with the child order fixed: octant order (`OCTANT`) or sorted.
#[inline(always)]
pub(super) fn closest_ordered_in<N: NodeTest, const OCTANT: bool>(
    bvh: &Bvh,
    ray: &Ray,
) -> Option<Hit> {
    if bvh.nodes.is_empty() || !ray_is_valid(ray) {
        return None;
    }
    if stack_bound(bvh.depth) <= ARRAY_STACK {
        closest_with::<_, N, OCTANT>(bvh, ray, SingleStack::new())
    } else {
        closest_with::<_, N, OCTANT>(bvh, ray, HeapStack::new(stack_bound(bvh.depth)))
    }
}

/// Occlusion of `ray` with the node test `N`.
#[inline(always)]
pub(super) fn occluded_in<N: NodeTest>(bvh: &Bvh, ray: &Ray) -> bool {
    if bvh.nodes.is_empty() || !ray_is_valid(ray) {
        return false;
    }
    if octant_order() {
        occluded_ordered_in::<N, true>(bvh, ray)
    } else {
        occluded_ordered_in::<N, false>(bvh, ray)
    }
}

/// [`occluded_in`] with the child order fixed: nearest first in octant order (`OCTANT`) or
/// the last slot first.
#[inline(always)]
fn occluded_ordered_in<N: NodeTest, const OCTANT: bool>(bvh: &Bvh, ray: &Ray) -> bool {
    if stack_bound(bvh.depth) <= ARRAY_STACK {
        occluded_with::<_, N, OCTANT>(bvh, ray, SingleStack::new())
    } else {
        occluded_with::<_, N, OCTANT>(bvh, ray, HeapStack::new(stack_bound(bvh.depth)))
    }
}

/// The ray's octant, the index of [`Node::order`]: bit `a` set when direction component `a`
/// is negative (the sign bit decides, as for the near planes).
#[inline(always)]
pub(super) fn octant(ray: &Ray) -> usize {
    let d = ray.dir.to_array();
    (0..3).fold(0, |o, a| o | usize::from(d[a].is_sign_negative()) << a)
}

#[inline(always)]
pub(super) fn leaf_range(r: u32) -> std::ops::Range<usize> {
    let first = (r & FIRST_MASK) as usize;
    let count = ((r & !LEAF_BIT) >> COUNT_SHIFT) as usize;
    first..first + count
}

/// The single-ray kernels' step after a node in octant order. Of the hit children in `mask`
/// (bit `i` for `child[i]`, entry distance `tn[i]`, nearest first), all but the nearest are
/// prefetched and pushed, farthest first; the nearest is returned, to be visited next. It is
/// not prefetched: its loads are the very next ones, their addresses known.
#[inline(always)]
fn push_all_but_nearest<S: Stack>(
    bvh: &Bvh,
    stack: &mut S,
    mut mask: u32,
    tn: &[f32; 8],
    child: &[u32; 8],
) -> u32 {
    let nearest = mask.trailing_zeros() as usize;
    mask &= mask - 1;
    while mask != 0 {
        let i = 31 - mask.leading_zeros() as usize;
        mask ^= 1 << i;
        prefetch_child(bvh, child[i]);
        stack.push(Entry {
            r: child[i],
            t: tn[i],
        });
    }
    child[nearest]
}

#[inline(always)]
fn closest_with<S: Stack, N: NodeTest, const OCTANT: bool>(
    bvh: &Bvh,
    ray: &Ray,
    mut stack: S,
) -> Option<Hit> {
    let woop = WoopRay::new(ray.origin, ray.dir);
    let nr = N::new(ray, &woop);
    let octant = octant(ray);
    // Until the first hit, t must be < ray.t_max; afterwards (t, prim) must be smaller.
    // The closest candidate so far as (BVH-order index, b1, b2); its original index (in the
    // leaf's lines, already in cache) is read on an exact tie and once at the end.
    let mut best: Option<(usize, f32, f32)> = None;
    let mut best_t = ray.t_max;
    let mut cull = best_t * FAR_SCALE;
    let mut cur = 0u32;
    loop {
        if cur & LEAF_BIT != 0 {
            let range = leaf_range(cur);
            let first = range.start;
            nr.leaf_hits(&woop, &bvh.tris[range], best_t, |j, (t, b1, b2)| {
                let k = first + j;
                let better = t < best_t
                    || (t == best_t
                        && best.is_some_and(|(bk, _, _)| bvh.tris[k].prim < bvh.tris[bk].prim));
                if better {
                    best = Some((k, b1, b2));
                    best_t = t;
                    cull = t * FAR_SCALE;
                }
                false
            });
        } else if OCTANT {
            let node = &bvh.nodes[cur as usize];
            // The nearest goes straight to `cur` (its entry distance is ≤ `cull` by the box
            // test).
            if let Some(next) = nr.visit_ordered(bvh, node, best_t, node.order[octant], &mut stack)
            {
                cur = next;
                continue;
            }
        } else {
            let node = &bvh.nodes[cur as usize];
            let (mut mask, tn) = nr.intersect(node, best_t);
            if mask != 0 {
                let base = stack.len();
                while mask != 0 {
                    let slot = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    prefetch(bvh, node.child[slot]);
                    stack.push(Entry {
                        r: node.child[slot],
                        t: tn[slot],
                    });
                }
                stack.sort_top(base);
            }
        }
        loop {
            match stack.pop() {
                None => {
                    return best.map(|(k, b1, b2)| Hit {
                        t: best_t,
                        prim: bvh.tris[k].prim,
                        b1,
                        b2,
                    })
                }
                Some(e) if e.t <= cull => {
                    cur = e.r;
                    break;
                }
                Some(_) => {}
            }
        }
    }
}

#[inline(always)]
fn occluded_with<S: Stack, N: NodeTest, const OCTANT: bool>(
    bvh: &Bvh,
    ray: &Ray,
    mut stack: S,
) -> bool {
    let woop = WoopRay::new(ray.origin, ray.dir);
    let nr = N::new(ray, &woop);
    let octant = octant(ray);
    let mut cur = 0u32;
    loop {
        if cur & LEAF_BIT != 0 {
            let mut hit = false;
            nr.leaf_hits(
                &woop,
                &bvh.tris[leaf_range(cur)],
                ray.t_max,
                |_, (t, _, _)| {
                    hit = t < ray.t_max;
                    hit
                },
            );
            if hit {
                return true;
            }
        } else if OCTANT {
            // As the closest-hit kernel: the nearest in octant order next, the others pushed
            // farthest first (the nearest occluder is the likeliest to be found early).
            // (The pushed entry distances are not needed.)
            let node = &bvh.nodes[cur as usize];
            if let Some(next) =
                nr.visit_ordered(bvh, node, ray.t_max, node.order[octant], &mut stack)
            {
                cur = next;
                continue;
            }
        } else {
            let node = &bvh.nodes[cur as usize];
            let (mut mask, _) = nr.intersect(node, ray.t_max);
            if mask != 0 {
                // The last slot hit is visited next (it would be on top of the stack), not
                // pushed nor prefetched: its loads are the very next ones.
                let last = 31 - mask.leading_zeros() as usize;
                mask ^= 1 << last;
                while mask != 0 {
                    let slot = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    prefetch(bvh, node.child[slot]);
                    stack.push(Entry {
                        r: node.child[slot],
                        t: 0.0,
                    });
                }
                cur = node.child[last];
                continue;
            }
        }
        match stack.pop() {
            None => return false,
            Some(e) => cur = e.r,
        }
    }
}

/// The state of one closest-hit traversal of the batch kernel, advanced one node or leaf at a
/// time by [`ClosestLane::step`]. It does exactly what [`closest_with`] does, in the same
/// order, so both return identical hits (`batch_equals_single_ray` tests it); the single-ray
/// kernel keeps its own loop because keeping the state in a struct cost it 5–8 %.
struct ClosestLane<S, N, const OCTANT: bool> {
    woop: WoopRay,
    nr: N,
    /// The ray's octant ([`octant`]), for `OCTANT` lanes.
    octant: usize,
    /// The closest candidate so far as (BVH-order index, b1, b2); its original index is
    /// read on an exact tie and once at the end.
    best: Option<(usize, f32, f32)>,
    /// Until the first hit, t must be < ray.t_max; afterwards (t, prim) must be smaller.
    best_t: f32,
    cull: f32,
    /// The node or leaf to process next.
    cur: u32,
    stack: S,
}

impl<N: NodeTest, const OCTANT: bool> ClosestLane<BatchStack, N, OCTANT> {
    #[inline(always)]
    fn new(ray: &Ray, stack: BatchStack) -> Self {
        let woop = WoopRay::new(ray.origin, ray.dir);
        Self {
            nr: N::new(ray, &woop),
            woop,
            octant: octant(ray),
            best: None,
            best_t: ray.t_max,
            cull: ray.t_max * FAR_SCALE,
            cur: 0,
            stack,
        }
    }

    /// Starts over with another ray, keeping the stack's storage.
    #[inline(always)]
    fn restart(&mut self, ray: &Ray) {
        self.woop = WoopRay::new(ray.origin, ray.dir);
        self.nr = N::new(ray, &self.woop);
        self.octant = octant(ray);
        self.best = None;
        self.best_t = ray.t_max;
        self.cull = ray.t_max * FAR_SCALE;
        self.cur = 0;
        self.stack.clear();
    }

    /// Processes `cur` and pops the next node or leaf into it; false when the traversal is
    /// finished.
    #[inline(always)]
    fn step(&mut self, bvh: &Bvh) -> bool {
        let cur = self.cur;
        if cur & LEAF_BIT != 0 {
            let range = leaf_range(cur);
            let first = range.start;
            let (best, best_t, cull) = (&mut self.best, &mut self.best_t, &mut self.cull);
            let limit = *best_t;
            self.nr
                .leaf_hits(&self.woop, &bvh.tris[range], limit, |j, (t, b1, b2)| {
                    let k = first + j;
                    let better = t < *best_t
                        || (t == *best_t
                            && best.is_some_and(|(bk, _, _)| bvh.tris[k].prim < bvh.tris[bk].prim));
                    if better {
                        *best = Some((k, b1, b2));
                        *best_t = t;
                        *cull = t * FAR_SCALE;
                    }
                    false
                });
        } else if OCTANT {
            let node = &bvh.nodes[cur as usize];
            self.nr
                .push_ordered(node, self.best_t, node.order[self.octant], &mut self.stack);
        } else {
            let node = &bvh.nodes[cur as usize];
            let (mut mask, tn) = self.nr.intersect(node, self.best_t);
            if mask != 0 {
                let base = self.stack.len();
                while mask != 0 {
                    let slot = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    self.stack.push(Entry {
                        r: node.child[slot],
                        t: tn[slot],
                    });
                }
                self.stack.sort_top(base);
            }
        }
        loop {
            match self.stack.pop() {
                None => return false,
                Some(e) if e.t <= self.cull => {
                    self.cur = e.r;
                    return true;
                }
                Some(_) => {}
            }
        }
    }

    #[inline(always)]
    fn result(&self, bvh: &Bvh) -> Option<Hit> {
        self.best.map(|(k, b1, b2)| Hit {
            t: self.best_t,
            prim: bvh.tris[k].prim,
            b1,
            b2,
        })
    }
}

/// The state of one occlusion traversal (see [`ClosestLane`]).
struct OcclusionLane<S, N> {
    woop: WoopRay,
    nr: N,
    t_max: f32,
    cur: u32,
    hit: bool,
    stack: S,
}

impl<N: NodeTest> OcclusionLane<BatchStack, N> {
    #[inline(always)]
    fn new(ray: &Ray, stack: BatchStack) -> Self {
        let woop = WoopRay::new(ray.origin, ray.dir);
        Self {
            nr: N::new(ray, &woop),
            woop,
            t_max: ray.t_max,
            cur: 0,
            hit: false,
            stack,
        }
    }

    /// Starts over with another ray, keeping the stack's storage.
    #[inline(always)]
    fn restart(&mut self, ray: &Ray) {
        self.woop = WoopRay::new(ray.origin, ray.dir);
        self.nr = N::new(ray, &self.woop);
        self.t_max = ray.t_max;
        self.cur = 0;
        self.hit = false;
        self.stack.clear();
    }

    /// Processes `cur` and pops the next node or leaf into it; false when the traversal is
    /// finished (a hit was found or nothing is left).
    #[inline(always)]
    fn step(&mut self, bvh: &Bvh) -> bool {
        let cur = self.cur;
        if cur & LEAF_BIT != 0 {
            let t_max = self.t_max;
            let mut hit = false;
            self.nr.leaf_hits(
                &self.woop,
                &bvh.tris[leaf_range(cur)],
                t_max,
                |_, (t, _, _)| {
                    hit = t < t_max;
                    hit
                },
            );
            if hit {
                self.hit = true;
                return false;
            }
        } else {
            let node = &bvh.nodes[cur as usize];
            self.nr.push_all(node, self.t_max, &mut self.stack);
        }
        match self.stack.pop() {
            None => false,
            Some(e) => {
                self.cur = e.r;
                true
            }
        }
    }
}

/// Rays traced interleaved by the batch kernels.
/// 12 measured best on the anchor's incoherent rays (Mrays per CPU-second, one window:
/// 4 lanes 1.99, 8 lanes 2.69, 12 lanes 2.82, 16 lanes 2.78; single ray 1.00).
pub(crate) const BATCH_LANES: usize = 12;

/// Prefetches a node (all four cache lines) or a leaf's triangles (up to three lines): in the
/// single-ray loop kernels every child pushed on the stack, so that its misses are under way
/// while other work goes on.
#[inline(always)]
pub(super) fn prefetch(bvh: &Bvh, r: u32) {
    for p in prefetch_lines(bvh, r) {
        prefetch_line(p);
    }
}

/// The prefetch of one child reference `r`, the one visited next (the single-ray block
/// kernels' child popped next; the node or leaf a batch lane visits at its next turn): four
/// lines from its first byte, a node's whole 256 bytes or a leaf's first triangle and the
/// lines after it (a leaf's ≤ 108 bytes span at most three of them; the rest is a hint
/// about the triangles that follow). One address, selected without a branch, and no
/// clamping to the leaf's end: half the address work of [`prefetch_lines`] (in the batch
/// lanes, about 10 instructions less per step: session 27, `docs/ray-layer.md`).
#[inline(always)]
pub(super) fn prefetch_child(bvh: &Bvh, r: u32) {
    let first = child_first_byte(bvh, r);
    for k in 0..4 {
        prefetch_line(first.wrapping_add(64 * k));
    }
}

/// The first byte of the node or of the leaf's first triangle that `r` references, made
/// without a branch on the leaf bit (wrapping pointer arithmetic, no indexing: see
/// [`prefetch_lines`]).
#[inline(always)]
fn child_first_byte(bvh: &Bvh, r: u32) -> *const u8 {
    const TRI: usize = std::mem::size_of::<LeafTri>();
    let leaf_first = bvh
        .tris
        .as_ptr()
        .cast::<u8>()
        .wrapping_add((r & FIRST_MASK) as usize * TRI) as usize;
    let node = bvh.nodes.as_ptr().wrapping_add(r as usize).cast::<u8>() as usize;
    // All ones for a leaf, zero for a node.
    let leaf = 0usize.wrapping_sub(usize::from(r & LEAF_BIT != 0));
    ((leaf_first & leaf) | (node & !leaf)) as *const u8
}

/// The four addresses [`prefetch`] touches for the reference `r`: a node's four cache lines,
/// or a leaf's first triangle byte, the line after it (at most the last byte) and the last
/// byte of its last triangle, twice (≤ 3 triangles of 40 bytes span at most three lines).
///
/// **Without a branch on the leaf bit**: both the leaf's and the node's addresses are made
/// (wrapping pointer arithmetic, no indexing, so a node reference read as a leaf range or
/// the other way round is harmless) and one is selected with a mask. The branch was
/// mispredicted about one time in three — the batch lanes alternate nodes and leaves
/// unpredictably — and the step that follows branches on the same bit again (cachegrind's
/// branch simulation on the photon pass: 1.0 M mispredicts here and 1.5 M at the step's
/// test, of 3.9 M steps).
#[inline(always)]
fn prefetch_lines(bvh: &Bvh, r: u32) -> [*const u8; 4] {
    const TRI: usize = std::mem::size_of::<LeafTri>();
    let range = leaf_range(r);
    let tris = bvh.tris.as_ptr().cast::<u8>();
    let leaf_first = tris.wrapping_add(range.start * TRI) as usize;
    let leaf_end = tris.wrapping_add(range.end * TRI).wrapping_sub(1) as usize;
    let node = bvh.nodes.as_ptr().wrapping_add(r as usize).cast::<u8>() as usize;
    // All ones for a leaf, zero for a node.
    let leaf = 0usize.wrapping_sub(usize::from(r & LEAF_BIT != 0));
    let first = (leaf_first & leaf) | (node & !leaf);
    let last = (leaf_end & leaf) | (node.wrapping_add(192) & !leaf);
    let line = |k: usize| first.wrapping_add(64 * k).min(last) as *const u8;
    [line(0), line(1), line(2), last as *const u8]
}

/// Closest hits of `rays` into `out` with the SSE node test (the fallback of
/// `traverse_wide.rs`; `Accel` picks the kernel).
pub(crate) fn closest_batch(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>]) {
    closest_batch_in::<NodeRay>(bvh, rays, out);
}

/// Occlusion of `rays` into `out` with the SSE node test.
pub(crate) fn occluded_batch(bvh: &Bvh, rays: &[Ray], out: &mut [bool]) {
    occluded_batch_in::<NodeRay>(bvh, rays, out);
}

/// Closest hits of `rays` into `out`, [`BATCH_LANES`] rays traversed interleaved: each lane
/// advances by one node or leaf in turn, so the cache misses of one ray overlap the work of
/// the others. Results are those of [`closest`], ray by ray, for any node test `N`.
#[inline(always)]
pub(super) fn closest_batch_in<N: NodeTest>(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>]) {
    if N::BATCH_OCTANT && octant_order() {
        closest_batch_ordered_in::<N, true>(bvh, rays, out);
    } else {
        closest_batch_ordered_in::<N, false>(bvh, rays, out);
    }
}

/// [`closest_batch_in`] with the lanes' child order fixed: octant order (`OCTANT`: the
/// default of the block lanes) or sorted by entry distance (the others, and every kernel
/// with `STAGELIGHT_TRAVERSAL=sorted`).
#[inline(always)]
pub(super) fn closest_batch_ordered_in<N: NodeTest, const OCTANT: bool>(
    bvh: &Bvh,
    rays: &[Ray],
    out: &mut [Option<Hit>],
) {
    assert_eq!(rays.len(), out.len(), "one result slot per ray");
    if bvh.nodes.is_empty() || stack_bound(bvh.depth) > ARRAY_STACK {
        for (r, o) in rays.iter().zip(out.iter_mut()) {
            *o = closest_in::<N>(bvh, r);
        }
        return;
    }
    let mut next = 0;
    // Hands out the next valid ray's index; invalid rays are answered on the spot.
    let mut take = |out: &mut [Option<Hit>]| {
        while next < rays.len() {
            let i = next;
            next += 1;
            if ray_is_valid(&rays[i]) {
                return Some(i);
            }
            out[i] = None;
        }
        None
    };
    let mut lanes: [Option<(usize, ClosestLane<BatchStack, N, OCTANT>)>; BATCH_LANES] =
        std::array::from_fn(|_| None);
    for slot in lanes.iter_mut() {
        *slot = take(out).map(|i| (i, ClosestLane::new(&rays[i], ArrayStack::new())));
    }
    let mut active = lanes.iter().filter(|l| l.is_some()).count();
    while active > 0 {
        for slot in lanes.iter_mut() {
            let Some((i, lane)) = slot else { continue };
            if lane.step(bvh) {
                prefetch_child(bvh, lane.cur);
                continue;
            }
            out[*i] = lane.result(bvh);
            match take(out) {
                Some(j) => {
                    lane.restart(&rays[j]);
                    *i = j;
                }
                None => {
                    *slot = None;
                    active -= 1;
                }
            }
        }
    }
}

/// Occlusion of `rays` into `out`, interleaved like [`closest_batch_in`]; results are those
/// of [`occluded`], ray by ray.
#[inline(always)]
pub(super) fn occluded_batch_in<N: NodeTest>(bvh: &Bvh, rays: &[Ray], out: &mut [bool]) {
    assert_eq!(rays.len(), out.len(), "one result slot per ray");
    if bvh.nodes.is_empty() || stack_bound(bvh.depth) > ARRAY_STACK {
        for (r, o) in rays.iter().zip(out.iter_mut()) {
            *o = occluded_in::<N>(bvh, r);
        }
        return;
    }
    let mut next = 0;
    let mut take = |out: &mut [bool]| {
        while next < rays.len() {
            let i = next;
            next += 1;
            if ray_is_valid(&rays[i]) {
                return Some(i);
            }
            out[i] = false;
        }
        None
    };
    let mut lanes: [Option<(usize, OcclusionLane<BatchStack, N>)>; BATCH_LANES] =
        std::array::from_fn(|_| None);
    for slot in lanes.iter_mut() {
        *slot = take(out).map(|i| (i, OcclusionLane::new(&rays[i], ArrayStack::new())));
    }
    let mut active = lanes.iter().filter(|l| l.is_some()).count();
    while active > 0 {
        for slot in lanes.iter_mut() {
            let Some((i, lane)) = slot else { continue };
            if lane.step(bvh) {
                prefetch_child(bvh, lane.cur);
                continue;
            }
            out[*i] = lane.hit;
            match take(out) {
                Some(j) => {
                    lane.restart(&rays[j]);
                    *i = j;
                }
                None => {
                    *slot = None;
                    active -= 1;
                }
            }
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn sort_puts_nearest_on_top() {
        let mut s = ArrayStack::<8>::new();
        for t in [3.0, 1.0, 2.0, 0.5] {
            s.push(Entry { r: 0, t });
        }
        s.sort_top(1);
        let order: Vec<f32> = std::iter::from_fn(|| s.pop().map(|e| e.t)).collect();
        assert_eq!(order, vec![0.5, 1.0, 2.0, 3.0]);
    }

    /// The branch-free prefetch addresses are the ones the branching version took, for every
    /// node and every leaf (1, 2 and 3 triangles) of a tree; [`prefetch_child`]'s first line
    /// is the same first byte.
    #[test]
    fn prefetch_lines_are_the_branching_ones() {
        fn branching(bvh: &Bvh, r: u32) -> [*const u8; 4] {
            if r & LEAF_BIT != 0 {
                let range = leaf_range(r);
                let first = std::ptr::from_ref(&bvh.tris[range.start]).cast::<u8>();
                let last = std::ptr::from_ref(&bvh.tris[range.end - 1]).cast::<u8>();
                let end = last.wrapping_add(std::mem::size_of::<LeafTri>() - 1);
                let mid = first.wrapping_add(64).min(end);
                [first, mid, end, end]
            } else {
                let node = std::ptr::from_ref(&bvh.nodes[r as usize]).cast::<u8>();
                [0, 64, 128, 192].map(|o| node.wrapping_add(o))
            }
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x51_7cc1_b727_220au64);
        let tris: Vec<[Vec3; 3]> = (0..5000)
            .map(|_| {
                let c = Vec3::new(rnd(), rnd(), rnd()) * 4.0;
                [
                    c,
                    c + Vec3::new(0.1, rnd() * 0.1, 0.0),
                    c + Vec3::new(0.0, 0.1, rnd() * 0.1),
                ]
            })
            .collect();
        let mut counts = [0usize; 4];
        for q in [
            crate::settings::BvhQuality::Fast,
            crate::settings::BvhQuality::Medium,
        ] {
            let bvh = super::super::bvh::build(&tris, q);
            let children = bvh
                .nodes
                .iter()
                .flat_map(|n| n.child)
                .filter(|&c| c != EMPTY_CHILD);
            for r in std::iter::once(0).chain(children) {
                assert_eq!(prefetch_lines(&bvh, r), branching(&bvh, r), "{r:#x}");
                // The single-ray kernels' prefetch starts at the same first byte.
                assert_eq!(child_first_byte(&bvh, r), branching(&bvh, r)[0], "{r:#x}");
                let kind = if r & LEAF_BIT != 0 {
                    leaf_range(r).len()
                } else {
                    0
                };
                counts[kind] += 1;
            }
        }
        assert!(counts.iter().all(|&c| c > 0), "{counts:?}");
    }

    #[test]
    fn stack_bound_covers_eight_per_level() {
        assert!(stack_bound(1) >= 8);
        assert!(stack_bound(15) <= ARRAY_STACK);
        assert!(stack_bound(16) > ARRAY_STACK);
    }

    fn hit_bits(h: Option<Hit>) -> Option<[u32; 4]> {
        h.map(|h| [h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()])
    }

    /// A soup of 3,000 small random triangles, and 3,000 nested, shrinking triangles (a
    /// hierarchy far deeper than the array stack allows).
    pub(in crate::accel) fn soup_and_nested(rnd: &mut impl FnMut() -> f32) -> [Vec<[Vec3; 3]>; 2] {
        let soup: Vec<[Vec3; 3]> = (0..3000)
            .map(|_| {
                let c = Vec3::new(rnd(), rnd(), rnd()) * 4.0;
                [
                    c,
                    c + Vec3::new(rnd(), rnd(), rnd()) * 0.3,
                    c + Vec3::new(rnd(), rnd(), rnd()) * 0.3,
                ]
            })
            .collect();
        let nested: Vec<[Vec3; 3]> = (0..3000)
            .map(|i| {
                let s = 0.997f32.powi(i);
                [
                    Vec3::new(-s, -s, i as f32 * 1e-3),
                    Vec3::new(s, -s, 0.0),
                    Vec3::new(0.0, s, 0.0),
                ]
            })
            .collect();
        [soup, nested]
    }

    /// `n` rays from around the meshes of [`soup_and_nested`]: every other one aimed at the
    /// nested triangles around the origin, every third with a finite `t_max`.
    pub(in crate::accel) fn test_rays(rnd: &mut impl FnMut() -> f32, n: usize) -> Vec<Ray> {
        (0..n)
            .map(|i| {
                let origin = Vec3::new(rnd(), rnd(), rnd()) * 5.0;
                let dir = if i % 2 == 0 {
                    Vec3::new(rnd(), rnd(), rnd().abs() * 3.0) - origin
                } else {
                    Vec3::new(rnd(), rnd(), rnd())
                };
                let t_max = if i % 3 == 0 {
                    rnd().abs() * 4.0
                } else {
                    f32::INFINITY
                };
                Ray { origin, dir, t_max }
            })
            .collect()
    }

    /// The batch kernels give the single-ray results bit for bit, for batches shorter and
    /// longer than the lane count, with invalid rays and finite `t_max` mixed in, and on a
    /// hierarchy too deep for the array stack (the batch falls back to single rays).
    #[test]
    fn batch_equals_single_ray() {
        let mut rnd = crate::accel::test_random::signed_uniform(0x2545_f491_4f6c_dd1du64);
        let [soup, nested] = soup_and_nested(&mut rnd);
        let mut rays = test_rays(&mut rnd, 2000);
        rays[5].dir = Vec3::ZERO;
        rays[17].origin.x = f32::NAN;
        rays[40].t_max = -1.0;
        for tris in [soup, nested] {
            let bvh = super::super::bvh::build(&tris, crate::settings::BvhQuality::Medium);
            for n in [0, 1, 5, BATCH_LANES, BATCH_LANES + 1, 100, rays.len()] {
                let rays = &rays[..n];
                let mut hits = vec![None; n];
                let mut occ = vec![true; n];
                let mut octant_hits = vec![None; n];
                closest_batch(&bvh, rays, &mut hits);
                closest_batch_ordered_in::<NodeRay, true>(&bvh, rays, &mut octant_hits);
                occluded_batch(&bvh, rays, &mut occ);
                for (i, r) in rays.iter().enumerate() {
                    assert_eq!(hit_bits(hits[i]), hit_bits(closest(&bvh, r)), "ray {i}");
                    // The lanes in octant order (the generic push): the same hit.
                    assert_eq!(hit_bits(octant_hits[i]), hit_bits(hits[i]), "ray {i}");
                    // Octant order and sorted children: the same hit.
                    assert_eq!(
                        hit_bits(closest_ordered_in::<NodeRay, true>(&bvh, r)),
                        hit_bits(closest_ordered_in::<NodeRay, false>(&bvh, r)),
                        "ray {i}"
                    );
                    assert_eq!(occ[i], occluded(&bvh, r), "ray {i}");
                }
            }
            assert!(hits_some(&bvh, &rays));
        }
    }

    /// The occlusion kernel answers the same in octant order (nearest first, the default) as
    /// in slot order, and both say whether the closest-hit kernel finds a hit, on a soup and
    /// on a hierarchy deeper than the array stack.
    #[test]
    fn occlusion_orders_agree_with_closest_hit() {
        let mut rnd = crate::accel::test_random::signed_uniform(0x6a09_e667_f3bc_c908u64);
        let [soup, nested] = soup_and_nested(&mut rnd);
        let rays = test_rays(&mut rnd, 3000);
        for tris in [soup, nested] {
            let bvh = super::super::bvh::build(&tris, crate::settings::BvhQuality::Medium);
            let (mut hit, mut missed) = (0, 0);
            for (i, r) in rays.iter().enumerate() {
                let octant = occluded_ordered_in::<NodeRay, true>(&bvh, r);
                assert_eq!(
                    octant,
                    occluded_ordered_in::<NodeRay, false>(&bvh, r),
                    "ray {i}"
                );
                assert_eq!(octant, closest(&bvh, r).is_some(), "ray {i}");
                if octant {
                    hit += 1;
                } else {
                    missed += 1;
                }
            }
            assert!(hit > 100 && missed > 100, "{hit} occluded, {missed} not");
        }
    }

    /// The frame stack (uninitialised slots) keeps exactly what the zero-filled array stack
    /// keeps through the same pushes, pops, block stores with `grow`, and sorts.
    #[test]
    fn frame_stack_equals_array_stack() {
        let mut rnd = crate::accel::test_random::signed_uniform(0x9e37_79b9_7f4a_7c15u64);
        let mut frame = FrameStack::<{ 64 + 8 }>::new();
        let mut array = ArrayStack::<{ 64 + 8 }>::new();
        let (mut pops, mut blocks) = (0, 0);
        for step in 0..20_000u32 {
            let x = rnd();
            let e = Entry {
                r: step,
                t: x * 10.0,
            };
            if x < -0.3 && frame.len() > 0 {
                let (a, b) = (frame.pop().unwrap(), array.pop().unwrap());
                assert_eq!((a.r, a.t.to_bits()), (b.r, b.t.to_bits()));
                pops += 1;
            } else if x < 0.3 && frame.len() < 64 {
                frame.push(e);
                array.push(e);
            } else if frame.len() <= 56 {
                let n = (step % 9) as usize;
                for s in [&mut frame as &mut dyn Stack, &mut array] {
                    let block = s.top_block();
                    for j in 0..n {
                        let t = e.t + j as f32;
                        // SAFETY: `top_block` points at eight writable slots; j < 8.
                        unsafe {
                            block.add(j).write(Entry {
                                r: step + j as u32,
                                t,
                            })
                        };
                    }
                    s.grow(n);
                    if step % 7 == 0 {
                        let from = s.len() - n;
                        s.sort_top(from);
                    }
                }
                blocks += 1;
            } else {
                frame.clear();
                array.clear();
            }
            assert_eq!(frame.len(), array.len());
            let bits = |v: &[Entry]| v.iter().map(|e| (e.r, e.t.to_bits())).collect::<Vec<_>>();
            assert_eq!(bits(&frame.entries()), bits(array.entries()));
        }
        assert!(pops > 1000 && blocks > 1000, "{pops} {blocks}");
    }

    fn hits_some(bvh: &Bvh, rays: &[Ray]) -> bool {
        rays.iter().filter(|r| closest(bvh, r).is_some()).count() > 10
    }

    /// Prefetching the last node and the last leaf (addresses at the very end of the arrays)
    /// is harmless.
    #[test]
    fn prefetch_of_last_node_and_leaf() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let bvh = super::super::bvh::build(&[tri], crate::settings::BvhQuality::Fast);
        let last_node = bvh.nodes.len() as u32 - 1;
        prefetch(&bvh, last_node);
        prefetch(
            &bvh,
            LEAF_BIT | (1 << COUNT_SHIFT) | (bvh.tris.len() as u32 - 1),
        );
        prefetch(&bvh, bvh.nodes[0].child[0]);
    }

    #[test]
    fn nan_slab_from_origin_on_plane_is_ignored() {
        // One child box [0,1]³; a ray in the plane x = 0 moving along +y from below.
        let mut node = Node::EMPTY;
        node.set_child(0, 0, glam::Vec3::ZERO, glam::Vec3::ONE);
        for (o, d) in [
            (glam::Vec3::new(0.0, -1.0, 0.5), glam::Vec3::Y),
            (glam::Vec3::new(1.0, -1.0, 1.0), glam::Vec3::Y),
            (
                glam::Vec3::new(0.0, -1.0, 0.5),
                glam::Vec3::new(-0.0, 1.0, 0.0),
            ),
        ] {
            let nr = NodeRay::new(&Ray {
                origin: o,
                dir: d,
                t_max: f32::INFINITY,
            });
            assert_eq!(nr.intersect(&node, f32::INFINITY).0, 1, "{o} {d}");
        }
        let outside = NodeRay::new(&Ray {
            origin: glam::Vec3::new(1.0f32.next_up(), -1.0, 0.5),
            dir: glam::Vec3::Y,
            t_max: f32::INFINITY,
        });
        assert_eq!(outside.intersect(&node, f32::INFINITY).0, 0);
    }
}
