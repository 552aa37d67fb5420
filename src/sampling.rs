//! Deterministic sampling: every random number derives from (seed, pixel/texel index,
//! sample index, dimension), never from a thread or a shared counter.
//!
//! Sequences are Owen-scrambled Sobol points (`sobol_burley`), one independent scramble per
//! pixel; beyond the table's 256 dimensions or 2¹⁶ samples a hash of the same inputs takes over.

mod quarter_trig;
mod sobol8;

use glam::{Vec2, Vec3};

/// A 32-bit integer hash with good avalanche (the `lowbias32` finaliser).
#[inline]
pub fn hash_u32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// Combines values into one well-mixed 32-bit seed.
#[inline]
pub fn hash_combine(values: &[u32]) -> u32 {
    let mut h = 0x9e37_79b9u32;
    for &v in values {
        h = hash_u32(h ^ hash_u32(v.wrapping_add(0x632b_e5ab)));
    }
    h
}

/// Folds a 64-bit user seed into 32 bits.
#[inline]
pub fn fold_seed(seed: u64) -> u32 {
    hash_combine(&[seed as u32, (seed >> 32) as u32])
}

/// Maps a 32-bit integer to a float in [0, 1).
#[inline]
pub fn u32_to_unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// Whether a pdf is usable: `pdf > 0 && pdf.is_finite()`, for every `f32` (NaN, ±0, ±∞,
/// subnormals) — as one integer compare: the positive finite non-zero floats are exactly the
/// bit patterns `1 ..= 0x7f7f_ffff`. LLVM turns the two float tests into a class test that
/// baseline x86-64 expands to ≈ 20 integer instructions.
#[inline(always)]
pub fn usable_pdf(pdf: f32) -> bool {
    pdf.to_bits().wrapping_sub(1) < 0x7f7f_ffff
}

/// A stream of sample dimensions for one (sequence seed, sample index).
///
/// Sobol dimensions are computed eight at a time ([`sobol8`]: the values of
/// `sobol_burley::sample_4d` for two dimension sets, bit for bit) and cached, so consecutive
/// dimensions cost an eighth each; the index scramble they share is made once.
#[derive(Debug, Clone)]
pub struct Sampler {
    seed: u32,
    index: u32,
    dimension: u32,
    /// The scrambled index of the Sobol sum ([`sobol8::scrambled_index`]).
    index_rev: u32,
    /// Which pair of four-dimension sets `cache` holds (`u32::MAX`: none).
    cached_pair: u32,
    cache: [f32; 8],
}

impl Sampler {
    /// The `index`-th point of the sequence scrambled by `seed`, starting at dimension 0.
    pub fn new(seed: u32, index: u32) -> Self {
        Self {
            seed,
            index,
            dimension: 0,
            index_rev: sobol8::scrambled_index(index, seed),
            cached_pair: u32::MAX,
            cache: [0.0; 8],
        }
    }

    /// The sampler for sample `index` of pixel (or texel, photon) `item` under `seed`.
    pub fn for_item(seed: u32, item: u64, index: u32) -> Self {
        Self::new(
            hash_combine(&[seed, item as u32, (item >> 32) as u32]),
            index,
        )
    }

    /// Next value in [0, 1).
    /// [`Sampler::for_item`] with its first eight Sobol dimensions already made (the same
    /// stream, bit for bit). A caller that makes the next sample's sampler before shading the
    /// current one takes the hashes and multiplies of its seed, index scramble and first
    /// dimensions off the sample's critical path: they run beside the current sample's work.
    /// Always inlined: made out of line (LLVM's choice moved with unrelated changes) it
    /// returned the 56-byte sampler through memory and its chains no longer overlapped the
    /// previous sample's work as well (`CameraRays::ray` waited: 1.4 % → 2.4 % of a sample).
    #[inline(always)]
    pub fn for_item_primed(seed: u32, item: u64, index: u32) -> Self {
        let mut s = Self::for_item(seed, item, index);
        if s.index < (1 << 16) {
            s.cache = sobol8::eight(s.index_rev, 0, s.seed);
            s.cached_pair = 0;
        }
        s
    }

    #[inline(always)]
    pub fn next_1d(&mut self) -> f32 {
        let d = self.dimension;
        self.dimension += 1;
        if d < sobol_burley::NUM_DIMENSIONS && self.index < (1 << 16) {
            let pair = d / 8;
            if pair != self.cached_pair {
                self.cache = sobol8::eight(self.index_rev, pair, self.seed);
                self.cached_pair = pair;
            }
            self.cache[(d % 8) as usize]
        } else {
            u32_to_unit(hash_combine(&[self.seed, self.index, d]))
        }
    }

    /// Next pair of values in [0, 1)².
    #[inline(always)]
    pub fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.next_1d(), self.next_1d())
    }

    /// Consumes one dimension and returns the seed of a fresh, independently scrambled child
    /// sequence (e.g. N light samples inside one camera sample: `Sampler::new(seed, j)`).
    pub fn child_seed(&mut self) -> u32 {
        let d = self.dimension;
        self.dimension += 1;
        hash_combine(&[self.seed, self.index, d, 0x5eed])
    }
}

/// `Sampler::new(seed, first + k).next_2d()` for `k in 0..count`, in order, handed to `f`:
/// the first two dimensions of consecutive samples (a bake texel's hemisphere rays), four
/// samples per pass of the lane arithmetic ([`sobol8::first_two_of_four`]), the same bits.
#[inline]
pub fn first_2d_of_run(seed: u32, first: u32, count: u32, mut f: impl FnMut(Vec2)) {
    let mut k = 0;
    // Four at a time while every index is inside the Sobol table (`next_1d`'s condition).
    while k + 4 <= count && u64::from(first) + u64::from(k) + 4 <= 1 << 16 {
        let revs: [u32; 4] =
            std::array::from_fn(|j| sobol8::scrambled_index(first + k + j as u32, seed));
        let v = sobol8::first_two_of_four(revs, seed);
        for j in 0..4 {
            f(Vec2::new(v[2 * j], v[2 * j + 1]));
        }
        k += 4;
    }
    for k in k..count {
        f(Sampler::new(seed, first.wrapping_add(k)).next_2d());
    }
}

/// Uniform point on a triangle (barycentrics b1, b2) from `u ∈ [0,1)²` (Heitz's low-distortion
/// square-to-triangle map).
pub fn sample_triangle(u: Vec2) -> (f32, f32) {
    let (mut b0, mut b1);
    if u.x < u.y {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    b0 = b0.clamp(0.0, 1.0);
    b1 = b1.clamp(0.0, 1.0 - b0);
    (b1, 1.0 - b0 - b1)
}

/// Cosine-weighted direction about +Z from `u ∈ [0,1)²` (concentric disk mapping);
/// pdf = cosθ/π.
#[inline]
pub fn sample_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = sample_concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// Direction uniform in solid angle over the hemisphere about +Z from `u ∈ [0,1)²`
/// (z = 1 − u.x, so z ∈ (0, 1]); pdf = 1/(2π).
#[inline]
pub fn sample_uniform_hemisphere(u: Vec2) -> Vec3 {
    let z = 1.0 - u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (sin, cos) = (std::f32::consts::TAU * u.y).sin_cos();
    Vec3::new(r * cos, r * sin, z)
}

/// Uniform point on the unit disk (Shirley–Chiu concentric mapping). The angle of the
/// second wedge, `π/2 − a`, is folded onto `a` (`cos(π/2 − a) = sin a`), so one quarter-turn
/// polynomial ([`quarter_trig`]) serves both.
#[inline]
pub fn sample_concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    if o.x.abs() > o.y.abs() {
        let (sin, cos) = quarter_trig::sin_cos_quarter(std::f32::consts::FRAC_PI_4 * (o.y / o.x));
        o.x * Vec2::new(cos, sin)
    } else {
        let (sin, cos) = quarter_trig::sin_cos_quarter(std::f32::consts::FRAC_PI_4 * (o.x / o.y));
        o.y * Vec2::new(sin, cos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usable_pdf_is_positive_and_finite_for_every_class() {
        let mut xs = vec![
            0.0f32,
            -0.0,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            f32::from_bits(0x8000_0001),
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            f32::from_bits(0x7f80_0001),
            f32::from_bits(0xffc0_0000),
            1.0,
            -1.0,
        ];
        let mut h = 0x1234_5678u32;
        for _ in 0..200_000 {
            h = hash_u32(h);
            xs.push(f32::from_bits(h));
        }
        // Every bit pattern near the class edges.
        for edge in [0u32, 0x7f7f_ffff, 0x7f80_0000, 0x8000_0000, 0xff80_0000] {
            for k in 0..64u32 {
                xs.push(f32::from_bits(edge.wrapping_add(k).wrapping_sub(32)));
            }
        }
        for x in xs {
            assert_eq!(
                usable_pdf(x),
                x > 0.0 && x.is_finite(),
                "{x} ({:#x})",
                x.to_bits()
            );
        }
    }

    #[test]
    fn samples_are_in_unit_interval_and_deterministic() {
        let mut a = Sampler::for_item(7, 12345, 3);
        let mut b = Sampler::for_item(7, 12345, 3);
        for _ in 0..600 {
            let x = a.next_1d();
            assert!((0.0..1.0).contains(&x));
            assert_eq!(x, b.next_1d());
        }
    }

    #[test]
    fn first_2d_of_run_is_next_2d_of_each_sample() {
        for (first, count) in [
            (0u32, 64u32),
            (5, 7),
            (65_530, 12),
            (u32::MAX - 2, 3),
            (100, 0),
        ] {
            let mut got = Vec::new();
            first_2d_of_run(0x5eed, first, count, |v| {
                got.push(v.to_array().map(f32::to_bits))
            });
            let want: Vec<_> = (0..count)
                .map(|k| {
                    let v = Sampler::new(0x5eed, first.wrapping_add(k)).next_2d();
                    v.to_array().map(f32::to_bits)
                })
                .collect();
            assert_eq!(got, want, "first {first} count {count}");
        }
    }

    /// A primed sampler gives the same stream as a plain one, bit for bit: every Sobol
    /// dimension and the hashed ones past them, indices inside and beyond the Sobol table,
    /// a child seed taken first.
    #[test]
    fn primed_sampler_gives_the_same_stream() {
        for (seed, item) in [(0u32, 0u64), (7, 12_345), (0xdead_beef, u64::MAX - 3)] {
            for index in [0u32, 1, 255, 65_535, 65_536, u32::MAX] {
                let mut a = Sampler::for_item(seed, item, index);
                let mut b = Sampler::for_item_primed(seed, item, index);
                for _ in 0..sobol_burley::NUM_DIMENSIONS + 8 {
                    assert_eq!(a.next_1d().to_bits(), b.next_1d().to_bits());
                }
                let mut a = Sampler::for_item(seed, item, index);
                let mut b = Sampler::for_item_primed(seed, item, index);
                assert_eq!(a.child_seed(), b.child_seed());
                for _ in 0..20 {
                    assert_eq!(a.next_1d().to_bits(), b.next_1d().to_bits());
                }
            }
        }
    }

    #[test]
    fn cached_eight_dimension_pairs_equal_single_dimensions() {
        for index in [0, 1, 7, 1000, 65535] {
            let mut s = Sampler::new(0xdead_beef, index);
            for d in 0..sobol_burley::NUM_DIMENSIONS {
                assert_eq!(s.next_1d(), sobol_burley::sample(index, d, 0xdead_beef));
            }
        }
        // A child seed in between skips a dimension without disturbing the others.
        let mut a = Sampler::new(5, 3);
        let (x0, _, x2) = (a.next_1d(), a.child_seed(), a.next_1d());
        assert_eq!(x0, sobol_burley::sample(3, 0, 5));
        assert_eq!(x2, sobol_burley::sample(3, 2, 5));
    }

    #[test]
    fn sobol_points_are_stratified() {
        // 16 points of one 2-D Sobol sequence fall one per 4×4 stratum.
        let mut seen = [false; 16];
        for i in 0..16 {
            let mut s = Sampler::new(99, i);
            let p = s.next_2d();
            let cell = (p.x * 4.0) as usize + 4 * (p.y * 4.0) as usize;
            assert!(!seen[cell], "two points in stratum {cell}");
            seen[cell] = true;
        }
    }

    #[test]
    fn concentric_disk_matches_the_library_trigonometry() {
        // The folded polynomial map against the textbook form with `f64` cos/sin.
        let n = 300;
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.25) / n as f32);
                let o = (2.0 * u - Vec2::ONE).as_dvec2();
                let (r, theta) = if o.x.abs() > o.y.abs() {
                    (o.x, std::f64::consts::FRAC_PI_4 * (o.y / o.x))
                } else {
                    (
                        o.y,
                        std::f64::consts::FRAC_PI_2 - std::f64::consts::FRAC_PI_4 * (o.x / o.y),
                    )
                };
                let want = r * glam::DVec2::new(theta.cos(), theta.sin());
                let got = sample_concentric_disk(u);
                assert!(got.length() <= 1.0, "{u} -> {got} outside the disk");
                assert!(
                    (got.as_dvec2() - want).abs().max_element() < 4e-7,
                    "{u}: {got} vs {want}"
                );
            }
        }
        assert_eq!(sample_concentric_disk(Vec2::splat(0.5)), Vec2::ZERO);
    }

    #[test]
    fn triangle_samples_are_inside_and_uniform() {
        let n = 4096;
        let mut left = 0;
        for i in 0..n {
            let mut s = Sampler::new(3, i);
            let (b1, b2) = sample_triangle(s.next_2d());
            assert!(b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0 + 1e-6);
            if b1 < 0.5 {
                left += 1;
            }
        }
        // Area of {b1 < 1/2} inside the triangle is 3/4 of the total.
        let frac = left as f32 / n as f32;
        assert!((frac - 0.75).abs() < 0.02, "{frac}");
    }
}
