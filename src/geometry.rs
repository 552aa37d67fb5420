//! World-space scene geometry, the output of the `build_accel` stage: every instance's
//! triangles flattened into world space, the BVH over them, and what shading needs to turn a
//! hit into a shading point (instance, material, interpolated normal and uv).
//!
//! Instancing is resolved by flattening: each leaf of the instance DAG contributes its
//! triangles transformed into world space. Traversal stays one-level (no ray transforms, no
//! nested stacks) and error bounds are computed on the world-space vertices the ray actually
//! meets.
//!
//! **Mirrored instances.** A transform with a negative determinant reverses a triangle's
//! winding, so the world triangle of a *mirrored* instance is stored with its last two
//! corners swapped ([`InstanceGeometry::world_order`]): every geometric normal computed from
//! world vertices (`SurfacePoint::ng`, and with it one-sided shading, emission, interiors,
//! photons and bakes) then points to the side its object-space winding calls the front, as
//! glTF and pbrt define it. A hit's barycentrics weigh the world triangle's corners, so mesh
//! attributes are read through [`InstanceGeometry::corners`]; unmirrored instances keep the
//! mesh's order, bit for bit.
//!
//! **Reversed orientation.** An object marked [`crate::components::ReverseOrientation`]
//! (RenderMan's `ReverseOrientation`, `Orientation "inside"`) has its front on the
//! object-space back: the same swap, so its instances' world triangles are stored swapped
//! unless they also mirror (the two cancel). Everything above then follows the reversed
//! front through the same rule.

use std::sync::Arc;

use glam::{Affine3A, Mat3A, Vec2, Vec3, Vec3A};
use hecs::Entity;

use crate::accel::{Accel, Hit, SurfacePoint};
use crate::components::{Displacement, Material, TriMesh};

/// One placed instance in the flattened scene.
#[derive(Debug, Clone)]
pub struct InstanceGeometry {
    /// The instance entity.
    pub entity: Entity,
    /// The object's mesh (object space).
    pub mesh: Arc<TriMesh>,
    /// Object-to-world transform.
    pub world_from_object: Affine3A,
    /// Transform for normals: inverse transpose of the linear part (in SIMD columns: a hit
    /// point's normal is transformed with three products and two sums, the scalar ones'
    /// operations in the same order).
    pub normal_from_object: Mat3A,
    /// Index into [`SceneGeometry::materials`] (of every triangle without one of its own).
    pub material: u32,
    /// Per local triangle, its material slot when the object's polygons name their own
    /// materials ([`crate::components::FaceMaterials`]); `None`: every triangle has `material`.
    pub face_materials: Option<Arc<Vec<u32>>>,
    /// First world triangle of this instance; its triangles are contiguous.
    pub first_triangle: u32,
    /// The object's displacement when it is in `Bump` mode (shading normals only).
    pub bump: Option<Arc<Displacement>>,
    /// The object's vertex colours (linear RGB, one per vertex of `mesh`), if it has them.
    pub colours: Option<Arc<Vec<Vec3>>>,
    /// The object's tangents (object space, `w` the handedness, one per vertex of `mesh`),
    /// if it has them ([`crate::components::VertexTangents`]).
    pub tangents: Option<Arc<Vec<glam::Vec4>>>,
    /// Whether `world_from_object` mirrors (negative determinant).
    pub mirrored: bool,
    /// Whether the object's orientation is reversed (its front is the object-space back).
    pub reversed: bool,
    /// The object's label ([`crate::components::ObjectLabel`]), if it has one.
    pub label: Option<u32>,
}

impl InstanceGeometry {
    /// What the `ObjectId` pass writes where instance `index` (this one) is seen: its
    /// object's label, else 1 + `index` (0 is the background's).
    pub fn object_id(&self, index: u32) -> u32 {
        self.label.unwrap_or(index + 1)
    }

    /// Whether `world_from_object` mirrors space (negative determinant), which makes
    /// [`Self::world_order`] swap a triangle's last two corners (unless the object's
    /// orientation is reversed).
    pub fn mirrors(world_from_object: &Affine3A) -> bool {
        world_from_object.matrix3.determinant() < 0.0
    }

    /// Whether the world triangles have their last two corners swapped: a mirrored instance
    /// of an object with its orientation as modelled, or an unmirrored one of an object with
    /// its orientation reversed.
    #[inline(always)]
    pub fn swapped(&self) -> bool {
        self.mirrored != self.reversed
    }

    /// A triangle's three per-corner values in the mesh's order, put in the order of its
    /// world triangle (the order a [`Hit`]'s barycentrics weigh): the last two swapped when
    /// [`Self::swapped`], so the world winding's front is the object's front.
    #[inline(always)]
    pub fn world_order<T>(&self, corners: [T; 3]) -> [T; 3] {
        Self::in_world_order(self.swapped(), corners)
    }

    /// [`Self::world_order`] for an instance whose triangles `swapped` says are swapped: the
    /// one rule the flattening (`build_accel`) and every attribute lookup share.
    #[inline(always)]
    pub fn in_world_order<T>(swapped: bool, [a, b, c]: [T; 3]) -> [T; 3] {
        if swapped {
            [a, c, b]
        } else {
            [a, b, c]
        }
    }

    /// Mesh vertex indices of local triangle `local`, in the order of its world triangle.
    #[inline(always)]
    pub fn corners(&self, local: usize) -> [usize; 3] {
        self.world_order(self.mesh.triangles[local])
            .map(|i| i as usize)
    }

    /// The hit on local triangle `local` at the barycentrics `(b1, b2)` of the mesh's
    /// corners 1 and 2 (a bake's texel sample), at `t = 0`.
    pub fn hit_at(&self, local: u32, b1: f32, b2: f32) -> Hit {
        let (b1, b2) = if self.swapped() { (b2, b1) } else { (b1, b2) };
        Hit {
            t: 0.0,
            prim: self.first_triangle + local,
            b1,
            b2,
        }
    }

    /// Material slot of the instance's local triangle `local`.
    pub fn material_of_local(&self, local: usize) -> u32 {
        self.face_materials
            .as_ref()
            .and_then(|f| f.get(local).copied())
            .unwrap_or(self.material)
    }

    /// Every material slot the instance's triangles use (its own first), without repeats.
    pub fn material_slots(&self) -> Vec<u32> {
        let mut slots = vec![self.material];
        for &s in self.face_materials.iter().flat_map(|f| f.iter()) {
            if !slots.contains(&s) {
                slots.push(s);
            }
        }
        slots
    }
}

/// Everything about a hit that shading needs.
#[derive(Debug, Clone, Copy)]
pub struct ShadingPoint {
    /// Hit position with error bounds and unit geometric normal (world space).
    pub surface: SurfacePoint,
    /// Unit shading normal (interpolated vertex normals when the mesh has them), on the
    /// same side as `surface.ng`.
    pub normal: Vec3,
    /// Texture coordinates (zero when the mesh has none).
    pub uv: Vec2,
    /// Index into [`SceneGeometry::materials`].
    pub material: u32,
    /// Index into [`SceneGeometry::instances`].
    pub instance: u32,
    /// World triangle index.
    pub prim: u32,
}

/// World-space triangles, their BVH and shading attributes.
pub struct SceneGeometry {
    /// BVH over every world triangle.
    pub accel: Accel,
    /// Instance slot of each world triangle.
    pub triangle_instance: Vec<u32>,
    /// Placed instances, in entity order.
    pub instances: Vec<InstanceGeometry>,
    /// Materials referenced by instances.
    pub materials: Vec<Material>,
    /// Material entity of each entry of `materials`.
    pub material_entities: Vec<Entity>,
    /// World-space position of render space's zero (see
    /// [`crate::components::SceneOrigin`]): every position here is relative to it.
    pub origin: glam::DVec3,
}

impl SceneGeometry {
    /// The geometry of a scene without triangles (`build_accel` skipped): no instance, no
    /// material, no hierarchy; every ray misses. `shade` shades with it so that camera rays
    /// still meet the visible lights and the environment.
    pub fn empty(origin: glam::DVec3) -> Self {
        Self {
            accel: Accel::without_hierarchy(Vec::new()),
            triangle_instance: Vec::new(),
            instances: Vec::new(),
            materials: Vec::new(),
            material_entities: Vec::new(),
            origin,
        }
    }

    /// Number of world triangles.
    pub fn triangle_count(&self) -> usize {
        self.accel.len()
    }

    /// The accelerator's shortcuts past convex instances ([`crate::accel::Shortcuts`]),
    /// each instance's triangles a part.
    pub fn shortcuts(&self) -> &crate::accel::Shortcuts {
        self.accel.shortcuts(|| {
            let mut parts: Vec<std::ops::Range<u32>> = Vec::new();
            for (prim, &slot) in self.triangle_instance.iter().enumerate() {
                let prim = prim as u32;
                match parts.last_mut() {
                    Some(r) if self.triangle_instance[r.start as usize] == slot => r.end = prim + 1,
                    _ => parts.push(prim..prim + 1),
                }
            }
            parts
        })
    }

    /// Instance and mesh-local triangle index of world triangle `prim`.
    pub fn locate(&self, prim: u32) -> (&InstanceGeometry, usize) {
        let inst = &self.instances[self.triangle_instance[prim as usize] as usize];
        (inst, (prim - inst.first_triangle) as usize)
    }

    /// Material slot (index into [`Self::materials`]) of world triangle `prim`.
    pub fn material_slot(&self, prim: u32) -> u32 {
        let (inst, local) = self.locate(prim);
        inst.material_of_local(local)
    }

    /// Material of world triangle `prim`.
    pub fn material_of(&self, prim: u32) -> &Material {
        &self.materials[self.material_slot(prim) as usize]
    }

    /// Turns a hit into a shading point.
    pub fn shading_point(&self, hit: &Hit) -> ShadingPoint {
        self.shading_point_on(hit, self.accel.surface_point(hit))
    }

    /// [`Self::shading_point`] of `hit` whose surface point (`accel.surface_point(hit)`)
    /// the caller already has.
    #[inline]
    pub fn shading_point_on(&self, hit: &Hit, surface: SurfacePoint) -> ShadingPoint {
        let slot = self.triangle_instance[hit.prim as usize];
        let inst = &self.instances[slot as usize];
        let local = (hit.prim - inst.first_triangle) as usize;
        let [i0, i1, i2] = inst.corners(local);
        let b0 = 1.0 - hit.b1 - hit.b2;
        let mut normal = surface.ng;
        if let Some(ns) = &inst.mesh.normals {
            // In `Vec3A` lanes, with the scalar operations' order: the same bits.
            let [n0, n1, n2] = [ns[i0], ns[i1], ns[i2]].map(Vec3A::from);
            let n = inst.normal_from_object * (n0 * b0 + n1 * hit.b1 + n2 * hit.b2);
            let n = Vec3::from(n.normalize_or_zero());
            if n != Vec3::ZERO && n.is_finite() {
                normal = if n.dot(surface.ng) < 0.0 { -n } else { n };
            }
        }
        let uv = match &inst.mesh.uvs {
            Some(uv) => uv[i0] * b0 + uv[i1] * hit.b1 + uv[i2] * hit.b2,
            None => Vec2::ZERO,
        };
        ShadingPoint {
            surface,
            normal,
            uv,
            material: inst.material_of_local(local),
            instance: slot,
            prim: hit.prim,
        }
    }
}
