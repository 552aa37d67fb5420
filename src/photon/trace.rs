//! Tracing one photon: scattering through the materials' BSDFs in importance mode, Russian
//! roulette by the scattering weight, deposits at diffuse surfaces, and an exact account of
//! where its power went (absorbed, escaped, truncated).
//!
//! At each hit the photon's power is first attenuated by the absorption of the segment it
//! crossed (dielectric `col`), then — if the surface has a non-delta lobe — deposited, then
//! scattered: the BSDF is sampled with [`TransportMode::Importance`] (refraction conserves power,
//! no `1/η²`; H14) and the weight gets Veach's shading-normal correction
//! `|wo·nₛ||wi·n_g| / (|wo·n_g||wi·nₛ|)`. The photon survives with probability
//! `q = min(1, max channel of the weight)` and carries `power·weight/q` (Jensen): for grey
//! materials a surviving photon keeps its power, so a map's photons have even powers.

use glam::Vec3;

use super::kdtree::Photon;
use crate::accel::Ray;
use crate::sampling::Sampler;
use crate::shading::bsdf::{Scatter, TransportMode};
use crate::shading::integrator::{ShadeContext, Vertex};

/// Most surface interactions of one photon.
pub const MAX_BOUNCES: u32 = 64;

/// A photon at a diffuse (non-delta) surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deposit {
    /// The photon as a map stores it.
    pub photon: Photon,
    /// Scattering events before this hit (0 = straight from the light).
    pub bounces: u32,
    /// Whether every one of those events was specular (delta) and there was at least one:
    /// an `L S+ D` path, what the caustic map stores.
    pub caustic: bool,
}

/// How a photon's path ended and where its power went, W.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Fate {
    /// Power absorbed by surfaces and dielectric media (Russian roulette included).
    pub absorbed: Vec3,
    /// Power that left the scene.
    pub escaped: Vec3,
    /// Direction of the escaping photon (zero when none escaped).
    pub escape_dir: Vec3,
    /// Power dropped at [`MAX_BOUNCES`] or by `stop_after_diffuse`.
    pub truncated: Vec3,
    /// Where the last hit was (the absorbing surface's triangle), if any.
    pub last_prim: Option<u32>,
}

/// Traces a photon along `ray` carrying `power`, calling `deposit` at every diffuse hit. With
/// `stop_after_diffuse`, the path ends after its first non-specular scattering (no caustic
/// photon can follow: the caustic pass uses it).
pub fn trace_photon(
    ctx: &ShadeContext<'_>,
    mut ray: Ray,
    mut power: Vec3,
    sampler: &mut Sampler,
    stop_after_diffuse: bool,
    mut deposit: impl FnMut(Deposit),
) -> Fate {
    let mut fate = Fate::default();
    let mut specular_only = true;
    for bounces in 0..MAX_BOUNCES {
        let Some(hit) = ctx.geometry.accel.intersect(&ray) else {
            fate.escaped = power;
            fate.escape_dir = ray.dir.normalize_or_zero();
            return fate;
        };
        fate.last_prim = Some(hit.prim);
        let v = Vertex::new(ctx, &ray, &hit);
        let through = power * v.transmittance;
        fate.absorbed += power - through;
        power = through;
        let bsdf = match v.bsdf() {
            Some(b) if v.visible => b,
            _ => {
                fate.absorbed += power;
                return fate;
            }
        };
        let incoming = -ray.dir.normalize();
        if bsdf.has_non_delta() {
            deposit(Deposit {
                photon: Photon {
                    position: v.sp.surface.p,
                    power,
                    incoming,
                    normal: v.ng,
                },
                bounces,
                caustic: bounces > 0 && specular_only,
            });
        }
        let u = Vec3::new(sampler.next_1d(), sampler.next_1d(), sampler.next_1d());
        let u_rr = sampler.next_1d();
        let Some(s) = bsdf.sample_transport(v.wo, u, TransportMode::Importance) else {
            fate.absorbed += power;
            return fate;
        };
        let wi = v.frame.to_world(s.wi);
        // Adjoint BSDF with shading normals (Veach 1997, §5.3).
        let ns = v.frame.n;
        let correction =
            (incoming.dot(ns) * wi.dot(v.ng)).abs() / (incoming.dot(v.ng) * wi.dot(ns)).abs();
        let weight = s.weight() * correction;
        if !weight.is_finite() {
            fate.absorbed += power;
            return fate;
        }
        let q = weight.max_element().min(1.0);
        if q.is_nan() || u_rr >= q {
            fate.absorbed += power;
            return fate;
        }
        if !s.delta {
            specular_only = false;
        }
        let next_power = power * (weight / q);
        // What survival does not carry on (a colour-dependent weight) is absorbed; a weight
        // above 1 (shading-normal correction) makes this negative, keeping the account exact.
        fate.absorbed += power - next_power;
        if stop_after_diffuse && !specular_only {
            fate.truncated += next_power;
            return fate;
        }
        let Some(next) = v.spawn(s.wi, s.scatter == Scatter::Transmission) else {
            fate.absorbed += next_power;
            return fate;
        };
        power = next_power;
        ray = next;
    }
    fate.truncated += power;
    fate
}
