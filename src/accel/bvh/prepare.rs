//! The binned builder's input in one parallel pass over the caller's triangles: each
//! triangle's exact box, the degenerate-triangle filter, and the bounds of the boxes and of
//! their centroids (which `binned.rs` would otherwise fold in a second pass).
//!
//! When no triangle is degenerate (the common case) the boxes are indexed by the caller's
//! triangle index and no index list is made; otherwise the degenerate triangles' boxes are
//! dropped and `valid` names the caller's index of each remaining box.

use std::mem::MaybeUninit;

use glam::{Vec3, Vec3A};
use rayon::prelude::*;

use super::binned::Bounds;
use crate::accel::triangle::is_degenerate;

/// Triangles per task of the pass.
const CHUNK: usize = 1 << 14;

/// What [`prepare`] returns.
pub(super) struct Prepared {
    /// The exact box of every non-degenerate triangle, in the caller's order.
    pub(super) refs: Vec<Bounds>,
    /// The caller's index of each box; `None` when every triangle has one (`refs[i]` is
    /// triangle `i`'s box).
    pub(super) valid: Option<Vec<u32>>,
    /// Union of the boxes.
    pub(super) bounds: Bounds,
    /// Bounds of the boxes' centroids.
    pub(super) centroids: Bounds,
}

/// Per chunk: degenerate triangles, and the bounds and centroid bounds of the others.
type Summary = (usize, Bounds, Bounds);

fn merge(a: Summary, b: Summary) -> Summary {
    (a.0 + b.0, a.1.union(b.1), a.2.union(b.2))
}

/// Boxes, filter and bounds of `tris` (see the module header).
pub(super) fn prepare(tris: &[[Vec3; 3]]) -> Prepared {
    let n = tris.len();
    // Not advised as huge pages: a temporary, dropped before anything is traced (see
    // `huge_pages.rs`).
    let mut refs: Vec<Bounds> = Vec::with_capacity(n);
    let (degenerate, bounds, centroids) = refs.spare_capacity_mut()[..n]
        .par_chunks_mut(CHUNK)
        .zip(tris.par_chunks(CHUNK))
        .map(|(out, tris)| {
            let mut s: Summary = (0, Bounds::EMPTY, Bounds::EMPTY);
            for (slot, tri) in out.iter_mut().zip(tris) {
                let [v0, v1, v2] = tri.map(Vec3A::from);
                let b = Bounds::new(v0.min(v1).min(v2), v0.max(v1).max(v2));
                slot.write(b);
                if is_degenerate(tri) {
                    s.0 += 1;
                } else {
                    s.1 = s.1.union(b);
                    s.2.grow(b.centroid());
                }
            }
            s
        })
        .reduce(|| (0, Bounds::EMPTY, Bounds::EMPTY), merge);
    // SAFETY: the chunks cover `spare_capacity_mut()[..n]` and every slot of every chunk was
    // written above (`out` and `tris` have the same length), so the first `n` are initialised.
    unsafe { refs.set_len(n) };
    let valid = (degenerate > 0).then(|| {
        let valid: Vec<u32> = (0..n as u32)
            .into_par_iter()
            .filter(|&i| !is_degenerate(&tris[i as usize]))
            .collect();
        let kept: Vec<Bounds> = valid.par_iter().map(|&i| refs[i as usize]).collect();
        refs = kept;
        valid
    });
    Prepared {
        refs,
        valid,
        bounds,
        centroids,
    }
}

/// `MaybeUninit` keeps its layout: the chunks above write `Bounds` values in place.
const _: () = assert!(std::mem::size_of::<MaybeUninit<Bounds>>() == std::mem::size_of::<Bounds>());

#[cfg(test)]
mod tests {
    use super::*;

    /// The boxes are the triangles' min/max, the degenerate ones are dropped and named by
    /// `valid`, and the bounds are the folds of the kept boxes and centroids.
    #[test]
    fn boxes_filter_and_bounds() {
        let mut tris: Vec<[Vec3; 3]> = (0..3 * CHUNK + 5)
            .map(|i| {
                let f = i as f32;
                let c = Vec3::new((f * 0.37).sin(), (f * 0.11).cos(), f * 1e-3) * 10.0;
                [
                    c,
                    c + Vec3::new(0.3, 0.0, 0.1),
                    c + Vec3::new(0.0, 0.2, 0.3),
                ]
            })
            .collect();
        let check = |tris: &[[Vec3; 3]], p: &Prepared| {
            let kept: Vec<u32> = (0..tris.len() as u32)
                .filter(|&i| !is_degenerate(&tris[i as usize]))
                .collect();
            let names = p
                .valid
                .clone()
                .unwrap_or_else(|| (0..tris.len() as u32).collect());
            assert_eq!(names, kept);
            assert_eq!(p.refs.len(), kept.len());
            let (mut bounds, mut centroids) = (Bounds::EMPTY, Bounds::EMPTY);
            for (r, &i) in p.refs.iter().zip(&kept) {
                let [v0, v1, v2] = tris[i as usize].map(Vec3A::from);
                let want = Bounds::new(v0.min(v1).min(v2), v0.max(v1).max(v2));
                assert_eq!(r.bits(), want.bits());
                bounds = bounds.union(want);
                centroids.grow(want.centroid());
            }
            assert_eq!(p.bounds.bits(), bounds.bits());
            assert_eq!(p.centroids.bits(), centroids.bits());
        };
        let p = prepare(&tris);
        assert!(p.valid.is_none());
        check(&tris, &p);
        tris[7] = [Vec3::ZERO; 3];
        tris[CHUNK + 1][2] = Vec3::new(f32::NAN, 0.0, 0.0);
        tris[2 * CHUNK] = [Vec3::splat(1e30), Vec3::splat(1e30), Vec3::splat(1e30)];
        let p = prepare(&tris);
        assert_eq!(p.valid.as_ref().map(Vec::len), Some(tris.len() - 3));
        check(&tris, &p);
        assert!(prepare(&[]).refs.is_empty());
    }
}
