//! The `Direct` integrator's shadow rays toward an area light's samples, traced as
//! common-origin packets (`STAGELIGHT_SHADOW_PACKETS=on`, the default on large scenes) or
//! one query per sample (`off`): the same image bytes from the command line.

use std::path::PathBuf;
use std::process::Command;

/// The PNG bytes of `scene` rendered at 1 spp on `threads` threads with the packets `mode`
/// (`None`: the default choice).
fn render(test: &str, scene: &str, mode: Option<&str>, threads: &str) -> Vec<u8> {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight-shadow-packets-{test}-{}-{}",
        mode.unwrap_or("default"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out.png");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_stagelight"));
    cmd.arg("render")
        .arg(
            PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join("assets/scenes")
                .join(scene),
        )
        .arg("-o")
        .arg(&out)
        .args(["--spp", "1", "--threads", threads]);
    match mode {
        Some(m) => cmd.env("STAGELIGHT_SHADOW_PACKETS", m),
        None => cmd.env_remove("STAGELIGHT_SHADOW_PACKETS"),
    };
    let o = cmd.output().expect("run stagelight");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(&out).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    bytes
}

/// `procedural_shapes.ron` (55,494 triangles, a rectangular light of 8 samples: packets by
/// default) and `stairs.ron` (1,924 triangles: packets only when forced) give the same bytes
/// with the packets forced on, forced off and by default, at 1 and 2 threads.
#[test]
fn packets_and_one_query_per_sample_give_the_same_image() {
    for scene in ["procedural_shapes.ron", "stairs.ron"] {
        let off = render("same", scene, Some("off"), "1");
        assert!(off.len() > 1000, "{scene}: an image");
        for (mode, threads) in [(Some("on"), "1"), (Some("on"), "2"), (None, "2")] {
            let other = render("same", scene, mode, threads);
            assert!(
                other == off,
                "{scene}: {mode:?} at {threads} threads differs from off"
            );
        }
    }
}
