//! RIB scenes shade as the RenderMan Interface Specification 3.2 writes its standard shaders:
//! a `plastic` sphere under a `pointlight` and an `ambientlight` matches the closed form
//! `Cs·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness)` per
//! pixel, evaluated here in f64.

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use stagelight::scene::load_scene;

/// Writes `text` as `name` in a fresh folder of the temporary directory.
fn write_rib(name: &str, text: &str) -> PathBuf {
    let dir = crate::common::scratch_root()
        .join(format!("stagelight_rib_shading_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Renders the RIB at `path` at its own resolution, without writing files: the beauty pass.
fn render(path: &Path) -> (Vec<Vec3>, usize) {
    let mut scene = load_scene(path).unwrap_or_else(|e| panic!("{e}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("an image");
    (image.beauty, image.width as usize)
}

/// `(x, y, z)` of a RIB colour or point.
fn v(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

const W: usize = 48;
const H: usize = 36;
const FOV: f64 = 40.0;
const CS: [f64; 3] = [0.8, 0.45, 0.2];
const KA: f64 = 0.7;
const KD: f64 = 0.6;
const KS: f64 = 0.4;
const ROUGHNESS: f64 = 0.2;
const SPECULAR: [f64; 3] = [1.0, 0.8, 0.6];
const AMBIENT: [f64; 3] = [0.1, 0.05, 0.025];
const FROM: [f64; 3] = [2.0, 3.0, 1.0];
const INTENSITY: f64 = 12.0;
const LIGHTCOLOR: [f64; 3] = [1.0, 0.9, 0.8];
const CENTRE: [f64; 3] = [0.3, -0.2, 4.0];

fn scene() -> String {
    let c = |a: [f64; 3]| format!("[{} {} {}]", a[0], a[1], a[2]);
    format!(
        "# The closed-form test: every pixel one ray through its centre (a vanishing \
         gaussian), no gamma.\n\
         Format {W} {H} 1\nPixelSamples 1 1\nPixelFilter \"gaussian\" 0.0001 0.0001\n\
         Exposure 1 1\nProjection \"perspective\" \"fov\" [{FOV}]\nWorldBegin\n\
         LightSource \"ambientlight\" 1 \"intensity\" [0.1] \"lightcolor\" [1 0.5 0.25]\n\
         LightSource \"pointlight\" 2 \"from\" {} \"intensity\" [{INTENSITY}] \
         \"lightcolor\" {}\n\
         AttributeBegin\nColor {}\n\
         Surface \"plastic\" \"Ka\" {KA} \"Kd\" {KD} \"Ks\" {KS} \"roughness\" {ROUGHNESS} \
         \"specularcolor\" {}\n\
         ShadingRate 0.05\nTranslate {} {} {}\nSphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n",
        c(FROM),
        c(LIGHTCOLOR),
        c(CS),
        c(SPECULAR),
        CENTRE[0],
        CENTRE[1],
        CENTRE[2],
    )
}

/// The RI closed form seen through the centre of pixel `(x, y)` (row 0 at the top), in RIB
/// camera space (+x right, +y up, +z into the screen); `None` where the ray misses the
/// sphere or meets it close to its silhouette or to the light's terminator (where the
/// tessellated sphere's edge differs from the true one).
fn closed_form(x: usize, y: usize) -> Option<DVec3> {
    let aspect = W as f64 / H as f64;
    let t = (FOV.to_radians() / 2.0).tan();
    let sx = (-aspect + 2.0 * aspect * (x as f64 + 0.5) / W as f64) * t;
    let sy = (1.0 - 2.0 * (y as f64 + 0.5) / H as f64) * t;
    let d = DVec3::new(sx, sy, 1.0).normalize();
    let c = v(CENTRE);
    // |t·d − c|² = 1.
    let b = d.dot(c);
    let disc = b * b - (c.length_squared() - 1.0);
    if disc <= 0.0 {
        return None;
    }
    let p = d * (b - disc.sqrt());
    let n = (p - c).normalize();
    let view = -d;
    if n.dot(view) < 0.3 {
        return None;
    }
    let to_light = v(FROM) - p;
    let cl = v(LIGHTCOLOR) * (INTENSITY / to_light.length_squared());
    let l = to_light.normalize();
    let cos = n.dot(l);
    if cos.abs() < 0.05 {
        return None;
    }
    let mut c = v(CS) * (KA * v(AMBIENT));
    if cos > 0.0 {
        let h = (l + view).normalize();
        let spec = n.dot(h).max(0.0).powf(1.0 / ROUGHNESS);
        c += v(CS) * (KD * cos) * cl + v(SPECULAR) * (KS * spec) * cl;
    }
    Some(c)
}

#[test]
fn plastic_sphere_matches_the_ri_closed_form_per_pixel() {
    let path = write_rib("plastic.rib", &scene());
    let (beauty, width) = render(&path);
    assert_eq!((width, beauty.len()), (W, W * H));
    let mut worst = 0.0f64;
    let mut checked = 0;
    let mut lit = 0;
    for y in 0..H {
        for x in 0..W {
            let Some(expected) = closed_form(x, y) else {
                continue;
            };
            let got = beauty[y * W + x].as_dvec3();
            let err = (got - expected).abs().max_element();
            worst = worst.max(err);
            checked += 1;
            if expected.x > 0.2 {
                lit += 1;
            }
            assert!(
                err < 1e-3,
                "pixel ({x}, {y}): {got} vs the closed form {expected} (error {err})"
            );
        }
    }
    println!("plastic closed form: {checked} pixels, {lit} lit, max error {worst:.3e}");
    assert!(
        checked > 300 && lit > 50,
        "{checked} pixels checked, {lit} lit"
    );
}

#[test]
fn paintedplastic_texturename_paints_the_patch_with_the_image() {
    // A bilinear patch filling a square 90° view at distance 1, (s, t) running right and
    // down, lit by ambient light only (Kd = Ks = 0): every pixel is Cs·Ka·ambient·texture.
    let bricks = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/textures/bricks.png");
    let text = format!(
        "Format 32 32 1\nPixelSamples 1 1\nPixelFilter \"gaussian\" 0.0001 0.0001\n\
         Exposure 1 1\nProjection \"perspective\" \"fov\" [90]\nWorldBegin\n\
         LightSource \"ambientlight\" 1 \"intensity\" [0.5]\nColor [1 0.5 1]\n\
         Surface \"paintedplastic\" \"Ka\" 1 \"Kd\" 0 \"Ks\" 0 \"texturename\" \"{}\"\n\
         Patch \"bilinear\" \"P\" [-1 1 1  1 1 1  -1 -1 1  1 -1 1]\nWorldEnd\n",
        bricks.display()
    );
    let path = write_rib("painted.rib", &text);
    let (beauty, width) = render(&path);
    let tex = stagelight::shading::texture::image::load(
        &bricks,
        Some(stagelight::shading::texture::image::Encoding::Linear),
        stagelight::components::graph::Wrap::Repeat,
    )
    .unwrap();
    let mut worst = 0.0f32;
    for y in 0..32 {
        for x in 0..32 {
            let (s, t) = ((x as f32 + 0.5) / 32.0, (y as f32 + 0.5) / 32.0);
            let expected = Vec3::new(1.0, 0.5, 1.0) * 0.5 * tex.sample(glam::Vec2::new(s, 1.0 - t));
            let err = (beauty[y * width + x] - expected).abs().max_element();
            worst = worst.max(err);
        }
    }
    println!("paintedplastic texture: max error {worst:.3e}");
    assert!(worst < 1e-3, "max error {worst}");
    let spread = beauty.iter().map(|c| c.x).fold(0.0f32, f32::max)
        - beauty.iter().map(|c| c.x).fold(1.0f32, f32::min);
    assert!(spread > 0.05, "the texture shows: spread {spread}");
}
