//! Tiny hand-built scenes for the unit tests of the integrators and the photon pass: world
//! triangles with one material each, flattened the way `build_accel` flattens instances
//! (one instance per object, identity transform).

use std::sync::Arc;

use glam::{Affine3A, Mat3A, Vec3};

use crate::accel::{Accel, Hit, Ray};
use crate::components::{
    Displacement, DisplacementMode, Material, ScalarNode, Shader, TriMesh, UvAxis,
};
use crate::geometry::{InstanceGeometry, SceneGeometry};
use crate::settings::BvhQuality;

/// One object: world-space triangles and their material.
pub struct Object {
    /// Triangles, counter-clockwise seen from the front.
    pub triangles: Vec<[Vec3; 3]>,
    /// Its material.
    pub material: Material,
}

/// A closed cube of half-size 1 (grey Lambert, seen from inside), a glass floor patch of
/// absorption colour `glass` across it at z = −0.3, and two wall panels at y = 0.99 with the
/// materials `panels` (instances 0 to 3 in that order).
pub fn room_with_panels(glass: Vec3, panels: [Material; 2]) -> SceneGeometry {
    let panel = |x: f32| {
        quad(
            Vec3::new(x, 0.99, -0.7),
            Vec3::new(0.6, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.4),
        )
    };
    let [left, right] = panels;
    geometry(vec![
        Object {
            triangles: inward_cube(1.0),
            material: lambert(0.7),
        },
        Object {
            triangles: floor(0.8, -0.3),
            material: material(Shader::Dielectric {
                ior: 1.5,
                ior_out: 1.0,
                col: glass,
            }),
        },
        Object {
            triangles: panel(-0.6),
            material: left,
        },
        Object {
            triangles: panel(0.2),
            material: right,
        },
    ])
}

/// A bump displacement (a sine along u) for an instance: points whose shading normal a
/// texture changes.
pub fn sine_bump() -> Arc<Displacement> {
    Arc::new(Displacement {
        shader: ScalarNode::Sine {
            amplitude: 0.05,
            factor: 7.0,
            axis: UvAxis::U,
        },
        bound: None,
        mode: DisplacementMode::Bump,
    })
}

/// A one-sided, non-emitting material with `shader`.
pub fn material(shader: Shader) -> Material {
    Material {
        shader,
        two_sided: false,
        emission: Vec3::ZERO,
        graph: None,
        ..Default::default()
    }
}

/// A grey Lambert material of albedo `rho`.
pub fn lambert(rho: f32) -> Material {
    material(Shader::Lambert {
        albedo: Vec3::splat(rho),
    })
}

/// The parallelogram `corner + s·u + t·v`, `s, t ∈ [0, 1]`, as two triangles whose front
/// faces along `u × v`.
pub fn quad(corner: Vec3, u: Vec3, v: Vec3) -> Vec<[Vec3; 3]> {
    vec![
        [corner, corner + u, corner + u + v],
        [corner, corner + u + v, corner + v],
    ]
}

/// The square `[−h, h]²` in the plane `z = z`, facing `+z`.
pub fn floor(h: f32, z: f32) -> Vec<[Vec3; 3]> {
    quad(
        Vec3::new(-h, -h, z),
        Vec3::new(2.0 * h, 0.0, 0.0),
        Vec3::new(0.0, 2.0 * h, 0.0),
    )
}

/// A grey floor (albedo 0.8, `[−10, 10]²` at `z = 0`, facing up) under a mirror ceiling
/// (the same square at `z = 1`, facing down): a photon reflected by the ceiling is a caustic.
pub fn mirror_over_floor() -> SceneGeometry {
    geometry(vec![
        Object {
            triangles: floor(10.0, 0.0),
            material: lambert(0.8),
        },
        Object {
            triangles: quad(
                Vec3::new(-10.0, -10.0, 1.0),
                Vec3::new(0.0, 20.0, 0.0),
                Vec3::new(20.0, 0.0, 0.0),
            ),
            material: material(Shader::Mirror { color: Vec3::ONE }),
        },
    ])
}

/// The six faces of the cube `[−h, h]³`, each facing inward.
pub fn inward_cube(h: f32) -> Vec<[Vec3; 3]> {
    let c = Vec3::splat(-h);
    let (x, y, z) = (
        Vec3::new(2.0 * h, 0.0, 0.0),
        Vec3::new(0.0, 2.0 * h, 0.0),
        Vec3::new(0.0, 0.0, 2.0 * h),
    );
    let far = Vec3::splat(h);
    [
        quad(c, x, y),
        quad(c, z, x),
        quad(c, y, z),
        quad(far, -y, -x),
        quad(far, -x, -z),
        quad(far, -z, -y),
    ]
    .concat()
}

/// The flattened scene of `objects`.
pub fn geometry(objects: Vec<Object>) -> SceneGeometry {
    let mut world = hecs::World::new();
    let mut triangles = Vec::new();
    let mut triangle_instance = Vec::new();
    let mut instances = Vec::new();
    let mut materials = Vec::new();
    let mut material_entities = Vec::new();
    for (slot, object) in objects.into_iter().enumerate() {
        let positions: Vec<Vec3> = object.triangles.iter().flatten().copied().collect();
        let mesh = TriMesh {
            triangles: (0..object.triangles.len() as u32)
                .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
                .collect(),
            positions,
            normals: None,
            uvs: None,
        };
        instances.push(InstanceGeometry {
            entity: world.spawn(()),
            mesh: Arc::new(mesh),
            world_from_object: Affine3A::IDENTITY,
            normal_from_object: Mat3A::IDENTITY,
            material: slot as u32,
            face_materials: None,
            first_triangle: triangles.len() as u32,
            bump: None,
            colours: None,
            tangents: None,
            mirrored: false,
            reversed: false,
            label: None,
        });
        triangle_instance.extend(std::iter::repeat_n(slot as u32, object.triangles.len()));
        triangles.extend(object.triangles);
        materials.push(object.material);
        material_entities.push(world.spawn(()));
    }
    SceneGeometry {
        accel: Accel::build(triangles, BvhQuality::Medium),
        triangle_instance,
        instances,
        materials,
        material_entities,
        origin: glam::DVec3::ZERO,
    }
}

/// The ray from `origin` along `dir` and its first hit (panics when it misses).
pub fn hit(geometry: &SceneGeometry, origin: Vec3, dir: Vec3) -> (Ray, Hit) {
    let ray = Ray {
        origin,
        dir,
        t_max: f32::INFINITY,
    };
    let hit = geometry.accel.intersect(&ray).expect("the test ray hits");
    (ray, hit)
}
