//! Contours (issue 11): line positions, edge counts, widths, per-material shaders, the SVG
//! against a real SVG rasteriser, skipping, determinism, farm merges and bad input.

use std::path::Path;

use glam::Vec2;
use stagelight::contour::{ContourImage, ContourLine};
use stagelight::frame::Frame;
use stagelight::scene::load_scene_str;

use crate::common::{run_in, scratch_dir, stderr_of};

/// A scene of `objects`/`instances`/`materials` (RON list entries) seen by a `w × h` camera
/// at `eye` looking at the origin, with `options` fields; outputs `outputs`.
fn scene(w: u32, h: u32, eye: (f32, f32, f32), options: &str, body: &str, outputs: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, {options}),
    cameras: [(name: "cam", fov_y: 40.0, resolution: ({w}, {h}),
        placement: LookAt(eye: ({}, {}, {}), target: (0, 0, 0), up: (0, 0, 1)),
        outputs: [{outputs}])],
    {body}
    render: (root: "root", camera: "cam"),
)"#,
        eye.0, eye.1, eye.2
    )
}

/// Loads `text` and runs every stage but `write_output`.
fn render(text: &str) -> Frame {
    let mut scene = load_scene_str(text, Path::new("contours_test.ron"))
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    crate::common::render(&mut scene.world, scene.settings.clone())
}

fn contours(text: &str) -> ContourImage {
    render(text).outputs.contours.expect("contours drawn")
}

const SPHERE: &str = r#"
    materials: [(name: "ink", shader: Constant(color: (0.8, 0.8, 0.8)),
                 contour: Simple(color: (0, 0, 0, 1), width: 1.0))],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "ink",
               approximation: Parametric(u: 96, v: 48))],
    instances: [(name: "ball_1", of: "ball")],
    groups: [(name: "root", members: ["ball_1"])],
"#;

/// The sphere's silhouette: every line point, and every point of the SVG outline (at half
/// the width on either side), lies on the projected circle within 0.25 px.
#[test]
fn sphere_silhouette_lies_on_the_projected_circle() {
    let distance = 5.0f32;
    for (w, h) in [(48, 40), (120, 90), (200, 160)] {
        let img = contours(&scene(
            w,
            h,
            (0.0, -distance, 0.0),
            "",
            SPHERE,
            r#"(file: "s.svg")"#,
        ));
        // Angular radius asin(R/D); pixels per unit of tan: (h/2)/tan(fov/2).
        let alpha = (1.0 / distance).asin();
        let r = alpha.tan() / 20f32.to_radians().tan() * h as f32 / 2.0;
        let centre = Vec2::new(w as f32, h as f32) / 2.0;
        assert_eq!(img.lines.len(), 1, "{w}×{h}: one closed silhouette");
        assert!(img.lines[0].closed);
        assert!(
            img.lines[0].points.len() as f32 > 4.0 * r,
            "a crossing per pixel row/column"
        );
        for p in &img.lines[0].points {
            let d = (p.pos - centre).length();
            assert!(
                (d - r).abs() < 0.25,
                "{w}×{h}: {} is {d} from the centre, r = {r}",
                p.pos
            );
        }
        let half = 0.01 * h.min(w) as f32 / 2.0;
        for p in svg_points(&stagelight::contour::svg::encode_svg(&img)) {
            let d = (p - centre).length();
            let off = (d - (r - half)).abs().min((d - (r + half)).abs());
            assert!(off < 0.25, "{w}×{h}: SVG point {p} is {d} from the centre");
        }
    }
}

/// Every point of every `<polygon>` of an SVG document.
fn svg_points(svg: &str) -> Vec<Vec2> {
    svg.split("points=\"")
        .skip(1)
        .flat_map(|rest| {
            rest[..rest.find('"').unwrap()]
                .split_whitespace()
                .map(|xy| {
                    let (x, y) = xy.split_once(',').unwrap();
                    Vec2::new(x.parse().unwrap(), y.parse().unwrap())
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Straight pieces of a line: Douglas–Peucker with `tolerance` pixels, then (for a closed
/// line) the pieces meeting at the first point merged when they are collinear.
fn straight_pieces(line: &ContourLine, tolerance: f32) -> usize {
    fn dp(p: &[Vec2], tol: f32) -> Vec<Vec2> {
        let (a, b) = (p[0], p[p.len() - 1]);
        let dist = |q: Vec2| {
            let d = b - a;
            if d.length() < 1e-6 {
                (q - a).length()
            } else {
                ((q - a).perp_dot(d) / d.length()).abs()
            }
        };
        let (k, far) = p
            .iter()
            .enumerate()
            .map(|(i, &q)| (i, dist(q)))
            .fold((0, 0.0), |m, x| if x.1 > m.1 { x } else { m });
        if far <= tol || p.len() < 3 {
            return vec![a, b];
        }
        let mut left = dp(&p[..=k], tol);
        left.pop();
        left.extend(dp(&p[k..], tol));
        left
    }
    let mut pts: Vec<Vec2> = line.points.iter().map(|p| p.pos).collect();
    if line.closed {
        pts.push(pts[0]);
    }
    let simple = dp(&pts, tolerance);
    let mut pieces = simple.len() - 1;
    if line.closed && pieces > 2 {
        let first = (simple[1] - simple[0]).normalize();
        let last = (simple[0] - simple[simple.len() - 2]).normalize();
        if first.dot(last) > 10f32.to_radians().cos() {
            pieces -= 1;
        }
    }
    pieces
}

fn cube(normal_angle: f32) -> String {
    scene(
        200,
        200,
        (3.1, 2.3, 2.6),
        &format!("contours: (contrast: (normal_angle: {normal_angle}))"),
        r#"
    materials: [(name: "ink", shader: Constant(color: (0.8, 0.8, 0.8)),
                 contour: Simple(color: (0, 0, 0, 1), width: 0.5))],
    objects: [(name: "cube", mesh: Inline(
        vertices: [(-0.5, -0.5, -0.5), (0.5, -0.5, -0.5), (0.5, 0.5, -0.5), (-0.5, 0.5, -0.5),
                   (-0.5, -0.5, 0.5), (0.5, -0.5, 0.5), (0.5, 0.5, 0.5), (-0.5, 0.5, 0.5)],
        polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]),
        material: "ink")],
    instances: [(name: "cube_1", of: "cube")],
    groups: [(name: "root", members: ["cube_1"])],
"#,
        r#"(file: "c.svg")"#,
    )
}

/// A cube seen from a corner: its 9 visible edges (6 silhouette, 3 creases) with the
/// normal-angle contrast, none across its flat faces; only the 6 silhouette edges with the
/// threshold above 90°.
#[test]
fn a_cube_from_a_corner_has_nine_edges_or_six_without_creases() {
    let count =
        |img: &ContourImage| -> usize { img.lines.iter().map(|l| straight_pieces(l, 0.8)).sum() };
    let creased = contours(&cube(60.0));
    assert_eq!(count(&creased), 9);
    assert_eq!(
        creased.lines.len(),
        6,
        "3 silhouette chains and 3 creases between 4 junctions"
    );
    let outline = contours(&cube(100.0));
    assert_eq!(outline.lines.len(), 1, "one closed hexagon");
    assert_eq!(count(&outline), 6);
}

/// Two quads side by side, each filling its half of a 400×300 image edge to edge; only the
/// left one has a contour shader (`width`), a vertical edge at x ≈ 130.3.
fn two_quads(width: f32) -> String {
    format!(
        r#"Scene(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (400, 300),
        placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)),
        outputs: [(file: "q.png", passes: [Beauty, Contours])])],
    materials: [
        (name: "inked", shader: Constant(color: (0.2, 0.4, 0.8)),
         contour: Simple(color: (1, 0, 0, 1), width: {width})),
        (name: "plain", shader: Constant(color: (0.8, 0.4, 0.2))),
    ],
    objects: [
        (name: "left", mesh: Inline(vertices: [(-0.9, -3, 0), (-0.9, 3, 0), (-9, 3, 0), (-9, -3, 0)],
            polygons: [[3, 0, 1, 2]]), material: "inked"),
        (name: "right", mesh: Inline(vertices: [(0.9, -1, 0), (9, -1, 0), (9, 1, 0), (0.9, 1, 0)],
            polygons: [[0, 1, 2, 3]]), material: "plain"),
    ],
    instances: [(name: "l", of: "left"), (name: "r", of: "right")],
    groups: [(name: "root", members: ["l", "r"])],
    render: (root: "root", camera: "cam"),
)"#
    )
}

/// `Simple(width: 1.0)` at 400×300 is 3 px wide (1 % of 300) ± 0.25 px across the line;
/// the quad without a contour shader gets no lines.
#[test]
fn width_is_percent_of_the_smaller_dimension_and_only_inked_materials_get_lines() {
    let img = contours(&two_quads(1.0));
    let row = 150;
    let across: f32 = (0..200).map(|x| img.layer[row * 400 + x].w).sum();
    assert!((across - 3.0).abs() <= 0.25, "{across} px");
    assert!(
        img.lines.iter().all(|l| l.material == 1),
        "lines only around the inked quad"
    );
    // Nothing near the plain quad's edges (x > 200).
    let right: f32 = (0..300)
        .flat_map(|y| (200..400).map(move |x| (x, y)))
        .map(|(x, y)| img.layer[y * 400 + x].w)
        .sum();
    assert_eq!(right, 0.0);
    // Red ink.
    let peak = img.layer[row * 400..row * 400 + 200]
        .iter()
        .fold(glam::Vec4::ZERO, |m, c| if c.w > m.w { *c } else { m });
    assert!(
        (peak - glam::Vec4::new(1.0, 0.0, 0.0, 1.0))
            .abs()
            .max_element()
            < 1e-6,
        "{peak}"
    );
}

/// The SVG, drawn by a real SVG rasteriser (resvg), covers the pixels the contour layer
/// covers (IoU ≥ 0.95 of the pixels at least half covered).
#[test]
fn svg_rasterised_by_resvg_matches_the_contour_layer() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/contours.ron"
    ))
    .unwrap()
    .replace("resolution: (160, 120)", "resolution: (480, 360)");
    let img = contours(&text);
    let svg = stagelight::contour::svg::encode_svg(&img);
    let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default())
        .expect("the SVG parses");
    let mut pixmap = resvg::tiny_skia::Pixmap::new(img.width, img.height).unwrap();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    let (mut both, mut either) = (0usize, 0usize);
    for (i, c) in img.layer.iter().enumerate() {
        let vector = pixmap.pixels()[i].alpha() >= 128;
        let raster = c.w >= 0.5;
        both += usize::from(vector && raster);
        either += usize::from(vector || raster);
    }
    assert!(either > 500, "the scene has lines ({either} px)");
    let iou = both as f64 / either as f64;
    assert!(iou >= 0.95, "IoU {iou:.3} ({both} / {either})");
}

/// Without a contour shader `draw_contours` is skipped with its reason, and the files are
/// byte for byte those of a run without the stage.
#[test]
fn skipped_without_contour_shaders_and_output_unchanged() {
    let text = scene(
        40,
        30,
        (0.0, -5.0, 0.0),
        "",
        &SPHERE.replace(
            "contour: Simple(color: (0, 0, 0, 1), width: 1.0)",
            "two_sided: false",
        ),
        r#"(file: "s.png"), (file: "s.exr", passes: [Beauty, Depth])"#,
    );
    let files = |with_stage: bool| {
        let mut scene = load_scene_str(&text, Path::new("t.ron")).unwrap();
        let mut frame = Frame::new(scene.settings.clone());
        frame.inputs.hold_files = true;
        let stages: Vec<_> = stagelight::systems::STAGES
            .iter()
            .copied()
            .filter(|s| with_stage || s.name != "draw_contours")
            .collect();
        stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame).unwrap();
        let bytes: Vec<Vec<u8>> = frame.held_files.iter().map(|f| f.bytes.clone()).collect();
        (frame, bytes)
    };
    let (frame, with) = files(true);
    let stage = frame
        .report
        .stages
        .iter()
        .find(|s| s.stage == "draw_contours")
        .unwrap();
    assert!(!stage.ran);
    assert_eq!(stage.reason, "no material in use has a contour shader");
    let (_, without) = files(false);
    assert_eq!(with.len(), 2);
    assert!(with == without, "byte-identical files");
}

/// Lines and layer are the same at 1 and 2 threads.
#[test]
fn identical_lines_at_one_and_two_threads() {
    let text = cube(60.0);
    let at = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| contours(&text))
    };
    assert!(at(1) == at(2));
}

/// `render --part` + `merge` give the contour files of a single render, byte for byte.
#[test]
fn farm_parts_merge_into_the_same_contour_files() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/contours.ron");
    let single = scratch_dir("contours-single");
    let o = run_in(&single, &["render", scene]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let farm = scratch_dir("contours-farm");
    for part in ["1/3", "2/3", "3/3"] {
        let file = format!("part_{}.exr", &part[..1]);
        let o = run_in(&farm, &["render", scene, "--part", part, "-o", &file]);
        assert!(o.status.success(), "{}", stderr_of(&o));
    }
    let o = run_in(&farm, &["merge", "part_1.exr", "part_2.exr", "part_3.exr"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    for name in ["contours.png", "contours.svg"] {
        let a = std::fs::read(single.join(name)).unwrap();
        let b = std::fs::read(farm.join(name)).unwrap();
        assert!(a == b, "{name} differs after the merge");
    }
    let _ = std::fs::remove_dir_all(single);
    let _ = std::fs::remove_dir_all(farm);
}

/// Parts rendered with `--disable output` merge into the files of a single render with that
/// flag: the merge reads the switched-off features from the parts, so it draws no contour
/// lines (it drew them, as if the parts had been rendered without the flag), and like the
/// single render it writes the PNG but not the SVG, which would hold nothing.
#[test]
fn parts_rendered_with_output_shaders_off_merge_without_contour_lines() {
    let dir = scratch_dir("contours-disabled-farm");
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/contours.ron"
    ))
    .unwrap()
    .replace("resolution: (160, 120)", "resolution: (40, 30)")
    .replace("samples: 4", "samples: 1");
    std::fs::write(dir.join("contours.ron"), text).unwrap();
    let (single, farm) = (dir.join("single"), dir.join("farm"));
    for d in [&single, &farm] {
        std::fs::create_dir_all(d).unwrap();
    }
    let ok = |d: &Path, args: &[&str]| {
        let o = run_in(d, args);
        assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
    };
    let scene = "../contours.ron";
    ok(&single, &["render", scene, "--disable", "output"]);
    for part in ["1/3", "2/3", "3/3"] {
        let file = format!("part_{}.exr", &part[..1]);
        let args = ["render", scene, "--disable", "output", "--part", part, "-o"];
        ok(&farm, &[&args[..], &[&file]].concat());
    }
    ok(&farm, &["merge", "part_1.exr", "part_2.exr", "part_3.exr"]);
    for d in [&single, &farm] {
        assert!(!d.join("contours.svg").exists(), "{}", d.display());
    }
    let a = std::fs::read(single.join("contours.png")).unwrap();
    let b = std::fs::read(farm.join("contours.png")).unwrap();
    assert!(a == b, "contours.png differs after the merge");
    let _ = std::fs::remove_dir_all(dir);
}

/// The `merge --stats` table's row of `stage`: whether it ran, its rays and its reason.
fn merge_row(stats: &str, stage: &str) -> (bool, u64, String) {
    let line = stats
        .lines()
        .find(|l| l.split_whitespace().next() == Some(stage))
        .unwrap_or_else(|| panic!("no {stage} row in\n{stats}"));
    let fields: Vec<&str> = line.split_whitespace().collect();
    let ran = fields[1] == "yes";
    // stage ran seconds items [unit] items/s rays reason…: the rays follow the rate.
    let rays_at = if fields[4].parse::<f64>().is_ok() {
        5
    } else {
        6
    };
    let reason = fields[rays_at + 1..].join(" ");
    (ran, fields[rays_at].parse().unwrap(), reason)
}

/// A merge that draws no contours — a contour shader, but no output shows contours, or
/// parts rendered with `--disable output` — builds no geometry and traces no rays: the
/// geometry stages skip with the reason, `shade` keeps no contour store. The files are the
/// single render's bytes.
#[test]
fn a_merge_that_draws_no_contours_builds_no_geometry() {
    let dir = scratch_dir("contours-merge-undrawn");
    let unshown = scene(24, 16, (0.0, -5.0, 0.0), "", SPHERE, r#"(file: "s.png")"#);
    let shown = scene(
        24,
        16,
        (0.0, -5.0, 0.0),
        "",
        SPHERE,
        r#"(file: "s.png", passes: [Beauty, Contours])"#,
    );
    let ok = |d: &Path, args: &[&str]| {
        let o = run_in(d, args);
        assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
        String::from_utf8_lossy(&o.stdout).to_string() + &stderr_of(&o)
    };
    for (name, text, flags, why) in [
        (
            "unshown",
            &unshown,
            &[][..],
            "no output shows contours (1 material(s) with a contour shader)",
        ),
        (
            "disabled",
            &shown,
            &["--disable", "output"][..],
            "output shaders disabled (1 material(s) with a contour shader)",
        ),
    ] {
        let d = dir.join(name);
        std::fs::create_dir_all(d.join("farm")).unwrap();
        std::fs::write(d.join("s.ron"), text).unwrap();
        ok(&d, &[&["render", "s.ron"][..], flags].concat());
        for k in 1..=2 {
            let (part, file) = (format!("{k}/2"), format!("p{k}.exr"));
            let args = ["render", "../s.ron", "--part", &part, "-o", &file];
            ok(&d.join("farm"), &[&args[..], flags].concat());
        }
        let stats = ok(&d.join("farm"), &["merge", "p1.exr", "p2.exr", "--stats"]);
        for stage in ["expand_geometry", "tessellate", "build_accel"] {
            assert_eq!(
                merge_row(&stats, stage),
                (
                    false,
                    0,
                    format!("the image is merged from part files; no contours are drawn: {why}")
                ),
                "{name}: {stats}"
            );
        }
        assert_eq!(merge_row(&stats, "shade").1, 0, "{name}: {stats}");
        assert_eq!(
            merge_row(&stats, "draw_contours"),
            (false, 0, why.to_string()),
            "{name}: {stats}"
        );
        assert!(
            std::fs::read(d.join("s.png")).unwrap() == std::fs::read(d.join("farm/s.png")).unwrap(),
            "{name}: s.png differs after the merge"
        );
    }
    // With the lines shown, the merge builds the geometry and draws them.
    let d = dir.join("shown");
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("s.ron"), &shown).unwrap();
    for k in 1..=2 {
        let (part, file) = (format!("{k}/2"), format!("p{k}.exr"));
        ok(&d, &["render", "s.ron", "--part", &part, "-o", &file]);
    }
    let stats = ok(&d, &["merge", "p1.exr", "p2.exr", "--stats"]);
    assert!(merge_row(&stats, "build_accel").0, "{stats}");
    assert!(merge_row(&stats, "draw_contours").0, "{stats}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Loads `text`, expecting the errors (or, with `Ok`, the warnings) it reports.
fn diagnostics(text: &str) -> Result<Vec<String>, String> {
    match load_scene_str(text, Path::new("bad.ron")) {
        Ok(s) => Ok(s.located_warnings),
        Err(e) => Err(e.to_string()),
    }
}

const QUAD: &str = r#"
    objects: [(name: "q", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
        polygons: [[0, 1, 2, 3]]), material: "m")],
    instances: [(name: "q_1", of: "q")],
    groups: [(name: "root", members: ["q_1"])],
"#;

#[test]
fn a_width_of_zero_is_a_located_error() {
    let body = format!(
        "materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)),\n contour: Simple(width: 0))],{QUAD}"
    );
    let e = diagnostics(&scene(
        8,
        8,
        (0.0, -5.0, 0.5),
        "",
        &body,
        r#"(file: "a.svg")"#,
    ))
    .unwrap_err();
    assert_eq!(
        e.trim_end(),
        "bad.ron:7:25: error: contour width must be positive, found 0\n  help: widths are in percent of the smaller image dimension, e.g. `width: 0.5`; to draw no contours, leave out `contour`"
    );
}

#[test]
fn an_svg_output_without_contour_shaders_is_a_located_error() {
    let body =
        format!("materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],{QUAD}");
    let e = diagnostics(&scene(
        8,
        8,
        (0.0, -5.0, 0.5),
        "",
        &body,
        r#"(file: "lines.svg")"#,
    ))
    .unwrap_err();
    assert_eq!(
        e.trim_end(),
        "bad.ron:5:26: error: output \"lines.svg\" shows contours, but no material has a contour shader\n  help: give a material a contour shader, e.g. `contour: Simple(color: (0, 0, 0, 1), width: 0.5)`"
    );
}

#[test]
fn a_contour_shader_no_output_shows_is_a_located_warning() {
    let body = format!(
        "materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)),\n contour: Simple())],{QUAD}"
    );
    let w = diagnostics(&scene(
        8,
        8,
        (0.0, -5.0, 0.5),
        "",
        &body,
        r#"(file: "a.png")"#,
    ))
    .unwrap();
    assert_eq!(
        w,
        ["bad.ron:7:11: warning: material \"m\" has a contour shader, but no camera output shows contours\n  help: add an output such as `(file: \"lines.svg\")` or a `Contours` pass"]
    );
}

/// A contour shader on a material no instance places draws nothing because of that, not
/// for want of an output: the warning says so (it said "no camera output shows contours").
#[test]
fn a_contour_shader_on_an_unused_material_says_it_is_unused() {
    let body = format!(
        "materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5))),\n (name: \"ink\", shader: Lambert(albedo: (0.5, 0.5, 0.5)),\n contour: Simple())],{QUAD}"
    );
    let w = diagnostics(&scene(
        8,
        8,
        (0.0, -5.0, 0.5),
        "",
        &body,
        r#"(file: "a.png")"#,
    ))
    .unwrap();
    assert_eq!(
        w,
        ["bad.ron:8:11: warning: material \"ink\" has a contour shader, but no instance uses the material: its contours are never drawn\n  help: contours are drawn around the objects placed with a material; place one with \"ink\", or leave out its contour shader"]
    );
}

/// Each text's numbers, in pairs, as points.
fn point_lists(shapes: impl Iterator<Item = String>) -> Vec<Vec<Vec2>> {
    shapes
        .map(|s| {
            let n: Vec<f32> = s
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter_map(|t| t.parse().ok())
                .collect();
            n.chunks(2).map(|p| Vec2::new(p[0], p[1])).collect()
        })
        .collect()
}

/// The EPS writer draws the SVG's polygons: its header holds the image size as bounding
/// box, it fills one path per `<polygon>` (one group per `<g>`), and each path has the
/// polygon's points with y flipped (PostScript's y goes up), within the printed 0.001.
#[test]
fn eps_draws_the_svg_polygons_with_the_image_as_bounding_box() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/contours.ron"
    ))
    .unwrap();
    let img = contours(&text);
    let svg = stagelight::contour::svg::encode_svg(&img);
    let eps = stagelight::contour::eps::encode_eps(&img);
    let header: Vec<&str> = eps.lines().take_while(|l| *l != "%%EndComments").collect();
    assert_eq!(header[0], "%!PS-Adobe-3.0 EPSF-3.0");
    let bbox = header
        .iter()
        .find_map(|l| l.strip_prefix("%%BoundingBox: "))
        .expect("a bounding box");
    assert_eq!(bbox, format!("0 0 {} {}", img.width, img.height));
    assert_eq!(
        eps.matches("% material ").count(),
        svg.matches("<g id=").count()
    );
    // SVG polygons in document order; EPS paths: from a point's `m` to the `f`.
    let svg_shapes = point_lists(
        svg.split("points=\"")
            .skip(1)
            .map(|s| s[..s.find('"').unwrap()].to_string()),
    );
    // The prolog defines `/f`, `/m` and `/l`; the paths follow it.
    let body = &eps[eps.find("%%EndProlog").unwrap()..];
    let (mut eps_shapes, mut numbers, mut shape) = (Vec::new(), Vec::new(), Vec::new());
    for token in body.split_whitespace() {
        match token {
            "m" | "l" => {
                shape.push(Vec2::new(numbers[0], numbers[1]));
                numbers.clear();
            }
            "f" => eps_shapes.push(std::mem::take(&mut shape)),
            _ => match token.parse::<f32>() {
                Ok(v) => numbers.push(v),
                Err(_) => numbers.clear(),
            },
        }
    }
    assert!(svg_shapes.len() > 10, "the scene has lines");
    assert_eq!(eps_shapes.len(), svg_shapes.len());
    for (e, s) in eps_shapes.iter().zip(&svg_shapes) {
        assert_eq!(e.len(), s.len());
        for (a, b) in e.iter().zip(s) {
            let flipped = Vec2::new(b.x, img.height as f32 - b.y);
            assert!(
                (*a - flipped).abs().max_element() <= 1.5e-3,
                "{a} vs {flipped}"
            );
        }
    }
}

/// `render -o lines.svg` / `-o lines.eps` replaces the camera's vector output (the PNG is
/// still written), with the same drawing as the scene's own SVG; on a camera without one it
/// is added.
#[test]
fn dash_o_with_a_vector_extension_writes_the_contour_lines() {
    let dir = scratch_dir("contours-dash-o");
    let scene_of = |outputs: &str| {
        let body = SPHERE.replace("width: 1.0", "width: 2.0");
        scene(48, 40, (0.0, -5.0, 0.0), "", &body, outputs)
    };
    std::fs::write(
        dir.join("both.ron"),
        scene_of(r#"(file: "a.png", passes: [Beauty, Contours]), (file: "a.svg")"#),
    )
    .unwrap();
    std::fs::write(
        dir.join("png.ron"),
        scene_of(r#"(file: "b.png", passes: [Beauty, Contours])"#),
    )
    .unwrap();
    let ok = |args: &[&str]| {
        let o = run_in(&dir, args);
        assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
    };
    ok(&["render", "both.ron"]);
    ok(&["render", "both.ron", "-o", "lines.svg"]);
    ok(&["render", "both.ron", "-o", "lines.eps"]);
    ok(&["render", "png.ron", "-o", "added.svg"]);
    let read = |name: &str| std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(
        read("lines.svg") == read("a.svg"),
        "-o lines.svg: the scene's drawing"
    );
    assert!(
        read("added.svg") == read("a.svg"),
        "added to a camera without one"
    );
    assert!(read("b.png") == read("a.png"), "the image output is kept");
    let eps = String::from_utf8(read("lines.eps")).unwrap();
    assert!(eps.contains("\n%%BoundingBox: 0 0 48 40\n"));
    let svg = String::from_utf8(read("a.svg")).unwrap();
    assert_eq!(
        eps.split_whitespace().filter(|t| *t == "f").count(),
        svg.matches("<polygon").count()
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// A vector `-o` on a scene without contour shaders, or an unknown extension, is a usage
/// error that writes nothing.
#[test]
fn dash_o_vector_without_contour_shaders_is_a_usage_error() {
    let dir = scratch_dir("contours-dash-o-bad");
    let body =
        format!("materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],{QUAD}");
    std::fs::write(
        dir.join("plain.ron"),
        scene(8, 8, (0.0, -5.0, 0.5), "", &body, r#"(file: "a.png")"#),
    )
    .unwrap();
    let o = run_in(&dir, &["render", "plain.ron", "-o", "lines.eps"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o).trim_end(),
        "error: -o lines.eps writes contour lines, but no material of the scene has a contour shader\n  help: give a material `contour: Simple(color: (0, 0, 0, 1), width: 0.5)`, or write a .png or .exr"
    );
    let o = run_in(&dir, &["render", "plain.ron", "-o", "lines.ps"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o).trim_end(),
        "error: cannot tell the output format of lines.ps from its extension\n  help: name a .png or .exr file for the image, or an .svg or .eps file for the contour lines"
    );
    assert_eq!(crate::common::dir_names(&dir), ["plain.ron"]);
    let _ = std::fs::remove_dir_all(dir);
}

/// A ball behind the camera, seen only in a mirror facing the camera: no lines at the
/// default `ray_depth: 0`; with `ray_depth: 1` one closed outline, on the projected circle
/// of the ball's mirror image (distance 5 + 15) and inside the mirror's region.
#[test]
fn an_object_seen_only_in_a_mirror_gets_lines_in_the_mirror_with_ray_depth() {
    let body = r#"
    materials: [(name: "ink", shader: Constant(color: (0.8, 0.8, 0.8)),
                 contour: Simple(color: (0, 0, 0, 1), width: 1.0)),
                (name: "glass", shader: Mirror(color: (0.9, 0.9, 0.9)))],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "ink",
               approximation: Parametric(u: 96, v: 48)),
              (name: "mirror", mesh: Inline(vertices: [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)],
               polygons: [[0, 1, 2, 3]]), material: "glass")],
    instances: [(name: "ball_1", of: "ball", transform: [Translate((0, -15, 0))]),
                (name: "mirror_1", of: "mirror")],
    groups: [(name: "root", members: ["ball_1", "mirror_1"])],
"#;
    let (w, h) = (80u32, 60u32);
    let text = |depth: u32| {
        scene(
            w,
            h,
            (0.0, -5.0, 0.0),
            &format!("contours: (ray_depth: {depth})"),
            body,
            r#"(file: "m.svg")"#,
        )
    };
    assert!(
        contours(&text(0)).lines.is_empty(),
        "the ball is behind the camera"
    );
    let img = contours(&text(1));
    // The mirror image of the ball: radius 1 at distance 5 + 15.
    let alpha = (1.0f32 / 20.0).asin();
    let r = alpha.tan() / 20f32.to_radians().tan() * h as f32 / 2.0;
    let mirror = 1.0 / 5.0 / 20f32.to_radians().tan() * h as f32 / 2.0;
    let centre = Vec2::new(w as f32, h as f32) / 2.0;
    assert_eq!(img.lines.len(), 1, "one outline");
    assert!(img.lines[0].closed);
    for p in &img.lines[0].points {
        let d = (p.pos - centre).length();
        assert!((d - r).abs() < 0.35, "{:?}: {d} vs radius {r}", p.pos);
        let off = (p.pos - centre).abs();
        assert!(
            off.max_element() < mirror,
            "inside the mirror ({mirror} px)"
        );
    }
}

/// `Layered(width: 2, thinning: 0.5)` on a ball whose right half is seen through a
/// transparent sheet (`Opacity` 0.3, no contour shader): with `ray_depth: 1` the left half of
/// the outline (no layer in front) is 2 % of 60 px = 1.2 px wide, the right half (one layer in
/// front) 0.6 px; at `ray_depth: 0` only the left half is drawn.
#[test]
fn layered_contours_thin_by_the_layers_in_front() {
    let body = r#"
    materials: [(name: "ink", shader: Constant(color: (0.8, 0.8, 0.8)),
                 contour: Layered(color: (0, 0, 0, 1), width: 2.0, thinning: 0.5)),
                (name: "sheet", shader: Opacity(opacity: (0.3, 0.3, 0.3), input: Constant(color: (1, 1, 1))))],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "ink",
               approximation: Parametric(u: 96, v: 48)),
              (name: "sheet", mesh: Inline(vertices: [(0, -2, -3), (3, -2, -3), (3, -2, 3), (0, -2, 3)],
               polygons: [[0, 1, 2, 3]]), material: "sheet")],
    instances: [(name: "ball_1", of: "ball"), (name: "sheet_1", of: "sheet")],
    groups: [(name: "root", members: ["ball_1", "sheet_1"])],
"#;
    let (w, h) = (80u32, 60u32);
    let centre = w as f32 / 2.0;
    let widths = |depth: u32| -> Vec<(f32, f32)> {
        let img = contours(&scene(
            w,
            h,
            (0.0, -5.0, 0.0),
            &format!("contours: (ray_depth: {depth})"),
            body,
            r#"(file: "l.svg")"#,
        ));
        img.lines
            .iter()
            .flat_map(|l| l.points.iter().map(|p| (p.pos.x, p.width)))
            .collect()
    };
    for depth in [0, 1] {
        let points = widths(depth);
        let (mut near, mut behind) = (0, 0);
        for (x, width) in &points {
            if (width - 1.2).abs() < 1e-4 {
                assert!(*x < centre + 0.5, "ray_depth {depth}: full width at x {x}");
                near += 1;
            } else {
                assert!(
                    (width - 0.6).abs() < 1e-4,
                    "ray_depth {depth}: width {width}"
                );
                assert!(*x > centre - 0.5, "ray_depth {depth}: thinned at x {x}");
                behind += 1;
            }
        }
        assert!(
            near > 10,
            "ray_depth {depth}: {near} points on the left half"
        );
        match depth {
            0 => assert_eq!(behind, 0),
            _ => assert!(behind > 10, "{behind} points behind the sheet"),
        }
    }
}

/// `Layered(thinning: 0)` and `ray_depth: 9` are located errors.
#[test]
fn a_zero_thinning_and_a_too_deep_ray_depth_are_located_errors() {
    let body = format!(
        "materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)),\n contour: Layered(thinning: 0))],{QUAD}"
    );
    let e = diagnostics(&scene(
        8,
        8,
        (0.0, -5.0, 0.5),
        "contours: (ray_depth: 9)",
        &body,
        r#"(file: "a.svg")"#,
    ))
    .unwrap_err();
    let lines: Vec<&str> = e.lines().filter(|l| l.contains("error:")).collect();
    assert_eq!(lines.len(), 2, "{e}");
    assert!(
        lines[0].starts_with("bad.ron:2:")
            && lines[0].ends_with(": error: contour ray_depth must be at most 8, found 9"),
        "{e}"
    );
    assert!(
        lines[1].starts_with("bad.ron:7:")
            && lines[1].ends_with(": error: thinning must be in (0, 1], found 0"),
        "{e}"
    );
}

/// A contour shader with no output that shows contours (a PNG of the beauty only): the stage
/// is skipped with the reason, and the file is the bytes of the same scene without the
/// shader; `-o lines.svg` on the command line makes it run.
#[test]
fn skipped_when_no_output_shows_contours() {
    let dir = scratch_dir("contours-unshown");
    let text = scene(24, 16, (0.0, -5.0, 0.0), "", SPHERE, r#"(file: "s.png")"#);
    let plain = text.replace(
        "contour: Simple(color: (0, 0, 0, 1), width: 1.0)",
        "two_sided: false",
    );
    assert_ne!(plain, text);
    std::fs::write(dir.join("inked.ron"), &text).unwrap();
    std::fs::write(dir.join("plain.ron"), &plain).unwrap();
    let stats = |args: &[&str]| {
        let o = run_in(&dir, args);
        assert!(o.status.success(), "{}", stderr_of(&o));
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
        let stage = json["stages"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["stage"] == "draw_contours")
            .cloned()
            .unwrap();
        (
            stage["ran"].as_bool().unwrap(),
            stage["reason"].as_str().unwrap().to_string(),
        )
    };
    let json = ["--stats-json", "stats.json"];
    let (ran, reason) = stats(&[&["render", "inked.ron", "-o", "a.png"][..], &json].concat());
    assert!(!ran);
    assert_eq!(
        reason,
        "no output shows contours (1 material(s) with a contour shader)"
    );
    stats(&[&["render", "plain.ron", "-o", "b.png"][..], &json].concat());
    assert_eq!(
        std::fs::read(dir.join("a.png")).unwrap(),
        std::fs::read(dir.join("b.png")).unwrap()
    );
    let (ran, _) = stats(&[&["render", "inked.ron", "-o", "lines.svg"][..], &json].concat());
    assert!(ran);
    let _ = std::fs::remove_dir_all(&dir);
}
