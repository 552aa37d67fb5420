//! The tutorial's RSL shaders built into the RIB reader (seed 001; `docs/rib.md`, *The
//! tutorial's shaders*): each renders the closed form of its printed source per pixel
//! (`myLight`, `mySurface`, `simplemirror`, `stairs`) or reads as the description its source
//! computes (`myDisplacement`); unknown parameters are located errors with "did you mean";
//! the seed's scenes that call them read without a fallback warning.

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use stagelight::scene::desc::{AxisDesc, ScalarDesc};
use stagelight::scene::import::rib::read_rib;
use stagelight::scene::import::to_ron::to_ron;
use stagelight::scene::load_scene;

/// Writes `text` as `name` in a fresh folder of the temporary directory.
fn write_rib(name: &str, text: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_rib_tutorial_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Renders the RIB at `path` at its own resolution: the beauty pass.
fn render(path: &Path) -> Vec<Vec3> {
    let mut scene = load_scene(path).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    frame.outputs.image.expect("an image").beauty
}

const N: usize = 40;

/// A square image of one ray per pixel centre, no gamma, 90° field of view, then `world`.
fn scene(world: &str) -> String {
    format!(
        "Format {N} {N} 1\nPixelSamples 1 1\nPixelFilter \"gaussian\" 0.0001 0.0001\n\
         Exposure 1 1\nProjection \"perspective\" \"fov\" [90]\nWorldBegin\n{world}WorldEnd\n"
    )
}

/// The RIB camera-space direction through the centre of pixel `(x, y)` (row 0 at the top),
/// scaled to z = 1.
fn ray(x: usize, y: usize) -> DVec3 {
    let sx = -1.0 + 2.0 * (x as f64 + 0.5) / N as f64;
    let sy = 1.0 - 2.0 * (y as f64 + 0.5) / N as f64;
    DVec3::new(sx, sy, 1.0)
}

/// The unit square `[-1, 1]²` at z = 0 as a bilinear patch.
const PATCH: &str = "Patch \"bilinear\" \"P\" [ -1 -1 0 1 -1 0 -1 1 0 1 1 0 ]\n";

/// Asserts every pixel of `got` is `expected(x, y)` within 1e-3 (where it is `Some`).
fn assert_closed_form(got: &[Vec3], mut expected: impl FnMut(usize, usize) -> Option<DVec3>) {
    let mut checked = 0;
    for y in 0..N {
        for x in 0..N {
            let Some(e) = expected(x, y) else { continue };
            let g = got[y * N + x].as_dvec3();
            assert!(
                (g - e).abs().max_element() < 1e-3,
                "pixel ({x}, {y}): {g} vs the closed form {e}"
            );
            checked += 1;
        }
    }
    assert!(checked > N * N / 2, "{checked} pixels checked");
}

#[test]
fn my_light_fades_linearly_from_near_to_far_without_inverse_square() {
    // myLight at the eye (from (0,0,0)), a matte wall at z = 6 (Kd 1): Cs·Kd·Cl·cos with
    // Cl = intensity·lightcolor·(1 − (len − near)/(far − near)), 1 below near.
    let (near, far, intensity, z) = (6.5, 9.0, 2.0, 6.0);
    let path = write_rib(
        "my_light.rib",
        &scene(&format!(
            "LightSource \"myLight\" 1 \"float intensity\" [{intensity}] \"float near\" \
             [{near}] \"float far\" [{far}] \"color lightcolor\" [1 0.5 0.25]\n\
             Surface \"matte\" \"Kd\" [1]\nTranslate 0 0 {z}\nScale 8 8 1\n{PATCH}"
        )),
    );
    let beauty = render(&path);
    let mut ramped = 0;
    assert_closed_form(&beauty, |x, y| {
        let len = (ray(x, y) * z).length();
        let cos = z / len;
        let brightness = if len < near {
            1.0
        } else if len > far {
            0.0
        } else {
            1.0 - (len - near) / (far - near)
        };
        ramped += usize::from(brightness > 0.05 && brightness < 0.95);
        Some(DVec3::new(1.0, 0.5, 0.25) * (intensity * brightness * cos))
    });
    // The ramp is exercised, not only its ends (1/d² would give other values everywhere).
    assert!(ramped > 100, "{ramped} pixels on the ramp");
}

#[test]
fn my_surface_is_the_repeated_soft_disk_times_ka_ambient() {
    // Only an ambient light: Ci = myCs·Ka·ambient(), myCs = mix(red, yellow, inDisk) over
    // (mod(10s, 1), mod(10t, 1)); the patch at z = 1 fills the 90° view exactly.
    let path = write_rib(
        "my_surface.rib",
        &scene(&format!(
            "LightSource \"ambientlight\" 1 \"intensity\" [0.8]\n\
             Surface \"mySurface\" \"Ka\" [0.5]\nTranslate 0 0 1\n{PATCH}"
        )),
    );
    let beauty = render(&path);
    let smoothstep = |a: f64, b: f64, x: f64| {
        let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    };
    let mut inside = 0;
    assert_closed_form(&beauty, |x, y| {
        let r = ray(x, y);
        let (s, t) = ((r.x + 1.0) / 2.0, (r.y + 1.0) / 2.0);
        let (ss, tt) = ((s * 10.0).rem_euclid(1.0), (t * 10.0).rem_euclid(1.0));
        let dist = ((ss - 0.5).powi(2) + (tt - 0.5).powi(2)).sqrt();
        let in_disk = 1.0 - smoothstep(0.3, 0.5, dist);
        inside += usize::from(in_disk > 0.99);
        Some(DVec3::new(1.0, in_disk, 0.0) * (0.5 * 0.8))
    });
    assert!(inside > 100, "{inside} pixels inside a disk");
}

#[test]
fn simplemirror_shows_the_traced_reflection() {
    // A mirror facing the camera at z = 2 reflects a constant wall behind the eye.
    let path = write_rib(
        "simplemirror.rib",
        &scene(&format!(
            "AttributeBegin\nSurface \"simplemirror\"\nColor [1 1 0]\nTranslate 0 0 2\n\
             Scale 10 10 1\n{PATCH}AttributeEnd\n\
             AttributeBegin\nSurface \"constant\"\nColor [0.2 0.6 0.9]\nTranslate 0 0 -1\n\
             Scale 100 100 1\n{PATCH}AttributeEnd\n"
        )),
    );
    let beauty = render(&path);
    assert_closed_form(&beauty, |_, _| Some(DVec3::new(0.2, 0.6, 0.9)));
}

/// Half the field of view of [`stairs_scene`], as its tangent.
const STAIRS_TAN: f64 = 0.221_694_662_639_660_9; // tan(12.5°)

/// The seed's stairs patch (`stairs.shader.rib`'s `PatchMesh`) turned to face the eye under
/// `surface`, lit by a distant light of intensity 1 arriving from `wi = (0, −1, −2)/√5`
/// (toward the light). `Rotate 180 0 1 0` maps object `(x, y, z)` to `(−x, y, −z)`: the
/// tread normal `up = (0, 0, 1)` becomes `(0, 0, −1)`, toward the eye, the riser normal
/// `front = (0, −1, 0)` stays; v runs from y = −1 (z = 7) to y = 1 (z = 5).
fn stairs_scene(surface: &str) -> String {
    format!(
        "Format {N} {N} 1\nPixelSamples 1 1\nPixelFilter \"gaussian\" 0.0001 0.0001\n\
         Exposure 1 1\nProjection \"perspective\" \"fov\" [25]\nWorldBegin\n\
         LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 1 2]\n{surface}\n\
         Translate 0 0 6\nRotate 180 0 1 0\n\
         PatchMesh \"bilinear\" 2 \"nonperiodic\" 2 \"nonperiodic\" \
         \"P\" [-1 -1 -1 1 -1 -1 -1 1 1 1 1 1]\nWorldEnd\n"
    )
}

/// The patch's `v` under the centre of pixel `(x, y)` of [`stairs_scene`] and the unit
/// direction toward the eye there; `None` off the patch or within `margin` of its edges.
fn stairs_hit(x: usize, y: usize, margin: f64) -> Option<(f64, DVec3)> {
    let d = ray(x, y) * DVec3::new(STAIRS_TAN, STAIRS_TAN, 1.0);
    // The plane y + z = 6 (world y = 2v − 1, z = 7 − 2v).
    let t = 6.0 / (d.y + d.z);
    let p = d * t;
    let v = (p.y + 1.0) / 2.0;
    let inside = p.x.abs() < 1.0 - margin && v > margin && v < 1.0 - margin;
    inside.then(|| (v, -d.normalize()))
}

/// `stairs`' `Ci` for the unit normal `n` with Cs = 1, Ka·ambient() = 0 and one light of
/// `Cl = 1` from `wi`: `Kd·(n·wi) + Ks·max(0, n·H)^(1/roughness)`, `H = normalize(wi + V)`.
fn stairs_ci(n: DVec3, wo: DVec3, kd: f64, ks: f64, roughness: f64) -> f64 {
    let wi = DVec3::new(0.0, -1.0, -2.0).normalize();
    let h = (wi + wo).normalize();
    kd * n.dot(wi).max(0.0) + ks * n.dot(h).max(0.0).powf(1.0 / roughness)
}

/// The printed `stairs` `Nf` (§4.2, the version with `fuzz`), branch for branch.
fn printed_stairs_nf(v: f64, steps: f64, fuzz: f64, front: DVec3, up: DVec3) -> DVec3 {
    let sv = (v * steps).rem_euclid(1.0);
    if sv < 0.5 - fuzz {
        if sv > fuzz || v * steps <= fuzz {
            front
        } else {
            let p = 0.5 + sv / (2.0 * fuzz);
            (1.0 - p) * up + p * front
        }
    } else if sv > 0.5 + fuzz {
        if sv < 1.0 - fuzz || v >= 1.0 - fuzz / steps {
            up
        } else {
            let p = (sv - 1.0 + fuzz) / (2.0 * fuzz);
            (1.0 - p) * up + p * front
        }
    } else {
        let p = (sv - 0.5 + fuzz) / (2.0 * fuzz);
        (1.0 - p) * front + p * up
    }
}

#[test]
fn stairs_shades_with_the_object_space_riser_and_tread_normals() {
    // One step (steps 1, a negligible fuzz): the riser normal `front` below v = ½, the tread
    // normal `up` above, in the object space of the patch, each exactly (Kd·cos θ·E plus the
    // highlight about it), though both lean 45° from the patch's own normal.
    let path = write_rib(
        "stairs_one_step.rib",
        &stairs_scene(
            "Surface \"stairs\" \"float steps\" [1] \"float fuzz\" [0.0001] \"float Kd\" [0.8] \
             \"float Ks\" [0.3] \"float roughness\" [0.25]",
        ),
    );
    let beauty = render(&path);
    let (front, up) = (DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.0, 0.0, -1.0));
    let mut seen = [0; 2];
    for (y, x) in (0..N).flat_map(|y| (0..N).map(move |x| (y, x))) {
        let Some((v, wo)) = stairs_hit(x, y, 0.02) else {
            continue;
        };
        if (v - 0.5).abs() < 0.02 {
            continue;
        }
        seen[usize::from(v > 0.5)] += 1;
        let n = if v < 0.5 { front } else { up };
        let e = stairs_ci(n, wo, 0.8, 0.3, 0.25);
        let g = beauty[y * N + x].as_dvec3();
        assert!(
            (g - DVec3::splat(e)).abs().max_element() < 1e-3,
            "pixel ({x}, {y}), v = {v}: {g} vs the closed form {e}"
        );
    }
    assert!(
        seen.iter().all(|&n| n > 200),
        "{seen:?} riser and tread pixels"
    );
}

#[test]
fn stairs_with_four_steps_alternates_riser_and_tread_rows() {
    // The printed default (steps 4, fuzz 0.05; Ks 0 for two flat values): up the centre
    // column the rows go riser, tread, riser, tread, … four times, each band Kd·cos θ of its
    // normal — 0.5·(1/√5) on a riser, 0.5·(2/√5) on a tread — and every row is Kd·cos θ of
    // the printed `Nf` (normalised) at its v, the blend near the edges included.
    let path = write_rib(
        "stairs_four_steps.rib",
        &stairs_scene("Surface \"stairs\" \"float Ks\" [0]"),
    );
    let beauty = render(&path);
    let (riser, tread) = (0.5 / 5f64.sqrt(), 1.0 / 5f64.sqrt());
    let (front, up) = (DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.0, 0.0, -1.0));
    let mut bands = Vec::new();
    let (mut rows, mut blended) = (0, 0);
    for y in (0..N).rev() {
        let Some((v, wo)) = stairs_hit(N / 2, y, 0.0) else {
            continue;
        };
        rows += 1;
        let nf = printed_stairs_nf(v, 4.0, 0.05, front, up).normalize();
        let e = stairs_ci(nf, wo, 0.5, 0.0, 0.1);
        let g = f64::from(beauty[y * N + N / 2].x);
        assert!((g - e).abs() < 1e-3, "row {y} (v = {v}): {g} vs {e}");
        let band = if (g - riser).abs() < 1e-3 {
            "riser"
        } else if (g - tread).abs() < 1e-3 {
            "tread"
        } else {
            blended += 1;
            continue;
        };
        if bands.last() != Some(&band) {
            bands.push(band);
        }
    }
    assert!(blended < rows / 4, "{blended} of {rows} rows blended");
    assert!(rows > 25, "{rows} rows on the patch");
    assert_eq!(
        bands,
        ["riser", "tread"].repeat(4),
        "bands from the bottom up"
    );
}

#[test]
fn stairs_converts_to_ron_as_plastic_with_an_object_space_normal() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/seeds/rib/stairs_shader.rib");
    let bytes = std::fs::read(&path).unwrap();
    let text = to_ron(&read_rib(&path, &bytes).unwrap().desc).unwrap();
    let squeezed: String = text.split_whitespace().collect();
    assert!(
        squeezed.contains(
            "bump:Bump(object_normal:Mix(a:(0.0,-1.0,0.0),b:(0.0,0.0,1.0),t:Steps(uv:Uv,steps:100.0,fuzz:0.05,),),scale:1.0,)"
        ),
        "{text}"
    );
}

#[test]
fn my_displacement_is_the_sum_of_the_printed_sines() {
    let path = write_rib(
        "my_displacement.rib",
        &scene(&format!(
            "Attribute \"render\" \"truedisplacement\" [1]\n\
             Displacement \"myDisplacement\"\nTranslate 0 0 3\n{PATCH}"
        )),
    );
    let bytes = std::fs::read(&path).unwrap();
    let desc = read_rib(&path, &bytes).unwrap().desc;
    let d = desc.objects[0].displacement.as_ref().expect("displaced");
    let sine = |axis| ScalarDesc::Sine {
        amplitude: 0.1,
        factor: 20.0,
        axis,
    };
    assert_eq!(
        format!("{:?}", d.shader),
        format!(
            "{:?}",
            ScalarDesc::Sum(vec![sine(AxisDesc::V), sine(AxisDesc::U)])
        )
    );
}

#[test]
fn unknown_parameters_of_the_tutorial_shaders_are_located_errors() {
    let path = write_rib(
        "tutorial_params.rib",
        &scene(
            "LightSource \"myLight\" 1 \"float nearr\" [3]\n\
             Surface \"mySurface\" \"float roughnes\" [0.2]\n\
             Displacement \"myDisplacement\" \"float amp\" [1]\n\
             Sphere 1 -1 1 360\n\
             Surface \"simplemirror\" \"Kr\" [1]\nSphere 1 -1 1 360\n\
             Surface \"stairs\" \"float step\" [100]\nSphere 1 -1 1 360\n",
        ),
    );
    let bytes = std::fs::read(&path).unwrap();
    let Err(errors) = read_rib(&path, &bytes) else {
        panic!("accepted")
    };
    let shown: Vec<String> = errors
        .iter()
        .map(|e| e.to_string().replace(&path.display().to_string(), "t.rib"))
        .collect();
    assert_eq!(
        shown,
        [
            "t.rib:7:25: error: unknown parameter \"nearr\" of light \"myLight\"\n  help: did \
             you mean \"near\"?",
            "t.rib:8:21: error: unknown parameter \"roughnes\" of surface \"mySurface\"\n  \
             help: did you mean \"roughness\"?",
            "t.rib:9:31: error: unknown parameter \"amp\" of displacement \"myDisplacement\"\n  \
             help: no parameters are defined",
            "t.rib:11:24: error: unknown parameter \"Kr\" of surface \"simplemirror\"\n  help: \
             no parameters are defined",
            "t.rib:13:18: error: unknown parameter \"step\" of surface \"stairs\"\n  help: did \
             you mean \"steps\"?",
        ]
    );
}

#[test]
fn the_seed_scenes_calling_the_tutorial_shaders_read_without_a_fallback() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/seeds/rib");
    for (file, calls) in [
        ("test_sphere.rib", &["\"myLight\"", "\"mySurface\""][..]),
        ("aircaustics.rib", &["\"simplemirror\""][..]),
        (
            "shadertest_light.rib",
            &["\"myLight\"", "\"mySurface\"", "Imager \"myImager\"\n"][..],
        ),
        ("shadertest_displace.rib", &["\"myDisplacement\""][..]),
        ("shadertest_bump.rib", &["\"myDisplacement\""][..]),
        (
            "stairs_shader.rib",
            &["\"stairs\" \"float steps\" [ 100 ]"][..],
        ),
    ] {
        let path = root.join(file);
        let bytes = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&bytes);
        for call in calls {
            assert!(text.contains(call), "{file} calls {call}");
        }
        let scene = read_rib(&path, &bytes).unwrap_or_else(|e| panic!("{file}: {e:?}"));
        for w in &scene.warnings {
            let w = w.to_string();
            assert!(
                !w.contains("unknown surface shader") && !w.contains("shader \""),
                "{file}: {w}"
            );
        }
        if file == "shadertest_light.rib" {
            // The imager is the tutorial's disk, not a stand-in background.
            let imager = scene.desc.cameras[0].imager.as_ref().unwrap();
            assert!(
                imager.pattern.is_some() && imager.background.is_none(),
                "{file}"
            );
        }
        if file == "test_sphere.rib" {
            // The light is kept: ambientlight and myLight.
            assert_eq!(scene.desc.lights.len(), 2, "{file}");
        }
    }
}
