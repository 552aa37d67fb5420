//! Photon mapping (Jensen; mental ray's caustics and global illumination): emission from the
//! lights ([`emit`]), tracing and deposits ([`trace`]), the parallel photon pass that fills a
//! map ([`pass`]), the kd-tree and density estimate ([`kdtree`]), the radiance the
//! `Direct` integrator adds from the maps ([`estimate`]), and photon map files: their format
//! ([`file`]), the content hash that decides reuse ([`key`]) and where they are kept
//! ([`store`]).
//!
//! **Path-space partition** (what each part of a `Direct` render computes at a diffuse point
//! seen by the camera, directly or through mirrors and glass):
//! - direct light `L D E`: the light loop (shadow rays);
//! - caustics `L S+ D E`: the caustic map, visualised directly (`S` = delta: mirror, glass,
//!   transparency);
//! - indirect diffuse `L (S|D)* D D E`: one final-gather bounce whose hits read the global
//!   map (which stores every diffuse hit, direct ones included, except caustic `L S+ D`
//!   hits). Gather rays that hit delta surfaces or lights add nothing, so no path is counted
//!   twice; `L …D S D E` paths through a mirror after a diffuse bounce and `L S+ D D E`
//!   (a caustic seen through one diffuse bounce: a few very bright photons, which made
//!   speckles) are not computed.
//!
//! The path tracer (`Path` integrator) ignores the maps: it is the reference.

pub mod aim;
pub mod emit;
pub mod estimate;
pub mod file;
pub mod filter;
pub mod kdtree;
pub mod key;
pub mod pass;
pub mod roles;
pub mod store;
pub mod trace;

pub use emit::Emission;
pub use filter::PhotonFilter;
pub use kdtree::{Gather, Neighbour, Photon, PhotonMap};
pub use pass::{trace_map, trace_map_by_light, MapKind};
pub use roles::PhotonRoles;
pub use trace::{trace_photon, trace_photon_with_roles, Deposit, Fate};

/// A photon map and the knobs of the estimates that read it.
#[derive(Debug, Clone)]
pub struct GatherMap {
    /// The photons.
    pub map: PhotonMap,
    /// Photons per estimate (k), ≥ 2.
    pub gather: usize,
    /// Largest gather radius, world units (resolved: never 0).
    pub radius: f32,
    /// Final-gather rays per shading point (global map only).
    pub final_gather: u32,
    /// Photons emitted to build it.
    pub emitted: u64,
    /// Weighting of the photons in an estimate.
    pub filter: PhotonFilter,
}

impl GatherMap {
    /// The gather its estimates use.
    pub fn gather(&self) -> Gather {
        Gather::Nearest {
            k: self.gather,
            r_max: self.radius,
        }
    }
}

/// The output of `trace_photons`.
#[derive(Debug, Clone, Default)]
pub struct PhotonMaps {
    /// Caustic map (`L S+ D` photons), if caustics are on.
    pub caustics: Option<GatherMap>,
    /// Global map (every diffuse hit), if global illumination is on.
    pub global: Option<GatherMap>,
}

impl PhotonMaps {
    /// Photons stored over both maps.
    pub fn stored(&self) -> u64 {
        [&self.caustics, &self.global]
            .into_iter()
            .flatten()
            .map(|m| m.map.len() as u64)
            .sum()
    }
}
