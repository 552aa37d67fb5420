//! The grid, bvh and photon diagnostic views are drawn from pixel-centre rays: `shade`
//! takes no sample for them (unless an output reads the coverage or a component pass), and
//! `trace_photons` runs only for the photon view. The views' bytes are pinned: they are
//! those written when the samples were still taken.

use std::path::Path;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// A glass ball over a floor under a point light, caustics on, 4 samples, 40×40, with the
/// camera `outputs`.
fn ball(outputs: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: 4, caustics: (photons: 4000, gather: 20)),
    cameras: [(name: "cam", fov_y: 50, resolution: (40, 40),
        placement: LookAt(eye: (2.5, 0, 6), target: (2.5, 0, 0), up: (0, 1, 0)),
        outputs: [{outputs}])],
    lights: [(name: "lamp", kind: Point(position: (-2, 0, 4)), intensity: 40)],
    materials: [
        (name: "floor", shader: Lambert(albedo: (0.7, 0.7, 0.7))),
        (name: "glass", shader: Dielectric(ior: 1.5)),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 10, size_y: 10), material: "floor"),
        (name: "ball", mesh: Sphere(radius: 0.6), material: "glass",
         approximation: Parametric(u: 16, v: 8)),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "ball_1", of: "ball", transform: [Translate((1, 0, 0.9))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ball_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// FNV-1a (64 bits) of `bytes`.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// `(ran, reason, items, unit)` of `name` in `stats.json`.
fn stage(dir: &Path, name: &str) -> (bool, String, u64, String) {
    let r = crate::common::stage_row(&dir.join("stats.json"), name);
    (r.ran, r.reason, r.items, r.unit)
}

#[test]
fn centre_ray_views_take_no_samples_and_keep_their_bytes() {
    let dir = scratch_dir("diagnostic-centre-rays");
    std::fs::write(dir.join("s.ron"), ball(r#"(file: "ball.png")"#)).unwrap();
    // FNV-1a of the PNGs written before this change (the samples taken, then replaced).
    for (view, name, hash) in [
        ("grid:world:0.5", "grid", 0x2c91_aac7_e833_78e3u64),
        ("bvh:depth", "bvh", 0x85e7_bc69_f264_76b8),
        ("photon:density:1000", "photon", 0x4660_638a_0b28_538a),
    ] {
        let o = run_in(
            &dir,
            &[
                "render",
                "s.ron",
                "--diagnostic",
                view,
                "--stats-json",
                "stats.json",
            ],
        );
        assert!(o.status.success(), "{}", stderr_of(&o));
        let why = format!(
            "the diagnostic {name} view is drawn from pixel-centre rays and no output reads the coverage or a component pass"
        );
        assert_eq!(
            stage(&dir, "shade"),
            (
                true,
                format!(
                    "render camera 40×40, diagnostic {name}, only the pixel-centre rays: {why}"
                ),
                1600,
                "centre rays".into()
            )
        );
        let (ran, reason, ..) = stage(&dir, "trace_photons");
        if name == "photon" {
            assert_eq!((ran, reason.as_str()), (true, "caustics (4000 photons)"));
        } else {
            assert_eq!(
                (ran, reason),
                (
                    false,
                    format!("{why}; photon maps are read only by the shaded samples")
                )
            );
        }
        let png = std::fs::read(dir.join("ball.png")).unwrap();
        assert_eq!(fnv1a(&png), hash, "{view}");
    }
    // An EXR's `A` beside `Beauty` is the samples' coverage: they are taken.
    std::fs::write(dir.join("s.ron"), ball(r#"(file: "ball.exr")"#)).unwrap();
    let o = run_in(
        &dir,
        &[
            "render",
            "s.ron",
            "--diagnostic",
            "grid:world:0.5",
            "--stats-json",
            "stats.json",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert_eq!(
        stage(&dir, "shade"),
        (
            true,
            "render camera 40×40, diagnostic grid".into(),
            6400,
            "samples".into()
        )
    );
}
