//! What the image writers take from the contours: the EXR contour layer's channels and the
//! PNG composite (contours over the beauty, or over a background colour).

use glam::Vec3;

use super::ContourImage;

/// EXR channel names of the contour layer (premultiplied RGBA).
pub const CHANNELS: [&str; 4] = ["contour.R", "contour.G", "contour.B", "contour.A"];

/// The contour layer as EXR channels, named [`CHANNELS`].
pub fn exr_channels(image: &ContourImage) -> Vec<(&'static str, Vec<f32>)> {
    (0..4)
        .map(|k| (CHANNELS[k], image.layer.iter().map(|c| c[k]).collect()))
        .collect()
}

/// The contour layer composited (premultiplied `over`, in linear light) over `beauty` and
/// its `alpha` in place, or, with `paper`, over that opaque colour alone.
pub fn composite(
    beauty: &mut [Vec3],
    alpha: &mut [f32],
    image: &ContourImage,
    paper: Option<Vec3>,
) {
    for (i, c) in image.layer.iter().enumerate() {
        let a = c.w;
        let (under, under_alpha) = match paper {
            Some(p) => (p, 1.0),
            None => (beauty[i], alpha[i]),
        };
        beauty[i] = c.truncate() + under * (1.0 - a);
        alpha[i] = a + under_alpha * (1.0 - a);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    #[test]
    fn composite_is_premultiplied_over() {
        let beauty = vec![Vec3::new(0.2, 0.4, 0.6), Vec3::ZERO];
        let alpha = vec![1.0, 0.0];
        let image = ContourImage {
            width: 2,
            height: 1,
            lines: Vec::new(),
            material_names: Vec::new(),
            layer: vec![Vec4::new(0.0, 0.0, 0.5, 0.5), Vec4::ZERO],
        };
        let (mut b, mut a) = (beauty.clone(), alpha.clone());
        composite(&mut b, &mut a, &image, None);
        assert_eq!(b[0], Vec3::new(0.1, 0.2, 0.8));
        assert_eq!(a[1], 0.0, "no line, no coverage");
        let (mut b, mut a) = (beauty, alpha);
        composite(&mut b, &mut a, &image, Some(Vec3::ONE));
        assert_eq!(b[1], Vec3::ONE);
        assert_eq!(b[0], Vec3::new(0.5, 0.5, 1.0));
        assert_eq!(a[0], 1.0);
    }
}
