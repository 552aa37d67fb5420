//! Fuzz target: arbitrary bytes as an OBJ file. Parsing returns a checked mesh (indices in
//! range, finite positions) or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = stagelight::scene::parse_obj_bytes(data) {
        let n = mesh.positions.len() as u32;
        for t in &mesh.triangles {
            assert!(t.iter().all(|&i| i < n));
        }
        assert!(mesh.positions.iter().all(|p| p.is_finite()));
    }
});
