//! Procedural 2-D patterns over texture coordinates: checker, the seed's fuzzy disk, the
//! seed's stairs blend, RenderMan's `smoothstep`, and uv repetition (`mod(s·10, 1)`). Plain
//! arithmetic on glam values, shared by the shader graphs (`shading::texture`) and the
//! imager's pattern (`image_io::imager_pattern`), which may not depend on each other.

use glam::{Vec2, Vec3};

/// Which of the two checker colours covers `uv` with `scale` squares per unit of u and v:
/// 0 where `⌊u·scale⌋ + ⌊v·scale⌋` is even, 1 where it is odd.
pub fn checker(uv: Vec2, scale: f32) -> f32 {
    let c = (uv * scale).floor();
    if !c.is_finite() {
        return 0.0;
    }
    ((c.x as i64).wrapping_add(c.y as i64)).rem_euclid(2) as f32
}

/// RenderMan `smoothstep(e0, e1, x)`: 0 below `e0`, 1 at and above `e1`, the cubic
/// `t²(3 − 2t)` of `t = (x − e0)/(e1 − e0)` in between (a step at `e0` when `e0 = e1`).
pub fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    if x.is_nan() {
        return 0.0;
    }
    if x < e0 {
        return 0.0;
    }
    if x >= e1 {
        return 1.0;
    }
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The seed's disk: how much `uv` is inside the disk of `radius` around `center`,
/// `1 − smoothstep(radius − fuzz, radius + fuzz, |uv − center|)`.
pub fn disk(uv: Vec2, center: Vec2, radius: f32, fuzz: f32) -> f32 {
    let fuzz = fuzz.abs();
    1.0 - smoothstep(radius - fuzz, radius + fuzz, uv.distance(center))
}

/// `mod(x, 1)` as in the shading language: `x − ⌊x⌋`, in [0, 1) (0 for non-finite input).
pub fn fract(x: f32) -> f32 {
    let f = x - x.floor();
    if f.is_finite() && f < 1.0 {
        f
    } else {
        0.0
    }
}

/// The seed's repeated texture coordinates `(mod(s·scale, 1), mod(t·scale, 1))`.
pub fn repeat(uv: Vec2, scale: f32) -> Vec2 {
    Vec2::new(fract(uv.x * scale), fract(uv.y * scale))
}

/// The seed's `stairs` shader (§4.2, its last version, with `fuzz`) as one number: the
/// weight `w` of a step's tread normal `up` against its riser normal `front` at `v`, the
/// shader's `Nf = (1 − w)·front + w·up`. With `sv = mod(v·steps, 1)` (the riser below
/// `sv = ½`, the tread above) the printed branches give
///
/// - `sv < ½ − fuzz`: 0; but where `sv ≤ fuzz` above the bottom edge (`v·steps > fuzz`) the
///   tread below blends in: `w = ½ − sv/(2·fuzz)`;
/// - `sv > ½ + fuzz`: 1; but where `sv ≥ 1 − fuzz` below the top edge
///   (`v < 1 − fuzz/steps`) the riser above blends in: `w = 1 − (sv − 1 + fuzz)/(2·fuzz)`;
/// - otherwise (the edge in the middle of a step): `w = (sv − ½ + fuzz)/(2·fuzz)`.
///
/// `w` is ½ on every edge between steps and in [0, 1] for every `fuzz > 0`. A `fuzz` of 0
/// or less (or NaN) is the first printed version, without a blend: 0 for `sv < ½`, else 1.
pub fn steps(v: f32, steps: f32, fuzz: f32) -> f32 {
    let x = v * steps;
    let sv = fract(x);
    if fuzz.is_nan() || fuzz <= 0.0 {
        return if sv < 0.5 { 0.0 } else { 1.0 };
    }
    if sv < 0.5 - fuzz {
        if sv > fuzz || x <= fuzz {
            0.0
        } else {
            0.5 - sv / (2.0 * fuzz)
        }
    } else if sv > 0.5 + fuzz {
        if sv < 1.0 - fuzz || v >= 1.0 - fuzz / steps {
            1.0
        } else {
            1.0 - (sv - 1.0 + fuzz) / (2.0 * fuzz)
        }
    } else {
        (sv - 0.5 + fuzz) / (2.0 * fuzz)
    }
}

/// `mix(a, b, t) = a·(1 − t) + b·t`.
pub fn mix(a: Vec3, b: Vec3, t: f32) -> Vec3 {
    a * (1.0 - t) + b * t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates_by_cell_parity() {
        assert_eq!(checker(Vec2::new(0.05, 0.05), 4.0), 0.0);
        assert_eq!(checker(Vec2::new(0.30, 0.05), 4.0), 1.0);
        assert_eq!(checker(Vec2::new(0.30, 0.30), 4.0), 0.0);
        // Negative coordinates keep the parity pattern (no mirror at 0).
        assert_eq!(checker(Vec2::new(-0.1, 0.05), 4.0), 1.0);
        assert_eq!(checker(Vec2::new(f32::NAN, 0.0), 4.0), 0.0);
    }

    #[test]
    fn smoothstep_matches_the_cubic() {
        assert_eq!(smoothstep(0.2, 0.6, 0.1), 0.0);
        assert_eq!(smoothstep(0.2, 0.6, 0.6), 1.0);
        assert!((smoothstep(0.2, 0.6, 0.4) - 0.5).abs() < 1e-6);
        let t: f32 = 0.25;
        assert!((smoothstep(0.0, 4.0, 1.0) - t * t * (3.0 - 2.0 * t)).abs() < 1e-6);
        assert_eq!(smoothstep(0.5, 0.5, 0.49), 0.0);
        assert_eq!(smoothstep(0.5, 0.5, 0.5), 1.0);
    }

    #[test]
    fn disk_is_one_inside_zero_outside_and_half_on_the_rim() {
        let c = Vec2::splat(0.5);
        assert_eq!(disk(c, c, 0.4, 0.1), 1.0);
        assert_eq!(disk(Vec2::new(0.5, 0.0), c, 0.3, 0.1), 0.0);
        assert!((disk(Vec2::new(0.9, 0.5), c, 0.4, 0.1) - 0.5).abs() < 1e-5);
        // Without fuzz the edge is sharp.
        assert_eq!(disk(Vec2::new(0.89, 0.5), c, 0.4, 0.0), 1.0);
        assert_eq!(disk(Vec2::new(0.91, 0.5), c, 0.4, 0.0), 0.0);
    }

    #[test]
    fn steps_follows_the_printed_branches() {
        // steps 4, fuzz 0.1: sv = mod(4v, 1); v = 0.25·(k + sv).
        let w = |k: f32, sv: f32| steps(0.25 * (k + sv), 4.0, 0.1);
        let near = |a: f32, b: f32| (a - b).abs() < 1e-5;
        // Riser and tread away from the edges.
        assert_eq!(w(1.0, 0.3), 0.0);
        assert_eq!(w(1.0, 0.7), 1.0);
        // Middle edge: (sv − 0.5 + fuzz)/(2·fuzz).
        assert!(near(w(1.0, 0.5), 0.5));
        assert!(near(w(1.0, 0.45), 0.25));
        assert!(near(w(1.0, 0.58), 0.9));
        // Bottom of a step above the first: ½ − sv/(2·fuzz).
        assert!(near(w(1.0, 0.05), 0.25));
        assert!(near(w(2.0, 0.0), 0.5));
        // Top of a step below the last: 1 − (sv − 1 + fuzz)/(2·fuzz).
        assert!(near(w(1.0, 0.95), 0.75));
        assert!(near(w(1.0, 0.99), 0.55));
        // The bottom edge (v·steps ≤ fuzz) is all riser, the top (v ≥ 1 − fuzz/steps) all
        // tread.
        assert_eq!(w(0.0, 0.05), 0.0);
        assert_eq!(w(0.0, 0.0), 0.0);
        assert_eq!(w(3.0, 0.95), 1.0);
        // Without fuzz, the first printed version.
        assert_eq!(steps(0.3, 4.0, 0.0), 0.0);
        assert_eq!(steps(0.375, 4.0, 0.0), 1.0);
        assert_eq!(steps(0.25, 4.0, -1.0), 0.0);
    }

    #[test]
    fn repeat_is_the_seed_modulo() {
        let r = repeat(Vec2::new(0.123, -0.123), 10.0);
        assert!(
            (r.x - 0.23).abs() < 1e-5 && (r.y - 0.77).abs() < 1e-5,
            "{r}"
        );
        assert_eq!(fract(f32::INFINITY), 0.0);
    }

    /// The RSL's Hermite step, also at a zero-width band (moved from the imager's copy).
    #[test]
    fn smoothstep_is_the_rsl_hermite_step() {
        assert_eq!(smoothstep(0.3, 0.5, 0.29), 0.0);
        assert_eq!(smoothstep(0.3, 0.5, 0.5), 1.0);
        assert!((smoothstep(0.3, 0.5, 0.4) - 0.5).abs() < 1e-6);
        assert!((smoothstep(0.0, 1.0, 0.25) - 0.15625).abs() < 1e-6);
        assert_eq!(smoothstep(0.4, 0.4, 0.39), 0.0);
        assert_eq!(smoothstep(0.4, 0.4, 0.4), 1.0);
    }
}
