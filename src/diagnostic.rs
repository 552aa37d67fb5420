//! Diagnostic modes (mental ray's `diagnostic samples on`, `diagnostic grid …`,
//! `diagnostic photon …`, `diagnostic bsp …`; RON `options.diagnostic`; CLI `render
//! --diagnostic samples`): the beauty pass replaced by a false-colour view of how the renderer
//! worked, for tuning a scene's options. The grid, photon and BVH views are drawn by
//! [`crate::diagnostic_view`].

use glam::Vec3;

/// One diagnostic view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Diagnostic {
    /// Samples per pixel: grey level `samples taken / most samples a pixel may take`, so
    /// where adaptive sampling refined shows bright (uniform sampling: every pixel 1).
    Samples,
    /// Coloured grid lines every `size` units of `space` on every surface (mental ray
    /// `diagnostic grid object|world|camera S`; see [`crate::diagnostic_view`]).
    Grid {
        /// The coordinates the lines follow.
        space: GridSpace,
        /// Distance between lines, units of `space` (> 0).
        size: f32,
    },
    /// Every material replaced by a false-colour view of the photon maps (mental ray
    /// `diagnostic photon density|irradiance N`), `max` showing red.
    Photon {
        /// What is shown.
        quantity: PhotonQuantity,
        /// The value shown at the top of the colour scale (> 0).
        max: f32,
    },
    /// What the pixel-centre camera ray cost the ray-tracing hierarchy (mental ray
    /// `diagnostic bsp depth|size`, for its BSP tree), on the false-colour scale.
    Bvh {
        /// What is shown.
        quantity: BvhQuantity,
        /// The value shown red; `None`: the tree's depth (`Depth`) or the image's largest
        /// count (`Size`).
        max: Option<u32>,
    },
}

/// What a BVH diagnostic shows per pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BvhQuantity {
    /// The deepest tree level the ray entered (the root's children are level 1).
    Depth,
    /// The triangles the ray tested in the leaves it entered.
    Size,
}

/// The coordinates a grid diagnostic follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GridSpace {
    /// Each object's own coordinates.
    Object,
    /// World coordinates.
    World,
    /// The render camera's coordinates.
    Camera,
}

/// What a photon diagnostic shows at each surface point seen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhotonQuantity {
    /// Photons per unit area (both maps' density estimates, photon counts instead of powers).
    Density,
    /// Irradiance, W/m² (both maps' density estimates).
    Irradiance,
}

impl Diagnostic {
    /// Parses a diagnostic's command-line form: `samples`, `grid:SPACE:SIZE` (`SPACE` one of
    /// `object`, `world`, `camera`), `photon:density|irradiance:MAX`, `bvh:depth|size[:MAX]`.
    pub fn parse(text: &str) -> Result<Self, String> {
        let text = text.trim();
        let parts: Vec<&str> = text.split(':').collect();
        let positive = |what: &str, v: &str| -> Result<f32, String> {
            match v.parse::<f32>() {
                Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
                _ => Err(format!("the {what} must be a number > 0, found \"{v}\"")),
            }
        };
        match parts.as_slice() {
            ["samples"] => Ok(Self::Samples),
            ["grid", space, size] => {
                let space = match *space {
                    "object" => GridSpace::Object,
                    "world" => GridSpace::World,
                    "camera" => GridSpace::Camera,
                    other => {
                        return Err(format!(
                            "unknown grid space \"{other}\" (expected object, world or camera)"
                        ))
                    }
                };
                let size = positive("grid size", size)?;
                Ok(Self::Grid { space, size })
            }
            ["photon", quantity, max] => {
                let quantity = match *quantity {
                    "density" => PhotonQuantity::Density,
                    "irradiance" => PhotonQuantity::Irradiance,
                    other => {
                        return Err(format!(
                            "unknown photon diagnostic \"{other}\" (expected density or irradiance)"
                        ))
                    }
                };
                let max = positive("photon diagnostic maximum", max)?;
                Ok(Self::Photon { quantity, max })
            }
            ["bvh", quantity, max @ ..] if max.len() <= 1 => {
                let quantity = match *quantity {
                    "depth" => BvhQuantity::Depth,
                    "size" => BvhQuantity::Size,
                    other => {
                        return Err(format!(
                            "unknown bvh diagnostic \"{other}\" (expected depth or size)"
                        ))
                    }
                };
                let max = match max.first() {
                    None => None,
                    Some(m) => match m.parse::<u32>() {
                        Ok(x) if x > 0 => Some(x),
                        _ => {
                            return Err(format!(
                            "the bvh diagnostic maximum must be a whole number > 0, found \"{m}\""
                        ))
                        }
                    },
                };
                Ok(Self::Bvh { quantity, max })
            }
            _ => Err(format!(
                "unknown diagnostic \"{text}\" (expected samples, grid:SPACE:SIZE, \
                 photon:density|irradiance:MAX or bvh:depth|size[:MAX])"
            )),
        }
    }

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Samples => "samples",
            Self::Grid { .. } => "grid",
            Self::Photon { .. } => "photon",
            Self::Bvh { .. } => "bvh",
        }
    }
}

/// The samples view of per-pixel sample counts: `taken / max` in every channel (`max` ≥ 1).
pub fn samples_view(samples: &[u32], max: u32) -> Vec<Vec3> {
    let max = max.max(1) as f32;
    samples
        .iter()
        .map(|&n| Vec3::splat(n as f32 / max))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_scaled_to_the_most_a_pixel_may_take() {
        assert_eq!(
            samples_view(&[4, 16, 8], 16),
            [Vec3::splat(0.25), Vec3::ONE, Vec3::splat(0.5)]
        );
        assert_eq!(Diagnostic::parse("samples"), Ok(Diagnostic::Samples));
        assert_eq!(
            Diagnostic::parse("grid"),
            Err(
                "unknown diagnostic \"grid\" (expected samples, grid:SPACE:SIZE, \
                 photon:density|irradiance:MAX or bvh:depth|size[:MAX])"
                    .into()
            )
        );
        assert_eq!(
            Diagnostic::parse("grid:world:0.5"),
            Ok(Diagnostic::Grid {
                space: GridSpace::World,
                size: 0.5
            })
        );
        assert_eq!(
            Diagnostic::parse("photon:irradiance:20"),
            Ok(Diagnostic::Photon {
                quantity: PhotonQuantity::Irradiance,
                max: 20.0
            })
        );
        assert_eq!(
            Diagnostic::parse("grid:world:0"),
            Err("the grid size must be a number > 0, found \"0\"".into())
        );
        assert_eq!(
            Diagnostic::parse("bvh:depth"),
            Ok(Diagnostic::Bvh {
                quantity: BvhQuantity::Depth,
                max: None
            })
        );
        assert_eq!(
            Diagnostic::parse("bvh:size:40"),
            Ok(Diagnostic::Bvh {
                quantity: BvhQuantity::Size,
                max: Some(40)
            })
        );
        assert_eq!(
            Diagnostic::parse("bvh:size:0"),
            Err("the bvh diagnostic maximum must be a whole number > 0, found \"0\"".into())
        );
        assert_eq!(
            Diagnostic::parse("bvh:leaves"),
            Err("unknown bvh diagnostic \"leaves\" (expected depth or size)".into())
        );
        assert_eq!(
            Diagnostic::parse("grid:screen:1"),
            Err("unknown grid space \"screen\" (expected object, world or camera)".into())
        );
    }
}
