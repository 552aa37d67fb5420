//! The tutorial's imager shader `myImager` (seed 001 §3.2.3, its last version) built into
//! the RIB reader as the camera imager's `pattern`: every pixel of the PNG is the closed form
//! `mix(red, yellow, 1 − smoothstep(0.3, 0.5, |P/(xres, yres) − (0.5, 0.5)|))` of its centre's
//! raster position (geometry included, display values after `Exposure`, alpha 1); the
//! converted RON renders the same bytes; parameters and unknown imager names are located
//! messages.

use std::path::Path;

use stagelight::image_io::png_codec::{read_png, DecodedPng, Samples};
use stagelight::scene::import::rib::read_rib;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

const W: u32 = 40;
const H: u32 = 30;

/// A 40 × 30 scene behind `Imager "myImager"`: a lit sphere over the image centre, display
/// gamma 2.2 (which the imager's display values do not get), an RGBA PNG.
fn scene() -> String {
    format!(
        "Format {W} {H} 1\nDisplay \"t.png\" \"file\" \"rgba\"\nExposure 1.0 2.2\n\
         PixelSamples 1 1\nProjection \"perspective\" \"fov\" [90]\nImager \"myImager\"\n\
         WorldBegin\nLightSource \"pointlight\" 1 \"intensity\" [10]\nTranslate 0 0 3\n\
         Sphere 1 -1 1 360\nWorldEnd\n"
    )
}

/// The RSL `smoothstep`: 0 below `min`, 1 from `max`, `t²(3 − 2t)` between.
fn smoothstep(min: f64, max: f64, v: f64) -> f64 {
    let t = ((v - min) / (max - min)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// `myImager`'s green at pixel `(x, y)` (its red is 1 and its blue 0 everywhere):
/// `inDisk = 1 − smoothstep(radius − fuzz, radius + fuzz, distance)` at the pixel centre.
fn in_disk(x: u32, y: u32) -> f64 {
    let here = ((x as f64 + 0.5) / W as f64, (y as f64 + 0.5) / H as f64);
    let dist = (here.0 - 0.5).hypot(here.1 - 0.5);
    1.0 - smoothstep(0.4 - 0.1, 0.4 + 0.1, dist)
}

fn rgba8(png: &DecodedPng) -> &[u8] {
    assert_eq!((png.width, png.height, png.channels), (W, H, 4));
    match &png.samples {
        Samples::Eight(s) => s,
        Samples::Sixteen(_) => panic!("16-bit"),
    }
}

/// Asserts every pixel of the PNG at `path` is the closed form within 1/255, alpha 255;
/// returns the green byte of pixel (35, 15), which lies in the fuzz band.
fn assert_disk(path: &Path) -> u8 {
    let png = read_png(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let s = rgba8(&png);
    for y in 0..H {
        for x in 0..W {
            let i = 4 * (y * W + x) as usize;
            let g = 255.0 * in_disk(x, y);
            assert!(
                s[i] == 255 && (f64::from(s[i + 1]) - g).abs() <= 1.0 && s[i + 2] == 0,
                "pixel ({x}, {y}): {:?}, expected (255, {g:.2}, 0)",
                &s[i..i + 3]
            );
            assert_eq!(s[i + 3], 255, "alpha of pixel ({x}, {y})");
        }
    }
    s[4 * (15 * W + 35) as usize + 1]
}

#[test]
fn my_imager_paints_every_pixel_with_the_closed_form_disk() {
    let dir = scratch_dir("rib-my-imager");
    std::fs::write(dir.join("t.rib"), scene()).unwrap();
    let o = run_in(&dir, &["render", "t.rib", "--spp", "1"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert!(!stderr_of(&o).contains("warning"), "{}", stderr_of(&o));
    let band = assert_disk(&dir.join("t.png"));
    // (35, 15): centre (0.8875, 0.5167), 0.388 from (0.5, 0.5): between radius ∓ fuzz, so
    // neither colour; 255·(1 − smoothstep) = 150.6, not 2.2-gamma-encoded (≈ 201).
    let g = 255.0 * in_disk(35, 15);
    assert!((150.0..151.0).contains(&g), "{g}");
    assert!((f64::from(band) - g).abs() <= 1.0, "{band}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn converted_ron_writes_the_pattern_and_renders_the_same_bytes() {
    let dir = scratch_dir("rib-my-imager-convert");
    std::fs::write(dir.join("t.rib"), scene()).unwrap();
    let o = run_in(&dir, &["convert", "t.rib", "-o", "t.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let ron = std::fs::read_to_string(dir.join("t.ron")).unwrap();
    let flat: String = ron.split_whitespace().collect();
    assert!(
        flat.contains(
            "pattern:Disk(center:(0.5,0.5),radius:0.4,fuzz:0.1,inside:(1.0,1.0,0.0),\
             outside:(1.0,0.0,0.0),)"
        ),
        "{ron}"
    );
    for (scene, png) in [("t.rib", "a.png"), ("t.ron", "b.png")] {
        let o = run_in(&dir, &["render", scene, "--spp", "1", "-o", png]);
        assert!(o.status.success(), "{}", stderr_of(&o));
    }
    let (a, b) = (dir.join("a.png"), dir.join("b.png"));
    assert_disk(&a);
    assert!(
        std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(),
        "the PNGs differ"
    );
    // The RON's pattern is checked like any value: a negative radius is a located error.
    let bad = ron.replacen("radius: 0.4", "radius: -0.4", 1);
    let line = bad
        .lines()
        .position(|l| l.contains("radius: -0.4"))
        .unwrap()
        + 1;
    std::fs::write(dir.join("bad.ron"), &bad).unwrap();
    let o = run_in(&dir, &["check", "bad.ron"]);
    assert!(!o.status.success());
    let err = stderr_of(&o);
    assert!(
        err.contains(&format!("bad.ron:{line}:"))
            && err.contains("error: radius must not be negative, found -0.4"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The messages of reading `text` as `t.rib`, errors if it is refused, else warnings.
fn messages(name: &str, text: &str) -> Vec<String> {
    let dir = scratch_dir(name);
    let path = dir.join("t.rib");
    std::fs::write(&path, text).unwrap();
    let shown = match read_rib(&path, text.as_bytes()) {
        Ok(scene) => scene.warnings.iter().map(|w| w.to_string()).collect(),
        Err(errors) => errors.iter().map(|e| e.to_string()).collect::<Vec<_>>(),
    };
    let _ = std::fs::remove_dir_all(&dir);
    let prefix = path.display().to_string();
    shown.iter().map(|m| m.replace(&prefix, "t.rib")).collect()
}

#[test]
fn my_imager_takes_no_parameters() {
    assert_eq!(
        messages(
            "rib-my-imager-params",
            "Imager \"myImager\" \"fuzz\" [0.2]\nImager \"myImager\" \"float radius\" [0.3]\n\
             WorldBegin\nWorldEnd\n"
        ),
        [
            "t.rib:1:19: error: unknown parameter \"fuzz\" of imager \"myImager\"\n  help: no \
             parameters are defined",
            "t.rib:2:19: error: unknown parameter \"radius\" of imager \"myImager\"\n  help: no \
             parameters are defined",
        ]
    );
}

#[test]
fn an_unknown_imager_is_ignored_with_the_imagers_we_have() {
    assert_eq!(
        messages(
            "rib-my-imager-unknown",
            "Imager \"myimager\"\nImager \"cmyk\"\nWorldBegin\nWorldEnd\n"
        ),
        [
            "t.rib:1:8: warning: ignored imager shader \"myimager\": not one of ours\n  help: \
             did you mean \"myImager\"?",
            "t.rib:2:8: warning: ignored imager shader \"cmyk\": not one of ours\n  help: \
             expected \"background\" or \"myImager\"",
        ]
    );
}

#[test]
fn the_last_imager_called_is_the_one_used() {
    let read = |text: &str| {
        let path = Path::new("t.rib");
        let scene = read_rib(path, text.as_bytes()).unwrap();
        let imager = scene.desc.cameras[0].imager.clone().unwrap();
        (imager.background, imager.pattern.is_some())
    };
    let background = "Imager \"background\" \"background\" [0 0 1]\n";
    let disk = "Imager \"myImager\"\n";
    let world = "WorldBegin\nWorldEnd\n";
    assert_eq!(read(&format!("{background}{disk}{world}")), (None, true));
    assert_eq!(
        read(&format!("{disk}{background}{world}")),
        (Some((0.0, 0.0, 1.0)), false)
    );
}
