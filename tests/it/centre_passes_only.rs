//! Outputs that hold only pixel-centre passes (depth, normal, ids) read no camera sample:
//! `shade` traces one ray per pixel centre and `trace_photons` is skipped, with the reasons
//! in `--stats-json` and `plan`; the passes' bytes are those of a render that also shades
//! the samples, and farm parts merge to them.

use std::path::{Path, PathBuf};

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// The GI Cornell box at `side`² pixels, 4 samples, 2000 global photons, with `outputs`.
fn cornell_gi(side: u32, outputs: &str) -> String {
    let scenes = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let text = std::fs::read_to_string(scenes.join("cornell_box_gi.ron")).unwrap();
    let geometry = scenes.join("lib/cornell_geometry.ron");
    let replaced = text
        .replace(
            r#""lib/cornell_geometry.ron""#,
            &format!("{:?}", geometry.display().to_string()),
        )
        .replace(
            "resolution: (256, 256)",
            &format!("resolution: ({side}, {side})"),
        )
        .replace("samples: 16,", "samples: 4,")
        .replace("photons: 50000,", "photons: 2000,")
        .replace(
            r#"outputs: [(file: "cornell_box_gi.png", passes: [Beauty])]"#,
            &format!("outputs: [{outputs}]"),
        );
    assert!(
        replaced.contains(outputs) && replaced.contains("samples: 4,"),
        "{replaced}"
    );
    replaced
}

/// The `--stats-json` row of `name`: (ran, reason, items, unit, rays).
fn stage(dir: &Path, name: &str) -> (bool, String, u64, String, u64) {
    let r = crate::common::stage_row(&dir.join("stats.json"), name);
    (r.ran, r.reason, r.items, r.unit, r.rays)
}

fn render_stats(dir: &Path) {
    let o = run_in(
        dir,
        &["render", "s.ron", "--stats", "--stats-json", "stats.json"],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
}

/// The plan's line of `name`: `" 4 trace_photons    skip …"`.
fn plan_line(dir: &Path, name: &str) -> String {
    let o = run_in(dir, &["plan", "s.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let out = String::from_utf8_lossy(&o.stdout).to_string();
    out.lines()
        .find(|l| l.split_whitespace().nth(1) == Some(name))
        .unwrap_or_else(|| panic!("no {name} in\n{out}"))
        .to_string()
}

const DEPTH_ONLY: &str = r#"(file: "depth_only.exr", passes: [Depth, ObjectId])"#;

const WHY: &str = r#"no output reads the shaded image: only pixel-centre passes ("depth_only.exr": Depth, ObjectId)"#;

#[test]
fn depth_and_id_outputs_trace_only_the_pixel_centres_and_no_photons() {
    let dir = scratch_dir("centre-passes-only");
    std::fs::write(dir.join("s.ron"), cornell_gi(16, DEPTH_ONLY)).unwrap();
    let photons_skip = format!("{WHY}; photon maps are read only by the shaded samples");
    let shade_run = format!("render camera 16×16, only the pixel-centre rays: {WHY}");
    assert_eq!(
        plan_line(&dir, "trace_photons"),
        format!(" 4 trace_photons    skip {photons_skip}")
    );
    assert_eq!(
        plan_line(&dir, "shade"),
        format!(" 6 shade            run  {shade_run}")
    );
    render_stats(&dir);
    assert_eq!(
        stage(&dir, "trace_photons"),
        (false, photons_skip, 0, String::new(), 0)
    );
    // One closest-hit ray per pixel centre, no shadow ray.
    assert_eq!(
        stage(&dir, "shade"),
        (true, shade_run, 256, "centre rays".into(), 256)
    );
    let centres = std::fs::read(dir.join("depth_only.exr")).unwrap();

    // The same passes beside a shaded PNG: samples and photons, and the same EXR bytes.
    let with_beauty = format!(r#"{DEPTH_ONLY}, (file: "b.png")"#);
    std::fs::write(dir.join("s.ron"), cornell_gi(16, &with_beauty)).unwrap();
    render_stats(&dir);
    let (ran, reason, ..) = stage(&dir, "trace_photons");
    assert!(ran, "{reason}");
    let (ran, reason, items, unit, _) = stage(&dir, "shade");
    assert_eq!(
        (ran, reason.as_str(), items, unit.as_str()),
        (true, "render camera 16×16", 1024, "samples")
    );
    assert!(std::fs::read(dir.join("depth_only.exr")).unwrap() == centres);

    // Farm parts (they shade: the merge may write any output) merge to the same bytes.
    std::fs::write(dir.join("s.ron"), cornell_gi(16, DEPTH_ONLY)).unwrap();
    std::fs::remove_file(dir.join("depth_only.exr")).unwrap();
    for (count, split) in [(2, "tiles"), (2, "samples")] {
        let parts: Vec<String> = (1..=count)
            .map(|k| {
                let name = format!("part_{k}.exr");
                let part = format!("{k}/{count}");
                let args = [
                    "render", "s.ron", "--part", &part, "--split", split, "-o", &name,
                ];
                let o = run_in(&dir, &args);
                assert!(o.status.success(), "{}", stderr_of(&o));
                name
            })
            .collect();
        let o = run_in(&dir, &["merge", &parts[0], &parts[1]]);
        assert!(o.status.success(), "{}", stderr_of(&o));
        assert!(
            std::fs::read(dir.join("depth_only.exr")).unwrap() == centres,
            "{split} parts differ"
        );
    }
}

/// Each output that reads a sample keeps them (and the photon maps): the coverage (`Alpha`,
/// an EXR's `A` beside `Beauty`), a component pass, a PNG; normals, ids and camera-space
/// passes read none.
#[test]
fn outputs_that_read_samples_keep_them() {
    let dir = scratch_dir("centre-passes-samples");
    for (outputs, centres_only) in [
        (r#"(file: "a.exr", passes: [Depth, Alpha])"#, false),
        (r#"(file: "a.exr", passes: [Depth, Emission])"#, false),
        (
            r#"(file: "a.exr", passes: [Beauty], beauty_alpha: false)"#,
            false,
        ),
        (r#"(file: "a.png", passes: [Alpha])"#, false),
        (
            r#"(file: "a.exr", passes: [Normal]), (file: "b.png")"#,
            false,
        ),
        (r#"(file: "a.exr", passes: [Normal, MaterialId])"#, true),
        (
            r#"(file: "a.exr", passes: [CameraDepth, CameraPosition])"#,
            true,
        ),
    ] {
        std::fs::write(dir.join("s.ron"), cornell_gi(16, outputs)).unwrap();
        let shade = plan_line(&dir, "shade");
        let photons = plan_line(&dir, "trace_photons");
        assert_eq!(
            shade.contains("only the pixel-centre rays"),
            centres_only,
            "{outputs}: {shade}"
        );
        assert_eq!(
            photons.contains(" skip "),
            centres_only,
            "{outputs}: {photons}"
        );
    }
}

/// A lit square filling part of a 64×64 view, 1 sample per pixel, with `outputs`.
fn square(outputs: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 1),
    cameras: [(name: "cam", fov_y: 40, resolution: (64, 64),
        placement: LookAt(eye: (0, 0, 4), target: (0, 0, 0)), outputs: [{outputs}])],
    lights: [(name: "lamp", kind: Point(position: (0, 2, 3)), intensity: 10)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.6, 0.6, 0.6)))],
    objects: [(name: "sq", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
        polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "sq_1", of: "sq")],
    groups: [(name: "world", members: ["sq_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// `(rays_closest, rays_occlusion)` of `shade` in `dir/stats.json`.
fn shade_rays(dir: &Path) -> (u64, u64) {
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("stats.json")).unwrap()).unwrap();
    let s = json["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == "shade")
        .unwrap()
        .clone();
    (
        s["rays_closest"].as_u64().unwrap(),
        s["rays_occlusion"].as_u64().unwrap(),
    )
}

/// Outputs that read no pixel-centre pass get no pixel-centre ray: a beauty PNG (with or
/// without alpha) takes one closest-hit ray per sample, 4096, where 8192 were traced, and
/// its bytes are those of the render that also writes a `Depth` pass (which traces them).
#[test]
fn no_pixel_centre_ray_where_no_output_reads_a_centre_pass() {
    let dir = scratch_dir("centre-rays-unread");
    let with_depth = r#"(file: "b.png"), (file: "a.png", passes: [Beauty, Alpha]), (file: "d.exr", passes: [Depth])"#;
    std::fs::write(dir.join("s.ron"), square(with_depth)).unwrap();
    render_stats(&dir);
    let (closest, occlusion) = shade_rays(&dir);
    assert_eq!(closest, 2 * 4096, "the centre rays and the samples'");
    let beauty = std::fs::read(dir.join("b.png")).unwrap();
    let alpha = std::fs::read(dir.join("a.png")).unwrap();
    for outputs in [
        r#"(file: "b.png"), (file: "a.png", passes: [Beauty, Alpha])"#,
        r#"(file: "b.png", passes: [Beauty]), (file: "a.exr", beauty_alpha: false)"#,
    ] {
        for f in ["b.png", "a.png"] {
            let _ = std::fs::remove_file(dir.join(f));
        }
        std::fs::write(dir.join("s.ron"), square(outputs)).unwrap();
        render_stats(&dir);
        assert_eq!(shade_rays(&dir), (4096, occlusion), "{outputs}");
        assert!(
            std::fs::read(dir.join("b.png")).unwrap() == beauty,
            "{outputs}"
        );
        if outputs.contains("a.png") {
            assert!(std::fs::read(dir.join("a.png")).unwrap() == alpha);
        }
    }
}
