//! The light, shadow and environment example scenes, each checked for its defining property:
//! `area_lights.ron` (visible lights appear at their radiance, invisible ones do not),
//! `shadows_coloured.ron` (the shadow of a transparent red sheet has exactly the predicted
//! RGB), `environment.ron` (the floor's irradiance is the integral of the EXR sky).

use std::path::PathBuf;

use glam::Vec3;
use stagelight::components::{world_from_look_at, Camera, Instance, Name, RenderCamera};
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::{load_scene, read_lat_long, LoadedScene};

fn scene_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name)
}

fn load(name: &str) -> LoadedScene {
    load_scene(&scene_path(name)).unwrap_or_else(|e| panic!("{name}:\n{e}"))
}

fn render(scene: &mut LoadedScene, spp: u32) -> FrameBuffers {
    let mut settings = scene.settings.clone();
    settings.spp = spp;
    let frame = crate::common::render(&mut scene.world, settings);
    frame.outputs.image.expect("image")
}

fn resize(scene: &mut LoadedScene, w: u32, h: u32) {
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        camera.width = w;
        camera.height = h;
        camera.aspect = w as f32 / h as f32;
    }
}

fn close(a: Vec3, b: Vec3, rel: f32) -> bool {
    ((a - b).abs() / b.abs().max(Vec3::splat(1e-6))).max_element() < rel
}

/// `area_lights.ron`: the visible sphere (1, 0.9, 0.7)·12 and tube (0.7, 0.8, 1)·20 are seen
/// by the camera at exactly their radiance, covering their pixels (alpha 1) and hiding the
/// floor behind them; the invisible rectangle and disc (radiance 16) appear nowhere.
#[test]
fn area_lights_scene_shows_only_visible_lights() {
    let mut scene = load("area_lights.ron");
    resize(&mut scene, 80, 60);
    let fb = render(&mut scene, 4);
    let sphere = Vec3::new(1.0, 0.9, 0.7) * 12.0;
    let tube = Vec3::new(0.7, 0.8, 1.0) * 20.0;
    let count = |want: Vec3| fb.beauty.iter().filter(|c| close(**c, want, 1e-5)).count();
    assert!(count(sphere) >= 4, "sphere pixels: {}", count(sphere));
    assert!(count(tube) >= 2, "tube pixels: {}", count(tube));
    assert_eq!(count(Vec3::splat(16.0)), 0);
    // Everything else is the dim, lit floor and boxes.
    let brightest_other = fb
        .beauty
        .iter()
        .filter(|c| !close(**c, sphere, 0.5) && !close(**c, tube, 0.5))
        .map(|c| c.max_element())
        .fold(0.0, f32::max);
    assert!(brightest_other < 8.0, "{brightest_other}");
    assert!(fb.beauty.iter().all(|c| c.is_finite()));
}

/// `shadows_coloured.ron`: the centre pixel sees the floor right below the lamp, in the
/// shadow of the sheet that lets (0.5, 0.2, 0.1) through: exactly
/// `0.8/π · 30/4² · (0.5, 0.2, 0.1)` (a point light: no noise), while the floor outside the
/// shadow stays white (R = G = B).
#[test]
fn coloured_shadow_has_the_predicted_rgb() {
    let mut scene = load("shadows_coloured.ron");
    let fb = render(&mut scene, 4);
    let (w, h) = (81usize, 61usize);
    let centre = fb.beauty[(h / 2) * w + w / 2];
    let want = 0.8 / std::f32::consts::PI * 30.0 / 16.0 * Vec3::new(0.5, 0.2, 0.1);
    assert!(close(centre, want, 2e-3), "{centre} vs {want}");
    // Bottom-left corner: floor far outside both shadows, white light.
    let corner = fb.beauty[(h - 1) * w];
    assert!(corner.max_element() > 0.0);
    assert!(
        (corner.x - corner.y).abs() < 1e-6 && (corner.y - corner.z).abs() < 1e-6,
        "{corner}"
    );
}

/// `environment.ron`: with the balls removed, the floor at the origin receives the sky's
/// irradiance `Σ L_texel · Δφ · (sin²θ₁ − sin²θ₀)/2` over the upper hemisphere (the map's
/// texels are constant), so its radiance is `albedo/π · E` within 1 %; camera rays that miss
/// see the sky with alpha 0.
#[test]
fn environment_scene_floor_gets_the_sky_irradiance() {
    let mut scene = load("environment.ron");
    let balls: Vec<hecs::Entity> = scene
        .world
        .query::<(hecs::Entity, &Name, &Instance)>()
        .iter()
        .filter(|(_, n, _)| n.0.contains("ball"))
        .map(|(e, ..)| e)
        .collect();
    assert_eq!(balls.len(), 2);
    for e in balls {
        scene.world.despawn(e).unwrap();
    }
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        camera.world_from_camera =
            world_from_look_at(Vec3::new(0.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y).unwrap();
        camera.width = 3;
        camera.height = 3;
        camera.aspect = 1.0;
        camera.fov_y = 0.5f32.to_radians();
    }
    let fb = render(&mut scene, 256);
    let map =
        read_lat_long(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/textures/sky.exr"))
            .unwrap();
    let (w, h) = (map.width as usize, map.height as usize);
    let mut e = 0.0f64;
    for y in 0..h / 2 {
        let t0 = std::f64::consts::PI * y as f64 / h as f64;
        let t1 = std::f64::consts::PI * (y + 1) as f64 / h as f64;
        let band =
            (t1.sin().powi(2) - t0.sin().powi(2)) / 2.0 * 2.0 * std::f64::consts::PI / w as f64;
        for x in 0..w {
            e += map.texels[y * w + x].x as f64 * band;
        }
    }
    let want = 0.5 / std::f64::consts::PI * e;
    let got = fb.beauty[4].x as f64;
    assert!((got - want).abs() / want < 0.01, "{got} vs {want}");
    assert_eq!(fb.alpha[4], 1.0);

    // The full scene: the top row sees only sky.
    let mut scene = load("environment.ron");
    resize(&mut scene, 32, 18);
    let fb = render(&mut scene, 1);
    assert!(fb.alpha[..32].iter().all(|a| *a == 0.0));
    assert!(fb.beauty[..32].iter().all(|c| c.min_element() > 0.1));
}

/// The three example scenes give identical bytes at 1 and 2 threads.
#[test]
fn light_scenes_do_not_depend_on_the_thread_count() {
    for name in ["area_lights.ron", "shadows_coloured.ron", "environment.ron"] {
        let render_with = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| {
                    let mut scene = load(name);
                    resize(&mut scene, 40, 30);
                    render(&mut scene, 2)
                })
        };
        let bits = |fb: &FrameBuffers| -> Vec<u32> {
            fb.beauty
                .iter()
                .flat_map(|c| c.to_array().map(f32::to_bits))
                .chain(fb.alpha.iter().map(|a| a.to_bits()))
                .collect()
        };
        assert_eq!(bits(&render_with(1)), bits(&render_with(2)), "{name}");
    }
}
