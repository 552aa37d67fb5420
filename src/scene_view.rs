//! The scene's shared elements read out of the world the same way by every stage: the
//! render camera with its lens shaders, atmosphere and imager; the emitters in entity order
//! (the order every light index, and so every output byte, depends on); the environment;
//! and the light set built from them. Stages call these instead of writing their own
//! queries.

use hecs::{Entity, World};

use crate::components::{
    Atmosphere, AtmosphereFade, Camera, Emitter, Environment, Fade, Fog, Imager, Lens, Lenses,
    RenderCamera,
};
use crate::farm::part::Share;
use crate::features::{Feature, Features};
use crate::geometry::SceneGeometry;
use crate::settings::RenderSettings;
use crate::shading::LightSet;

/// The render camera and what is attached to it.
#[derive(Debug, Clone)]
pub struct RenderView {
    /// The camera (placement, projection, resolution, outputs).
    pub camera: Camera,
    /// Its lens shaders, in order (empty: a pinhole).
    pub lenses: Vec<Lens>,
    /// The fog the camera sits in, if any.
    pub atmosphere: Option<Fog>,
    /// Its fade atmosphere (`mib_volume`), if any.
    pub fade: Option<Fade>,
    /// Its imager (PNG outputs), if any.
    pub imager: Option<Imager>,
}

impl RenderView {
    /// The view with the switched-off features left out: no lens shaders when
    /// [`Feature::Lens`] is off (a pinhole), no atmosphere when [`Feature::Volume`] is.
    pub fn without(mut self, off: Features) -> Self {
        if off.contains(Feature::Lens) {
            self.lenses.clear();
        }
        if off.contains(Feature::Volume) {
            self.atmosphere = None;
            self.fade = None;
        }
        self
    }
}

/// The render camera, if the scene names one.
pub fn render_view(world: &World) -> Option<RenderView> {
    world
        .query::<(
            &Camera,
            &RenderCamera,
            Option<&Lenses>,
            Option<&Atmosphere>,
            Option<&AtmosphereFade>,
            Option<&Imager>,
        )>()
        .iter()
        .next()
        .map(|(c, _, l, a, f, i)| RenderView {
            camera: c.clone(),
            lenses: l.map(|l| l.0.clone()).unwrap_or_default(),
            atmosphere: a.map(|a| a.0),
            fade: f.map(|f| f.0),
            imager: i.copied(),
        })
}

/// The outputs a run writes for the render camera of `world` (none without one): its
/// listed outputs with the command line's `overrides` applied.
pub fn render_outputs(
    world: &World,
    overrides: &crate::frame::OutputOverrides,
) -> Result<Vec<crate::components::OutputSpec>, String> {
    let listed = render_view(world)
        .map(|v| v.camera.outputs)
        .unwrap_or_default();
    overrides.apply(&listed)
}

/// Whether anyone reads the render camera's image in this run: the caller keeps it
/// ([`crate::frame::RunInputs::caller_keeps_image`]), a farm part file stores it, or the
/// camera (after `-o`) has an output to write.
pub fn image_is_read(world: &World, inputs: &crate::frame::RunInputs) -> bool {
    inputs.caller_keeps_image
        || inputs.part.is_some()
        || written_outputs(world, inputs).map_or(true, |outputs| !outputs.is_empty())
}

/// The render outputs (after `-o`) this run writes: all of them but the
/// [`unwritten_outputs`].
pub fn written_outputs(
    world: &World,
    inputs: &crate::frame::RunInputs,
) -> Result<Vec<crate::components::OutputSpec>, String> {
    let mut outputs = render_outputs(world, &inputs.outputs)?;
    if let Some(unwritten) = unwritten_outputs(world, inputs) {
        outputs.retain(|o| !unwritten.paths.contains(&o.path));
    }
    Ok(outputs)
}

/// Render outputs that a run does not write, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unwritten {
    /// Their paths, in the camera's output order.
    pub paths: Vec<std::path::PathBuf>,
    /// Why no contour lines are drawn ([`contours_drawn`]'s reason).
    pub why: String,
}

impl Unwritten {
    /// The words of the run report and of the warning:
    /// `"lines.eps" not written, no contours are drawn: output shaders disabled (…)`.
    pub fn reason(&self) -> String {
        let names: Vec<String> = self
            .paths
            .iter()
            .map(|p| format!("\"{}\"", p.display()))
            .collect();
        format!(
            "{} not written, no contours are drawn: {}",
            names.join(", "),
            self.why
        )
    }
}

/// The outputs that hold only contour lines (SVG, EPS) in a run that draws none
/// ([`contours_drawn`] says no: output shaders disabled, every contrast criterion off):
/// they are not written, rather than written empty. `None` when there are none, and for a
/// farm part (it writes its part file; the merge writes the outputs).
pub fn unwritten_outputs(world: &World, inputs: &crate::frame::RunInputs) -> Option<Unwritten> {
    use crate::components::ImageFormat;
    if inputs.part.is_some() {
        return None;
    }
    let why = contours_drawn(world, inputs).err()?;
    let paths: Vec<std::path::PathBuf> = render_outputs(world, &inputs.outputs)
        .ok()?
        .into_iter()
        .filter(|o| matches!(o.format, ImageFormat::Svg | ImageFormat::Eps))
        .map(|o| o.path)
        .collect();
    (!paths.is_empty()).then_some(Unwritten { paths, why })
}

/// Whether an output of this run (after `-o`) writes straight alpha
/// ([`crate::components::OutputSpec::writes_straight_alpha`]): the outputs that need the
/// environment's share of partly covered pixels to take it out of their colour.
pub fn straight_alpha_written(world: &World, inputs: &crate::frame::RunInputs) -> bool {
    render_outputs(world, &inputs.outputs)
        .is_ok_and(|outputs| outputs.iter().any(|o| o.writes_straight_alpha()))
}

/// Whether this run draws contour lines on the render camera's image (an image being
/// shaded aside): `Ok` with the number of materials with a contour shader when one exists,
/// output shaders are on, the run is not a farm part, some contrast criterion is on and an
/// output shows contours (an SVG or EPS, or a `Contours` pass, after `-o`); else `Err` with
/// the reason. `draw_contours`
/// runs by it, `shade` keeps the contour store by it, and a merge rebuilds the geometry
/// (for the bisection rays) only for it.
pub fn contours_drawn(world: &World, inputs: &crate::frame::RunInputs) -> Result<usize, String> {
    use crate::components::{ContourShader, ImageFormat, Pass};
    let n = crate::schedule::count_with::<ContourShader>(world);
    if n == 0 {
        return Err("no material in use has a contour shader".into());
    }
    if inputs.settings.disabled.contains(Feature::Output) {
        return Err(format!(
            "output shaders disabled ({n} material(s) with a contour shader)"
        ));
    }
    if let Some(run) = &inputs.part {
        return Err(format!(
            "{}: contours are drawn when the parts are merged",
            run.part
        ));
    }
    let contrast = world
        .query::<&crate::components::ContourContrast>()
        .iter()
        .next()
        .copied()
        .unwrap_or_default();
    if !contrast.any_on() {
        return Err(format!(
            "every contour contrast criterion is off ({n} material(s) with a contour shader)"
        ));
    }
    let shown = render_outputs(world, &inputs.outputs)
        .unwrap_or_default()
        .iter()
        .any(|o| {
            matches!(o.format, ImageFormat::Svg | ImageFormat::Eps)
                || o.passes.contains(&Pass::Contours)
        });
    if !shown {
        return Err(format!(
            "no output shows contours ({n} material(s) with a contour shader)"
        ));
    }
    Ok(n)
}

/// Why nothing in this run traces rays into the scene geometry (`None`: something does — a
/// render camera whose image is read, or a bake). A render part that computes nothing
/// ([`part_share`]) reads no geometry either, nor does a bake part that owns no texel where
/// the scene alone tells ([`idle_bake_part`]): the reason is then the part's. The geometry
/// stages skip by it: without a reader, shapes expanded, surfaces diced and a hierarchy
/// built are thrown away.
pub fn geometry_unused(world: &World, inputs: &crate::frame::RunInputs) -> Option<String> {
    let tasks = inputs.tasks;
    let idle = match part_share(world, inputs) {
        Some(Share::Nothing(why)) => Some(why),
        _ => None,
    };
    let renders =
        tasks.render && has_render_camera(world) && image_is_read(world, inputs) && idle.is_none();
    let idle_bake = idle_bake_part(world, inputs);
    let bakes = tasks.bake
        && crate::schedule::any_with::<crate::components::BakeRequest>(world)
        && idle_bake.is_none();
    let idle = idle.or(idle_bake);
    match (renders || bakes, tasks.render, idle) {
        (true, ..) => None,
        (false, _, Some(why)) => Some(why),
        (false, true, None) => Some("no render camera traces rays".into()),
        (false, false, None) => Some("nothing in this run traces rays".into()),
    }
}

/// What a render part (`render --part K/N`) computes of the render camera's image
/// ([`crate::farm::Part::share`]); `None` when the run renders no part or there is no
/// render camera. A part with no pixels or samples to compute skips `shade` and the stages
/// that feed only it, and writes an empty part file.
pub fn part_share(world: &World, inputs: &crate::frame::RunInputs) -> Option<Share> {
    let run = inputs.part.as_ref()?;
    if !inputs.tasks.render || inputs.merging() {
        return None;
    }
    let camera = render_view(world)?.camera;
    let spp = crate::adaptive::SampleBudget::new(&inputs.settings).min;
    Some(run.part.share(camera.width, camera.height, spp))
}

/// Why this run's bake part (`bake --part K/N`) owns no texel, when the scene alone tells:
/// every request has a fixed size and only texture targets
/// ([`crate::farm::idle_bake_part`]). Such a part needs no geometry: the geometry stages
/// skip for this reason and `bake_lightmaps` writes only its empty part file. `None` in any
/// other run, and where the requests' sizes come from the geometry.
pub fn idle_bake_part(world: &World, inputs: &crate::frame::RunInputs) -> Option<String> {
    let run = inputs.part.as_ref()?;
    let tasks = inputs.tasks;
    if tasks.render || !tasks.bake || inputs.merging() || inputs.merged_bake.is_some() {
        return None;
    }
    crate::farm::idle_bake_part::idle_before_geometry(world, run.part)
}

/// [`geometry_unused`] for the stages that make geometry (`expand_geometry`, `tessellate`):
/// only where a render camera exists or a bake part owns no texel, so that a library caller
/// running them on a world without a camera still gets the meshes it asked for.
pub fn geometry_discarded(world: &World, inputs: &crate::frame::RunInputs) -> Option<String> {
    if has_render_camera(world) || idle_bake_part(world, inputs).is_some() {
        geometry_unused(world, inputs)
    } else {
        None
    }
}

/// Whether the scene has a render camera (cheap; for run conditions).
pub fn has_render_camera(world: &World) -> bool {
    crate::schedule::any_with::<RenderCamera>(world)
}

/// Every emitter, in entity order.
pub fn emitters(world: &World) -> Vec<Emitter> {
    let mut emitters: Vec<(Entity, Emitter)> = world
        .query::<(Entity, &Emitter)>()
        .iter()
        .map(|(e, l)| (e, l.clone()))
        .collect();
    emitters.sort_by_key(|(e, _)| e.to_bits());
    emitters.into_iter().map(|(_, l)| l).collect()
}

/// World-space position of render space's zero ([`crate::components::SceneOrigin`]; the
/// world origin without one).
pub fn scene_origin(world: &World) -> glam::DVec3 {
    world
        .query::<&crate::components::SceneOrigin>()
        .iter()
        .next()
        .map_or(glam::DVec3::ZERO, |o| o.0)
}

/// The scene's environment, if any.
pub fn environment(world: &World) -> Option<Environment> {
    world.query::<&Environment>().iter().next().cloned()
}

/// Whether the light set includes the environment as a light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WithEnvironment {
    /// Shading and baking: rays that leave the scene see the environment, which is sampled.
    Yes,
    /// The photon pass: the environment sends no photons.
    No,
}

/// The light set every stage shades with: the emitters in entity order, the emitting
/// triangles of `geometry`, and (optionally) the environment.
pub fn light_set(
    world: &World,
    geometry: Option<&SceneGeometry>,
    settings: &RenderSettings,
    environment: WithEnvironment,
) -> LightSet {
    let lights = LightSet::new(&emitters(world), geometry, settings.light_samples);
    match environment {
        WithEnvironment::Yes => lights.with_environment(self::environment(world).as_ref()),
        WithEnvironment::No => lights,
    }
}
