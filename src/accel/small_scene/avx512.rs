//! The small-scene group test in one AVX-512 register: a group's sixteen triangles against
//! one ray, with the lane arithmetic of the AVX2 halves in `small_scene.rs` (and so of
//! [`WoopRay::intersect`]): the same IEEE operations in the same order, no fused
//! multiply-add, an exact division, `vmaxps` with the same NaN rule; compare results come
//! back as mask registers instead of `movemask`s.

use std::arch::x86_64::{
    __m512, _mm512_abs_ps, _mm512_add_ps, _mm512_castps_si512, _mm512_cmp_ps_mask,
    _mm512_cmplt_epi32_mask, _mm512_div_ps, _mm512_load_ps, _mm512_max_ps, _mm512_mul_ps,
    _mm512_or_si512, _mm512_set1_ps, _mm512_setzero_ps, _mm512_setzero_si512, _mm512_storeu_ps,
    _mm512_sub_ps, _mm512_xor_si512, _CMP_EQ_OQ, _CMP_GT_OQ, _CMP_LT_OQ,
};

use super::super::triangle::{gamma, WoopRay};
use super::super::{Hit, Ray};
use super::{Group, GroupTest, Lanes, SmallScene, LANES};

/// # Safety
/// The CPU must support AVX2 and AVX-512F.
#[target_feature(enable = "avx2,avx512f")]
pub(super) unsafe fn closest(scene: &SmallScene, ray: &Ray) -> Option<Hit> {
    scene.closest_with::<LaneRay16>(ray)
}

/// # Safety
/// The CPU must support AVX2 and AVX-512F.
#[target_feature(enable = "avx2,avx512f")]
pub(super) unsafe fn occluded(scene: &SmallScene, ray: &Ray) -> bool {
    scene.occluded_with::<LaneRay16>(ray)
}

/// Per-ray constants of the 16-lane test. Made only inside the AVX-512 functions above, so
/// its methods may use AVX-512F.
struct LaneRay16 {
    /// The axis permutation `[kx, ky, kz]` (each < 3).
    axes: [usize; 3],
    /// The origin in the ray's axis order.
    o: [__m512; 3],
    sx: __m512,
    sy: __m512,
    sz: __m512,
}

impl GroupTest for LaneRay16 {
    #[inline(always)]
    fn new(woop: &WoopRay) -> Self {
        let [kx, ky, kz] = woop.axes();
        let axes = [kx.min(2), ky.min(2), kz.min(2)];
        let o = woop.origin();
        let (sx, sy, sz) = woop.shear();
        // SAFETY: AVX-512F intrinsics on values; this type exists only inside the AVX-512
        // functions.
        let splat = |x: f32| unsafe { _mm512_set1_ps(x) };
        Self {
            axes,
            o: [splat(o[axes[0]]), splat(o[axes[1]]), splat(o[axes[2]])],
            sx: splat(sx),
            sy: splat(sy),
            sz: splat(sz),
        }
    }

    #[inline(always)]
    fn test(&self, g: &Group, t_limit: f32, out: &mut Lanes) {
        let [x0, y0, z0] = self.vertex(g, 0);
        let [x1, y1, z1] = self.vertex(g, 1);
        let [x2, y2, z2] = self.vertex(g, 2);
        // SAFETY: AVX-512F intrinsics on values (AVX-512 functions only); the stores write
        // the sixteen-float arrays of `out`.
        unsafe {
            let max3 = |a: __m512, b: __m512, c: __m512| _mm512_max_ps(_mm512_max_ps(a, b), c);
            let g = |n: u32| _mm512_set1_ps(gamma(n));
            let eq = |a: __m512, b: __m512| u32::from(_mm512_cmp_ps_mask::<_CMP_EQ_OQ>(a, b));
            let lt = |a: __m512, b: __m512| u32::from(_mm512_cmp_ps_mask::<_CMP_LT_OQ>(a, b));
            let gt = |a: __m512, b: __m512| u32::from(_mm512_cmp_ps_mask::<_CMP_GT_OQ>(a, b));
            let zero = _mm512_setzero_ps();
            // Shear.
            let x0 = _mm512_add_ps(x0, _mm512_mul_ps(self.sx, z0));
            let y0 = _mm512_add_ps(y0, _mm512_mul_ps(self.sy, z0));
            let x1 = _mm512_add_ps(x1, _mm512_mul_ps(self.sx, z1));
            let y1 = _mm512_add_ps(y1, _mm512_mul_ps(self.sy, z1));
            let x2 = _mm512_add_ps(x2, _mm512_mul_ps(self.sx, z2));
            let y2 = _mm512_add_ps(y2, _mm512_mul_ps(self.sy, z2));
            // Edge functions.
            let e0 = _mm512_sub_ps(_mm512_mul_ps(x1, y2), _mm512_mul_ps(y1, x2));
            let e1 = _mm512_sub_ps(_mm512_mul_ps(x2, y0), _mm512_mul_ps(y2, x0));
            let e2 = _mm512_sub_ps(_mm512_mul_ps(x0, y1), _mm512_mul_ps(y0, x1));
            let zero_lanes = eq(e0, zero) | eq(e1, zero) | eq(e2, zero);
            // Outside: two edge functions of different signs (the sign bits; see the AVX2
            // test for the zero and NaN lanes).
            let bits = |v: __m512| _mm512_castps_si512(v);
            let outside = u32::from(_mm512_cmplt_epi32_mask(
                _mm512_or_si512(
                    _mm512_xor_si512(bits(e0), bits(e1)),
                    _mm512_xor_si512(bits(e0), bits(e2)),
                ),
                _mm512_setzero_si512(),
            ));
            let inside = !outside & 0xffff & !zero_lanes;
            out.hit = 0;
            out.slow = 0;
            if zero_lanes | inside == 0 {
                return;
            }
            let det = _mm512_add_ps(_mm512_add_ps(e0, e1), e2);
            let zs0 = _mm512_mul_ps(z0, self.sz);
            let zs1 = _mm512_mul_ps(z1, self.sz);
            let zs2 = _mm512_mul_ps(z2, self.sz);
            let t_scaled = _mm512_add_ps(
                _mm512_add_ps(_mm512_mul_ps(e0, zs0), _mm512_mul_ps(e1, zs1)),
                _mm512_mul_ps(e2, zs2),
            );
            let same_sign =
                (gt(det, zero) & gt(t_scaled, zero)) | (lt(det, zero) & lt(t_scaled, zero));
            let candidate = same_sign & inside;
            if zero_lanes | candidate == 0 {
                return;
            }
            let inv_det = _mm512_div_ps(_mm512_set1_ps(1.0), det);
            let t = _mm512_mul_ps(t_scaled, inv_det);
            let max_zt = max3(_mm512_abs_ps(zs0), _mm512_abs_ps(zs1), _mm512_abs_ps(zs2));
            let delta_z = _mm512_mul_ps(g(3), max_zt);
            let max_xt = max3(_mm512_abs_ps(x0), _mm512_abs_ps(x1), _mm512_abs_ps(x2));
            let max_yt = max3(_mm512_abs_ps(y0), _mm512_abs_ps(y1), _mm512_abs_ps(y2));
            let max_z = max3(_mm512_abs_ps(z0), _mm512_abs_ps(z1), _mm512_abs_ps(z2));
            let delta_x = _mm512_mul_ps(g(5), _mm512_add_ps(max_xt, max_z));
            let delta_y = _mm512_mul_ps(g(5), _mm512_add_ps(max_yt, max_z));
            let delta_e = _mm512_mul_ps(
                _mm512_set1_ps(2.0),
                _mm512_add_ps(
                    _mm512_add_ps(
                        _mm512_mul_ps(_mm512_mul_ps(g(2), max_xt), max_yt),
                        _mm512_mul_ps(delta_y, max_xt),
                    ),
                    _mm512_mul_ps(delta_x, max_yt),
                ),
            );
            let max_e = max3(_mm512_abs_ps(e0), _mm512_abs_ps(e1), _mm512_abs_ps(e2));
            let delta_t = _mm512_mul_ps(
                _mm512_mul_ps(
                    _mm512_set1_ps(3.0),
                    _mm512_add_ps(
                        _mm512_add_ps(
                            _mm512_mul_ps(_mm512_mul_ps(g(3), max_e), max_zt),
                            _mm512_mul_ps(delta_e, max_zt),
                        ),
                        _mm512_mul_ps(delta_z, max_e),
                    ),
                ),
                _mm512_abs_ps(inv_det),
            );
            let sure = gt(t, delta_t);
            let near = lt(t, _mm512_set1_ps(t_limit));
            out.hit = candidate & sure & near;
            out.slow = zero_lanes | (candidate & !sure);
            if out.hit != 0 {
                _mm512_storeu_ps(out.t.as_mut_ptr(), t);
                _mm512_storeu_ps(out.b1.as_mut_ptr(), _mm512_mul_ps(e1, inv_det));
                _mm512_storeu_ps(out.b2.as_mut_ptr(), _mm512_mul_ps(e2, inv_det));
            }
        }
    }
}

impl LaneRay16 {
    /// Vertex `v` of the group's sixteen triangles: `(x, y, z)` translated to the origin, in
    /// the ray's axis order.
    #[inline(always)]
    fn vertex(&self, g: &Group, v: usize) -> [__m512; 3] {
        let [kx, ky, kz] = self.axes;
        // SAFETY: AVX-512F intrinsics (AVX-512 functions only); the aligned loads read
        // 16-float arrays of a `Group`, which is 64-byte aligned with every array at a
        // multiple of 64 bytes.
        unsafe {
            let load = |a: &[f32; LANES]| _mm512_load_ps(a.as_ptr());
            [
                _mm512_sub_ps(load(&g.v[v][kx]), self.o[0]),
                _mm512_sub_ps(load(&g.v[v][ky]), self.o[1]),
                _mm512_sub_ps(load(&g.v[v][kz]), self.o[2]),
            ]
        }
    }
}
