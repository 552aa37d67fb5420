//! The sRGB transfer function.

/// Linear [0,1] → sRGB-encoded [0,1] (IEC 61966-2-1). Non-finite and negative values map to 0.
pub fn encode(linear: f32) -> f32 {
    if linear.is_nan() || linear <= 0.0 {
        return 0.0;
    }
    let l = linear.min(1.0);
    if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// Linear value → 8-bit sRGB code, rounded to nearest.
pub fn to_u8(linear: f32) -> u8 {
    (encode(linear) * 255.0 + 0.5) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endpoints_and_midpoint() {
        assert_eq!(to_u8(0.0), 0);
        assert_eq!(to_u8(1.0), 255);
        assert_eq!(to_u8(2.0), 255);
        assert_eq!(to_u8(f32::NAN), 0);
        // 18 % grey encodes to about 118.
        assert_eq!(to_u8(0.18), 118);
    }
}
