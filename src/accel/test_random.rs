//! The tests' random numbers: a xorshift64 stream of floats uniform in [−1, 1), the same
//! stream for the same seed, so every ray-layer test draws its soups and rays reproducibly;
//! and a tessellated ball.

use glam::Vec3;

/// Floats uniform in [−1, 1) (24 random bits each) from a xorshift64 generator seeded with
/// `seed` (non-zero).
pub(crate) fn signed_uniform(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    }
}

/// A UV sphere of `rings` × `segments` quads (two triangles each, poles fans), its faces
/// counter-clockwise from outside.
pub(crate) fn uv_sphere(centre: Vec3, radius: f32, rings: u32, segments: u32) -> Vec<[Vec3; 3]> {
    let at = |i: u32, j: u32| {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        let phi = std::f32::consts::TAU * (j % segments) as f32 / segments as f32;
        if i == 0 || i == rings {
            return centre + Vec3::new(0.0, 0.0, radius * theta.cos().signum());
        }
        centre
            + radius
                * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                )
    };
    let mut tris = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if i != 0 {
                tris.push([a, b, d]);
            }
            if i + 1 != rings {
                tris.push([b, c, d]);
            }
        }
    }
    tris
}
