//! The `stagelight` command line: a thin front end over the scene loader and the stage table.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use clap::{Args, Parser, Subcommand};
use stagelight::bake::gltf_copy_refusals;
use stagelight::components::BakeRequest;
use stagelight::farm::{PartNumber, PartRun, Split};
use stagelight::frame::{Frame, OutputOverrides, RunInputs, Tasks};
use stagelight::guard::limits::MAX_THREADS;
use stagelight::guard::outputs::same_file_key;
use stagelight::scene::LoadedScene;
use stagelight::systems;

/// Exit code for scene and runtime errors.
const EXIT_ERROR: u8 = 1;
/// Exit code for command-line usage errors.
const EXIT_USAGE: u8 = 2;

#[derive(Parser)]
#[command(
    name = "stagelight",
    version,
    about = "Offline renderer and texture baker in the lineage of mental ray"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene's camera outputs.
    Render(RenderArgs),
    /// Bake every bake request of a scene into textures.
    Bake(BakeArgs),
    /// Run a scene's whole pipeline (render, and bake when it has bake requests) and report
    /// each stage's throughput; outputs go to a temporary directory and are deleted.
    Bench(BenchArgs),
    /// Measure what accuracy costs in time: render once per knob value (and seed), compare
    /// with a converged reference, write a CSV/JSON table and an SVG plot.
    Sweep(SweepArgs),
    /// Print the stages in order with run/skip and the reason each would get for this scene,
    /// without running any.
    Plan(PlanArgs),
    /// Write a scene in any readable format (RIB, .mi, glTF, RON) as the equivalent RON scene.
    Convert {
        /// Scene file (.ron, .rib, .mi, .gltf or .glb).
        scene: PathBuf,
        /// The RON file to write.
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
    },
    /// Merge the part files of `render --part K/N` into the outputs a single-machine render
    /// writes, bit-identical.
    Merge(MergeArgs),
    /// Write Slurm batch scripts that render a scene as a job array of parts and merge them.
    Farm(FarmArgs),
    /// Trace a scene's photon maps once and keep them (in `--photon-cache DIR` or the
    /// scene's `photon_map` file) for later renders, sweeps and farm parts to load.
    Photons(PhotonsArgs),
    /// Validate a scene without rendering; exit 0 when nothing known before the first stage
    /// stops a render (adaptive tessellation past the budget is a warning: it is known only
    /// once diced).
    Check {
        /// Scene file (.ron, .rib, .mi, .gltf or .glb).
        scene: PathBuf,
        /// Memory budget the estimates are checked against (as for `render`).
        #[arg(long = "memory-limit", value_name = "BYTES", value_parser = stagelight::budget::parse_bytes)]
        memory_limit: Option<u64>,
    },
}

#[derive(Args)]
struct RenderArgs {
    /// Scene file (.ron, .rib, .mi, .gltf or .glb).
    scene: PathBuf,
    /// Render this camera (by name; a glTF file's cameras are named after the file's)
    /// instead of the scene's render camera.
    #[arg(long, value_name = "NAME")]
    camera: Option<String>,
    /// Write the image here instead of the camera's first image output (.png or .exr), or the
    /// contour lines instead of its first vector output (.svg or .eps); added if it has none.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Samples per pixel (overrides the scene's `options.samples`, adaptive included).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    spp: Option<u32>,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    threads: Option<u32>,
    /// Random seed (overrides the scene's `options.seed`).
    #[arg(long)]
    seed: Option<u64>,
    #[command(flatten)]
    stages: StageFlags,
    /// Replace the beauty pass by a diagnostic view: `samples` (samples per pixel),
    /// `grid:object|world|camera:SIZE` (grid lines), `photon:density|irradiance:MAX`,
    /// `bvh:depth|size[:MAX]` (what each pixel's ray cost the BVH).
    #[arg(long, value_name = "MODE", value_parser = stagelight::diagnostic::Diagnostic::parse)]
    diagnostic: Option<stagelight::diagnostic::Diagnostic>,
    /// Print the per-stage report.
    #[arg(long)]
    stats: bool,
    /// Write the per-stage report as JSON.
    #[arg(long = "stats-json", value_name = "FILE")]
    stats_json: Option<PathBuf>,
    /// Also bake the scene's bake requests (into the working directory).
    #[arg(long)]
    bake: bool,
    /// Render only part K of N (1-based) and write it as a part file to `-o PART.exr`, for
    /// `stagelight merge`.
    #[arg(long, value_name = "K/N", conflicts_with = "bake")]
    part: Option<PartNumber>,
    /// How `--part` divides the render: `tiles` (interleaved 16×16 pixel tiles) or
    /// `samples` (a range of every pixel's sample indices).
    #[arg(long, value_enum, default_value = "tiles", requires = "part")]
    split: SplitArg,
    /// Memory budget in bytes (binary suffixes K, M, G, T; KB… and KiB… mean the same); default: the smallest of half
    /// the physical memory, `ulimit -v` and the cgroup limit.
    #[arg(long = "memory-limit", value_name = "BYTES", value_parser = stagelight::budget::parse_bytes)]
    memory_limit: Option<u64>,
}

/// The `render` flags that decide which stages run, shared with `plan` so that it plans
/// the same run.
#[derive(Args)]
struct StageFlags {
    /// Radiance integrator (overrides the scene's `options.integrator`).
    #[arg(long, value_enum)]
    integrator: Option<IntegratorArg>,
    /// Switch kinds of shaders off for this run, added to the scene's `options.disable`:
    /// a comma-separated list of lens, volume, geometry, displacement, output.
    #[arg(long, value_name = "FEATURES", value_parser = stagelight::features::Features::parse_list)]
    disable: Option<stagelight::features::Features>,
    /// Load the photon maps from `DIR/<hash>.pmap` when that file exists, else trace them
    /// and keep them there (overrides the scene's `photon_map` file).
    #[arg(long = "photon-cache", value_name = "DIR")]
    photon_cache: Option<PathBuf>,
}

impl StageFlags {
    /// Applies `--integrator` and `--disable` to `settings`.
    fn apply(&self, settings: &mut stagelight::settings::RenderSettings) {
        if let Some(integrator) = self.integrator {
            settings.integrator = integrator.integrator();
        }
        if let Some(off) = self.disable {
            settings.disabled = settings.disabled.union(off);
        }
    }
}

#[derive(Args)]
struct PhotonsArgs {
    /// Scene file (.ron, .rib, .mi, .gltf or .glb).
    scene: PathBuf,
    /// Keep the maps in `DIR/<hash>.pmap` (default: the scene's `photon_map` file).
    #[arg(long = "photon-cache", value_name = "DIR")]
    photon_cache: Option<PathBuf>,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    threads: Option<u32>,
    /// Random seed (overrides the scene's `options.seed`; renders must use the same one).
    #[arg(long)]
    seed: Option<u64>,
    /// Print the per-stage report.
    #[arg(long)]
    stats: bool,
    /// Memory budget in bytes (as for `render`).
    #[arg(long = "memory-limit", value_name = "BYTES", value_parser = stagelight::budget::parse_bytes)]
    memory_limit: Option<u64>,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum SplitArg {
    /// Interleaved 16×16 pixel tiles.
    Tiles,
    /// Ranges of every pixel's sample indices.
    Samples,
}

impl SplitArg {
    fn split(self) -> Split {
        match self {
            SplitArg::Tiles => Split::Tiles,
            SplitArg::Samples => Split::Samples,
        }
    }
}

#[derive(Args)]
struct MergeArgs {
    /// The part files (every part of one render or of one bake, each once, in any order).
    #[arg(required = true)]
    parts: Vec<PathBuf>,
    /// Render parts: write the image here instead of the camera's first output of its kind
    /// (.png or .exr; .svg or .eps for the contour lines).
    /// Bake parts: the directory for the textures (default: the working directory).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// The scene the parts were rendered from (default: the path recorded in the parts).
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    threads: Option<u32>,
    /// Print the per-stage report.
    #[arg(long)]
    stats: bool,
    /// Bake parts: also write `DIR/<scene>.glb` with the merged textures applied, as `bake
    /// --write-gltf` writes it (docs/gltf.md).
    #[arg(long = "write-gltf")]
    write_gltf: bool,
}

#[derive(Args)]
struct FarmArgs {
    /// Scene file (.ron, .rib, .mi, .gltf or .glb).
    scene: PathBuf,
    /// Number of parts (array tasks).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    parts: u32,
    /// Directory for the scripts, part files and logs (created).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// How the render is divided.
    #[arg(long, value_enum, default_value = "tiles")]
    split: SplitArg,
    /// Where the merge job writes (default: the camera's outputs).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Samples per pixel for every part.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    spp: Option<u32>,
    /// Random seed for every part.
    #[arg(long)]
    seed: Option<u64>,
    /// Slurm partition.
    #[arg(long)]
    partition: Option<String>,
    /// CPUs (and worker threads) per part (at most 1024, as `render --threads`).
    #[arg(long = "cpus-per-task", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    cpus_per_task: u32,
    /// Memory per part, as Slurm writes it (e.g. 4G).
    #[arg(long)]
    mem: Option<String>,
    /// Time limit per job, as Slurm writes it (e.g. 01:00:00).
    #[arg(long)]
    time: Option<String>,
    /// Submit with `sbatch` and print the job ids.
    #[arg(long)]
    submit: bool,
    /// Bake the scene's bake requests as parts (`bake --part K/N`) instead of rendering;
    /// `-o` is then the texture directory of the merge.
    #[arg(long, conflicts_with_all = ["spp", "split"])]
    bake: bool,
    /// With `--bake`: the merge job also writes the baked glTF (`merge --write-gltf`) into
    /// the texture directory.
    #[arg(long = "write-gltf")]
    write_gltf: bool,
}

#[derive(Args)]
struct BakeArgs {
    /// Scene file (.ron, .rib, .mi, .gltf or .glb).
    scene: PathBuf,
    /// Directory for the baked textures (default: the working directory).
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    output: Option<PathBuf>,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    threads: Option<u32>,
    /// Random seed (overrides the scene's `options.seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Print the per-stage report.
    #[arg(long)]
    stats: bool,
    /// Write the per-stage report (and the bake reports) as JSON.
    #[arg(long = "stats-json", value_name = "FILE")]
    stats_json: Option<PathBuf>,
    /// How indirect light of lightmaps is gathered: `direct` (diffuse gather) or `path` (the
    /// path-traced reference integrator); overrides the scene's `options.integrator`.
    #[arg(long, value_enum)]
    integrator: Option<IntegratorArg>,
    /// Memory budget in bytes (binary suffixes K, M, G, T; KB… and KiB… mean the same); default: the smallest of half
    /// the physical memory, `ulimit -v` and the cgroup limit.
    #[arg(long = "memory-limit", value_name = "BYTES", value_parser = stagelight::budget::parse_bytes)]
    memory_limit: Option<u64>,
    /// Bake only part K of N (1-based; interleaved 16×16 texel tiles of all requests) and
    /// write it undilated as `bake_part_K_of_N.exr` into the output directory, for
    /// `stagelight merge`.
    #[arg(long, value_name = "K/N")]
    part: Option<PartNumber>,
    /// Also write `DIR/<scene>.glb` with the bakes applied (lightmap and occlusion on
    /// TEXCOORD_1, per-vertex bakes as COLOR_0; docs/gltf.md): for a glTF scene a copy whose
    /// materials reference the baked textures, for any other scene a standalone glTF of its
    /// baked geometry. Not with `--part`: `merge --write-gltf` writes it for a bake done in
    /// parts.
    #[arg(long = "write-gltf")]
    write_gltf: bool,
}

#[derive(Args)]
struct PlanArgs {
    /// Scene file (.ron, .rib, .mi, .gltf or .glb).
    scene: PathBuf,
    /// Plan `render --bake` (render and bake).
    #[arg(long, conflicts_with = "bake_only")]
    bake: bool,
    /// Plan `stagelight bake` (bake only).
    #[arg(long = "bake-only")]
    bake_only: bool,
    #[command(flatten)]
    stages: StageFlags,
    /// Plan the render of this camera (by name) instead of the scene's render camera, as
    /// `render --camera` renders it.
    #[arg(long)]
    camera: Option<String>,
    /// Plan a render that writes its image here (.png or .exr, or .svg/.eps for contours),
    /// as `render -o` writes it: a camera without outputs then runs its stages.
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Samples per pixel, as `render --spp` (a fixed count overrides adaptive sampling).
    #[arg(long)]
    spp: Option<u32>,
    /// Print the plan as JSON on stdout.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct BenchArgs {
    /// Scene file (.ron, .rib, .mi, .gltf or .glb).
    scene: PathBuf,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    threads: Option<u32>,
    /// Print the report as JSON on stdout.
    #[arg(long)]
    json: bool,
    /// Memory budget in bytes (binary suffixes K, M, G, T; KB… and KiB… mean the same); default: the smallest of half
    /// the physical memory, `ulimit -v` and the cgroup limit.
    #[arg(long = "memory-limit", value_name = "BYTES", value_parser = stagelight::budget::parse_bytes)]
    memory_limit: Option<u64>,
    /// Radiance integrator (overrides the scene's `options.integrator`).
    #[arg(long, value_enum)]
    integrator: Option<IntegratorArg>,
}

#[derive(Args)]
struct SweepArgs {
    /// Scene file (.ron, .rib, .mi, .gltf or .glb).
    scene: PathBuf,
    /// The knob and its values: spp, adaptive_contrast, light_samples, max_depth, bvh_quality,
    /// tessellation, bake_samples, photons, gather_radius, gather_count, passes, filter
    /// (e.g. `--knob spp=1,4,16,64`).
    #[arg(long, value_name = "NAME=V1,V2,…")]
    knob: String,
    /// Reference image (linear EXR, same size); rendered and cached in the output directory
    /// when absent.
    #[arg(long, value_name = "FILE.exr")]
    reference: Option<PathBuf>,
    /// Samples per pixel (or bake samples per texel) of a rendered reference.
    #[arg(long = "reference-spp", default_value_t = 1024, value_parser = clap::value_parser!(u32).range(1..))]
    reference_spp: u32,
    /// Seeds per value (2 or more also report bias² and variance).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    seeds: u32,
    /// Output directory for sweep.csv, sweep.json, sweep.svg and the cached reference.
    #[arg(long, default_value = "sweep_out")]
    out: PathBuf,
    /// Integrator of the swept runs (overrides the scene's `options.integrator`); the
    /// reference is always rendered by the path tracer.
    #[arg(long, value_enum)]
    integrator: Option<IntegratorArg>,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    threads: Option<u32>,
    /// Denoise the swept bakes in texel space (every AO and lightmap output without its own
    /// `denoise` gets the default one; the reference is not denoised): equal-time error with
    /// and without the denoiser. Needs `--knob bake_samples=…`.
    #[arg(long)]
    denoise: bool,
    /// Fit and plot the error of pixels [X0, X1) × [Y0, Y1) (e.g. a caustic) instead of the
    /// whole image's; the table has both.
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = stagelight::sweep::Crop::parse)]
    crop: Option<stagelight::sweep::Crop>,
    /// Memory budget of every run (as for `render`); every knob value, and the reference
    /// when it is rendered, is checked against it before the first run.
    #[arg(long = "memory-limit", value_name = "BYTES", value_parser = stagelight::budget::parse_bytes)]
    memory_limit: Option<u64>,
}

/// `--integrator` values.
#[derive(Clone, Copy, clap::ValueEnum)]
enum IntegratorArg {
    /// Direct lighting with traced mirror/refraction rays.
    Direct,
    /// Unbiased path tracing (the reference).
    Path,
}

impl IntegratorArg {
    fn integrator(self) -> stagelight::settings::Integrator {
        match self {
            IntegratorArg::Direct => stagelight::settings::Integrator::Direct,
            IntegratorArg::Path => stagelight::settings::Integrator::Path,
        }
    }
}

/// `eprintln!` without its panic when standard error is closed (`stagelight sweep … 2>&1 |
/// head -2`): a message that cannot be written is dropped, and the command runs on to its
/// usual exit status.
macro_rules! errln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// `print!` to standard output without its panic when the reader has gone
/// (`stagelight plan | head -1`): the process ends quietly with status 0, as a pipeline
/// expects; any other write error is reported and ends it with status 1.
macro_rules! out {
    ($($arg:tt)*) => { write_stdout(format_args!($($arg)*), false) };
}

/// `println!` with [`out!`]'s handling of a reader that has gone.
macro_rules! outln {
    ($($arg:tt)*) => { write_stdout(format_args!($($arg)*), true) };
}

fn write_stdout(args: std::fmt::Arguments, newline: bool) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let written = stdout
        .write_fmt(args)
        .and_then(|()| {
            if newline {
                stdout.write_all(b"\n")
            } else {
                Ok(())
            }
        })
        .and_then(|()| stdout.flush());
    if let Err(e) = written {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        errln!("error: cannot write to standard output: {e}");
        std::process::exit(i32::from(EXIT_ERROR));
    }
}

fn main() -> ExitCode {
    let _ = tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        // `FILE: warning: …`, as the scene's located warnings print.
        .event_format(stagelight::log_format::DiagnosticStyle)
        .try_init();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(EXIT_USAGE)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    let _ = REFUSED_OUTCOME.set(refused_outcome(&cli.command));
    match cli.command {
        Command::Check {
            scene,
            memory_limit,
        } => check(&scene, memory_limit),
        Command::Plan(args) => plan(args),
        Command::Convert { scene, output } => convert(&scene, &output),
        Command::Merge(args) => merge(args),
        Command::Farm(args) => farm(args),
        Command::Photons(args) => photons(args),
        Command::Render(args) => render(args),
        Command::Bake(args) => bake(args),
        Command::Bench(args) => bench(args),
        Command::Sweep(args) => sweep(args),
    }
}

/// Loads the scene at `path`, its image textures counted against `budget` before they are
/// decoded, printing its warnings (or its errors).
fn load(path: &Path, budget: &stagelight::budget::Budget) -> Result<LoadedScene, ExitCode> {
    match stagelight::scene::load_scene_within(path, budget) {
        Ok(scene) => {
            for w in &scene.located_warnings {
                errln!("{w}");
            }
            Ok(scene)
        }
        Err(errors) => {
            errln!("{errors}");
            errln!("{}", refusal_line(errors.0.len(), errors.1.len(), path));
            Err(ExitCode::from(EXIT_ERROR))
        }
    }
}

/// What a refused run did not do, for the last line of its report (`1 error in a.rib;
/// nothing baked`): set once from the command, before anything is read.
static REFUSED_OUTCOME: std::sync::OnceLock<&'static str> = std::sync::OnceLock::new();

/// The tail of a refusal's count line for `command` (`check` only counts: it writes nothing).
fn refused_outcome(command: &Command) -> &'static str {
    match command {
        Command::Check { .. } => "",
        Command::Plan(_) => "; nothing planned",
        Command::Convert { .. } => "; nothing converted",
        Command::Merge(_) => "; nothing merged",
        Command::Farm(_) => "; no scripts written",
        Command::Photons(_) => "; no photon map written",
        Command::Render(_) => "; nothing rendered",
        Command::Bake(_) => "; nothing baked",
        Command::Bench(_) => "; nothing measured",
        Command::Sweep(_) => "; nothing swept",
    }
}

/// The count line that ends a refusal: `2 errors and 1 warning in a.rib; nothing rendered`.
fn refusal_line(errors: usize, warnings: usize, path: &Path) -> String {
    format!(
        "{}{} in {}{}",
        counted(errors, "error"),
        match warnings {
            0 => String::new(),
            n => format!(" and {}", counted(n, "warning")),
        },
        path.display(),
        REFUSED_OUTCOME
            .get()
            .copied()
            .unwrap_or("; nothing rendered")
    )
}

/// `1 error`, `2 errors`.
fn counted(n: usize, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}

fn check(path: &Path, memory_limit: Option<u64>) -> ExitCode {
    match load(path, &budget(memory_limit)) {
        Ok(scene) => {
            // What `render --bake` would write and need, with the scene's own outputs.
            let mut frame = Frame::new(scene.settings.clone());
            frame.inputs.tasks = Tasks {
                render: true,
                bake: true,
            };
            frame.inputs.budget = budget(memory_limit);
            if let Err(code) = check_run(path, &scene, &frame.inputs, None) {
                return code;
            }
            // Adaptive approximations are diced (and refused past the budget) only by a
            // render: what can be known now is their worst case.
            for w in stagelight::budget::worst_case::warnings(&scene.world, &frame.inputs.budget) {
                errln!("{}", w.with_severity(stagelight::scene::Severity::Warning));
            }
            let entities = scene.world.len();
            outln!("{}: ok ({entities} entities)", path.display());
            ExitCode::SUCCESS
        }
        Err(code) => code,
    }
}

/// The run's memory budget: `--memory-limit`, else the machine's and process's limits.
fn budget(memory_limit: Option<u64>) -> stagelight::budget::Budget {
    memory_limit.map_or_else(
        stagelight::budget::Budget::detect,
        stagelight::budget::Budget::given,
    )
}

/// Refuses a run, before anything runs, whose estimated memory exceeds its budget (exit 1)
/// or whose outputs would overwrite an input or each other (exit 2 when a flag names the
/// output, 1 when the scene does).
fn check_run(
    path: &Path,
    scene: &LoadedScene,
    inputs: &RunInputs,
    stats_json: Option<&Path>,
) -> Result<(), ExitCode> {
    let refused = stagelight::budget::estimate::check(
        &scene.world,
        &inputs.settings,
        inputs.tasks,
        &inputs.budget,
    );
    if !refused.is_empty() {
        let refused = stagelight::guard::locate::options_located(path, refused);
        for d in &refused {
            errln!("{d}");
        }
        errln!("{}", refusal_line(refused.len(), 0, path));
        return Err(ExitCode::from(EXIT_ERROR));
    }
    check_outputs(path, scene, inputs, stats_json)
}

/// Refuses a run whose outputs would overwrite an input or each other (before anything
/// runs): exit 2 when a flag names the output, 1 when the scene does.
fn check_outputs(
    path: &Path,
    scene: &LoadedScene,
    inputs: &RunInputs,
    stats_json: Option<&Path>,
) -> Result<(), ExitCode> {
    refuse_clashes(
        path,
        &stagelight::guard::outputs::check(path, &scene.world, inputs, stats_json),
    )
}

/// Refuses a merge — or, from `farm`, its merge job — whose outputs would overwrite one of
/// the part files it reads: exit 2 when a flag names the output, 1 when the scene does.
fn check_part_files(
    path: &Path,
    scene: &LoadedScene,
    inputs: &RunInputs,
    parts: &stagelight::guard::part_files::PartFiles,
) -> Result<(), ExitCode> {
    let outputs = stagelight::guard::outputs::planned_outputs(&scene.world, inputs, None);
    refuse_clashes(
        path,
        &stagelight::guard::part_files::clashes(parts, &outputs),
    )
}

/// Prints `clashes` and the count line; exit 2 when a flag takes part in one, else 1.
fn refuse_clashes(
    path: &Path,
    clashes: &[stagelight::guard::outputs::Clash],
) -> Result<(), ExitCode> {
    if clashes.is_empty() {
        return Ok(());
    }
    for c in clashes {
        errln!("{}", c.text);
    }
    errln!("{}", refusal_line(clashes.len(), 0, path));
    Err(ExitCode::from(if clashes.iter().any(|c| c.usage) {
        EXIT_USAGE
    } else {
        EXIT_ERROR
    }))
}

fn plan(args: PlanArgs) -> ExitCode {
    let out = args.output.as_deref();
    let file = |f| stagelight::guard::dir_flags::usable_file("-o", f, "out.png");
    if let Err(code) = usable_paths(&[out.map_or(Ok(()), file)]) {
        return code;
    }
    let mut scene = match load(&args.scene, &budget(None)) {
        Ok(s) => s,
        Err(code) => return code,
    };
    // The camera and the image a `render` with the same flags would use.
    if let Some(name) = &args.camera {
        if let Err(message) = stagelight::camera_choice::use_camera(&mut scene.world, name) {
            errln!("{message}");
            return ExitCode::from(EXIT_USAGE);
        }
    }
    let overrides = match checked_overrides(args.output.clone(), &scene.world, &args.scene) {
        Ok(o) => o,
        Err(code) => return code,
    };
    if args.output.is_some() && !stagelight::scene_view::has_render_camera(&scene.world) {
        errln!("error: the scene has no render camera");
        return ExitCode::from(EXIT_USAGE);
    }
    let mut settings = scene.settings.clone();
    if let Some(spp) = args.spp {
        settings.spp = spp;
        settings.adaptive = None;
    }
    args.stages.apply(&mut settings);
    let mut frame = Frame::new(settings);
    frame.inputs.outputs = overrides;
    frame.inputs.photon_cache = args.stages.photon_cache.clone();
    frame.inputs.tasks = Tasks {
        render: !args.bake_only,
        bake: args.bake || args.bake_only,
    };
    // Planned as `render` runs it: the image is read only through outputs.
    frame.inputs.caller_keeps_image = false;
    frame.inputs.budget = budget(None);
    // What `check` and `render` refuse before the first stage (the memory budget, outputs
    // that would overwrite an input or each other) is refused here too: no plan of a run
    // that would not start.
    if let Err(code) = check_run(&args.scene, &scene, &frame.inputs, None) {
        return code;
    }
    let planned = systems::plan(&scene.world, &mut frame);
    if args.json {
        match serde_json::to_string_pretty(&planned) {
            Ok(j) => outln!("{j}"),
            Err(e) => {
                errln!("error: cannot encode the plan: {e}");
                return ExitCode::from(EXIT_ERROR);
            }
        }
        return ExitCode::SUCCESS;
    }
    let task = match (frame.inputs.tasks.render, frame.inputs.tasks.bake) {
        (true, true) => "render --bake",
        (true, false) => "render",
        _ => "bake",
    };
    outln!("plan for {} ({task}):", args.scene.display());
    for (i, p) in planned.iter().enumerate() {
        outln!(
            "{:>2} {:<16} {:<4} {}",
            i + 1,
            p.stage,
            if p.run { "run" } else { "skip" },
            p.reason
        );
    }
    ExitCode::SUCCESS
}

/// `stagelight convert SCENE -o OUT.ron`: checks the scene as `render` would, then writes
/// its description (as its reader produced it; a RIB file's archives inlined) as RON that
/// loads into the same description, its relative input paths rewritten for OUT's directory
/// (`relocate`; a missing directory is created, as `render -o` creates one). Written
/// atomically (`commit_all`): on failure neither the file nor the created directory stays.
fn convert(scene: &Path, output: &Path) -> ExitCode {
    use stagelight::scene::import::{reader_for, to_ron::to_ron, FORMATS};
    let file = stagelight::guard::dir_flags::usable_file("-o", output, "scene.ron");
    if let Err(code) = usable_paths(&[file]) {
        return code;
    }
    if let Err(code) = load(scene, &budget(None)) {
        return code;
    }
    let fail = |message: String| {
        errln!("{message}");
        ExitCode::from(EXIT_ERROR)
    };
    let inputs = stagelight::scene::inputs::scene_inputs(scene, None);
    let key = stagelight::guard::outputs::same_file_key(output);
    if let Some(input) = inputs
        .iter()
        .find(|i| stagelight::guard::outputs::same_file_key(i) == key)
    {
        errln!(
            "error: -o {} would overwrite the scene input {}\n  help: write the RON scene to another file",
            output.display(),
            input.display()
        );
        return ExitCode::from(EXIT_USAGE);
    }
    let bytes = match std::fs::read(scene) {
        Ok(b) => b,
        Err(e) => {
            let reason = stagelight::guard::io_reason(&e);
            return fail(format!("error: cannot read {}: {reason}", scene.display()));
        }
    };
    let format = match reader_for(FORMATS, scene) {
        Ok(f) => f,
        Err((reason, help)) => {
            return fail(format!("{}: {reason}\n  help: {help}", scene.display()))
        }
    };
    // The scene loaded above (its warnings printed): the reader accepts it again.
    let desc = match (format.read)(scene, &bytes) {
        Ok(read) => read.desc,
        Err(failure) => {
            let errors = failure.errors.iter().map(ToString::to_string);
            return fail(errors.collect::<Vec<_>>().join("\n"));
        }
    };
    // The output's directory must exist for `relocate` to find its real path.
    let dir = output.parent().filter(|d| !d.as_os_str().is_empty());
    let created = dir.and_then(|d| {
        d.ancestors()
            .filter(|a| !a.as_os_str().is_empty() && !a.exists())
            .last()
    });
    let created = created.map(Path::to_path_buf);
    let undo = |message: String| {
        if let Some(c) = &created {
            let _ = std::fs::remove_dir_all(c);
        }
        fail(message)
    };
    if let (Some(dir), Some(_)) = (dir, &created) {
        if let Err(e) = std::fs::create_dir_all(dir) {
            let reason = stagelight::guard::io_reason(&e);
            return undo(format!("error: cannot create {}: {reason}", dir.display()));
        }
    }
    let desc = match stagelight::scene::import::relocate::relocate_inputs(desc, scene, output) {
        Ok(d) => d,
        Err(message) => return undo(format!("error: {message}")),
    };
    let text = match to_ron(&desc) {
        Ok(t) => t,
        Err(e) => {
            return undo(format!(
                "error: cannot write {} as RON: {e}",
                scene.display()
            ))
        }
    };
    let file = stagelight::image_io::PendingFile::new(output.to_path_buf(), text.into_bytes());
    if let Err((p, e)) = stagelight::image_io::commit_all(&[file]) {
        let reason = stagelight::guard::io_reason(&e);
        return undo(format!("error: cannot write {}: {reason}", p.display()));
    }
    outln!("{}: wrote {}", scene.display(), output.display());
    ExitCode::SUCCESS
}

/// Refuses, before the scene is read, the paths of flags a run would write into that cannot
/// be used (`guard::dir_flags`): a usage error, exit 2.
fn usable_paths(checks: &[Result<(), String>]) -> Result<(), ExitCode> {
    match checks.iter().find_map(|c| c.as_ref().err()) {
        None => Ok(()),
        Some(message) => {
            errln!("error: {message}");
            Err(ExitCode::from(EXIT_USAGE))
        }
    }
}

fn set_threads(threads: Option<u32>) -> Result<(), ExitCode> {
    if let Some(threads) = threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(threads as usize)
            .build_global()
        {
            errln!("error: cannot start {threads} worker threads: {e}");
            return Err(ExitCode::from(EXIT_ERROR));
        }
    }
    Ok(())
}

/// Starts the worker pool, loads the scene and applies the command-line overrides common to
/// `render` and `bake`.
fn prepare(
    scene: &Path,
    threads: Option<u32>,
    seed: Option<u64>,
    integrator: Option<IntegratorArg>,
    memory_limit: Option<u64>,
) -> Result<(LoadedScene, stagelight::settings::RenderSettings), ExitCode> {
    set_threads(threads)?;
    let scene = load(scene, &budget(memory_limit))?;
    let mut settings = scene.settings.clone();
    if let Some(seed) = seed {
        settings.seed = seed;
    }
    if let Some(integrator) = integrator {
        settings.integrator = integrator.integrator();
    }
    Ok((scene, settings))
}

fn render(args: RenderArgs) -> ExitCode {
    use stagelight::guard::dir_flags::{usable_cache_dir, usable_file};
    let cache = args.stages.photon_cache.as_deref();
    let out = args.output.as_deref();
    let stats_json = args.stats_json.as_deref();
    if let Err(code) = usable_paths(&[
        cache.map_or(Ok(()), |d| usable_cache_dir("--photon-cache", d)),
        out.map_or(Ok(()), |f| usable_file("-o", f, "out.png")),
        stats_json.map_or(Ok(()), |f| usable_file("--stats-json", f, "stats.json")),
    ]) {
        return code;
    }
    let (mut scene, mut settings) = match prepare(
        &args.scene,
        args.threads,
        args.seed,
        None,
        args.memory_limit,
    ) {
        Ok(p) => p,
        Err(code) => return code,
    };
    if let Some(name) = &args.camera {
        if args.part.is_some() {
            let help = stagelight::camera_choice::render_camera_help(
                scene_syntax(&args.scene),
                &args.scene,
                name,
            );
            errln!("error: --camera cannot be combined with --part\n  help: the merge job renders the scene's render camera; {help}");
            return ExitCode::from(EXIT_USAGE);
        }
        if let Err(message) = stagelight::camera_choice::use_camera(&mut scene.world, name) {
            errln!("{message}");
            return ExitCode::from(EXIT_USAGE);
        }
    }
    if let Some(spp) = args.spp {
        // A fixed count overrides the scene's adaptive sampling too.
        settings.spp = spp;
        settings.adaptive = None;
    }
    args.stages.apply(&mut settings);
    if args.diagnostic.is_some() {
        settings.diagnostic = args.diagnostic;
    }
    if let Some(message) = stagelight::diagnostic_needs::missing(
        &settings,
        &stagelight::format_helps::photon_maps_help(scene_syntax(&args.scene), &args.scene),
    ) {
        errln!("error: {message}");
        let flagged = args.diagnostic.is_some() || args.stages.integrator.is_some();
        return ExitCode::from(if flagged { EXIT_USAGE } else { EXIT_ERROR });
    }
    if let Some(number) = args.part {
        // A part file is an EXR whatever else `-o` could name: said before the formats a
        // render writes.
        if let Err(message) =
            stagelight::part_refusals::part_file_output(number, args.output.as_deref())
        {
            errln!("error: {message}");
            return ExitCode::from(EXIT_USAGE);
        }
    }
    let overrides = match checked_overrides(args.output.clone(), &scene.world, &args.scene) {
        Ok(o) => o,
        Err(code) => return code,
    };
    if args.output.is_some() && !stagelight::scene_view::has_render_camera(&scene.world) {
        errln!("error: the scene has no render camera");
        return ExitCode::from(EXIT_USAGE);
    }
    let part = match args.part {
        Some(number) => match part_run(&args, number, &scene, &settings) {
            Ok(run) => Some(run),
            Err(message) => {
                errln!("error: {message}");
                return ExitCode::from(EXIT_USAGE);
            }
        },
        None => None,
    };
    let mut frame = Frame::new(settings);
    frame.inputs.budget = budget(args.memory_limit);
    frame.inputs.outputs = overrides;
    frame.inputs.part = part;
    frame.inputs.photon_cache = args.stages.photon_cache.clone();
    frame.inputs.tasks = Tasks {
        render: true,
        bake: args.bake,
    };
    frame.inputs.caller_keeps_image = false;
    run_and_report(
        &args.scene,
        &mut scene,
        frame,
        args.stats,
        args.stats_json.as_deref(),
    )
}

/// `stagelight photons`: the stages through `trace_photons`, keeping the maps.
fn photons(args: PhotonsArgs) -> ExitCode {
    let cache = args.photon_cache.as_deref();
    let dir = |d| stagelight::guard::dir_flags::usable_cache_dir("--photon-cache", d);
    if let Err(code) = usable_paths(&[cache.map_or(Ok(()), dir)]) {
        return code;
    }
    let (mut scene, settings) = match prepare(
        &args.scene,
        args.threads,
        args.seed,
        None,
        args.memory_limit,
    ) {
        Ok(p) => p,
        Err(code) => return code,
    };
    if args.photon_cache.is_none() && settings.photon_map.is_none() {
        let file = stagelight::scene::syntax::Helps {
            ron: ", or add `photon_map: (file: \"scene.pmap\")` to the scene's options",
            mi: ", or add `photonmap file \"scene.pmap\"` to the options block",
            rib: " (a RIB file names no photon map file)",
            gltf: " (a glTF file names no photon map file)",
        };
        errln!(
            "error: nowhere to keep the photon maps of {}\n  help: give --photon-cache DIR{}",
            args.scene.display(),
            scene_syntax(&args.scene).help_each(file)
        );
        return ExitCode::from(EXIT_USAGE);
    }
    let mut frame = Frame::new(settings);
    frame.inputs.budget = budget(args.memory_limit);
    frame.inputs.photon_cache = args.photon_cache;
    frame.inputs.outputs.discard = true;
    frame.inputs.stop_after = Some("trace_photons");
    let mut plan_frame = Frame::new(frame.inputs.settings.clone());
    plan_frame.inputs = frame.inputs.clone();
    let planned = systems::plan(&scene.world, &mut plan_frame);
    if let Some(p) = planned
        .iter()
        .find(|p| p.stage == "trace_photons" && !p.run)
    {
        let on = stagelight::format_helps::photon_maps_help(scene_syntax(&args.scene), &args.scene);
        errln!(
            "error: {} traces no photons: {}\n  help: photon maps are built for caustics or global illumination, with the Direct integrator: {on}",
            args.scene.display(),
            p.reason
        );
        return ExitCode::from(EXIT_ERROR);
    }
    run_and_report(&args.scene, &mut scene, frame, args.stats, None)
}

/// The part a `render --part K/N` run computes, after checking the flags that go with it
/// (its `-o PART.exr` is checked before).
fn part_run(
    args: &RenderArgs,
    number: PartNumber,
    scene: &LoadedScene,
    settings: &stagelight::settings::RenderSettings,
) -> Result<PartRun, String> {
    let split = args.split.split();
    let diagnostic_flag = args.diagnostic.is_some();
    if let Some(message) = stagelight::part_refusals::part_refusal(
        &scene.world,
        settings,
        number,
        split,
        diagnostic_flag,
    ) {
        return Err(message);
    }
    Ok(PartRun {
        part: stagelight::farm::Part {
            index: number.index,
            count: number.count,
            split,
        },
        scene: part_scene_name(&args.scene),
        scene_hash: stagelight::farm::scene_hash(&args.scene, scene.source_hash, &scene.world),
    })
}

fn merge(args: MergeArgs) -> ExitCode {
    if let Err(code) = set_threads(args.threads) {
        return code;
    }
    // SIGINT and SIGTERM stop a merge as they stop a render — exit 130, nothing written —
    // from its start: reading and adding the parts cannot poll the flag, so the handler's
    // deadline ends it there (nothing is written before the commit).
    let cancel = Arc::new(AtomicBool::new(false));
    stagelight::guard::interrupt::install(cancel.clone());
    if args
        .parts
        .first()
        .is_some_and(|p| stagelight::farm::bake_part_file::is_bake_part_file(p))
    {
        return merge_bake(args, cancel);
    }
    let file = |f| stagelight::guard::dir_flags::usable_file("-o", f, "out.png");
    if let Err(code) = usable_paths(&[args.output.as_deref().map_or(Ok(()), file)]) {
        return code;
    }
    if let Some(out) = &args.output {
        if args
            .parts
            .iter()
            .any(|p| same_file_key(p) == same_file_key(out))
        {
            errln!(
                "error: -o {} is one of the part files being merged\n  help: write the merged image to a new file",
                out.display()
            );
            return ExitCode::from(EXIT_USAGE);
        }
    }
    let parts = match stagelight::farm::merge::read_parts(&args.parts) {
        Ok(parts) => parts,
        Err(message) => {
            errln!("error: {message}\nnothing written");
            return ExitCode::from(EXIT_ERROR);
        }
    };
    if args.write_gltf {
        let refusal = gltf_copy_refusals::render_parts_refusal(&args.parts[0]);
        errln!("error: {refusal}");
        return ExitCode::from(EXIT_USAGE);
    }
    let image = match stagelight::farm::merge::merge(&parts) {
        Ok(image) => image,
        Err(message) => {
            errln!("error: {message}\nnothing written");
            return ExitCode::from(EXIT_ERROR);
        }
    };
    let header = &parts[0].file.header;
    let (scene_path, mut scene) =
        match part_scene(&args, &header.scene, header.scene_hash, "render") {
            Ok(s) => s,
            Err(code) => return code,
        };
    let overrides = match checked_overrides(args.output.clone(), &scene.world, &scene_path) {
        Ok(o) => o,
        Err(code) => return code,
    };
    let mut settings = scene.settings.clone();
    // Contours and the geometry stages run again in the merge: with the parts' `--disable`.
    header.recorded.apply(&mut settings);
    let mut frame = Frame::new(settings);
    frame.inputs.outputs = overrides;
    frame.inputs.merged_image = Some(image);
    frame.inputs.cancel = cancel;
    let parts = stagelight::guard::part_files::PartFiles::Given(&args.parts);
    if let Err(code) = check_part_files(&scene_path, &scene, &frame.inputs, &parts) {
        return code;
    }
    run_and_report(&scene_path, &mut scene, frame, args.stats, None)
}

/// The `-o` override of the first output, checked against the scene's outputs and
/// contours; a usage error is printed and its exit code returned.
fn checked_overrides(
    first: Option<PathBuf>,
    world: &hecs::World,
    scene_path: &Path,
) -> Result<OutputOverrides, ExitCode> {
    let overrides = OutputOverrides {
        first,
        ..OutputOverrides::default()
    };
    // The help speaks the scene file's language (`.mi` statements for a mental ray scene).
    let syntax = scene_syntax(scene_path);
    overrides
        .check()
        .and_then(|()| overrides.check_contours(world, syntax, scene_path))
        .map_err(|message| {
            errln!("error: {message}");
            ExitCode::from(EXIT_USAGE)
        })?;
    let listed = stagelight::scene_view::render_view(world).map(|v| v.camera.outputs);
    if let Some(warning) = overrides.png_drops_passes(&listed.unwrap_or_default()) {
        errln!("warning: {warning}");
    }
    Ok(overrides)
}

/// The syntax the scene file at `path` is written in (by its extension, as the readers
/// are chosen; RON when none takes it), so that a help shows what to write in that file.
fn scene_syntax(path: &Path) -> stagelight::scene::syntax::Syntax {
    stagelight::scene::import::syntax_of(path)
}

/// How a part file names its scene: the path as given, made absolute against the working
/// directory, so that `merge` finds it from any directory.
fn part_scene_name(scene: &Path) -> String {
    std::path::absolute(scene)
        .unwrap_or_else(|_| scene.to_path_buf())
        .display()
        .to_string()
}

/// The scene a set of part files came from (`--scene`, else the path in their header),
/// loaded and checked against the parts' content hash; `verb` is `render` or `bake`.
fn part_scene(
    args: &MergeArgs,
    header_scene: &str,
    parts_hash: u64,
    verb: &str,
) -> Result<(PathBuf, LoadedScene), ExitCode> {
    let scene_path = args
        .scene
        .clone()
        .unwrap_or_else(|| PathBuf::from(header_scene));
    if args.scene.is_none() && !scene_path.exists() {
        errln!(
            "error: the parts came from the scene {}, which is not there
  help: pass the scene they came from with --scene SCENE
nothing written",
            scene_path.display()
        );
        return Err(ExitCode::from(EXIT_ERROR));
    }
    let scene = load(&scene_path, &budget(None))?;
    let hash = stagelight::farm::scene_hash(&scene_path, scene.source_hash, &scene.world);
    let recorded = Path::new(header_scene);
    let other_scene = args.scene.is_some()
        && stagelight::guard::outputs::same_file_key(&scene_path)
            != stagelight::guard::outputs::same_file_key(recorded);
    if hash != parts_hash && other_scene {
        // The parts record their scene: a different file is not an edit of it.
        let help = if recorded.exists() {
            format!(
                "leave out --scene to merge with {header_scene}, or {verb} the parts again from {}",
                scene_path.display()
            )
        } else {
            format!("{verb} the parts again from {}", scene_path.display())
        };
        errln!(
            "error: the parts came from the scene {header_scene}, not from {} (content hash {hash:016x}, the parts have {parts_hash:016x})\n  help: {help}\nnothing written",
            scene_path.display(),
        );
        return Err(ExitCode::from(EXIT_ERROR));
    }
    if hash != parts_hash {
        let done = if verb == "bake" { "baked" } else { "rendered" };
        // With --scene given, that scene is the one to use: only new parts help.
        let help = if args.scene.is_some() {
            format!("{verb} the parts again from {}", scene_path.display())
        } else {
            format!("{verb} the parts again, or pass the scene they came from with --scene")
        };
        // The hash covers every file the scene reads, and the parts record only the hash:
        // name the scene and the files it reads.
        errln!(
            "error: {} changed since the parts were {done} (content hash {hash:016x}, the parts have {parts_hash:016x})\n  help: {help}\nnothing written",
            stagelight::farm::changed_scene::changed_content(&scene_path),
        );
        return Err(ExitCode::from(EXIT_ERROR));
    }
    Ok((scene_path, scene))
}

/// `stagelight merge` of bake parts: assembles the texels, then bakes the scene's requests
/// from them (dilation and encoding as a single bake) into `-o DIR`; `cancel` is the flag
/// the merge's SIGINT/SIGTERM handler sets.
fn merge_bake(args: MergeArgs, cancel: Arc<AtomicBool>) -> ExitCode {
    use stagelight::farm::bake_part::merge;
    use stagelight::farm::bake_part_file::read_parts;
    let dir = |d| stagelight::guard::dir_flags::usable_dir("-o", d);
    if let Err(code) = usable_paths(&[args.output.as_deref().map_or(Ok(()), dir)]) {
        return code;
    }
    let merged = match read_parts(&args.parts).and_then(|parts| {
        let header = parts[0].file.header.clone();
        merge(&parts).map(|merged| (header, merged))
    }) {
        Ok(m) => m,
        Err(message) => {
            errln!("error: {message}\nnothing written");
            return ExitCode::from(EXIT_ERROR);
        }
    };
    let (header, merged) = merged;
    let (scene_path, mut scene) = match part_scene(&args, &header.scene, header.scene_hash, "bake")
    {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut settings = scene.settings.clone();
    settings.seed = header.seed;
    header.recorded.apply(&mut settings);
    if stagelight::farm::settings_hash(&settings) != header.settings_hash {
        errln!(
            "error: the parts were baked with other settings than {} gives (written by another stagelight version?)\n  help: bake the parts again with this stagelight\nnothing written",
            scene_path.display()
        );
        return ExitCode::from(EXIT_ERROR);
    }
    let mut frame = Frame::new(settings);
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    if let Some(dir) = args.output {
        frame.inputs.bake_dir = dir;
    }
    if args.write_gltf {
        // The copy `bake --write-gltf` writes: same path rule, same bytes.
        frame.inputs.write_gltf = Some(scene_path.clone());
    }
    frame.inputs.merged_bake = Some(merged);
    frame.inputs.cancel = cancel;
    let parts = stagelight::guard::part_files::PartFiles::Given(&args.parts);
    if let Err(code) = check_part_files(&scene_path, &scene, &frame.inputs, &parts) {
        return code;
    }
    run_and_report(&scene_path, &mut scene, frame, args.stats, None)
}

fn farm(args: FarmArgs) -> ExitCode {
    use stagelight::guard::dir_flags::{usable_dir, usable_file};
    if args.write_gltf && !args.bake {
        errln!("error: {}", gltf_copy_refusals::render_farm_refusal());
        return ExitCode::from(EXIT_USAGE);
    }
    let output = args.output.as_deref().map_or(Ok(()), |o| {
        if args.bake {
            usable_dir("-o", o)
        } else {
            usable_file("-o", o, "out.exr")
        }
    });
    if let Err(code) = usable_paths(&[usable_dir("--out", &args.out), output]) {
        return code;
    }
    if let Some(message) = stagelight::farm::slurm::directive_refusal(&args.out) {
        errln!("error: {message}");
        return ExitCode::from(EXIT_USAGE);
    }
    if args.submit && !stagelight::farm::slurm::sbatch_on_path() {
        // Said before any script is written: a run that fails writes nothing.
        let submit = std::path::absolute(args.out.join("submit.sh")).unwrap_or_default();
        errln!(
            "error: --submit needs `sbatch`, which is not on PATH (is this a Slurm submit host?)\n  help: leave out --submit to write the scripts, then run `bash {}` on a machine where sbatch works",
            stagelight::farm::slurm::quote(&submit.to_string_lossy())
        );
        return ExitCode::from(EXIT_ERROR);
    }
    let mut scene = match load(&args.scene, &budget(None)) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if args.bake {
        if scene.world.query::<&BakeRequest>().iter().next().is_none() {
            errln!("{}", no_bake_requests(&args.scene));
            return ExitCode::from(EXIT_ERROR);
        }
    } else if !stagelight::scene_view::has_render_camera(&scene.world) {
        errln!("error: {} has no render camera", args.scene.display());
        return ExitCode::from(EXIT_ERROR);
    }
    if let Err(code) = farm_refusals(&args, &mut scene) {
        return code;
    }
    // A render that traces photon maps gets a photon job before its array.
    let photons = !args.bake && {
        let mut settings = scene.settings.clone();
        if let Some(seed) = args.seed {
            settings.seed = seed;
        }
        let mut frame = Frame::new(settings);
        systems::plan(&scene.world, &mut frame)
            .iter()
            .any(|p| p.stage == "trace_photons" && p.run)
    };
    let job = match stagelight::farm::slurm::job(
        &args.scene,
        &args.out,
        args.output.as_deref(),
        stagelight::farm::slurm::JobOptions {
            parts: args.parts,
            split: args.split.split(),
            bake: args.bake,
            write_gltf: args.write_gltf,
            photons,
            spp: args.spp,
            seed: args.seed,
            partition: args.partition.clone(),
            cpus_per_task: args.cpus_per_task,
            mem: args.mem.clone(),
            time: args.time.clone(),
        },
    ) {
        Ok(job) => job,
        Err(message) => {
            errln!("error: {message}");
            return ExitCode::from(EXIT_ERROR);
        }
    };
    let written = match stagelight::farm::slurm::write(&job) {
        Ok(w) => w,
        Err(message) => {
            errln!("error: {message}");
            return ExitCode::from(EXIT_ERROR);
        }
    };
    for path in &written {
        errln!("wrote {}", path.display());
    }
    if !args.submit {
        let submit = job.out.join("submit.sh");
        errln!(
            "submit with: bash {}",
            stagelight::farm::slurm::quote(&submit.to_string_lossy())
        );
        return ExitCode::SUCCESS;
    }
    match std::process::Command::new("bash")
        .arg(job.out.join("submit.sh"))
        .status()
    {
        Ok(status) if status.success() => ExitCode::SUCCESS,
        Ok(status) => {
            errln!("error: submitting with sbatch failed ({status})");
            ExitCode::from(EXIT_ERROR)
        }
        Err(e) => {
            errln!("error: cannot run bash to submit: {e}");
            ExitCode::from(EXIT_ERROR)
        }
    }
}

/// Refuses a farm job, before any script is written, that its parts or its merge job would
/// refuse, with the messages `render --part` and `merge` give: a part that cannot be
/// divided (a diagnostic view, `--split samples` of adaptive sampling or component passes),
/// a merge output of no known format (`-o out.jpg`) and outputs that overwrite an input of
/// the scene or each other (for a bake the textures and, with `--write-gltf`, the glTF copy
/// the merge job writes); and more parts than there is work for (for a bake, found by
/// running the geometry stages on `scene`) and a render whose merge would write nothing.
fn farm_refusals(args: &FarmArgs, scene: &mut LoadedScene) -> Result<(), ExitCode> {
    let mut settings = scene.settings.clone();
    if let Some(seed) = args.seed {
        settings.seed = seed;
    }
    if let Some(spp) = args.spp {
        settings.spp = spp;
        settings.adaptive = None;
    }
    let mut frame = Frame::new(settings);
    if args.bake {
        frame.inputs.tasks = Tasks {
            render: false,
            bake: true,
        };
        if let Some(dir) = &args.output {
            frame.inputs.bake_dir = dir.clone();
        }
        if args.write_gltf {
            // The merge job's baked glTF, checked with its textures.
            frame.inputs.write_gltf = Some(args.scene.clone());
        }
    } else {
        let number = PartNumber {
            index: 1,
            count: args.parts,
        };
        let split = args.split.split();
        let settings = &frame.inputs.settings;
        if let Some(message) =
            stagelight::part_refusals::part_refusal(&scene.world, settings, number, split, false)
        {
            errln!("error: {message}");
            return Err(ExitCode::from(EXIT_USAGE));
        }
        frame.inputs.outputs = checked_overrides(args.output.clone(), &scene.world, &args.scene)?;
        let refusal =
            stagelight::part_refusals::no_outputs_refusal(&scene.world, &frame.inputs.outputs)
                .map(|m| (m, EXIT_ERROR))
                .or_else(|| {
                    stagelight::part_refusals::part_count_refusal(
                        &scene.world,
                        &frame.inputs.settings,
                        args.parts,
                        split,
                    )
                    .map(|m| (m, EXIT_USAGE))
                });
        if let Some((message, code)) = refusal {
            errln!("error: {message}");
            return Err(ExitCode::from(code));
        }
    }
    check_outputs(&args.scene, scene, &frame.inputs, None)?;
    // The merge job reads the part files the array writes into `--out`.
    let parts = stagelight::guard::part_files::PartFiles::Farm {
        dir: &args.out,
        count: args.parts,
        bake: args.bake,
    };
    check_part_files(&args.scene, scene, &frame.inputs, &parts)?;
    if args.bake {
        let refusal =
            bake_tile_count(&mut scene.world, &mut frame).and_then(|(tiles, requests)| {
                stagelight::part_refusals::bake_part_count_refusal(args.parts, tiles, requests)
            });
        if let Some(message) = refusal {
            errln!("error: {message}");
            return Err(ExitCode::from(EXIT_USAGE));
        }
    }
    Ok(())
}

/// The bake's tiles and requests, after running the geometry stages on `world` (through
/// `frame`, which must bake): the sizes of density-sized and per-vertex requests come from the
/// built geometry. `None` for a scene whose requests cannot be prepared (its parts report it).
fn bake_tile_count(world: &mut hecs::World, frame: &mut Frame) -> Option<(u64, usize)> {
    systems::run_before("bake_lightmaps", world, frame).ok()?;
    let prepared =
        stagelight::bake::request::prepare_bakes(world, frame.outputs.geometry.as_ref()).ok()?;
    Some((
        systems::bake_lightmaps::bake_tiles(&prepared),
        prepared.len(),
    ))
}

fn bake(args: BakeArgs) -> ExitCode {
    use stagelight::guard::dir_flags::{usable_dir, usable_file};
    if let (Some(number), true) = (args.part, args.write_gltf) {
        let refusal = gltf_copy_refusals::part_refusal(number.index, number.count);
        errln!("error: {refusal}");
        return ExitCode::from(EXIT_USAGE);
    }
    let stats_json = args.stats_json.as_deref();
    if let Err(code) = usable_paths(&[
        args.output
            .as_deref()
            .map_or(Ok(()), |d| usable_dir("-o", d)),
        stats_json.map_or(Ok(()), |f| usable_file("--stats-json", f, "stats.json")),
    ]) {
        return code;
    }
    let (mut scene, settings) = match prepare(
        &args.scene,
        args.threads,
        args.seed,
        args.integrator,
        args.memory_limit,
    ) {
        Ok(p) => p,
        Err(code) => return code,
    };
    if scene.world.query::<&BakeRequest>().iter().next().is_none() {
        errln!("{}", no_bake_requests(&args.scene));
        return ExitCode::from(EXIT_ERROR);
    }
    let mut frame = Frame::new(settings);
    frame.inputs.budget = budget(args.memory_limit);
    frame.inputs.tasks = Tasks {
        render: false,
        bake: true,
    };
    if let Some(dir) = args.output {
        frame.inputs.bake_dir = dir;
    }
    frame.inputs.part = args.part.map(|number| PartRun {
        part: stagelight::farm::Part {
            index: number.index,
            count: number.count,
            split: Split::Tiles,
        },
        scene: part_scene_name(&args.scene),
        scene_hash: stagelight::farm::scene_hash(&args.scene, scene.source_hash, &scene.world),
    });
    if args.write_gltf {
        frame.inputs.write_gltf = Some(args.scene.clone());
    }
    run_and_report(
        &args.scene,
        &mut scene,
        frame,
        args.stats,
        args.stats_json.as_deref(),
    )
}

/// The refusal of `bake` (and `farm --bake`) for a scene without bake requests, its help in
/// the scene file's language.
fn no_bake_requests(scene: &Path) -> String {
    let ron = "add `bake: (resolution: (512, 512), outputs: [(kind: AmbientOcclusion())])` to an instance";
    let syntax = scene_syntax(scene);
    let converted = format!(
        "a {} file asks for no bakes: write the scene as RON (`{}`) and {ron} there",
        syntax.name(),
        stagelight::scene::syntax::convert_command(scene)
    );
    let help = syntax.help_each(stagelight::scene::syntax::Helps {
        ron,
        mi: &converted,
        rib: &converted,
        gltf: &converted,
    });
    format!(
        "error: {} has no bake requests\n  help: {help}",
        scene.display()
    )
}

fn bench(args: BenchArgs) -> ExitCode {
    if let Err(code) = set_threads(args.threads) {
        return code;
    }
    let mut scene = match load(&args.scene, &budget(args.memory_limit)) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let scratch = std::env::temp_dir().join(format!("stagelight-bench-{}", std::process::id()));
    let mut settings = scene.settings.clone();
    // A bench traces its photons: a kept photon map file would hide their cost.
    settings.photon_map = None;
    if let Some(integrator) = args.integrator {
        settings.integrator = integrator.integrator();
    }
    let mut frame = Frame::new(settings);
    // Outputs land in the scratch directory, under their own file names.
    frame.inputs.outputs.directory = Some(scratch.clone());
    frame.inputs.tasks = Tasks {
        render: true,
        bake: scene.world.query::<&BakeRequest>().iter().next().is_some(),
    };
    frame.inputs.bake_dir = scratch.join("bake");
    stagelight::bake::files::confine_to_bake_dir(&mut scene.world);
    frame.inputs.budget = budget(args.memory_limit);
    let refused = stagelight::budget::estimate::check(
        &scene.world,
        &frame.inputs.settings,
        frame.inputs.tasks,
        &frame.inputs.budget,
    );
    if !refused.is_empty() {
        for d in stagelight::guard::locate::options_located(&args.scene, refused) {
            errln!("{d}");
        }
        return ExitCode::from(EXIT_ERROR);
    }
    let cancel = frame.inputs.cancel.clone();
    let _ = ctrlc::set_handler(move || cancel.store(true, Ordering::SeqCst));
    let result = systems::run(&mut scene.world, &mut frame);
    let _ = std::fs::remove_dir_all(&scratch);
    match result {
        Ok(()) => {}
        Err(e) => {
            errln!("{e}");
            return ExitCode::from(e.exit_code());
        }
    }
    let photons = frame.outputs.photons.as_ref().map(|maps| {
        let seconds = frame
            .report
            .stages
            .iter()
            .find(|s| s.stage == "trace_photons" && s.ran)
            .map_or(0.0, |s| s.seconds);
        stagelight::photon::throughput::PhotonThroughput::new(maps, seconds, frame.report.threads)
    });
    if args.json {
        let value = serde_json::json!({
            "scene": args.scene.display().to_string(),
            "threads": frame.report.threads,
            "total_seconds": frame.report.total_seconds,
            "stages": frame.report.stages,
            "bakes": frame.outputs.bake_reports,
            "photons": photons,
        });
        match serde_json::to_string_pretty(&value) {
            Ok(j) => outln!("{j}"),
            Err(e) => {
                errln!("error: cannot encode the report: {e}");
                return ExitCode::from(EXIT_ERROR);
            }
        }
    } else {
        outln!(
            "{} on {} thread(s)",
            args.scene.display(),
            frame.report.threads
        );
        out!("{}", frame.report.to_throughput_table());
        if let Some(p) = photons {
            outln!("{}", p.line());
        }
        for r in &frame.outputs.bake_reports {
            outln!("bake {}", r.summary());
        }
    }
    ExitCode::SUCCESS
}

fn sweep(args: SweepArgs) -> ExitCode {
    use stagelight::sweep::{run_sweep, Knob, SweepFiles, SweepOptions};
    if let Err(code) = set_threads(args.threads) {
        return code;
    }
    let reference = args.reference.as_deref();
    if let Err(code) = usable_paths(&[
        stagelight::guard::dir_flags::usable_dir("--out", &args.out),
        reference.map_or(Ok(()), stagelight::sweep::reference_file::usable),
    ]) {
        return code;
    }
    let knob = match Knob::parse(&args.knob) {
        Ok(k) => k,
        Err(e) => {
            errln!("error: {e}");
            return ExitCode::from(EXIT_USAGE);
        }
    };
    let opts = SweepOptions {
        scene: args.scene.clone(),
        knob,
        seeds: args.seeds,
        reference: args.reference,
        reference_samples: args.reference_spp,
        out: args.out.clone(),
        integrator: args.integrator.map(IntegratorArg::integrator),
        reference_integrator: stagelight::settings::Integrator::Path,
        denoise: args.denoise,
        crop: args.crop,
        budget: budget(args.memory_limit),
        cancel: Arc::new(AtomicBool::new(false)),
        files: Arc::new(SweepFiles::new(&args.out)),
    };
    // SIGINT and SIGTERM stop the sweep as they stop a render: exit 130, no result written
    // (its scratch textures are removed; a reference it cached, complete, stays for the next
    // sweep).
    let (finished, written) = (opts.files.clone(), opts.files.clone());
    stagelight::guard::interrupt::install_with(
        opts.cancel.clone(),
        move || finished.result_in_place(),
        move || written.remove_partial(),
    );
    let summary = match run_sweep(&opts, systems::run, |step| errln!("sweep: {step}")) {
        Ok(s) => s,
        Err(e) => {
            errln!("{e}");
            return ExitCode::from(match &e {
                stagelight::sweep::SweepError::Stage(s) => s.exit_code(),
                stagelight::sweep::SweepError::Crop(_)
                | stagelight::sweep::SweepError::ReferenceSize(_)
                | stagelight::sweep::SweepError::Reference(_) => EXIT_USAGE,
                stagelight::sweep::SweepError::Knob(k) if k.is_usage() => EXIT_USAGE,
                _ => EXIT_ERROR,
            });
        }
    };
    let json = serde_json::to_string_pretty(&summary).unwrap_or_default();
    let svg = match stagelight::sweep::plot::svg(&summary) {
        Ok(s) => s,
        Err(e) => {
            errln!("error: cannot draw the plot: {e}");
            return ExitCode::from(EXIT_ERROR);
        }
    };
    let files = [
        ("sweep.csv", summary.to_csv()),
        ("sweep.json", json),
        ("sweep.svg", svg),
    ]
    .map(|(name, text)| {
        stagelight::image_io::PendingFile::new(args.out.join(name), text.into_bytes())
    });
    if opts.cancel.load(Ordering::SeqCst) {
        opts.files.remove_partial();
        errln!("{}", stagelight::stage_error::StageError::Interrupted);
        return ExitCode::from(stagelight::stage_error::EXIT_INTERRUPTED);
    }
    if let Err((p, e)) = opts.files.commit_result(&files) {
        errln!("error: cannot write {}: {e}", p.display());
        return ExitCode::from(EXIT_ERROR);
    }
    out!("{}", summary.to_csv());
    outln!("{}", summary.conclusion());
    for f in &files {
        errln!("wrote {}", f.path.display());
    }
    ExitCode::SUCCESS
}

/// Refuses clashing outputs, runs the stage table, commits the run's files together with
/// `--stats-json` (all or nothing) and prints what happened.
fn run_and_report(
    scene_path: &Path,
    scene: &mut LoadedScene,
    mut frame: Frame,
    stats: bool,
    stats_json: Option<&Path>,
) -> ExitCode {
    if let Err(code) = check_run(scene_path, scene, &frame.inputs, stats_json) {
        return code;
    }
    frame.inputs.progress = std::io::stderr().is_terminal();
    frame.inputs.hold_files = true;
    // SIGINT and SIGTERM both stop the run within half a second: exit 130, no file.
    stagelight::guard::interrupt::install(frame.inputs.cancel.clone());

    match systems::run(&mut scene.world, &mut frame) {
        Ok(()) => {}
        Err(e) => {
            errln!("{e}");
            return ExitCode::from(e.exit_code());
        }
    }
    if stats {
        out!("{}", frame.report.to_table());
        for r in &frame.outputs.bake_reports {
            outln!("bake {}", r.summary());
        }
    }
    if let Some(path) = stats_json {
        let value = serde_json::json!({
            "threads": frame.report.threads,
            "total_seconds": frame.report.total_seconds,
            "stages": frame.report.stages,
            "bakes": frame.outputs.bake_reports,
            "written": frame.report.written,
        });
        let json = match serde_json::to_string_pretty(&value) {
            Ok(j) => j,
            Err(e) => {
                errln!("error: cannot encode the report: {e}");
                return ExitCode::from(EXIT_ERROR);
            }
        };
        frame
            .held_files
            .push(stagelight::image_io::PendingFile::new(
                path.to_path_buf(),
                json.into_bytes(),
            ));
    }
    if frame.cancelled() {
        errln!("{}", stagelight::stage_error::StageError::Interrupted);
        return ExitCode::from(stagelight::stage_error::EXIT_INTERRUPTED);
    }
    if let Err((p, e)) = stagelight::image_io::commit_all(&frame.held_files) {
        errln!(
            "error: cannot write {}: {}; no file of this run was written",
            p.display(),
            stagelight::guard::io_reason(&e)
        );
        return ExitCode::from(EXIT_ERROR);
    }
    // Outputs of contour lines in a run that draws none are not written: said per file.
    let unwritten = (frame.inputs.tasks.render && frame.inputs.stop_after.is_none())
        .then(|| stagelight::scene_view::unwritten_outputs(&scene.world, &frame.inputs))
        .flatten();
    if let Some(u) = &unwritten {
        for path in &u.paths {
            errln!(
                "{}: warning: not written, no contours are drawn: {}",
                path.display(),
                u.why
            );
        }
    }
    for path in &frame.report.written {
        errln!("wrote {}", path.display());
    }
    if frame.inputs.stop_after.is_some() {
        for r in frame.report.stages.iter().filter(|r| !r.ran) {
            if r.stage == "trace_photons" {
                errln!("photon maps {}", r.reason);
            }
        }
    } else if frame.report.written.is_empty() && frame.inputs.tasks.render && unwritten.is_none() {
        errln!("note: the render camera has no outputs; nothing written (use -o FILE)");
    }
    ExitCode::SUCCESS
}
