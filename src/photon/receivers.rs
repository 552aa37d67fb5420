//! Whether a photon map can store anything at all, decided from the world (so `plan`
//! answers as the run does, before any geometry is built): the photon walk
//! ([`super::walk`]) stores a photon only on an instance whose role for the map receives
//! ([`super::roles`]) and whose material stores — its photon shader's `stores()`, else a
//! BSDF with a lobe that is not a delta. The answer errs towards storing: materials and
//! instances are not paired, and any shader but a mirror or glass (alone or behind an
//! opacity) counts as one with a non-delta lobe.

use hecs::World;

use super::pass::MapKind;
use crate::components::{Instance, Material, PhotonFlags, Scatter, Shader};

/// Why no photon of `kind`'s map can be stored (`None`: some may be): no instance receives
/// for it, or no material stores photons. Scatter copies, spawned later, are not judged:
/// with a `Scatter` in the world the answer is `None`.
pub fn nothing_receives(world: &World, kind: MapKind) -> Option<String> {
    if world.query::<&Scatter>().iter().next().is_some() {
        return None;
    }
    let mut instances = world.query::<(&Instance, Option<&PhotonFlags>)>();
    let mut any_instance = false;
    let mut any_receives = false;
    for (_, flags) in instances.iter() {
        any_instance = true;
        let f = flags.copied().unwrap_or_default();
        let role = match kind {
            MapKind::Caustics => f.caustic,
            MapKind::Global => f.globillum,
        };
        // Without a flag: the global map's default receives; the caustic map's default
        // receives unless the material's photon shader stores nothing, which the material
        // test below covers.
        any_receives |= role.is_none_or(|r| r.receives());
    }
    if !any_instance {
        return None;
    }
    let flag = match kind {
        MapKind::Caustics => "caustic",
        MapKind::Global => "globillum",
    };
    if !any_receives {
        return Some(format!(
            "no instance receives photons ({flag} 0 or 1 on every one: the receive bit 2 is off)"
        ));
    }
    let stores = world.query::<&Material>().iter().any(|m| match &m.photon {
        Some(p) => p.stores(),
        None => !only_delta(&m.shader),
    });
    (!stores).then(|| {
        "no material stores photons (mirror and glass reflect or refract every one; a photon shader stores none where it reflects and refracts everything)".to_string()
    })
}

/// Whether every lobe of `shader` is a delta (mirror, refraction, pass-through), so that a
/// photon is never stored on it.
fn only_delta(shader: &Shader) -> bool {
    match shader {
        Shader::Mirror { .. } | Shader::Dielectric { .. } => true,
        Shader::Opacity { input, .. } => only_delta(input),
        _ => false,
    }
}
