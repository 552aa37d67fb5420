//! BVH build and single-ray traversal throughput on the Embree anchor's workload
//! (`/work/shared/anchors/embree/gen_scene.py`: a 1,046,528-triangle displaced sphere, 1M
//! coherent primary rays, 1M incoherent random rays), so the numbers compare directly with
//! `embree_bench` on the same files.
//!
//! * Data: `${STAGELIGHT_BENCH_DATA:-target/bench-data}` (`mesh.bin`, `rays_coherent.bin`,
//!   `rays_incoherent.bin`). When missing, the bench runs `python3 gen_scene.py <dir>` (script
//!   path: `${STAGELIGHT_GEN_SCENE:-../shared/anchors/embree/gen_scene.py}`); without
//!   python3/numpy it says how to get them and falls back to a smaller workload generated here.
//! * First a summary table (best of `${STAGELIGHT_BENCH_REPS:-3}`): Mrays/s per query for 1 and
//!   2 threads (rayon pools; 1 thread also per CPU-second of the tracing thread), hit counts
//!   checked against the anchor's (715,018 coherent; 602,740 incoherent for Embree and obvhs,
//!   602,741 here: see `EXPECTED_HITS_INCOHERENT`), and build times (wall; 1 thread also CPU
//!   of the building thread) split by phase (`AccelStats::build_phases`: prepare, hierarchy,
//!   reinsertion, collapse, layout).
//! * Then criterion groups (10 samples each): `build`, `build/{1,2}t` (thread scaling of the
//!   Medium build), `trace/{1,2}t`, and `tiny`, a small
//!   generated scene that needs no data.
//!
//! Run: `cargo bench --bench bvh` (add `-- tiny` for the small group only, `-- summary` for
//! the table only; `STAGELIGHT_BENCH_THREADS="1 2"`, `STAGELIGHT_BENCH_QUALITIES="fast medium"`
//! and `STAGELIGHT_BENCH_API="single batch"` select what the table measures; `packet` adds
//! closest-hit rows traced as common-origin packets of 64 consecutive rays
//! (`Accel::intersect_packet`, what the `shade` stage does with a pinhole pixel's camera
//! rays); an API list naming none of them, e.g. `none`, leaves only the build lines).

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use criterion::{Criterion, Throughput};
use glam::Vec3;
use rayon::prelude::*;
use stagelight::accel::{Accel, Ray};
use stagelight::settings::BvhQuality;

/// Hit counts of the anchor's ray sets. Embree 3 (default, non-robust mode) and obvhs report
/// 602,740 incoherent hits; the watertight test finds one more: ray 374,651 starts inside the
/// closed mesh and crosses it 2e-6 (in barycentrics) from a shared edge, where the
/// non-watertight tests leak (checked against obvhs's own traversal and triangle test).
const EXPECTED_HITS_COHERENT: u64 = 715_018;
const EXPECTED_HITS_INCOHERENT: u64 = 602_741;

/// A mesh and its three ray sets.
struct Workload {
    name: String,
    tris: Vec<[Vec3; 3]>,
    coherent: Vec<Ray>,
    incoherent: Vec<Ray>,
    /// True for the anchor's files (hit counts are checked).
    anchor: bool,
}

fn read_u32s(bytes: &[u8]) -> impl Iterator<Item = u32> + '_ {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
}

fn read_mesh(path: &Path) -> std::io::Result<Vec<[Vec3; 3]>> {
    let bytes = std::fs::read(path)?;
    let mut words = read_u32s(&bytes);
    let nv = words.next().unwrap_or(0) as usize;
    let nt = words.next().unwrap_or(0) as usize;
    let words: Vec<u32> = words.collect();
    if words.len() < nv * 3 + nt * 3 {
        return Err(std::io::Error::other(format!(
            "{}: truncated",
            path.display()
        )));
    }
    let verts: Vec<Vec3> = words[..nv * 3]
        .chunks_exact(3)
        .map(|c| {
            Vec3::new(
                f32::from_bits(c[0]),
                f32::from_bits(c[1]),
                f32::from_bits(c[2]),
            )
        })
        .collect();
    Ok(words[nv * 3..nv * 3 + nt * 3]
        .chunks_exact(3)
        .map(|c| {
            [
                verts[c[0] as usize],
                verts[c[1] as usize],
                verts[c[2] as usize],
            ]
        })
        .collect())
}

fn read_rays(path: &Path) -> std::io::Result<Vec<Ray>> {
    let bytes = std::fs::read(path)?;
    let mut words = read_u32s(&bytes);
    let n = words.next().unwrap_or(0) as usize;
    let f: Vec<f32> = words.map(f32::from_bits).collect();
    if f.len() < n * 8 {
        return Err(std::io::Error::other(format!(
            "{}: truncated",
            path.display()
        )));
    }
    // Per ray: ox oy oz dx dy dz tmin tmax (tmin is 0 in every set; our rays start at 0).
    Ok(f.chunks_exact(8)
        .take(n)
        .map(|r| Ray {
            origin: Vec3::new(r[0], r[1], r[2]),
            dir: Vec3::new(r[3], r[4], r[5]),
            t_max: r[7],
        })
        .collect())
}

fn data_dir() -> PathBuf {
    match std::env::var_os("STAGELIGHT_BENCH_DATA") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("target/bench-data"),
    }
}

fn load_anchor(dir: &Path) -> std::io::Result<Workload> {
    Ok(Workload {
        name: format!("anchor ({})", dir.display()),
        tris: read_mesh(&dir.join("mesh.bin"))?,
        coherent: read_rays(&dir.join("rays_coherent.bin"))?,
        incoherent: read_rays(&dir.join("rays_incoherent.bin"))?,
        anchor: true,
    })
}

/// Loads the anchor's files, generating them with `gen_scene.py` when missing; falls back to
/// a generated workload when that is impossible.
fn load_or_generate() -> Workload {
    let dir = data_dir();
    if let Ok(w) = load_anchor(&dir) {
        return w;
    }
    let script = std::env::var("STAGELIGHT_GEN_SCENE").unwrap_or_else(|_| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../shared/anchors/embree/gen_scene.py"
        )
        .to_string()
    });
    eprintln!(
        "bench data missing in {}; running python3 {script} …",
        dir.display()
    );
    let status = std::process::Command::new("python3")
        .arg(&script)
        .arg(&dir)
        .status();
    match status {
        Ok(s) if s.success() => match load_anchor(&dir) {
            Ok(w) => return w,
            Err(e) => eprintln!("generated files unreadable: {e}"),
        },
        Ok(s) => eprintln!("gen_scene.py failed ({s})"),
        Err(e) => eprintln!("cannot run python3: {e}"),
    }
    eprintln!(
        "To benchmark on the Embree anchor's workload: install python3 and numpy \
         (`pip install numpy`), then `python3 {script} {}` (or set STAGELIGHT_BENCH_DATA to a \
         directory holding mesh.bin, rays_coherent.bin, rays_incoherent.bin). Falling back to \
         a smaller generated workload (256×128 sphere, 256² + 65,536 rays).",
        dir.display()
    );
    generated(256, 128, 256, 1 << 16)
}

/// The anchor's displaced UV sphere and ray sets, generated in Rust at any size.
fn generated(nu: usize, nv: usize, res: usize, n_incoherent: usize) -> Workload {
    use std::f64::consts::PI;
    let mut verts = Vec::new();
    for j in 1..nv {
        let theta = j as f64 / nv as f64 * PI;
        for i in 0..nu {
            let phi = i as f64 / nu as f64 * 2.0 * PI;
            let r = 1.0
                + 0.1 * (6.0 * theta).sin() * (5.0 * phi).cos()
                + 0.03 * (40.0 * theta).sin() * (37.0 * phi).sin();
            verts.push(Vec3::new(
                (r * theta.sin() * phi.cos()) as f32,
                (r * theta.cos()) as f32,
                (r * theta.sin() * phi.sin()) as f32,
            ));
        }
    }
    let (top, bot) = (verts.len(), verts.len() + 1);
    verts.push(Vec3::Y);
    verts.push(-Vec3::Y);
    let vid = |j: usize, i: usize| j * nu + i % nu;
    let mut tris = Vec::new();
    for i in 0..nu {
        tris.push([verts[top], verts[vid(0, i + 1)], verts[vid(0, i)]]);
        tris.push([verts[bot], verts[vid(nv - 2, i)], verts[vid(nv - 2, i + 1)]]);
    }
    for j in 0..nv - 2 {
        for i in 0..nu {
            let (a, b, c, d) = (
                verts[vid(j, i)],
                verts[vid(j, i + 1)],
                verts[vid(j + 1, i)],
                verts[vid(j + 1, i + 1)],
            );
            tris.push([a, b, d]);
            tris.push([a, d, c]);
        }
    }
    let eye = Vec3::new(0.3, 0.4, 2.6);
    let fwd = (-eye).normalize();
    let right = fwd.cross(Vec3::Y).normalize();
    let up = right.cross(fwd);
    let tan_half = (50f32.to_radians() * 0.5).tan();
    let mut coherent = Vec::with_capacity(res * res);
    for y in 0..res {
        for x in 0..res {
            let u = ((x as f32 + 0.5) / res as f32 * 2.0 - 1.0) * tan_half;
            let v = (1.0 - (y as f32 + 0.5) / res as f32 * 2.0) * tan_half;
            coherent.push(Ray {
                origin: eye,
                dir: (fwd + right * u + up * v).normalize(),
                t_max: f32::INFINITY,
            });
        }
    }
    let (lo, hi) = verts
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), &v| {
            (l.min(v), h.max(v))
        });
    let mut state = 12345u64;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    };
    let incoherent = (0..n_incoherent)
        .map(|_| {
            let o = lo + Vec3::new(next(), next(), next()) * (hi - lo);
            let z = next() * 2.0 - 1.0;
            let phi = next() * std::f32::consts::TAU;
            let s = (1.0 - z * z).max(0.0).sqrt();
            Ray {
                origin: o,
                dir: Vec3::new(s * phi.cos(), s * phi.sin(), z),
                t_max: f32::INFINITY,
            }
        })
        .collect();
    Workload {
        name: format!("generated {nu}x{nv} sphere"),
        tris,
        coherent,
        incoherent,
        anchor: false,
    }
}

/// Which query a trace runs.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Query {
    Closest,
    Occluded,
    ClosestBatch,
    OccludedBatch,
    /// Closest hits in common-origin packets of [`PACKET_RAYS`] consecutive rays.
    ClosestPacket,
}

/// Rays per packet of [`Query::ClosestPacket`] (the packet kernel's size).
const PACKET_RAYS: usize = 64;

/// Traces all rays in 4096-ray chunks (the anchor's OpenMP `dynamic, 4096`); returns hits and
/// the sum of hit distances.
fn trace(accel: &Accel, rays: &[Ray], query: Query) -> (u64, f64) {
    rays.par_chunks(4096)
        .map(|chunk| {
            let (mut hits, mut tsum) = (0u64, 0f64);
            match query {
                Query::ClosestBatch => {
                    let mut out = vec![None; chunk.len()];
                    accel.intersect_batch(chunk, &mut out);
                    for h in out.iter().flatten() {
                        hits += 1;
                        tsum += f64::from(h.t);
                    }
                    return (hits, tsum);
                }
                Query::ClosestPacket => {
                    let mut out = vec![None; chunk.len()];
                    for (rs, os) in chunk.chunks(PACKET_RAYS).zip(out.chunks_mut(PACKET_RAYS)) {
                        accel.intersect_packet(rs, os);
                    }
                    for h in out.iter().flatten() {
                        hits += 1;
                        tsum += f64::from(h.t);
                    }
                    return (hits, tsum);
                }
                Query::OccludedBatch => {
                    let mut out = vec![false; chunk.len()];
                    accel.occluded_batch(chunk, &mut out);
                    hits += out.iter().filter(|&&o| o).count() as u64;
                    return (hits, tsum);
                }
                _ => {}
            }
            for r in chunk {
                match query {
                    Query::Closest => {
                        if let Some(h) = accel.intersect(r) {
                            hits += 1;
                            tsum += f64::from(h.t);
                        }
                    }
                    Query::Occluded => hits += u64::from(accel.occluded(r)),
                    _ => unreachable!(),
                }
            }
            (hits, tsum)
        })
        .reduce(|| (0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// CPU time of the calling thread in seconds (Linux `/proc/thread-self/schedstat`).
fn thread_cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(s.split_whitespace().next()?.parse::<f64>().ok()? * 1e-9)
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("rayon pool")
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

/// The summary table: best-of-N wall (and 1-thread CPU) throughput, hit cross-check.
fn summary(w: &Workload, reps: usize) {
    println!(
        "# stagelight ray layer on {}: {} triangles",
        w.name,
        w.tris.len()
    );
    println!("# load average at start: {}", load_average());
    let env_list =
        |key: &str, default: &str| std::env::var(key).unwrap_or_else(|_| default.to_string());
    let thread_counts: Vec<usize> = env_list("STAGELIGHT_BENCH_THREADS", "1 2")
        .split_whitespace()
        .filter_map(|s| s.parse().ok())
        .collect();
    let qualities = env_list("STAGELIGHT_BENCH_QUALITIES", "fast medium");
    let mut accels = Vec::new();
    for (q, name) in [
        (BvhQuality::Fast, "fast"),
        (BvhQuality::Medium, "medium"),
        (BvhQuality::High, "high"),
    ] {
        if !qualities.split_whitespace().any(|s| s == name) {
            continue;
        }
        for &threads in &thread_counts {
            // Wall time, and for 1 thread also the CPU time of the building thread (robust
            // against time-slicing on a shared host).
            // The phases are those of the fastest (wall) build.
            let (best, best_cpu, phases) = (0..reps)
                .map(|_| {
                    pool(threads).install(|| {
                        let tris = w.tris.clone();
                        let c0 = thread_cpu_seconds();
                        let stats = Accel::build(tris, q).stats();
                        let cpu = match (c0, thread_cpu_seconds()) {
                            (Some(a), Some(b)) if threads == 1 => b - a,
                            _ => f64::NAN,
                        };
                        (stats.build_seconds, cpu, stats.build_phases)
                    })
                })
                .fold(
                    (f64::INFINITY, f64::INFINITY, Default::default()),
                    |a, b| {
                        let (wall, phases) = if b.0 < a.0 { (b.0, b.2) } else { (a.0, a.2) };
                        (wall, a.1.min(b.1), phases)
                    },
                );
            let cpu = if threads == 1 {
                format!(", {:.0} ms cpu", best_cpu * 1e3)
            } else {
                String::new()
            };
            let ms = |s: f64| s * 1e3;
            println!(
                "build quality={name} threads={threads}: {:.0} ms wall{cpu} (prepare {:.0}, hierarchy {:.0}, reinsertion {:.0}, collapse {:.0}, layout {:.0})",
                best * 1e3,
                ms(phases.prepare),
                ms(phases.hierarchy),
                ms(phases.reinsertion),
                ms(phases.collapse),
                ms(phases.layout),
            );
        }
        accels.push((name, Accel::build(w.tris.clone(), q)));
    }
    for (name, accel) in &accels {
        let s = accel.stats();
        println!(
            "# quality={name}: {} nodes, depth {}, SAH cost {:.4}, mesh + BVH {:.1} MB = {:.1} bytes/triangle",
            s.nodes,
            s.depth,
            s.sah_cost,
            s.bytes as f64 * 1e-6,
            s.bytes as f64 / s.triangles as f64
        );
        let apis = env_list("STAGELIGHT_BENCH_API", "single batch");
        let mut rows = Vec::new();
        for (set, rays, single, batch, expected) in [
            (
                "coherent",
                &w.coherent,
                Query::Closest,
                Query::ClosestBatch,
                EXPECTED_HITS_COHERENT,
            ),
            (
                "incoherent",
                &w.incoherent,
                Query::Closest,
                Query::ClosestBatch,
                EXPECTED_HITS_INCOHERENT,
            ),
            (
                "occluded",
                &w.incoherent,
                Query::Occluded,
                Query::OccludedBatch,
                EXPECTED_HITS_INCOHERENT,
            ),
        ] {
            // Single and batch rows alternate, so each pair is measured in the same window.
            for api in apis.split_whitespace() {
                match api {
                    "single" => rows.push((set.to_string(), rays, single, expected)),
                    "batch" => rows.push((format!("{set}/batch"), rays, batch, expected)),
                    "packet" if single == Query::Closest => rows.push((
                        format!("{set}/packet"),
                        rays,
                        Query::ClosestPacket,
                        expected,
                    )),
                    _ => {}
                }
            }
        }
        for (set, rays, query, expected) in rows {
            for &threads in &thread_counts {
                let p = pool(threads);
                let (mut best_wall, mut best_cpu, mut result) =
                    (f64::INFINITY, f64::INFINITY, (0, 0.0));
                for _ in 0..reps {
                    let (wall, cpu, r) = p.install(|| {
                        let c0 = thread_cpu_seconds();
                        let t0 = Instant::now();
                        let r = trace(accel, rays, query);
                        let wall = t0.elapsed().as_secs_f64();
                        let cpu = match (c0, thread_cpu_seconds()) {
                            (Some(a), Some(b)) if threads == 1 => b - a,
                            _ => f64::NAN,
                        };
                        (wall, cpu, r)
                    });
                    best_wall = best_wall.min(wall);
                    best_cpu = best_cpu.min(cpu);
                    result = r;
                }
                let n = rays.len() as f64;
                let check = if !w.anchor {
                    ""
                } else if result.0 == expected {
                    if expected == EXPECTED_HITS_INCOHERENT {
                        " ok (anchor 602,740 + 1 edge leak of non-watertight tests)"
                    } else {
                        " ok"
                    }
                } else {
                    " MISMATCH"
                };
                println!(
                    "{name:6} {set:16} threads={threads}: {:6.2} Mrays/s wall, {:6.2} Mrays/cpu-s, hits {}{check}, tsum {:.6e}",
                    n / best_wall * 1e-6,
                    n / best_cpu * 1e-6,
                    result.0,
                    result.1
                );
            }
        }
    }
    println!("# load average at end: {}", load_average());
}

fn criterion_groups(c: &mut Criterion, w: &Workload, group: &str) {
    let mut g = c.benchmark_group(format!("{group}/build"));
    g.sample_size(10)
        .throughput(Throughput::Elements(w.tris.len() as u64));
    for (q, name) in [(BvhQuality::Fast, "fast"), (BvhQuality::Medium, "medium")] {
        g.bench_function(name, |b| {
            b.iter(|| Accel::build(black_box(w.tris.clone()), q))
        });
    }
    g.finish();
    // Build thread scaling: every pass runs on the current rayon pool (the binned-SAH
    // builder's subtrees and binning, obvhs's PLOC for the other presets, the collapse).
    for threads in [1, 2] {
        let p = pool(threads);
        let mut g = c.benchmark_group(format!("{group}/build/{threads}t"));
        g.sample_size(10)
            .throughput(Throughput::Elements(w.tris.len() as u64));
        g.bench_function("medium", |b| {
            b.iter(|| p.install(|| Accel::build(black_box(w.tris.clone()), BvhQuality::Medium)))
        });
        g.finish();
    }
    let accel = Accel::build(w.tris.clone(), BvhQuality::Medium);
    for threads in [1, 2] {
        let p = pool(threads);
        let mut g = c.benchmark_group(format!("{group}/trace/{threads}t"));
        g.sample_size(10);
        for (set, rays, query) in [
            ("coherent", &w.coherent, Query::Closest),
            ("incoherent", &w.incoherent, Query::Closest),
            ("occluded", &w.incoherent, Query::Occluded),
        ] {
            g.throughput(Throughput::Elements(rays.len() as u64));
            g.bench_function(set, |b| {
                b.iter(|| p.install(|| trace(&accel, black_box(rays), query)))
            });
        }
        g.finish();
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    // `cargo test --benches` runs this with `--test`: only the tiny workload, once.
    let test_mode = args.iter().any(|a| a == "--test");
    let filter = |p: &str| {
        args.iter()
            .skip(1)
            .any(|a| !a.starts_with('-') && a.starts_with(p))
    };
    let reps = std::env::var("STAGELIGHT_BENCH_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    if filter("summary") {
        // `cargo bench --bench bvh -- summary`: the table only, no criterion groups.
        summary(&load_or_generate(), reps);
        return;
    }
    let mut c = Criterion::default().configure_from_args();
    let tiny = generated(64, 32, 128, 1 << 14);
    criterion_groups(&mut c, &tiny, "tiny");
    if !test_mode && !filter("tiny") {
        let w = load_or_generate();
        summary(&w, reps);
        criterion_groups(&mut c, &w, "anchor");
    }
    c.final_summary();
}
