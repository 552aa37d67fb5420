//! Lattice gradient noise shared by displacement shaders (`tessellation::displace`) and
//! texture nodes (`shading::texture::noise`): improved Perlin noise with a quintic fade and
//! hashed cube-edge gradients. Deterministic: the value depends only on the point and the
//! seed, never on threads or evaluation order.

use glam::DVec3;

/// Conservative bound of one Perlin octave (3-D gradient noise with cube-edge gradients
/// stays within √3/2·√2 ≈ 1.22 in theory, about ±1 in practice).
pub const PERLIN_BOUND: f64 = 1.25;

/// A 64-bit mix (splitmix64 finaliser).
pub fn mix(mut x: u64) -> u64 {
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// Improved-Perlin gradient at a lattice point: one of the 12 cube-edge directions.
fn gradient(ix: i64, iy: i64, iz: i64, seed: u64, d: DVec3) -> f64 {
    let h = mix(seed
        ^ mix((ix as u64).wrapping_mul(0x8da6_b343)
            ^ (iy as u64).wrapping_mul(0xd816_3841)
            ^ (iz as u64).wrapping_mul(0xcb1a_b31f)));
    match h % 12 {
        0 => d.x + d.y,
        1 => -d.x + d.y,
        2 => d.x - d.y,
        3 => -d.x - d.y,
        4 => d.x + d.z,
        5 => -d.x + d.z,
        6 => d.x - d.z,
        7 => -d.x - d.z,
        8 => d.y + d.z,
        9 => -d.y + d.z,
        10 => d.y - d.z,
        _ => -d.y - d.z,
    }
}

/// Perlin gradient noise (quintic fade), deterministic in (`p`, `seed`); about ±1.
pub fn perlin(p: DVec3, seed: u64) -> f64 {
    if !p.is_finite() {
        return 0.0;
    }
    let f = p.floor();
    // Saturating casts; neighbours wrap (huge points give meaningless but finite noise).
    let (ix, iy, iz) = (f.x as i64, f.y as i64, f.z as i64);
    let d = p - f;
    let fade = |t: f64| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let (u, v, w) = (fade(d.x), fade(d.y), fade(d.z));
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let g = |dx: i64, dy: i64, dz: i64| {
        gradient(
            ix.wrapping_add(dx),
            iy.wrapping_add(dy),
            iz.wrapping_add(dz),
            seed,
            d - DVec3::new(dx as f64, dy as f64, dz as f64),
        )
    };
    let x00 = lerp(g(0, 0, 0), g(1, 0, 0), u);
    let x10 = lerp(g(0, 1, 0), g(1, 1, 0), u);
    let x01 = lerp(g(0, 0, 1), g(1, 0, 1), u);
    let x11 = lerp(g(0, 1, 1), g(1, 1, 1), u);
    lerp(lerp(x00, x10, v), lerp(x01, x11, v), w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perlin_is_deterministic_bounded_and_zero_on_lattice() {
        let mut max: f64 = 0.0;
        for i in 0..2000 {
            let p = DVec3::new(
                i as f64 * 0.137,
                i as f64 * 0.071 - 3.0,
                (i % 17) as f64 * 0.29,
            );
            let a = perlin(p, 7);
            assert_eq!(a, perlin(p, 7));
            max = max.max(a.abs());
        }
        assert!(max <= PERLIN_BOUND && max > 0.3, "{max}");
        assert_eq!(perlin(DVec3::new(3.0, -2.0, 5.0), 1), 0.0);
    }
}
