//! Photon-pass throughput for `stagelight bench`: photons emitted and stored by the maps of a
//! run, and emitted photons per second per thread of the `trace_photons` stage.

use serde::Serialize;

use super::PhotonMaps;

/// Photons a run emitted and stored, and how fast.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhotonThroughput {
    /// Photons emitted over every map and pass (a map's `emitted` counts all its passes).
    pub emitted: u64,
    /// Photons stored over every map and pass.
    pub stored: u64,
    /// Wall-clock seconds of the photon pass.
    pub seconds: f64,
    /// Worker threads.
    pub threads: usize,
    /// Emitted photons per second per thread.
    pub emitted_per_second_per_thread: f64,
    /// Stored photons per second per thread.
    pub stored_per_second_per_thread: f64,
}

impl PhotonThroughput {
    /// The throughput of `maps`, traced in `seconds` on `threads` threads (rates 0 when the
    /// time is 0).
    pub fn new(maps: &PhotonMaps, seconds: f64, threads: usize) -> Self {
        let emitted: u64 = [&maps.caustics, &maps.global]
            .into_iter()
            .flatten()
            .map(|m| m.emitted)
            .sum();
        let stored = maps.stored();
        let per = seconds * threads.max(1) as f64;
        let rate = |n: u64| if per > 0.0 { n as f64 / per } else { 0.0 };
        Self {
            emitted,
            stored,
            seconds,
            threads,
            emitted_per_second_per_thread: rate(emitted),
            stored_per_second_per_thread: rate(stored),
        }
    }

    /// One line for the bench's table.
    pub fn line(&self) -> String {
        format!(
            "photons: {} emitted, {} stored in {:.4} s on {} thread(s): {:.0} emitted/s/thread, {:.0} stored/s/thread",
            self.emitted,
            self.stored,
            self.seconds,
            self.threads,
            self.emitted_per_second_per_thread,
            self.stored_per_second_per_thread
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photon::{GatherMap, Photon, PhotonFilter, PhotonMap};
    use glam::Vec3;

    #[test]
    fn counts_every_map_and_divides_by_threads() {
        let photon = Photon {
            position: Vec3::ZERO,
            power: Vec3::ONE,
            incoming: Vec3::Z,
            normal: Vec3::Z,
        };
        let map = |n: usize, emitted: u64| GatherMap {
            map: PhotonMap::build(vec![photon; n]),
            gather: 8,
            radius: 1.0,
            final_gather: 1,
            emitted,
            filter: PhotonFilter::Box,
            progressive: None,
        };
        let maps = PhotonMaps {
            caustics: Some(map(30, 100)),
            global: Some(map(50, 200)),
            gather_caustics: Some(map(3, 100)),
            gather_irradiance: None,
        };
        let t = PhotonThroughput::new(&maps, 2.0, 4);
        assert_eq!((t.emitted, t.stored), (300, 80));
        assert_eq!(t.emitted_per_second_per_thread, 300.0 / 8.0);
        assert_eq!(t.stored_per_second_per_thread, 10.0);
        assert!(t.line().starts_with("photons: 300 emitted, 80 stored"));
    }
}
