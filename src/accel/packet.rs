//! Common-origin ray packets: up to [`PACKET_RAYS`] rays that leave from a few shared origins
//! (the hemisphere rays of a bake texel's sample positions) traverse the hierarchy together,
//! for occlusion ([`Accel::occluded_packet`]) and closest hits ([`Accel::intersect_packet`]).
//!
//! * **Shared node work**: per node, the child planes minus each of the packet's origins are
//!   computed once; each ray only multiplies them by its reciprocal direction. The product,
//!   the `max(n, acc)`/`min(f, acc)` chain, the far scale and the ordered `≤` are those of the
//!   single-ray slab test (`traverse.rs`), so every ray's child mask is the single-ray
//!   kernel's bit for bit. The packet's loop (pop, node fetch, pushes) runs once per node for
//!   all its rays, without a branch per ray.
//! * **Masks**: a stack entry carries the rays that entered the child (a 64-bit mask; the
//!   AVX2 test ORs each ray's bit into the slots it enters, in two registers, the SSE test
//!   transposes the per-ray child masks with `pmovmskb`), so a ray tests exactly the leaves
//!   its own traversal reaches, with the same watertight test (`WoopRay::intersect`; the
//!   AVX2 kernels test a leaf's triangles against eight of the rays at once with its exact
//!   arithmetic, `packet_leaf.rs`).
//!   Occlusion retires a ray at its first hit below its `t_max`; closest hit keeps each ray's
//!   smallest `(t, original index)` with its own `t` as the far end of its box tests. The
//!   answers are therefore `occluded`'s and `intersect`'s, ray by ray, bit for bit (the tests
//!   below compare them on rays from shared origins in boxes, near surfaces, with zero
//!   direction components of both signs and finite and infinite `t_max`).
//! * **Kernels**: AVX2 (the eight children of a node in one register, one ray at a time),
//!   chosen at run time (`is_x86_feature_detected!`); the SSE test (two groups of four) as the
//!   fallback, and with `STAGELIGHT_TRAVERSAL=sse` (read once) for A/B runs.
//! * **Few branches per node** (occlusion): the leaf slots come from one mask, the inner
//!   children are pushed without a branch each, every origin's planes are made whether it
//!   has rays in the node or not, the ray lanes' axis permutation is chosen with masks, and
//!   the leaf test compares `t < t_max` in the vector: their outcomes vary from node to
//!   node and ray to ray, so branches on them mispredicted (issue 17, session 18).
//! * **Packing**: rays are taken in order; a packet closes at [`PACKET_RAYS`] rays or when a
//!   ninth distinct origin (compared bit for bit) comes. Invalid rays are answered without
//!   traversal. Rays from many origins are still answered exactly, only without the sharing.

use std::ops::Range;

use glam::{Vec3, Vec4};

use super::bvh::{Bvh, Node, EMPTY_CHILD, LEAF_BIT};
use super::packet_leaf::RayLanes;
use super::traverse::{leaf_range, octant, FAR_SCALE_FACTOR};
use super::triangle::{ray_is_valid, WoopRay};
use super::{Accel, Hit, Ray};

/// Rays in one packet (one bit each in a `u64` mask).
pub(crate) const PACKET_RAYS: usize = 64;

/// Distinct origins in one packet (a texel's four sample positions, each with the origins
/// above and below its surface).
const PACKET_ORIGINS: usize = 8;

impl Accel {
    /// Occlusion of rays that share few origins: `out[i]` is `self.occluded(&rays[i])`, bit
    /// for bit, traced in common-origin packets (`packet.rs`): faster than one query per ray
    /// when many rays leave from each origin.
    ///
    /// # Panics
    /// When `rays` and `out` differ in length.
    pub fn occluded_packet(&self, rays: &[Ray], out: &mut [bool]) {
        assert_eq!(rays.len(), out.len(), "one result slot per ray");
        self.counters.add_occlusion(rays.len() as u64);
        with_scratch(|scratch| {
            #[cfg(target_arch = "x86_64")]
            if use_avx2() {
                // SAFETY: AVX2 was detected on this CPU (`use_avx2`).
                unsafe { occluded_avx2(&self.bvh, rays, out, scratch) };
                return;
            }
            occluded_in::<Planes4>(&self.bvh, rays, out, scratch);
        });
    }

    /// Closest hits of rays that share few origins: `out[i]` is `self.intersect(&rays[i])`,
    /// bit for bit, traced in common-origin packets like [`Accel::occluded_packet`].
    ///
    /// # Panics
    /// When `rays` and `out` differ in length.
    pub fn intersect_packet(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        assert_eq!(rays.len(), out.len(), "one result slot per ray");
        self.counters.add_closest(rays.len() as u64);
        with_scratch(|scratch| {
            #[cfg(target_arch = "x86_64")]
            if use_avx2() {
                // SAFETY: AVX2 was detected on this CPU (`use_avx2`).
                unsafe { closest_avx2(&self.bvh, rays, out, scratch) };
                return;
            }
            closest_in::<Planes4>(&self.bvh, rays, out, scratch);
        });
    }
}

/// A thread's packet and traversal stack, kept between calls (a bake makes one call per
/// texel: no allocation per call).
struct Scratch {
    packet: Packet,
    stack: Vec<(u32, u64)>,
}

impl Scratch {
    fn new() -> Self {
        Self {
            packet: Packet::new(),
            stack: Vec::new(),
        }
    }
}

/// Runs `f` with this thread's [`Scratch`].
fn with_scratch(f: impl FnOnce(&mut Scratch)) {
    thread_local! {
        static SCRATCH: std::cell::RefCell<Option<Box<Scratch>>> =
            const { std::cell::RefCell::new(None) };
    }
    SCRATCH.with_borrow_mut(|s| f(s.get_or_insert_with(|| Box::new(Scratch::new()))));
}

/// Whether the AVX2 packet kernels run (AVX2 present, not turned off by
/// `STAGELIGHT_TRAVERSAL=sse…`, as for the single-ray kernels).
#[cfg(target_arch = "x86_64")]
fn use_avx2() -> bool {
    static CHOICE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *CHOICE.get_or_init(|| {
        std::arch::is_x86_feature_detected!("avx2")
            && !std::env::var("STAGELIGHT_TRAVERSAL").is_ok_and(|v| v.starts_with("sse"))
    })
}

/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn occluded_avx2(bvh: &Bvh, rays: &[Ray], out: &mut [bool], scratch: &mut Scratch) {
    occluded_in::<wide::Planes8>(bvh, rays, out, scratch);
}

/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn closest_avx2(bvh: &Bvh, rays: &[Ray], out: &mut [Option<Hit>], scratch: &mut Scratch) {
    closest_in::<wide::Planes8>(bvh, rays, out, scratch);
}

/// The rays of one packet, ready for traversal: per ray its caller's index, origin, the
/// reciprocal direction and near planes of the slab test, its `t_max` and watertight-test
/// constants.
struct Packet {
    len: usize,
    index: [usize; PACKET_RAYS],
    origin_of: [u8; PACKET_RAYS],
    inv: [[f32; 3]; PACKET_RAYS],
    /// Near plane per axis (`2·axis`, plus 1 when the direction's sign bit is set).
    near: [[u8; 3]; PACKET_RAYS],
    t_max: [f32; PACKET_RAYS],
    dir: [Vec3; PACKET_RAYS],
    /// Each ray's watertight test, made only for the kernels that test leaves one ray at a
    /// time (`PacketTest::SCALAR_LEAVES`); the others use `lanes` and [`Packet::woop_of`].
    woop: Vec<WoopRay>,
    /// The same constants as arrays over the rays (the AVX2 leaf test's ray lanes).
    lanes: RayLanes<PACKET_RAYS>,
    origins: [Vec3; PACKET_ORIGINS],
    /// The rays leaving from each origin.
    origin_rays: [u64; PACKET_ORIGINS],
    n_origins: usize,
}

impl Packet {
    fn new() -> Self {
        Self {
            len: 0,
            index: [0; PACKET_RAYS],
            origin_of: [0; PACKET_RAYS],
            inv: [[0.0; 3]; PACKET_RAYS],
            near: [[0; 3]; PACKET_RAYS],
            t_max: [0.0; PACKET_RAYS],
            dir: [Vec3::ZERO; PACKET_RAYS],
            woop: Vec::with_capacity(PACKET_RAYS),
            lanes: RayLanes::new(),
            origins: [Vec3::ZERO; PACKET_ORIGINS],
            origin_rays: [0; PACKET_ORIGINS],
            n_origins: 0,
        }
    }

    fn clear(&mut self) {
        self.len = 0;
        self.n_origins = 0;
        self.origin_rays = [0; PACKET_ORIGINS];
        self.woop.clear();
    }

    /// Adds ray `index` (valid); false (nothing added) when the packet is full or the ray
    /// would bring a new origin past [`PACKET_ORIGINS`]. With `scalar_leaves` the ray's
    /// `WoopRay` is kept, else its lanes are set without it.
    #[inline(always)]
    fn add(&mut self, index: usize, ray: &Ray, scalar_leaves: bool) -> bool {
        if self.len == PACKET_RAYS {
            return false;
        }
        let bits = ray.origin.to_array().map(f32::to_bits);
        let found = self.origins[..self.n_origins]
            .iter()
            .position(|o| o.to_array().map(f32::to_bits) == bits);
        let o = match found {
            Some(o) => o,
            None if self.n_origins < PACKET_ORIGINS => {
                self.origins[self.n_origins] = ray.origin;
                self.n_origins += 1;
                self.n_origins - 1
            }
            None => return false,
        };
        let i = self.len;
        let d = ray.dir.to_array();
        self.index[i] = index;
        self.origin_of[i] = o as u8;
        self.origin_rays[o] |= 1 << i;
        self.inv[i] = ray.dir.recip().to_array();
        // The sign bit decides (−0.0 counts as negative, matching 1/−0 = −∞).
        self.near[i] = [0, 1, 2].map(|a| (2 * a + usize::from(d[a].is_sign_negative())) as u8);
        self.t_max[i] = ray.t_max;
        self.dir[i] = ray.dir;
        if scalar_leaves {
            self.woop.push(WoopRay::new(ray.origin, ray.dir));
        } else {
            self.lanes.set_ray(i, ray.origin, ray.dir);
        }
        self.len += 1;
        true
    }

    /// Ray `i`'s watertight test (for the lanes the vector leaf test leaves to the scalar
    /// one).
    #[inline(always)]
    fn woop_of(&self, i: usize) -> WoopRay {
        WoopRay::new(self.origins[self.origin_of[i] as usize], self.dir[i])
    }

    /// Every ray of the packet.
    fn all(&self) -> u64 {
        if self.len == PACKET_RAYS {
            u64::MAX
        } else {
            (1u64 << self.len) - 1
        }
    }
}

/// The slab test of a packet's rays against one node's children, in one instruction set.
/// `prepare` subtracts the origins of `rays` from the node's planes once; `mask` answers ray
/// `i`'s child mask (bit `s` for slot `s`), which is the single-ray test's mask for that ray
/// and `t_far`, bit for bit.
trait PacketTest {
    /// Whether the leaf tests take one ray at a time (`Packet::woop` kept per ray; else
    /// the ray lanes).
    const SCALAR_LEAVES: bool = true;

    fn new() -> Self;
    fn prepare(&mut self, node: &Node, packet: &Packet, rays: u64);
    fn mask(&self, packet: &Packet, i: usize, t_far: f32) -> u32;

    /// Per child slot the rays of `rays` that enter it (ray `i`'s far end `t_far[i]`), and
    /// the slots that some ray enters (zero: the entered masks are not computed). Here the
    /// per-ray masks transposed by [`child_rays`]; the AVX2 test accumulates them in
    /// registers.
    #[inline(always)]
    fn child_masks(
        &self,
        packet: &Packet,
        rays: u64,
        t_far: &[f32; PACKET_RAYS],
    ) -> ([u64; 8], u32) {
        let mut masks = [0u8; PACKET_RAYS];
        let mut any = 0;
        for i in bits(rays) {
            let m = self.mask(packet, i, t_far[i]);
            masks[i] = m as u8;
            any |= m;
        }
        if any == 0 {
            return ([0; 8], 0);
        }
        (child_rays(&masks, packet.len.div_ceil(16)), any)
    }

    /// The rays of `rays` that hit one of the triangles `range` (a leaf) with `t < t_max`,
    /// each answer that of `WoopRay::intersect`. One ray and one triangle at a time here;
    /// the AVX2 test takes eight rays at once (`packet_leaf.rs`).
    #[inline(always)]
    fn leaf_occluded(&self, bvh: &Bvh, packet: &Packet, range: Range<usize>, rays: u64) -> u64 {
        let mut hit = 0;
        for i in bits(rays) {
            let woop = &packet.woop[i];
            let t_max = packet.t_max[i];
            for k in range.clone() {
                if woop
                    .intersect(&bvh.tris[k].v)
                    .is_some_and(|(t, _, _)| t < t_max)
                {
                    hit |= 1 << i;
                    break;
                }
            }
        }
        hit
    }

    /// Updates the closest candidates `best`, `best_t` of the rays of `rays` with the
    /// triangles `range` (a leaf), triangle by triangle for each ray, with the answers of
    /// `WoopRay::intersect`.
    #[inline(always)]
    fn leaf_closest(
        &self,
        bvh: &Bvh,
        packet: &Packet,
        range: Range<usize>,
        rays: u64,
        best: &mut Best,
    ) {
        for i in bits(rays) {
            let woop = &packet.woop[i];
            for k in range.clone() {
                if let Some(hit) = woop.intersect(&bvh.tris[k].v) {
                    best.offer(bvh, i, k, hit);
                }
            }
        }
    }
}

/// Per ray of a packet, the closest candidate as (BVH-order index, b1, b2) and its `t`,
/// which starts at `t_max` (the single-ray kernel's state).
struct Best {
    hit: [Option<(usize, f32, f32)>; PACKET_RAYS],
    t: [f32; PACKET_RAYS],
}

impl Best {
    /// Ray `i` met triangle `k` (BVH order) at `(t, b1, b2)`: kept when nearer, or as near
    /// with a smaller caller index (the single-ray kernel's rule).
    #[inline(always)]
    fn offer(&mut self, bvh: &Bvh, i: usize, k: usize, (t, b1, b2): (f32, f32, f32)) {
        let better = t < self.t[i]
            || (t == self.t[i]
                && self.hit[i].is_some_and(|(bk, _, _)| bvh.tris[k].prim < bvh.tris[bk].prim));
        if better {
            self.hit[i] = Some((k, b1, b2));
            self.t[i] = t;
        }
    }
}

/// The SSE test (two groups of four children), the fallback: the operations of
/// `traverse::NodeRay::intersect` with `bounds − origin` computed once per node and origin.
struct Planes4 {
    /// `minus[origin][group][plane]`.
    minus: [[[Vec4; 6]; 2]; PACKET_ORIGINS],
    groups: usize,
}

impl PacketTest for Planes4 {
    fn new() -> Self {
        Self {
            minus: [[[Vec4::ZERO; 6]; 2]; PACKET_ORIGINS],
            groups: 2,
        }
    }

    #[inline(always)]
    fn prepare(&mut self, node: &Node, packet: &Packet, rays: u64) {
        // Children are packed: an empty slot 4 means the second group is empty.
        self.groups = if node.child[4] == EMPTY_CHILD { 1 } else { 2 };
        for o in 0..packet.n_origins {
            if packet.origin_rays[o] & rays == 0 {
                continue;
            }
            let origin = packet.origins[o].to_array();
            for g in 0..self.groups {
                for (k, m) in self.minus[o][g].iter_mut().enumerate() {
                    *m = node.bounds[k][g] - Vec4::splat(origin[k / 2]);
                }
            }
        }
    }

    #[inline(always)]
    fn mask(&self, packet: &Packet, i: usize, t_far: f32) -> u32 {
        let minus = &self.minus[packet.origin_of[i] as usize];
        let (near, inv) = (packet.near[i], packet.inv[i]);
        let mut mask = 0;
        for (g, minus) in minus.iter().enumerate().take(self.groups) {
            // `a.max(acc)` is SSE `maxps(a, acc)`, which returns `acc` when either is NaN:
            // a NaN slab is ignored, as in the single-ray test.
            let mut tn = Vec4::ZERO;
            let mut tf = Vec4::splat(t_far);
            for a in 0..3 {
                let inv = Vec4::splat(inv[a]);
                let n = minus[near[a] as usize] * inv;
                let f = minus[near[a] as usize ^ 1] * inv;
                tn = n.max(tn);
                tf = f.min(tf);
            }
            let tf = tf * FAR_SCALE_FACTOR;
            mask |= tn.cmple(tf).bitmask() << (4 * g);
        }
        mask
    }
}

#[cfg(target_arch = "x86_64")]
mod wide {
    //! The AVX2 packet test: a node's eight children in one register.
    use std::arch::x86_64::{
        __m256, __m256i, _mm256_and_si256, _mm256_castps_si256, _mm256_castsi256_ps,
        _mm256_castsi256_si128, _mm256_cmp_ps, _mm256_cmpeq_epi32, _mm256_cvtepu32_epi64,
        _mm256_extracti128_si256, _mm256_loadu_ps, _mm256_max_ps, _mm256_min_ps,
        _mm256_movemask_ps, _mm256_mul_ps, _mm256_or_si256, _mm256_set1_epi32, _mm256_set1_ps,
        _mm256_setzero_ps, _mm256_setzero_si256, _mm256_slli_epi64, _mm256_storeu_si256,
        _mm256_sub_ps, _CMP_LE_OS,
    };

    use std::ops::Range;

    use super::super::packet_leaf::{Group8, LANES};
    use super::{
        bits, Best, Bvh, Node, Packet, PacketTest, FAR_SCALE_FACTOR, PACKET_ORIGINS, PACKET_RAYS,
    };

    /// Planes minus each origin, eight children per register. Only made inside the AVX2
    /// kernels (the type is private to this file), so its methods may use AVX.
    pub(super) struct Planes8 {
        minus: [[__m256; 6]; PACKET_ORIGINS],
    }

    impl Planes8 {
        /// Ray `i`'s slab test against the node's eight children: lane `s` all ones when
        /// it enters slot `s` (the single-ray test's operations and order).
        #[inline(always)]
        fn entered(&self, packet: &Packet, i: usize, t_far: f32) -> __m256 {
            let minus = &self.minus[packet.origin_of[i] as usize];
            let (near, inv) = (packet.near[i], packet.inv[i]);
            // SAFETY: AVX intrinsics; this type exists only inside the AVX2 kernels.
            unsafe {
                let mut tn = _mm256_setzero_ps();
                let mut tf = _mm256_set1_ps(t_far);
                for a in 0..3 {
                    let inv = _mm256_set1_ps(inv[a]);
                    let n = _mm256_mul_ps(minus[near[a] as usize], inv);
                    let f = _mm256_mul_ps(minus[near[a] as usize ^ 1], inv);
                    // `max(n, acc)` returns `acc` when either is NaN, as SSE `maxps` does.
                    tn = _mm256_max_ps(n, tn);
                    tf = _mm256_min_ps(f, tf);
                }
                let tf = _mm256_mul_ps(tf, _mm256_set1_ps(FAR_SCALE_FACTOR));
                _mm256_cmp_ps::<_CMP_LE_OS>(tn, tf)
            }
        }
    }

    impl PacketTest for Planes8 {
        const SCALAR_LEAVES: bool = false;

        #[inline(always)]
        fn new() -> Self {
            // SAFETY: AVX; this type exists only inside the AVX2 kernels.
            let zero = unsafe { _mm256_setzero_ps() };
            Self {
                minus: [[zero; 6]; PACKET_ORIGINS],
            }
        }

        #[inline(always)]
        fn prepare(&mut self, node: &Node, packet: &Packet, _rays: u64) {
            // SAFETY: AVX intrinsics; this type exists only inside the AVX2 kernels. Each
            // load reads one plane `bounds[k]` (two `Vec4`s, 32 bytes) through a pointer to
            // it. No closures
            // here: they would not inherit the AVX2 target feature.
            unsafe {
                let mut planes = [_mm256_setzero_ps(); 6];
                for (k, p) in planes.iter_mut().enumerate() {
                    *p = _mm256_loadu_ps(node.bounds[k].as_ptr().cast());
                }
                // Every origin, also those without rays here: a branch per origin would
                // mispredict (about once per node), six subtractions do not.
                for o in 0..packet.n_origins {
                    let origin = packet.origins[o].to_array();
                    for (k, m) in self.minus[o].iter_mut().enumerate() {
                        *m = _mm256_sub_ps(planes[k], _mm256_set1_ps(origin[k / 2]));
                    }
                }
            }
        }

        #[inline(always)]
        fn mask(&self, packet: &Packet, i: usize, t_far: f32) -> u32 {
            // SAFETY: AVX intrinsics; this type exists only inside the AVX2 kernels.
            unsafe { _mm256_movemask_ps(self.entered(packet, i, t_far)) as u32 }
        }

        /// The masks accumulated in two registers, one 32-bit lane per child slot (rays
        /// 0–31 and 32–63): each ray ORs its bit into the slots it enters. No per-ray byte
        /// stores and no transposition (whose 16-byte load waited for those stores).
        #[inline(always)]
        fn child_masks(
            &self,
            packet: &Packet,
            rays: u64,
            t_far: &[f32; PACKET_RAYS],
        ) -> ([u64; 8], u32) {
            // SAFETY: AVX2 intrinsics; this type exists only inside the AVX2 kernels. The
            // stores write two local arrays of four `u64` each.
            unsafe {
                let zero = _mm256_setzero_si256();
                let (mut lo, mut hi) = (zero, zero);
                // One loop over the rays (a second would mispredict its exit once more per
                // node): ray `i`'s bit goes to `lo` (rays 0–31) or `hi` (32–63).
                for i in bits(rays) {
                    let c = _mm256_castps_si256(self.entered(packet, i, t_far[i]));
                    let bit = 1u64 << i;
                    lo = _mm256_or_si256(lo, _mm256_and_si256(c, _mm256_set1_epi32(bit as i32)));
                    hi = _mm256_or_si256(
                        hi,
                        _mm256_and_si256(c, _mm256_set1_epi32((bit >> 32) as i32)),
                    );
                }
                let none = _mm256_cmpeq_epi32(_mm256_or_si256(lo, hi), zero);
                let any = !(_mm256_movemask_ps(_mm256_castsi256_ps(none)) as u32) & 0xff;
                // Slot s: lane s of `lo` in the low half, of `hi` in the high half.
                let first = _mm256_or_si256(
                    _mm256_cvtepu32_epi64(_mm256_castsi256_si128(lo)),
                    _mm256_slli_epi64::<32>(_mm256_cvtepu32_epi64(_mm256_castsi256_si128(hi))),
                );
                let second = _mm256_or_si256(
                    _mm256_cvtepu32_epi64(_mm256_extracti128_si256::<1>(lo)),
                    _mm256_slli_epi64::<32>(_mm256_cvtepu32_epi64(_mm256_extracti128_si256::<1>(
                        hi,
                    ))),
                );
                let mut out = [0u64; 8];
                _mm256_storeu_si256(out.as_mut_ptr().cast::<__m256i>(), first);
                _mm256_storeu_si256(out.as_mut_ptr().add(4).cast::<__m256i>(), second);
                (out, any)
            }
        }

        /// Eight rays at a time against each triangle (`packet_leaf.rs`); the lanes the
        /// vector test cannot decide are answered by the scalar test.
        #[inline(always)]
        fn leaf_occluded(&self, bvh: &Bvh, packet: &Packet, range: Range<usize>, rays: u64) -> u64 {
            let mut hit = 0;
            let mut rest = rays;
            while rest != 0 {
                let g = rest.trailing_zeros() as usize / LANES;
                let at = LANES * g;
                let mut lanes = (rest >> at) as u32 & 0xff;
                rest &= !(0xff << at);
                let group = Group8::load(&packet.lanes, g);
                // SAFETY: AVX load of eight floats inside `t_max` (at + 8 ≤ 64: `at` is a
                // multiple of 8 below 64), through a reference.
                let t_max = unsafe { _mm256_loadu_ps(packet.t_max.as_ptr().add(at)) };
                for k in range.clone() {
                    let tri = &bvh.tris[k].v;
                    let found = group.occludes(tri, lanes, t_max);
                    let mut h = found.hit;
                    for j in bits(u64::from(found.slow)) {
                        let t_max = packet.t_max[at + j];
                        if packet
                            .woop_of(at + j)
                            .intersect(tri)
                            .is_some_and(|(t, _, _)| t < t_max)
                        {
                            h |= 1 << j;
                        }
                    }
                    lanes &= !h;
                    hit |= u64::from(h) << at;
                    if lanes == 0 {
                        break;
                    }
                }
            }
            hit
        }

        /// Eight rays at a time against each triangle, in the leaf's order; slow lanes by
        /// the scalar test.
        #[inline(always)]
        fn leaf_closest(
            &self,
            bvh: &Bvh,
            packet: &Packet,
            range: Range<usize>,
            rays: u64,
            best: &mut Best,
        ) {
            let mut rest = rays;
            while rest != 0 {
                let g = rest.trailing_zeros() as usize / LANES;
                let at = LANES * g;
                let lanes = (rest >> at) as u32 & 0xff;
                rest &= !(0xff << at);
                let group = Group8::load(&packet.lanes, g);
                for k in range.clone() {
                    let tri = &bvh.tris[k].v;
                    let found = group.test(tri, lanes);
                    for j in bits(u64::from(found.hit | found.slow)) {
                        let hit = if found.slow >> j & 1 != 0 {
                            match packet.woop_of(at + j).intersect(tri) {
                                Some(hit) => hit,
                                None => continue,
                            }
                        } else {
                            (found.t[j], found.b1[j], found.b2[j])
                        };
                        best.offer(bvh, at + j, k, hit);
                    }
                }
            }
        }
    }
}

/// Per child slot, the rays whose mask (`masks[ray]`, bit `slot`) has it: the 64×8 bit
/// matrix transposed (`pmovmskb` on x86-64, SSE2 is baseline there). Only the first
/// `16·chunks` rays are read.
#[inline(always)]
fn child_rays(masks: &[u8; PACKET_RAYS], chunks: usize) -> [u64; 8] {
    let mut out = [0u64; 8];
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{__m128i, _mm_add_epi8, _mm_loadu_si128, _mm_movemask_epi8};
        for chunk in 0..chunks {
            // SAFETY: SSE2 is baseline on x86_64; the load reads 16 bytes inside `masks`
            // (chunk < 4) through a reference to it.
            unsafe {
                let mut v =
                    _mm_loadu_si128(std::ptr::from_ref(&masks[16 * chunk]).cast::<__m128i>());
                // The top bit of each byte is slot 7's; doubling moves the next slot up.
                for slot in (0..8).rev() {
                    out[slot] |= u64::from(_mm_movemask_epi8(v) as u16) << (16 * chunk);
                    v = _mm_add_epi8(v, v);
                }
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    for (i, &m) in masks.iter().enumerate().take(16 * chunks) {
        for (slot, o) in out.iter_mut().enumerate() {
            *o |= u64::from(m >> slot & 1) << i;
        }
    }
    out
}

/// The set bits of a mask, lowest first.
#[inline(always)]
fn bits(mut m: u64) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (m != 0).then(|| {
            let i = m.trailing_zeros() as usize;
            m &= m - 1;
            i
        })
    })
}

/// Fills `packet` with the valid rays of `rays` from `start` on (invalid rays hit nothing
/// and are left out) until it is full; returns where the next packet starts.
#[inline(always)]
fn fill<T: PacketTest>(rays: &[Ray], start: usize, packet: &mut Packet) -> usize {
    packet.clear();
    let mut i = start;
    while i < rays.len() {
        if ray_is_valid(&rays[i]) && !packet.add(i, &rays[i], T::SCALAR_LEAVES) {
            break;
        }
        i += 1;
    }
    i
}

/// Occlusion of `rays` into `out` with the packet test `T`.
#[inline(always)]
fn occluded_in<T: PacketTest>(bvh: &Bvh, rays: &[Ray], out: &mut [bool], scratch: &mut Scratch) {
    out.fill(false);
    if bvh.nodes.is_empty() {
        return;
    }
    let Scratch { packet, stack } = scratch;
    let mut test = T::new();
    // A plain loop, not closures: a closure would not inherit the AVX2 target feature.
    let mut next = 0;
    while next < rays.len() {
        next = fill::<T>(rays, next, packet);
        let hit = occluded_packet(bvh, packet, &mut test, stack);
        for i in bits(hit) {
            out[packet.index[i]] = true;
        }
    }
}

/// The rays of `packet` that are occluded (a mask).
///
/// Few data-dependent branches per node (they mispredict on the rays' varying masks): the
/// leaf and inner children come from one mask of the node's leaf slots, and the inner ones
/// are pushed without a branch each (every slot is written, the stack top advances only over
/// the entered inner children), so `stack` is a slice of slots, not a `Vec` of entries.
#[inline(always)]
fn occluded_packet<T: PacketTest>(
    bvh: &Bvh,
    packet: &Packet,
    test: &mut T,
    stack: &mut Vec<(u32, u64)>,
) -> u64 {
    let mut active = packet.all();
    if stack.len() < STACK_SLOTS {
        stack.resize(STACK_SLOTS, (0, 0));
    }
    stack[0] = (0, active);
    let mut top = 1;
    while top > 0 {
        top -= 1;
        let (node_ref, rays) = stack[top];
        let rays = rays & active;
        if rays == 0 {
            continue;
        }
        let node = &bvh.nodes[node_ref as usize];
        test.prepare(node, packet, rays);
        let (entered, any) = test.child_masks(packet, rays, &packet.t_max);
        let leaves = leaf_slots(node);
        // Leaves first: a ray that hits one needs no further nodes.
        for slot in bits(u64::from(any & leaves)) {
            let rays = entered[slot] & active;
            if rays != 0 {
                active &= !test.leaf_occluded(bvh, packet, leaf_range(node.child[slot]), rays);
            }
        }
        if active == 0 {
            break;
        }
        if top + 8 > stack.len() {
            stack.resize(2 * stack.len(), (0, 0));
        }
        let inner = any & !leaves;
        for (slot, (&child, &rays)) in node.child.iter().zip(&entered).enumerate() {
            stack[top] = (child, rays);
            top += (inner >> slot & 1) as usize;
        }
    }
    packet.all() & !active
}

/// Stack slots kept for the occlusion kernel (it grows when a deep hierarchy needs more).
/// Unit tests start from 8, so that every packet test also runs the growth path.
const STACK_SLOTS: usize = if cfg!(test) { 8 } else { 128 };

/// The slots of `node` that hold leaves (bit `s` for slot `s`; empty slots count as leaves,
/// they are never entered).
#[inline(always)]
fn leaf_slots(node: &Node) -> u32 {
    let mut leaves = 0;
    for (slot, &child) in node.child.iter().enumerate() {
        leaves |= (child >> 31) << slot;
    }
    leaves
}

/// Closest hits of `rays` into `out` with the packet test `T`.
#[inline(always)]
fn closest_in<T: PacketTest>(
    bvh: &Bvh,
    rays: &[Ray],
    out: &mut [Option<Hit>],
    scratch: &mut Scratch,
) {
    out.fill(None);
    if bvh.nodes.is_empty() {
        return;
    }
    let Scratch { packet, stack } = scratch;
    let mut test = T::new();
    let mut next = 0;
    while next < rays.len() {
        next = fill::<T>(rays, next, packet);
        if packet.len == 0 {
            continue;
        }
        let octant = octant(&rays[packet.index[0]]);
        let hits = closest_packet(bvh, packet, octant, &mut test, stack);
        for (i, hit) in hits.iter().enumerate().take(packet.len) {
            out[packet.index[i]] = *hit;
        }
    }
}

/// The closest hit of each ray of `packet`. Children are visited in the node's order for
/// `octant` (the first ray's): leaves at once, inner nodes pushed farthest first.
#[inline(always)]
fn closest_packet<T: PacketTest>(
    bvh: &Bvh,
    packet: &Packet,
    octant: usize,
    test: &mut T,
    stack: &mut Vec<(u32, u64)>,
) -> [Option<Hit>; PACKET_RAYS] {
    let mut best = Best {
        hit: [None; PACKET_RAYS],
        t: packet.t_max,
    };
    stack.clear();
    stack.push((0, packet.all()));
    while let Some((node_ref, rays)) = stack.pop() {
        let node = &bvh.nodes[node_ref as usize];
        test.prepare(node, packet, rays);
        let (entered, any) = test.child_masks(packet, rays, &best.t);
        if any == 0 {
            continue;
        }
        let order = node.order[octant];
        let slot_at = |k: usize| (order >> (3 * k) & 7) as usize;
        for k in 0..8 {
            let slot = slot_at(k);
            let child = node.child[slot];
            if any >> slot & 1 == 0 || child & LEAF_BIT == 0 {
                continue;
            }
            test.leaf_closest(bvh, packet, leaf_range(child), entered[slot], &mut best);
        }
        // Farthest first, so that the nearest is popped next.
        for k in (0..8).rev() {
            let slot = slot_at(k);
            let child = node.child[slot];
            if any >> slot & 1 != 0 && child & LEAF_BIT == 0 {
                stack.push((child, entered[slot]));
            }
        }
    }
    std::array::from_fn(|i| {
        best.hit[i].map(|(k, b1, b2)| Hit {
            t: best.t[i],
            prim: bvh.tris[k].prim,
            b1,
            b2,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::super::bvh::build;
    use super::super::{spawn, traverse};
    use super::*;
    use crate::settings::BvhQuality;

    fn hit_bits(h: Option<Hit>) -> Option<[u32; 4]> {
        h.map(|h| [h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()])
    }

    /// A closed box [−1, 1]³ (12 triangles), a soup of random triangles inside and around
    /// it, and triangles on the integer grid (so that rays run along box planes).
    fn scene(rnd: &mut impl FnMut() -> f32) -> Vec<[Vec3; 3]> {
        let mut tris = Vec::new();
        for axis in 0..3 {
            for side in [-1.0f32, 1.0] {
                let corner = |u: f32, v: f32| {
                    let mut p = [0.0; 3];
                    p[axis] = side;
                    p[(axis + 1) % 3] = u;
                    p[(axis + 2) % 3] = v;
                    Vec3::from_array(p)
                };
                let (a, b, c, d) = (
                    corner(-1.0, -1.0),
                    corner(1.0, -1.0),
                    corner(1.0, 1.0),
                    corner(-1.0, 1.0),
                );
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
        for i in 0..1500 {
            let c = if i % 2 == 0 {
                Vec3::new(rnd(), rnd(), rnd()) * 3.0
            } else {
                (Vec3::new(rnd(), rnd(), rnd()) * 3.0).round() * 0.5
            };
            let s = 0.05 + 0.3 * rnd().abs();
            tris.push([c, c + Vec3::X * s, c + Vec3::new(0.0, s, rnd() * s)]);
        }
        tris
    }

    /// Origins: inside the box, on a grid plane, far outside, and just off surfaces (spawned
    /// from a hit point of the soup with its error bound, on either side); per origin a
    /// group of rays with random directions, some with zero components of either sign,
    /// finite (short and long) and infinite `t_max`; groups of 1–70 rays, origins repeated
    /// so that packets mix up to and past eight origins.
    fn rays(tris: &[[Vec3; 3]], rnd: &mut impl FnMut() -> f32) -> Vec<Ray> {
        let mut origins = vec![
            Vec3::ZERO,
            Vec3::new(0.5, -0.25, 0.75),
            Vec3::new(1.0, 0.0, 0.5),
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(9.0, 8.0, -7.0),
        ];
        for (k, tri) in tris.iter().enumerate().step_by(97).take(12) {
            let (b1, b2) = (0.3, 0.25 + 0.01 * (k % 7) as f32);
            let sp = spawn::surface_point(tri, b1, b2);
            let side = if k % 2 == 0 { sp.ng } else { -sp.ng };
            origins.push(spawn::offset_ray_origin(sp.p, sp.p_err, sp.ng, side));
        }
        let mut out = Vec::new();
        for (g, &origin) in origins.iter().enumerate().cycle().take(90) {
            let count = [1, 5, 16, 33, 64, 70][g % 6];
            for i in 0..count {
                let mut dir = Vec3::new(rnd(), rnd(), rnd());
                match i % 7 {
                    0 => dir.x = 0.0,
                    1 => dir.y = -0.0,
                    2 => dir = Vec3::new(-0.0, 0.0, if rnd() < 0.0 { -1.0 } else { 1.0 }),
                    _ => {}
                }
                let t_max = match i % 4 {
                    0 => 0.05 + rnd().abs() * 0.3,
                    1 => 2.0 + rnd().abs() * 3.0,
                    _ => f32::INFINITY,
                };
                out.push(Ray { origin, dir, t_max });
            }
        }
        // Invalid rays are answered (no hit) without traversal.
        out.insert(
            3,
            Ray {
                origin: Vec3::ZERO,
                dir: Vec3::ZERO,
                t_max: f32::INFINITY,
            },
        );
        out.insert(
            40,
            Ray {
                origin: Vec3::new(f32::NAN, 0.0, 0.0),
                dir: Vec3::X,
                t_max: 1.0,
            },
        );
        out
    }

    fn rng() -> impl FnMut() -> f32 {
        crate::accel::test_random::signed_uniform(0x2545_f491_4f6c_dd1du64)
    }

    /// Both packet kernels (SSE groups of four, and AVX2 where this CPU has it) and the
    /// public entry points answer, ray by ray and bit for bit, what the single-ray SSE kernel
    /// answers: occlusion and closest hits (t, triangle, barycentrics), from shared origins
    /// inside a closed box, near surfaces, on grid planes, with zero direction components
    /// and finite and infinite `t_max`.
    #[test]
    fn packets_equal_single_ray_queries() {
        let mut rnd = rng();
        let tris = scene(&mut rnd);
        let rays = rays(&tris, &mut rnd);
        assert!(rays.len() > 2000);
        for q in [BvhQuality::Fast, BvhQuality::Medium] {
            let bvh = build(&tris, q);
            let want_occ: Vec<bool> = rays.iter().map(|r| traverse::occluded(&bvh, r)).collect();
            let want_hit: Vec<_> = rays
                .iter()
                .map(|r| hit_bits(traverse::closest(&bvh, r)))
                .collect();
            let (occluded, open) = (
                want_occ.iter().filter(|o| **o).count(),
                want_occ.iter().filter(|o| !**o).count(),
            );
            assert!(
                occluded > 500 && open > 500,
                "{occluded} occluded, {open} open"
            );
            let mut occ = vec![true; rays.len()];
            let mut hit = vec![None; rays.len()];
            let mut scratch = Scratch::new();
            occluded_in::<Planes4>(&bvh, &rays, &mut occ, &mut scratch);
            closest_in::<Planes4>(&bvh, &rays, &mut hit, &mut scratch);
            check(&rays, &occ, &hit, &want_occ, &want_hit, "SSE");
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: AVX2 was detected just above.
                unsafe {
                    occluded_avx2(&bvh, &rays, &mut occ, &mut scratch);
                    closest_avx2(&bvh, &rays, &mut hit, &mut scratch);
                }
                check(&rays, &occ, &hit, &want_occ, &want_hit, "AVX2");
            }
        }
        // Through `Accel` (the kernel this CPU runs), which counts the queries.
        let accel = Accel::build(tris, BvhQuality::Medium);
        let mut occ = vec![false; rays.len()];
        let mut hit = vec![None; rays.len()];
        accel.occluded_packet(&rays, &mut occ);
        accel.intersect_packet(&rays, &mut hit);
        for (i, r) in rays.iter().enumerate() {
            assert_eq!(occ[i], accel.occluded(r), "{r:?}");
            assert_eq!(hit_bits(hit[i]), hit_bits(accel.intersect(r)), "{r:?}");
        }
        let counts = accel.ray_counts();
        let n = rays.len() as u64;
        assert_eq!((counts.closest, counts.occlusion), (2 * n, 2 * n));
    }

    fn check(
        rays: &[Ray],
        occ: &[bool],
        hit: &[Option<Hit>],
        want_occ: &[bool],
        want_hit: &[Option<[u32; 4]>],
        kernel: &str,
    ) {
        for (i, r) in rays.iter().enumerate() {
            assert_eq!(occ[i], want_occ[i], "{kernel} occlusion, ray {i}: {r:?}");
            assert_eq!(
                hit_bits(hit[i]),
                want_hit[i],
                "{kernel} closest, ray {i}: {r:?}"
            );
        }
    }

    /// Per node and packet, the AVX2 test's entered masks accumulated in registers
    /// (`Planes8::child_masks`) equal the per-ray masks transposed (the trait's default, the
    /// SSE test's), for every node of both hierarchies and packets of 1–64 rays, partial
    /// ray subsets included; and a node no ray enters gives no slot.
    #[test]
    fn register_masks_equal_the_transposed_masks() {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            /// # Safety
            /// The CPU must support AVX2.
            #[target_feature(enable = "avx2")]
            unsafe fn check_all(bvh: &Bvh, rays: &[Ray]) -> (usize, usize) {
                let mut packet = Packet::new();
                let mut test = <wide::Planes8 as PacketTest>::new();
                let (mut checked, mut entered_some) = (0, 0);
                let mut next = 0;
                while next < rays.len() {
                    next = fill::<wide::Planes8>(rays, next, &mut packet);
                    let all = packet.all();
                    for (n, node) in bvh.nodes.iter().enumerate() {
                        // All rays, and a sparse subset that varies with the node.
                        let subset = all & (0x9e37_79b9_7f4a_7c15u64.rotate_left(n as u32 % 64));
                        for rays in [all, subset] {
                            test.prepare(node, &packet, rays);
                            let (got, any) = test.child_masks(&packet, rays, &packet.t_max);
                            let mut masks = [0u8; PACKET_RAYS];
                            let mut want_any = 0;
                            for i in bits(rays) {
                                let m = test.mask(&packet, i, packet.t_max[i]);
                                masks[i] = m as u8;
                                want_any |= m;
                            }
                            assert_eq!(any, want_any, "node {n}");
                            if want_any != 0 {
                                let want = child_rays(&masks, packet.len.div_ceil(16));
                                assert_eq!(got, want, "node {n}");
                                entered_some += 1;
                            }
                            checked += 1;
                        }
                    }
                }
                (checked, entered_some)
            }
            let mut rnd = rng();
            let tris = scene(&mut rnd);
            let rays = rays(&tris, &mut rnd);
            for q in [BvhQuality::Fast, BvhQuality::Medium] {
                let bvh = build(&tris, q);
                // SAFETY: AVX2 was detected just above.
                let (checked, entered) = unsafe { check_all(&bvh, &rays) };
                assert!(checked > 10_000 && entered > 1_000, "{checked} {entered}");
            }
        }
    }

    /// The bit-matrix transposition gives each slot exactly the rays whose mask has it.
    #[test]
    fn child_rays_transposes_the_masks() {
        let mut rnd = rng();
        let mut masks = [0u8; PACKET_RAYS];
        for m in masks.iter_mut() {
            *m = ((rnd() + 1.0) * 127.9) as u8;
        }
        for chunks in 1..=4 {
            let t = child_rays(&masks, chunks);
            for (slot, rays) in t.iter().enumerate() {
                for (i, m) in masks.iter().enumerate() {
                    let want = i < 16 * chunks && m >> slot & 1 != 0;
                    assert_eq!(rays >> i & 1 != 0, want, "slot {slot}, ray {i}");
                }
            }
        }
    }

    #[test]
    fn empty_hierarchy_and_empty_input() {
        let accel = Accel::build(Vec::new(), BvhQuality::Fast);
        let r = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::X,
            t_max: f32::INFINITY,
        };
        let (mut occ, mut hit) = ([true], [None]);
        accel.occluded_packet(&[r], &mut occ);
        accel.intersect_packet(&[r], &mut hit);
        assert_eq!((occ, hit), ([false], [None]));
        accel.occluded_packet(&[], &mut []);
        accel.intersect_packet(&[], &mut []);
    }
}
