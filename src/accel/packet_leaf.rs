//! The packet kernels' leaf test in ray lanes: one triangle against eight rays of a
//! common-origin packet (`packet.rs`) at once, in the lanes of an AVX2 register, with the
//! arithmetic of [`WoopRay::intersect`] lane by lane.
//!
//! * **Ray lanes**: [`RayLanes`] keeps each packet ray's watertight-test constants in
//!   structure-of-arrays form (origin, shear, and its axis permutation as two sign masks per
//!   axis), so eight consecutive rays of the packet are eight aligned loads, made once per
//!   leaf and shared by the leaf's triangles. A triangle's vertices are broadcast, the
//!   lane's origin subtracted per original axis, and the differences put in the lane's
//!   `kx, ky, kz` order with two `vblendvps` each: the same subtraction the scalar test makes
//!   after its permutation, so the value is the same. The constants are made from the ray
//!   itself (`RayLanes::set_ray`: `WoopRay::new`'s axis choice as masks, its three
//!   divisions in one `divps`), without `WoopRay::new`'s branches.
//! * **Same answers, bit for bit**: the lanes then make the scalar test's IEEE operations in
//!   its order (shear, edge functions, determinant, `t`, the conservative `δt` bound), no
//!   fused multiply-add, an exact division, as `leaf_wide.rs` does with triangles in lanes.
//!   Lanes the scalar test would finish in `f64` (an edge function exactly zero, `t ≤ δt`)
//!   are reported as *slow* and the caller answers them with the scalar test. `maxps` may
//!   propagate a NaN where `f32::max` ignores it; that only makes `δt` NaN, which fails
//!   `t > δt` and sends the lane to the scalar test.

#[cfg(test)]
use super::triangle::WoopRay;

/// Rays in one group of lanes.
pub(super) const LANES: usize = 8;

/// Per packet ray, the watertight test's constants as arrays over the packet's rays.
/// `sel[2·a]` (`sel[2·a + 1]`) is `−0.0` (sign bit set) for a ray whose axis `a` of the
/// permuted frame (x, y, z) is the original x (y), else `+0.0`.
#[repr(C, align(32))]
pub(super) struct RayLanes<const N: usize> {
    pub(super) o: [[f32; N]; 3],
    pub(super) s: [[f32; N]; 3],
    pub(super) sel: [[f32; N]; 6],
}

impl<const N: usize> RayLanes<N> {
    pub(super) fn new() -> Self {
        Self {
            o: [[0.0; N]; 3],
            s: [[0.0; N]; 3],
            sel: [[0.0; N]; 6],
        }
    }

    /// Stores ray `i`'s constants from its `WoopRay` (the reference for
    /// [`RayLanes::set_ray`]).
    #[cfg(test)]
    pub(super) fn set(&mut self, i: usize, woop: &WoopRay) {
        let o = woop.origin();
        let (sx, sy, sz) = woop.shear();
        let axes = woop.axes();
        for k in 0..3 {
            self.o[k][i] = o[k];
            let a = axes[k];
            self.sel[2 * k][i] = if a == 0 { -0.0 } else { 0.0 };
            self.sel[2 * k + 1][i] = if a == 1 { -0.0 } else { 0.0 };
        }
        self.s[0][i] = sx;
        self.s[1][i] = sy;
        self.s[2][i] = sz;
    }
}

impl<const N: usize> RayLanes<N> {
    /// Stores the constants of the ray `origin`, `dir` without making its `WoopRay`: the
    /// same values as [`RayLanes::set`] with `WoopRay::new(origin, dir)`, bit for bit, but
    /// the dominant axis is chosen without branches (they mispredict on a hemisphere's
    /// directions, about once per ray).
    #[inline(always)]
    pub(super) fn set_ray(&mut self, i: usize, origin: glam::Vec3, dir: glam::Vec3) {
        let a = dir.abs();
        let (x_gt_y, x_gt_z, y_gt_z) = (a.x > a.y, a.x > a.z, a.y > a.z);
        // `WoopRay::new`'s nested choice: x if it beats y and z, else y if it beats z
        // (and x did not beat y), else z; the same comparisons, so the same axis. As masks
        // (all ones for the chosen axis), not indices.
        let mask = |b: bool| 0u32.wrapping_sub(u32::from(b));
        let z_is_x = mask(x_gt_y & x_gt_z);
        let z_is_y = mask(!x_gt_y & y_gt_z);
        let o = origin.to_array();
        for (k, &o) in o.iter().enumerate() {
            self.o[k][i] = o;
        }
        let ([sx, sy, sz], [on_x, on_y, on_z]) = shear(dir, z_is_x, z_is_y);
        // `sel[2·k]`: axis k of the permuted frame is the original x; `sel[2·k + 1]`: y.
        // (kx, ky, kz) is (y, z, x), (z, x, y) or (x, y, z).
        self.sel[0][i] = on_z;
        self.sel[1][i] = on_x;
        self.sel[2][i] = on_y;
        self.sel[3][i] = on_z;
        self.sel[4][i] = on_x;
        self.sel[5][i] = on_y;
        self.s[0][i] = sx;
        self.s[1][i] = sy;
        self.s[2][i] = sz;
    }
}

/// `WoopRay::new`'s shear `(−d[kx] / d[kz], −d[ky] / d[kz], 1 / d[kz])` for the permutation
/// given by the masks (`z_is_x`: kz is x; `z_is_y`: kz is y; neither: kz is z), and the
/// masks' sign bits as floats (`−0.0` for the chosen axis, x, y, z). The permuted direction
/// is selected with vector `and`/`or`, the signs made in a vector too: scalar selects on
/// these masks were compiled to branches (a float select has no `cmov`), which mispredicted
/// as often as `WoopRay::new`'s. The three quotients are one `divps`: the same IEEE
/// divisions, so the same bits.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn shear(dir: glam::Vec3, z_is_x: u32, z_is_y: u32) -> ([f32; 3], [f32; 3]) {
    use std::arch::x86_64::{
        _mm_and_ps, _mm_andnot_ps, _mm_castsi128_ps, _mm_div_ps, _mm_or_ps, _mm_set1_epi32,
        _mm_set1_ps, _mm_setr_epi32, _mm_setr_ps, _mm_shuffle_ps, _mm_storeu_ps, _mm_xor_ps,
    };
    let mut out = [0.0f32; 4];
    let mut signs = [0.0f32; 4];
    // SAFETY: SSE2 intrinsics (baseline on x86_64) on values; the stores write the local
    // four-float arrays.
    unsafe {
        let z_is_z = !(z_is_x | z_is_y);
        let masks = _mm_castsi128_ps(_mm_setr_epi32(
            z_is_x as i32,
            z_is_y as i32,
            z_is_z as i32,
            0,
        ));
        _mm_storeu_ps(signs.as_mut_ptr(), _mm_and_ps(masks, _mm_set1_ps(-0.0)));
        let on_x = _mm_setr_ps(dir.y, dir.z, dir.x, 0.0);
        let on_y = _mm_setr_ps(dir.z, dir.x, dir.y, 0.0);
        let on_z = _mm_setr_ps(dir.x, dir.y, dir.z, 0.0);
        let mx = _mm_castsi128_ps(_mm_set1_epi32(z_is_x as i32));
        let my = _mm_castsi128_ps(_mm_set1_epi32(z_is_y as i32));
        // (d[kx], d[ky], d[kz], 0).
        let d = _mm_or_ps(
            _mm_or_ps(_mm_and_ps(mx, on_x), _mm_and_ps(my, on_y)),
            _mm_andnot_ps(_mm_or_ps(mx, my), on_z),
        );
        // (−d[kx], −d[ky], 1, 1) / d[kz].
        let neg = _mm_xor_ps(d, _mm_setr_ps(-0.0, -0.0, 0.0, 0.0));
        let num = _mm_shuffle_ps::<0b1111_0100>(neg, _mm_set1_ps(1.0));
        let kz = _mm_shuffle_ps::<0b1010_1010>(d, d);
        _mm_storeu_ps(out.as_mut_ptr(), _mm_div_ps(num, kz));
    }
    ([out[0], out[1], out[2]], [signs[0], signs[1], signs[2]])
}

/// [`shear`] without SSE.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn shear(dir: glam::Vec3, z_is_x: u32, z_is_y: u32) -> ([f32; 3], [f32; 3]) {
    let d = dir.to_array();
    let kz = if z_is_x != 0 {
        0
    } else if z_is_y != 0 {
        1
    } else {
        2
    };
    let (kx, ky) = ([1, 2, 0][kz], [2, 0, 1][kz]);
    let sign = |on: bool| if on { -0.0 } else { 0.0 };
    (
        [-d[kx] / d[kz], -d[ky] / d[kz], 1.0 / d[kz]],
        [sign(kz == 0), sign(kz == 1), sign(kz == 2)],
    )
}

#[cfg(target_arch = "x86_64")]
pub(super) use wide::Group8;

#[cfg(target_arch = "x86_64")]
mod wide {
    use std::arch::x86_64::{
        __m256, _mm256_add_ps, _mm256_and_ps, _mm256_andnot_ps, _mm256_blendv_ps, _mm256_cmp_ps,
        _mm256_div_ps, _mm256_loadu_ps, _mm256_max_ps, _mm256_movemask_ps, _mm256_mul_ps,
        _mm256_or_ps, _mm256_set1_ps, _mm256_setzero_ps, _mm256_storeu_ps, _mm256_sub_ps,
        _CMP_EQ_OQ, _CMP_GT_OQ, _CMP_LT_OQ,
    };

    use glam::Vec3;

    use super::super::triangle::gamma;
    use super::{RayLanes, LANES};

    /// Eight rays' constants in registers. Only made inside the AVX2 packet kernels, so its
    /// methods may use AVX.
    pub(in super::super) struct Group8 {
        o: [__m256; 3],
        s: [__m256; 3],
        sel: [__m256; 6],
    }

    /// What a triangle test found for a group: bit `j` of `hit` for lane `j` decided as a
    /// hit (its `t`, `b1`, `b2` are lane `j` of the vectors), bit `j` of `slow` for a lane
    /// the caller must decide with the scalar test; lanes in neither mask are misses.
    pub(in super::super) struct Lanes8 {
        pub(in super::super) hit: u32,
        pub(in super::super) slow: u32,
        pub(in super::super) t: [f32; 8],
        pub(in super::super) b1: [f32; 8],
        pub(in super::super) b2: [f32; 8],
    }

    #[inline(always)]
    fn abs(v: __m256) -> __m256 {
        // SAFETY: AVX on values (AVX2 packet kernels only).
        unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), v) }
    }

    #[inline(always)]
    fn max3(a: __m256, b: __m256, c: __m256) -> __m256 {
        // SAFETY: AVX on values (AVX2 packet kernels only).
        unsafe { _mm256_max_ps(_mm256_max_ps(a, b), c) }
    }

    /// Floats `at … at + 7` of `a` (no closures in the AVX2 kernels: they would not inherit
    /// the target feature).
    #[inline(always)]
    fn load8<const N: usize>(a: &[f32; N], at: usize) -> __m256 {
        assert!(at + 8 <= N);
        // SAFETY: AVX load of eight floats inside `a` (asserted above), through a reference.
        unsafe { _mm256_loadu_ps(a.as_ptr().add(at)) }
    }

    #[inline(always)]
    fn splat(x: f32) -> __m256 {
        // SAFETY: AVX on values (AVX2 packet kernels only).
        unsafe { _mm256_set1_ps(x) }
    }

    impl Group8 {
        /// Rays `LANES·group … LANES·group + 7` of `lanes`.
        #[inline(always)]
        pub(in super::super) fn load<const N: usize>(lanes: &RayLanes<N>, group: usize) -> Self {
            let at = LANES * group;
            Self {
                o: [
                    load8(&lanes.o[0], at),
                    load8(&lanes.o[1], at),
                    load8(&lanes.o[2], at),
                ],
                s: [
                    load8(&lanes.s[0], at),
                    load8(&lanes.s[1], at),
                    load8(&lanes.s[2], at),
                ],
                sel: [
                    load8(&lanes.sel[0], at),
                    load8(&lanes.sel[1], at),
                    load8(&lanes.sel[2], at),
                    load8(&lanes.sel[3], at),
                    load8(&lanes.sel[4], at),
                    load8(&lanes.sel[5], at),
                ],
            }
        }

        /// Vertex `p` translated to each lane's origin, in the lane's axis order.
        #[inline(always)]
        fn vertex(&self, p: Vec3) -> [__m256; 3] {
            // SAFETY: AVX on values (AVX2 packet kernels only).
            unsafe {
                let dx = _mm256_sub_ps(splat(p.x), self.o[0]);
                let dy = _mm256_sub_ps(splat(p.y), self.o[1]);
                let dz = _mm256_sub_ps(splat(p.z), self.o[2]);
                [
                    _mm256_blendv_ps(_mm256_blendv_ps(dz, dy, self.sel[1]), dx, self.sel[0]),
                    _mm256_blendv_ps(_mm256_blendv_ps(dz, dy, self.sel[3]), dx, self.sel[2]),
                    _mm256_blendv_ps(_mm256_blendv_ps(dz, dy, self.sel[5]), dx, self.sel[4]),
                ]
            }
        }

        /// Tests triangle `tri` against the lanes in `lanes` (a mask; the others are not
        /// reported).
        #[inline(always)]
        pub(in super::super) fn test(&self, tri: &[Vec3; 3], lanes: u32) -> Lanes8 {
            // SAFETY: AVX on values (AVX2 packet kernels only).
            self.test_in::<false>(tri, lanes, unsafe { _mm256_setzero_ps() })
        }

        /// [`Group8::test`] for occlusion: `hit` only has the lanes whose `t` is below
        /// their `t_max` (lane `j` of `t_max`, compared as `t < t_max`), and `t`, `b1`, `b2`
        /// are not stored (no loop over the lanes afterwards). `slow` is `test`'s.
        #[inline(always)]
        pub(in super::super) fn occludes(
            &self,
            tri: &[Vec3; 3],
            lanes: u32,
            t_max: __m256,
        ) -> Lanes8 {
            self.test_in::<true>(tri, lanes, t_max)
        }

        #[inline(always)]
        fn test_in<const OCCLUSION: bool>(
            &self,
            tri: &[Vec3; 3],
            lanes: u32,
            t_max: __m256,
        ) -> Lanes8 {
            let [x0, y0, z0] = self.vertex(tri[0]);
            let [x1, y1, z1] = self.vertex(tri[1]);
            let [x2, y2, z2] = self.vertex(tri[2]);
            let [sx, sy, sz] = self.s;
            // SAFETY: AVX on values (AVX2 packet kernels only); the stores write local
            // arrays of eight floats.
            unsafe {
                let zero = _mm256_setzero_ps();
                // Shear.
                let x0 = _mm256_add_ps(x0, _mm256_mul_ps(sx, z0));
                let y0 = _mm256_add_ps(y0, _mm256_mul_ps(sy, z0));
                let x1 = _mm256_add_ps(x1, _mm256_mul_ps(sx, z1));
                let y1 = _mm256_add_ps(y1, _mm256_mul_ps(sy, z1));
                let x2 = _mm256_add_ps(x2, _mm256_mul_ps(sx, z2));
                let y2 = _mm256_add_ps(y2, _mm256_mul_ps(sy, z2));
                // Edge functions.
                let e0 = _mm256_sub_ps(_mm256_mul_ps(x1, y2), _mm256_mul_ps(y1, x2));
                let e1 = _mm256_sub_ps(_mm256_mul_ps(x2, y0), _mm256_mul_ps(y2, x0));
                let e2 = _mm256_sub_ps(_mm256_mul_ps(x0, y1), _mm256_mul_ps(y0, x1));
                let any_zero = _mm256_or_ps(
                    _mm256_or_ps(
                        _mm256_cmp_ps::<_CMP_EQ_OQ>(e0, zero),
                        _mm256_cmp_ps::<_CMP_EQ_OQ>(e1, zero),
                    ),
                    _mm256_cmp_ps::<_CMP_EQ_OQ>(e2, zero),
                );
                let any_neg = _mm256_or_ps(
                    _mm256_or_ps(
                        _mm256_cmp_ps::<_CMP_LT_OQ>(e0, zero),
                        _mm256_cmp_ps::<_CMP_LT_OQ>(e1, zero),
                    ),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(e2, zero),
                );
                let any_pos = _mm256_or_ps(
                    _mm256_or_ps(
                        _mm256_cmp_ps::<_CMP_GT_OQ>(e0, zero),
                        _mm256_cmp_ps::<_CMP_GT_OQ>(e1, zero),
                    ),
                    _mm256_cmp_ps::<_CMP_GT_OQ>(e2, zero),
                );
                let zero_lanes = _mm256_movemask_ps(any_zero) as u32;
                let inside =
                    !(_mm256_movemask_ps(any_neg) as u32 & _mm256_movemask_ps(any_pos) as u32);
                let mut out = Lanes8 {
                    hit: 0,
                    slow: 0,
                    t: [0.0; 8],
                    b1: [0.0; 8],
                    b2: [0.0; 8],
                };
                // Most triangles are missed by every lane: stop before the division.
                if (zero_lanes | inside) & lanes == 0 {
                    return out;
                }
                let det = _mm256_add_ps(_mm256_add_ps(e0, e1), e2);
                let zs0 = _mm256_mul_ps(z0, sz);
                let zs1 = _mm256_mul_ps(z1, sz);
                let zs2 = _mm256_mul_ps(z2, sz);
                let t_scaled = _mm256_add_ps(
                    _mm256_add_ps(_mm256_mul_ps(e0, zs0), _mm256_mul_ps(e1, zs1)),
                    _mm256_mul_ps(e2, zs2),
                );
                let same_sign = _mm256_or_ps(
                    _mm256_and_ps(
                        _mm256_cmp_ps::<_CMP_GT_OQ>(det, zero),
                        _mm256_cmp_ps::<_CMP_GT_OQ>(t_scaled, zero),
                    ),
                    _mm256_and_ps(
                        _mm256_cmp_ps::<_CMP_LT_OQ>(det, zero),
                        _mm256_cmp_ps::<_CMP_LT_OQ>(t_scaled, zero),
                    ),
                );
                let inv_det = _mm256_div_ps(splat(1.0), det);
                let t = _mm256_mul_ps(t_scaled, inv_det);
                let max_zt = max3(abs(zs0), abs(zs1), abs(zs2));
                let delta_z = _mm256_mul_ps(splat(gamma(3)), max_zt);
                let max_xt = max3(abs(x0), abs(x1), abs(x2));
                let max_yt = max3(abs(y0), abs(y1), abs(y2));
                let max_z = max3(abs(z0), abs(z1), abs(z2));
                let delta_x = _mm256_mul_ps(splat(gamma(5)), _mm256_add_ps(max_xt, max_z));
                let delta_y = _mm256_mul_ps(splat(gamma(5)), _mm256_add_ps(max_yt, max_z));
                let delta_e = _mm256_mul_ps(
                    splat(2.0),
                    _mm256_add_ps(
                        _mm256_add_ps(
                            _mm256_mul_ps(_mm256_mul_ps(splat(gamma(2)), max_xt), max_yt),
                            _mm256_mul_ps(delta_y, max_xt),
                        ),
                        _mm256_mul_ps(delta_x, max_yt),
                    ),
                );
                let max_e = max3(abs(e0), abs(e1), abs(e2));
                let delta_t = _mm256_mul_ps(
                    _mm256_mul_ps(
                        splat(3.0),
                        _mm256_add_ps(
                            _mm256_add_ps(
                                _mm256_mul_ps(_mm256_mul_ps(splat(gamma(3)), max_e), max_zt),
                                _mm256_mul_ps(delta_e, max_zt),
                            ),
                            _mm256_mul_ps(delta_z, max_e),
                        ),
                    ),
                    abs(inv_det),
                );
                let candidate = _mm256_movemask_ps(same_sign) as u32 & inside & !zero_lanes;
                let sure = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(t, delta_t)) as u32;
                out.hit = candidate & sure & lanes;
                out.slow = (zero_lanes | (candidate & !sure)) & lanes;
                if OCCLUSION {
                    out.hit &= _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(t, t_max)) as u32;
                } else if out.hit != 0 {
                    _mm256_storeu_ps(out.t.as_mut_ptr(), t);
                    _mm256_storeu_ps(out.b1.as_mut_ptr(), _mm256_mul_ps(e1, inv_det));
                    _mm256_storeu_ps(out.b2.as_mut_ptr(), _mm256_mul_ps(e2, inv_det));
                }
                out
            }
        }
    }
}

#[cfg(test)]
mod lane_set_tests {
    use glam::Vec3;

    use super::*;

    /// `set_ray` (branch-free axis choice) stores what `set` stores from `WoopRay::new`, bit
    /// for bit: ties between components (|x| = |y|, |x| = |z|, |y| = |z|, all equal), ±0
    /// components, subnormals, huge and tiny values, infinities and random directions.
    #[test]
    fn set_ray_equals_set_from_the_woop_ray() {
        let mut rnd = crate::accel::test_random::signed_uniform(0x9e37_79b9_7f4a_7c15);
        let specials = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            -2.0,
            1e-40,
            -1e-40,
            f32::MAX,
            f32::INFINITY,
        ];
        let mut dirs = Vec::new();
        for &x in &specials {
            for &y in &specials {
                for &z in &specials {
                    dirs.push(Vec3::new(x, y, z));
                }
            }
        }
        for _ in 0..100_000 {
            let mut d = Vec3::new(rnd(), rnd(), rnd());
            match dirs.len() % 5 {
                0 => d.y = -d.x,
                1 => d.z = d.y,
                2 => d.x = d.z,
                _ => {}
            }
            dirs.push(d);
        }
        let origin = Vec3::new(0.25, -3.0, 7.5);
        let (mut want, mut got) = (RayLanes::<1>::new(), RayLanes::<1>::new());
        let mut axes_seen = [0usize; 3];
        for d in dirs {
            let woop = WoopRay::new(origin, d);
            axes_seen[woop.axes()[2]] += 1;
            want.set(0, &woop);
            got.set_ray(0, origin, d);
            let bits = |l: &RayLanes<1>| {
                let mut v: Vec<u32> = l.o.iter().map(|a| a[0].to_bits()).collect();
                v.extend(l.s.iter().map(|a| a[0].to_bits()));
                v.extend(l.sel.iter().map(|a| a[0].to_bits()));
                v
            };
            assert_eq!(bits(&got), bits(&want), "{d:?}");
        }
        assert!(axes_seen.iter().all(|&n| n > 20_000), "{axes_seen:?}");
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use glam::Vec3;

    use super::*;

    /// Lane answers of the 8-ray test for `tri`, slow lanes finished by the scalar test (as
    /// the packet kernels do), and the slow lanes (a mask).
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn lane_answers(
        lanes: &RayLanes<LANES>,
        woops: &[WoopRay; LANES],
        tri: &[Vec3; 3],
        mask: u32,
    ) -> ([Option<[u32; 3]>; LANES], u32) {
        let found = Group8::load(lanes, 0).test(tri, mask);
        assert_eq!((found.hit | found.slow) & !mask, 0);
        assert_eq!(found.hit & found.slow, 0);
        let mut out = [None; LANES];
        for (j, o) in out.iter_mut().enumerate() {
            let hit = if found.slow >> j & 1 != 0 {
                woops[j].intersect(tri)
            } else if found.hit >> j & 1 != 0 {
                Some((found.t[j], found.b1[j], found.b2[j]))
            } else {
                None
            };
            *o = hit.map(|(t, b1, b2)| [t, b1, b2].map(f32::to_bits));
        }
        (out, found.slow)
    }

    /// The 8-ray lanes answer as the scalar `WoopRay::intersect`, bit for bit (t, b1, b2),
    /// with the eight rays of a group in different axis permutations and from shared and
    /// distinct origins: random triangles at scales 1e-6 to 1e6, rays through shared grid
    /// vertices and edges (edge functions exactly zero), origins on the triangle (t ≈ 0, the
    /// f64 refinement), grazing and axis-parallel rays, ±0 direction components, and
    /// non-finite vertices; lanes outside the mask are never reported.
    #[test]
    fn ray_lanes_equal_scalar_test() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("no AVX2 on this CPU: the scalar leaf test runs");
            return;
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x9e37_79b9_7f4a_7c15u64);
        let (mut hits, mut slow, mut fast, mut cases) = (0, 0, 0, 0);
        let mut kz_mixed = 0;
        for i in 0..40_000 {
            let scale = [1e-6, 1e-2, 1.0, 1e3, 1e6][i % 5];
            let grid = i % 3 == 0;
            let point = |rnd: &mut dyn FnMut() -> f32| {
                let p = Vec3::new(rnd(), rnd(), rnd()) * 4.0;
                if grid {
                    p.round() * scale
                } else {
                    p * scale
                }
            };
            let (c, a, b) = (point(&mut rnd), point(&mut rnd), point(&mut rnd));
            let mut tri = [c, a, b];
            if i % 997 == 0 {
                tri[1].y = [f32::NAN, f32::INFINITY, f32::MAX][i / 997 % 3];
            }
            let shared = point(&mut rnd) * 2.0;
            let mut lanes = RayLanes::<LANES>::new();
            let mut woops = [WoopRay::new(Vec3::ZERO, Vec3::X); LANES];
            let mut mask = 0u32;
            let mut axes = [0usize; LANES];
            for (j, woop) in woops.iter_mut().enumerate() {
                let origin = match (i + j) % 5 {
                    0 => tri[0] * 0.25 + tri[1] * 0.5 + tri[2] * 0.25,
                    1 | 2 => shared,
                    _ => point(&mut rnd) * 2.0,
                };
                let mut target = match (i + j) % 4 {
                    0 => c,
                    1 => (a + b) * 0.5,
                    _ => tri[0] * 0.3 + tri[1] * 0.3 + tri[2] * 0.4 + point(&mut rnd) * 0.1,
                };
                if (i + j) % 11 == 0 {
                    target.z = origin.z;
                }
                let mut dir = target - origin;
                match (i + 3 * j) % 13 {
                    0 => dir = Vec3::new(0.0, -0.0, 1.0),
                    1 => dir.x = -0.0,
                    2 => dir = Vec3::new(rnd(), 0.0, 0.0),
                    _ => {}
                }
                if dir == Vec3::ZERO || !dir.is_finite() {
                    continue;
                }
                *woop = WoopRay::new(origin, dir);
                lanes.set(j, woop);
                axes[j] = woop.axes()[2];
                // One lane in nine left out of the mask.
                if (i + j) % 9 != 0 {
                    mask |= 1 << j;
                }
            }
            kz_mixed += usize::from(axes.iter().any(|&k| k != axes[0]));
            // SAFETY: AVX2 was detected above.
            let (got, slow_lanes) = unsafe { lane_answers(&lanes, &woops, &tri, mask) };
            slow += slow_lanes.count_ones() as usize;
            for (j, woop) in woops.iter().enumerate() {
                let want = if mask >> j & 1 != 0 {
                    woop.intersect(&tri)
                        .map(|(t, b1, b2)| [t, b1, b2].map(f32::to_bits))
                } else {
                    None
                };
                assert_eq!(got[j], want, "lane {j}: {woop:?} {tri:?}");
                cases += 1;
                hits += usize::from(want.is_some());
                fast += usize::from(want.is_some() && slow_lanes >> j & 1 == 0);
            }
        }
        // Not vacuous: many hits decided in lanes, some lanes sent to the scalar test, and
        // most groups mix axis permutations.
        assert!(cases > 300_000, "{cases}");
        assert!(fast > 20_000, "{fast} of {hits}");
        assert!(slow > 1_000, "{slow}");
        assert!(kz_mixed > 20_000, "{kz_mixed}");
    }
}
