//! What the photon pass's rays cost the accelerator (issue 17, session 15): traces a scene's
//! caustic photons (aimed at the casters, as the stage aims them) one by one (as [`Tracing::PerPhoton`] does) with
//! `Accel::intersect_with_cost`, and prints the inner nodes and triangles tested per ray,
//! by where the ray starts (the light, or the instance it leaves) and what it hits, and what
//! the same rays cost through the accelerator's shortcuts past convex parts (the later ray,
//! plus the full query where the shortcut's answer is not certain; `Accel::shortcuts`). The
//! photons' paths are those of the pass (the same walk); only their seed differs from the
//! `trace_photons` stage's.
//!
//! `cargo run --release --example photon_ray_cost -- [SCENE] [PHOTONS]` (defaults:
//! `assets/scenes/caustics.ron`, 100,000).

use std::collections::BTreeMap;
use std::path::PathBuf;

use stagelight::accel::{Shortcut, Shortcuts};
use stagelight::components::PhotonFlags;
use stagelight::frame::Frame;
use stagelight::photon::aim::Aim;
use stagelight::photon::roles::instance_sphere;
use stagelight::photon::walk::Walk;
use stagelight::photon::{Emission, MapKind, PhotonRoles};
use stagelight::sampling::Sampler;
use stagelight::scene::load_scene;
use stagelight::scene_view::{light_set, WithEnvironment};
use stagelight::shading::ShadeContext;

/// Sums for one kind of ray.
#[derive(Default)]
struct Tally {
    rays: u64,
    nodes: u64,
    triangles: u64,
    deepest: u64,
    /// Through the shortcuts.
    short_nodes: u64,
    short_triangles: u64,
}

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/caustics.ron"),
        PathBuf::from,
    );
    let photons: u64 = args.next().and_then(|n| n.parse().ok()).unwrap_or(100_000);
    let mut scene = load_scene(&path).expect("the scene loads");
    let mut frame = Frame::new(scene.settings.clone());
    stagelight::systems::run_before("trace_photons", &mut scene.world, &mut frame)
        .expect("stages before trace_photons");
    let geometry = frame.outputs.geometry.as_ref().expect("geometry");
    let settings = &frame.inputs.settings;
    let lights = light_set(&scene.world, Some(geometry), settings, WithEnvironment::No);
    // The caustic pass's emission: aimed at the caustic casters, with their roles.
    let roles = PhotonRoles::new(geometry, |slot| {
        let entity = geometry.instances[slot].entity;
        scene.world.get::<&PhotonFlags>(entity).ok().map(|f| *f)
    });
    let spheres = roles
        .caustic_casters(geometry)
        .into_iter()
        .filter_map(|slot| instance_sphere(geometry, slot))
        .collect();
    let emission = Emission::new(&lights, geometry).aimed(Aim::new(spheres));
    let roles = roles.for_map(MapKind::Caustics);
    let ctx = ShadeContext::new(geometry, &lights, settings);
    let accel = &geometry.accel;
    let shortcuts = geometry.shortcuts();
    let instance = |prim: u32| geometry.triangle_instance[prim as usize];
    // (start: instance left or light, end: instance hit or miss) → tally.
    let mut tallies: BTreeMap<(String, String), Tally> = BTreeMap::new();
    for i in 0..photons {
        let mut sampler = Sampler::for_item(0x5e55, i, 0);
        let u = [(); 5].map(|_| sampler.next_1d());
        let Some(e) = emission.sample(geometry, u) else {
            continue;
        };
        let mut walk = Walk::new(&ctx, e.ray, e.power);
        let mut from = "light".to_string();
        while walk.live() {
            let (hit, cost) = accel.intersect_with_cost(walk.ray());
            let to = hit.map_or("miss".to_string(), |h| {
                let slot = instance(h.prim);
                let n = geometry.instances[slot as usize].mesh.triangles.len();
                format!("instance {slot} ({n} tris)")
            });
            let ray = walk.ray();
            let (short_nodes, short_triangles) = match walk
                .left()
                .map(|(from, cos)| shortcuts.shortcut(ray, from, cos))
            {
                Some(Shortcut::From(later)) => {
                    let (found, later_cost) = accel.intersect_with_cost(&later);
                    let again = match Shortcuts::confirm(accel, ray, found) {
                        Some(confirmed) => {
                            assert_eq!(Some(confirmed), hit, "the shortcut's hit");
                            (0, 0)
                        }
                        None => (cost.nodes, cost.triangles),
                    };
                    (later_cost.nodes + again.0, later_cost.triangles + again.1)
                }
                _ => (cost.nodes, cost.triangles),
            };
            let t = tallies.entry((from.clone(), to.clone())).or_default();
            t.short_nodes += u64::from(short_nodes);
            t.short_triangles += u64::from(short_triangles);
            t.rays += 1;
            t.nodes += u64::from(cost.nodes);
            t.triangles += u64::from(cost.triangles);
            t.deepest += u64::from(cost.deepest);
            walk.step(&ctx, roles, hit, &mut sampler, true, &mut |_| {});
            from = to;
        }
    }
    let stats = accel.stats();
    println!(
        "{}: {photons} caustic photons, {} triangles, {} nodes, depth {}, {} convex part(s)",
        path.display(),
        geometry.triangle_count(),
        stats.nodes,
        stats.depth,
        shortcuts.parts()
    );
    println!(
        "from → to: rays, per ray: inner nodes, triangles, deepest level \
         | through the shortcuts: inner nodes, triangles"
    );
    let mut all = Tally::default();
    for ((from, to), t) in &tallies {
        let per = |x: u64| x as f64 / t.rays as f64;
        println!(
            "{from} → {to}: {} rays, {:.1} nodes, {:.1} triangles, {:.1} deep \
             | {:.1} nodes, {:.1} triangles",
            t.rays,
            per(t.nodes),
            per(t.triangles),
            per(t.deepest),
            per(t.short_nodes),
            per(t.short_triangles)
        );
        all.rays += t.rays;
        all.nodes += t.nodes;
        all.triangles += t.triangles;
        all.short_nodes += t.short_nodes;
        all.short_triangles += t.short_triangles;
    }
    let per = |x: u64| x as f64 / all.rays.max(1) as f64;
    println!(
        "all: {} rays, {:.1} nodes, {:.1} triangles per ray \
         | through the shortcuts {:.1} nodes, {:.1} triangles",
        all.rays,
        per(all.nodes),
        per(all.triangles),
        per(all.short_nodes),
        per(all.short_triangles)
    );
}
