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
//! - indirect diffuse `L (S|D)* D S* D E`: one final-gather bounce, followed through any
//!   chain of purely specular surfaces (`S*`: mirrors, glass; [`gather_path`]) to the first
//!   diffuse surface, where it reads the global map (every diffuse hit, direct ones included,
//!   except caustic `L S+ D` hits) and the caustic map (those `L S+ D` hits: `L S+ D S* D
//!   E`), thinned to the global map's resolution ([`coarse`]). Gather rays that reach lights add nothing (direct light and `L S+ D E` come from the
//!   light loop and the caustic map), so no path is counted twice and none is missing (H23).
//!
//! The path tracer (`Path` integrator) ignores the maps: it is the reference.

pub mod aim;
pub mod batch;
pub mod coarse;
pub mod depth;
pub mod emit;
pub mod estimate;
pub mod file;
pub mod filter;
pub mod gather_path;
pub mod irradiance;
pub mod kdtree;
pub mod key;
pub mod light_lists;
pub mod neighbour_sort;
pub mod parts;
pub mod pass;
pub mod point_grid;
pub mod progressive;
pub mod receivers;
pub mod roles;
pub mod store;
pub mod throughput;
pub mod trace;
pub mod walk;

use glam::Vec3;

pub use batch::Tracing;
pub use emit::Emission;
pub use filter::PhotonFilter;
pub use kdtree::{Gather, Neighbour, Photon, PhotonMap};
pub use parts::PhotonParts;
pub use pass::{trace_map, trace_map_by_light, trace_map_with, MapKind};
pub use progressive::Progressive;
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
    /// The later passes of a progressive map (`map` is the first; `None`: one pass).
    pub progressive: Option<Progressive>,
}

impl GatherMap {
    /// The gather its estimates use.
    pub fn gather(&self) -> Gather {
        Gather::Nearest {
            k: self.gather,
            r_max: self.radius,
        }
    }

    /// The density estimate `Σ f(photon)·Φ / area` at `p` (normal `normal`): k-nearest, or
    /// the progressive estimate over every pass (irradiance for `f = 1`).
    pub fn density(
        &self,
        p: Vec3,
        normal: Vec3,
        scratch: &mut Vec<Neighbour>,
        f: impl Fn(&Photon) -> Vec3,
    ) -> Vec3 {
        match &self.progressive {
            Some(prog) => progressive::estimate(self, prog, p, normal, scratch, f),
            None => self
                .map
                .estimate_filtered(p, normal, self.gather(), self.filter, scratch, f),
        }
    }

    /// Photons stored over every pass.
    pub fn stored(&self) -> u64 {
        self.map.len() as u64 + self.progressive.as_ref().map_or(0, Progressive::stored)
    }
}

/// The output of `trace_photons`.
#[derive(Debug, Clone, Default)]
pub struct PhotonMaps {
    /// Caustic map (`L S+ D` photons), if caustics are on.
    pub caustics: Option<GatherMap>,
    /// Global map (every diffuse hit), if global illumination is on.
    pub global: Option<GatherMap>,
    /// The caustic map as final-gather rays read it ([`coarse::gather_view`]), when both
    /// maps exist.
    pub gather_caustics: Option<GatherMap>,
    /// Irradiance at photon positions for final-gather rays ([`irradiance`], each site
    /// computed on first use), when the global map exists and `precompute` is on.
    pub gather_irradiance: Option<irradiance::IrradiancePoints>,
}

impl PhotonMaps {
    /// Photons stored over both maps.
    pub fn stored(&self) -> u64 {
        [&self.caustics, &self.global]
            .into_iter()
            .flatten()
            .map(GatherMap::stored)
            .sum()
    }
}
