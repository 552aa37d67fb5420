//! Adaptive anti-aliasing (`samples: (min, max, contrast)`): flat pixels stop at `min` (or
//! one doubling next to an edge), pixels on an edge go to `max`, the error per sample beats uniform sampling at the same
//! total, the reported work is the samples taken, and the image is the same at 1 and 2
//! threads.

use crate::common;

use common::{all_finite, render_text};
use stagelight::framebuffer::FrameBuffers;

/// A white `Constant` region with a slanted edge across a 32×32 view, black elsewhere.
fn edge_scene(samples: &str) -> String {
    format!(
        r#"Scene(
    options: (samples: {samples}),
    cameras: [(name: "cam", fov_y: 40, resolution: (32, 32),
        placement: LookAt(eye: (0, 0, 0), target: (0, 0, -1)))],
    materials: [(name: "white", shader: Constant(color: (1, 1, 1)))],
    objects: [(name: "wedge", mesh: Inline(
        vertices: [(-1, -3, -5), (10, -3, -5), (10, 3, -5), (1, 3, -5)],
        polygons: [[0, 1, 2, 3]]), material: "white")],
    instances: [(name: "wedge_1", of: "wedge")],
    groups: [(name: "world", members: ["wedge_1"])],
    render: (root: "world", camera: "cam"),
)"#
    )
}

const ADAPTIVE: &str = "(min: 4, max: 64, contrast: (0.02, 0.02, 0.02))";

fn mse(a: &FrameBuffers, b: &FrameBuffers) -> f64 {
    a.beauty
        .iter()
        .zip(&b.beauty)
        .map(|(x, y)| f64::from((*x - *y).length_squared()))
        .sum::<f64>()
        / a.beauty.len() as f64
}

#[test]
fn flat_pixels_take_min_and_edge_pixels_take_max() {
    let (fb, items) = render_text(&edge_scene(ADAPTIVE), |_| {});
    assert!(all_finite(&fb));
    let (w, h) = (fb.width as usize, fb.height as usize);
    let flat = |i: usize| fb.beauty[i].x == 0.0 || fb.beauty[i].x == 1.0;
    let mut edge = 0;
    for i in 0..w * h {
        let (n, v) = (fb.samples[i], fb.beauty[i].x);
        let (x, y) = ((i % w) as isize, (i / w) as isize);
        let near_edge = (-1isize..=1).any(|dy| {
            (-1isize..=1).any(|dx| {
                let (nx, ny) = (x + dx, y + dy);
                nx >= 0
                    && ny >= 0
                    && nx < w as isize
                    && ny < h as isize
                    && !flat(ny as usize * w + nx as usize)
            })
        });
        if flat(i) && !near_edge {
            assert_eq!(n, 4, "flat pixel ({v}) took {n} samples");
        } else if v > 0.15 && v < 0.85 {
            assert_eq!(n, 64, "edge pixel ({v}) took {n} samples");
            edge += 1;
        }
        assert!((4..=64).contains(&n));
    }
    assert!(edge >= 20, "only {edge} edge pixels");
    let total: u64 = fb.samples.iter().map(|&n| u64::from(n)).sum();
    assert_eq!(items, total, "the shade stage reports the samples taken");
    assert!(total < 64 * 32 * 32 / 4, "{total} samples");
}

#[test]
fn adaptive_beats_uniform_at_equal_total_samples() {
    let (reference, _) = render_text(&edge_scene("1024"), |_| {});
    let (adaptive, taken) = render_text(&edge_scene(ADAPTIVE), |_| {});
    let pixels = (adaptive.width * adaptive.height) as u64;
    // Uniform gets at least as many samples in total (rounded up).
    let spp = taken.div_ceil(pixels) as u32;
    let (uniform, uniform_taken) = render_text(&edge_scene(&spp.to_string()), |_| {});
    assert!(uniform_taken >= taken);
    let (e_a, e_u) = (mse(&adaptive, &reference), mse(&uniform, &reference));
    eprintln!(
        "adaptive: {taken} samples, MSE {e_a:.3e}; uniform {spp} spp: {uniform_taken} samples, MSE {e_u:.3e}"
    );
    assert!(e_a < 0.5 * e_u, "adaptive MSE {e_a} vs uniform {e_u}");
}

#[test]
fn adaptive_images_do_not_depend_on_the_thread_count() {
    let render = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render_text(&edge_scene(ADAPTIVE), |_| {}).0)
    };
    let (one, two) = (render(1), render(2));
    let bytes = |fb: &FrameBuffers| -> Vec<u32> {
        fb.beauty
            .iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .chain(fb.alpha.iter().map(|a| a.to_bits()))
            .chain(fb.samples.iter().copied())
            .collect()
    };
    assert_eq!(bytes(&one), bytes(&two));
}

#[test]
fn a_fixed_count_takes_that_many_samples_everywhere() {
    let (fb, items) = render_text(&edge_scene("6"), |_| {});
    assert!(fb.samples.iter().all(|&n| n == 6));
    assert_eq!(items, 6 * 32 * 32);
}

#[test]
fn the_contrast_knob_trades_samples_for_error() {
    // Lower contrast: more samples, lower error (sweep knob `adaptive_contrast`).
    let (reference, _) = render_text(&edge_scene("4096"), |_| {});
    let mut last = (0u64, f64::INFINITY);
    for c in [0.2f32, 0.05, 0.01] {
        let (fb, taken) = render_text(&edge_scene("(min: 2, max: 1024)"), |s| {
            s.adaptive.as_mut().unwrap().contrast = glam::Vec3::splat(c);
        });
        let e = mse(&fb, &reference);
        eprintln!("contrast {c}: {taken} samples, MSE {e:.3e}");
        assert!(
            taken > last.0 && e < last.1,
            "contrast {c}: {taken} samples, MSE {e}"
        );
        last = (taken, e);
    }
}
