//! Procedural 2-D patterns over texture coordinates: checker, the seed's fuzzy disk,
//! RenderMan's `smoothstep`, and uv repetition (`mod(s·10, 1)`).

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
    fn repeat_is_the_seed_modulo() {
        let r = repeat(Vec2::new(0.123, -0.123), 10.0);
        assert!(
            (r.x - 0.23).abs() < 1e-5 && (r.y - 0.77).abs() < 1e-5,
            "{r}"
        );
        assert_eq!(fract(f32::INFINITY), 0.0);
    }
}
