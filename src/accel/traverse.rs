//! The traversal kernel over our 8-wide nodes: closest hit and occlusion, one ray at a time.
//!
//! * **Slab test** (pbrt-v4 `Bounds3::IntersectP`, Ize 2013): `t = (plane − o) · (1/d)` with the
//!   exact IEEE reciprocal (±∞ for zero components, never clamped), far distances scaled by
//!   `1 + 2γ3`. The only NaN is `0 · ∞` (origin exactly on a plane of an axis the ray does not
//!   move along); the min/max chain is ordered so that such a slab is ignored, which is the
//!   conservative answer. The entry distance is clamped at 0 — not at obvhs's 1e-4.
//! * **Order**: hit children are pushed sorted by entry distance, nearest on top; popped
//!   entries farther than the current closest hit are skipped.
//! * **Stack**: sized from the tree depth measured at build (a fixed array when that fits, a
//!   `Vec` otherwise), so it cannot overflow.
//! * **Ties**: the closest hit is the smallest `(t, original index)`, so the result does not
//!   depend on traversal order (the brute-force reference gives the same answer).

use glam::Vec4;

use super::bvh::{Bvh, Node, COUNT_SHIFT, EMPTY_CHILD, FIRST_MASK, LEAF_BIT};
use super::triangle::{gamma, ray_is_valid, WoopRay};
use super::{Hit, Ray};

/// Far slab distances are scaled by this to make the box test conservative.
const FAR_SCALE: f32 = 1.0 + 2.0 * gamma(3);

/// Per-ray constants of the slab test.
struct NodeRay {
    o: [Vec4; 3],
    inv: [Vec4; 3],
    near: [usize; 3],
    far: [usize; 3],
}

impl NodeRay {
    #[inline]
    fn new(ray: &Ray) -> Self {
        let inv = ray.dir.recip();
        let d = ray.dir.to_array();
        // The sign bit decides (−0.0 counts as negative, matching 1/−0 = −∞).
        let near = [0, 1, 2].map(|a| 2 * a + usize::from(d[a].is_sign_negative()));
        Self {
            o: [
                Vec4::splat(ray.origin.x),
                Vec4::splat(ray.origin.y),
                Vec4::splat(ray.origin.z),
            ],
            inv: [Vec4::splat(inv.x), Vec4::splat(inv.y), Vec4::splat(inv.z)],
            near,
            far: near.map(|n| n ^ 1),
        }
    }

    /// Tests the eight children against `[0, t_far]`; returns the hit mask and entry distances.
    #[inline(always)]
    fn intersect(&self, node: &Node, t_far: f32) -> (u32, [Vec4; 2]) {
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
                let n = (node.bounds[g][self.near[a]] - self.o[a]) * self.inv[a];
                let f = (node.bounds[g][self.far[a]] - self.o[a]) * self.inv[a];
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

/// A deferred child: its reference and entry distance.
#[derive(Clone, Copy, Default)]
struct Entry {
    r: u32,
    t: f32,
}

/// The traversal stack interface (fixed array or heap).
trait Stack {
    fn push(&mut self, e: Entry);
    fn pop(&mut self) -> Option<Entry>;
    fn len(&self) -> usize;
    /// Sorts the entries from `from` to the top so that the smallest `t` is on top.
    fn sort_top(&mut self, from: usize);
}

/// A stack in a fixed array; `push` past `N` panics (never silently overwrites), and `N` is
/// chosen from the measured tree depth so that it never happens.
struct ArrayStack<const N: usize> {
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
}

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
    fn sort_top(&mut self, from: usize) {
        sort_descending(&mut self.items[from..self.len]);
    }
}

impl Stack for Vec<Entry> {
    #[inline(always)]
    fn push(&mut self, e: Entry) {
        Vec::push(self, e);
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<Entry> {
        Vec::pop(self)
    }
    #[inline(always)]
    fn len(&self) -> usize {
        Vec::len(self)
    }
    #[inline(always)]
    fn sort_top(&mut self, from: usize) {
        sort_descending(&mut self[from..]);
    }
}

/// Largest number of entries a traversal of a tree with `depth` node levels can hold: each
/// level on the current path leaves at most 7 siblings, plus the 8 children just pushed.
fn stack_bound(depth: u32) -> usize {
    8 * depth as usize + 8
}

/// Array size used for shallow trees (every realistic scene; deeper ones use the heap).
const ARRAY_STACK: usize = 128;

/// Closest hit of `ray`.
pub(crate) fn closest(bvh: &Bvh, ray: &Ray) -> Option<Hit> {
    if bvh.nodes.is_empty() || !ray_is_valid(ray) {
        return None;
    }
    if stack_bound(bvh.depth) <= ARRAY_STACK {
        closest_with(bvh, ray, ArrayStack::<ARRAY_STACK>::new())
    } else {
        closest_with(bvh, ray, Vec::with_capacity(stack_bound(bvh.depth)))
    }
}

/// Whether anything is hit with `0 < t < ray.t_max`.
pub(crate) fn occluded(bvh: &Bvh, ray: &Ray) -> bool {
    if bvh.nodes.is_empty() || !ray_is_valid(ray) {
        return false;
    }
    if stack_bound(bvh.depth) <= ARRAY_STACK {
        occluded_with(bvh, ray, ArrayStack::<ARRAY_STACK>::new())
    } else {
        occluded_with(bvh, ray, Vec::with_capacity(stack_bound(bvh.depth)))
    }
}

#[inline(always)]
fn leaf_range(r: u32) -> std::ops::Range<usize> {
    let first = (r & FIRST_MASK) as usize;
    let count = ((r & !LEAF_BIT) >> COUNT_SHIFT) as usize;
    first..first + count
}

fn closest_with<S: Stack>(bvh: &Bvh, ray: &Ray, mut stack: S) -> Option<Hit> {
    let woop = WoopRay::new(ray.origin, ray.dir);
    let nr = NodeRay::new(ray);
    // Until the first hit, t must be < ray.t_max; afterwards (t, prim) must be smaller.
    // The closest candidate so far as (BVH-order index, b1, b2); its original index is looked
    // up only on an exact tie and once at the end (`prim_ids` is cold).
    let mut best: Option<(usize, f32, f32)> = None;
    let mut best_t = ray.t_max;
    let mut cull = best_t * FAR_SCALE;
    let mut cur = 0u32;
    loop {
        if cur & LEAF_BIT != 0 {
            for k in leaf_range(cur) {
                if let Some((t, b1, b2)) = woop.intersect(&bvh.tris[k]) {
                    let better = t < best_t
                        || (t == best_t
                            && best.is_some_and(|(bk, _, _)| bvh.prim_ids[k] < bvh.prim_ids[bk]));
                    if better {
                        best = Some((k, b1, b2));
                        best_t = t;
                        cull = t * FAR_SCALE;
                    }
                }
            }
        } else {
            let node = &bvh.nodes[cur as usize];
            let (mut mask, entry) = nr.intersect(node, best_t);
            if mask != 0 {
                let base = stack.len();
                let tn: [f32; 8] = {
                    let (a, b) = (entry[0].to_array(), entry[1].to_array());
                    [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
                };
                while mask != 0 {
                    let slot = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
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
                        prim: bvh.prim_ids[k],
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

fn occluded_with<S: Stack>(bvh: &Bvh, ray: &Ray, mut stack: S) -> bool {
    let woop = WoopRay::new(ray.origin, ray.dir);
    let nr = NodeRay::new(ray);
    let mut cur = 0u32;
    loop {
        if cur & LEAF_BIT != 0 {
            for k in leaf_range(cur) {
                if let Some((t, _, _)) = woop.intersect(&bvh.tris[k]) {
                    if t < ray.t_max {
                        return true;
                    }
                }
            }
        } else {
            let node = &bvh.nodes[cur as usize];
            let (mut mask, _) = nr.intersect(node, ray.t_max);
            while mask != 0 {
                let slot = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                stack.push(Entry {
                    r: node.child[slot],
                    t: 0.0,
                });
            }
        }
        match stack.pop() {
            None => return false,
            Some(e) => cur = e.r,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn stack_bound_covers_eight_per_level() {
        assert!(stack_bound(1) >= 8);
        assert!(stack_bound(15) <= ARRAY_STACK);
        assert!(stack_bound(16) > ARRAY_STACK);
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
