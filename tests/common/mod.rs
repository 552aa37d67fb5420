//! Shared helpers for integration tests: small worlds built directly from components (no
//! scene file), and running the stage table on them.

#![allow(dead_code)] // each test binary uses a different subset

use std::sync::Arc;

use glam::{Affine3A, Vec3};
use hecs::{Entity, World};
use stagelight::components::{
    Camera, Emitter, ImageFormat, Instance, LightShape, Material, MaterialRef, Name, OutputSpec,
    Pass, RenderCamera, Shader, TriMesh, WorldFromObject,
};
use stagelight::frame::Frame;
use stagelight::settings::RenderSettings;

/// A unit square in the z = 0 plane, `[-h, h]²`, facing +Z.
pub fn square(h: f32) -> TriMesh {
    TriMesh {
        positions: vec![
            Vec3::new(-h, -h, 0.0),
            Vec3::new(h, -h, 0.0),
            Vec3::new(h, h, 0.0),
            Vec3::new(-h, h, 0.0),
        ],
        normals: None,
        uvs: None,
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// Spawns a material entity.
pub fn material(world: &mut World, shader: Shader) -> Entity {
    world.spawn((
        Name("m".into()),
        Material {
            shader,
            two_sided: false,
            emission: Vec3::ZERO,
        },
    ))
}

/// Spawns an object and one instance of it.
pub fn instance(world: &mut World, mesh: TriMesh, xf: Affine3A, material: Entity) -> Entity {
    let mesh = Arc::new(mesh);
    let object = world.spawn((Name("obj".into()), mesh.clone()));
    world.spawn((
        Name("inst".into()),
        Instance { object, mesh },
        WorldFromObject(xf),
        MaterialRef(material),
    ))
}

/// Spawns the render camera at `eye` looking at `target` (+Y up, unless looking along Y).
pub fn camera(world: &mut World, eye: Vec3, target: Vec3, fov_deg: f32, w: u32, h: u32) -> Entity {
    let forward = (target - eye).normalize();
    let up = if forward.cross(Vec3::Y).length() < 1e-3 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    world.spawn((
        Name("cam".into()),
        Camera {
            world_from_camera: stagelight::components::world_from_look_at(eye, target, up).unwrap(),
            fov_y: fov_deg.to_radians(),
            width: w,
            height: h,
            aspect: w as f32 / h as f32,
            outputs: vec![OutputSpec {
                path: "unused.exr".into(),
                format: ImageFormat::Exr,
                passes: vec![Pass::Beauty, Pass::Depth, Pass::Normal],
            }],
        },
        RenderCamera,
    ))
}

/// Spawns a light.
pub fn light(world: &mut World, shape: LightShape, radiant: Vec3, samples: u32) -> Entity {
    world.spawn((
        Name("light".into()),
        Emitter {
            shape,
            radiant,
            shadows: true,
            samples,
        },
    ))
}

/// Runs every stage except `write_output`, returning the frame.
pub fn render(world: &mut World, settings: RenderSettings) -> Frame {
    let mut frame = Frame::new(settings);
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, world, &mut frame).expect("render");
    frame
}
pub mod chi2;
