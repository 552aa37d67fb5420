//! `trace_photons`: the photon pass. Emits photons from every light with power, traces them
//! through the scene's BSDFs and stores the caustic and global photon maps.
//!
//! **Reads:** `Emitter` entities and their `LightPhotons` (energy, photon counts);
//! `PhotonFlags` of instances (caster/receiver roles);
//! `outputs.geometry` (lights, emitting meshes, surfaces); `settings.photons` (photons,
//! radius, gather, aim, progressive passes per map), `settings.seed`.
//! **Writes:** `outputs.photons` (returned to the runner); the photon map file, when the
//! scene names one (`photon_map`) or the run has `--photon-cache DIR`, unless it was reused.
//! **Reuses:** that file when its content hash ([`crate::photon::key`]) matches: the maps
//! are loaded, and the report lists the stage as skipped, "loaded from FILE (hash …)".
//! **Runs when:** the run renders with the `Direct` integrator, caustics or global
//! illumination is on, geometry exists (with a caustic caster when only caustics are on),
//! some instance receives photons for a map that is on and some material stores them
//! (`crate::photon::receivers`), and some light emits power.
//! **After this stage:** `outputs.photons` holds the requested maps, each built from its own
//! number of emitted photons with powers summing (in expectation) to what reaches the
//! stored surfaces, identical at any thread count.

use hecs::World;

use super::prelude::*;
use super::MERGING;
use crate::components::{Emitter, LightPhotons, LightShape, Material, PhotonFlags};
use crate::farm::part::Share;
use crate::frame::Slot;
use crate::image_io::PendingFile;
use crate::photon::aim::Aim;
use crate::photon::coarse;
use crate::photon::emit::bounding_sphere;
use crate::photon::file::{encode, StoredMap, StoredMaps};
use crate::photon::irradiance::{IrradianceMaps, IrradiancePoints};
use crate::photon::key::photon_key;
use crate::photon::progressive::{trace_passes, Progressive, StartRadius};
use crate::photon::receivers::nothing_receives;
use crate::photon::roles::instance_sphere;
use crate::photon::store::{self, Miss};
use crate::photon::{
    trace_map_by_light, Emission, GatherMap, MapKind, PhotonMap, PhotonMaps, PhotonRoles,
};
use crate::sampling::fold_seed;
use crate::scene_view::{has_render_camera, light_set, WithEnvironment};
use crate::settings::{Integrator, PhotonMapSettings, PhotonSettings, RenderSettings};
use crate::shading::integrator::material_bsdfs::MaterialBsdfs;
use crate::shading::integrator::triangle_normals::TriangleNormals;
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
        ("caustics", MapKind::Caustics, p.caustics),
        (
            "global illumination",
            MapKind::Global,
            p.global_illumination,
        ),
    ]
    .into_iter()
    .filter_map(|(name, kind, m)| m.map(|m| format!("{name} ({})", emitted_text(world, kind, m))))
    .collect();
    if maps.is_empty() {
        return Decision::skip("caustics and global illumination are off");
    }
    if !frame.inputs.tasks.render
        || !has_render_camera(world)
        || !crate::scene_view::image_is_read(world, &frame.inputs)
    {
        return Decision::skip("no render camera reads photon maps in this run");
    }
    match crate::scene_view::part_share(world, &frame.inputs) {
        Some(Share::Nothing(why)) => return Decision::skip(why),
        Some(Share::CentresOnly(why)) => {
            return Decision::skip(format!(
                "{why}; its centre-sample passes read no photon maps"
            ))
        }
        _ => {}
    }
    // The photon view shows the maps from the pixel-centre rays; nothing else reads them
    // without samples.
    let photon_view = matches!(
        frame.inputs.settings.diagnostic,
        Some(crate::diagnostic::Diagnostic::Photon { .. })
    );
    if let Some(why) = crate::image_reads::samples_unread(world, &frame.inputs) {
        if !photon_view {
            return Decision::skip(format!(
                "{why}; photon maps are read only by the shaded samples"
            ));
        }
    }
    if frame.inputs.settings.integrator != Integrator::Direct {
        return Decision::skip("the path integrator does not read photon maps");
    }
    if !frame.outputs.has(Slot::Geometry) {
        return Decision::skip("no geometry receives photons");
    }
    if p.global_illumination.is_none() && nothing_casts_caustics(world) {
        return Decision::skip(
            "caustics are on, but nothing casts them (no mirror, glass or other specular material, no photon shader that reflects or refracts; a caustic flag on a diffuse surface casts none)",
        );
    }
    if let Some(why) = nothing_stored(world, &p) {
        return Decision::skip(why);
    }
    let lit = world
        .query::<&Emitter>()
        .iter()
        .any(|e| e.radiant.max_element() > 0.0)
        || world.query::<&Material>().iter().any(Material::is_emissive);
    if !lit {
        return Decision::skip("no light has power");
    }
    if !a_light_emits_photons(world, &p) {
        return Decision::skip(
            "no light emits photons for the maps requested (ambient lights send none; every other light has photon energy 0 or 0 photons for them)",
        );
    }
    let kept = match (
        &frame.inputs.photon_cache,
        &frame.inputs.settings.photon_map,
    ) {
        (Some(dir), _) => format!(
            "; runs unless {}/<hash>.pmap holds these maps (then they are loaded from it and the stage is reported skipped; the hash needs the built geometry), else keeps them there",
            dir.display()
        ),
        (None, Some(f)) => format!(
            "; runs unless {} holds these maps (same hash: then they are loaded from it and the stage is reported skipped; the hash needs the built geometry), else keeps them there",
            f.path.display()
        ),
        (None, None) => String::new(),
    };
    Decision::run(format!("{}{kept}", maps.join(" + ")))
}

/// The photons one pass of the map `kind` emits, as the reason says them: the map's
/// `photons` (`m.photons`), shared by the lights without a count of their own for it, plus
/// each light's own count (mental ray's `caustic photons` / `globillum photons`), as
/// [`trace_map_by_light`] emits them — `5000000 photons, the lights' own counts`.
fn emitted_text(world: &World, kind: MapKind, m: PhotonMapSettings) -> String {
    let mut shared = world.query::<&Material>().iter().any(Material::is_emissive);
    let mut own = 0u64;
    for (e, c) in world.query::<(&Emitter, Option<&LightPhotons>)>().iter() {
        let c = c.copied().unwrap_or_default();
        let power = c.energy.unwrap_or(e.radiant);
        if matches!(e.shape, LightShape::Ambient) || power.max_element() <= 0.0 {
            continue; // emits nothing
        }
        let count = match kind {
            MapKind::Caustics => c.caustic_photons,
            MapKind::Global => c.globillum_photons,
        };
        match count {
            Some(n) => own += u64::from(n),
            None => shared = true,
        }
    }
    let passes = m
        .progressive
        .map_or(String::new(), |p| format!(" × {} passes", p.passes));
    let map = u64::from(m.photons);
    match (shared, own) {
        (_, 0) => format!("{map} photons{passes}"),
        (false, own) => format!("{own} photons{passes}, the lights' own counts"),
        (true, own) => format!(
            "{} photons{passes}: {map} shared by the lights without a count, {own} the lights' own counts",
            map + own
        ),
    }
}

/// Whether some light sends photons into a requested map: an emitting material, or a light
/// other than an ambient one whose photon power (its `energy`, else its physical power) is
/// non-zero and whose own photon count for that map (mental ray's `caustic photons` /
/// `globillum photons`) is not 0. Mirrors what [`run`] traces: ambient lights and zero
/// power emit nothing, a count of 0 skips the light for that map.
fn a_light_emits_photons(world: &World, maps: &PhotonSettings) -> bool {
    if world.query::<&Material>().iter().any(Material::is_emissive) {
        return true;
    }
    world
        .query::<(&Emitter, Option<&LightPhotons>)>()
        .iter()
        .any(|(e, c)| {
            let c = c.copied().unwrap_or_default();
            let power = c.energy.unwrap_or(e.radiant);
            let sends = |map: Option<PhotonMapSettings>, count: Option<u32>| {
                map.is_some() && count != Some(0)
            };
            !matches!(e.shape, LightShape::Ambient)
                && power.max_element() > 0.0
                && (sends(maps.caustics, c.caustic_photons)
                    || sends(maps.global_illumination, c.globillum_photons))
        })
}

/// Whether nothing in the scene can cast caustic photons: no material that makes caustics
/// (mirror, glass, a specular term; [`crate::photon::roles::makes_caustics`]) and no photon
/// shader that reflects or refracts. A caustic flag does not make a diffuse surface a caster:
/// its photons are absorbed or scattered diffusely, never on an `L S+ D` path. The caustic
/// map alone would stay empty. Decided from the world, so `plan` gives the same answer
/// before any geometry exists.
fn nothing_casts_caustics(world: &World) -> bool {
    !world.query::<&Material>().iter().any(|m| {
        crate::photon::roles::makes_caustics(&m.shader) || m.photon.is_some_and(|p| p.scatters())
    })
}

/// Why no requested map can store a photon ([`nothing_receives`]: no instance receives for
/// it, or no material stores), or `None` when one can:
/// `global illumination is on, but no instance receives photons (globillum 0 or 1 …)`.
fn nothing_stored(world: &World, p: &PhotonSettings) -> Option<String> {
    let requested: Vec<(&str, MapKind)> = [
        ("caustics", MapKind::Caustics, p.caustics.is_some()),
        (
            "global illumination",
            MapKind::Global,
            p.global_illumination.is_some(),
        ),
    ]
    .into_iter()
    .filter(|r| r.2)
    .map(|(name, kind, _)| (name, kind))
    .collect();
    let mut whys = Vec::new();
    for &(name, kind) in &requested {
        whys.push((name, nothing_receives(world, kind)?));
    }
    Some(match whys.as_slice() {
        [(name, why)] => {
            let verb = if *name == "caustics" { "are" } else { "is" };
            format!("{name} {verb} on, but {why}")
        }
        _ => {
            let each: Vec<String> = whys.iter().map(|(n, w)| format!("{n}: {w}")).collect();
            format!(
                "caustics and global illumination are on, but no photon can be stored ({})",
                each.join("; ")
            )
        }
    })
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
    let normals = TriangleNormals::new(geometry);
    let bsdfs = MaterialBsdfs::new(geometry);
    let ctx = ShadeContext::new(geometry, &lights, settings)
        .with_normals(normals.as_ref())
        .with_bsdfs(Some(&bsdfs));
    let seed = fold_seed(settings.seed);
    let diagonal = 2.0 * bounding_sphere(geometry).1;
    let key = photon_key(geometry, &lights, &controls, &roles, settings);
    let kept = store::location(settings, frame.inputs.photon_cache.as_deref(), key);
    if let Some(at) = &kept {
        match store::load(at, key) {
            Ok(stored) => {
                let maps = gather_maps(stored, settings, diagonal);
                return Ok(Work::new(maps.stored(), "photons")
                    .with_output(StageOutput::Photons(maps))
                    .reused(format!(
                        "loaded from {} (hash {key:016x})",
                        at.path.display()
                    )));
            }
            Err(Miss::Unreadable(why)) => {
                tracing::warn!(file = %at.path.display(), "{why}");
            }
            Err(_) => {}
        }
    }
    let trace = |kind: MapKind, s: Option<PhotonMapSettings>| -> Result<_, StageError> {
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
        Ok(Some(StoredMap {
            map: PhotonMap::from_parts(photons.into_parts()),
            later: progressive.map(|p| p.later).unwrap_or_default(),
            emitted,
        }))
    };
    let stored = StoredMaps {
        key,
        caustics: trace(MapKind::Caustics, settings.photons.caustics)?,
        global: trace(MapKind::Global, settings.photons.global_illumination)?,
    };
    let pending: Vec<PendingFile> = kept
        .into_iter()
        // Shared: farm parts run without the photon job trace the same maps into the same
        // file at once (`--photon-cache DIR/<hash>.pmap`, or the scene's `photon_map`: same
        // hash, same bytes); each renames its complete copy over it, and none fails.
        .map(|at| PendingFile::shared(at.path, encode(&stored)))
        .collect();
    let maps = gather_maps(stored, settings, diagonal);
    Ok(Work::new(maps.stored(), "photons")
        .with_output(StageOutput::Photons(maps))
        .with_pending(pending))
}

/// The maps with the knobs of the estimates that read them (from `settings`, which the
/// content hash leaves out: they can change without tracing again), and the sites of the
/// irradiance final-gather rays read (each computed on first use, in `shade`).
fn gather_maps(stored: StoredMaps, settings: &RenderSettings, diagonal: f32) -> PhotonMaps {
    let knobs = |s: Option<PhotonMapSettings>, m: Option<StoredMap>| {
        let (s, m) = (s?, m?);
        Some(GatherMap {
            map: m.map,
            gather: s.gather.max(2) as usize,
            radius: if s.radius > 0.0 {
                s.radius
            } else {
                AUTO_RADIUS * diagonal
            },
            final_gather: s.final_gather.max(1),
            emitted: m.emitted,
            filter: s.filter,
            progressive: s.progressive.map(|p| Progressive {
                later: m.later,
                alpha: p.alpha,
                // An automatic radius only caps the start at each gather point.
                start: if s.radius > 0.0 {
                    StartRadius::Fixed
                } else {
                    StartRadius::Nearest
                },
            }),
        })
    };
    // An empty map adds nothing: without it no estimate is made and no final-gather ray is
    // traced (an empty global map stays while the caustic map has photons, which its
    // final-gather rays read).
    let caustics = knobs(settings.photons.caustics, stored.caustics).filter(|c| c.stored() > 0);
    let global = knobs(settings.photons.global_illumination, stored.global)
        .filter(|g| g.stored() > 0 || caustics.is_some());
    let gather_caustics = match (&caustics, &global) {
        (Some(c), Some(g)) => coarse::gather_view(c, g),
        _ => None,
    };
    let precompute = settings
        .photons
        .global_illumination
        .is_some_and(|s| s.precompute);
    let gather_irradiance = match &global {
        Some(g) if precompute => Some(IrradiancePoints::new(IrradianceMaps {
            global: g,
            caustics: gather_caustics.as_ref(),
        })),
        _ => None,
    };
    PhotonMaps {
        caustics,
        global,
        gather_caustics,
        gather_irradiance,
    }
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

    /// The reason says the photons the pass emits: a light's own count replaces the map's
    /// `photons` for that light, and the lights without one share the map's.
    #[test]
    fn the_reason_counts_the_lights_own_photons_as_emitted() {
        let base = scene(
            "global_illumination: (photons: 2000, gather: 8)",
            "",
            "",
            &[],
        );
        let own = "(name: \"lamp\", kind: Point(position: (0, 0, 2)), intensity: 2.0, globillum_photons: 700)";
        let lamp = "(name: \"lamp\", kind: Point(position: (0, 0, 2)), intensity: 2.0)";
        assert!(base.contains(lamp), "{base}");
        let second = "(name: \"lamp2\", kind: Point(position: (0, 0, 2)), intensity: 1.0, globillum_photons: 500)";
        for (text, reason, emitted) in [
            (
                base.replace(lamp, own),
                "global illumination (700 photons, the lights' own counts)",
                700,
            ),
            (
                base.replace(lamp, &format!("{lamp}, {second}")),
                "global illumination (2500 photons: 2000 shared by the lights without a count, 500 the lights' own counts)",
                2500,
            ),
        ] {
            let (mut world, mut frame) = load(&text, false);
            run_until("trace_photons", &mut world, &mut frame);
            assert_eq!(should_run(&world, &frame), Decision::run(reason));
            let (_, maps) = photons_of(&world, &frame);
            assert_eq!(maps.global.as_ref().unwrap().emitted, emitted);
        }
    }

    /// A spot aimed away from everything stores no photon: the maps are dropped, so the
    /// shading traces no final-gather ray into an empty map.
    #[test]
    fn an_empty_global_map_is_dropped() {
        let text = scene(
            "global_illumination: (photons: 2000, gather: 8)",
            "",
            "",
            &[],
        )
        .replace(
            "Point(position: (0, 0, 2))",
            "Spot(position: (0, 0, 2), target: (0, 0, 5), cone_angle: 20)",
        );
        let (mut world, mut frame) = load(&text, false);
        run_until("trace_photons", &mut world, &mut frame);
        let (stored, maps) = photons_of(&world, &frame);
        assert_eq!(stored, 0);
        assert!(maps.global.is_none() && maps.caustics.is_none());
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
