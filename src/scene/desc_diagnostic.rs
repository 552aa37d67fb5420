//! Scene description of the grid, photon and BVH diagnostics' choices (`options.diagnostic:
//! Grid(space: World, size: 0.5)`, `Photon(quantity: Density, max: 1000)`, `Bvh(quantity:
//! Depth)`; see `docs/scene-format.md`, "Diagnostic modes").

use serde::{Deserialize, Serialize};

use crate::diagnostic::{BvhQuantity, GridSpace, PhotonQuantity};

/// `space:` of a grid diagnostic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "GridSpace", deny_unknown_fields)]
pub enum GridSpaceDesc {
    /// Each object's own coordinates.
    Object,
    /// World coordinates.
    World,
    /// The render camera's coordinates.
    Camera,
}

impl GridSpaceDesc {
    /// The engine's space.
    pub fn space(self) -> GridSpace {
        match self {
            Self::Object => GridSpace::Object,
            Self::World => GridSpace::World,
            Self::Camera => GridSpace::Camera,
        }
    }
}

/// `quantity:` of a photon diagnostic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "PhotonQuantity", deny_unknown_fields)]
pub enum PhotonQuantityDesc {
    /// Photons per unit area.
    Density,
    /// Irradiance, W/m².
    Irradiance,
}

impl PhotonQuantityDesc {
    /// The engine's quantity.
    pub fn quantity(self) -> PhotonQuantity {
        match self {
            Self::Density => PhotonQuantity::Density,
            Self::Irradiance => PhotonQuantity::Irradiance,
        }
    }
}

/// `quantity:` of a BVH diagnostic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename = "BvhQuantity", deny_unknown_fields)]
pub enum BvhQuantityDesc {
    /// The deepest tree level each pixel's ray entered.
    Depth,
    /// The triangles each pixel's ray tested.
    Size,
}

impl BvhQuantityDesc {
    /// The engine's quantity.
    pub fn quantity(self) -> BvhQuantity {
        match self {
            Self::Depth => BvhQuantity::Depth,
            Self::Size => BvhQuantity::Size,
        }
    }
}
