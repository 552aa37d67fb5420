//! The `stagelight` command line: a thin front end over the scene loader and the stage table.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::Ordering;

use clap::{Args, Parser, Subcommand};
use stagelight::components::{Camera, ImageFormat, OutputSpec, Pass, RenderCamera};
use stagelight::frame::Frame;
use stagelight::scene::{load_scene, LoadedScene};
use stagelight::schedule::StageError;
use stagelight::systems;

/// Exit code for scene and runtime errors.
const EXIT_ERROR: u8 = 1;
/// Exit code for command-line usage errors.
const EXIT_USAGE: u8 = 2;
/// Exit code after SIGINT (128 + 2).
const EXIT_INTERRUPTED: u8 = 130;

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
    /// Validate a scene without rendering; exit 0 when it is renderable.
    Check {
        /// Scene file (RON).
        scene: PathBuf,
    },
}

#[derive(Args)]
struct RenderArgs {
    /// Scene file (RON).
    scene: PathBuf,
    /// Write the image here instead of the camera's first output (format from the extension:
    /// .png or .exr).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Samples per pixel (overrides the scene's `options.samples`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    spp: Option<u32>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    threads: Option<u32>,
    /// Random seed (overrides the scene's `options.seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Radiance integrator (overrides the scene's `options.integrator`).
    #[arg(long, value_enum)]
    integrator: Option<IntegratorArg>,
    /// Print the per-stage report.
    #[arg(long)]
    stats: bool,
    /// Write the per-stage report as JSON.
    #[arg(long = "stats-json", value_name = "FILE")]
    stats_json: Option<PathBuf>,
}

/// `--integrator` values.
#[derive(Clone, Copy, clap::ValueEnum)]
enum IntegratorArg {
    /// Direct lighting with traced mirror/refraction rays.
    Direct,
    /// Unbiased path tracing (the reference).
    Path,
}

fn main() -> ExitCode {
    let _ = tracing_subscriber::fmt()
        .with_writer(std::io::stderr)
        .with_target(false)
        .without_time()
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
    match cli.command {
        Command::Check { scene } => check(&scene),
        Command::Render(args) => render(args),
    }
}

fn load(path: &Path) -> Result<LoadedScene, ExitCode> {
    match load_scene(path) {
        Ok(scene) => {
            for w in &scene.warnings {
                eprintln!("warning: {w}");
            }
            Ok(scene)
        }
        Err(errors) => {
            eprintln!("{errors}");
            let n = errors.0.len();
            eprintln!(
                "{n} error{} in {}; nothing rendered",
                if n == 1 { "" } else { "s" },
                path.display()
            );
            Err(ExitCode::from(EXIT_ERROR))
        }
    }
}

fn check(path: &Path) -> ExitCode {
    match load(path) {
        Ok(scene) => {
            let entities = scene.world.len();
            println!("{}: ok ({entities} entities)", path.display());
            ExitCode::SUCCESS
        }
        Err(code) => code,
    }
}

fn format_from_extension(path: &Path) -> Option<ImageFormat> {
    match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "png" => Some(ImageFormat::Png),
        "exr" => Some(ImageFormat::Exr),
        _ => None,
    }
}

/// Points the render camera's first output at `path` (or adds one).
fn override_output(world: &mut hecs::World, path: &Path) -> Result<(), String> {
    let format = format_from_extension(path).ok_or_else(|| {
        format!(
            "cannot tell the image format of {}: use a .png or .exr extension",
            path.display()
        )
    })?;
    let mut query = world.query::<(&mut Camera, &RenderCamera)>();
    let Some((camera, _)) = query.iter().next() else {
        return Err("the scene has no render camera".into());
    };
    let mut passes = camera
        .outputs
        .first()
        .map(|o| o.passes.clone())
        .unwrap_or_else(|| vec![Pass::Beauty]);
    if format == ImageFormat::Png {
        passes.retain(|p| matches!(p, Pass::Beauty | Pass::Alpha));
        if passes.is_empty() {
            passes.push(Pass::Beauty);
        }
    }
    let spec = OutputSpec {
        path: path.to_path_buf(),
        format,
        passes,
    };
    if camera.outputs.is_empty() {
        camera.outputs.push(spec);
    } else {
        camera.outputs[0] = spec;
    }
    Ok(())
}

fn render(args: RenderArgs) -> ExitCode {
    if let Some(threads) = args.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(threads as usize)
            .build_global()
        {
            eprintln!("error: cannot start {threads} worker threads: {e}");
            return ExitCode::from(EXIT_ERROR);
        }
    }
    let mut scene = match load(&args.scene) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut settings = scene.settings.clone();
    if let Some(spp) = args.spp {
        settings.spp = spp;
    }
    if let Some(seed) = args.seed {
        settings.seed = seed;
    }
    if let Some(integrator) = args.integrator {
        settings.integrator = match integrator {
            IntegratorArg::Direct => stagelight::settings::Integrator::Direct,
            IntegratorArg::Path => stagelight::settings::Integrator::Path,
        };
    }
    if let Some(out) = &args.output {
        if let Err(message) = override_output(&mut scene.world, out) {
            eprintln!("error: {message}");
            return ExitCode::from(EXIT_USAGE);
        }
    }
    let mut frame = Frame::new(settings);
    frame.progress = std::io::stderr().is_terminal();
    let cancel = frame.cancel.clone();
    let _ = ctrlc::set_handler(move || cancel.store(true, Ordering::SeqCst));

    let result = systems::run(&mut scene.world, &mut frame);
    match result {
        Ok(()) => {}
        Err(StageError::Interrupted) => {
            eprintln!("interrupted; no output written");
            return ExitCode::from(EXIT_INTERRUPTED);
        }
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(EXIT_ERROR);
        }
    }
    if args.stats {
        print!("{}", frame.report.to_table());
    }
    if let Some(path) = &args.stats_json {
        let json = match serde_json::to_string_pretty(&frame.report) {
            Ok(j) => j,
            Err(e) => {
                eprintln!("error: cannot encode the report: {e}");
                return ExitCode::from(EXIT_ERROR);
            }
        };
        let file = stagelight::image_io::PendingFile {
            path: path.clone(),
            bytes: json.into_bytes(),
        };
        if let Err((p, e)) = stagelight::image_io::commit_all(&[file]) {
            eprintln!("error: cannot write {}: {e}", p.display());
            return ExitCode::from(EXIT_ERROR);
        }
    }
    for path in &frame.written {
        eprintln!("wrote {}", path.display());
    }
    if frame.written.is_empty() {
        eprintln!("note: the render camera has no outputs; nothing written (use -o FILE)");
    }
    ExitCode::SUCCESS
}
