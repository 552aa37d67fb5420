//! The per-run state, in three parts with one ownership rule each:
//!
//! - [`RunInputs`]: what the user asked for (settings with command-line overrides, tasks,
//!   output overrides, directories, progress, cancellation). Set before the run; read-only
//!   to every stage.
//! - [`StageOutputs`]: the typed output of each stage, each field written by exactly one
//!   stage (named on the field). Stages never write here themselves: a stage returns its
//!   output in its [`crate::schedule::Work`] and the runner stores it in the stage's declared
//!   slot. A skipped stage leaves its output `None`; consumers treat `None` as "no
//!   contribution".
//! - [`RunReport`]: filled by the runner only, including the files each stage wrote.
//! - [`Frame::held_files`]: the run's files, encoded but not written, when the caller asked
//!   to commit them itself (`RunInputs::hold_files`).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use crate::bake::BakeReport;
use crate::components::{ContourShader, ImageFormat, OutputSpec, Pass};
use crate::contour::ContourImage;
use crate::farm::PartRun;
use crate::framebuffer::FrameBuffers;
use crate::geometry::SceneGeometry;
use crate::image_io::PendingFile;
use crate::photon::PhotonMaps;
use crate::report::RunReport;
use crate::scene::syntax::{convert_command, Helps, Syntax};
use crate::settings::RenderSettings;
pub use crate::tasks::Tasks;

/// Where the render camera's outputs go, as the command line asked (pbrt's `--outfile`):
/// an option of the run, never an edit of the scene.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct OutputOverrides {
    /// `-o FILE`, format from the extension: an image (.png, .exr) replaces the camera's
    /// first image output, a vector drawing of the contours (.svg, .eps) its first vector
    /// output; either is added when the camera has none of its kind.
    pub first: Option<PathBuf>,
    /// Puts every output under this directory, keeping its file name (`stagelight bench`).
    pub directory: Option<PathBuf>,
    /// Writes no camera output at all (`stagelight sweep` compares images in memory).
    pub discard: bool,
}

impl OutputOverrides {
    /// Checks `-o`'s extension; the error is the message for the user.
    pub fn check(&self) -> Result<(), String> {
        match &self.first {
            Some(path) => format_from_extension(path).map(|_| ()),
            None => Ok(()),
        }
    }

    /// Checks that a vector `-o` (.svg, .eps) has contour lines to draw in `world`; the
    /// error is the message for the user, its help written in the `syntax` of the scene
    /// file `scene` (what to add to a mental ray `.mi` file or to RON; RIB and glTF have no
    /// contour shaders, so their help converts the scene to RON first).
    pub fn check_contours(
        &self,
        world: &hecs::World,
        syntax: Syntax,
        scene: &Path,
    ) -> Result<(), String> {
        let Some(path) = &self.first else {
            return Ok(());
        };
        let vector = format_from_extension(path).is_ok_and(is_vector);
        if vector && world.query::<&ContourShader>().iter().next().is_none() {
            let ron = "give a material `contour: Simple(color: (0, 0, 0, 1), width: 0.5)`";
            let converted = format!(
                "{} has no contour shaders: write the scene as RON (`{}`) and {ron} there",
                syntax.name(),
                convert_command(scene)
            );
            let help = syntax.help_each(Helps {
                ron,
                mi: "add `contour store \"contour_store_function\" ()` and `contour contrast \"contour_contrast_function_levels\" ()` to the options and `contour \"contour_shader_simple\" (\"color\" 0 0 0 1, \"width\" 0.5)` to a material",
                rib: &converted,
                gltf: &converted,
            });
            return Err(format!(
                "-o {} writes contour lines, but no material of the scene has a contour shader\n  help: {help}, or write a .png or .exr",
                path.display()
            ));
        }
        Ok(())
    }

    /// The warning for a `.png` `-o` that replaces a camera output (of those the camera
    /// lists as `outputs`) with passes a PNG cannot hold, naming the dropped passes; `None`
    /// when nothing is dropped.
    pub fn png_drops_passes(&self, outputs: &[OutputSpec]) -> Option<String> {
        let path = self.first.as_ref()?;
        if self.discard || format_from_extension(path).ok()? != ImageFormat::Png {
            return None;
        }
        let replaced = outputs.iter().find(|o| !is_vector(o.format))?;
        let dropped: Vec<String> = replaced
            .passes
            .iter()
            .filter(|p| !png_holds(**p))
            .map(|p| format!("{p:?}"))
            .collect();
        if dropped.is_empty() {
            return None;
        }
        Some(format!(
            "-o {} replaces the camera's output \"{}\" and drops its pass{} {}: a PNG holds only Beauty, Alpha and Contours\n  help: give -o an .exr file to keep every pass",
            path.display(),
            replaced.path.display(),
            if dropped.len() == 1 { "" } else { "es" },
            dropped.join(", ")
        ))
    }

    /// The outputs the run writes for a camera that lists `outputs`.
    pub fn apply(&self, outputs: &[OutputSpec]) -> Result<Vec<OutputSpec>, String> {
        if self.discard {
            return Ok(Vec::new());
        }
        let mut outputs = outputs.to_vec();
        if let Some(path) = &self.first {
            let format = format_from_extension(path)?;
            let replaced = outputs
                .iter()
                .position(|o| is_vector(o.format) == is_vector(format));
            let mut passes = match replaced {
                _ if is_vector(format) => vec![Pass::Contours],
                Some(k) => outputs[k].passes.clone(),
                None => vec![Pass::Beauty],
            };
            if format == ImageFormat::Png {
                passes.retain(|p| png_holds(*p));
                if passes.is_empty() {
                    passes.push(Pass::Beauty);
                }
            }
            let spec = OutputSpec {
                path: path.clone(),
                format,
                passes,
                beauty_alpha: replaced.is_none_or(|k| outputs[k].beauty_alpha),
            };
            match replaced {
                Some(k) => outputs[k] = spec,
                None => outputs.push(spec),
            }
        }
        if let Some(dir) = &self.directory {
            for (k, out) in outputs.iter_mut().enumerate() {
                let name = out
                    .path
                    .file_name()
                    .map(PathBuf::from)
                    .unwrap_or_else(|| PathBuf::from(format!("output_{k}")));
                out.path = dir.join(name);
            }
        }
        Ok(outputs)
    }
}

/// Whether a PNG output can hold `pass`.
fn png_holds(pass: Pass) -> bool {
    matches!(pass, Pass::Beauty | Pass::Alpha | Pass::Contours)
}

/// Whether `format` is a vector drawing of the contour lines rather than an image.
pub fn is_vector(format: ImageFormat) -> bool {
    matches!(format, ImageFormat::Svg | ImageFormat::Eps)
}

/// The output format named by a file's extension (`.png`, `.exr`, `.svg`, `.eps`); the error
/// is the message for the user, with its `help:` line.
pub fn format_from_extension(path: &Path) -> Result<ImageFormat, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(ImageFormat::Png),
        Some("exr") => Ok(ImageFormat::Exr),
        Some("svg") => Ok(ImageFormat::Svg),
        Some("eps") => Ok(ImageFormat::Eps),
        _ => Err(format!(
            "cannot tell the output format of {} from its extension\n  help: name a .png or .exr file for the image, or an .svg or .eps file for the contour lines",
            path.display()
        )),
    }
}

/// Everything the user asked for; read-only to stages.
#[derive(Debug, Clone)]
pub struct RunInputs {
    /// Render settings (scene `options` plus command-line overrides).
    pub settings: RenderSettings,
    /// What to do: render, bake or both.
    pub tasks: Tasks,
    /// Where camera outputs go when the command line redirects them.
    pub outputs: OutputOverrides,
    /// Directory for baked textures (relative paths resolve against the working directory).
    pub bake_dir: PathBuf,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Set from another thread (SIGINT, SIGTERM) to stop the run; stages poll it.
    pub cancel: Arc<AtomicBool>,
    /// Render only this farm part and write its part file (`render --part K/N`).
    pub part: Option<PartRun>,
    /// The image merged from part files (`stagelight merge`): `shade` passes it on instead
    /// of rendering, and the stages that only feed rendering skip.
    pub merged_image: Option<FrameBuffers>,
    /// The bake merged from bake part files (`stagelight merge`): `bake_lightmaps` dilates
    /// and encodes these texels instead of baking.
    pub merged_bake: Option<crate::farm::bake_part::MergedBake>,
    /// The memory budget the run's estimates are held to (see [`crate::budget`]).
    pub budget: crate::budget::Budget,
    /// Leave the run's files in [`Frame::held_files`] instead of committing them, so that the
    /// caller commits them together with its own (all or nothing).
    pub hold_files: bool,
    /// The glTF scene to write back with its baked textures (`bake --write-gltf`): the
    /// `bake_lightmaps` stage adds `<bake_dir>/<stem>.glb` to its files.
    pub write_gltf: Option<PathBuf>,
    /// `--photon-cache DIR`: photon maps are loaded from and kept in `DIR/<hash>.pmap`
    /// (before the scene's `photon_map` file).
    pub photon_cache: Option<PathBuf>,
    /// Run the stage table only through this stage (`stagelight photons` stops after
    /// `trace_photons`); `None`: every stage.
    pub stop_after: Option<&'static str>,
    /// The caller reads the rendered image from the frame (library use; the default). The
    /// command line's `render` clears it: the image is then read only through the camera's
    /// outputs or a part file, and with neither [`crate::scene_view::image_is_read`] is false and the
    /// stages that only feed the image skip.
    pub caller_keeps_image: bool,
}

impl RunInputs {
    /// Whether the image comes from merged part files rather than from rendering.
    pub fn merging(&self) -> bool {
        self.merged_image.is_some()
    }
}

/// A stage output slot: which field of [`StageOutputs`] a stage writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    /// [`StageOutputs::geometry`].
    Geometry,
    /// [`StageOutputs::photons`].
    Photons,
    /// [`StageOutputs::image`].
    Image,
    /// [`StageOutputs::bake_reports`].
    BakeReports,
    /// [`StageOutputs::contours`].
    Contours,
}

/// A stage's typed result, stored by the runner in the stage's slot.
pub enum StageOutput {
    /// World-space triangles, their BVH and shading attributes.
    Geometry(SceneGeometry),
    /// The caustic and global photon maps.
    Photons(PhotonMaps),
    /// The render camera's frame buffers.
    Image(FrameBuffers),
    /// One report per bake request.
    BakeReports(Vec<BakeReport>),
    /// The contour lines and their layer.
    Contours(ContourImage),
}

impl StageOutput {
    /// The slot this output belongs in.
    pub fn slot(&self) -> Slot {
        match self {
            StageOutput::Geometry(_) => Slot::Geometry,
            StageOutput::Photons(_) => Slot::Photons,
            StageOutput::Image(_) => Slot::Image,
            StageOutput::BakeReports(_) => Slot::BakeReports,
            StageOutput::Contours(_) => Slot::Contours,
        }
    }
}

/// The outputs of the stages, each with exactly one writer.
#[derive(Default)]
pub struct StageOutputs {
    /// Written by `build_accel`: world-space triangles, their BVH and shading attributes.
    pub geometry: Option<SceneGeometry>,
    /// Written by `trace_photons`: the caustic and global photon maps.
    pub photons: Option<PhotonMaps>,
    /// Written by `shade`: the render camera's frame buffers.
    pub image: Option<FrameBuffers>,
    /// Written by `bake_lightmaps`: one report per bake request.
    pub bake_reports: Vec<BakeReport>,
    /// Written by `draw_contours`: the contour lines and their rasterised layer.
    pub contours: Option<ContourImage>,
    /// Slots promised by stages a plan expects to run (`stagelight plan` runs no stage, so
    /// later run conditions ask [`StageOutputs::has`] instead of looking at the data).
    promised: Vec<Slot>,
}

impl StageOutputs {
    /// Whether `slot` holds data, or a stage planned to run before now will fill it.
    pub fn has(&self, slot: Slot) -> bool {
        self.promised.contains(&slot)
            || match slot {
                Slot::Geometry => self.geometry.is_some(),
                Slot::Photons => self.photons.is_some(),
                Slot::Image => self.image.is_some(),
                Slot::BakeReports => !self.bake_reports.is_empty(),
                Slot::Contours => self.contours.is_some(),
            }
    }

    /// Records that a planned stage will fill `slot` (planning only).
    pub(crate) fn promise(&mut self, slot: Slot) {
        self.promised.push(slot);
    }

    /// Stores a stage's output in its slot.
    pub(crate) fn store(&mut self, output: StageOutput) {
        match output {
            StageOutput::Geometry(g) => self.geometry = Some(g),
            StageOutput::Photons(p) => self.photons = Some(p),
            StageOutput::Image(i) => self.image = Some(i),
            StageOutput::BakeReports(r) => self.bake_reports = r,
            StageOutput::Contours(c) => self.contours = Some(c),
        }
    }
}

/// The whole per-run state: inputs, stage outputs and the report.
pub struct Frame {
    /// What the user asked for (read-only to stages).
    pub inputs: RunInputs,
    /// Each stage's output (stored by the runner).
    pub outputs: StageOutputs,
    /// Per-stage report (written by the runner).
    pub report: RunReport,
    /// The run's encoded files, not yet written, when `inputs.hold_files` is set (written by
    /// the runner).
    pub held_files: Vec<PendingFile>,
}

impl Frame {
    /// A fresh frame for a render with `settings` and no stage outputs yet.
    pub fn new(settings: RenderSettings) -> Self {
        Self {
            inputs: RunInputs {
                settings,
                tasks: Tasks::default(),
                outputs: OutputOverrides::default(),
                bake_dir: PathBuf::from("."),
                progress: false,
                cancel: Arc::new(AtomicBool::new(false)),
                part: None,
                merged_image: None,
                merged_bake: None,
                budget: crate::budget::Budget::unlimited(),
                hold_files: false,
                write_gltf: None,
                photon_cache: None,
                stop_after: None,
                caller_keeps_image: true,
            },
            outputs: StageOutputs::default(),
            report: RunReport::default(),
            held_files: Vec::new(),
        }
    }

    /// Whether the run was interrupted.
    pub fn cancelled(&self) -> bool {
        self.inputs.cancel.load(Ordering::Relaxed)
    }
}
