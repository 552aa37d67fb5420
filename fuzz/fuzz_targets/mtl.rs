//! Fuzz target: arbitrary bytes as an MTL material library. Parsing returns materials whose
//! values are in range (opacity in [0, 1], index of refraction > 0, colours finite and
//! ≥ 0) or an error at a line and column, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stagelight::scene::mesh_files::{mtl, Location, MeshFileError};

fuzz_target!(|data: &[u8]| {
    match mtl::parse(data) {
        Ok(materials) => {
            for m in &materials {
                assert!(m.opacity.is_none_or(|d| (0.0..=1.0).contains(&d)));
                assert!(m.ior.is_none_or(|n| n > 0.0));
                for c in [m.diffuse, m.specular, m.emission].into_iter().flatten() {
                    assert!(c.iter().all(|x| x.is_finite() && *x >= 0.0));
                }
            }
        }
        Err(e) => assert!(matches!(
            e,
            MeshFileError::Parse {
                at: Location::Text { line, column },
                ..
            } if line >= 1 && column >= 1
        )),
    }
});
