//! The lone-Lambert fast paths of [`Bsdf::eval`], [`Bsdf::pdf`] and [`Bsdf::sample`] against
//! the general sums over the lobes and [`Bsdf::sample_transport`], bit for bit.

use glam::Vec3;

use super::{Bsdf, BsdfSample, Lobe, TransportMode};
use crate::sampling::{hash_u32, u32_to_unit};

/// A sample's fields as bits: direction, value, pdf, delta, scatter kind.
type SampleBits = ([u32; 3], [u32; 3], u32, bool, u8);

/// Every field of a sample as bits (`−0` and `+0` differ, NaNs compare).
fn bits(s: Option<BsdfSample>) -> Option<SampleBits> {
    s.map(|s| {
        (
            s.wi.to_array().map(f32::to_bits),
            s.f.to_array().map(f32::to_bits),
            s.pdf.to_bits(),
            s.delta,
            s.scatter as u8,
        )
    })
}

/// A direction with components in (−1, 1) from a hash stream (not normalised: the fast
/// paths must agree on any input).
fn direction(k: &mut u32) -> Vec3 {
    let mut c = || {
        *k = hash_u32(k.wrapping_add(0x9e37_79b9));
        2.0 * u32_to_unit(*k) - 1.0
    };
    Vec3::new(c(), c(), c())
}

/// The BSDFs tested: lone Lambert lobes (clamped, zero and negative-zero channels, tiny) and,
/// for the general path, Lambert beside other lobes.
fn bsdfs() -> Vec<(Bsdf, bool)> {
    let lambert = |w: Vec3| Bsdf::from_lobes(&[(w, Lobe::Lambert)]).unwrap();
    let mut out: Vec<(Bsdf, bool)> = [
        Vec3::new(0.5, 0.3, 0.1),
        Vec3::ONE,
        Vec3::new(0.0, 0.2, 0.0),
        Vec3::new(-0.0, 0.5, 0.25),
        Vec3::new(2.0, 3.0, 4.0),
        Vec3::splat(1e-30),
        Vec3::new(0.7, 0.7, 0.7),
    ]
    .into_iter()
    .map(|w| (lambert(w), true))
    .collect();
    let phong = Lobe::Phong { exponent: 20.0 };
    let mixed = [
        vec![(Vec3::splat(0.4), Lobe::Lambert), (Vec3::splat(0.3), phong)],
        vec![
            (Vec3::splat(0.5), Lobe::Lambert),
            (Vec3::splat(0.5), Lobe::Mirror),
        ],
        vec![(Vec3::splat(0.6), phong)],
    ];
    out.extend(mixed.iter().map(|l| (Bsdf::from_lobes(l).unwrap(), false)));
    out
}

#[test]
fn lone_lambert_fast_paths_equal_the_general_sums_bit_for_bit() {
    let mut k = 12345u32;
    for (bsdf, lone) in bsdfs() {
        assert_eq!(bsdf.lambert_only().is_some(), lone, "{:?}", bsdf.lobes());
        for _ in 0..4000 {
            let (wo, wi) = (direction(&mut k), direction(&mut k));
            let wo = if k.is_multiple_of(5) { -wo.abs() } else { wo };
            let e = bsdf.eval(wo, wi).to_array().map(f32::to_bits);
            assert_eq!(e, bsdf.eval_lobes(wo, wi).to_array().map(f32::to_bits));
            assert_eq!(bsdf.pdf(wo, wi).to_bits(), bsdf.pdf_lobes(wo, wi).to_bits());
            let wo = wo.normalize();
            let u = (direction(&mut k) * 0.5 + Vec3::splat(0.5)).min(Vec3::splat(0.999_999));
            assert_eq!(
                bits(bsdf.sample(wo, u)),
                bits(bsdf.sample_transport(wo, u, TransportMode::Radiance)),
                "{:?} wo {wo} u {u}",
                bsdf.lobes()
            );
        }
        // The corners of the sample square (the disk's centre and edges).
        for u in [
            Vec3::ZERO,
            Vec3::new(0.3, 0.5, 0.5),
            Vec3::new(0.9, 0.0, 0.999_999),
        ] {
            let wo = Vec3::new(0.1, -0.2, 0.9).normalize();
            assert_eq!(
                bits(bsdf.sample(wo, u)),
                bits(bsdf.sample_transport(wo, u, TransportMode::Radiance))
            );
        }
    }
}
