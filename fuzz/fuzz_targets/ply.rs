//! Fuzz target: arbitrary bytes as a PLY file. Parsing returns a checked mesh (indices in
//! range, finite positions, one normal and UV per vertex where present) or a located error,
//! never a panic, and allocates no more than the input could hold.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stagelight::scene::mesh_files::MeshFormat;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = stagelight::scene::parse_mesh_bytes(MeshFormat::Ply, data) {
        let n = mesh.positions.len();
        for t in &mesh.triangles {
            assert!(t.iter().all(|&i| (i as usize) < n));
        }
        assert!(mesh.positions.iter().all(|p| p.is_finite()));
        assert!(mesh.normals.as_ref().is_none_or(|v| v.len() == n));
        assert!(mesh.uvs.as_ref().is_none_or(|v| v.len() == n));
    }
});
