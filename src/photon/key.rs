//! The content hash of a photon pass: everything the stored photons depend on, so that a
//! photon map file ([`super::file`]) is reused exactly when tracing again would store the
//! same photons.
//!
//! **In the hash:** the stagelight version and file format; the geometry after tessellation
//! (every instance's triangles, normals and UVs, transform, material slot and bump), the
//! materials (their shaders, textures, emission and light lists), the lights with their photon
//! controls, each instance's caster/receiver roles, the seed, the trace depths and photon trace depth, face
//! visibility, BVH quality, and per map whether it is built, its photon count, aiming and
//! progressive passes. **Not in it:** what only reads the maps — gather count, radius,
//! filter, final-gather rays, progressive `alpha` —
//! and everything else of the render (camera, samples, pixel filter, outputs), so tuning
//! those reuses the file, as mental ray's `photonmap file` intends.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::components::LightPhotons;
use crate::geometry::SceneGeometry;
use crate::hash::Fnv64;
use crate::settings::{PhotonMapSettings, RenderSettings};
use crate::shading::LightSet;

use super::roles::PhotonRoles;

/// The hash of one photon pass's inputs (see the module documentation).
pub fn photon_key(
    geometry: &SceneGeometry,
    lights: &LightSet,
    controls: &[LightPhotons],
    roles: &PhotonRoles,
    settings: &RenderSettings,
) -> u64 {
    let mut h = Fnv64::default();
    let _ = writeln!(
        h,
        "stagelight {} photon map {}",
        env!("CARGO_PKG_VERSION"),
        super::file::VERSION
    );
    let mut meshes: HashMap<*const crate::components::TriMesh, usize> = HashMap::new();
    for (slot, inst) in geometry.instances.iter().enumerate() {
        let ptr = std::sync::Arc::as_ptr(&inst.mesh);
        let next = meshes.len();
        let id = *meshes.entry(ptr).or_insert(next);
        let _ = writeln!(
            h,
            "instance {slot} mesh {id} material {} first {} transform {:?} bump {:?}",
            inst.material, inst.first_triangle, inst.world_from_object, inst.bump
        );
        if inst.mirrored {
            // Its world triangles keep the object-space front (written since that rule).
            let _ = writeln!(h, "mirrored, front kept");
        }
        if inst.reversed {
            // Its front is the object-space back (its world triangles are swapped once more).
            let _ = writeln!(h, "orientation reversed");
        }
        if let Some(faces) = &inst.face_materials {
            let _ = writeln!(h, "faces {faces:?}");
        }
        if id == next {
            let mesh = &inst.mesh;
            for p in &mesh.positions {
                h.bytes(vec3_bytes(p.to_array()).as_slice());
            }
            if let Some(normals) = &mesh.normals {
                h.bytes(b"normals");
                for n in normals {
                    h.bytes(vec3_bytes(n.to_array()).as_slice());
                }
            }
            if let Some(uvs) = &mesh.uvs {
                h.bytes(b"uvs");
                for uv in uvs {
                    h.bytes(&uv.x.to_le_bytes()).bytes(&uv.y.to_le_bytes());
                }
            }
            for t in &mesh.triangles {
                for i in t {
                    h.bytes(&i.to_le_bytes());
                }
            }
        }
    }
    let _ = writeln!(
        h,
        "origin {:?}\nmaterials {:?}\nlights {:?}\ncontrols {:?}\nroles {:?}",
        geometry.origin, geometry.materials, lights, controls, roles
    );
    let map = |m: Option<PhotonMapSettings>| {
        m.map(|m| (m.photons, m.aim, m.progressive.map(|p| p.passes)))
    };
    let _ = writeln!(
        h,
        "seed {} depth {} {} {} face {:?} bvh {:?} caustics {:?} global {:?}",
        settings.seed,
        settings.max_depth,
        settings.reflection_depth,
        settings.refraction_depth,
        settings.face,
        settings.bvh_quality,
        map(settings.photons.caustics),
        map(settings.photons.global_illumination),
    );
    // Written only when set, so files traced before the limit existed keep their hash.
    if settings.photons.depth != crate::settings::PhotonDepth::UNLIMITED {
        let _ = writeln!(h, "photon depth {:?}", settings.photons.depth);
    }
    h.finish()
}

fn vec3_bytes(v: [f32; 3]) -> [u8; 12] {
    let mut out = [0u8; 12];
    for (k, x) in v.iter().enumerate() {
        out[4 * k..4 * k + 4].copy_from_slice(&x.to_le_bytes());
    }
    out
}
