//! Queries by ray kind: surfaces that a kind of ray does not see (mental ray `visible`,
//! `shadow`, `trace` off; see [`crate::components::RayFlags`]) are passed through, and so
//! are the back faces of triangles marked [`FRONT_ONLY`] (`face: Cull`), for every kind.
//!
//! The masks are per triangle and optional: without them ([`Accel::set_ray_masks`] never
//! called, or every triangle seen by every kind from both sides) each query is the plain
//! one, bit for bit.
//! With them, a hit on a surface the kind does not see is stepped over: the ray is spawned
//! again from that hit ([`spawn_ray`], error-bounded) along the same direction and the search
//! goes on, at most [`MAX_PASSED`] times. The hit returned carries `t` along the caller's
//! ray, recomputed from the hit point.

use glam::Vec3;

use super::spawn::{geometric_normal, spawn_ray};
use super::{Accel, Hit, Ray, SurfacePoint};
use crate::components::{ALL_RAYS, CAMERA_RAYS, FRONT_ONLY, SECONDARY_RAYS, SHADOW_RAYS};

/// Fewest rays [`Accel::intersect_shared_origin_as`] traces as a packet. Coherent primary
/// rays of the 1 M-triangle anchor mesh, one thread, per CPU-second, packets of
/// consecutive rays against one query per ray: 4 rays 1.05×, 16 rays 1.57×, 64 rays 1.78×
/// (`docs/ray-layer.md`, session 30).
pub const PACKET_MIN_RAYS: usize = 8;

/// Most hidden surfaces one query steps over before it reports no hit (closest queries) or
/// no occluder (shadow queries).
pub const MAX_PASSED: u32 = 64;

/// What a ray is for, which decides the surfaces it sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RayKind {
    /// From the camera: sees surfaces that are `visible`.
    Camera,
    /// Toward a light: blocked by surfaces that cast shadows (`shadow`).
    Shadow,
    /// Reflection, refraction and gathering rays: see surfaces that are `trace`d.
    Secondary,
}

impl RayKind {
    /// The mask bit of this kind.
    pub fn bit(self) -> u8 {
        match self {
            Self::Camera => CAMERA_RAYS,
            Self::Shadow => SHADOW_RAYS,
            Self::Secondary => SECONDARY_RAYS,
        }
    }
}

impl Accel {
    /// Sets which ray kinds see each triangle (`masks[prim]`, bits of
    /// [`crate::components::RayFlags::mask`], and [`FRONT_ONLY`] where no ray sees its
    /// back face); when every triangle is seen by every kind from both sides the masks are
    /// dropped and queries stay the plain ones.
    ///
    /// # Panics
    /// When `masks` is not one entry per triangle.
    pub fn set_ray_masks(&mut self, masks: Vec<u8>) {
        assert_eq!(masks.len(), self.len(), "one ray mask per triangle");
        self.masks = masks.iter().any(|&m| m != ALL_RAYS).then_some(masks);
    }

    /// Whether some triangle is hidden from some kind of ray.
    pub fn has_ray_masks(&self) -> bool {
        self.masks.is_some()
    }

    /// Whether rays of `kind` see triangle `prim`.
    pub fn sees(&self, prim: u32, kind: RayKind) -> bool {
        self.masks
            .as_ref()
            .is_none_or(|m| m[prim as usize] & kind.bit() != 0)
    }

    /// Whether triangle `prim` is marked [`FRONT_ONLY`]: rays pass through its back face.
    #[inline]
    pub fn culls_back(&self, prim: u32) -> bool {
        self.masks
            .as_ref()
            .is_some_and(|m| m[prim as usize] & FRONT_ONLY != 0)
    }

    /// Whether a ray along `dir` meets triangle `prim` on its front face: the rule shading
    /// uses (`ng · −dir/|dir| > 0`, `ng` the unit [`geometric_normal`]).
    #[inline]
    pub fn meets_front(&self, prim: u32, dir: Vec3) -> bool {
        geometric_normal(&self.triangle(prim)).dot(-dir.normalize()) > 0.0
    }

    /// Whether rays of `kind` along `dir` see the hit on triangle `prim`: the kind's bit, and
    /// the front face where the triangle is [`FRONT_ONLY`].
    #[inline]
    fn sees_along(&self, masks: &[u8], prim: u32, dir: Vec3, kind: RayKind) -> bool {
        let m = masks[prim as usize];
        m & kind.bit() != 0 && (m & FRONT_ONLY == 0 || self.meets_front(prim, dir))
    }

    /// Closest hit that rays of `kind` see (see [`Accel::intersect`]).
    pub fn intersect_as(&self, ray: &Ray, kind: RayKind) -> Option<Hit> {
        let Some(masks) = &self.masks else {
            return self.intersect(ray);
        };
        let mut next = *ray;
        for _ in 0..=MAX_PASSED {
            let hit = self.intersect(&next)?;
            if self.sees_along(masks, hit.prim, ray.dir, kind) {
                if next == *ray {
                    return Some(hit);
                }
                let p = self.surface_point(&hit).p;
                let t = (p - ray.origin).dot(ray.dir) / ray.dir.length_squared();
                return Some(Hit { t, ..hit });
            }
            next = self.pass(ray, &hit)?;
        }
        None
    }

    /// Closest hits of rays of `kind` that share an origin (camera rays through one pixel):
    /// `out[i]` is `self.intersect_as(&rays[i], kind)` bit for bit. Traced as common-origin
    /// packets ([`Accel::intersect_packet`]) where those give the same answers and pay: no
    /// ray masks (a hidden surface is stepped over ray by ray), no small-scene path (it
    /// answers coplanar ties as brute force does, the tree may not), and at least
    /// [`PACKET_MIN_RAYS`] rays; otherwise one query per ray.
    ///
    /// # Panics
    /// When `rays` and `out` differ in length.
    pub fn intersect_shared_origin_as(&self, rays: &[Ray], kind: RayKind, out: &mut [Option<Hit>]) {
        assert_eq!(rays.len(), out.len(), "one result slot per ray");
        if self.packs_shared_origin(rays.len()) {
            self.intersect_packet(rays, out);
            return;
        }
        for (ray, hit) in rays.iter().zip(out) {
            *hit = self.intersect_as(ray, kind);
        }
    }

    /// Occlusion of rays of `kind` that share an origin (the shadow rays of one shading point
    /// toward an area light's samples): `out[i]` is `self.occluded_as(&rays[i], kind)` bit
    /// for bit, traced as common-origin packets ([`Accel::occluded_packet`]) where
    /// [`Accel::packs_shared_origin`] says so, else one query per ray.
    ///
    /// # Panics
    /// When `rays` and `out` differ in length.
    pub fn occluded_shared_origin_as(&self, rays: &[Ray], kind: RayKind, out: &mut [bool]) {
        assert_eq!(rays.len(), out.len(), "one result slot per ray");
        if self.packs_shared_origin(rays.len()) {
            self.occluded_packet(rays, out);
            return;
        }
        for (ray, hit) in rays.iter().zip(out) {
            *hit = self.occluded_as(ray, kind);
        }
    }

    /// Whether [`Accel::intersect_shared_origin_as`] and [`Accel::occluded_shared_origin_as`]
    /// trace `n` rays as packets (else one by one), so that a caller gathers its rays first
    /// only where that pays.
    pub fn packs_shared_origin(&self, n: usize) -> bool {
        self.masks.is_none() && self.small.is_none() && n >= PACKET_MIN_RAYS
    }

    /// Whether something that rays of `kind` see is on the segment (see
    /// [`Accel::occluded`]).
    pub fn occluded_as(&self, ray: &Ray, kind: RayKind) -> bool {
        if self.masks.is_none() {
            return self.occluded(ray);
        }
        // Any-hit first: a free segment needs no walk.
        self.occluded(ray) && self.intersect_as(ray, kind).is_some()
    }

    /// The rest of `ray` beyond `hit` (`None` when nothing of the segment is left).
    fn pass(&self, ray: &Ray, hit: &Hit) -> Option<Ray> {
        Self::beyond(ray, &self.surface_point(hit))
    }

    /// The rest of `ray` beyond the point `sp` it meets (`None` when nothing of the segment
    /// is left): spawned from `sp` (error-bounded) along the same direction, ending where
    /// `ray` ends.
    pub fn beyond(ray: &Ray, sp: &SurfacePoint) -> Option<Ray> {
        let mut next = spawn_ray(sp, ray.dir);
        if ray.t_max.is_finite() {
            let end: Vec3 = ray.origin + ray.dir * ray.t_max;
            next.t_max = (end - next.origin).dot(ray.dir) / ray.dir.length_squared();
            if next.t_max.is_nan() || next.t_max <= 0.0 {
                return None;
            }
        }
        Some(next)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::BvhQuality;

    fn wall(z: f32) -> [Vec3; 3] {
        [
            Vec3::new(-1.0, -1.0, z),
            Vec3::new(3.0, -1.0, z),
            Vec3::new(-1.0, 3.0, z),
        ]
    }

    #[test]
    fn front_only_triangles_are_passed_from_behind_by_every_kind() {
        let mut a = Accel::build(vec![wall(1.0), wall(2.0)], BvhQuality::Fast);
        // Both walls face +z: a ray along +z meets their backs.
        a.set_ray_masks(vec![ALL_RAYS | FRONT_ONLY, ALL_RAYS]);
        assert!(a.has_ray_masks());
        assert!(a.culls_back(0) && !a.culls_back(1));
        let up = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::Z,
            t_max: f32::INFINITY,
        };
        for kind in [RayKind::Camera, RayKind::Shadow, RayKind::Secondary] {
            let hit = a.intersect_as(&up, kind).unwrap();
            assert_eq!(hit.prim, 1, "{kind:?}");
            assert!((hit.t - 2.0).abs() < 1e-5);
            assert!(!a.occluded_as(&Ray { t_max: 1.5, ..up }, kind), "{kind:?}");
        }
        // From above, the front: seen.
        let down = Ray {
            origin: Vec3::new(0.0, 0.0, 1.5),
            dir: Vec3::NEG_Z,
            t_max: f32::INFINITY,
        };
        assert!(a.meets_front(0, down.dir) && !a.meets_front(0, up.dir));
        assert_eq!(a.intersect_as(&down, RayKind::Camera).unwrap().prim, 0);
        assert!(a.occluded_as(&down, RayKind::Shadow));
    }

    #[test]
    fn hidden_surfaces_are_passed_and_t_stays_on_the_callers_ray() {
        let mut a = Accel::build(vec![wall(1.0), wall(2.0)], BvhQuality::Fast);
        let ray = Ray {
            origin: Vec3::ZERO,
            dir: Vec3::Z,
            t_max: f32::INFINITY,
        };
        assert_eq!(a.intersect_as(&ray, RayKind::Camera).unwrap().prim, 0);
        a.set_ray_masks(vec![ALL_RAYS, ALL_RAYS]);
        assert!(!a.has_ray_masks());
        a.set_ray_masks(vec![SHADOW_RAYS, ALL_RAYS]);
        let hit = a.intersect_as(&ray, RayKind::Camera).unwrap();
        assert_eq!(hit.prim, 1);
        assert!((hit.t - 2.0).abs() < 1e-5);
        assert_eq!(a.intersect_as(&ray, RayKind::Shadow).unwrap().prim, 0);
        let short = Ray { t_max: 1.5, ..ray };
        assert!(a.occluded_as(&short, RayKind::Shadow));
        assert!(!a.occluded_as(&short, RayKind::Secondary));
        a.set_ray_masks(vec![CAMERA_RAYS, CAMERA_RAYS]);
        assert!(!a.occluded_as(&ray, RayKind::Shadow));
        assert!(a.intersect_as(&ray, RayKind::Secondary).is_none());
    }

    /// Shared-origin queries answer as `intersect_as` ray by ray, bit for bit, whichever way
    /// they are traced: packets over the tree (300 triangles; coplanar coincident copies for
    /// ties at equal `t`), one by one with ray masks, one by one on a small scene; 1 to 70
    /// rays (below and above the packet threshold, past one packet), a pixel's jittered
    /// camera rays from one origin with finite and infinite `t_max`.
    #[test]
    fn shared_origin_queries_answer_as_one_query_per_ray() {
        let mut rnd = crate::accel::test_random::signed_uniform(0x5a_4ed0_0000_0030u64);
        let mut tris: Vec<[Vec3; 3]> = (0..300)
            .map(|_| {
                let c = Vec3::new(rnd(), rnd(), rnd() + 3.0) * 2.0;
                let e = |r: &mut dyn FnMut() -> f32| Vec3::new(r(), r(), r()) * 0.8;
                [c, c + e(&mut rnd), c + e(&mut rnd)]
            })
            .collect();
        tris.extend([wall(4.0), wall(4.0), wall(5.0)]);
        let tree = Accel::build(tris.clone(), BvhQuality::Medium);
        assert!(tree.small.is_none() && !tree.has_ray_masks());
        let mut masked = Accel::build(tris.clone(), BvhQuality::Medium);
        masked.set_ray_masks(
            (0..tris.len())
                .map(|i| [ALL_RAYS, SHADOW_RAYS][i % 3 / 2])
                .collect(),
        );
        let small = Accel::build(tris[..20].to_vec(), BvhQuality::Medium);
        let bits =
            |h: Option<Hit>| h.map(|h| [h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()]);
        let origin = Vec3::new(0.1, -0.2, 0.0);
        let (mut hits, mut traced) = (0, 0);
        for n in 1..=70 {
            let rays: Vec<Ray> = (0..n)
                .map(|i| Ray {
                    origin,
                    dir: Vec3::new(0.3 + 0.05 * rnd(), 0.2 + 0.05 * rnd(), 1.0),
                    t_max: [f32::INFINITY, 7.0][i % 2],
                })
                .collect();
            for accel in [&tree, &masked, &small] {
                let mut out = vec![None; n];
                accel.intersect_shared_origin_as(&rays, RayKind::Camera, &mut out);
                for (ray, got) in rays.iter().zip(&out) {
                    let want = accel.intersect_as(ray, RayKind::Camera);
                    assert_eq!(bits(*got), bits(want), "{n} rays: {ray:?}");
                    hits += usize::from(want.is_some());
                    traced += 1;
                }
            }
        }
        // Not vacuous: most rays hit something.
        assert!(2 * hits > traced, "{hits} of {traced}");
    }
}
