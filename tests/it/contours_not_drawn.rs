//! A run that draws no contour lines — every contrast criterion off (`depth: None` is the
//! depth criterion's off state), or output shaders off (`output off`) — skips
//! `draw_contours`, writes no SVG or EPS output (they hold nothing but the lines) instead of
//! an empty one, and says so: in the `--stats` report (the stage's and `write_output`'s
//! reasons), and as a warning naming each file not written.

use std::path::Path;

use crate::common::{run_in, scratch_dir, stderr_of};

/// Every criterion of the contour contrast off.
const ALL_OFF: &str = "contours: (contrast: (instance: false, object: false, material: false,
        normal_angle: 180, depth: None, background: false))";

/// A lit ball with a contour shader, seen by a 24 × 16 camera with `outputs`.
fn ball(options: &str, outputs: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1, {options}),
    cameras: [(name: "cam", fov_y: 40.0, resolution: (24, 16),
        placement: LookAt(eye: (0, -5, 0), target: (0, 0, 0), up: (0, 0, 1)),
        outputs: [{outputs}])],
    materials: [(name: "ink", shader: Constant(color: (0.8, 0.8, 0.8)),
                 contour: Simple(color: (0, 0, 0, 1), width: 1.0))],
    objects: [(name: "ball", mesh: Sphere(radius: 1.0), material: "ink")],
    instances: [(name: "ball_1", of: "ball")],
    groups: [(name: "root", members: ["ball_1"])],
    render: (root: "root", camera: "cam"),
)"#
    )
}

/// `(ran, reason)` of `stage` in the `--stats-json` file `stats.json` in `dir`, checked
/// against its row of the `--stats` table in `stdout`.
fn stage(dir: &Path, stdout: &str, name: &str) -> (bool, String) {
    let r = crate::common::stage_row(&dir.join("stats.json"), name);
    let (ran, reason) = (r.ran, r.reason);
    let row = stdout
        .lines()
        .find(|l| l.split_whitespace().next() == Some(name))
        .unwrap_or_else(|| panic!("no {name} row in\n{stdout}"));
    assert_eq!(
        row.split_whitespace().nth(1),
        Some(if ran { "yes" } else { "no" })
    );
    assert!(row.ends_with(&format!("  {reason}")), "{row}");
    (ran, reason)
}

#[test]
fn every_contrast_criterion_off_skips_the_stage_and_writes_no_svg() {
    let dir = scratch_dir("contours-all-off");
    std::fs::write(
        dir.join("s.ron"),
        ball(ALL_OFF, r#"(file: "s.png"), (file: "lines.svg")"#),
    )
    .unwrap();
    let o = run_in(
        &dir,
        &["render", "s.ron", "--stats", "--stats-json", "stats.json"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).to_string();
    let why = "every contour contrast criterion is off (1 material(s) with a contour shader)";
    assert_eq!(stage(&dir, &stdout, "draw_contours"), (false, why.into()));
    assert_eq!(
        stage(&dir, &stdout, "write_output"),
        (
            true,
            format!("1 camera output(s); \"lines.svg\" not written, no contours are drawn: {why}")
        )
    );
    assert!(dir.join("s.png").is_file());
    assert!(!dir.join("lines.svg").exists(), "no empty SVG");
    let stderr = stderr_of(&o);
    assert!(
        stderr.contains(
            "s.ron:2:48: warning: every contour contrast criterion is off: no contour lines are drawn, and SVG and EPS outputs are not written\n  help: turn one on, e.g. `background: true`; to draw no contours, leave out the materials' `contour` shaders\n"
        ),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!(
            "lines.svg: warning: not written, no contours are drawn: {why}\n"
        )),
        "{stderr}"
    );
    // The image is the one of the scene without the contour output.
    std::fs::write(dir.join("plain.ron"), ball(ALL_OFF, r#"(file: "p.png")"#)).unwrap();
    let o = run_in(&dir, &["render", "plain.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert!(std::fs::read(dir.join("s.png")).unwrap() == std::fs::read(dir.join("p.png")).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

/// With the depth criterion alone off the lines are drawn (the silhouette).
#[test]
fn depth_none_alone_still_draws_the_silhouette() {
    let dir = scratch_dir("contours-depth-none");
    std::fs::write(
        dir.join("s.ron"),
        ball(
            "contours: (contrast: (depth: None))",
            r#"(file: "lines.svg")"#,
        ),
    )
    .unwrap();
    let o = run_in(&dir, &["render", "s.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let svg = std::fs::read_to_string(dir.join("lines.svg")).unwrap();
    assert_eq!(svg.matches("<polygon").count(), 1, "{svg}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// mental ray's `output off` with the camera's only output a contour EPS: nothing is
/// rendered or written, and the report and a warning say why.
#[test]
fn output_off_writes_no_eps_and_says_so() {
    let dir = scratch_dir("contours-output-off");
    let fixture =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_contours/square.mi");
    let text = std::fs::read_to_string(fixture)
        .unwrap()
        .replace("object space\n", "object space\noutput off\n");
    std::fs::write(dir.join("square.mi"), text).unwrap();
    let o = run_in(
        &dir,
        &[
            "render",
            "square.mi",
            "--spp",
            "1",
            "--stats",
            "--stats-json",
            "stats.json",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).to_string();
    let why = "output shaders disabled (1 material(s) with a contour shader)";
    let unwritten = format!("\"square.eps\" not written, no contours are drawn: {why}");
    assert_eq!(stage(&dir, &stdout, "draw_contours"), (false, why.into()));
    assert_eq!(
        stage(&dir, &stdout, "write_output"),
        (false, unwritten.clone())
    );
    assert_eq!(
        stage(&dir, &stdout, "shade"),
        (false, format!("nothing reads the image: {unwritten}"))
    );
    assert!(!dir.join("square.eps").exists(), "no empty EPS");
    let stderr = stderr_of(&o);
    assert!(
        stderr.contains(&format!(
            "square.eps: warning: not written, no contours are drawn: {why}\n"
        )),
        "{stderr}"
    );
    assert!(
        !stderr.contains("wrote") && !stderr.contains("note:"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
