//! `draw_contours`: mental ray's contour output — finds the edges of the contour store
//! between neighbouring pixel samples that the contour contrast asks for, places each by
//! bisection with extra camera rays, links them into polylines, styles each point with the
//! contour shader of the material on the front side, and rasterises the lines into an
//! anti-aliased RGBA contour layer (library: `crate::contour`).
//!
//! **Reads:** `outputs.image` (its `contour_store`), `outputs.geometry` (bisection rays),
//! the render `Camera` with its `Lenses`, `ContourShader` and `Name` of material entities,
//! the scene's `ContourContrast` (defaults without one).
//! **Writes:** `outputs.contours` (the lines — points, colour and width per point — and the
//! layer), returned to the runner.
//! **Runs when:** a shaded image exists, some material has a contour shader, output shaders
//! are on, some contrast criterion is on (`ContourContrast::any_on`), an output of the run
//! shows contours (an SVG or EPS, or a `Contours` pass), and the run is not a farm part (parts carry no contours: `stagelight merge` draws them from the
//! merged image, with the geometry stages run again for the bisection rays) — one answer,
//! `crate::scene_view::contours_drawn`, shared with `shade` and the merge's geometry stages.
//! **After this stage:** `outputs.contours` holds lines that depend only on the scene and
//! the image (not on the thread count), and a layer of the camera's resolution.

use hecs::World;

use super::prelude::*;
use crate::components::{ContourContrast, ContourShader, Name};
use crate::contour::contrast::{find_crossings, Contrast};
use crate::contour::linking::link;
use crate::contour::raster::rasterise;
use crate::contour::shaders::styled_lines;
use crate::contour::{ContourImage, Probe};
use crate::frame::Slot;
use crate::scene_view::render_view;
use crate::shading::CameraRays;

/// Run condition: an image, and contours to draw
/// ([`crate::scene_view::contours_drawn`]: contour shaders, output shaders on, not a farm
/// part, a contrast criterion on, an output showing them).
pub fn should_run(world: &World, frame: &Frame) -> Decision {
    // Why no contours are drawn comes first: it is also why `shade` made no image when
    // the only outputs hold contour lines.
    let n = match crate::scene_view::contours_drawn(world, &frame.inputs) {
        Ok(n) => n,
        Err(why) => return Decision::skip(why),
    };
    if !frame.outputs.has(Slot::Image) {
        return Decision::skip("no shaded image");
    }
    Decision::run(format!("{n} material(s) with a contour shader"))
}

/// Finds, links, styles and rasterises the contour lines.
pub fn run(world: &World, frame: &Frame) -> Result<Work, StageError> {
    let fb = frame
        .outputs
        .image
        .as_ref()
        .ok_or_else(|| StageError::Internal("no image".into()))?;
    let store = fb
        .contour_store
        .as_ref()
        .ok_or_else(|| StageError::Internal("shade kept no contour store".into()))?;
    let view = render_view(world)
        .ok_or_else(|| StageError::Internal("no render camera".into()))?
        .without(frame.inputs.settings.disabled);
    let rays = CameraRays::with_lenses(&view.camera, &view.lenses);
    let geometry = frame.outputs.geometry.as_ref();
    let entities = geometry.map_or(&[][..], |g| &g.material_entities[..]);
    let shaders: Vec<Option<ContourShader>> = entities
        .iter()
        .map(|&e| world.get::<&ContourShader>(e).ok().map(|s| *s))
        .collect();
    let material_names: Vec<String> = entities
        .iter()
        .map(|&e| {
            world
                .get::<&Name>(e)
                .map_or_else(|_| String::new(), |n| n.0.clone())
        })
        .collect();
    let settings = world
        .query::<&ContourContrast>()
        .iter()
        .next()
        .copied()
        .unwrap_or_default();
    let has_shader = |s: &crate::contour::ContourSample| {
        s.material
            .checked_sub(1)
            .and_then(|m| shaders.get(m as usize))
            .is_some_and(Option::is_some)
    };
    let min_dimension = fb.width.min(fb.height) as f32;
    let contrast = Contrast::new(settings);
    // Deeper levels first: what mirrors and refractions show lies behind the first hits'
    // lines, which are drawn over it.
    let mut lines = Vec::new();
    for level in store.deeper.iter().rev().chain([store]) {
        let probe = Probe::new(geometry, &rays).at_level(level.level);
        let crossings = find_crossings(level, &probe, &contrast, &has_shader);
        if frame.cancelled() {
            return Err(StageError::Interrupted);
        }
        let chains = link(&crossings);
        lines.extend(styled_lines(chains, &shaders, min_dimension, level.level));
    }
    let layer = rasterise(&lines, fb.width, fb.height);
    let points: usize = lines.iter().map(|l| l.points.len()).sum();
    let image = ContourImage {
        width: fb.width,
        height: fb.height,
        lines,
        material_names,
        layer,
    };
    Ok(Work::new(points as u64, "line points").with_output(StageOutput::Contours(image)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::systems::tiny_scene::{load, run_until, scene};

    #[test]
    fn outlines_the_square_only_when_its_material_has_a_contour_shader() {
        let text = scene("", "", "", &[]).replace(
            "shader: Lambert(albedo: (0.5, 0.5, 0.5))",
            "shader: Lambert(albedo: (0.5, 0.5, 0.5)), contour: Simple(color: (1, 0, 0, 1), width: 10.0)",
        ).replace("passes: [Beauty]", "passes: [Beauty, Contours]");
        let (mut world, mut frame) = load(&text, false);
        run_until("draw_contours", &mut world, &mut frame);
        assert_eq!(
            should_run(&world, &frame),
            Decision::run("1 material(s) with a contour shader")
        );
        let work = run(&world, &frame).unwrap();
        let Some(StageOutput::Contours(image)) = work.output else {
            panic!("draw_contours returns the contours");
        };
        // The square's outline is one closed loop.
        assert_eq!(image.lines.len(), 1);
        assert!(image.lines[0].closed);
        assert!(image.layer.iter().any(|c| c.w > 0.99));
        assert_eq!(image.material_names, ["grey"]);
    }

    #[test]
    fn skipped_without_a_contour_shader() {
        let (mut world, mut frame) = load(&scene("", "", "", &[]), false);
        run_until("draw_contours", &mut world, &mut frame);
        assert_eq!(
            should_run(&world, &frame),
            Decision::skip("no material in use has a contour shader")
        );
        assert!(frame.outputs.image.unwrap().contour_store.is_none());
    }
}
