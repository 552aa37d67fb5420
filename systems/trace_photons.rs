//! `trace_photons`: the photon pass. Emits photons from every light with power, traces them
//! through the scene's BSDFs and stores the caustic and global photon maps.
//!
//! **Reads:** `Emitter` entities; `frame.geometry` (lights, emitting meshes, surfaces);
//! `settings.photons` (photons, radius, gather per map), `settings.seed`.
//! **Writes:** `frame.photons`.
//! **Runs when:** the run renders with the `Direct` integrator, caustics or global
//! illumination is on, geometry exists, and some light emits power.
//! **After this stage:** `frame.photons` holds the requested maps, each built from its own
//! number of emitted photons with powers summing (in expectation) to what reaches the
//! stored surfaces, identical at any thread count.

use hecs::{Entity, World};

use super::prelude::*;
use crate::components::{Emitter, Material, RenderCamera};
use crate::photon::emit::bounding_sphere;
use crate::photon::{trace_map, Emission, GatherMap, MapKind, PhotonMap, PhotonMaps};
use crate::sampling::fold_seed;
use crate::settings::{Integrator, PhotonMapSettings};
use crate::shading::{LightSet, ShadeContext};

/// Automatic gather radius as a fraction of the scene's bounding-box diagonal.
const AUTO_RADIUS: f32 = 0.02;

/// Run condition: a map is requested, something reads it, and a light has power.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    let p = frame.settings.photons;
    let maps: Vec<String> = [
        ("caustics", p.caustics),
        ("global illumination", p.global_illumination),
    ]
    .into_iter()
    .filter_map(|(name, m)| m.map(|m| format!("{name} ({} photons)", m.photons)))
    .collect();
    if maps.is_empty() {
        return Decision::skip("caustics and global illumination are off");
    }
    if !frame.tasks.render || !crate::schedule::any_with::<RenderCamera>(world) {
        return Decision::skip("no render camera reads photon maps in this run");
    }
    if frame.settings.integrator != Integrator::Direct {
        return Decision::skip("the path integrator does not read photon maps");
    }
    if frame.geometry.is_none() {
        return Decision::skip("no geometry receives photons");
    }
    let lit = world
        .query::<&Emitter>()
        .iter()
        .any(|e| e.radiant.max_element() > 0.0)
        || world.query::<&Material>().iter().any(Material::is_emissive);
    if !lit {
        return Decision::skip("no light has power");
    }
    Decision::run(maps.join(" + "))
}

/// Builds `frame.photons`.
pub fn run(world: &mut World, frame: &mut Frame) -> Result<Work, StageError> {
    let geometry = frame
        .geometry
        .as_ref()
        .ok_or_else(|| StageError::Invalid("photon pass without geometry".into()))?;
    let mut emitters: Vec<(Entity, Emitter)> = world
        .query::<(Entity, &Emitter)>()
        .iter()
        .map(|(e, l)| (e, l.clone()))
        .collect();
    emitters.sort_by_key(|(e, _)| e.to_bits());
    let emitters: Vec<Emitter> = emitters.into_iter().map(|(_, l)| l).collect();
    let lights = LightSet::new(&emitters, Some(geometry), frame.settings.light_samples);
    let emission = Emission::new(&lights, geometry);
    let ctx = ShadeContext::new(geometry, &lights, &frame.settings);
    let seed = fold_seed(frame.settings.seed);
    let diagonal = 2.0 * bounding_sphere(geometry).1;
    let build = |kind: MapKind, s: Option<PhotonMapSettings>| -> Result<_, StageError> {
        let Some(s) = s else { return Ok(None) };
        let photons = trace_map(&ctx, &emission, kind, s.photons, seed, &frame.cancel)
            .ok_or(StageError::Interrupted)?;
        Ok(Some(GatherMap {
            map: PhotonMap::build(photons),
            gather: s.gather.max(2) as usize,
            radius: if s.radius > 0.0 {
                s.radius
            } else {
                AUTO_RADIUS * diagonal
            },
            final_gather: s.final_gather.max(1),
            emitted: u64::from(s.photons),
        }))
    };
    let maps = PhotonMaps {
        caustics: build(MapKind::Caustics, frame.settings.photons.caustics)?,
        global: build(MapKind::Global, frame.settings.photons.global_illumination)?,
    };
    let stored = maps.stored();
    frame.photons = Some(maps);
    Ok(Work {
        items: stored,
        unit: "photons",
    })
}
