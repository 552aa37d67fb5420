//! Up-front peak-memory estimates of a run, per scene element, before any stage allocates
//! (issue 18, family 2). `check`, `render` and `bake` run the same estimates.
//!
//! | element | estimate |
//! | --- | --- |
//! | render camera | pixels × [`BYTES_PER_PIXEL`] (frame buffers, per-pixel sample state of both adaptive passes, encoded outputs) |
//! | object | placed triangles × [`BYTES_PER_TRIANGLE`] (world copy, BVH build and nodes, shading data): loaded meshes by their triangles, grids by `2·nx·ny`, surfaces with a `Parametric`/`Regular` approximation by their rates before dicing (located at the `approximation`), scatters by copies × prototype triangles (+ [`BYTES_PER_INSTANCE`] per copy) |
//! | photon map | emitted photons × [`BYTES_PER_PHOTON`] |
//! | bake request | texels × (targets + 1) × [`BYTES_PER_TEXEL`]; a density-sized texture at the size the bake gives it from the placed mesh's area and UVs (`crate::bake::density`), or at `max_size` where those are known only later (generated UVs, diced or displaced surfaces) |
//! | image texture | its decoded texels and alpha (12 and 4 bytes each), located at its `file` ([`DecodedImage`], spawned by the loader, which also refuses a texture whose reading alone would not fit) |
//! | environment map | its radiance texels (12 bytes each); the scene environment's also its importance-sampling tables (8 bytes per texel and 60 per row) and the weights they are built from (4 bytes per texel), located at its `file` (`shading::lights::environment::footprint`; the loader refuses a map whose reading alone would not fit) |
//! | displacement image | its heights (4 bytes each), located at its `file` (the loader refuses an image whose reading alone would not fit) |
//!
//! Adaptive approximations (spatial, curvature) and subdivision meshes are not estimated at
//! load: their rates depend on the diced surface. The tessellator checks the triangle count
//! its rates give before it dices ([`max_triangles`]), so those fail at `tessellate`, located
//! at the approximation, instead of allocating; `check` warns about an adaptive surface
//! whose worst case exceeds that limit ([`super::worst_case`]). The constants come from peak resident memory measured
//! on a 2 M-triangle and a 4 M-pixel scene (README, *Reliability*).

use std::collections::HashMap;

use hecs::{Entity, World};

use super::{human, Budget};
use crate::components::{
    Approximation, ApproximationLink, BakeRequest, BakeResolution, Camera, DecodedImage,
    Displacement, DisplacementMode, Instance, Name, Procedural, RenderCamera, ResolutionLink,
    Scatter, SecondUvs, SourceLink, SubdivMesh, Surface, Technique, TriMesh, UvSource,
    WorldFromObject,
};
use crate::scene::Diagnostic;
use crate::settings::RenderSettings;
use crate::tasks::Tasks;
use crate::tessellation::rates::MAX_FIXED_RATE;
use crate::tessellation::PatchSource;

/// Peak bytes per pixel of the render camera (measured: 806 MB peak for a 2000×2000 EXR
/// render of two triangles, ≈ 200 B per pixel; rounded up for adaptive sampling's second
/// pass).
pub const BYTES_PER_PIXEL: u64 = 256;
/// Peak bytes per placed triangle (measured: 701 MB peak for a 1000×1000 grid, 2 M
/// triangles, ≈ 350 B per triangle).
pub const BYTES_PER_TRIANGLE: u64 = 384;
/// Bytes per scattered copy besides its triangles (entity, instance geometry).
pub const BYTES_PER_INSTANCE: u64 = 512;
/// Peak bytes per emitted photon (stored photons of every bounce, kd-tree).
pub const BYTES_PER_PHOTON: u64 = 256;
/// Peak bytes per texel and baked texture.
pub const BYTES_PER_TEXEL: u64 = 128;

/// The estimated peak of one element.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The element, as messages name it: `camera "cam"`, `object "floor"`.
    pub element: String,
    /// Where it is declared.
    pub at: Option<SourceLink>,
    /// What needs the memory: `frame buffers of 100000×100000 pixels`.
    pub what: String,
    /// Estimated peak bytes.
    pub bytes: u64,
    /// What to change.
    pub help: &'static str,
}

impl Estimate {
    /// The refusal of this estimate under `budget`, located at the element.
    pub fn refusal(&self, budget: &Budget) -> Diagnostic {
        let (file, line, column) = self.at.as_ref().map_or((Default::default(), 1, 1), |l| {
            (l.file.clone(), l.line, l.column)
        });
        Diagnostic {
            file,
            line,
            column,
            message: format!(
                "{}: {} need about {}, more than the memory budget of {budget}",
                self.element,
                self.what,
                human(self.bytes)
            ),
            help: Some(format!(
                "{}, or raise the budget with --memory-limit BYTES",
                self.help
            )),
        }
    }
}

/// The largest triangle count one tessellated object may reach under `budget`.
pub fn max_triangles(budget: &Budget) -> u64 {
    budget.bytes / BYTES_PER_TRIANGLE
}

fn named(world: &World, e: Entity) -> (String, Option<SourceLink>) {
    let name = world
        .get::<&Name>(e)
        .map_or_else(|_| "?".to_string(), |n| n.0.clone());
    (name, world.get::<&SourceLink>(e).ok().map(|l| (*l).clone()))
}

/// Where an object's triangle count is decided by its approximation: the written
/// `approximation` value ([`ApproximationLink`]), else the object.
pub fn approximation_at(world: &World, object: Entity) -> Option<SourceLink> {
    match world.get::<&ApproximationLink>(object) {
        Ok(l) => Some(l.0.clone()),
        Err(_) => world.get::<&SourceLink>(object).ok().map(|l| (*l).clone()),
    }
}

/// The approximation an object is diced with (its own, else the default).
pub fn approximation_of(world: &World, object: Entity) -> Approximation {
    world
        .get::<&Approximation>(object)
        .map_or_else(|_| Approximation::default(), |a| *a)
}

/// Patches of an object's parametric surface (patch meshes, NURBS, quadrics, and the
/// generators that expand to a quadric), before any stage runs.
pub fn surface_patches(world: &World, object: Entity) -> Option<u64> {
    if let Ok(s) = world.get::<&Surface>(object) {
        let patches = match &*s {
            Surface::Patches(m) => crate::tessellation::patch::PatchMeshSource::new(m)
                .ok()
                .map(|p| p.patch_count()),
            Surface::Nurbs(n) => crate::tessellation::nurbs::NurbsSource::new(n)
                .ok()
                .map(|p| p.patch_count()),
            Surface::Quadric(q) => crate::tessellation::quadric::QuadricSource::new(q)
                .ok()
                .map(|p| p.patch_count()),
        }?;
        return Some(patches as u64);
    }
    let p = world.get::<&Procedural>(object).ok()?;
    let Ok(crate::procedural::Expanded::Surface(Surface::Quadric(q))) =
        crate::procedural::expand(&p)
    else {
        return None;
    };
    let patches = crate::tessellation::quadric::QuadricSource::new(&q)
        .ok()?
        .patch_count();
    Some(patches as u64)
}

/// Triangles an object's own geometry becomes, when that is known before the stages run,
/// and whether its approximation decides them.
fn object_triangles(world: &World, object: Entity) -> Option<(u64, String, bool)> {
    if let Ok(mesh) = world.get::<&std::sync::Arc<TriMesh>>(object) {
        return Some((mesh.triangles.len() as u64, "triangles".into(), false));
    }
    if let Ok(p) = world.get::<&Procedural>(object) {
        if let Procedural::Grid(g) = *p {
            let t = 2 * u64::from(g.nx) * u64::from(g.ny);
            return Some((t, format!("triangles of a {}×{} grid", g.nx, g.ny), false));
        }
    }
    let approx = approximation_of(world, object);
    let per_patch = |patches: u64| -> Option<(u64, String, bool)> {
        let clamp = |r: u32| u64::from(r.clamp(1, MAX_FIXED_RATE));
        match approx.technique {
            Technique::Parametric { u, v } => {
                let (u, v) = (clamp(u), clamp(v));
                Some((
                    2 * patches * u * v,
                    format!("triangles of {patches} patch(es) diced {u}×{v}"),
                    true,
                ))
            }
            Technique::Regular { u, v } => {
                let (u, v) = (clamp(u), clamp(v));
                Some((
                    2 * u * v,
                    format!("triangles of a surface diced {u}×{v}"),
                    true,
                ))
            }
            _ => None,
        }
    };
    if let Some(patches) = surface_patches(world, object) {
        return per_patch(patches);
    }
    if let Ok(m) = world.get::<&SubdivMesh>(object) {
        // Every face becomes at least one patch per corner after the first refinement.
        return per_patch(m.face_sizes.iter().map(|&s| u64::from(s)).sum());
    }
    None
}

/// Every element's estimate for a run doing `tasks` with `settings`, in a fixed order
/// (camera, objects in entity order, photon maps, bake requests, then the decoded images:
/// image textures in the order read, environment maps and displacement images).
pub fn estimates(world: &World, settings: &RenderSettings, tasks: Tasks) -> Vec<Estimate> {
    let mut out = Vec::new();
    if tasks.render {
        for (e, c, _) in world.query::<(Entity, &Camera, &RenderCamera)>().iter() {
            let (name, at) = named(world, e);
            // Located at the resolution's width, the value to change.
            let at = world
                .get::<&ResolutionLink>(e)
                .map_or(at, |l| Some(l.0.clone()));
            let pixels = u64::from(c.width) * u64::from(c.height);
            out.push(Estimate {
                element: format!("camera \"{name}\""),
                at,
                what: format!("the frame buffers of {}×{} pixels", c.width, c.height),
                bytes: pixels.saturating_mul(BYTES_PER_PIXEL),
                help: "lower the camera's resolution",
            });
        }
    }
    // Placed triangles per object: instances × the object's triangles.
    let mut instances: HashMap<Entity, u64> = HashMap::new();
    for inst in world.query::<&Instance>().iter() {
        *instances.entry(inst.object).or_default() += 1;
    }
    let mut objects: Vec<Entity> = instances.keys().copied().collect();
    objects.sort_by_key(|e| e.to_bits());
    for object in objects {
        let copies = instances[&object];
        let (name, at) = named(world, object);
        let scatter = world.get::<&Scatter>(object).ok().map(|s| *s);
        let (bytes, what, at) = if let Some(s) = scatter {
            let proto = object_triangles(world, s.prototype).map_or(0, |(t, ..)| t);
            let n = copies.saturating_mul(u64::from(s.count));
            (
                n.saturating_mul(proto.saturating_mul(BYTES_PER_TRIANGLE) + BYTES_PER_INSTANCE),
                format!("{n} scattered copies of {proto} triangles"),
                at,
            )
        } else {
            match object_triangles(world, object) {
                Some((t, what, by_approximation)) => (
                    t.saturating_mul(copies).saturating_mul(BYTES_PER_TRIANGLE),
                    if copies > 1 {
                        format!("{copies} placed copies of {t} {what}")
                    } else {
                        format!("{t} {what}")
                    },
                    if by_approximation {
                        approximation_at(world, object)
                    } else {
                        at
                    },
                ),
                None => continue,
            }
        };
        out.push(Estimate {
            element: format!("object \"{name}\""),
            at,
            what,
            bytes,
            help: "use fewer or coarser triangles",
        });
    }
    let maps = [
        ("caustics", settings.photons.caustics),
        ("global_illumination", settings.photons.global_illumination),
    ];
    for (key, map) in maps {
        if let Some(m) = map {
            // A progressive map keeps every pass.
            let (passes, what) = match m.progressive {
                Some(p) => (p.passes, format!("{} × {} passes", m.photons, p.passes)),
                None => (1, m.photons.to_string()),
            };
            out.push(Estimate {
                element: format!("options.{key}"),
                at: None,
                what: format!("the {what} photons of the photon map"),
                bytes: (u64::from(m.photons) * u64::from(passes)).saturating_mul(BYTES_PER_PHOTON),
                help: "emit fewer photons",
            });
        }
    }
    // Lights with their own photon counts emit them on top of the maps' `photons`.
    let mut lights: Vec<(Entity, crate::components::LightPhotons)> = world
        .query::<(Entity, &crate::components::LightPhotons)>()
        .iter()
        .map(|(e, c)| (e, *c))
        .collect();
    lights.sort_by_key(|(e, _)| e.to_bits());
    for (e, c) in lights {
        let on = |map: &Option<crate::settings::PhotonMapSettings>, n: Option<u32>| match map {
            Some(m) => u64::from(n.unwrap_or(0)) * u64::from(m.progressive.map_or(1, |p| p.passes)),
            None => 0,
        };
        let n = on(&settings.photons.caustics, c.caustic_photons)
            + on(&settings.photons.global_illumination, c.globillum_photons);
        if n > 0 {
            let (name, at) = named(world, e);
            out.push(Estimate {
                element: format!("light \"{name}\""),
                at,
                what: format!("the {n} photons it emits"),
                bytes: n.saturating_mul(BYTES_PER_PHOTON),
                help: "emit fewer photons",
            });
        }
    }
    if tasks.bake {
        let mut requests: Vec<_> = world
            .query::<(Entity, &BakeRequest)>()
            .iter()
            .map(|(e, r)| (e, r.clone()))
            .collect();
        requests.sort_by_key(|(e, _)| e.to_bits());
        for (e, r) in requests {
            let (_, at) = named(world, e);
            let (w, h) = bake_size(world, e, &r);
            let texels = u64::from(w) * u64::from(h);
            let textures = r.targets.len() as u64 + 1;
            out.push(Estimate {
                element: format!("bake request on instance \"{}\"", r.name),
                at,
                what: format!("{textures} texture(s) of {w}×{h} texels"),
                bytes: texels
                    .saturating_mul(textures)
                    .saturating_mul(BYTES_PER_TEXEL),
                help: "lower the bake resolution",
            });
        }
    }
    // Images decoded at load (textures, environment maps, displacement images): their texels
    // stay for the whole run.
    let mut images: Vec<(Entity, DecodedImage)> = world
        .query::<(Entity, &DecodedImage)>()
        .iter()
        .map(|(e, d)| (e, *d))
        .collect();
    images.sort_by_key(|(e, _)| e.to_bits());
    for (e, image) in images {
        let (name, at) = named(world, e);
        out.push(Estimate {
            element: format!("image \"{name}\""),
            at,
            what: image.describe(),
            bytes: image.bytes,
            help: "use a smaller image (or fewer)",
        });
    }
    out
}

/// The texture size of bake request `r` on instance `e`: a fixed resolution as written; a
/// density-sized one as the bake will size it (`crate::bake::density`) when its mesh and UVs
/// are known before any stage runs (a loaded mesh, not truly displaced, baked on its own or
/// its second UV set), else `max_size` (generated UVs, surfaces diced later).
fn bake_size(world: &World, e: Entity, r: &BakeRequest) -> (u32, u32) {
    let max_size = match r.resolution {
        BakeResolution::Fixed { width, height } => return (width, height),
        BakeResolution::Density { max_size, .. } => (max_size, max_size),
    };
    let (Ok(instance), Ok(placement)) =
        (world.get::<&Instance>(e), world.get::<&WorldFromObject>(e))
    else {
        return max_size;
    };
    let mesh = &instance.mesh;
    let displaced = world
        .get::<&Displacement>(instance.object)
        .is_ok_and(|d| d.mode == DisplacementMode::True);
    if mesh.triangles.is_empty() || displaced {
        return max_size;
    }
    let uvs = match (r.uvs, &mesh.uvs) {
        (UvSource::Mesh | UvSource::MeshOrUnwrap, Some(_)) => {
            crate::bake::corner_uvs(mesh, r.uvs, 1, 0).ok()
        }
        (UvSource::SecondSet, _) => world
            .get::<&SecondUvs>(instance.object)
            .ok()
            .and_then(|s| crate::bake::second_set_corner_uvs(mesh, &s.0).ok()),
        _ => None,
    };
    uvs.and_then(|uvs| {
        crate::bake::density::mesh_uv_resolution(r.resolution, mesh, &placement.0, &uvs).ok()
    })
    .unwrap_or(max_size)
}

/// The refusals of a run under `budget`: every element whose estimate alone exceeds it, or,
/// when each fits but all together do not, the largest one with the total.
pub fn check(
    world: &World,
    settings: &RenderSettings,
    tasks: Tasks,
    budget: &Budget,
) -> Vec<Diagnostic> {
    let all = estimates(world, settings, tasks);
    let over: Vec<Diagnostic> = all
        .iter()
        .filter(|e| !budget.fits(e.bytes))
        .map(|e| e.refusal(budget))
        .collect();
    if !over.is_empty() {
        return over;
    }
    let total = all.iter().fold(0u64, |t, e| t.saturating_add(e.bytes));
    if budget.fits(total) {
        return Vec::new();
    }
    let Some(largest) = all.iter().max_by_key(|e| e.bytes) else {
        return Vec::new();
    };
    let mut d = largest.refusal(budget);
    d.message = format!(
        "{}: {} need about {}, and the whole run about {}, more than the memory budget of {budget}",
        largest.element,
        largest.what,
        human(largest.bytes),
        human(total)
    );
    vec![d]
}
