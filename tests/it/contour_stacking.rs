//! The PNG composite of contours and the SVG and EPS writers stack the contour lines in one
//! order (`contour::stacking`): where lines of two materials cross, the line on top is the
//! same one in every output (the SVG used to group by ascending material index, so the
//! material of the lower index was always drawn under the others).

use glam::{Vec2, Vec3, Vec4};
use stagelight::contour::eps::encode_eps;
use stagelight::contour::raster::rasterise;
use stagelight::contour::stacking::layers;
use stagelight::contour::svg::encode_svg;
use stagelight::contour::{output, ContourImage, ContourLine, ContourPoint};

const SIZE: u32 = 21;
const RED: Vec4 = Vec4::new(1.0, 0.0, 0.0, 1.0);
const BLUE: Vec4 = Vec4::new(0.0, 0.0, 1.0, 1.0);

/// An opaque straight line 5 px wide.
fn line(material: u32, from: Vec2, to: Vec2, color: Vec4) -> ContourLine {
    let point = |pos| ContourPoint {
        pos,
        color,
        width: 5.0,
    };
    ContourLine {
        material,
        closed: false,
        points: vec![point(from), point(to)],
    }
}

/// A red line of material 2 across the image, a blue line of material 1 down over it (linked
/// after it, so on top), and a second red line of material 2 apart from both.
fn crossing() -> ContourImage {
    let lines = vec![
        line(2, Vec2::new(2.0, 10.5), Vec2::new(19.0, 10.5), RED),
        line(1, Vec2::new(10.5, 2.0), Vec2::new(10.5, 19.0), BLUE),
        line(2, Vec2::new(2.0, 3.0), Vec2::new(6.0, 3.0), RED),
    ];
    let layer = rasterise(&lines, SIZE, SIZE);
    ContourImage {
        width: SIZE,
        height: SIZE,
        lines,
        material_names: vec!["ink_blue".into(), "ink_red".into()],
        layer,
    }
}

#[test]
fn the_topmost_line_at_a_crossing_is_the_same_in_the_png_and_the_svg() {
    let image = crossing();
    let order: Vec<u32> = layers(&image.lines).iter().map(|l| l.material).collect();
    assert_eq!(order, [2, 1, 2], "layers bottom to top, in line order");
    let centre = (10 * SIZE + 10) as usize;

    // The PNG composite (over white paper): the blue line, fully covering the crossing pixel.
    let n = (SIZE * SIZE) as usize;
    let (mut beauty, mut alpha) = (vec![Vec3::ZERO; n], vec![0.0; n]);
    output::composite(&mut beauty, &mut alpha, &image, Some(Vec3::ONE));
    assert_eq!(beauty[centre], Vec3::new(0.0, 0.0, 1.0));
    assert_eq!(alpha[centre], 1.0);

    // The SVG, drawn by a real SVG rasteriser: blue on top there too.
    let svg = encode_svg(&image);
    let ids: Vec<&str> = svg
        .split("<g id=\"")
        .skip(1)
        .map(|rest| rest.split('"').next().unwrap())
        .collect();
    assert_eq!(ids, ["ink_red", "ink_blue", "ink_red-2"], "{svg}");
    let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default())
        .expect("the SVG parses");
    let mut pixmap = resvg::tiny_skia::Pixmap::new(SIZE, SIZE).unwrap();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    let p = pixmap.pixels()[centre];
    assert_eq!((p.red(), p.green(), p.blue(), p.alpha()), (0, 0, 255, 255));

    // The EPS fills its layers in the same order (PostScript paints later fills on top).
    let eps = encode_eps(&image);
    let materials: Vec<&str> = eps
        .lines()
        .filter_map(|l| l.strip_prefix("% material "))
        .collect();
    assert_eq!(materials, ["ink_red", "ink_blue", "ink_red"], "{eps}");
}
