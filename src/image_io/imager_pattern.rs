//! Painting an imager's [`ImagerPattern`] (the seed tutorial's `myImager`): the display
//! colour of a pixel from its raster position alone.
//!
//! RenderMan's imager sees `P` as the pixel's raster position; pixel values are the filtered
//! image sampled at the pixel centres (RISpec 3.2, §4.1.2 *Displays*), so `P` is taken at the
//! centre `(x + ½, y + ½)` of the pixel in column `x` and row `y` (row 0 at the top): the
//! pattern is then symmetric about the image centre as the RSL's is, where the corner
//! `(x, y)` would shift it by half a pixel toward the top left.

use glam::{Vec2, Vec3};

use crate::components::ImagerPattern;

impl ImagerPattern {
    /// The display colour of the pixel in column `x`, row `y` of a `width` × `height` image.
    pub fn paint(&self, x: u32, y: u32, width: u32, height: u32) -> Vec3 {
        let here = Vec2::new(
            (x as f32 + 0.5) / width.max(1) as f32,
            (y as f32 + 0.5) / height.max(1) as f32,
        );
        match *self {
            ImagerPattern::Disk {
                center,
                radius,
                fuzz,
                inside,
                outside,
            } => crate::pattern::mix(
                outside,
                inside,
                crate::pattern::disk(here, center, radius, fuzz),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DISK: ImagerPattern = ImagerPattern::Disk {
        center: Vec2::new(0.5, 0.5),
        radius: 0.4,
        fuzz: 0.1,
        inside: Vec3::new(1.0, 1.0, 0.0),
        outside: Vec3::new(1.0, 0.0, 0.0),
    };

    #[test]
    fn the_disk_is_inside_at_the_centre_outside_at_the_corners_and_blends_between() {
        // 10 × 10: pixel (4, 4) has its centre at (0.45, 0.45), 0.07 from the disk's centre.
        assert_eq!(DISK.paint(4, 4, 10, 10), Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(DISK.paint(0, 0, 10, 10), Vec3::new(1.0, 0.0, 0.0));
        // Pixel (9, 5): centre (0.95, 0.55), distance √(0.45² + 0.05²) in the fuzz band.
        let d = (0.45f32 * 0.45 + 0.05 * 0.05).sqrt();
        let t = (d - 0.3) / 0.2;
        let g = 1.0 - t * t * (3.0 - 2.0 * t);
        let c = DISK.paint(9, 5, 10, 10);
        assert!(
            (c - Vec3::new(1.0, g, 0.0)).abs().max_element() < 1e-6,
            "{c}"
        );
        assert!(g > 0.0 && g < 1.0);
    }
}
