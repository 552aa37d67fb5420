//! Fuzz target: arbitrary bytes as a photon map file (`photon_map` / `--photon-cache`): a
//! decoded file holds only finite photons and valid split axes and encodes back to the same
//! bytes; anything else is an error, never a panic or a huge allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stagelight::photon::file::{decode, encode};

fuzz_target!(|data: &[u8]| {
    if let Ok(maps) = decode(data) {
        for stored in [&maps.caustics, &maps.global].into_iter().flatten() {
            for map in std::iter::once(&stored.map).chain(&stored.later) {
                assert!(map.axes().iter().all(|&a| a < 3));
                assert!(map
                    .photons()
                    .iter()
                    .all(|p| p.position.is_finite() && p.power.is_finite()));
            }
        }
        assert_eq!(encode(&maps), data);
    }
});
