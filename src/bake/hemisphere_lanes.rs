//! Cosine-weighted hemisphere directions for a run of sample points at once: the AO baker's
//! ray generation ([`super::ao`]) with the arithmetic in SIMD lanes.
//!
//! Per sample `u` the direction is `t·x + b·y + n·z` for `(x, y, z) =
//! sample_cosine_hemisphere(u)` — the very expression the scalar path writes, in a plain
//! loop over structure-of-arrays inputs that the compiler vectorises (the concentric disk's
//! two wedges become a select, both computed). Vectorising keeps every lane's IEEE
//! operations and their order (Rust never contracts to FMA nor reassociates), so each
//! direction is the scalar one bit for bit (`lanes_equal_the_scalar_directions`). The loop
//! is compiled twice: with AVX2 (eight lanes; chosen at run time) and for the baseline
//! (SSE2, four lanes).

use glam::{Vec2, Vec3};

use crate::sampling::sample_cosine_hemisphere;

/// The frame directions are made in: tangents `t`, `b` and the normal `n`.
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    /// First tangent.
    pub t: Vec3,
    /// Second tangent.
    pub b: Vec3,
    /// Normal (the hemisphere's pole).
    pub n: Vec3,
}

/// Sample points in, directions out, as arrays over the samples (kept between calls).
#[derive(Debug, Default)]
pub struct DirectionLanes {
    /// The samples' first and second coordinates.
    pub u: [Vec<f32>; 2],
    /// The directions' x, y and z, one per sample after [`DirectionLanes::directions`].
    pub d: [Vec<f32>; 3],
}

impl DirectionLanes {
    /// Forgets the samples.
    pub fn clear(&mut self) {
        self.u[0].clear();
        self.u[1].clear();
    }

    /// Appends a sample point.
    #[inline]
    pub fn push(&mut self, u: Vec2) {
        self.u[0].push(u.x);
        self.u[1].push(u.y);
    }

    /// The direction of sample `k` (after [`DirectionLanes::directions`]).
    #[inline]
    pub fn direction(&self, k: usize) -> Vec3 {
        Vec3::new(self.d[0][k], self.d[1][k], self.d[2][k])
    }

    /// Computes the cosine-weighted direction about `frame` of every sample.
    pub fn directions(&mut self, frame: Frame) {
        let n = self.u[0].len();
        for d in &mut self.d {
            d.clear();
            d.resize(n, 0.0);
        }
        #[cfg(target_arch = "x86_64")]
        if use_avx2() {
            // SAFETY: AVX2 was detected on this CPU (`use_avx2`).
            unsafe { directions_avx2(&self.u, &mut self.d, frame) };
            return;
        }
        directions_in(&self.u, &mut self.d, frame);
    }
}

/// Whether the AVX2 copy of the loop runs (detected once).
#[cfg(target_arch = "x86_64")]
fn use_avx2() -> bool {
    static CHOICE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *CHOICE.get_or_init(|| std::arch::is_x86_feature_detected!("avx2"))
}

/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn directions_avx2(u: &[Vec<f32>; 2], d: &mut [Vec<f32>; 3], frame: Frame) {
    directions_in(u, d, frame);
}

/// The loop itself: no calls left after inlining, no early exits, so it vectorises.
#[inline(always)]
fn directions_in(u: &[Vec<f32>; 2], d: &mut [Vec<f32>; 3], frame: Frame) {
    let [ux, uy] = u;
    let [dx, dy, dz] = d;
    let n = ux
        .len()
        .min(uy.len())
        .min(dx.len())
        .min(dy.len())
        .min(dz.len());
    let (ux, uy) = (&ux[..n], &uy[..n]);
    let (dx, dy, dz) = (&mut dx[..n], &mut dy[..n], &mut dz[..n]);
    let Frame { t, b, n: normal } = frame;
    for k in 0..n {
        let local = sample_cosine_hemisphere(Vec2::new(ux[k], uy[k]));
        let dir = t * local.x + b * local.y + normal * local.z;
        dx[k] = dir.x;
        dy[k] = dir.y;
        dz[k] = dir.z;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every lane's direction equals the scalar expression's bit for bit, with AVX2 and with
    /// the baseline loop, for sample points on a fine grid, at the disk's wedge borders
    /// (`|x| = |y|`), the centre (both zero), the edges (0 and just below 1), for several
    /// frames and for run lengths that leave partial vectors.
    #[test]
    fn lanes_equal_the_scalar_directions() {
        let below_one = 1.0 - f32::EPSILON / 2.0;
        let mut points = vec![
            Vec2::splat(0.5),
            Vec2::new(0.5, 0.0),
            Vec2::new(0.0, 0.5),
            Vec2::ZERO,
            Vec2::new(below_one, 0.0),
            Vec2::splat(below_one),
            Vec2::new(0.25, 0.75),
            Vec2::new(0.75, 0.25),
        ];
        for i in 0..97 {
            for j in 0..89 {
                points.push(Vec2::new(i as f32 / 97.0, j as f32 / 89.0));
            }
        }
        // Wedge borders: |2u − 1| equal in both coordinates.
        for i in 0..200 {
            let a = i as f32 / 200.0;
            points.push(Vec2::new(a, a));
            points.push(Vec2::new(a, 1.0 - a));
        }
        let frames = [Vec3::Z, -Vec3::X, Vec3::new(0.3, -0.4, 0.866).normalize()].map(|n| {
            let frame = crate::shading::frame::ShadingFrame::from_normal(n);
            Frame {
                t: frame.s,
                b: frame.t,
                n,
            }
        });
        for frame in frames {
            for len in [points.len(), 1, 3, 13] {
                let want: Vec<[u32; 3]> = points[..len]
                    .iter()
                    .map(|&u| {
                        let l = sample_cosine_hemisphere(u);
                        (frame.t * l.x + frame.b * l.y + frame.n * l.z)
                            .to_array()
                            .map(f32::to_bits)
                    })
                    .collect();
                let mut lanes = DirectionLanes::default();
                for &u in &points[..len] {
                    lanes.push(u);
                }
                let got = |lanes: &DirectionLanes| -> Vec<[u32; 3]> {
                    (0..len)
                        .map(|k| lanes.direction(k).to_array().map(f32::to_bits))
                        .collect()
                };
                lanes.directions(frame);
                assert_eq!(got(&lanes), want, "dispatched, {len} samples");
                directions_in(&lanes.u, &mut lanes.d, frame);
                assert_eq!(got(&lanes), want, "baseline, {len} samples");
            }
        }
    }
}
