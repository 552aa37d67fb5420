//! Photon flags on objects and instances (mental ray `caustic 0|1|2|3`, `globillum 0|1|2|3`):
//! their values checked, their inheritance down the instance DAG (see [`super::dag::flatten`]:
//! the closest instance that sets a flag wins, then the object's own), and the warning for a
//! caustic caster whose material also lets shadow rays through (its light would be counted
//! twice: once by the shadow rays, once by the caustic photons — the seed's rule that a
//! caustic caster should have no shadow shader). Also the lights' photon controls
//! (`energy`, `caustic_photons`, `globillum_photons`).

use super::desc::LightDesc;
use super::diagnostics::Sources;
use super::message::Diagnostic;
use super::syntax::{Helps, Syntax};
use super::validate::Merged;
use crate::components::{LightPhotons, Material, PhotonFlags, PhotonRole};
use crate::photon::roles::makes_caustics;
use crate::shading::shadow::material_passes_shadows;

/// Largest valid flag value (3: casts and receives).
const MAX_FLAG: u8 = 3;

fn flags(caustic: Option<u8>, globillum: Option<u8>) -> PhotonFlags {
    PhotonFlags {
        caustic: caustic.map(|v| PhotonRole(v.min(MAX_FLAG))),
        globillum: globillum.map(|v| PhotonRole(v.min(MAX_FLAG))),
    }
}

/// The flags instance `inst` sets itself.
pub fn instance_flags(m: &Merged<'_>, inst: usize) -> PhotonFlags {
    let d = m.instances[inst].desc;
    flags(d.caustic, d.globillum)
}

/// The flags object `o` sets itself.
pub fn object_flags(m: &Merged<'_>, o: usize) -> PhotonFlags {
    let d = m.objects[o].desc;
    flags(d.caustic, d.globillum)
}

/// A light's photon controls (checked by [`check`]).
pub fn light_photons(d: &LightDesc) -> LightPhotons {
    LightPhotons {
        energy: d
            .energy
            .map(|(r, g, b)| glam::DVec3::new(r, g, b).as_vec3().max(glam::Vec3::ZERO)),
        caustic_photons: d.caustic_photons,
        globillum_photons: d.globillum_photons,
    }
}

/// Reports every flag outside `0..=3` and every light `energy` that is negative or not
/// finite.
pub fn check(src: &mut Sources, m: &Merged<'_>) {
    for it in &m.lights {
        let Some((r, g, b)) = it.desc.energy else {
            continue;
        };
        let ok = [r, g, b]
            .iter()
            .all(|v| v.is_finite() && *v >= 0.0 && *v <= f32::MAX as f64);
        if !ok {
            src.error(
                it.file,
                &it.at(".energy"),
                format!("energy must be finite and non-negative, found ({r}, {g}, {b})"),
                Some(
                    "energy is the photon power in W per channel; (0, 0, 0) emits no photons"
                        .into(),
                ),
            );
        }
    }
    let objects = m
        .objects
        .iter()
        .map(|it| (it.file, it.path.clone(), it.desc.caustic, it.desc.globillum));
    let instances = m
        .instances
        .iter()
        .map(|it| (it.file, it.path.clone(), it.desc.caustic, it.desc.globillum));
    for (file, path, caustic, globillum) in objects.chain(instances) {
        for (name, value) in [("caustic", caustic), ("globillum", globillum)] {
            let Some(v) = value.filter(|&v| v > MAX_FLAG) else {
                continue;
            };
            src.error(
                file,
                &format!("{path}.{name}"),
                format!("{name} must be 0, 1, 2 or 3, found {v}"),
                Some("0 = none, 1 = casts, 2 = receives, 3 = casts and receives".into()),
            );
        }
    }
}

/// A placed object as the shadow-caster warning sees it.
pub struct PlacedFlags<'a> {
    /// DAG path of the leaf.
    pub path: &'a str,
    /// Innermost instance (index into `Merged::instances`).
    pub instance: usize,
    /// The object (index into `Merged::objects`).
    pub object: usize,
    /// Its material (index into `Merged::materials`).
    pub material: Option<usize>,
    /// Its resolved flags.
    pub photon: PhotonFlags,
}

/// Warns, once per instance and material, about leaves whose explicit caustic flag casts
/// while their material lets shadow rays through and sends caustic photons on (it reflects
/// or refracts them): only then is the light it transmits carried twice. Nothing to warn
/// about without a caustic map (`caustic_map` false), or for a material that only passes
/// light straight through (an `Opacity` over a diffuse shader: photons that pass it are
/// direct light, never stored as caustics). `materials[i]` is the checked material `i`.
pub fn warn_shadow_casters<'a>(
    src: &mut Sources,
    m: &Merged<'_>,
    leaves: impl Iterator<Item = PlacedFlags<'a>>,
    materials: &[Option<&Material>],
    caustic_map: bool,
) {
    if !caustic_map {
        return;
    }
    let mut seen = Vec::new();
    for leaf in leaves {
        let Some(role) = leaf.photon.caustic.filter(|r| r.casts()) else {
            continue;
        };
        let Some(material) = leaf.material else {
            continue;
        };
        let Some(Some(mat)) = materials.get(material) else {
            continue;
        };
        let sends_caustics =
            makes_caustics(&mat.shader) || mat.photon.is_some_and(|p| p.scatters());
        if !material_passes_shadows(mat)
            || !sends_caustics
            || seen.contains(&(leaf.instance, material))
        {
            continue;
        }
        seen.push((leaf.instance, material));
        let it = &m.instances[leaf.instance];
        let (file, path) = if it.desc.caustic.is_some() {
            (it.file, it.at(".caustic"))
        } else {
            let o = &m.objects[leaf.object];
            (o.file, o.at(".caustic"))
        };
        let pos = src.pos(file, &path);
        let syntax = src.syntax(file);
        let flag = match syntax {
            Syntax::Mi => format!(" (caustic {})", role.0),
            // AIR's rule sets the flag: a caustic colour that is not black casts.
            Syntax::Rib => String::new(),
            Syntax::Ron | Syntax::Gltf => format!(" (caustic: {})", role.0),
        };
        let message = format!(
            "\"{}\" casts caustics{flag} but its material \"{}\" lets shadow rays through: \
             the light it transmits is counted twice, by shadow rays and by caustic photons",
            leaf.path, m.materials[material].desc.name
        );
        let mi = if mat.shadow.is_some() {
            "set `caustic 0` or `caustic 2` on it, or leave out the material's `shadow` shader"
        } else {
            "set `caustic 0` or `caustic 2` on it, or make the material opaque"
        };
        let help = syntax.help_each(Helps {
            ron: "set `caustic: 0` or `caustic: 2` on it, or make the material opaque",
            mi,
            rib: "make it opaque (`Opacity 1 1 1`), or make its `Attribute \"caustic\"` colours black so that it casts no caustics",
            gltf: "set `caustic: 0` or `caustic: 2` on it, or make the material opaque",
        });
        src.push_warning(file, Diagnostic::at(pos, message, Some(help)));
    }
}
