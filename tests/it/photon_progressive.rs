//! Issue 16 item 6: progressive photon mapping (`caustics: (…, progressive: (passes, alpha))`,
//! hard case H21) on an analytic caustic — a point light over a perfect mirror lights a
//! diffuse ceiling as its mirror image would: `E(x) = I·(H + h) / d³`.

use glam::Vec3;
use stagelight::photon::progressive::gather_passes;
use stagelight::photon::{GatherMap, PhotonMap};
use stagelight::settings::PhotonFilter;

/// Light height `h` over the mirror (z = 0) and ceiling height `H`.
const LIGHT: f32 = 1.0;
const CEILING: f32 = 3.0;

/// A mirror floor, a grey ceiling facing down and a point light of intensity 1 between them;
/// `caustics` is the map's settings.
fn scene(caustics: &str) -> String {
    format!(
        r#"Scene(
    options: (caustics: ({caustics})),
    cameras: [(name: "cam", fov_y: 40, resolution: (2, 2),
        placement: LookAt(eye: (0, -2, 2), target: (0, 0, 3), up: (0, 0, 1)),
        outputs: [(file: "ceiling.png")])],
    lights: [(name: "bulb", kind: Point(position: (0, 0, {LIGHT})), intensity: 1)],
    materials: [
        (name: "mirror", shader: Mirror()),
        (name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5))),
    ],
    objects: [
        (name: "floor", mesh: Grid(size_x: 40, size_y: 40), material: "mirror"),
        (name: "ceiling", mesh: Grid(size_x: 40, size_y: 40), material: "grey"),
    ],
    instances: [
        (name: "floor_1", of: "floor"),
        (name: "ceiling_1", of: "ceiling",
         transform: [Rotate(axis: (1, 0, 0), degrees: 180), Translate((0, 0, {CEILING}))]),
    ],
    groups: [(name: "world", members: ["floor_1", "ceiling_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

/// The caustic map of `scene(caustics)`, traced on `threads` threads.
fn caustic_map(caustics: &str, threads: usize) -> GatherMap {
    let text = scene(caustics);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let frame = pool.install(|| crate::common::photon_frame(&text, "mirror.ron"));
    frame
        .outputs
        .photons
        .and_then(|m| m.caustics)
        .expect("caustic map")
}

/// Irradiance on the ceiling at `(x, 0, H)` from the light's mirror image at `(0, 0, −h)`.
fn exact(x: f32) -> f64 {
    let dz = f64::from(CEILING + LIGHT);
    let d2 = f64::from(x * x) + dz * dz;
    dz / (d2 * d2.sqrt())
}

/// Relative RMS error over points of the ceiling of the progressive estimate from the first
/// `n` passes of `map`.
fn error(passes: &[&PhotonMap], radius: f32, alpha: f32) -> f64 {
    let points = [0.0f32, 0.4, 0.8, 1.2, 1.6, 2.0];
    let mut scratch = Vec::new();
    let sq: f64 = points
        .iter()
        .map(|&x| {
            let stats = gather_passes(
                passes.iter().copied(),
                Vec3::new(x, 0.0, CEILING),
                -Vec3::Z,
                radius,
                alpha,
                PhotonFilter::Box,
                &mut scratch,
                |_| Vec3::ONE,
            );
            (f64::from(stats.estimate(passes.len()).x) / exact(x) - 1.0).powi(2)
        })
        .sum();
    (sq / points.len() as f64).sqrt()
}

fn slope(points: &[(usize, f64)]) -> f64 {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .map(|&(n, e)| ((n as f64).ln(), e.ln()))
        .collect();
    let n = xy.len() as f64;
    let mx = xy.iter().map(|p| p.0).sum::<f64>() / n;
    let my = xy.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

/// The caustic error falls with passes at α = 0.7 (measured log-log slope, no plateau) and
/// stays at the fixed radius's bias with α = 1; the map holds every pass and its estimate
/// is the progressive one.
#[test]
fn the_caustic_error_falls_with_passes() {
    let (radius, passes) = (3.0, 32);
    let map = caustic_map(
        &format!("photons: 1000, radius: {radius}, progressive: (passes: {passes}, alpha: 0.7)"),
        2,
    );
    let later = &map.progressive.as_ref().expect("progressive").later;
    assert_eq!(later.len(), passes - 1);
    assert_eq!(map.emitted, 1000 * passes as u64);
    let all: Vec<&PhotonMap> = std::iter::once(&map.map).chain(later).collect();
    let curve = |alpha: f32| -> Vec<(usize, f64)> {
        (0..=passes.ilog2())
            .map(|k| 1usize << k)
            .map(|n| (n, error(&all[..n], radius, alpha)))
            .collect()
    };
    let (shrinking, fixed) = (curve(0.7), curve(1.0));
    println!("passes, relative RMS error of the caustic (α = 0.7, α = 1):");
    for (a, b) in shrinking.iter().zip(&fixed) {
        println!("{:3} {:.4} {:.4}", a.0, a.1, b.1);
    }
    let (s, f) = (slope(&shrinking[1..]), slope(&fixed[1..]));
    println!("log-log slope over 2…{passes} passes: α = 0.7: {s:.3}, α = 1: {f:.3}");
    assert!(s < -0.2, "slope {s}");
    assert!(f > -0.1, "fixed radius slope {f}");
    assert!(shrinking[shrinking.len() - 1].1 < 0.5 * shrinking[0].1);
    // The map's own estimate is the progressive one over every pass.
    let mut scratch = Vec::new();
    let p = Vec3::new(0.4, 0.0, CEILING);
    let own = map.density(p, -Vec3::Z, &mut scratch, |_| Vec3::ONE);
    let stats = gather_passes(
        all.iter().copied(),
        p,
        -Vec3::Z,
        radius,
        0.7,
        PhotonFilter::Box,
        &mut scratch,
        |_| Vec3::ONE,
    );
    assert_eq!(own, stats.estimate(passes));
}

/// Every pass is the same at 1 and 3 threads; one pass is the ordinary map.
#[test]
fn progressive_passes_are_identical_at_any_thread_count() {
    let settings = "photons: 1500, radius: 1, progressive: (passes: 3, alpha: 0.7)";
    let (a, b) = (caustic_map(settings, 1), caustic_map(settings, 3));
    let passes = |m: &GatherMap| -> Vec<Vec<stagelight::photon::Photon>> {
        std::iter::once(&m.map)
            .chain(&m.progressive.as_ref().unwrap().later)
            .map(|p| p.photons().to_vec())
            .collect()
    };
    let (pa, pb) = (passes(&a), passes(&b));
    assert_eq!(pa.len(), 3);
    assert!(pa.iter().all(|p| !p.is_empty()));
    assert_ne!(pa[0], pa[1], "passes are seeded apart");
    assert_eq!(pa, pb);
    let plain = caustic_map("photons: 1500, radius: 1", 2);
    assert_eq!(plain.map.photons(), a.map.photons());
    assert!(plain.progressive.is_none());
}
