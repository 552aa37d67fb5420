//! The SIMD leaf test (x86-64, inside the AVX2 kernels only): a leaf's ≤ 3 triangles
//! against one ray at once, one triangle per lane of a 4-wide register, with the arithmetic
//! of [`WoopRay::intersect`] lane by lane.
//!
//! * **Same answers, bit for bit**: every lane makes the scalar test's IEEE operations in the
//!   same order (subtract, shear, edge functions, determinant, `t`, the conservative `δt`
//!   bound), with no fused multiply-add and an exact division, so a lane's `t`, `b1`, `b2` are
//!   the scalar ones. The rare lanes the scalar test would finish in `f64` (an edge function
//!   exactly zero; `t ≤ δt`) are reported as *slow* and the caller runs the scalar test on
//!   them, so those cases cannot differ either. Where the scalar `f32::max` ignores a NaN,
//!   `maxps` may propagate it; that can only make `δt` NaN, which fails `t > δt` and sends the
//!   lane to the scalar test.
//! * **Loads**: each vertex is read with one unaligned 16-byte load inside its own triangle
//!   (vertex 2 from 4 bytes earlier, so nothing past its 36 bytes of vertices is read), put
//!   in the ray's axis order by one `vpermilps` with a per-ray control (no dynamic indexing
//!   per triangle), and the three triangles are transposed into lanes. A leaf of fewer than three
//!   triangles reads its last one again (no branch on the count) and masks the extra lanes.

use std::arch::x86_64::{
    __m128, __m128i, _mm_add_ps, _mm_and_ps, _mm_andnot_ps, _mm_cmpeq_ps, _mm_cmpgt_ps,
    _mm_cmplt_ps, _mm_div_ps, _mm_loadu_ps, _mm_max_ps, _mm_movehl_ps, _mm_movelh_ps,
    _mm_movemask_ps, _mm_mul_ps, _mm_or_ps, _mm_permutevar_ps, _mm_set1_ps, _mm_setr_epi32,
    _mm_setr_ps, _mm_setzero_ps, _mm_storeu_ps, _mm_sub_ps, _mm_unpackhi_ps, _mm_unpacklo_ps,
};

use glam::Vec3;

use super::bvh::LeafTri;
use super::triangle::{gamma, WoopRay};

/// Per-ray constants of the 4-lane leaf test. Made only inside the AVX2 kernels (through
/// `NodeRay8`), so its methods may use AVX.
pub(super) struct LeafRay4 {
    /// `vpermilps` controls: vertices 0 and 1 (loaded from their own first float), vertex 2
    /// (loaded one float early).
    perm: __m128i,
    perm2: __m128i,
    /// The origin in the ray's axis order (`o[kx], o[ky], o[kz]`, last lane repeated).
    o: __m128,
    sx: __m128,
    sy: __m128,
    sz: __m128,
}

/// What a leaf test found: bit `j` of `hit` for a lane the vector test decided as a hit
/// (its `t`, `b1`, `b2` are lane `j` of the arrays), bit `j` of `slow` for a lane the caller
/// must decide with the scalar test. Lanes in neither mask are misses.
pub(super) struct LeafLanes {
    pub(super) hit: u32,
    pub(super) slow: u32,
    pub(super) t: [f32; 4],
    pub(super) b1: [f32; 4],
    pub(super) b2: [f32; 4],
}

impl LeafLanes {
    const MISS: Self = Self {
        hit: 0,
        slow: 0,
        t: [0.0; 4],
        b1: [0.0; 4],
        b2: [0.0; 4],
    };
}

impl LeafRay4 {
    #[inline(always)]
    pub(super) fn new(woop: &WoopRay) -> Self {
        let [kx, ky, kz] = woop.axes();
        let [kx, ky, kz] = [kx as i32, ky as i32, kz as i32];
        let o = woop.origin();
        let (sx, sy, sz) = woop.shear();
        let ko = [o[kx as usize], o[ky as usize], o[kz as usize]];
        // SAFETY: SSE/AVX intrinsics on values; this type exists only inside the AVX2
        // kernels.
        unsafe {
            Self {
                perm: _mm_setr_epi32(kx, ky, kz, kz),
                perm2: _mm_setr_epi32(kx + 1, ky + 1, kz + 1, kz + 1),
                o: _mm_setr_ps(ko[0], ko[1], ko[2], ko[2]),
                sx: _mm_set1_ps(sx),
                sy: _mm_set1_ps(sy),
                sz: _mm_set1_ps(sz),
            }
        }
    }

    /// Vertex `v` of `tri`, translated to the origin, in the ray's axis order.
    #[inline(always)]
    fn vertex(&self, tri: &[Vec3; 3], v: usize) -> __m128 {
        let base = std::ptr::from_ref(tri).cast::<f32>();
        // SAFETY: AVX intrinsics (AVX2 kernels only). The loads read 16 bytes at float 0, 3
        // or 5 of the 9-float triangle `tri` points to: floats 0–3, 3–6 and 5–8, all inside
        // it.
        unsafe {
            let (p, ctrl) = match v {
                0 => (_mm_loadu_ps(base), self.perm),
                1 => (_mm_loadu_ps(base.add(3)), self.perm),
                _ => (_mm_loadu_ps(base.add(5)), self.perm2),
            };
            _mm_sub_ps(_mm_permutevar_ps(p, ctrl), self.o)
        }
    }

    /// Vertex `v` of the three triangles as lanes: `(x, y, z)` in the ray's axis order,
    /// translated to the origin (lane 3 repeats lane 2).
    #[inline(always)]
    fn lanes(&self, tris: [&[Vec3; 3]; 3], v: usize) -> [__m128; 3] {
        // Not `array::map`: it is not inlined here (a call and a `vzeroupper` per use).
        let [p0, p1, p2] = [
            self.vertex(tris[0], v),
            self.vertex(tris[1], v),
            self.vertex(tris[2], v),
        ];
        // SAFETY: SSE shuffles on values (AVX2 kernels only).
        unsafe {
            let a = _mm_unpacklo_ps(p0, p1); // x0 x1 y0 y1
            let b = _mm_unpacklo_ps(p2, p2); // x2 x2 y2 y2
            let c = _mm_unpackhi_ps(p0, p1); // z0 z1 . .
            let d = _mm_unpackhi_ps(p2, p2); // z2 z2 . .
            [
                _mm_movelh_ps(a, b),
                _mm_movehl_ps(b, a),
                _mm_movelh_ps(c, d),
            ]
        }
    }

    /// Tests the leaf's triangles (1 to 3).
    #[inline(always)]
    pub(super) fn test(&self, tris: &[LeafTri]) -> LeafLanes {
        let n = tris.len();
        debug_assert!((1..=3).contains(&n));
        // Three triangles whatever the count: the last one repeated (no branch).
        let tri = [&tris[0].v, &tris[1.min(n - 1)].v, &tris[2.min(n - 1)].v];
        let [x0, y0, z0] = self.lanes(tri, 0);
        let [x1, y1, z1] = self.lanes(tri, 1);
        let [x2, y2, z2] = self.lanes(tri, 2);
        // SAFETY: SSE intrinsics on values (AVX2 kernels only); the stores write local
        // arrays of four floats.
        unsafe {
            let abs = |v: __m128| _mm_andnot_ps(_mm_set1_ps(-0.0), v);
            let max3 = |a: __m128, b: __m128, c: __m128| _mm_max_ps(_mm_max_ps(a, b), c);
            let g = |n: u32| _mm_set1_ps(gamma(n));
            let zero = _mm_setzero_ps();
            // Shear.
            let x0 = _mm_add_ps(x0, _mm_mul_ps(self.sx, z0));
            let y0 = _mm_add_ps(y0, _mm_mul_ps(self.sy, z0));
            let x1 = _mm_add_ps(x1, _mm_mul_ps(self.sx, z1));
            let y1 = _mm_add_ps(y1, _mm_mul_ps(self.sy, z1));
            let x2 = _mm_add_ps(x2, _mm_mul_ps(self.sx, z2));
            let y2 = _mm_add_ps(y2, _mm_mul_ps(self.sy, z2));
            // Edge functions.
            let e0 = _mm_sub_ps(_mm_mul_ps(x1, y2), _mm_mul_ps(y1, x2));
            let e1 = _mm_sub_ps(_mm_mul_ps(x2, y0), _mm_mul_ps(y2, x0));
            let e2 = _mm_sub_ps(_mm_mul_ps(x0, y1), _mm_mul_ps(y0, x1));
            let any_zero = _mm_or_ps(
                _mm_or_ps(_mm_cmpeq_ps(e0, zero), _mm_cmpeq_ps(e1, zero)),
                _mm_cmpeq_ps(e2, zero),
            );
            let any_neg = _mm_or_ps(
                _mm_or_ps(_mm_cmplt_ps(e0, zero), _mm_cmplt_ps(e1, zero)),
                _mm_cmplt_ps(e2, zero),
            );
            let any_pos = _mm_or_ps(
                _mm_or_ps(_mm_cmpgt_ps(e0, zero), _mm_cmpgt_ps(e1, zero)),
                _mm_cmpgt_ps(e2, zero),
            );
            let lanes = (1u32 << n) - 1;
            let zero_lanes = _mm_movemask_ps(any_zero) as u32;
            let inside = !(_mm_movemask_ps(any_neg) as u32 & _mm_movemask_ps(any_pos) as u32);
            // Most leaves are missed by every lane: stop before the division.
            if (zero_lanes | inside) & lanes == 0 {
                return LeafLanes::MISS;
            }
            let det = _mm_add_ps(_mm_add_ps(e0, e1), e2);
            let zs0 = _mm_mul_ps(z0, self.sz);
            let zs1 = _mm_mul_ps(z1, self.sz);
            let zs2 = _mm_mul_ps(z2, self.sz);
            let t_scaled = _mm_add_ps(
                _mm_add_ps(_mm_mul_ps(e0, zs0), _mm_mul_ps(e1, zs1)),
                _mm_mul_ps(e2, zs2),
            );
            let same_sign = _mm_or_ps(
                _mm_and_ps(_mm_cmpgt_ps(det, zero), _mm_cmpgt_ps(t_scaled, zero)),
                _mm_and_ps(_mm_cmplt_ps(det, zero), _mm_cmplt_ps(t_scaled, zero)),
            );
            let inv_det = _mm_div_ps(_mm_set1_ps(1.0), det);
            let t = _mm_mul_ps(t_scaled, inv_det);
            let max_zt = max3(abs(zs0), abs(zs1), abs(zs2));
            let delta_z = _mm_mul_ps(g(3), max_zt);
            let max_xt = max3(abs(x0), abs(x1), abs(x2));
            let max_yt = max3(abs(y0), abs(y1), abs(y2));
            let max_z = max3(abs(z0), abs(z1), abs(z2));
            let delta_x = _mm_mul_ps(g(5), _mm_add_ps(max_xt, max_z));
            let delta_y = _mm_mul_ps(g(5), _mm_add_ps(max_yt, max_z));
            let delta_e = _mm_mul_ps(
                _mm_set1_ps(2.0),
                _mm_add_ps(
                    _mm_add_ps(
                        _mm_mul_ps(_mm_mul_ps(g(2), max_xt), max_yt),
                        _mm_mul_ps(delta_y, max_xt),
                    ),
                    _mm_mul_ps(delta_x, max_yt),
                ),
            );
            let max_e = max3(abs(e0), abs(e1), abs(e2));
            let delta_t = _mm_mul_ps(
                _mm_mul_ps(
                    _mm_set1_ps(3.0),
                    _mm_add_ps(
                        _mm_add_ps(
                            _mm_mul_ps(_mm_mul_ps(g(3), max_e), max_zt),
                            _mm_mul_ps(delta_e, max_zt),
                        ),
                        _mm_mul_ps(delta_z, max_e),
                    ),
                ),
                abs(inv_det),
            );
            let candidate = _mm_movemask_ps(same_sign) as u32 & inside & !zero_lanes;
            let sure = _mm_movemask_ps(_mm_cmpgt_ps(t, delta_t)) as u32;
            let mut out = LeafLanes {
                hit: candidate & sure & lanes,
                slow: (zero_lanes | (candidate & !sure)) & lanes,
                t: [0.0; 4],
                b1: [0.0; 4],
                b2: [0.0; 4],
            };
            if out.hit != 0 {
                _mm_storeu_ps(out.t.as_mut_ptr(), t);
                _mm_storeu_ps(out.b1.as_mut_ptr(), _mm_mul_ps(e1, inv_det));
                _mm_storeu_ps(out.b2.as_mut_ptr(), _mm_mul_ps(e2, inv_det));
            }
            out
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the vector test answers for triangle `j` of `tris`, with its slow lanes finished
    /// by the scalar test (as the AVX2 kernels do), and whether the lane was slow.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    unsafe fn lane_answers(woop: &WoopRay, tris: &[[Vec3; 3]]) -> Vec<(Option<[u32; 3]>, bool)> {
        let lanes = LeafRay4::new(woop).test(&LeafTri::numbered(tris));
        assert_eq!((lanes.hit | lanes.slow) >> tris.len(), 0);
        assert_eq!(lanes.hit & lanes.slow, 0);
        (0..tris.len())
            .map(|j| {
                let slow = lanes.slow >> j & 1 != 0;
                let hit = if slow {
                    woop.intersect(&tris[j])
                } else if lanes.hit >> j & 1 != 0 {
                    Some((lanes.t[j], lanes.b1[j], lanes.b2[j]))
                } else {
                    None
                };
                (hit.map(|(t, b1, b2)| [t, b1, b2].map(f32::to_bits)), slow)
            })
            .collect()
    }

    /// The 4-lane leaf test answers as the scalar `WoopRay::intersect`, bit for bit (t, b1,
    /// b2), for leaves of 1, 2 and 3 triangles: random soups at scales from 1e-6 to 1e6, and
    /// the hard cases: rays through shared grid vertices and edges (edge functions exactly
    /// zero), origins on the triangle (t ≈ 0, the f64 refinement), grazing and axis-parallel
    /// rays, zero and negative-zero direction components, and non-finite coordinates.
    #[test]
    fn lanes_equal_scalar_test() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("no AVX2 on this CPU: the scalar leaf test runs");
            return;
        }
        let mut rnd = crate::accel::test_random::signed_uniform(0x51f1_5e5d_a2b7_c3e1u64);
        let (mut hits, mut slow, mut fast, mut cases) = (0, 0, 0, 0);
        for i in 0..60_000 {
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
            // Three triangles around a shared vertex, sharing edges pairwise on the grid.
            let c = point(&mut rnd);
            let a = point(&mut rnd);
            let b = point(&mut rnd);
            let d = point(&mut rnd);
            let mut tris = [[c, a, b], [c, b, d], [a, d, c]];
            let origin = match i % 7 {
                // On the first triangle: t ≈ 0.
                0 => tris[0][0] * 0.25 + tris[0][1] * 0.5 + tris[0][2] * 0.25,
                _ => point(&mut rnd) * 2.0,
            };
            let mut target = match i % 4 {
                0 => c,
                1 => (a + b) * 0.5,
                _ => point(&mut rnd),
            };
            if i % 11 == 0 {
                target.z = origin.z; // grazing: in the plane z = origin.z
            }
            let mut dir = target - origin;
            match i % 13 {
                0 => dir = Vec3::new(0.0, -0.0, 1.0),
                1 => dir.x = -0.0,
                2 => dir = Vec3::new(rnd(), 0.0, 0.0),
                _ => {}
            }
            if i % 997 == 0 {
                tris[i / 997 % 3][1].y = [f32::NAN, f32::INFINITY, f32::MAX][i / 997 % 3];
            }
            if dir == Vec3::ZERO || !dir.is_finite() {
                continue;
            }
            let woop = WoopRay::new(origin, dir);
            for n in 1..=3 {
                let leaf = &tris[..n];
                // SAFETY: AVX2 was detected above.
                let got = unsafe { lane_answers(&woop, leaf) };
                for (j, tri) in leaf.iter().enumerate() {
                    let want = woop
                        .intersect(tri)
                        .map(|(t, b1, b2)| [t, b1, b2].map(f32::to_bits));
                    assert_eq!(got[j].0, want, "{origin} {dir} {tri:?}");
                    cases += 1;
                    hits += usize::from(want.is_some());
                    slow += usize::from(got[j].1);
                    fast += usize::from(want.is_some() && !got[j].1);
                }
            }
        }
        // The cases are not vacuous: many hits decided in the lanes, and some lanes sent to
        // the scalar test (zero edge functions, t ≈ 0).
        assert!(cases > 300_000, "{cases}");
        assert!(fast > 20_000, "{fast} of {hits}");
        assert!(slow > 1_000, "{slow}");
    }
}
