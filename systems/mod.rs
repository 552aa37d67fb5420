//! The stage table: the whole frame order in one place, each stage with its run condition,
//! the data it reads and writes, and its body. The documentation table below is generated
//! from [`STAGES`] (`stagelight plan --table`) and a unit test keeps it equal:
//!
//! <!-- stage table start -->
//! | order | stage | runs when | reads | writes |
//! | --- | --- | --- | --- | --- |
//! | 1 | `expand_geometry` | any object has procedural geometry (`Procedural`, `Scatter`) | `Procedural`, `Scatter`, scatter surfaces and prototypes | meshes or `Surface`s on objects; scatter copies as instances (world) |
//! | 2 | `tessellate` | a parametric surface, subdivision mesh or true displacement exists (or a quadric waits for expansion) | `Surface`, `SubdivMesh`, `Displacement`, `Approximation`, render camera (raster-space rates) | triangle meshes on objects and their instances (world) |
//! | 3 | `build_accel` | instances with triangles (or geometry pending) and a render camera or bake request in this run, not a farm part that owns nothing (a render part without pixels or samples; a bake part past the last texel tile of fixed-size texture requests) | `Instance`, `WorldFromObject`, `MaterialRef`, `Material`, bump `Displacement`, `settings.bvh_quality` | `outputs.geometry` |
//! | 4 | `trace_photons` | caustics or global illumination on (caustics with a caster), a `Direct` render whose samples an output reads (not only pixel-centre passes) or a photon diagnostic view, geometry, a surface that receives and stores photons, a light with power | `Emitter`s, `outputs.geometry`, `settings.photons` | `outputs.photons` |
//! | 5 | `bake_lightmaps` | bake requests, in a run that bakes (a bake part that owns no texel: only its empty part file) | `BakeRequest`s, `Emitter`s, `Environment`, `outputs.geometry`, `inputs.bake_dir`, `inputs.write_gltf` | texture files (and the baked glTF copy); `outputs.bake_reports` |
//! | 6 | `shade` | a render camera, in a run that renders (a farm part: one that owns pixels or samples); only the pixel-centre rays when no output reads a sample, none of them when nothing reads a pixel-centre pass | render camera, lenses, atmosphere, `Interior`s, `Emitter`s, `Environment`, `outputs.geometry`, `outputs.photons` | `outputs.image` |
//! | 7 | `draw_contours` | a shaded image, a material with a contour shader, a contrast criterion on, an output showing contours, not a farm part | `outputs.image` (contour store), `outputs.geometry`, render camera, `ContourShader`s, `ContourContrast` | `outputs.contours` |
//! | 8 | `write_output` | a shaded image and outputs to write (SVG/EPS only when contours are drawn), or a farm part that owns nothing (its empty part file) | `outputs.image`, `outputs.contours`, camera outputs with `inputs.outputs` overrides, `Imager` | image files, SVG contour lines |
//! <!-- stage table end -->

pub mod bake_lightmaps;
pub mod build_accel;
pub mod draw_contours;
pub mod expand_geometry;
pub mod shade;
pub mod tessellate;
pub mod trace_photons;
pub mod write_output;

#[cfg(test)]
mod tiny_scene;

use hecs::World;

use crate::frame::Slot;
use crate::schedule::{PlannedStage, StageBody};
use prelude::*;

/// Imports shared by the stage modules.
mod prelude {
    pub use crate::frame::{Frame, StageOutput};
    pub use crate::schedule::{Decision, Stage, StageError, Work};
}

/// Why the stages that only feed rendering skip in `stagelight merge`.
pub const MERGING: &str = "the image is merged from part files";

/// Why a geometry stage skips in `stagelight merge`, if it does: always unless the merge
/// draws contours ([`crate::scene_view::contours_drawn`]), whose contour store and
/// bisection rays need the scene geometry. The reason is [`MERGING`], followed by why no
/// contours are drawn when a material has a contour shader.
pub fn merge_skip(world: &World, frame: &Frame) -> Option<String> {
    if !frame.inputs.merging() {
        return None;
    }
    if !crate::schedule::any_with::<crate::components::ContourShader>(world) {
        return Some(MERGING.into());
    }
    let why = crate::scene_view::contours_drawn(world, &frame.inputs).err()?;
    Some(format!("{MERGING}; no contours are drawn: {why}"))
}

/// The ordered stage table.
pub const STAGES: &[Stage] = &[
    Stage {
        name: "expand_geometry",
        runs_when: "any object has procedural geometry (`Procedural`, `Scatter`)",
        reads: "`Procedural`, `Scatter`, scatter surfaces and prototypes",
        writes: "meshes or `Surface`s on objects; scatter copies as instances (world)",
        slot: None,
        condition: expand_geometry::should_run,
        body: StageBody::EditsWorld(expand_geometry::run),
    },
    Stage {
        name: "tessellate",
        runs_when: "a parametric surface, subdivision mesh or true displacement exists (or a quadric waits for expansion)",
        reads: "`Surface`, `SubdivMesh`, `Displacement`, `Approximation`, render camera (raster-space rates)",
        writes: "triangle meshes on objects and their instances (world)",
        slot: None,
        condition: tessellate::should_run,
        body: StageBody::EditsWorld(tessellate::run),
    },
    Stage {
        name: "build_accel",
        runs_when: "instances with triangles (or geometry pending) and a render camera or bake request in this run, not a farm part that owns nothing (a render part without pixels or samples; a bake part past the last texel tile of fixed-size texture requests)",
        reads: "`Instance`, `WorldFromObject`, `MaterialRef`, `Material`, bump `Displacement`, `settings.bvh_quality`",
        writes: "`outputs.geometry`",
        slot: Some(Slot::Geometry),
        condition: build_accel::should_run,
        body: StageBody::ReadsWorld(build_accel::run),
    },
    Stage {
        name: "trace_photons",
        runs_when: "caustics or global illumination on (caustics with a caster), a `Direct` render whose samples an output reads (not only pixel-centre passes) or a photon diagnostic view, geometry, a surface that receives and stores photons, a light with power",
        reads: "`Emitter`s, `outputs.geometry`, `settings.photons`",
        writes: "`outputs.photons`",
        slot: Some(Slot::Photons),
        condition: trace_photons::should_run,
        body: StageBody::ReadsWorld(trace_photons::run),
    },
    Stage {
        name: "bake_lightmaps",
        runs_when: "bake requests, in a run that bakes (a bake part that owns no texel: only its empty part file)",
        reads: "`BakeRequest`s, `Emitter`s, `Environment`, `outputs.geometry`, `inputs.bake_dir`, `inputs.write_gltf`",
        writes: "texture files (and the baked glTF copy); `outputs.bake_reports`",
        slot: Some(Slot::BakeReports),
        condition: bake_lightmaps::should_run,
        body: StageBody::ReadsWorld(bake_lightmaps::run),
    },
    Stage {
        name: "shade",
        runs_when: "a render camera, in a run that renders (a farm part: one that owns pixels or samples); only the pixel-centre rays when no output reads a sample, none of them when nothing reads a pixel-centre pass",
        reads: "render camera, lenses, atmosphere, `Interior`s, `Emitter`s, `Environment`, `outputs.geometry`, `outputs.photons`",
        writes: "`outputs.image`",
        slot: Some(Slot::Image),
        condition: shade::should_run,
        body: StageBody::ReadsWorld(shade::run),
    },
    Stage {
        name: "draw_contours",
        runs_when: "a shaded image, a material with a contour shader, a contrast criterion on, an output showing contours, not a farm part",
        reads: "`outputs.image` (contour store), `outputs.geometry`, render camera, `ContourShader`s, `ContourContrast`",
        writes: "`outputs.contours`",
        slot: Some(Slot::Contours),
        condition: draw_contours::should_run,
        body: StageBody::ReadsWorld(draw_contours::run),
    },
    Stage {
        name: "write_output",
        runs_when: "a shaded image and outputs to write (SVG/EPS only when contours are drawn), or a farm part that owns nothing (its empty part file)",
        reads: "`outputs.image`, `outputs.contours`, camera outputs with `inputs.outputs` overrides, `Imager`",
        writes: "image files, SVG contour lines",
        slot: None,
        condition: write_output::should_run,
        body: StageBody::ReadsWorld(write_output::run),
    },
];

/// Runs the table over `world` (through `frame.inputs.stop_after` when set); the report
/// lands in `frame.report`.
pub fn run(world: &mut World, frame: &mut Frame) -> Result<(), StageError> {
    let end = frame
        .inputs
        .stop_after
        .and_then(|last| STAGES.iter().position(|s| s.name == last))
        .map_or(STAGES.len(), |i| i + 1);
    crate::schedule::run_stages(&STAGES[..end], world, frame)
}

/// Runs the stages before the one named `name` (as [`run`] would), leaving their outputs in
/// `frame`: how benches and tools prepare the inputs of one stage.
pub fn run_before(name: &str, world: &mut World, frame: &mut Frame) -> Result<(), StageError> {
    let end = STAGES
        .iter()
        .position(|s| s.name == name)
        .ok_or_else(|| StageError::Internal(format!("no stage named {name}")))?;
    crate::schedule::run_stages(&STAGES[..end], world, frame)
}

/// What each stage would do for this world and these inputs, without running any.
pub fn plan(world: &World, frame: &mut Frame) -> Vec<PlannedStage> {
    crate::schedule::plan(STAGES, world, frame)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table in this module's header is the one generated from `STAGES`.
    #[test]
    fn documented_table_matches_the_stage_table() {
        let source = include_str!("mod.rs");
        let start = source.find("<!-- stage table start -->").unwrap();
        let end = source.find("<!-- stage table end -->").unwrap();
        let documented: String = source[start..end]
            .lines()
            .skip(1)
            .map(|l| l.trim_start_matches("//!").trim_start())
            .filter(|l| !l.is_empty())
            .map(|l| format!("{l}\n"))
            .collect();
        assert_eq!(documented, crate::schedule::stage_table_markdown(STAGES));
    }

    /// Stage names are the module names, unique, and only geometry stages edit the world.
    #[test]
    fn names_are_unique_and_only_geometry_stages_edit_the_world() {
        let mut names: Vec<_> = STAGES.iter().map(|s| s.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), STAGES.len());
        for s in STAGES {
            let edits = matches!(s.body, StageBody::EditsWorld(_));
            assert_eq!(
                edits,
                ["expand_geometry", "tessellate"].contains(&s.name),
                "{}",
                s.name
            );
        }
        let slots: Vec<_> = STAGES.iter().filter_map(|s| s.slot).collect();
        for (i, a) in slots.iter().enumerate() {
            assert!(!slots[i + 1..].contains(a), "two writers of {a:?}");
        }
    }
}
