//! Displacement: scalar nodes evaluated at surface points (their noise is [`crate::noise`]).

use glam::{DVec2, DVec3};

use super::{finite, GeometryError, SurfaceSample};
use crate::components::{Displacement, ImageMap, ScalarNode, UvAxis};
use crate::noise::{mix, perlin, PERLIN_BOUND};

/// A validated displacement, ready to move points.
#[derive(Debug, Clone)]
pub struct Displacer<'a> {
    node: &'a ScalarNode,
    bound: f64,
}

impl<'a> Displacer<'a> {
    /// Validates the shader (finite parameters, image sizes) and fixes the bound.
    pub fn new(d: &'a Displacement) -> Result<Self, GeometryError> {
        validate(&d.shader)?;
        let bound = match d.bound {
            Some(b) => {
                let b = finite("bound", b)?;
                if b < 0.0 {
                    return Err(GeometryError::OutOfRange {
                        parameter: "bound",
                        value: b,
                        expected: "≥ 0",
                    });
                }
                b
            }
            None => node_bound(&d.shader),
        };
        Ok(Self {
            node: &d.shader,
            bound,
        })
    }

    /// The displacement bound (object units).
    pub fn bound(&self) -> f64 {
        self.bound
    }

    /// The displacement amount at a surface point, clamped to ±bound.
    pub fn amount(&self, p: DVec3, uv: DVec2) -> f64 {
        let d = eval(self.node, p, uv);
        if d.is_finite() {
            d.clamp(-self.bound, self.bound)
        } else {
            0.0
        }
    }

    /// The point `s.p` moved along the unit direction `n` by the amount at `s`.
    pub fn displace(&self, s: &SurfaceSample, n: DVec3) -> DVec3 {
        s.p + n * self.amount(s.p, s.uv)
    }
}

/// Checks every parameter of a node tree.
pub fn validate(node: &ScalarNode) -> Result<(), GeometryError> {
    match node {
        ScalarNode::Constant(c) => finite("constant", *c).map(drop),
        ScalarNode::Sine {
            amplitude, factor, ..
        } => {
            finite("amplitude", *amplitude)?;
            finite("factor", *factor).map(drop)
        }
        ScalarNode::Noise {
            amplitude,
            frequency,
            lacunarity,
            gain,
            ..
        } => {
            finite("amplitude", *amplitude)?;
            finite("frequency", *frequency)?;
            finite("lacunarity", *lacunarity)?;
            finite("gain", *gain).map(drop)
        }
        ScalarNode::Image(img) => {
            finite("scale", img.scale)?;
            finite("offset", img.offset)?;
            let expected = img.width as u64 * img.height as u64;
            if img.width == 0 || img.height == 0 || img.texels.len() as u64 != expected {
                return Err(GeometryError::BadCount {
                    message: format!(
                        "image map: expected {}×{} = {expected} texels, found {}",
                        img.width,
                        img.height,
                        img.texels.len()
                    ),
                });
            }
            Ok(())
        }
        ScalarNode::Sum(xs) | ScalarNode::Product(xs) => xs.iter().try_for_each(validate),
    }
}

/// A conservative bound of |node| over all inputs.
pub fn node_bound(node: &ScalarNode) -> f64 {
    match node {
        ScalarNode::Constant(c) => c.abs() as f64,
        ScalarNode::Sine { amplitude, .. } => amplitude.abs() as f64,
        ScalarNode::Noise {
            amplitude,
            octaves,
            gain,
            ..
        } => {
            let g = gain.abs() as f64;
            let sum: f64 = (0..(*octaves).clamp(1, 12)).map(|i| g.powi(i as i32)).sum();
            amplitude.abs() as f64 * sum * PERLIN_BOUND
        }
        ScalarNode::Image(img) => {
            let m = img.texels.iter().fold(0f32, |a, t| a.max(t.abs()));
            (m * img.scale.abs() + img.offset.abs()) as f64
        }
        ScalarNode::Sum(xs) => xs.iter().map(node_bound).sum(),
        ScalarNode::Product(xs) => xs.iter().map(node_bound).product(),
    }
}

/// Evaluates a node at object-space point `p` with texture coordinates `uv`.
pub fn eval(node: &ScalarNode, p: DVec3, uv: DVec2) -> f64 {
    match node {
        ScalarNode::Constant(c) => *c as f64,
        ScalarNode::Sine {
            amplitude,
            factor,
            axis,
        } => {
            let s = if *axis == UvAxis::U { uv.x } else { uv.y };
            *amplitude as f64 * (s * *factor as f64 * std::f64::consts::PI).sin()
        }
        ScalarNode::Noise {
            amplitude,
            frequency,
            octaves,
            lacunarity,
            gain,
            seed,
        } => {
            let mut sum = 0.0;
            let mut f = *frequency as f64;
            let mut a = 1.0;
            for i in 0..(*octaves).clamp(1, 12) {
                let o = octave_offset(*seed, i);
                sum += a * perlin(p * f + o, *seed ^ i as u64);
                f *= *lacunarity as f64;
                a *= *gain as f64;
            }
            *amplitude as f64 * sum
        }
        ScalarNode::Image(img) => sample_image(img, uv),
        ScalarNode::Sum(xs) => xs.iter().map(|x| eval(x, p, uv)).sum(),
        ScalarNode::Product(xs) => xs.iter().map(|x| eval(x, p, uv)).product(),
    }
}

/// Bilinear, repeat-wrapped lookup of an image map.
fn sample_image(img: &ImageMap, uv: DVec2) -> f64 {
    let (w, h) = (img.width as i64, img.height as i64);
    if w == 0 || h == 0 || img.texels.len() as i64 != w * h {
        return 0.0;
    }
    let x = uv.x * w as f64 - 0.5;
    let y = uv.y * h as f64 - 0.5;
    if !x.is_finite() || !y.is_finite() {
        return 0.0;
    }
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |xi: i64, yi: i64| {
        let (xi, yi) = (xi.rem_euclid(w), yi.rem_euclid(h));
        img.texels[(yi * w + xi) as usize] as f64
    };
    let (x0, y0) = (x0 as i64, y0 as i64);
    let top = texel(x0, y0) * (1.0 - fx) + texel(x0 + 1, y0) * fx;
    let bottom = texel(x0, y0 + 1) * (1.0 - fx) + texel(x0 + 1, y0 + 1) * fx;
    let v = top * (1.0 - fy) + bottom * fy;
    v * img.scale as f64 + img.offset as f64
}

/// Per-octave domain offset so octaves do not line up at the origin.
fn octave_offset(seed: u64, octave: u32) -> DVec3 {
    let h = mix(seed ^ (0x9e37_79b9_7f4a_7c15u64.wrapping_mul(octave as u64 + 1)));
    let f = |s: u32| ((h >> s) & 0xffff) as f64 / 65536.0 * 256.0;
    DVec3::new(f(0), f(16), f(32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_sine_pattern_and_bound() {
        let node = ScalarNode::Sine {
            amplitude: 0.01,
            factor: 50.0,
            axis: UvAxis::U,
        };
        let v = eval(&node, DVec3::ZERO, DVec2::new(0.01, 0.0));
        assert!((v - 0.01).abs() < 1e-9);
        assert!((node_bound(&node) - 0.01).abs() < 1e-9);
        let d = Displacement {
            shader: ScalarNode::Constant(2.0),
            bound: Some(0.5),
            mode: crate::components::DisplacementMode::True,
        };
        assert_eq!(
            Displacer::new(&d).unwrap().amount(DVec3::ZERO, DVec2::ZERO),
            0.5
        );
    }

    #[test]
    fn image_map_is_bilinear_and_validated() {
        let img = ImageMap {
            width: 2,
            height: 1,
            texels: std::sync::Arc::new(vec![0.0, 1.0]),
            scale: 2.0,
            offset: -1.0,
        };
        let v = sample_image(&img, DVec2::new(0.5, 0.5));
        assert!((v - 0.0).abs() < 1e-12); // halfway between texels: 0.5·2 − 1
        let bad = ScalarNode::Image(ImageMap {
            texels: std::sync::Arc::new(vec![0.0]),
            ..img
        });
        assert!(validate(&bad).is_err());
    }
}
