//! The sweep driver: loads the scene fresh for every (value, seed), applies the knob, runs
//! the pipeline it is given, and compares each result with the reference.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use glam::Vec3;
use hecs::World;

use crate::budget::Budget;
use crate::frame::{Frame, Tasks};
use crate::hash::Fnv64;
use crate::scene::{load_scene_within, Diagnostic, LoadedScene, SceneErrors};
use crate::schedule::StageError;
use crate::settings::{Integrator, RenderSettings};
use crate::sweep::bake_reference;
use crate::sweep::budget_check::{self, Runs};
use crate::sweep::crop::Crop;
use crate::sweep::integrator_check;
use crate::sweep::knob::{Knob, KnobError};
use crate::sweep::leftovers::SweepFiles;
use crate::sweep::metrics::compare;
use crate::sweep::reference_file;
use crate::sweep::reference_setting::{self, reference_depth, reference_setting, ReferenceDepth};
use crate::sweep::report::{SweepRow, SweepSummary};

/// Runs the stage table over a world (`systems::run`, passed in by the CLI).
pub type Pipeline = fn(&mut World, &mut Frame) -> Result<(), StageError>;

/// What to sweep and how.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// The scene.
    pub scene: PathBuf,
    /// The knob and its values.
    pub knob: Knob,
    /// Seeds per value (bias² and variance need ≥ 2).
    pub seeds: u32,
    /// A reference image/texture (linear EXR); rendered when absent.
    pub reference: Option<PathBuf>,
    /// Samples per pixel (or bake samples) of a rendered reference.
    pub reference_samples: u32,
    /// Output directory (tables, plot, cached reference, scratch files).
    pub out: PathBuf,
    /// Integrator of the swept runs; `None` keeps the scene's.
    pub integrator: Option<Integrator>,
    /// Integrator of a rendered reference (the path tracer: the converged reference).
    pub reference_integrator: Integrator,
    /// Denoise the swept bakes (`--denoise`): every AO and lightmap output without its own
    /// `denoise` gets the default one; the reference is never denoised.
    pub denoise: bool,
    /// A pixel rectangle (e.g. a caustic) whose error is fitted and plotted; the whole
    /// image's is still tabulated.
    pub crop: Option<Crop>,
    /// The memory budget of every run (checked for every setting before the first run).
    pub budget: Budget,
    /// Set by SIGINT or SIGTERM: every run polls it, and the sweep stops between runs.
    pub cancel: Arc<AtomicBool>,
    /// What the sweep writes before its result, removed when it ends without one.
    pub files: Arc<SweepFiles>,
}

/// Why a sweep failed.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// The scene does not load.
    #[error("{0}")]
    Scene(#[from] SceneErrors),
    /// The knob cannot be swept here.
    #[error("error: {0}")]
    Knob(#[from] KnobError),
    /// A setting of the sweep would not fit the memory budget (found before any run).
    #[error("{}", budget_text(scene, refusals))]
    Budget {
        /// The scene file.
        scene: PathBuf,
        /// Every refusal, located.
        refusals: Vec<Diagnostic>,
    },
    /// A run failed.
    #[error("{0}")]
    Stage(#[from] StageError),
    /// `--crop` lies outside the image the runs render (a usage error).
    #[error("error: {0}")]
    Crop(String),
    /// `--reference` is not of the runs' size (a usage error).
    #[error("error: {0}")]
    ReferenceSize(String),
    /// `--reference` holds no RGB image to compare with (a part file, a cut file; a usage
    /// error).
    #[error("error: {0}")]
    Reference(String),
    /// Reading or writing a file failed.
    #[error("error: {path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}

/// The refusals, then `N error(s) in SCENE; nothing swept`.
fn budget_text(scene: &Path, refusals: &[Diagnostic]) -> String {
    let mut text: String = refusals.iter().map(|d| format!("{d}\n")).collect();
    let n = refusals.len();
    text.push_str(&format!(
        "{n} error{} in {}; nothing swept",
        if n == 1 { "" } else { "s" },
        scene.display()
    ));
    text
}

fn io(path: &Path, message: impl std::fmt::Display) -> SweepError {
    SweepError::Io {
        path: path.to_path_buf(),
        message: message.to_string(),
    }
}

/// One run's result: the compared image and the per-stage seconds.
struct RunResult {
    image: Vec<Vec3>,
    width: u32,
    height: u32,
    stage_seconds: Vec<(String, f64)>,
    seconds: f64,
}

fn run_once(
    opts: &SweepOptions,
    pipeline: Pipeline,
    configure: impl Fn(&mut World, &mut RenderSettings),
    seed: u64,
    tag: &str,
) -> Result<RunResult, SweepError> {
    let mut scene = load_scene_within(&opts.scene, &opts.budget)?;
    let mut settings = scene.settings.clone();
    configure(&mut scene.world, &mut settings);
    settings.seed = settings.seed.wrapping_add(seed);
    // Every run traces its own photons: a kept photon map file would hide their cost.
    settings.photon_map = None;
    let mut frame = Frame::new(settings);
    frame.inputs.cancel = opts.cancel.clone();
    // The tessellator refuses adaptive rates that would not fit (known only once diced).
    frame.inputs.budget = opts.budget.clone();
    let scratch = opts.files.scratch().join(tag);
    frame.inputs.bake_dir = scratch.clone();
    crate::bake::files::confine_to_bake_dir(&mut scene.world);
    frame.inputs.tasks = tasks(opts);
    // Nothing is written into the user's directories: the image is compared in memory.
    frame.inputs.outputs.discard = true;
    pipeline(&mut scene.world, &mut frame)?;
    stop_if_cancelled(opts)?;
    let image = if opts.knob.is_bake() {
        let path = frame
            .report
            .written
            .iter()
            .find(|p| p.extension().is_some_and(|e| e == "exr"))
            .cloned()
            .ok_or_else(|| io(&scratch, "the bake wrote no EXR texture to compare (give the first bake output `format: Exr`)"))?;
        let img = read_exr_rgb(&path)?;
        let _ = std::fs::remove_dir_all(&scratch);
        img
    } else {
        let fb = frame.outputs.image.as_ref();
        (
            fb.map(|fb| fb.beauty.clone()).unwrap_or_default(),
            fb.map_or(0, |fb| fb.width),
            fb.map_or(0, |fb| fb.height),
        )
    };
    let (image, width, height) = image;
    Ok(RunResult {
        image,
        width,
        height,
        stage_seconds: frame
            .report
            .stages
            .iter()
            .map(|s| (s.stage.to_string(), s.seconds))
            .collect(),
        seconds: frame.report.total_seconds,
    })
}

/// What every run of the sweep does: render, or bake for a bake knob.
fn tasks(opts: &SweepOptions) -> Tasks {
    Tasks {
        render: !opts.knob.is_bake(),
        bake: opts.knob.is_bake(),
    }
}

/// How the reference run configures the scene: the scene's own knob setting, except the
/// sample count, which it raises, and a knob whose accuracy is a setting (`max_depth`,
/// `tessellation`), which takes its most accurate value ([`reference_setting`]); the trace
/// depth, raised when the swept runs read photon maps ([`reference_depth`]); and the
/// reference's integrator.
fn configure_reference(opts: &SweepOptions) -> impl Fn(&mut World, &mut RenderSettings) + '_ {
    configure_reference_at(opts, true)
}

/// [`configure_reference`], with the most accurate knob setting when `accurate`, else with
/// the scene's own.
fn configure_reference_at(
    opts: &SweepOptions,
    accurate: bool,
) -> impl Fn(&mut World, &mut RenderSettings) + '_ {
    move |world, settings| {
        if let Some(setting) = reference_setting(&opts.knob, settings).filter(|_| accurate) {
            setting.apply(0, world, settings);
        }
        if let Some(depth) = rendered_depth(opts, settings).setting() {
            depth.apply(0, world, settings);
        }
        match opts.knob {
            Knob::BakeSamples(_) => {
                Knob::BakeSamples(vec![opts.reference_samples]).apply(0, world, settings)
            }
            _ => {
                settings.spp = opts.reference_samples;
                settings.adaptive = None;
            }
        }
        settings.integrator = opts.reference_integrator;
    }
}

/// The trace depth of a rendered reference on a scene with `scene` settings (a bake's
/// reference keeps the scene's: no bake reads photon maps).
fn rendered_depth(opts: &SweepOptions, scene: &RenderSettings) -> ReferenceDepth {
    if opts.knob.is_bake() {
        return ReferenceDepth::Scene(scene.max_depth);
    }
    let swept = opts.integrator.unwrap_or(scene.integrator);
    reference_depth(&opts.knob, scene, swept)
}

/// How the run of knob value `i` configures the scene.
fn configure_value(opts: &SweepOptions, i: usize) -> impl Fn(&mut World, &mut RenderSettings) + '_ {
    move |world, settings| {
        if let Some(integrator) = opts.integrator {
            settings.integrator = integrator;
        }
        opts.knob.apply(i, world, settings);
        if opts.denoise {
            denoise_bakes(world);
        }
    }
}

/// Refuses, before the first run, a sweep whose reference (when rendered) or any knob value
/// would not fit the memory budget.
fn check_budget(opts: &SweepOptions, reference_runs: bool) -> Result<(), SweepError> {
    let reference = configure_reference(opts);
    let own = configure_reference_at(opts, false);
    let values: Vec<_> = (0..opts.knob.len())
        .map(|i| configure_value(opts, i))
        .collect();
    let runs = Runs {
        scene: &opts.scene,
        tasks: tasks(opts),
        budget: &opts.budget,
        reference: &reference,
        own: &own,
        reference_runs,
        values: values
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let c: budget_check::Configure<'_> = c;
                (format!("{}={}", opts.knob.name(), opts.knob.label(i)), c)
            })
            .collect(),
    };
    let refusals = budget_check::refusals(&runs)?;
    if refusals.is_empty() {
        return Ok(());
    }
    Err(SweepError::Budget {
        scene: opts.scene.clone(),
        refusals,
    })
}

/// Gives every AO and lightmap output of every bake request the default denoiser, unless it
/// has its own.
fn denoise_bakes(world: &mut World) {
    use crate::components::{BakeKind, BakeRequest, Denoise};
    for request in world.query_mut::<&mut BakeRequest>() {
        for t in &mut request.targets {
            let noisy = matches!(
                t.kind,
                BakeKind::AmbientOcclusion { .. } | BakeKind::Lightmap { .. }
            );
            if noisy && !t.format.is_per_vertex() && t.denoise.is_none() {
                t.denoise = Some(Denoise::default());
            }
        }
    }
}

/// Reads the R, G, B channels of a linear EXR, with its width and height.
pub fn read_exr_rgb(path: &Path) -> Result<(Vec<Vec3>, u32, u32), SweepError> {
    use crate::image_io::exr_limits;
    use exr::prelude::*;
    exr_limits::check_file(path, exr_limits::MAX_IMAGE_SAMPLES).map_err(|e| io(path, e))?;
    // `read_first_rgba_layer_from_file`'s reader, on the calling thread (see
    // `texture::image::decode_exr`).
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |res: Vec2<usize>, _: &RgbaChannels| {
                (
                    res.width(),
                    res.height(),
                    vec![Vec3::ZERO; res.width() * res.height()],
                )
            },
            |(w, _, px): &mut (usize, usize, Vec<Vec3>),
             pos,
             (r, g, b, _a): (f32, f32, f32, f32)| {
                px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b);
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_file(path)
        .map_err(|e| io(path, e))?;
    let (w, h, px) = image.layer_data.channel_data.pixels;
    Ok((px, w as u32, h as u32))
}

/// The cache file of a rendered reference: keyed by the scene's content hash (every file
/// it reads and every loaded mesh, as farm parts are: [`crate::farm::scene_hash`]), the
/// sample count, whether it is a bake, the reference's integrator and its knob setting
/// (`max_depth=16`, when the knob's accuracy is a setting).
fn reference_cache(opts: &SweepOptions, scene: &LoadedScene, setting: Option<&str>) -> PathBuf {
    let content = crate::farm::scene_hash(&opts.scene, scene.source_hash, &scene.world);
    let mut tag = format!(
        "{content:016x}:{}:{}:{:?}",
        opts.reference_samples,
        opts.knob.is_bake(),
        opts.reference_integrator
    );
    if let Some(setting) = setting {
        tag = format!("{tag}:{setting}");
    }
    let h = Fnv64::default().bytes(tag.as_bytes()).finish();
    opts.out.join(format!("reference_{h:016x}.exr"))
}

/// Refuses a `--crop` outside the render camera's image before the reference is rendered.
/// A given `--reference` (read at once) and a bake sweep's texture are checked once read.
fn check_crop_fits_camera(opts: &SweepOptions, world: &World) -> Result<(), SweepError> {
    let (Some(c), None, false) = (opts.crop, &opts.reference, opts.knob.is_bake()) else {
        return Ok(());
    };
    let Some(view) = crate::scene_view::render_view(world) else {
        return Ok(());
    };
    let (w, h) = (view.camera.width, view.camera.height);
    if c.fits(w, h) {
        return Ok(());
    }
    Err(SweepError::Crop(format!(
        "the crop {c} (pixels [X0, X1) × [Y0, Y1)) does not fit the camera's {w}×{h} pixels\n  help: give X1 ≤ {w} and Y1 ≤ {h}"
    )))
}

/// Ends the sweep when SIGINT or SIGTERM has set its cancel flag.
fn stop_if_cancelled(opts: &SweepOptions) -> Result<(), SweepError> {
    if opts.cancel.load(Ordering::SeqCst) {
        return Err(StageError::Interrupted.into());
    }
    Ok(())
}

/// Runs the sweep and returns its summary (the caller writes the files). However it ends, its
/// scratch directory is removed; interrupted, so is an output directory it created that
/// holds nothing else ([`SweepFiles::remove_partial`]). A reference it rendered and cached
/// stays for the next sweep.
pub fn run_sweep(
    opts: &SweepOptions,
    pipeline: Pipeline,
    progress: impl FnMut(&str),
) -> Result<SweepSummary, SweepError> {
    let result = sweep_runs(opts, pipeline, progress);
    // A failed sweep, like an interrupted one, leaves no output directory it created
    // behind, unless a reference it rendered is cached there.
    match &result {
        Ok(_) => opts.files.remove_scratch(),
        Err(_) => opts.files.remove_partial(),
    }
    result
}

fn sweep_runs(
    opts: &SweepOptions,
    pipeline: Pipeline,
    mut progress: impl FnMut(&str),
) -> Result<SweepSummary, SweepError> {
    let (cached, setting, camera_size, bake) = {
        let scene = load_scene_within(&opts.scene, &opts.budget)?;
        opts.knob.check(&scene.world, &scene.settings)?;
        let integrator = opts.integrator.unwrap_or(scene.settings.integrator);
        integrator_check::check(&opts.knob, integrator)?;
        if opts.denoise && !opts.knob.is_bake() {
            return Err(KnobError::DenoiseNeedsBake(opts.knob.name()).into());
        }
        check_crop_fits_camera(opts, &scene.world)?;
        let knob_setting = reference_setting(&opts.knob, &scene.settings);
        let depth = rendered_depth(opts, &scene.settings);
        // The cache key holds the settings the reference changes; the description also
        // says the depth it keeps.
        let key = knob_setting
            .iter()
            .chain(depth.setting().as_ref())
            .map(reference_setting::describe)
            .collect::<Vec<_>>();
        let description = knob_setting
            .iter()
            .map(reference_setting::describe)
            .chain(depth.describe().filter(|_| !opts.knob.is_bake()))
            .collect::<Vec<_>>();
        let key = (!key.is_empty()).then(|| key.join(", "));
        let setting = (!description.is_empty()).then(|| description.join(", "));
        let camera_size = crate::scene_view::render_view(&scene.world)
            .map(|v| (v.camera.width, v.camera.height))
            .filter(|_| !opts.knob.is_bake());
        let bake = opts.knob.is_bake().then(|| {
            bake_reference::describe(
                &scene.world,
                opts.reference_samples,
                opts.reference_integrator,
            )
        });
        (
            reference_cache(opts, &scene, key.as_deref()),
            setting,
            camera_size,
            bake,
        )
    };
    let rendered = bake
        .clone()
        .unwrap_or_else(|| describe_rendered(opts, setting.as_deref()));
    let with_setting = setting.map_or_else(String::new, |s| format!(", {s}"));
    check_budget(opts, opts.reference.is_none() && !cached.exists())?;
    // The output directory is made only once the reference is read (or rendered) and its
    // size checked: a bad `--reference` leaves nothing behind.
    let (reference, ref_width, ref_height) = match &opts.reference {
        Some(path) => {
            let (image, width, height) = read_exr_rgb(path).map_err(|e| match e {
                SweepError::Io { message, .. } => {
                    SweepError::Reference(reference_file::unreadable(path, &message))
                }
                other => other,
            })?;
            if let Some(size) = camera_size.filter(|&s| s != (width, height)) {
                return Err(SweepError::ReferenceSize(reference_file::size_mismatch(
                    path,
                    (width, height),
                    size,
                )));
            }
            (image, width, height)
        }
        None if cached.exists() => {
            progress(&format!(
                "reference: cached {}{with_setting}",
                cached.display()
            ));
            read_exr_rgb(&cached)?
        }
        None => {
            progress(&match &bake {
                Some(bake) => format!("reference: {bake}"),
                None => format!(
                    "reference: {} samples{with_setting}",
                    opts.reference_samples
                ),
            });
            let r = run_once(
                opts,
                pipeline,
                configure_reference(opts),
                0x05ee_d0ef,
                "reference",
            )?;
            let texture = crate::bake::TexelImage {
                width: r.width,
                height: r.height,
                valid: vec![true; r.image.len()],
                texels: r.image.clone(),
            };
            let bytes = texture.encode_exr().map_err(|e| io(&cached, e))?;
            stop_if_cancelled(opts)?;
            // Committed whole (or not at all), it outlives an interruption of the runs that
            // follow: the next sweep of this scene and reference settings reads it. Shared:
            // its name is the hash of what it holds, so sweeps into one directory at once
            // all write it (the last rename stays).
            std::fs::create_dir_all(&opts.out).map_err(|e| io(&opts.out, e))?;
            crate::image_io::commit_all(&[crate::image_io::PendingFile::shared(
                cached.clone(),
                bytes,
            )])
            .map_err(|(p, e)| io(&p, e))?;
            (r.image, r.width, r.height)
        }
    };
    if let Some(c) = opts.crop {
        if !c.fits(ref_width, ref_height) {
            return Err(io(
                opts.reference.as_deref().unwrap_or(&cached),
                format!(
                    "the crop {c} (pixels [X0, X1) × [Y0, Y1)) does not fit the reference's {ref_width}×{ref_height} pixels"
                ),
            ));
        }
    }
    std::fs::create_dir_all(&opts.out).map_err(|e| io(&opts.out, e))?;
    let reference_crop = opts.crop.map(|c| c.cut(&reference, ref_width));
    let mut rows = Vec::with_capacity(opts.knob.len());
    for i in 0..opts.knob.len() {
        let mut images = Vec::new();
        let (mut seconds, mut stage_seconds): (f64, Vec<(String, f64)>) = (0.0, Vec::new());
        for seed in 0..opts.seeds.max(1) {
            stop_if_cancelled(opts)?;
            progress(&format!(
                "{} = {} (seed {seed})",
                opts.knob.name(),
                opts.knob.label(i)
            ));
            let r = run_once(
                opts,
                pipeline,
                configure_value(opts, i),
                seed as u64,
                &format!("{i}_{seed}"),
            )?;
            if (r.width, r.height) != (ref_width, ref_height) {
                return Err(match &opts.reference {
                    Some(path) => SweepError::ReferenceSize(reference_file::size_mismatch(
                        path,
                        (ref_width, ref_height),
                        (r.width, r.height),
                    )),
                    None => io(
                        &cached,
                        format!(
                            "the cached reference is {ref_width}×{ref_height}, the run {}×{}",
                            r.width, r.height
                        ),
                    ),
                });
            }
            seconds += r.seconds;
            if stage_seconds.is_empty() {
                stage_seconds = r.stage_seconds.clone();
            } else {
                for (acc, (_, s)) in stage_seconds.iter_mut().zip(&r.stage_seconds) {
                    acc.1 += s;
                }
            }
            images.push(r.image);
        }
        let k = opts.seeds.max(1) as f64;
        for s in &mut stage_seconds {
            s.1 /= k;
        }
        rows.push(SweepRow {
            value: opts.knob.label(i),
            stage_seconds,
            seconds: seconds / k,
            error: compare(&images, &reference),
            crop_error: opts.crop.zip(reference_crop.as_ref()).map(|(c, r)| {
                let cut: Vec<Vec<Vec3>> = images.iter().map(|i| c.cut(i, ref_width)).collect();
                compare(&cut, r)
            }),
            seeds: opts.seeds.max(1),
        });
    }
    let knob = if opts.denoise {
        format!("{}+denoise", opts.knob.name())
    } else {
        opts.knob.name().to_string()
    };
    let reference = match &opts.reference {
        Some(path) => format!("{} (--reference)", path.display()),
        None => rendered,
    };
    Ok(SweepSummary::new(
        &knob,
        &opts.scene.display().to_string(),
        opts.crop,
        rows,
        opts.knob.cost_order().as_deref(),
    )
    .with_reference(reference))
}

/// What a rendered reference is, for the progress line and the summary: `path tracer, 1024
/// samples`, with the knob's setting when the reference sets it (`, max_depth=16`).
fn describe_rendered(opts: &SweepOptions, setting: Option<&str>) -> String {
    let integrator = match opts.reference_integrator {
        Integrator::Path => "path tracer",
        Integrator::Direct => "direct lighting",
    };
    let mut text = format!("{integrator}, {} samples", opts.reference_samples);
    if let Some(setting) = setting {
        text.push_str(&format!(", {setting}"));
    }
    text
}
