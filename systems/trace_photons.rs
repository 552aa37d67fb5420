//! `trace_photons`: the photon pass. Emits photons from every light with power, traces them
//! through the scene's BSDFs and stores the caustic and global photon maps.
//!
//! **Reads:** `Emitter` entities and their `LightPhotons` (energy, photon counts);
//! `PhotonFlags` of instances (caster/receiver roles);
//! `outputs.geometry` (lights, emitting meshes, surfaces); `settings.photons` (photons,
//! radius, gather, aim, progressive passes per map), `settings.seed`.
//! **Writes:** `outputs.photons` (returned to the runner).
//! **Runs when:** the run renders with the `Direct` integrator, caustics or global
//! illumination is on, geometry exists, and some light emits power.
//! **After this stage:** `outputs.photons` holds the requested maps, each built from its own
//! number of emitted photons with powers summing (in expectation) to what reaches the
//! stored surfaces, identical at any thread count.

use hecs::World;

use super::prelude::*;
use super::MERGING;
use crate::components::{Emitter, LightPhotons, Material, PhotonFlags};
use crate::frame::Slot;
use crate::photon::aim::Aim;
use crate::photon::emit::bounding_sphere;
use crate::photon::progressive::trace_passes;
use crate::photon::roles::instance_sphere;
use crate::photon::{
    trace_map_by_light, Emission, GatherMap, MapKind, PhotonMap, PhotonMaps, PhotonRoles,
};
use crate::sampling::fold_seed;
use crate::scene_view::{has_render_camera, light_set, WithEnvironment};
use crate::settings::{Integrator, PhotonMapSettings};
use crate::shading::ShadeContext;

/// Automatic gather radius as a fraction of the scene's bounding-box diagonal.
const AUTO_RADIUS: f32 = 0.02;

/// Run condition: a map is requested, something reads it, and a light has power.
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    if frame.inputs.merging() {
        return Decision::skip(MERGING);
    }
    let p = frame.inputs.settings.photons;
    let maps: Vec<String> = [
        ("caustics", p.caustics),
        ("global illumination", p.global_illumination),
    ]
    .into_iter()
    .filter_map(|(name, m)| {
        m.map(|m| match m.progressive {
            Some(p) => format!("{name} ({} photons × {} passes)", m.photons, p.passes),
            None => format!("{name} ({} photons)", m.photons),
        })
    })
    .collect();
    if maps.is_empty() {
        return Decision::skip("caustics and global illumination are off");
    }
    if !frame.inputs.tasks.render || !has_render_camera(world) {
        return Decision::skip("no render camera reads photon maps in this run");
    }
    if frame.inputs.settings.integrator != Integrator::Direct {
        return Decision::skip("the path integrator does not read photon maps");
    }
    if !frame.outputs.has(Slot::Geometry) {
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

/// Traces the requested photon maps.
pub fn run(world: &World, frame: &Frame) -> Result<Work, StageError> {
    let geometry = frame
        .outputs
        .geometry
        .as_ref()
        .ok_or_else(|| StageError::Internal("photon pass without geometry".into()))?;
    let settings = &frame.inputs.settings;
    let lights = light_set(world, Some(geometry), settings, WithEnvironment::No);
    let controls = light_controls(world);
    let energies: Vec<_> = controls.iter().map(|c| c.energy).collect();
    let emission = Emission::with_energies(&lights, geometry, &energies);
    let roles = PhotonRoles::new(geometry, |slot| {
        let entity = geometry.instances[slot].entity;
        world.get::<&PhotonFlags>(entity).ok().map(|f| *f)
    });
    let ctx = ShadeContext::new(geometry, &lights, settings);
    let seed = fold_seed(settings.seed);
    let diagonal = 2.0 * bounding_sphere(geometry).1;
    let build = |kind: MapKind, s: Option<PhotonMapSettings>| -> Result<_, StageError> {
        let Some(s) = s else { return Ok(None) };
        let aimed;
        let emission = if kind == MapKind::Caustics && s.aim {
            let spheres = roles
                .caustic_casters(geometry)
                .into_iter()
                .filter_map(|slot| instance_sphere(geometry, slot))
                .collect();
            aimed = emission.clone().aimed(Aim::new(spheres));
            &aimed
        } else {
            &emission
        };
        let counts: Vec<(usize, u32)> = controls
            .iter()
            .enumerate()
            .filter_map(|(i, c)| match kind {
                MapKind::Caustics => c.caustic_photons.map(|n| (i, n)),
                MapKind::Global => c.globillum_photons.map(|n| (i, n)),
            })
            .collect();
        let pass = |seed| {
            let roles = roles.for_map(kind);
            let cancel = &frame.inputs.cancel;
            trace_map_by_light(
                &ctx, emission, roles, kind, s.photons, &counts, seed, cancel,
            )
        };
        let (photons, progressive, emitted) =
            trace_passes(s.progressive, seed, pass).ok_or(StageError::Interrupted)?;
        Ok(Some(GatherMap {
            map: PhotonMap::build(photons),
            gather: s.gather.max(2) as usize,
            radius: if s.radius > 0.0 {
                s.radius
            } else {
                AUTO_RADIUS * diagonal
            },
            final_gather: s.final_gather.max(1),
            emitted,
            filter: s.filter,
            progressive,
        }))
    };
    let maps = PhotonMaps {
        caustics: build(MapKind::Caustics, settings.photons.caustics)?,
        global: build(MapKind::Global, settings.photons.global_illumination)?,
    };
    let stored = maps.stored();
    Ok(Work::new(stored, "photons").with_output(StageOutput::Photons(maps)))
}

/// Each emitter's photon controls, in the order of the light set (entity order).
fn light_controls(world: &World) -> Vec<LightPhotons> {
    let mut lights: Vec<(u64, LightPhotons)> = world
        .query::<(hecs::Entity, &Emitter, Option<&LightPhotons>)>()
        .iter()
        .map(|(e, _, c)| (e.to_bits().get(), c.copied().unwrap_or_default()))
        .collect();
    lights.sort_by_key(|&(bits, _)| bits);
    lights.into_iter().map(|(_, c)| c).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::systems::tiny_scene::{load, run_until, scene};

    fn photons_of(world: &World, frame: &Frame) -> (u64, PhotonMaps) {
        let work = run(world, frame).unwrap();
        match work.output {
            Some(StageOutput::Photons(maps)) => (work.items, maps),
            _ => panic!("trace_photons returns the maps"),
        }
    }

    #[test]
    fn a_global_map_lands_on_the_lit_square_deterministically() {
        let text = scene(
            "global_illumination: (photons: 2000, gather: 8)",
            "",
            "",
            &[],
        );
        let (mut world, mut frame) = load(&text, false);
        run_until("trace_photons", &mut world, &mut frame);
        assert_eq!(
            should_run(&world, &frame),
            Decision::run("global illumination (2000 photons)")
        );
        let (stored, maps) = photons_of(&world, &frame);
        let global = maps.global.as_ref().unwrap();
        assert!(maps.caustics.is_none());
        assert_eq!(global.emitted, 2000);
        // A point light 2 above the centre of a 2×2 square sends a fraction Ω/4π of its
        // photons onto it, Ω = 4·asin(1/5) = 0.80543 sr: 0.064094. The GI map stores those
        // first hits; bounces leave into open space. Binomial: within 4σ.
        let p = 4.0 * 0.2f64.asin() / (4.0 * std::f64::consts::PI);
        let sigma = (p * (1.0 - p) / 2000.0).sqrt();
        let fraction = stored as f64 / 2000.0;
        assert!(
            (fraction - p).abs() < 4.0 * sigma,
            "stored fraction {fraction} vs {p}"
        );
        assert_eq!(photons_of(&world, &frame).0, stored, "same seed, same map");
    }

    #[test]
    fn skipped_when_no_map_is_requested() {
        let (world, frame) = load(&scene("", "", "", &[]), false);
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("caustics and global illumination are off")
        );
    }
}
