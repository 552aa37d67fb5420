//! The sweep's crop: a pixel rectangle (e.g. a caustic) whose error is fitted and plotted
//! instead of the whole image's, parsed from `--crop X0,Y0,X1,Y1` and cut out of images.

use glam::Vec3;
use serde::Serialize;

/// Pixels `[x0, x1) × [y0, y1)` of an image (row 0 at the top, as in the EXR).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Crop {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl Crop {
    /// Parses `X0,Y0,X1,Y1` (four whole numbers, `X0 < X1`, `Y0 < Y1`); the error says what
    /// was expected.
    pub fn parse(text: &str) -> Result<Self, String> {
        let numbers: Vec<u32> = text
            .split(',')
            .map(|v| v.trim().parse::<u32>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("expected four whole numbers X0,Y0,X1,Y1, found \"{text}\""))?;
        let [x0, y0, x1, y1] = numbers[..] else {
            return Err(format!(
                "expected four whole numbers X0,Y0,X1,Y1, found {} in \"{text}\"",
                numbers.len()
            ));
        };
        if x0 >= x1 || y0 >= y1 {
            return Err(format!(
                "the crop {text} is empty: it needs X0 < X1 and Y0 < Y1 (pixels [X0, X1) × [Y0, Y1))"
            ));
        }
        Ok(Self { x0, y0, x1, y1 })
    }

    /// Whether the crop lies inside a `width × height` image.
    pub fn fits(&self, width: u32, height: u32) -> bool {
        self.x1 <= width && self.y1 <= height
    }

    /// The crop's pixels of a `width`-wide image, row by row (the crop must fit).
    pub fn cut(&self, image: &[Vec3], width: u32) -> Vec<Vec3> {
        let w = width as usize;
        (self.y0 as usize..self.y1 as usize)
            .flat_map(|y| image[y * w + self.x0 as usize..y * w + self.x1 as usize].iter())
            .copied()
            .collect()
    }
}

impl std::fmt::Display for Crop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{},{},{},{}", self.x0, self.y0, self.x1, self.y1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_refuses_with_the_reason() {
        let c = Crop::parse("71, 50,92,62").unwrap();
        assert_eq!((c.x0, c.y0, c.x1, c.y1), (71, 50, 92, 62));
        assert_eq!(c.to_string(), "71,50,92,62");
        assert_eq!(
            Crop::parse("1,2,3").unwrap_err(),
            "expected four whole numbers X0,Y0,X1,Y1, found 3 in \"1,2,3\""
        );
        assert_eq!(
            Crop::parse("1,2,x,4").unwrap_err(),
            "expected four whole numbers X0,Y0,X1,Y1, found \"1,2,x,4\""
        );
        assert!(Crop::parse("5,2,5,4").unwrap_err().contains("is empty"));
        assert!(c.fits(92, 62) && !c.fits(91, 62) && !c.fits(92, 61));
    }

    #[test]
    fn cuts_the_rectangle_row_by_row() {
        // A 4 × 3 image whose pixel (x, y) holds x + 10 y.
        let image: Vec<Vec3> = (0..12)
            .map(|i| Vec3::splat((i % 4 + 10 * (i / 4)) as f32))
            .collect();
        let c = Crop::parse("1,1,3,3").unwrap();
        let values: Vec<f32> = c.cut(&image, 4).iter().map(|p| p.x).collect();
        assert_eq!(values, [11.0, 12.0, 21.0, 22.0]);
    }
}
