//! Shared helpers for integration tests: small worlds built directly from components (no
//! scene file), and running the stage table on them.

pub mod cli;
mod meshes;
mod mi_text;
mod photon_pass;
pub mod png;
mod rays;
mod rib_text;
mod scene_text;
mod scratch;
mod stats_json;
pub use cli::*;
pub use meshes::*;
pub use mi_text::*;
pub use photon_pass::*;
pub use rays::*;
pub use rib_text::*;
pub use scene_text::*;
pub use scratch::scratch_root;
pub use stats_json::*;

use std::sync::Arc;

use glam::{Affine3A, Vec3};
use hecs::{Entity, World};
use stagelight::components::{
    Camera, Emitter, ImageFormat, Instance, LightShape, Material, MaterialRef, Name, OutputSpec,
    Pass, RenderCamera, Shader, TriMesh, WorldFromObject,
};
use stagelight::frame::Frame;
use stagelight::settings::RenderSettings;

/// Every RON scene in `assets/scenes/`, sorted by path.
pub fn example_scenes() -> Vec<std::path::PathBuf> {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut scenes: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    scenes.sort();
    assert!(
        scenes.len() >= 3,
        "expected the example scenes in {}",
        dir.display()
    );
    scenes
}

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
            graph: None,
            ..Default::default()
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
                beauty_alpha: true,
            }],
            space_scale: 1.0,
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
            shadow_factor: 0.0,
            samples,
            visible: false,
            attenuation: None,
            inverse_square: true,
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

/// An axis-aligned box from `a` to `b` with outward-facing, counter-clockwise faces.
pub fn box_mesh(a: Vec3, b: Vec3) -> TriMesh {
    let faces: [[Vec3; 4]; 6] = [
        [
            Vec3::new(a.x, a.y, b.z),
            Vec3::new(b.x, a.y, b.z),
            Vec3::new(b.x, b.y, b.z),
            Vec3::new(a.x, b.y, b.z),
        ],
        [
            Vec3::new(a.x, a.y, a.z),
            Vec3::new(a.x, b.y, a.z),
            Vec3::new(b.x, b.y, a.z),
            Vec3::new(b.x, a.y, a.z),
        ],
        [
            Vec3::new(b.x, a.y, a.z),
            Vec3::new(b.x, b.y, a.z),
            Vec3::new(b.x, b.y, b.z),
            Vec3::new(b.x, a.y, b.z),
        ],
        [
            Vec3::new(a.x, a.y, a.z),
            Vec3::new(a.x, a.y, b.z),
            Vec3::new(a.x, b.y, b.z),
            Vec3::new(a.x, b.y, a.z),
        ],
        [
            Vec3::new(a.x, b.y, a.z),
            Vec3::new(a.x, b.y, b.z),
            Vec3::new(b.x, b.y, b.z),
            Vec3::new(b.x, b.y, a.z),
        ],
        [
            Vec3::new(a.x, a.y, a.z),
            Vec3::new(b.x, a.y, a.z),
            Vec3::new(b.x, a.y, b.z),
            Vec3::new(a.x, a.y, b.z),
        ],
    ];
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for f in faces {
        let base = positions.len() as u32;
        positions.extend_from_slice(&f);
        triangles.push([base, base + 1, base + 2]);
        triangles.push([base, base + 2, base + 3]);
    }
    TriMesh {
        positions,
        normals: None,
        uvs: None,
        triangles,
    }
}

/// A UV sphere of radius `r` at `centre` with outward normals and smooth vertex normals.
pub fn sphere_mesh(centre: Vec3, r: f32, rings: u32, segments: u32) -> TriMesh {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..=segments {
            let phi = 2.0 * std::f32::consts::PI * j as f32 / segments as f32;
            let n = Vec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            positions.push(centre + n * r);
            normals.push(n);
        }
    }
    let mut triangles = Vec::new();
    let w = segments + 1;
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (
                i * w + j,
                i * w + j + 1,
                (i + 1) * w + j + 1,
                (i + 1) * w + j,
            );
            if i != 0 {
                triangles.push([a, d, b]);
            }
            if i != rings - 1 {
                triangles.push([b, d, c]);
            }
        }
    }
    TriMesh {
        positions,
        normals: Some(normals),
        uvs: None,
        triangles,
    }
}

/// Spawns a material entity with every field given.
pub fn material_full(world: &mut World, shader: Shader, two_sided: bool, emission: Vec3) -> Entity {
    world.spawn((
        Name("m".into()),
        Material {
            shader,
            two_sided,
            emission,
            graph: None,
            ..Default::default()
        },
    ))
}
