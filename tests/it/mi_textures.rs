//! Issue 13: mental ray's base texture shaders in `.mi` — `color texture "name" "file"`,
//! `mib_texture_lookup` of `mib_texture_remap` of `mib_texture_vector`, and the vertices'
//! `t` references — render the texels where mental ray puts them (every pixel against a
//! closed-form bilinear lookup of the fixture PNG); malformed chains give exact located
//! messages.

use std::path::{Path, PathBuf};

use glam::Vec3;
use stagelight::components::{Camera, RenderCamera};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::import::to_ron::to_ron;
use stagelight::scene::{load_scene, load_scene_str, LoadedScene};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mi_textures/tiles.mi")
}

/// The fixture PNG's texels (linear: 0 and 255 decode to 0 and 1 exactly), `[row][column]`
/// with row 0 at v = 0 (the file's bottom row).
const TEXELS: [[Vec3; 2]; 2] = [
    [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)],
    [Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 1.0, 1.0)],
];

/// Bilinear lookup with repeat wrap, texel centres at `(i + ½) / 2`.
fn lookup(u: f64, v: f64) -> [f64; 3] {
    let s = u * 2.0 - 0.5;
    let t = v * 2.0 - 0.5;
    let (i, j) = (s.floor(), t.floor());
    let (fs, ft) = (s - i, t - j);
    let texel = |i: f64, j: f64| TEXELS[j.rem_euclid(2.0) as usize][i.rem_euclid(2.0) as usize];
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let at = |i, j| f64::from(texel(i, j)[c]);
        *o = (1.0 - ft) * ((1.0 - fs) * at(i, j) + fs * at(i + 1.0, j))
            + ft * ((1.0 - fs) * at(i, j + 1.0) + fs * at(i + 1.0, j + 1.0));
    }
    out
}

fn render(mut scene: LoadedScene) -> (u32, u32, Vec<Vec3>) {
    let size = scene
        .world
        .query_mut::<(&Camera, &RenderCamera)>()
        .into_iter()
        .map(|(c, _)| (c.width, c.height))
        .next()
        .expect("a render camera");
    let mut settings = scene.settings.clone();
    settings.spp = 1;
    settings.adaptive = None;
    let frame = crate::common::render(&mut scene.world, settings);
    (
        size.0,
        size.1,
        frame.outputs.image.expect("an image").beauty,
    )
}

/// Every pixel inside the plane z = −1: `mib_illum_lambert` with `diffuse` = the texel
/// lookup at `frac(2·uv)` (`repeat 2 2 1`), lit by the unattenuated point light at the eye:
/// `lookup · cos θ`, within 1 % (+ 10⁻³ absolute for the dark channels).
fn check_tiles(scene: LoadedScene) {
    let (w, h, beauty) = render(scene);
    let (tan_x, tan_y) = (16.0 / 12.0, 1.0);
    let pixel = 2.0 * tan_x / f64::from(w);
    let mut checked = 0;
    for j in 1..h - 1 {
        for i in 0..w {
            let x = ((f64::from(i) + 0.5) / f64::from(w) * 2.0 - 1.0) * tan_x;
            let y = (1.0 - (f64::from(j) + 0.5) / f64::from(h) * 2.0) * tan_y;
            if x.abs() > 1.0 - pixel {
                continue;
            }
            // The one sample lies somewhere in the pixel: the value must lie within the
            // range the formula takes over the pixel (a 5 × 5 grid of points).
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for a in 0..5 {
                for b in 0..5 {
                    let x = x + (f64::from(a) / 4.0 - 0.5) * pixel;
                    let y = y + (f64::from(b) / 4.0 - 0.5) * pixel;
                    // The plane's corners carry uv (0, 0) at (−1, −1) to (1, 1) at (1, 1).
                    let (u, v) = ((x + 1.0) / 2.0, (y + 1.0) / 2.0);
                    let colour = lookup((2.0 * u).fract(), (2.0 * v).fract());
                    let cos = 1.0 / (x * x + y * y + 1.0).sqrt();
                    for c in 0..3 {
                        lo[c] = lo[c].min(colour[c] * cos);
                        hi[c] = hi[c].max(colour[c] * cos);
                    }
                }
            }
            let got = beauty[(j * w + i) as usize];
            for c in 0..3 {
                let g = f64::from(got[c]);
                assert!(
                    g >= lo[c] * 0.99 - 1e-3 && g <= hi[c] * 1.01 + 1e-3,
                    "pixel ({i}, {j}) channel {c}: {g} outside [{}, {}]",
                    lo[c],
                    hi[c]
                );
            }
            checked += 1;
        }
    }
    assert!(checked > w * h / 2, "{checked}");
}

#[test]
fn mib_texture_lookup_shows_the_texels_where_mental_ray_puts_them() {
    let bytes = std::fs::read(fixture()).unwrap();
    let read = read_mi(&fixture(), &bytes).unwrap();
    let warned: Vec<&str> = read
        .warnings
        .iter()
        .map(|w| w.problem.message.as_str())
        .filter(|m| !m.contains("is written as"))
        .collect();
    assert!(warned.is_empty(), "{warned:?}");
    check_tiles(load_scene(&fixture()).unwrap());
    // The same through RON (`convert`): the bind is an Image node of a Repeat.
    let ron = to_ron(&read.desc).unwrap();
    assert!(ron.contains("Image("), "{ron}");
    check_tiles(load_scene_str(&ron, &fixture().with_extension("ron")).unwrap());
}

#[test]
fn malformed_texture_chains_give_exact_located_messages() {
    let text = std::fs::read_to_string(fixture()).unwrap();
    let dir =
        crate::common::scratch_root().join(format!("stagelight_mi_tex_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            text.replace("(\"tex\" \"quads\"", "(\"tex\" \"qauds\""),
            "bad.mi:11:45: error: unknown texture \"qauds\"",
        ),
        (
            text.replace(
                "\"repeat\" 2 2 1)",
                "\"transform\" 0 1 0 0  1 0 0 0  0 0 1 0  0 0 0 1)",
            ),
            "bad.mi:10:68: error: only scale-and-translation \"transform\" matrices of \
             \"mib_texture_remap\" are mapped",
        ),
        (
            text.replace("\"input\" = \"coord\"", "\"input\" = \"lookup\""),
            "bad.mi:10:45: error: \"lookup\" is a \"mib_texture_lookup\", not a texture \
             coordinate shader",
        ),
        (
            text.replace(
                "color texture \"quads\" \"quads.png\"",
                "color texture \"quads\" 3",
            ),
            "bad.mi:7:23: error: texture \"quads\" needs an image file (a procedural texture \
             is not mapped)\nbad.mi:11:45: error: unknown texture \"quads\"",
        ),
        (
            text.replace("v 3 t 7", "v 3 t 9"),
            "bad.mi:90:7: error: vector index 9 is out of range (the group has 8 vectors)",
        ),
    ];
    for (bad, want) in cases {
        let path = dir.join("bad.mi");
        std::fs::write(&path, &bad).unwrap();
        let got = match load_scene(&path) {
            Ok(_) => "ok".to_string(),
            // The errors alone (the file's warnings come with them: `e.1`).
            Err(e) => {
                e.0.iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join("\n")
            }
        };
        let prefix = format!("{}/", dir.display());
        assert_eq!(got.replace(&prefix, "").trim_end(), want);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
