//! RIB polygons with holes: the first loop of a `GeneralPolygon` (of each polygon of a
//! `PointsGeneralPolygons`) is its outline, the others are holes, which show what is behind.

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
