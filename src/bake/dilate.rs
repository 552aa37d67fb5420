//! Dilation (padding): grows every chart outward by N texels so bilinear filtering and mip
//! maps do not pull background across UV seams. Baked texels are never overwritten.

use glam::Vec3;

use crate::bake::texture::TexelImage;

/// Grows valid regions by `passes` texels: each pass fills every empty texel that has valid
/// 8-neighbours with their mean (edge neighbours weighted 2, corners 1). Returns the number of
/// texels filled.
pub fn dilate(image: &mut TexelImage, passes: u32) -> u64 {
    let (w, h) = (image.width as i64, image.height as i64);
    let mut filled = 0u64;
    for _ in 0..passes {
        let mut updates = Vec::new();
        for j in 0..h {
            for i in 0..w {
                let idx = (j * w + i) as usize;
                if image.valid[idx] {
                    continue;
                }
                let mut sum = Vec3::ZERO;
                let mut weight = 0.0f32;
                for dj in -1..=1i64 {
                    for di in -1..=1i64 {
                        if di == 0 && dj == 0 {
                            continue;
                        }
                        let (ni, nj) = (i + di, j + dj);
                        if ni < 0 || nj < 0 || ni >= w || nj >= h {
                            continue;
                        }
                        let n = (nj * w + ni) as usize;
                        if image.valid[n] {
                            let wgt = if di == 0 || dj == 0 { 2.0 } else { 1.0 };
                            sum += image.texels[n] * wgt;
                            weight += wgt;
                        }
                    }
                }
                if weight > 0.0 {
                    updates.push((idx, sum / weight));
                }
            }
        }
        if updates.is_empty() {
            break;
        }
        filled += updates.len() as u64;
        for (idx, value) in updates {
            image.texels[idx] = value;
            image.valid[idx] = true;
        }
    }
    filled
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fills_gutters_and_keeps_covered_texels() {
        let mut img = TexelImage::new(7, 7);
        // One valid texel in the middle with value 1, another at a corner with value 3.
        img.texels[3 * 7 + 3] = Vec3::ONE;
        img.valid[3 * 7 + 3] = true;
        img.texels[0] = Vec3::splat(3.0);
        img.valid[0] = true;
        let before = img.clone();
        let filled = dilate(&mut img, 1);
        // Covered texels unchanged.
        assert_eq!(img.texels[3 * 7 + 3], before.texels[3 * 7 + 3]);
        assert_eq!(img.texels[0], before.texels[0]);
        // The ring around the centre is filled with the centre's value.
        assert!(img.valid[2 * 7 + 2] && img.texels[2 * 7 + 4] == Vec3::ONE);
        // Two rings of width 1: 8 around the centre + 3 around the corner.
        assert_eq!(filled, 11);
        // Two more passes reach texels two rings out, none left out at distance ≤ 3.
        dilate(&mut img, 2);
        assert!(img.valid.iter().all(|&v| v));
    }
}
