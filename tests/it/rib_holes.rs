//! RIB polygons with holes: the first loop of a `GeneralPolygon` (of each polygon of a
//! `PointsGeneralPolygons`) is its outline, the others are holes, which show what is behind;
//! a polygon too intricate to cut within the step limit is a located error.

use std::path::Path;

use glam::Vec3;
use stagelight::scene::load_scene_str;

/// The beauty image of `polygon` in white (`constant`) on black, 32 × 32 pixels over the
/// square [−1, 1]² of the plane z = 1 (16 pixels a unit).
fn render(polygon: &str) -> Vec<Vec3> {
    let text = format!(
        "Format 32 32 1\nPixelSamples 1 1\nPixelFilter \"gaussian\" 0.0001 0.0001\n\
         Projection \"perspective\" \"fov\" [90]\nWorldBegin\nSurface \"constant\"\n\
         Translate 0 0 1\n{polygon}\nWorldEnd\n"
    );
    let mut scene =
        load_scene_str(&text, Path::new("t.rib")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert!(
        scene.located_warnings.is_empty(),
        "{:?}",
        scene.located_warnings
    );
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("an image").beauty
}

/// White pixels, and whether the pixel at the centre of the hole is black.
fn coverage(image: &[Vec3]) -> (usize, bool) {
    let white = image.iter().filter(|p| p.min_element() > 0.5).count();
    let centre = image[16 * 32 + 16].max_element() < 1e-6;
    (white, centre)
}

/// A square of side 1.5 (24 × 24 pixels) with a square hole of side 0.5 (8 × 8 pixels):
/// 576 − 64 = 512 white pixels.
const OUTLINE: &str = "-0.75 -0.75 0  0.75 -0.75 0  0.75 0.75 0  -0.75 0.75 0";
const HOLE: &str = "-0.25 -0.25 0  -0.25 0.25 0  0.25 0.25 0  0.25 -0.25 0";

#[test]
fn a_general_polygon_shows_the_background_through_its_hole() {
    let image = render(&format!("GeneralPolygon [4 4] \"P\" [{OUTLINE}  {HOLE}]"));
    let (white, centre_black) = coverage(&image);
    assert!(centre_black, "the hole shows the background");
    assert!(
        white.abs_diff(512) <= 24,
        "{white} white pixels, expected 512 ± one row"
    );
    // The hole wound the same way as the outline is a hole too.
    let same_way = "-0.25 -0.25 0  0.25 -0.25 0  0.25 0.25 0  -0.25 0.25 0";
    let image = render(&format!(
        "GeneralPolygon [4 4] \"P\" [{OUTLINE}  {same_way}]"
    ));
    assert_eq!(coverage(&image), (white, true));
}

#[test]
fn points_general_polygons_cut_each_polygon_by_its_own_holes() {
    let image = render(&format!(
        "PointsGeneralPolygons [2] [4 4] [0 1 2 3 4 5 6 7] \"P\" [{OUTLINE}  {HOLE}]"
    ));
    let (white, centre_black) = coverage(&image);
    assert!(centre_black, "the hole shows the background");
    assert!(
        white.abs_diff(512) <= 24,
        "{white} white pixels, expected 512 ± one row"
    );
}

#[test]
fn a_polygon_too_intricate_to_cut_is_a_located_error_not_a_hang() {
    // A comb of 10,000 teeth with a hole along its back: every cut along the back sees the
    // whole comb. The former clipping took 7 s of CPU on it; the cut stops at its step
    // limit (docs/rib.md, Holes) and says so at `nvertices`.
    let mut points = vec![(0.0, 0.0), (20_000.0, 0.0)];
    for t in (0..10_000).rev() {
        let x = 2.0 * t as f64;
        points.extend([
            (x + 2.0, 1.0),
            (x + 1.5, 4.0),
            (x + 1.0, 4.0),
            (x + 1.0, 1.0),
        ]);
    }
    points.dedup();
    let outline = points.len();
    points.extend([(1.5, 0.25), (1.5, 0.75), (19_999.5, 0.75), (19_999.5, 0.25)]);
    let p: Vec<String> = points.iter().map(|(x, y)| format!("{x} {y} 0")).collect();
    let text = format!(
        "Format 32 32 1\nWorldBegin\nGeneralPolygon [{outline} 4] \"P\" [{}]\nWorldEnd\n",
        p.join(" ")
    );
    let start = std::time::Instant::now();
    let errors = load_scene_str(&text, Path::new("t.rib"))
        .err()
        .expect("refused");
    assert!(start.elapsed().as_secs_f64() < 10.0);
    assert_eq!(
        errors.0[0].to_string(),
        "t.rib:3:16: error: polygon 0 of GeneralPolygon is too intricate to cut around its \
         holes: its 40006 corners take more than 200000000 steps\n  help: split it into \
         several polygons, each with its own holes (docs/rib.md, Holes)"
    );
}
