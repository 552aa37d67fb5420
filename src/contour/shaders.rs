//! Contour shaders: the colour and width of a line point from the material's
//! [`ContourShader`] and the crossing under it (formulas on each variant).

use glam::{Vec3, Vec4};

use super::contrast::Crossing;
use super::linking::Chain;
use super::{ContourLine, ContourPoint};
use crate::components::ContourShader;

/// Rec. 709 luminance weights.
const LUMINANCE: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// Colour (linear RGBA, straight alpha) and width (pixels) of the line at `c` drawn by
/// `shader`, in an image whose smaller dimension is `min_dimension` pixels; `level`: the
/// ray level of the crossing's samples (the layers in front, see `ContourStore::level`).
/// Width 0: no line here (a silhouette shader away from the outline).
pub fn style(shader: &ContourShader, c: &Crossing, min_dimension: f32, level: u32) -> (Vec4, f32) {
    let (color, percent) = match *shader {
        ContourShader::Simple { color, width } => (color, width),
        ContourShader::Silhouette { color, width } => {
            (color, if c.is_outline() { width } else { 0.0 })
        }
        ContourShader::DepthFade {
            near,
            far,
            near_color,
            far_color,
            near_width,
            far_width,
        } => {
            let t = ((c.front.depth - near) / (far - near)).clamp(0.0, 1.0);
            (
                near_color.lerp(far_color, t),
                near_width + (far_width - near_width) * t,
            )
        }
        ContourShader::Curvature {
            color,
            min_width,
            max_width,
        } => {
            let angle = if c.is_outline() {
                std::f32::consts::PI
            } else {
                c.front.normal.dot(c.back.normal).clamp(-1.0, 1.0).acos()
            };
            (
                color,
                min_width + (max_width - min_width) * angle / std::f32::consts::PI,
            )
        }
        ContourShader::FactorColor { factor, width } => {
            ((c.front.color * factor).extend(1.0), width)
        }
        ContourShader::WidthFromLight {
            color,
            dark_width,
            lit_width,
        } => {
            let light = c.front.color.dot(LUMINANCE).clamp(0.0, 1.0);
            (color, dark_width + (lit_width - dark_width) * light)
        }
        ContourShader::Layered {
            color,
            width,
            thinning,
        } => (
            color,
            width * thinning.powi(level.min(i32::MAX as u32) as i32),
        ),
    };
    (color, percent * 0.01 * min_dimension)
}

/// Styles every chain of ray level `level` with the contour shader of its material
/// (`shaders[material − 1]`; chains of materials without one were never linked, and are
/// dropped if met). Points the shader gives no width break their chain: the runs of at
/// least two drawn points between them become the lines.
pub fn styled_lines(
    chains: Vec<Chain>,
    shaders: &[Option<ContourShader>],
    min_dimension: f32,
    level: u32,
) -> Vec<ContourLine> {
    let mut lines = Vec::new();
    for chain in chains {
        let Some(shader) = chain
            .material
            .checked_sub(1)
            .and_then(|m| shaders.get(m as usize))
            .and_then(Option::as_ref)
        else {
            continue;
        };
        let points: Vec<Option<ContourPoint>> = chain
            .points
            .iter()
            .map(|p| {
                let (color, width) = style(shader, &p.crossing, min_dimension, level);
                (width > 0.0).then_some(ContourPoint {
                    pos: p.pos,
                    color,
                    width,
                })
            })
            .collect();
        if points.iter().all(Option::is_some) {
            lines.push(ContourLine {
                material: chain.material,
                closed: chain.closed,
                points: points.into_iter().flatten().collect(),
            });
            continue;
        }
        for run in points.split(Option::is_none) {
            if run.len() >= 2 {
                lines.push(ContourLine {
                    material: chain.material,
                    closed: false,
                    points: run.iter().flatten().copied().collect(),
                });
            }
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contour::store::ContourSample;
    use glam::Vec2;

    fn crossing(depth: f32, color: Vec3, back_normal: Vec3) -> Crossing {
        let front = ContourSample {
            instance: 1,
            object: 1,
            material: 1,
            normal: Vec3::Z,
            depth,
            color,
        };
        Crossing {
            pos: Vec2::ZERO,
            front,
            back: ContourSample {
                normal: back_normal,
                depth: depth + 1.0,
                ..front
            },
        }
    }

    #[test]
    fn each_shader_follows_its_formula() {
        let black = Vec4::new(0.0, 0.0, 0.0, 1.0);
        let white = Vec4::ONE;
        let c = crossing(3.0, Vec3::new(0.5, 0.5, 0.5), Vec3::X);
        let simple = ContourShader::Simple {
            color: black,
            width: 1.0,
        };
        assert_eq!(style(&simple, &c, 300.0, 0), (black, 3.0), "1 % of 300 px");
        let fade = ContourShader::DepthFade {
            near: 2.0,
            far: 6.0,
            near_color: black,
            far_color: white,
            near_width: 2.0,
            far_width: 0.0,
        };
        let (col, w) = style(&fade, &c, 100.0, 0);
        assert!((col - Vec4::new(0.25, 0.25, 0.25, 1.0)).abs().max_element() < 1e-6);
        assert!((w - 1.5).abs() < 1e-6);
        let curv = ContourShader::Curvature {
            color: black,
            min_width: 0.0,
            max_width: 2.0,
        };
        assert!(
            (style(&curv, &c, 100.0, 0).1 - 1.0).abs() < 1e-5,
            "90° is half"
        );
        let factor = ContourShader::FactorColor {
            factor: 0.5,
            width: 1.0,
        };
        assert_eq!(
            style(&factor, &c, 100.0, 0).0,
            Vec4::new(0.25, 0.25, 0.25, 1.0)
        );
        let light = ContourShader::WidthFromLight {
            color: black,
            dark_width: 2.0,
            lit_width: 1.0,
        };
        assert!(
            (style(&light, &c, 100.0, 0).1 - 1.5).abs() < 1e-5,
            "L = 0.5"
        );
        let layered = ContourShader::Layered {
            color: black,
            width: 2.0,
            thinning: 0.5,
        };
        for (level, width) in [(0, 2.0), (1, 1.0), (3, 0.25)] {
            assert_eq!(
                style(&layered, &c, 100.0, level),
                (black, width),
                "2·0.5^{level}"
            );
        }
    }

    /// Another placed copy of the same object behind the edge is another object to the
    /// outline shaders: a silhouette line, and the curvature shader's widest.
    #[test]
    fn another_instance_of_the_same_object_is_an_outline() {
        let black = Vec4::new(0.0, 0.0, 0.0, 1.0);
        let mut copy = crossing(3.0, Vec3::ONE, Vec3::Z);
        copy.back.instance = 2;
        assert_eq!(copy.back.object, copy.front.object);
        let silhouette = ContourShader::Silhouette {
            color: black,
            width: 1.0,
        };
        assert_eq!(style(&silhouette, &copy, 100.0, 0), (black, 1.0));
        let curvature = ContourShader::Curvature {
            color: black,
            min_width: 0.0,
            max_width: 2.0,
        };
        assert_eq!(style(&curvature, &copy, 100.0, 0), (black, 2.0), "180°");
    }

    #[test]
    fn a_silhouette_shader_draws_only_the_outline_and_splits_its_chains() {
        use super::super::linking::{Chain, ChainPoint};
        let black = Vec4::new(0.0, 0.0, 0.0, 1.0);
        let shader = ContourShader::Silhouette {
            color: black,
            width: 1.0,
        };
        let inside = crossing(3.0, Vec3::ONE, Vec3::X);
        let mut outline = inside;
        outline.back.instance = 2;
        outline.back.object = 2;
        assert_eq!(style(&shader, &inside, 100.0, 0).1, 0.0, "a crease");
        assert_eq!(style(&shader, &outline, 100.0, 0), (black, 1.0));
        // outline, outline, crease, outline, outline, outline: two lines.
        let kinds = [true, true, false, true, true, true];
        let chain = Chain {
            material: 1,
            closed: true,
            points: kinds
                .iter()
                .enumerate()
                .map(|(k, &o)| ChainPoint {
                    pos: Vec2::new(k as f32, 0.0),
                    crossing: if o { outline } else { inside },
                })
                .collect(),
        };
        let lines = styled_lines(vec![chain], &[Some(shader)], 100.0, 0);
        let xs: Vec<Vec<f32>> = lines
            .iter()
            .map(|l| l.points.iter().map(|p| p.pos.x).collect())
            .collect();
        assert_eq!(xs, [vec![0.0, 1.0], vec![3.0, 4.0, 5.0]]);
        assert!(lines.iter().all(|l| !l.closed));
    }
}
