//! The geometry error type: bad parameters of geometry shaders, surfaces, approximations and
//! displacement. The scene loader and the geometry stages surface these to the user.

use std::fmt;

/// Why a piece of geometry cannot be generated or tessellated.
#[derive(Debug, Clone, PartialEq)]
pub enum GeometryError {
    /// A parameter is NaN or infinite.
    NotFinite {
        /// Parameter name as in the scene file (`"radius"`).
        parameter: &'static str,
    },
    /// A parameter lies outside its valid range.
    OutOfRange {
        /// Parameter name as in the scene file.
        parameter: &'static str,
        /// The value given.
        value: f64,
        /// The valid range, in words (`"> 0"`, `"(0, 360]"`).
        expected: &'static str,
    },
    /// Array sizes do not agree (control points, knots, face indices).
    BadCount {
        /// What is wrong, e.g. `"points: expected 16 (nu × nv), found 12"`.
        message: String,
    },
    /// A raster-space approximation needs a render camera and the scene has none.
    NoCamera,
    /// A referenced entity lacks what it must carry (e.g. a scatter surface without a mesh).
    MissingData {
        /// What is missing.
        message: String,
    },
    /// The approximation's rates ask for more triangles than the memory budget allows
    /// (found before dicing).
    TooManyTriangles {
        /// Triangles the rates give.
        triangles: u64,
        /// The most the budget allows.
        limit: u64,
    },
}

impl fmt::Display for GeometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GeometryError::NotFinite { parameter } => {
                write!(f, "parameter `{parameter}` is not a finite number")
            }
            GeometryError::OutOfRange {
                parameter,
                value,
                expected,
            } => write!(f, "parameter `{parameter}` = {value} is out of range (expected {expected})"),
            GeometryError::BadCount { message } => f.write_str(message),
            GeometryError::NoCamera => f.write_str(
                "the approximation measures edges in raster pixels but the scene has no render camera",
            ),
            GeometryError::MissingData { message } => f.write_str(message),
            GeometryError::TooManyTriangles { triangles, limit } => write!(
                f,
                "its approximation would make {triangles} triangles, more than the {limit} the memory budget allows (coarsen the approximation, or raise --memory-limit)"
            ),
        }
    }
}

impl std::error::Error for GeometryError {}

/// `value` as the shortest decimal that reads back as it (`0.3`, not `0.30000001192092896`):
/// the number as the scene wrote it, for messages.
pub(crate) fn as_written(value: f32) -> f64 {
    value.to_string().parse().unwrap_or(value as f64)
}

/// Checks that `value` is finite.
pub(crate) fn finite(parameter: &'static str, value: f32) -> Result<f64, GeometryError> {
    if value.is_finite() {
        Ok(value as f64)
    } else {
        Err(GeometryError::NotFinite { parameter })
    }
}

/// Checks that `value` is finite and > 0.
pub(crate) fn positive(parameter: &'static str, value: f32) -> Result<f64, GeometryError> {
    let v = finite(parameter, value)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(GeometryError::OutOfRange {
            parameter,
            value: as_written(value),
            expected: "> 0",
        })
    }
}

/// Checks a sweep angle in degrees: finite, in (0, 360]. Returns radians.
pub(crate) fn sweep(parameter: &'static str, degrees: f32) -> Result<f64, GeometryError> {
    let v = finite(parameter, degrees)?;
    if v > 0.0 && v <= 360.0 {
        Ok(v.to_radians())
    } else {
        Err(GeometryError::OutOfRange {
            parameter,
            value: as_written(degrees),
            expected: "(0, 360] degrees",
        })
    }
}
