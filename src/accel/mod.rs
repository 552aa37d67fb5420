//! Ray layer: watertight triangle intersection, robust ray spawning and the BVH over the
//! scene's world-space triangles.
//!
//! * [`Accel`] builds the hierarchy with `obvhs` and traverses it with its own kernel
//!   (`traverse.rs`); triangles are tested with the watertight test of `triangle.rs`.
//! * Instances are flattened by the caller: stagelight hands every instance's triangles to
//!   [`Accel::build`] already transformed into world space (obvhs has no transformed
//!   two-level traversal). Hit points, error bounds and offsets are therefore all in world
//!   space.
//! * Rays leaving a surface are made with [`spawn_ray`], [`spawn_ray_to`] and
//!   [`spawn_ray_to_surface`] from a [`SurfacePoint`] (`spawn.rs`): the origin is offset by
//!   the point's own error bound, never by a fixed epsilon.
//!
//! * Every query is counted ([`Accel::ray_counts`], `counters.rs`) for the per-stage ledger.
//!
//! Design notes and measurements: `docs/ray-layer.md`.

mod brute;
mod bvh;
mod counters;
mod huge_pages;
#[cfg(target_arch = "x86_64")]
mod leaf_wide;
mod packet;
mod packet_leaf;
mod ray_kind;
mod shortcut;
#[cfg(target_arch = "x86_64")]
mod small_scene;
mod spawn;
mod traversal_cost;
mod traverse;
#[cfg(target_arch = "x86_64")]
mod traverse_wide;
mod triangle;

use glam::Vec3;

use crate::settings::BvhQuality;

pub use brute::brute_force_intersect;
pub use bvh::BuildPhases;
pub use counters::RayCounts;
pub use ray_kind::{RayKind, MAX_PASSED, PACKET_MIN_RAYS};
pub use shortcut::{Shortcut, Shortcuts};
pub use spawn::{
    geometric_normal, offset_ray_origin, spawn_ray, spawn_ray_to, spawn_ray_to_surface,
    surface_point_with_normal, SHADOW_EPSILON,
};
pub use traversal_cost::TraversalCost;
pub use triangle::{gamma, intersect_triangle, is_degenerate, MACHINE_EPSILON};

/// A ray segment `origin + t·dir`, `t ∈ (0, t_max)`. `dir` need not be unit length; `t` is in
/// units of `dir`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Origin.
    pub origin: Vec3,
    /// Direction (not necessarily normalised).
    pub dir: Vec3,
    /// Far end of the segment (exclusive).
    pub t_max: f32,
}

/// A ray/triangle hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Parametric distance along the ray.
    pub t: f32,
    /// Index of the triangle in the order given to [`Accel::build`].
    pub prim: u32,
    /// Barycentric weight of vertex 1.
    pub b1: f32,
    /// Barycentric weight of vertex 2 (vertex 0 has `1 − b1 − b2`).
    pub b2: f32,
}

/// A point on a surface with its floating-point error bound, from which rays are spawned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Position computed from barycentrics.
    pub p: Vec3,
    /// Conservative per-axis absolute error bound of `p`.
    pub p_err: Vec3,
    /// Unit geometric normal, `(v1 − v0) × (v2 − v0)` normalised.
    pub ng: Vec3,
}

/// Size and build statistics of an [`Accel`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccelStats {
    /// Triangles given to [`Accel::build`].
    pub triangles: usize,
    /// Triangles in the hierarchy (degenerate ones are left out).
    pub bvh_triangles: usize,
    /// 8-wide nodes.
    pub nodes: usize,
    /// Node levels on the longest root-to-leaf path.
    pub depth: u32,
    /// Wall-clock build time in seconds.
    pub build_seconds: f64,
    /// The build time by phase.
    pub build_phases: BuildPhases,
    /// SAH cost of the hierarchy: expected node visits plus 0.3 per triangle test, for a ray
    /// that hits the root box (`collapse.rs`; lower is better).
    pub sah_cost: f64,
    /// Heap bytes of the mesh and the hierarchy: the triangles (one copy, in BVH order), the
    /// two index maps between BVH order and the caller's order, and the nodes.
    pub bytes: usize,
}

/// BVH over world-space triangles. `Send + Sync`: build once, trace from many threads.
pub struct Accel {
    /// The hierarchy; it also holds the triangles (`Bvh::tris`, BVH order).
    bvh: bvh::Bvh,
    counters: counters::Counters,
    /// Ray kinds that see each triangle (`ray_kind.rs`); `None`: every kind sees all.
    masks: Option<Vec<u8>>,
    /// Every triangle in SIMD lane groups when the mesh is small (`small_scene.rs`): single
    /// rays are then answered without the tree.
    #[cfg(target_arch = "x86_64")]
    small: Option<small_scene::SmallScene>,
    /// Shortcuts past convex parts (`shortcut.rs`), made on first use.
    shortcuts: std::sync::OnceLock<Shortcuts>,
}

impl Accel {
    /// Builds the hierarchy. Degenerate triangles (zero area, non-finite vertices) are kept in
    /// the index space but never hit. `triangles` is dropped once the hierarchy holds its
    /// BVH-order copy.
    pub fn build(triangles: Vec<[Vec3; 3]>, quality: BvhQuality) -> Self {
        let bvh = bvh::build(&triangles, quality);
        drop(triangles);
        #[cfg(target_arch = "x86_64")]
        let small = small_scene::SmallScene::build(&bvh.tris, small_scene::max_triangles());
        Self {
            bvh,
            counters: counters::Counters::new(),
            masks: None,
            #[cfg(target_arch = "x86_64")]
            small,
            shortcuts: std::sync::OnceLock::new(),
        }
    }

    /// The triangles without a hierarchy, for a run that reads them ([`Accel::triangle`],
    /// [`Accel::len`]) but traces no ray — a bake merge, whose texels come from the parts:
    /// every ray misses. Building the hierarchy there was most of the merge's time.
    pub fn without_hierarchy(triangles: Vec<[Vec3; 3]>) -> Self {
        Self {
            bvh: bvh::unindexed(&triangles),
            counters: counters::Counters::new(),
            masks: None,
            #[cfg(target_arch = "x86_64")]
            small: None,
            shortcuts: std::sync::OnceLock::new(),
        }
    }

    /// Whether [`Accel::shortcuts`] were made already.
    pub fn has_shortcuts(&self) -> bool {
        self.shortcuts.get().is_some()
    }

    /// The shortcuts past the convex ones of `parts` (disjoint ranges of triangles, asked
    /// for on the first call only; `shortcut.rs`).
    pub fn shortcuts(&self, parts: impl FnOnce() -> Vec<std::ops::Range<u32>>) -> &Shortcuts {
        self.shortcuts
            .get_or_init(|| Shortcuts::build(self, &parts()))
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.bvh.tris.len()
    }

    /// True when there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.bvh.tris.is_empty()
    }

    /// Vertices of triangle `prim` (index in the order given to [`Accel::build`]).
    pub fn triangle(&self, prim: u32) -> [Vec3; 3] {
        self.bvh.tris[self.bvh.slot_of[prim as usize] as usize].v
    }

    /// Closest hit along the ray (`0 < t < t_max`); ties at equal `t` go to the smallest
    /// `prim`. Rays with a non-finite origin or direction, a zero direction or `t_max ≤ 0`
    /// hit nothing.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        self.counters.add_closest(1);
        // A small mesh without the tree (`small_scene.rs`), else the widest kernel this CPU
        // runs (`traverse_wide.rs`), else SSE: same answers.
        #[cfg(target_arch = "x86_64")]
        if let Some(hit) = self.small.as_ref().and_then(|s| s.closest(ray)) {
            return hit;
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(hit) = traverse_wide::closest(&self.bvh, ray) {
            return hit;
        }
        traverse::closest(&self.bvh, ray)
    }

    /// Whether anything is hit along the ray segment (`0 < t < t_max`).
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.counters.add_occlusion(1);
        #[cfg(target_arch = "x86_64")]
        if let Some(hit) = self.small.as_ref().and_then(|s| s.occluded(ray)) {
            return hit;
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(hit) = traverse_wide::occluded(&self.bvh, ray) {
            return hit;
        }
        traverse::occluded(&self.bvh, ray)
    }

    /// Closest hits of a batch of rays: `out[i]` is `self.intersect(&rays[i])`, bit for bit.
    /// Several rays are traversed interleaved, so that the memory latency of one overlaps the
    /// work of the others: faster than one call per ray for incoherent rays.
    ///
    /// # Panics
    /// When `rays` and `out` differ in length.
    pub fn intersect_batch(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        self.counters.add_closest(rays.len() as u64);
        #[cfg(target_arch = "x86_64")]
        if traverse_wide::closest_batch(&self.bvh, rays, out) {
            return;
        }
        traverse::closest_batch(&self.bvh, rays, out);
    }

    /// Occlusion of a batch of rays: `out[i]` is `self.occluded(&rays[i])`, traversed
    /// interleaved like [`Accel::intersect_batch`].
    ///
    /// # Panics
    /// When `rays` and `out` differ in length.
    pub fn occluded_batch(&self, rays: &[Ray], out: &mut [bool]) {
        self.counters.add_occlusion(rays.len() as u64);
        #[cfg(target_arch = "x86_64")]
        if traverse_wide::occluded_batch(&self.bvh, rays, out) {
            return;
        }
        traverse::occluded_batch(&self.bvh, rays, out);
    }

    /// [`Accel::intersect`]'s hit together with what finding it cost the hierarchy (nodes and
    /// triangles tested, deepest level entered), for the BVH diagnostic view. A slower,
    /// instrumented walk of the same traversal; not counted in [`Accel::ray_counts`].
    pub fn intersect_with_cost(&self, ray: &Ray) -> (Option<Hit>, TraversalCost) {
        traversal_cost::closest_with_cost(&self.bvh, ray)
    }

    /// Surface point of a hit, computed from its barycentrics, with error bounds.
    pub fn surface_point(&self, hit: &Hit) -> SurfacePoint {
        spawn::surface_point(&self.triangle(hit.prim), hit.b1, hit.b2)
    }

    /// Rays traced through this accelerator so far, by kind, over every thread (see
    /// `counters.rs`): exact once the tracing threads have finished.
    pub fn ray_counts(&self) -> RayCounts {
        self.counters.totals()
    }

    /// Wall-clock seconds [`Accel::build`] took.
    pub fn build_seconds(&self) -> f64 {
        self.bvh.build_seconds
    }

    /// Size and build statistics.
    pub fn stats(&self) -> AccelStats {
        AccelStats {
            triangles: self.bvh.tris.len(),
            bvh_triangles: self.bvh.hierarchy_triangles,
            nodes: self.bvh.nodes.len(),
            depth: self.bvh.depth,
            build_seconds: self.bvh.build_seconds,
            build_phases: self.bvh.phases,
            sah_cost: self.bvh.sah_cost,
            bytes: std::mem::size_of_val(self.bvh.tris.as_slice())
                + std::mem::size_of_val(self.bvh.slot_of.as_slice())
                + std::mem::size_of_val(self.bvh.nodes.as_slice()),
        }
    }
}

#[cfg(test)]
pub(crate) mod test_random;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accel_is_send_sync() {
        fn check<T: Send + Sync>() {}
        check::<Accel>();
    }

    #[test]
    fn empty_accel_hits_nothing() {
        let a = Accel::build(Vec::new(), BvhQuality::Fast);
        let r = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::X,
            t_max: f32::INFINITY,
        };
        assert!(a.is_empty() && a.intersect(&r).is_none() && !a.occluded(&r));
    }

    /// Without a hierarchy the triangles come back in the caller's order and every query
    /// misses, single, batched or as a packet — even a ray straight through a triangle, which
    /// the built accelerator hits.
    #[test]
    fn triangles_without_a_hierarchy_are_read_but_never_hit() {
        let tris: Vec<[Vec3; 3]> = (0..40)
            .map(|i| {
                let z = i as f32;
                [
                    Vec3::new(-1.0, -1.0, z),
                    Vec3::new(1.0, -1.0, z),
                    Vec3::new(0.0, 1.0, z),
                ]
            })
            .collect();
        let ray = Ray {
            origin: Vec3::new(0.0, 0.0, -1.0),
            dir: Vec3::Z,
            t_max: f32::INFINITY,
        };
        let built = Accel::build(tris.clone(), BvhQuality::Medium);
        assert_eq!(built.intersect(&ray).map(|h| h.prim), Some(0));
        let bare = Accel::without_hierarchy(tris.clone());
        assert_eq!(bare.len(), 40);
        for (i, t) in tris.iter().enumerate() {
            assert_eq!(bare.triangle(i as u32), *t);
        }
        assert!(bare.intersect(&ray).is_none() && !bare.occluded(&ray));
        let rays = vec![ray; 9];
        let mut hits = vec![None; 9];
        bare.intersect_batch(&rays, &mut hits);
        let mut blocked = vec![true; 9];
        bare.occluded_batch(&rays, &mut blocked);
        assert!(hits.iter().all(Option::is_none) && blocked.iter().all(|b| !b));
    }

    /// One triangle copy: `triangle(prim)` gives back the caller's triangles, degenerate ones
    /// included, in the caller's order, and the byte count is that copy, two `u32` maps and
    /// the nodes.
    #[test]
    fn triangles_come_back_in_caller_order_from_one_copy() {
        let mut tris: Vec<[Vec3; 3]> = (0..300)
            .map(|i| {
                let c = Vec3::new(
                    (i as f32 * 0.7).sin(),
                    (i as f32 * 0.3).cos(),
                    i as f32 * 0.01,
                );
                [c, c + Vec3::X * 0.1, c + Vec3::Y * 0.1]
            })
            .collect();
        tris[0] = [Vec3::ZERO; 3];
        tris[150] = [Vec3::NAN, Vec3::X, Vec3::Y];
        tris[299] = [Vec3::ONE; 3];
        let a = Accel::build(tris.clone(), BvhQuality::Medium);
        assert_eq!(a.len(), tris.len());
        for (i, t) in tris.iter().enumerate() {
            assert_eq!(
                a.triangle(i as u32).map(|v| v.to_array().map(f32::to_bits)),
                t.map(|v| v.to_array().map(f32::to_bits)),
                "triangle {i}"
            );
        }
        let s = a.stats();
        assert_eq!((s.triangles, s.bvh_triangles), (300, 297));
        assert_eq!(s.bytes, 300 * (36 + 4 + 4) + s.nodes * 256);
        let degenerate_only = Accel::build(vec![[Vec3::ONE; 3]; 2], BvhQuality::Fast);
        assert_eq!(degenerate_only.triangle(1), [Vec3::ONE; 3]);
    }

    #[test]
    fn single_triangle_hit_and_surface_point() {
        let tri = [
            Vec3::new(-1.0, -1.0, 2.0),
            Vec3::new(1.0, -1.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0),
        ];
        let a = Accel::build(vec![tri], BvhQuality::Medium);
        let r = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::Z,
            t_max: f32::INFINITY,
        };
        let h = a.intersect(&r).unwrap();
        assert_eq!((h.prim, h.t), (0, 2.0));
        assert!(a.occluded(&r));
        let sp = a.surface_point(&h);
        assert!((sp.p - Vec3::new(0.0, 0.0, 2.0)).length() < 1e-6);
        assert_eq!(sp.ng, Vec3::Z);
        assert!(a
            .intersect(&spawn_ray(&sp, Vec3::new(0.3, 0.1, -1.0)))
            .is_none());
    }
}
