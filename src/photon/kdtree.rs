//! A photon map: stored photons in a balanced kd-tree (implicit, median-split, the tree order
//! is the array order), k-nearest-neighbour and fixed-radius gathers, and the density
//! estimate built on them.
//!
//! **Estimator.** For a gather of the `k` nearest photons within `r_max`, the estimate is
//! `Σ_{i<k} f(pᵢ)·Φᵢ / (π r_k²)`: the k-th photon only fixes the radius and is not summed.
//! For a Poisson photon field of density λ this is unbiased, `E[(k−1)/(π r_k²)] = λ`, while the
//! classic `Σ_{i≤k} Φᵢ / (π r_k²)` overestimates by `k/(k−1)` (Garcia et al., CGF 2012; H20).
//! When fewer than `k` photons lie within `r_max`, it becomes the fixed-radius estimate
//! `Σ Φᵢ / (π r_max²)`, also unbiased on uniform regions. Photons whose stored normal
//! differs from the query normal (`n_p·n_q ≤ 0.9`, Jensen) are ignored, so light does not leak
//! through thin walls or around corners. Near a surface's boundary the disc covers empty
//! space and the estimate falls (½ at a straight edge): a known, documented bias.

use std::cmp::Ordering;

use glam::{Vec3, Vec3A};

use crate::prefetch::prefetch_line;
use crate::settings::PhotonFilter;

/// Smallest `n_p·n_q` for a photon to count in an estimate at a point with normal `n_q`.
pub const NORMAL_FILTER: f32 = 0.9;

/// One stored photon.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Photon {
    /// Where it landed.
    pub position: Vec3,
    /// Power it carries, W (already divided by the number of emitted photons).
    pub power: Vec3,
    /// Unit direction toward where it came from (the `wi` of the estimate).
    pub incoming: Vec3,
    /// Unit geometric normal on the side it arrived from.
    pub normal: Vec3,
}

/// One gathered photon.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbour {
    /// Squared distance to the query point.
    pub dist2: f32,
    /// Index into [`PhotonMap::photons`].
    pub index: u32,
}

/// Which photons an estimate uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gather {
    /// The `k` nearest within `r_max` (`k − 1` summed over `π r_k²`), falling back to the
    /// fixed radius `r_max` when fewer are found.
    Nearest {
        /// Photons per estimate, ≥ 2.
        k: usize,
        /// Largest radius.
        r_max: f32,
    },
    /// Every photon within a fixed radius.
    Radius(f32),
}

/// Photons in a kd-tree.
#[derive(Debug, Clone, Default)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    axes: Vec<u8>,
    /// What the search reads at every node, in tree order: 16 bytes instead of a 48-byte
    /// photon, so four nodes share a cache line.
    nodes: Vec<SearchNode>,
}

/// A photon's position and its node's split axis, packed for the search (the split
/// coordinate is `position[axis]`).
#[derive(Debug, Clone, Copy)]
#[repr(C)]
struct SearchNode {
    position: [f32; 3],
    axis: u32,
}

fn search_nodes(photons: &[Photon], axes: &[u8]) -> Vec<SearchNode> {
    photons
        .iter()
        .zip(axes)
        .map(|(p, &a)| SearchNode {
            position: p.position.to_array(),
            axis: u32::from(a).min(2),
        })
        .collect()
}

impl SearchNode {
    fn position(&self) -> Vec3 {
        Vec3::from_array(self.position)
    }

    /// The node's coordinate along its split axis (`axis` is at most 2 by construction, so
    /// the bounds check never fails; a `% 3` here put a multiply and a shift on the walk's
    /// dependent chain, node load to next node).
    fn split(&self) -> f32 {
        self.position[self.axis as usize]
    }
}

/// Deepest pending entry the iterative search can need: one per tree level, and an implicit
/// median tree of `n < 2³²` nodes (photon indices are `u32`) has at most 32 levels.
const SEARCH_STACK: usize = 32;

impl PhotonMap {
    /// Builds the tree (deterministic: the same photons in the same order give the same tree).
    /// Photons with a non-finite position or power are dropped.
    pub fn build(mut photons: Vec<Photon>) -> Self {
        let finite = |p: &Photon| p.position.is_finite() && p.power.is_finite();
        let key = |(i, p): (usize, &Photon)| BuildKey {
            position: p.position.to_array(),
            index: i as u32,
        };
        // One pass over the photons makes the keys and checks them (traced photons are
        // finite); only a map with a dropped photon reads them again.
        let mut all_finite = true;
        let mut keys: Vec<BuildKey> = photons
            .iter()
            .enumerate()
            .inspect(|(_, p)| all_finite &= finite(p))
            .map(key)
            .collect();
        if !all_finite {
            photons.retain(finite);
            keys = photons.iter().enumerate().map(key).collect();
        }
        Self::from_keys(keys, |i| &photons[i as usize])
    }

    /// [`PhotonMap::build`] of the photons of `parts` in order (the work items' vectors of a
    /// photon pass, [`super::PhotonParts::into_parts`]), the same tree bit for bit, without concatenating them first: each key
    /// carries its photon's part and offset, and the photons are gathered into tree order
    /// straight from the parts (the concatenation faulted and copied a second array of the
    /// map's size). Falls back to the concatenation when a photon is not finite or the
    /// (part, offset) pairs do not fit in 32 bits.
    pub fn from_parts(parts: Vec<Vec<Photon>>) -> Self {
        let longest = parts.iter().map(Vec::len).max().unwrap_or(0);
        // Offsets in the low `shift` bits, the part above them.
        let shift = usize::BITS - longest.leading_zeros();
        let fits = (parts.len() as u64) << shift <= 1 << 32;
        let finite = |p: &Photon| p.position.is_finite() && p.power.is_finite();
        if !fits || !parts.iter().flatten().all(finite) {
            return Self::build(parts.concat());
        }
        let mut keys = Vec::with_capacity(parts.iter().map(Vec::len).sum());
        for (part, photons) in parts.iter().enumerate() {
            let base = (part as u64) << shift;
            keys.extend(photons.iter().enumerate().map(|(i, p)| BuildKey {
                position: p.position.to_array(),
                index: (base | i as u64) as u32,
            }));
        }
        let mask = (1u64 << shift).wrapping_sub(1) as u32;
        Self::from_keys(keys, |i| {
            &parts[(u64::from(i) >> shift) as usize][(i & mask) as usize]
        })
    }

    /// The tree of `keys` (each key's `index` names its photon to `photon`): the median
    /// build, then the photons gathered into tree order.
    fn from_keys<'p>(mut keys: Vec<BuildKey>, photon: impl Fn(u32) -> &'p Photon) -> Self {
        let mut axes = vec![0u8; keys.len()];
        build(&mut keys, &mut axes);
        // A gather, not an in-place permutation: its loads are independent (following the
        // permutation's cycles in place made the whole render 5–8 % slower). Tree order is
        // spatial and the photons are in emission order, so every load misses the caches
        // (and the TLB, in a map of tens of megabytes): each photon's lines are prefetched
        // `GATHER_AHEAD` photons early (885,577 caustic photons: 68–69 ms → 50–53 ms).
        let mut photons = Vec::with_capacity(keys.len());
        for (i, k) in keys.iter().enumerate() {
            if let Some(ahead) = keys.get(i + GATHER_AHEAD) {
                prefetch_photon(photon(ahead.index));
            }
            photons.push(*photon(k.index));
        }
        for (k, &a) in keys.iter_mut().zip(&axes) {
            k.index = u32::from(a);
        }
        // The keys' buffer becomes the search nodes' (same size and alignment: the
        // collect reuses the allocation).
        let nodes = keys
            .into_iter()
            .map(|k| SearchNode {
                position: k.position,
                axis: k.index,
            })
            .collect();
        Self {
            photons,
            axes,
            nodes,
        }
    }

    /// A tree stored earlier: `photons` in tree order and the split axis of each node, as
    /// [`PhotonMap::photons`] and [`PhotonMap::axes`] gave them. `None` when the lengths
    /// differ, an axis is not 0–2 or a value is not finite (any such tree searches safely, but
    /// only a built one finds the right photons).
    pub fn from_tree(photons: Vec<Photon>, axes: Vec<u8>) -> Option<Self> {
        let finite = photons
            .iter()
            .all(|p| p.position.is_finite() && p.power.is_finite());
        (photons.len() == axes.len() && axes.iter().all(|&a| a < 3) && finite).then(|| Self {
            nodes: search_nodes(&photons, &axes),
            photons,
            axes,
        })
    }

    /// The split axis of each node, in tree order (0 = x, 1 = y, 2 = z).
    pub fn axes(&self) -> &[u8] {
        &self.axes
    }

    /// Number of stored photons.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// True when no photon is stored.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The photons in tree order.
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// Total power of the stored photons, W.
    pub fn total_power(&self) -> Vec3 {
        self.photons.iter().fold(Vec3::ZERO, |s, p| s + p.power)
    }

    /// The at most `k` photons nearest to `p` strictly within `r_max` whose normal passes the
    /// filter against `normal` (none: no filter), sorted by distance (ties by index).
    pub fn nearest(
        &self,
        p: Vec3,
        normal: Option<Vec3>,
        k: usize,
        r_max: f32,
        out: &mut Vec<Neighbour>,
    ) {
        out.clear();
        if k == 0 || r_max.is_nan() || r_max <= 0.0 || !p.is_finite() {
            return;
        }
        if k == 1 {
            // The final-gather irradiance lookup: no heap, the same answer.
            if let Some(best) = self.nearest_one(p, normal, r_max * r_max) {
                out.push(best);
            }
            return;
        }
        let mut q = Query {
            p,
            normal,
            k,
            max_d2: r_max * r_max,
            found: std::mem::take(out),
        };
        self.search(&mut q);
        *out = q.found;
        // Distinct keys (indices are): any sort gives this order.
        super::neighbour_sort::sort(out, |n| {
            (u64::from(n.dist2.to_bits()) << 32) | u64::from(n.index)
        });
    }

    /// The density estimate `Σ f(photon)·Φ / area` at `p` (normal `normal`) — irradiance for
    /// `f = 1`, reflected radiance for `f` = the BSDF toward the photon's direction.
    pub fn estimate(
        &self,
        p: Vec3,
        normal: Vec3,
        gather: Gather,
        scratch: &mut Vec<Neighbour>,
        f: impl Fn(&Photon) -> Vec3,
    ) -> Vec3 {
        self.estimate_filtered(p, normal, gather, PhotonFilter::Box, scratch, f)
    }

    /// [`PhotonMap::estimate`] with each photon weighted by `filter` over the gather disc
    /// (see [`super::filter`]).
    pub fn estimate_filtered(
        &self,
        p: Vec3,
        normal: Vec3,
        gather: Gather,
        filter: PhotonFilter,
        scratch: &mut Vec<Neighbour>,
        f: impl Fn(&Photon) -> Vec3,
    ) -> Vec3 {
        let sum = |n: &[Neighbour], r2: f32| {
            n.iter().fold(Vec3::ZERO, |s, nb| {
                let ph = &self.photons[nb.index as usize];
                match filter {
                    PhotonFilter::Box => s + f(ph) * ph.power,
                    _ => s + f(ph) * ph.power * filter.weight(nb.dist2, r2),
                }
            })
        };
        let area = |r2: f32| std::f32::consts::PI * r2;
        match gather {
            Gather::Nearest { k, r_max } => {
                let k = k.max(2);
                self.nearest(p, Some(normal), k, r_max, scratch);
                if scratch.len() == k && scratch[k - 1].dist2 > 0.0 {
                    let r2 = scratch[k - 1].dist2;
                    sum(&scratch[..k - 1], r2) / area(r2)
                } else {
                    sum(scratch, r_max * r_max) / area(r_max * r_max)
                }
            }
            Gather::Radius(r) => {
                self.nearest(p, Some(normal), usize::MAX, r, scratch);
                sum(scratch, r * r) / area(r * r)
            }
        }
    }

    /// The in-order walk of the implicit tree — near side, the node, then the far side
    /// when its splitting plane is closer than the current bound — with an explicit stack.
    /// `visit` offers a node and returns the bound after the offer, so nodes are offered in
    /// exactly the order of the recursive definition (ties keep the first photon offered).
    fn walk(&self, p: Vec3, mut visit: impl FnMut(usize) -> f32) {
        // Indexed with `axis & 3`, so the compiler needs no bounds check on the hot path.
        let p = p.extend(0.0).to_array();
        // (node, its plane distance, far range) of the nodes whose near side is in progress.
        let mut stack = [(0u32, 0f32, 0u32, 0u32); SEARCH_STACK];
        let mut depth = 0;
        let (mut lo, mut hi) = (0, self.nodes.len().min(u32::MAX as usize) as u32);
        loop {
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                let node = &self.nodes[mid as usize];
                let d = p[(node.axis & 3) as usize] - node.split();
                let (near, far) = if d < 0.0 {
                    ((lo, mid), (mid + 1, hi))
                } else {
                    ((mid + 1, hi), (lo, mid))
                };
                stack[depth & (SEARCH_STACK - 1)] = (mid, d, far.0, far.1);
                depth += 1;
                (lo, hi) = near;
            }
            if depth == 0 {
                return;
            }
            depth -= 1;
            let (mid, d, far_lo, far_hi) = stack[depth & (SEARCH_STACK - 1)];
            let bound = visit(mid as usize);
            if d * d < bound {
                (lo, hi) = (far_lo, far_hi);
            }
        }
    }

    /// The nearest photon strictly within `sqrt(max_d2)` that passes the normal filter, ties
    /// to the least index (the rule of [`super::point_grid::PointGrid::nearest`]): the far
    /// side of a plane is visited while a photon at the current distance could lie there.
    fn nearest_one(&self, p: Vec3, normal: Option<Vec3>, max_d2: f32) -> Option<Neighbour> {
        let mut best: Option<Neighbour> = None;
        self.walk(p, |i| {
            let d2 = (self.nodes[i].position() - p).length_squared();
            let better = match best {
                Some(b) => d2 < b.dist2 || d2 == b.dist2 && (i as u32) < b.index,
                None => d2 < max_d2,
            };
            if better && normal.is_none_or(|n| self.photons[i].normal.dot(n) > NORMAL_FILTER) {
                best = Some(Neighbour {
                    dist2: d2,
                    index: i as u32,
                });
            }
            // The walk visits a far side when the plane is strictly nearer than this.
            best.map_or(max_d2, |b| b.dist2.next_up())
        });
        best
    }

    fn search(&self, q: &mut Query) {
        self.walk(q.p, |i| {
            q.offer(&self.nodes[i], &self.photons, i);
            q.max_d2
        });
    }
}

/// A k-nearest search in progress. `found` holds the accepted photons; once it holds `k` of
/// them it is a max-heap by (squared distance bits, index), and `max_d2` is its top's
/// distance, so a later photon is accepted only when strictly nearer and then replaces the
/// top: the photons kept are those a push-then-pop heap keeps, in any visiting order.
struct Query {
    p: Vec3,
    normal: Option<Vec3>,
    k: usize,
    max_d2: f32,
    found: Vec<Neighbour>,
}

/// Heap order of a gathered photon: non-negative floats order like their bit patterns.
fn heap_key(n: &Neighbour) -> (u32, u32) {
    (n.dist2.to_bits(), n.index)
}

impl Query {
    fn offer(&mut self, node: &SearchNode, photons: &[Photon], i: usize) {
        let d2 = (node.position() - self.p).length_squared();
        if d2.is_nan() || d2 >= self.max_d2 {
            return;
        }
        if let Some(n) = self.normal {
            if photons[i].normal.dot(n) <= NORMAL_FILTER {
                return;
            }
        }
        let candidate = Neighbour {
            dist2: d2,
            index: i as u32,
        };
        if self.found.len() < self.k {
            self.found.push(candidate);
            if self.found.len() == self.k {
                make_max_heap(&mut self.found);
                self.max_d2 = self.found[0].dist2;
            }
            return;
        }
        // Full: `d2` is below the top's distance, so the candidate replaces the top.
        self.found[0] = candidate;
        sift_down(&mut self.found, 0);
        self.max_d2 = self.found[0].dist2;
    }
}

fn make_max_heap(heap: &mut [Neighbour]) {
    for i in (0..heap.len() / 2).rev() {
        sift_down(heap, i);
    }
}

fn sift_down(heap: &mut [Neighbour], mut i: usize) {
    loop {
        let left = 2 * i + 1;
        if left >= heap.len() {
            return;
        }
        let right = left + 1;
        let child = if right < heap.len() && heap_key(&heap[right]) > heap_key(&heap[left]) {
            right
        } else {
            left
        };
        if heap_key(&heap[child]) <= heap_key(&heap[i]) {
            return;
        }
        heap.swap(i, child);
        i = child;
    }
}

/// How many photons ahead [`PhotonMap::from_keys`] prefetches the one it will gather.
const GATHER_AHEAD: usize = 16;

/// Prefetches the cache lines of `p` (its first and last byte: a 48-byte photon spans one
/// or two lines; a hint, no effect on memory or results).
#[inline(always)]
fn prefetch_photon(p: &Photon) {
    let first = std::ptr::from_ref(p).cast::<u8>();
    prefetch_line(first);
    prefetch_line(first.wrapping_add(std::mem::size_of::<Photon>() - 1));
}

/// Subtrees of at least this many photons are built on two rayon tasks.
const PARALLEL_BUILD_MIN: usize = 16_384;

/// What the build moves around instead of a 48-byte [`Photon`]: its position and its index
/// among the photons (which breaks ties between equal coordinates, [`select_on`]); the
/// photons follow their keys once at the end. [`PhotonMap::from_parts`]'s indices (part,
/// then offset) order the photons as their concatenation does, so both build one tree.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
struct BuildKey {
    position: [f32; 3],
    index: u32,
}

/// `keys.select_nth_unstable_by(mid, …)` on coordinate `AXIS` (`partial_cmp`, incomparable as
/// equal). Which of the photons at the median's coordinate end on which side is the
/// selection algorithm's choice; [`settle_ties`] then makes it the index order.
fn select_on<const AXIS: usize>(keys: &mut [BuildKey], mid: usize) {
    keys.select_nth_unstable_by(mid, |a, b| {
        a.position[AXIS]
            .partial_cmp(&b.position[AXIS])
            .unwrap_or(Ordering::Equal)
    });
}

/// After [`select_on`] (`keys[..mid]` at or below the median's coordinate `m` on `axis`,
/// `keys[mid + 1..]` at or above it): of the photons at `m`, the ones with the smallest
/// indices fill the lower side's places, the next is the median, the rest go above. The
/// split is then the one by (coordinate, index), a total order (indices are distinct), so
/// the two sides are the same *sets* whatever permutation the selection left; the build
/// recurses to single photons, so the tree does not depend on the standard library's
/// selection algorithm, which has changed between Rust releases. (Format 1's trees kept the
/// algorithm's choice: photons on a wall all share one coordinate.) Breaking ties in the
/// selection's comparison instead took its fast path for runs of equal keys away: the
/// build took 1.5× as many instructions (tenth of the photon-heavy scene).
fn settle_ties(keys: &mut [BuildKey], mid: usize, axis: usize) {
    let m = keys[mid].position[axis];
    let (left, right) = keys.split_at_mut(mid);
    // Below: those under `m` first; above (after the median): those at `m` first.
    let under = partition(left, |k| k.position[axis] < m);
    let at_above = partition(&mut right[1..], |k| k.position[axis] == m);
    let tied = &mut keys[under..=mid + at_above];
    tied.select_nth_unstable_by_key(mid - under, |k| k.index);
}

/// Moves the keys for which `first` holds to the front; returns how many there are.
fn partition(keys: &mut [BuildKey], first: impl Fn(&BuildKey) -> bool) -> usize {
    let mut n = 0;
    for i in 0..keys.len() {
        if first(&keys[i]) {
            keys.swap(n, i);
            n += 1;
        }
    }
    n
}

/// The keys' bounding box, `(min, max)` per axis: [`Vec3A`] lanes (one `minps` and one
/// `maxps` per key) computing what [`Vec3::min`]/[`Vec3::max`] compute lane by lane (`if a <
/// b { a } else { b }`, the `minps` rule), so the extent `max − min` has the bits of the
/// scalar fold ([`tests::the_extent_is_the_scalar_folds`]).
fn bounds(keys: &[BuildKey]) -> (Vec3A, Vec3A) {
    keys.iter().fold(
        (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY)),
        |(lo, hi), k| {
            let p = Vec3A::from_array(k.position);
            (lo.min(p), hi.max(p))
        },
    )
}

/// Median split along the widest axis, recursively; `axes[mid]` records the split.
fn build(keys: &mut [BuildKey], axes: &mut [u8]) {
    let all = bounds(keys);
    build_within(keys, axes, all);
}

/// [`build`] of keys whose [`bounds`] are `(lo, hi)`. Each node computes its two sides'
/// bounds (which the sides need for their own splits), and they tell it whether a photon
/// beside the median shares its coordinate: only then are the ties settled.
fn build_within(keys: &mut [BuildKey], axes: &mut [u8], (lo, hi): (Vec3A, Vec3A)) {
    if keys.len() <= 1 {
        return;
    }
    let ext = Vec3::from(hi - lo);
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let mid = keys.len() / 2;
    match axis {
        0 => select_on::<0>(keys, mid),
        1 => select_on::<1>(keys, mid),
        _ => select_on::<2>(keys, mid),
    }
    axes[mid] = axis as u8;
    let m = keys[mid].position[axis];
    let sides = |keys: &[BuildKey]| (bounds(&keys[..mid]), bounds(&keys[mid + 1..]));
    let (mut below, mut above) = sides(keys);
    // Below holds coordinates ≤ m and above ≥ m: a tie shows as below's max or above's min.
    if below.1[axis] == m || above.0[axis] == m {
        settle_ties(keys, mid, axis);
        (below, above) = sides(keys);
    }
    let (left, rest) = keys.split_at_mut(mid);
    let (left_axes, rest_axes) = axes.split_at_mut(mid);
    let right = (&mut rest[1..], &mut rest_axes[1..]);
    // The two halves are disjoint and built the same way on any thread: same tree bytes.
    if left.len() >= PARALLEL_BUILD_MIN {
        rayon::join(
            || build_within(left, left_axes, below),
            || build_within(right.0, right.1, above),
        );
    } else {
        build_within(left, left_axes, below);
        build_within(right.0, right.1, above);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize) -> Vec<Photon> {
        (0..n * n)
            .map(|i| Photon {
                position: Vec3::new((i % n) as f32, (i / n) as f32, 0.0),
                power: Vec3::ONE,
                incoming: Vec3::Z,
                normal: Vec3::Z,
            })
            .collect()
    }

    #[test]
    fn nearest_matches_brute_force() {
        let map = PhotonMap::build(grid(20));
        let p = Vec3::new(7.3, 4.6, 0.2);
        let mut out = Vec::new();
        map.nearest(p, Some(Vec3::Z), 9, 100.0, &mut out);
        let mut brute: Vec<f32> = map
            .photons()
            .iter()
            .map(|ph| (ph.position - p).length_squared())
            .collect();
        brute.sort_by(f32::total_cmp);
        let got: Vec<f32> = out.iter().map(|n| n.dist2).collect();
        assert_eq!(got, brute[..9].to_vec());
    }

    #[test]
    fn radius_and_normal_filter_limit_the_gather() {
        let mut photons = grid(10);
        photons[0].normal = -Vec3::Z;
        let map = PhotonMap::build(photons);
        let mut out = Vec::new();
        map.nearest(Vec3::ZERO, Some(Vec3::Z), 50, 1.5, &mut out);
        // Within 1.5 of the origin: (0,0) (filtered out), (1,0), (0,1), (1,1).
        assert_eq!(out.len(), 3);
        map.nearest(Vec3::ZERO, None, 50, 1.5, &mut out);
        assert_eq!(out.len(), 4);
    }

    /// Deterministic pseudo-random points in the unit cube (a 64-bit LCG).
    fn scattered(n: usize, seed: u64) -> Vec<Vec3> {
        let mut x = seed;
        let mut next = move || {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 40) as f32 / (1u64 << 24) as f32
        };
        (0..n).map(|_| Vec3::new(next(), next(), next())).collect()
    }

    #[test]
    fn the_tree_is_the_same_built_on_one_thread_or_two() {
        // Enough photons that the halves go to rayon tasks (`PARALLEL_BUILD_MIN`), on a
        // lattice so that split ties occur.
        let photons: Vec<Photon> = scattered(4 * PARALLEL_BUILD_MIN, 21)
            .into_iter()
            .map(|p| Photon {
                position: (p * 32.0).round(),
                power: p,
                incoming: Vec3::Z,
                normal: Vec3::Z,
            })
            .collect();
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("thread pool");
            pool.install(|| PhotonMap::build(photons.clone()))
        };
        let (one, two) = (on(1), on(2));
        assert_eq!(one.photons(), two.photons());
        assert_eq!(one.axes(), two.axes());
    }

    /// The tree by another algorithm: at every node a full stable sort of the photons (with
    /// their input indices) by the split coordinate, then by index, instead of a selection.
    fn sorted_build(photons: &mut [(u32, Photon)], axes: &mut [u8]) {
        if photons.len() <= 1 {
            return;
        }
        let (lo, hi) = photons.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), (_, p)| (lo.min(p.position), hi.max(p.position)),
        );
        let ext = hi - lo;
        let axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        photons.sort_by(|(i, a), (j, b)| {
            a.position[axis]
                .partial_cmp(&b.position[axis])
                .unwrap_or(Ordering::Equal)
                .then(i.cmp(j))
        });
        let mid = photons.len() / 2;
        axes[mid] = axis as u8;
        let (left, rest) = photons.split_at_mut(mid);
        let (left_axes, rest_axes) = axes.split_at_mut(mid);
        sorted_build(left, left_axes);
        sorted_build(&mut rest[1..], &mut rest_axes[1..]);
    }

    /// The extent of [`bounds`] (`max − min`), in SIMD lanes, gives the bits of the scalar
    /// [`Vec3`] fold it replaced, for signed zeros (`min(0, −0)` keeps the second operand in
    /// both), subnormals, huge and infinite coordinates, and a lone key.
    #[test]
    fn the_extent_is_the_scalar_folds() {
        let scalar = |keys: &[BuildKey]| {
            let (lo, hi) = keys.iter().fold(
                (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                |(lo, hi), k| {
                    let p = Vec3::from_array(k.position);
                    (lo.min(p), hi.max(p))
                },
            );
            hi - lo
        };
        let special = [
            0.0,
            -0.0,
            1e-40,
            -1e-40,
            3.0e38,
            -3.0e38,
            f32::INFINITY,
            1.5,
        ];
        let mut sets: Vec<Vec<[f32; 3]>> = vec![vec![[0.0, -0.0, 1.0]]];
        for (n, seed) in [(2usize, 3u64), (9, 4), (100, 5), (1000, 6)] {
            let points = scattered(n, seed);
            sets.push(
                points
                    .iter()
                    .enumerate()
                    .map(|(i, p)| {
                        let pick = |j: usize, v: f32| {
                            if (i + j).is_multiple_of(3) {
                                special[(i * 7 + j) % special.len()]
                            } else {
                                v - 0.5
                            }
                        };
                        [pick(0, p.x), pick(1, p.y), pick(2, p.z)]
                    })
                    .collect(),
            );
            // Only signed zeros on an axis: the extent's sign of zero is what the fold gives.
            sets.push(
                (0..n)
                    .map(|i| [if i % 2 == 0 { 0.0 } else { -0.0 }, i as f32, -0.0])
                    .collect(),
            );
        }
        for set in sets {
            let keys: Vec<BuildKey> = set
                .iter()
                .enumerate()
                .map(|(i, &position)| BuildKey {
                    position,
                    index: i as u32,
                })
                .collect();
            let (lo, hi) = bounds(&keys);
            let (got, want) = (Vec3::from(hi - lo), scalar(&keys));
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            assert_eq!(bits(got), bits(want), "{set:?}");
        }
    }

    /// The tree does not depend on the selection algorithm: the build's `select_nth_unstable`
    /// and a full stable sort at every node give the same photons in the same order, the
    /// same axes and search nodes. Coarse lattices (many equal coordinates: without the
    /// index tie-break, which of the equal photons lands where follows each algorithm's
    /// moves, and this fails), signed zeros (equal, different bits), photons on a plane and
    /// repeated photons; sizes around the selection's small-slice thresholds and above the
    /// parallel split.
    #[test]
    fn the_tree_does_not_depend_on_the_selection_algorithm() {
        let mut sets: Vec<Vec<Photon>> = Vec::new();
        for (n, seed, cells) in [
            (5usize, 1u64, 2.0f32),
            (17, 2, 3.0),
            (63, 3, 4.0),
            (64, 4, 4.0),
            (65, 5, 2.0),
            (1000, 6, 8.0),
            (5000, 7, 0.0),
            (3 * PARALLEL_BUILD_MIN, 8, 64.0),
        ] {
            let photons = scattered(n, seed)
                .into_iter()
                .enumerate()
                .map(|(i, p)| {
                    let mut position = if cells > 0.0 {
                        (p * cells).round() - Vec3::splat(cells / 2.0)
                    } else {
                        p
                    };
                    if i % 7 == 0 {
                        position.y = 0.0;
                    }
                    if i % 11 == 0 {
                        position.z = -0.0;
                    }
                    Photon {
                        position,
                        power: Vec3::splat(i as f32),
                        incoming: Vec3::Z,
                        normal: Vec3::Y,
                    }
                })
                .collect();
            sets.push(photons);
        }
        sets.push(vec![grid(1)[0]; 300]);
        for photons in sets {
            let map = PhotonMap::build(photons.clone());
            let mut indexed: Vec<(u32, Photon)> = (0..).zip(photons).collect();
            let mut axes = vec![0u8; indexed.len()];
            sorted_build(&mut indexed, &mut axes);
            let want: Vec<Photon> = indexed.into_iter().map(|(_, p)| p).collect();
            assert_eq!(map.photons(), &want[..], "{} photons", want.len());
            // Photon powers are their input indices: the permutation itself is the same.
            let order = |p: &[Photon]| p.iter().map(|p| p.power.x).collect::<Vec<_>>();
            assert_eq!(order(map.photons()), order(&want));
            assert_eq!(map.axes(), &axes[..]);
            let nodes = search_nodes(&want, &axes);
            for (a, b) in map.nodes.iter().zip(&nodes) {
                assert_eq!((a.position, a.axis), (b.position, b.axis));
            }
        }
    }

    /// A map built from a pass's parts is the map of their concatenation, bit for bit: the
    /// photons in tree order, the axes and the search nodes; with empty parts, one part, a
    /// lattice full of ties split unevenly, and a non-finite photon (the fallback drops it).
    #[test]
    fn a_map_from_parts_is_the_map_of_their_concatenation() {
        let lattice = |n: usize, seed: u64| -> Vec<Photon> {
            scattered(n, seed)
                .into_iter()
                .enumerate()
                .map(|(i, p)| Photon {
                    position: (p * 6.0).round(),
                    power: Vec3::splat(i as f32),
                    incoming: Vec3::Z,
                    normal: Vec3::Y,
                })
                .collect()
        };
        let mut cases: Vec<Vec<Vec<Photon>>> = vec![
            vec![],
            vec![Vec::new(), Vec::new()],
            vec![lattice(1, 1)],
            vec![lattice(700, 2)],
            vec![lattice(300, 3), Vec::new(), lattice(1, 4), lattice(4096, 5)],
            (0..40).map(|i| lattice(i * 37 % 129, i as u64)).collect(),
            vec![lattice(3 * PARALLEL_BUILD_MIN, 6), lattice(17, 7)],
        ];
        let mut bad = lattice(50, 8);
        bad[20].position.x = f32::NAN;
        bad[30].power.y = f32::INFINITY;
        cases.push(vec![lattice(60, 9), bad, lattice(10, 10)]);
        for parts in cases {
            let all: Vec<Photon> = parts.concat();
            let want = PhotonMap::build(all.clone());
            let got = PhotonMap::from_parts(parts.clone());
            let photon_bits = |ps: &[Photon]| -> Vec<[u32; 12]> {
                ps.iter()
                    .map(|p| {
                        let f = [p.position, p.power, p.incoming, p.normal];
                        std::array::from_fn(|i| f[i / 3][i % 3].to_bits())
                    })
                    .collect()
            };
            let bits = |m: &PhotonMap| {
                let p = photon_bits(m.photons());
                let n: Vec<([u32; 3], u32)> = m
                    .nodes
                    .iter()
                    .map(|n| (n.position.map(f32::to_bits), n.axis))
                    .collect();
                (p, m.axes().to_vec(), n)
            };
            assert_eq!(bits(&got), bits(&want), "{} photons", all.len());
        }
    }

    #[test]
    fn k_nearest_matches_brute_force_on_scattered_points() {
        let photons: Vec<Photon> = scattered(3000, 1)
            .into_iter()
            .map(|p| Photon {
                position: p,
                power: Vec3::ONE,
                incoming: Vec3::Z,
                normal: Vec3::Z,
            })
            .collect();
        let map = PhotonMap::build(photons);
        let mut out = Vec::new();
        for (qi, q) in scattered(40, 2).into_iter().enumerate() {
            for (k, r_max) in [(1, 1.0), (7, 0.2), (50, 0.15), (200, 2.0)] {
                map.nearest(q, None, k, r_max, &mut out);
                let mut brute: Vec<(f32, u32)> = map
                    .photons()
                    .iter()
                    .enumerate()
                    .map(|(i, ph)| ((ph.position - q).length_squared(), i as u32))
                    .filter(|&(d2, _)| d2 < r_max * r_max)
                    .collect();
                brute.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                brute.truncate(k);
                let got: Vec<(f32, u32)> = out.iter().map(|n| (n.dist2, n.index)).collect();
                assert_eq!(got, brute, "query {qi}, k {k}, r_max {r_max}");
            }
        }
    }

    /// The recursive in-order walk the iterative one replaced: the near side, the node
    /// (`offer` returns the bound after it), then the far side when its plane is closer.
    fn recursive_walk(
        map: &PhotonMap,
        (lo, hi): (usize, usize),
        p: Vec3,
        offer: &mut impl FnMut(usize, &Photon) -> f32,
    ) {
        if lo >= hi {
            return;
        }
        let mid = (lo + hi) / 2;
        let ph = &map.photons()[mid];
        let axis = map.axes()[mid] as usize;
        let d = p[axis] - ph.position[axis];
        let (near, far) = if d < 0.0 {
            ((lo, mid), (mid + 1, hi))
        } else {
            ((mid + 1, hi), (lo, mid))
        };
        recursive_walk(map, near, p, offer);
        if d * d < offer(mid, ph) {
            recursive_walk(map, far, p, offer);
        }
    }

    /// The `k = 1` answer by definition: the least squared distance strictly within the
    /// radius among photons passing the normal filter, ties to the least index.
    fn brute_nearest_one(
        map: &PhotonMap,
        p: Vec3,
        normal: Vec3,
        max_d2: f32,
    ) -> Option<(f32, u32)> {
        (0..map.len())
            .map(|i| ((map.photons()[i].position - p).length_squared(), i as u32))
            .filter(|&(d2, i)| {
                d2 < max_d2 && map.photons()[i as usize].normal.dot(normal) > NORMAL_FILTER
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
    }

    #[test]
    fn nearest_one_is_the_least_distance_then_index_with_the_normal_filter() {
        // Scattered points, every third one repeated exactly (ties in distance), a quarter
        // facing the other way (normal filter), on a coarse lattice so plane ties occur too.
        let mut photons = Vec::new();
        for (i, p) in scattered(4000, 7).into_iter().enumerate() {
            let p = (p * 16.0).round() / 16.0;
            let normal = if i % 4 == 0 { -Vec3::Z } else { Vec3::Z };
            let ph = Photon {
                position: p,
                power: Vec3::ONE,
                incoming: Vec3::Z,
                normal,
            };
            photons.push(ph);
            if i % 3 == 0 {
                photons.push(Photon {
                    power: Vec3::X,
                    ..ph
                });
            }
        }
        let map = PhotonMap::build(photons);
        let mut out = Vec::new();
        let mut found = 0;
        for q in scattered(300, 8) {
            for r_max in [0.02f32, 0.1, 2.0] {
                let want = brute_nearest_one(&map, q, Vec3::Z, r_max * r_max);
                map.nearest(q, Some(Vec3::Z), 1, r_max, &mut out);
                let got = out.first().map(|n| (n.dist2, n.index));
                assert_eq!(got, want, "query {q}, r_max {r_max}");
                found += usize::from(got.is_some());
            }
        }
        assert!(found > 600, "only {found} queries found a photon");
    }

    /// The k-nearest search before the in-place heap: the recursive walk offering each
    /// photon to a `std` max-heap, pushed and then popped past `k`.
    fn recursive_k_nearest(
        map: &PhotonMap,
        range: (usize, usize),
        p: Vec3,
        k: usize,
        bound: &mut f32,
        heap: &mut std::collections::BinaryHeap<(u32, u32)>,
    ) {
        recursive_walk(map, range, p, &mut |i, ph| {
            let d2 = (ph.position - p).length_squared();
            if d2 < *bound && ph.normal.dot(Vec3::Z) > NORMAL_FILTER {
                heap.push((d2.to_bits(), i as u32));
                if heap.len() > k {
                    heap.pop();
                }
                if heap.len() == k {
                    *bound = f32::from_bits(heap.peek().map_or(0, |e| e.0));
                }
            }
            *bound
        });
    }

    #[test]
    fn k_nearest_keeps_the_photons_of_a_push_and_pop_heap_with_ties() {
        // A coarse lattice with repeated points: many photons at exactly the k-th distance,
        // where which ones are kept depends on the order they are offered in.
        let mut photons = Vec::new();
        for (i, p) in scattered(3000, 11).into_iter().enumerate() {
            let p = (p * 8.0).round() / 8.0;
            let normal = if i % 5 == 0 { -Vec3::Z } else { Vec3::Z };
            for copy in 0..1 + i % 3 {
                photons.push(Photon {
                    position: p,
                    power: Vec3::splat(copy as f32),
                    incoming: Vec3::Z,
                    normal,
                });
            }
        }
        let map = PhotonMap::build(photons);
        let mut out = Vec::new();
        let mut full = 0;
        for q in scattered(200, 12) {
            let q = (q * 16.0).round() / 16.0;
            for (k, r_max) in [(2, 0.3f32), (8, 0.3), (64, 0.5), (300, 2.0)] {
                let mut heap = std::collections::BinaryHeap::new();
                let mut bound = r_max * r_max;
                recursive_k_nearest(&map, (0, map.len()), q, k, &mut bound, &mut heap);
                let want: Vec<(f32, u32)> = heap
                    .into_sorted_vec()
                    .into_iter()
                    .map(|(d2, i)| (f32::from_bits(d2), i))
                    .collect();
                map.nearest(q, Some(Vec3::Z), k, r_max, &mut out);
                let got: Vec<(f32, u32)> = out.iter().map(|n| (n.dist2, n.index)).collect();
                assert_eq!(got, want, "query {q}, k {k}, r_max {r_max}");
                full += usize::from(got.len() == k);
            }
        }
        assert!(full > 300, "only {full} gathers were full");
    }

    #[test]
    fn fixed_radius_estimate_counts_the_disc_and_invalid_photons_are_dropped() {
        let mut photons = grid(10);
        photons[5].position = Vec3::NAN;
        photons[6].power = Vec3::INFINITY;
        let map = PhotonMap::build(photons);
        assert_eq!(map.len(), 98);
        assert_eq!(map.total_power(), Vec3::splat(98.0));
        // Within 1.2 of (3, 3): the centre and its 4 edge neighbours (diagonals are √2 away).
        let mut scratch = Vec::new();
        let e = map.estimate(
            Vec3::new(3.0, 3.0, 0.0),
            Vec3::Z,
            Gather::Radius(1.2),
            &mut scratch,
            |_| Vec3::ONE,
        );
        let expected = 5.0 / (std::f32::consts::PI * 1.44);
        assert!(
            (e - Vec3::splat(expected)).abs().max_element() < 1e-6,
            "{e}"
        );
    }
}
