//! The frame buffers split into rows, so that the worker shading a row writes its pixels in
//! place: no per-pixel results of the whole image are collected, moved or copied.

use std::ops::Add;

use glam::Vec3;

use super::PixelResult;
use crate::exact_sum::ExactSum;
use crate::framebuffer::{FrameBuffers, PixelSums};

/// One row of the frame buffers, with its part of the farm part's exact sums and of the
/// component passes when those are kept.
pub(super) struct RowOut<'a> {
    beauty: &'a mut [Vec3],
    alpha: &'a mut [f32],
    depth: &'a mut [f32],
    normal: &'a mut [Vec3],
    object_id: &'a mut [u32],
    material_id: &'a mut [u32],
    samples: &'a mut [u32],
    sums: Option<SumsRow<'a>>,
    components: Option<&'a mut [[Vec3; 6]]>,
    environment: Option<&'a mut [Vec3]>,
}

/// A row of a farm part's exact sums, covered counts, dropped counts and environment sums.
type SumsRow<'a> = (
    &'a mut [[ExactSum; 3]],
    &'a mut [u32],
    &'a mut [u32],
    Option<&'a mut [[ExactSum; 3]]>,
);

/// Samples taken and dropped, summed over pixels.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(super) struct Totals {
    /// Samples taken (including dropped ones).
    pub taken: u64,
    /// Non-finite samples dropped.
    pub dropped: u64,
}

impl Add for Totals {
    type Output = Self;

    fn add(self, other: Self) -> Self {
        Self {
            taken: self.taken + other.taken,
            dropped: self.dropped + other.dropped,
        }
    }
}

impl<'a> RowOut<'a> {
    /// The `height` rows of `width` pixels of `fb` (with its environment share when it
    /// keeps one), `sums` and `components` (row-major buffers of `width × height` values).
    pub(super) fn split(
        fb: &'a mut FrameBuffers,
        sums: Option<&'a mut PixelSums>,
        components: Option<&'a mut Vec<[Vec3; 6]>>,
        width: usize,
        height: usize,
    ) -> Vec<Self> {
        let FrameBuffers {
            beauty,
            alpha,
            depth,
            normal,
            object_id,
            material_id,
            samples,
            environment,
            ..
        } = fb;
        let (mut beauty, mut alpha, mut depth) = (&mut beauty[..], &mut alpha[..], &mut depth[..]);
        let (mut normal, mut object_id) = (&mut normal[..], &mut object_id[..]);
        let (mut material_id, mut samples) = (&mut material_id[..], &mut samples[..]);
        let mut sums = sums.map(|s| {
            let environment = s.environment.as_mut().map(|e| &mut e[..]);
            (
                &mut s.sums[..],
                &mut s.covered[..],
                &mut s.dropped[..],
                environment,
            )
        });
        let mut components = components.map(|c| &mut c[..]);
        let mut environment = environment.as_mut().map(|e| &mut e[..]);
        (0..height)
            .map(|_| RowOut {
                beauty: next_row(&mut beauty, width),
                alpha: next_row(&mut alpha, width),
                depth: next_row(&mut depth, width),
                normal: next_row(&mut normal, width),
                object_id: next_row(&mut object_id, width),
                material_id: next_row(&mut material_id, width),
                samples: next_row(&mut samples, width),
                sums: sums.as_mut().map(|(s, c, d, e)| {
                    let e = e.as_mut().map(|e| next_row(e, width));
                    (
                        next_row(s, width),
                        next_row(c, width),
                        next_row(d, width),
                        e,
                    )
                }),
                components: components.as_mut().map(|c| next_row(c, width)),
                environment: environment.as_mut().map(|e| next_row(e, width)),
            })
            .collect()
    }

    /// Writes pixel `x` of the row (an empty pixel when this part does not `own` it) and
    /// returns its samples taken and dropped.
    pub(super) fn store(&mut self, x: usize, p: &PixelResult, owned: bool) -> Totals {
        let empty;
        let p = if owned {
            p
        } else {
            empty = PixelResult::empty();
            &empty
        };
        if let Some((sums, covered, dropped, environment)) = &mut self.sums {
            sums[x] = *p.samples.sums();
            covered[x] = p.samples.covered;
            dropped[x] = p.samples.dropped;
            if let Some(e) = environment {
                e[x] = p.environment.as_deref().copied().unwrap_or_default();
            }
        }
        self.beauty[x] = p.samples.value();
        self.alpha[x] = p.samples.alpha();
        self.depth[x] = p.depth;
        self.normal[x] = p.normal;
        self.object_id[x] = p.object_id;
        self.material_id[x] = p.material_id;
        self.samples[x] = p.samples.taken;
        if let Some(c) = &mut self.components {
            c[x] = p.component_values();
        }
        if let Some(e) = &mut self.environment {
            e[x] = p.environment_value();
        }
        Totals {
            taken: u64::from(p.samples.taken),
            dropped: u64::from(p.samples.dropped),
        }
    }
}

/// The first `width` values of `rest`, which keeps the others.
fn next_row<'a, T>(rest: &mut &'a mut [T], width: usize) -> &'a mut [T] {
    let (row, tail) = std::mem::take(rest).split_at_mut(width);
    *rest = tail;
    row
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::adaptive::PixelSamples;

    /// A pixel whose every field depends on its index `i`.
    fn pixel(i: usize) -> PixelResult {
        let mut samples = PixelSamples::default();
        for k in 0..=(i % 3) {
            let v = (i * 7 + k) as f32 * 0.125;
            samples.add(Vec3::new(v, -v, 1.0 / (v + 1.0)), k % 2 == 0);
        }
        if i % 4 == 1 {
            samples.add(Vec3::NAN, true);
        }
        let c = DVec3::new(i as f64, 0.5, -(i as f64));
        let mut environment = [ExactSum::default(); 3];
        environment[i % 3].add(i as f32 * 0.25);
        PixelResult {
            depth: i as f32 + 0.25,
            normal: Vec3::new(i as f32, 1.0, 2.0),
            object_id: i as u32 * 3,
            material_id: i as u32 * 5 + 1,
            samples,
            components: Some(Box::new([c, c * 2.0, c, c, c * 3.0, c])),
            environment: Some(Box::new(environment)),
        }
    }

    /// What the flat row-major loop wrote for pixel `i`.
    fn flat(fb: &mut FrameBuffers, sums: &mut PixelSums, comps: &mut [[Vec3; 6]], i: usize) {
        let p = if i % 5 == 2 {
            PixelResult::empty()
        } else {
            pixel(i)
        };
        sums.sums[i] = *p.samples.sums();
        sums.covered[i] = p.samples.covered;
        sums.dropped[i] = p.samples.dropped;
        if let Some(e) = &mut sums.environment {
            e[i] = p.environment.as_deref().copied().unwrap_or_default();
        }
        if let Some(e) = &mut fb.environment {
            e[i] = p.environment_value();
        }
        fb.beauty[i] = p.samples.value();
        fb.alpha[i] = p.samples.alpha();
        fb.depth[i] = p.depth;
        fb.normal[i] = p.normal;
        fb.object_id[i] = p.object_id;
        fb.material_id[i] = p.material_id;
        fb.samples[i] = p.samples.taken;
        comps[i] = p.component_values();
    }

    #[test]
    fn rows_written_in_place_equal_the_row_major_buffers() {
        let (width, height) = (5, 3);
        let n = width * height;
        let empty_sums = || PixelSums {
            sums: vec![Default::default(); n],
            covered: vec![0; n],
            dropped: vec![0; n],
            environment: Some(vec![Default::default(); n]),
        };
        let with_environment = || FrameBuffers {
            environment: Some(vec![Vec3::ZERO; n]),
            ..FrameBuffers::new(5, 3)
        };
        let (mut expected, mut expected_sums) = (with_environment(), empty_sums());
        let mut expected_comps = vec![[Vec3::ZERO; 6]; n];
        for i in 0..n {
            flat(&mut expected, &mut expected_sums, &mut expected_comps, i);
        }
        let (mut fb, mut sums) = (with_environment(), empty_sums());
        let mut comps = vec![[Vec3::ZERO; 6]; n];
        let mut rows = RowOut::split(&mut fb, Some(&mut sums), Some(&mut comps), width, height);
        assert_eq!(rows.len(), height);
        let mut totals = Totals::default();
        // Rows in reverse and pixels right to left: the order of the workers does not matter.
        for y in (0..height).rev() {
            for x in (0..width).rev() {
                let i = y * width + x;
                totals = totals + rows[y].store(x, &pixel(i), i % 5 != 2);
            }
        }
        assert_eq!(fb, expected);
        assert_eq!(sums, expected_sums);
        let environment = expected.environment.as_ref().unwrap();
        assert!(environment.iter().filter(|e| **e != Vec3::ZERO).count() > n / 2);
        assert_eq!(comps, expected_comps);
        let taken = expected.samples.iter().map(|&s| u64::from(s)).sum();
        let dropped = expected_sums.dropped.iter().map(|&d| u64::from(d)).sum();
        assert_eq!(totals, Totals { taken, dropped });
        assert!(dropped > 0 && taken > dropped);
    }

    #[test]
    fn an_image_without_columns_has_empty_rows() {
        let mut fb = FrameBuffers::new(0, 4);
        let rows = RowOut::split(&mut fb, None, None, 0, 4);
        assert_eq!(rows.len(), 4);
        assert!(rows.iter().all(|r| r.beauty.is_empty() && r.sums.is_none()));
    }
}
