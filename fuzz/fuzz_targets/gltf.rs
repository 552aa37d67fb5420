//! Fuzz target: arbitrary bytes as a glTF or GLB file, read as a mesh (a checked mesh —
//! indices in range, finite positions, one normal and UV per vertex where present — or an
//! error with the element or byte offset) and as a whole scene (a description or located
//! errors), never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stagelight::scene::mesh_files::MeshFormat;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = stagelight::scene::parse_mesh_bytes(MeshFormat::Gltf, data) {
        let n = mesh.positions.len();
        for t in &mesh.triangles {
            assert!(t.iter().all(|&i| (i as usize) < n));
        }
        assert!(mesh.positions.iter().all(|p| p.is_finite()));
        assert!(mesh.normals.as_ref().is_none_or(|v| v.len() == n));
        assert!(mesh.uvs.as_ref().is_none_or(|v| v.len() == n));
    }
    let path = std::path::Path::new("fuzz.glb");
    if let Err(failure) = stagelight::scene::import::gltf_scene::read(path, data) {
        assert!(!failure.errors.is_empty());
    }
});
