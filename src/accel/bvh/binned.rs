//! stagelight's own builder of the binary hierarchy: top-down binned SAH (32 centroid bins
//! per axis; an exact sweep over the three axes for nodes of at most `SWEEP_MAX` triangles),
//! leaves of one or two triangles, written straight into obvhs's `Bvh2` layout for
//! `collapse.rs`.
//!
//! * **Parallel and deterministic**: subtrees above `PARALLEL_PRIMS` triangles go to
//!   `rayon::join`, large nodes bin in parallel chunks; bins merge by min/max and integer
//!   counts (exact in any order), so the splits, and hence the tree bytes, are the same at
//!   any thread count. Each parallel subtree owns a fixed slice of the node array (`2n − 2`
//!   slots for the descendants of a node of `n` triangles, the most they can need).
//! * **Depth-first layout**: a node's two children are adjacent, followed by the left
//!   child's descendants, then the right child's, so the collapse walks memory in order. A
//!   subtree built on one thread is packed: the right child's descendants follow the left
//!   child's directly, with no slots left for leaves of two triangles that could have split,
//!   so it fills a prefix of its slice (about 60 %; session 34, `docs/ray-layer.md`).
//! * **Exact boxes**: a leaf's box is its triangles' min/max, an inner node's the union of
//!   its children's, as `collapse.rs` requires.
//! * **Extreme geometry**: SAH costs that overflow `f32` (extents around 1e19 and beyond) or
//!   subtrees deeper than `SAH_DEPTH` fall back to a median split over the bins (or over
//!   positions when all centroids share one bin), so every split makes progress and the
//!   recursion stays shallow.

use glam::Vec3A;
use obvhs::{
    aabb::Aabb,
    bvh2::{node::Bvh2Node, Bvh2},
};
use rayon::prelude::*;

/// Centroid bins per axis.
const BINS: usize = 32;
/// Fewer bins for smaller nodes (`SMALL_BINS` up to `SMALL_NODE` triangles, then
/// `MID_BINS` up to `MID_NODE`): a node's bins are cleared and swept whatever its size.
const SMALL_BINS: usize = 8;
const SMALL_NODE: usize = 32;
const MID_BINS: usize = 16;
const MID_NODE: usize = 128;
/// Nodes with at most this many triangles are split by an exact sweep instead of bins.
const SWEEP_MAX: usize = 8;
/// Subtrees of at most this many triangles are binary leaves (the collapse decides how the
/// triangles of neighbouring leaves share 8-wide leaves of up to three).
const LEAF_MAX: usize = 2;
/// Subtrees with more triangles than this build their two halves in parallel.
const PARALLEL_PRIMS: usize = 4096;
/// Nodes with more triangles than this bin in parallel chunks of `BIN_CHUNK`.
const PARALLEL_BINNING: usize = 1 << 16;
const BIN_CHUNK: usize = 1 << 14;
/// Below this depth splits minimise the SAH; deeper ones split at the median.
const SAH_DEPTH: u32 = 48;
/// Nodes with at least this many triangles bin into two sets of bins (see `Bins::add`).
const DUAL_BINNING: usize = 256;

/// An axis-aligned box: a triangle's exact box is the builder's input.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bounds {
    lo: Vec3A,
    hi: Vec3A,
}

impl Bounds {
    pub(super) const EMPTY: Bounds = Bounds {
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
    };

    /// The box of the points `lo` and `hi` (`lo ≤ hi` on every axis).
    pub(crate) fn new(lo: Vec3A, hi: Vec3A) -> Bounds {
        Bounds { lo, hi }
    }

    #[inline(always)]
    pub(super) fn union(self, o: Bounds) -> Bounds {
        Bounds {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    #[inline(always)]
    pub(super) fn grow(&mut self, p: Vec3A) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }

    #[inline(always)]
    fn half_area(self) -> f32 {
        let d = self.hi - self.lo;
        (d.x + d.y) * d.z + d.x * d.y
    }

    /// The centre, halved before the sum so that it cannot overflow.
    #[inline(always)]
    pub(super) fn centroid(self) -> Vec3A {
        self.lo * 0.5 + self.hi * 0.5
    }

    /// The bits of the box's six planes (for tests comparing boxes exactly).
    #[cfg(test)]
    pub(super) fn bits(self) -> [u32; 6] {
        let [a, b, c] = self.lo.to_array().map(f32::to_bits);
        let [d, e, f] = self.hi.to_array().map(f32::to_bits);
        [a, b, c, d, e, f]
    }

    fn node(self, prim_count: u32, first_index: u32) -> Bvh2Node {
        Bvh2Node::new(
            Aabb {
                min: self.lo,
                max: self.hi,
            },
            prim_count,
            first_index,
        )
    }
}

/// Maps centroids to `N` bins over a node's centroid bounds.
#[derive(Clone, Copy)]
struct BinMap<const N: usize> {
    origin: Vec3A,
    scale: Vec3A,
}

impl<const N: usize> BinMap<N> {
    const POWER_OF_TWO: () = assert!(N.is_power_of_two());

    fn new(centroids: Bounds) -> Self {
        let () = Self::POWER_OF_TWO;
        let extent = centroids.hi - centroids.lo;
        let scale = Vec3A::from_array(extent.to_array().map(|e| {
            if e > 0.0 && e.is_finite() {
                N as f32 / e
            } else {
                0.0
            }
        }));
        Self {
            origin: centroids.lo,
            scale,
        }
    }

    /// The bin of `c` on each axis (NaN from `inf · 0` maps to bin 0): the position is
    /// clamped to `[0, N − 1]` in `f32` and truncated by one vector conversion, which is
    /// what the saturating casts `t as u32` and `.min(N − 1)` give, lane by lane.
    #[inline(always)]
    fn bins(&self, c: Vec3A) -> [usize; 3] {
        let t = (c - self.origin) * self.scale;
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{
                __m128, _mm_cvtsi128_si32 as lane0, _mm_cvttps_epi32, _mm_max_ps, _mm_min_ps,
                _mm_set1_ps, _mm_setzero_ps, _mm_shuffle_epi32 as shuffle,
            };
            // SAFETY: SSE and SSE2 are part of the x86_64 baseline. `maxps` returns its
            // second operand when either is NaN, so NaN becomes 0.
            let b = unsafe {
                let t = _mm_max_ps(__m128::from(t), _mm_setzero_ps());
                let b = _mm_cvttps_epi32(_mm_min_ps(t, _mm_set1_ps((N - 1) as f32)));
                [lane0(b), lane0(shuffle::<1>(b)), lane0(shuffle::<2>(b))]
            };
            // `N` is a power of two and `b < N` already: the mask only tells the compiler,
            // which then drops the bounds checks of the bin updates.
            b.map(|b| b as usize & (N - 1))
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            t.as_uvec3().to_array().map(|b| (b as usize).min(N - 1))
        }
    }

    /// Whether `c` falls in a bin below `bin` on `axis`, for an axis a split was chosen on:
    /// its scale is finite and positive and `c − origin` is finite and not negative, so
    /// `t < bin` is `floor(t) < bin`, the test [`Self::bins`] implies.
    #[inline(always)]
    fn below(&self, c: Vec3A, axis: usize, bin: f32) -> bool {
        (c[axis] - self.origin[axis]) * self.scale[axis] < bin
    }
}

/// Boxes and counts of the triangles in each of `N` bins, per axis.
#[derive(Clone)]
struct Bins<const N: usize> {
    bounds: [[Bounds; N]; 3],
    counts: [[u32; N]; 3],
}

impl<const N: usize> Bins<N> {
    fn new() -> Self {
        Self {
            bounds: [[Bounds::EMPTY; N]; 3],
            counts: [[0; N]; 3],
        }
    }

    /// Bins `refs`. Consecutive triangles often fall in the same bins (the mesh order, and
    /// the partitions, keep neighbours together), so each bin update would wait for the
    /// previous one's store: above `DUAL_BINNING` triangles, even and odd ones go to two
    /// sets of bins, merged at the end (min/max and integer counts: the same bins).
    fn add(&mut self, map: &BinMap<N>, refs: &[Bounds]) {
        if refs.len() < DUAL_BINNING {
            for &r in refs {
                self.put(map, r);
            }
            return;
        }
        let mut odd = Self::new();
        let mut pairs = refs.chunks_exact(2);
        for pair in &mut pairs {
            self.put(map, pair[0]);
            odd.put(map, pair[1]);
        }
        for &r in pairs.remainder() {
            self.put(map, r);
        }
        self.merge_from(&odd);
    }

    #[inline(always)]
    fn put(&mut self, map: &BinMap<N>, r: Bounds) {
        let bins = map.bins(r.centroid());
        for ((bounds, counts), b) in self.bounds.iter_mut().zip(&mut self.counts).zip(bins) {
            bounds[b] = bounds[b].union(r);
            counts[b] += 1;
        }
    }

    fn merge_from(&mut self, o: &Self) {
        for axis in 0..3 {
            for b in 0..N {
                self.bounds[axis][b] = self.bounds[axis][b].union(o.bounds[axis][b]);
                self.counts[axis][b] += o.counts[axis][b];
            }
        }
    }

    fn merge(mut self, o: Self) -> Self {
        self.merge_from(&o);
        self
    }
}

/// How a node is split: on `axis`, bins below `bin` go left.
struct BinSplit {
    axis: usize,
    bin: usize,
    left: Bounds,
    right: Bounds,
}

/// Builds the binary hierarchy over `refs` (each triangle's exact box, indexed by the
/// primitive index the hierarchy reports).
#[cfg(test)]
pub(crate) fn build(refs: Vec<Bounds>) -> Bvh2 {
    let (bounds, centroids) = refs
        .par_iter()
        .fold(
            || (Bounds::EMPTY, Bounds::EMPTY),
            |(b, c), r| {
                let mut c = c;
                c.grow(r.centroid());
                (b.union(*r), c)
            },
        )
        .reduce(
            || (Bounds::EMPTY, Bounds::EMPTY),
            |a, b| (a.0.union(b.0), a.1.union(b.1)),
        );
    build_bounded(refs, bounds, centroids)
}

/// [`build`] given the union of the boxes (`bounds`) and the bounds of their centroids.
pub(super) fn build_bounded(refs: Vec<Bounds>, bounds: Bounds, centroids: Bounds) -> Bvh2 {
    let builder = Builder {
        packed: PARALLEL_PRIMS,
    };
    builder.build(refs, bounds, centroids)
}

/// How a hierarchy is laid out: subtrees of at most `packed` triangles (those built on one
/// thread) are packed ([`Builder::packed`]); larger ones own `2n − 2` slots each.
struct Builder {
    packed: usize,
}

impl Builder {
    fn build(&self, mut refs: Vec<Bounds>, bounds: Bounds, centroids: Bounds) -> Bvh2 {
        let n = refs.len();
        assert!(n > 0);
        let mut ids: Vec<u32> = (0..n as u32).collect();
        // `2n − 1` slots, the size with one triangle per leaf: every subtree above `packed`
        // triangles owns a slice of that size, and the slots its leaves of two triangles do not
        // use stay zero (the default node), as do the tails of packed subtrees. Zeroed pages from
        // the allocator: no 100 MB fill pass on a million triangles, and pages nothing is written
        // to are never faulted in (4 KiB pages: a temporary, not advised as huge, see
        // `huge_pages.rs`).
        let mut nodes: Vec<Bvh2Node> = bytemuck::zeroed_vec(2 * n - 1);
        if n <= LEAF_MAX {
            nodes[0] = bounds.node(n as u32, 0);
        } else {
            nodes[0] = bounds.node(0, 1);
            let part = Part {
                refs: &mut refs,
                ids: &mut ids,
                first: 0,
                centroids,
                depth: 0,
            };
            self.node(part, &mut nodes[1..], 1);
        }
        Bvh2 {
            nodes,
            primitive_indices: ids,
            ..Bvh2::default()
        }
    }

    /// Splits the node of `part` (at least two triangles) and writes its descendants into
    /// `out` (`2n − 2` nodes, the first at global index `base`): the two children, then the
    /// left child's descendants, then the right child's.
    fn node(&self, part: Part<'_>, out: &mut [Bvh2Node], base: u32) {
        let n = part.len();
        debug_assert!(n >= 2 && out.len() == 2 * n - 2);
        if n <= self.packed {
            self.packed(part, out, base);
            return;
        }
        let ([left_box, right_box], [left, right]) = part.split();
        let (pair, rest) = out.split_at_mut(2);
        let (left_out, right_out) = rest.split_at_mut(2 * left.len() - 2);
        let left_base = base + 2;
        let right_base = left_base + left_out.len() as u32;
        pair[0] = left.child(left_box, left_base);
        pair[1] = right.child(right_box, right_base);
        rayon::join(
            || {
                if left.len() > LEAF_MAX {
                    self.node(left, left_out, left_base);
                }
            },
            || {
                if right.len() > LEAF_MAX {
                    self.node(right, right_out, right_base);
                }
            },
        );
    }

    /// [`Builder::node`] for a subtree built on one thread: its descendants are written
    /// packed at the start of `out` (the two children, the left child's descendants, then
    /// the right child's, with no room left for leaves that could have split), and their
    /// number is returned. The rest of `out` is not touched — about 40 % of the `2n − 2`
    /// slots, since most leaves hold two triangles — so its 4 KiB pages are never faulted
    /// in, and the collapse reads the tree from fewer pages.
    fn packed(&self, part: Part<'_>, out: &mut [Bvh2Node], base: u32) -> usize {
        debug_assert!(part.len() >= 2 && out.len() >= 2 * part.len() - 2);
        let ([left_box, right_box], [left, right]) = part.split();
        let left_base = base + 2;
        out[0] = left.child(left_box, left_base);
        let mut used = 2;
        if left.len() > LEAF_MAX {
            used += self.packed(left, &mut out[2..], left_base);
        }
        let right_base = base + used as u32;
        out[1] = right.child(right_box, right_base);
        if right.len() > LEAF_MAX {
            used += self.packed(right, &mut out[used..], right_base);
        }
        used
    }
}

/// The triangles of one node of the hierarchy being built: their boxes and ids (reordered in
/// place by the splits), the leaf-order index of the first, the bounds of their centroids and
/// the node's depth.
struct Part<'a> {
    refs: &'a mut [Bounds],
    ids: &'a mut [u32],
    first: u32,
    centroids: Bounds,
    depth: u32,
}

impl<'a> Part<'a> {
    fn len(&self) -> usize {
        self.refs.len()
    }

    /// Splits the node in two ([`split`]): the children's boxes and parts.
    fn split(self) -> ([Bounds; 2], [Part<'a>; 2]) {
        let Part {
            refs,
            ids,
            first,
            centroids,
            depth,
        } = self;
        let (nl, left, right, lc, rc) = split(refs, ids, centroids, depth);
        let (lrefs, rrefs) = refs.split_at_mut(nl);
        let (lids, rids) = ids.split_at_mut(nl);
        let part = |refs, ids, first, centroids| Part {
            refs,
            ids,
            first,
            centroids,
            depth: depth + 1,
        };
        (
            [left, right],
            [
                part(lrefs, lids, first, lc),
                part(rrefs, rids, first + nl as u32, rc),
            ],
        )
    }

    /// This part's node, of box `bounds`, in its parent's pair: a leaf of its triangles when
    /// it has at most `LEAF_MAX`, else an inner node whose children start at `children`.
    fn child(&self, bounds: Bounds, children: u32) -> Bvh2Node {
        if self.len() <= LEAF_MAX {
            bounds.node(self.len() as u32, self.first)
        } else {
            bounds.node(0, children)
        }
    }
}

/// The split of a node: its left count, both boxes and both centroid bounds (a sweep for
/// small nodes, else binned with as many bins as the node's size calls for).
#[inline(always)]
fn split(
    refs: &mut [Bounds],
    ids: &mut [u32],
    centroids: Bounds,
    depth: u32,
) -> (usize, Bounds, Bounds, Bounds, Bounds) {
    let n = refs.len();
    if n <= SWEEP_MAX {
        let (nl, left, right) = sweep(refs, ids);
        (nl, left, right, Bounds::EMPTY, Bounds::EMPTY)
    } else if n <= SMALL_NODE {
        split_binned::<SMALL_BINS>(refs, ids, centroids, depth)
    } else if n <= MID_NODE {
        split_binned::<MID_BINS>(refs, ids, centroids, depth)
    } else {
        split_binned::<BINS>(refs, ids, centroids, depth)
    }
}

/// Splits a node over `N` bins and partitions its slices: returns the left count, both
/// boxes and both centroid bounds.
fn split_binned<const N: usize>(
    refs: &mut [Bounds],
    ids: &mut [u32],
    centroids: Bounds,
    depth: u32,
) -> (usize, Bounds, Bounds, Bounds, Bounds) {
    let map = BinMap::<N>::new(centroids);
    match binned_split(refs, &map, depth) {
        Some(s) => {
            let (nl, lc, rc) = partition(refs, ids, &map, s.axis, s.bin);
            (nl, s.left, s.right, lc, rc)
        }
        None => {
            // All centroids in one bin on every axis: halve by position.
            let nl = refs.len() / 2;
            let fold = |r: &[Bounds]| {
                r.iter()
                    .fold((Bounds::EMPTY, Bounds::EMPTY), |(b, mut c), x| {
                        c.grow(x.centroid());
                        (b.union(*x), c)
                    })
            };
            let (left, lc) = fold(&refs[..nl]);
            let (right, rc) = fold(&refs[nl..]);
            (nl, left, right, lc, rc)
        }
    }
}

/// The binned split of a node: least SAH cost (`A_l·n_l + A_r·n_r`) above `SAH_DEPTH`,
/// else (or when every cost overflows) the bin boundary nearest the median on the axis with
/// the most occupied bins. `None` when every axis has a single occupied bin.
#[inline(never)]
fn binned_split<const N: usize>(refs: &[Bounds], map: &BinMap<N>, depth: u32) -> Option<BinSplit> {
    let bins = if refs.len() > PARALLEL_BINNING {
        refs.par_chunks(BIN_CHUNK)
            .fold(Bins::<N>::new, |mut bins, chunk| {
                bins.add(map, chunk);
                bins
            })
            .reduce(Bins::new, Bins::merge)
    } else {
        let mut bins = Bins::<N>::new();
        bins.add(map, refs);
        bins
    };
    let n = refs.len() as u32;
    let mut best: Option<(f32, usize, usize)> = None;
    if depth < SAH_DEPTH {
        for axis in 0..3 {
            // Right sides: area and count of bins b.. for every b.
            let mut right_area = [0.0f32; N];
            let mut acc = Bounds::EMPTY;
            for b in (1..N).rev() {
                acc = acc.union(bins.bounds[axis][b]);
                right_area[b] = acc.half_area();
            }
            let (mut acc, mut count) = (Bounds::EMPTY, 0u32);
            for (b, &right) in right_area.iter().enumerate().skip(1) {
                acc = acc.union(bins.bounds[axis][b - 1]);
                count += bins.counts[axis][b - 1];
                if count == 0 || count == n {
                    continue;
                }
                let cost = acc.half_area() * count as f32 + right * (n - count) as f32;
                if cost < best.map_or(f32::INFINITY, |(c, _, _)| c) {
                    best = Some((cost, axis, b));
                }
            }
        }
    }
    let (axis, bin) = match best {
        Some((_, axis, bin)) => (axis, bin),
        None => {
            // Median: the axis with the most occupied bins, the boundary nearest n/2.
            let occupied = |axis: usize| bins.counts[axis].iter().filter(|&&c| c > 0).count();
            let axis = (0..3).max_by_key(|&a| (occupied(a), 3 - a))?;
            if occupied(axis) < 2 {
                return None;
            }
            let mut count = 0u32;
            let mut pick = (u32::MAX, 0);
            for b in 1..N {
                count += bins.counts[axis][b - 1];
                if count == 0 || count == n {
                    continue;
                }
                let off = (2 * count).abs_diff(n);
                if off < pick.0 {
                    pick = (off, b);
                }
            }
            (axis, pick.1)
        }
    };
    let fold = |range: std::ops::Range<usize>| {
        range.fold(Bounds::EMPTY, |acc, b| acc.union(bins.bounds[axis][b]))
    };
    Some(BinSplit {
        axis,
        bin,
        left: fold(0..bin),
        right: fold(bin..N),
    })
}

/// Moves the triangles whose centroid falls in a bin below `bin` on `axis` to the front
/// (Hoare: scan from both ends, one swap per misplaced pair); returns their count and the
/// centroid bounds of both sides.
fn partition<const N: usize>(
    refs: &mut [Bounds],
    ids: &mut [u32],
    map: &BinMap<N>,
    axis: usize,
    bin: usize,
) -> (usize, Bounds, Bounds) {
    let bin = bin as f32;
    let (mut lc, mut rc) = (Bounds::EMPTY, Bounds::EMPTY);
    let (mut i, mut j) = (0, refs.len());
    loop {
        while i < j {
            let c = refs[i].centroid();
            if !map.below(c, axis, bin) {
                break;
            }
            lc.grow(c);
            i += 1;
        }
        while i < j {
            let c = refs[j - 1].centroid();
            if map.below(c, axis, bin) {
                break;
            }
            rc.grow(c);
            j -= 1;
        }
        if i >= j {
            return (i, lc, rc);
        }
        // `refs[i]` goes right, `refs[j − 1]` left.
        lc.grow(refs[j - 1].centroid());
        rc.grow(refs[i].centroid());
        refs.swap(i, j - 1);
        ids.swap(i, j - 1);
        i += 1;
        j -= 1;
    }
}

/// Exact SAH split of a small node: on each axis the triangles sorted by centroid (ties by
/// position), every split position costed; the slices are reordered by the best axis's order.
/// Returns the left count and both boxes.
fn sweep(refs: &mut [Bounds], ids: &mut [u32]) -> (usize, Bounds, Bounds) {
    let n = refs.len();
    let mut best = (f32::INFINITY, 0usize, n / 2);
    let mut orders = [[0u8; SWEEP_MAX]; 3];
    let mut centroid = [Vec3A::ZERO; SWEEP_MAX];
    for (c, r) in centroid.iter_mut().zip(refs.iter()) {
        *c = r.centroid();
    }
    for (axis, order) in orders.iter_mut().enumerate() {
        let order = &mut order[..n];
        // Stable sort by centroid (`total_cmp`; ties keep their positions) as ranks: one
        // distinct integer per triangle, (total-order key, position), and each triangle's
        // rank is the number of smaller ones.
        let keys: [u64; SWEEP_MAX] = std::array::from_fn(|k| {
            let bits = centroid[k][axis].to_bits() as i32;
            let total = (bits ^ (((bits >> 31) as u32) >> 1) as i32) as u32 ^ 1 << 31;
            u64::from(total) << 8 | k as u64
        });
        let keys = &keys[..n];
        for (k, &key) in keys.iter().enumerate() {
            order[keys.iter().filter(|&&o| o < key).count()] = k as u8;
        }
        let mut right_area = [0.0f32; SWEEP_MAX];
        let mut acc = Bounds::EMPTY;
        for k in (1..n).rev() {
            acc = acc.union(refs[order[k] as usize]);
            right_area[k] = acc.half_area();
        }
        let mut acc = Bounds::EMPTY;
        for k in 1..n {
            acc = acc.union(refs[order[k - 1] as usize]);
            let cost = acc.half_area() * k as f32 + right_area[k] * (n - k) as f32;
            // Ties go to the more balanced split (identical boxes halve).
            let balance = |k: usize| (2 * k).abs_diff(n);
            if cost < best.0 || cost == best.0 && balance(k) < balance(best.2) {
                best = (cost, axis, k);
            }
        }
    }
    let (_, axis, nl) = best;
    let order = &orders[axis][..n];
    let mut r = [Bounds::EMPTY; SWEEP_MAX];
    let mut d = [0u32; SWEEP_MAX];
    for (k, &o) in order.iter().enumerate() {
        r[k] = refs[o as usize];
        d[k] = ids[o as usize];
    }
    refs.copy_from_slice(&r[..n]);
    ids.copy_from_slice(&d[..n]);
    let fold = |s: &[Bounds]| s.iter().fold(Bounds::EMPTY, |a, b| a.union(*b));
    (nl, fold(&refs[..nl]), fold(&refs[nl..]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    fn soup(n: usize, seed: u64) -> Vec<Bounds> {
        let mut state = seed;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..n)
            .map(|_| {
                let c = Vec3A::new(rnd(), rnd() * 0.5, rnd() * 2.0) * 8.0;
                let e = Vec3A::new(rnd(), rnd(), rnd()) * 0.2;
                Bounds::new(c - e, c + e)
            })
            .collect()
    }

    /// Every primitive sits in exactly one leaf, leaves hold one, node boxes are the exact
    /// unions of their children's, children follow their parent; returns the depth.
    fn check(bvh: &Bvh2, refs: &[Bounds]) -> usize {
        let n = refs.len();
        assert_eq!(bvh.nodes.len(), 2 * n - 1);
        let mut seen = vec![false; n];
        let mut stack = vec![(0usize, 1usize)];
        let mut depth = 0;
        let bits = |a: Vec3A| a.to_array().map(f32::to_bits);
        while let Some((i, d)) = stack.pop() {
            depth = depth.max(d);
            let node = &bvh.nodes[i];
            let (lo, hi) = if node.prim_count != 0 {
                assert!(node.prim_count as usize <= LEAF_MAX);
                let (mut lo, mut hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
                for k in 0..node.prim_count {
                    let p = bvh.primitive_indices[(node.first_index + k) as usize] as usize;
                    assert!(!std::mem::replace(&mut seen[p], true));
                    (lo, hi) = (lo.min(refs[p].lo), hi.max(refs[p].hi));
                }
                (lo, hi)
            } else {
                let l = node.first_index as usize;
                assert!(l > i);
                stack.push((l, d + 1));
                stack.push((l + 1, d + 1));
                let (a, b) = (&bvh.nodes[l].aabb, &bvh.nodes[l + 1].aabb);
                (a.min.min(b.min), a.max.max(b.max))
            };
            assert_eq!(bits(node.aabb.min), bits(lo), "node {i}");
            assert_eq!(bits(node.aabb.max), bits(hi), "node {i}");
        }
        assert!(seen.iter().all(|&s| s));
        depth
    }

    #[test]
    fn valid_hierarchy_for_small_and_large_inputs() {
        for (n, seed) in [
            (1, 1),
            (2, 2),
            (3, 3),
            (8, 4),
            (9, 5),
            (1000, 6),
            (70_000, 7),
        ] {
            let refs = soup(n, seed);
            let depth = check(&build(refs.clone()), &refs);
            assert!(
                depth <= 2 * (n.max(2) as f64).log2().ceil() as usize + 4,
                "{n}: {depth}"
            );
        }
    }

    /// The tree's bytes do not depend on the thread count (parallel binning above
    /// `PARALLEL_BINNING` triangles, parallel subtrees above `PARALLEL_PRIMS`).
    #[test]
    fn same_hierarchy_at_every_thread_count() {
        let refs = soup(3 * PARALLEL_BINNING / 2, 9);
        let at = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| build(refs.clone()))
        };
        let (one, three) = (at(1), at(3));
        assert_eq!(one.primitive_indices, three.primitive_indices);
        let words = |b: &Bvh2| -> Vec<[u32; 8]> {
            let bits = |a: Vec3A| a.to_array().map(f32::to_bits);
            b.nodes
                .iter()
                .map(|n| {
                    let ([a, b, c], [d, e, f]) = (bits(n.aabb.min), bits(n.aabb.max));
                    [a, b, c, d, e, f, n.prim_count, n.first_index]
                })
                .collect()
        };
        assert!(words(&one) == words(&three));
    }

    /// Packing subtrees changes where nodes lie, not the tree: walked from the root, the
    /// packed and the spread layout (every subtree in its own `2n − 2` slots) have the same
    /// nodes (boxes, leaf ranges) and primitive order. The spread layout writes into more
    /// than 90 % of the array's 4 KiB pages; the packed one into less than 70 %, at most one
    /// page more than its nodes fill when the whole tree is one packed subtree.
    #[test]
    fn packed_subtrees_are_the_spread_tree_renumbered() {
        // The nodes in depth-first order, and the 4 KiB pages of the array that hold them.
        let walk = |b: &Bvh2| -> (Vec<[u32; 8]>, usize) {
            let bits = |a: Vec3A| a.to_array().map(f32::to_bits);
            let (mut out, mut pages, mut stack) = (Vec::new(), HashSet::new(), vec![0usize]);
            while let Some(i) = stack.pop() {
                pages.insert(i * std::mem::size_of::<Bvh2Node>() / 4096);
                let n = &b.nodes[i];
                let ([a, b2, c], [d, e, f]) = (bits(n.aabb.min), bits(n.aabb.max));
                let leaf_first = if n.prim_count == 0 {
                    stack.extend([n.first_index as usize + 1, n.first_index as usize]);
                    u32::MAX
                } else {
                    n.first_index
                };
                out.push([a, b2, c, d, e, f, n.prim_count, leaf_first]);
            }
            (out, pages.len())
        };
        for (n, seed) in [(3000, 21), (300_000, 22)] {
            let refs = soup(n, seed);
            let (bounds, centroids) =
                refs.iter()
                    .fold((Bounds::EMPTY, Bounds::EMPTY), |(b, mut c), r| {
                        c.grow(r.centroid());
                        (b.union(*r), c)
                    });
            let packed = Builder {
                packed: PARALLEL_PRIMS,
            }
            .build(refs.clone(), bounds, centroids);
            let spread = Builder { packed: 0 }.build(refs.clone(), bounds, centroids);
            check(&packed, &refs);
            assert_eq!(packed.primitive_indices, spread.primitive_indices);
            let ((p, p_pages), (s, s_pages)) = (walk(&packed), walk(&spread));
            assert!(p == s, "{n} triangles: the trees differ");
            let page_of = |nodes: usize| (nodes * std::mem::size_of::<Bvh2Node>()).div_ceil(4096);
            let (used, all) = (page_of(p.len()), page_of(packed.nodes.len()));
            if n <= PARALLEL_PRIMS {
                assert!(p_pages <= used + 1, "{n}: {p_pages} pages for {used}");
            }
            assert!(s_pages * 10 > all * 9, "{n}: spread {s_pages} of {all}");
            assert!(p_pages * 10 < all * 7, "{n}: packed {p_pages} of {all}");
        }
    }

    /// Identical boxes (every centroid in one bin), a geometric progression of sizes and
    /// positions (SAH costs that overflow `f32`), and extents up to 1e38 all build valid
    /// hierarchies of logarithmic depth.
    #[test]
    fn degenerate_distributions_stay_shallow() {
        let same = vec![Bounds::new(Vec3A::ZERO, Vec3A::ONE); 5000];
        assert!(check(&build(same.clone()), &same) <= 14);
        let geometric: Vec<Bounds> = (0..2000)
            .map(|i| {
                let s = 1.05f32.powi(i % 1800);
                Bounds::new(Vec3A::splat(s), Vec3A::splat(s * 1.5))
            })
            .collect();
        let d = check(&build(geometric.clone()), &geometric);
        assert!(d <= SAH_DEPTH as usize + 24, "{d}");
        let mut huge = soup(3000, 11);
        huge.push(Bounds::new(Vec3A::splat(-1.5e38), Vec3A::splat(1.5e38)));
        huge.push(Bounds::new(Vec3A::splat(1e37), Vec3A::splat(3e38)));
        let d = check(&build(huge.clone()), &huge);
        assert!(d <= 30, "{d}");
    }
}
