//! RON types of the camera's lens and volume shaders, material interiors, and the
//! `samples` option (a count, or adaptive `(min, max, contrast)`), as written by the user.

use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::desc_values::V3;

/// A lens shader in a camera's `lens: [...]` list.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Lens", deny_unknown_fields)]
pub enum LensDesc {
    /// Thin-lens depth of field; exactly one of `radius` and `fstop`.
    ThinLens {
        /// Aperture radius, metres.
        #[serde(default)]
        radius: Option<f64>,
        /// f-number: aperture diameter = focal length / fstop, the focal length being that of
        /// a 36 × 24 mm film with the camera's `fov_y` (12 mm / tan(fov_y / 2)).
        #[serde(default)]
        fstop: Option<f64>,
        /// Distance to the plane in focus, metres.
        focus_distance: f64,
    },
    /// Equidistant fisheye with `fov` degrees across the image height, in (0, 360].
    Fisheye {
        /// Full field of view, degrees.
        fov: f64,
    },
    /// Lat-long 360° × 180° projection.
    Spherical,
    /// Off-axis pinhole (RenderMan's off-centre `ScreenWindow`): the image window moved by
    /// `(x, y)` half-heights of the image plane, +x right, +y up; must be the first lens.
    Shift {
        /// Horizontal shift, half-heights.
        x: f64,
        /// Vertical shift, half-heights.
        y: f64,
    },
}

/// A volume shader (`atmosphere` on a camera, `interior` on a material).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(rename = "Volume", deny_unknown_fields)]
pub enum VolumeDesc {
    /// Fog: homogeneous, or bounded by a height, or with a noise-varied density.
    Fog {
        /// Absorption coefficient per channel, 1/m, default `(0, 0, 0)`.
        #[serde(default)]
        sigma_a: V3,
        /// Scattering coefficient per channel, 1/m, default `(0, 0, 0)`.
        #[serde(default)]
        sigma_s: V3,
        /// Henyey–Greenstein asymmetry in (−1, 1), default 0 (isotropic).
        #[serde(default)]
        g: f64,
        /// Fog only below this world y, default none (everywhere).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        height: Option<f64>,
        /// How much a 3D noise varies the density about 1, in [0, 1], default 0 (uniform).
        #[serde(default, skip_serializing_if = "is_zero")]
        nonuniform: f64,
        /// Feature size of that noise, scene units (> 0), default 1.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        noise_scale: f64,
    },
    /// A fade of the radiance toward `color` over `max`, linear (mental ray's `mib_volume`)
    /// or exponential (RenderMan's `fog`); camera `atmosphere` only.
    Fade {
        /// The colour every camera-side segment fades to.
        color: V3,
        /// Largest blend weight, in [0, 1], default 1.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        opacity: f64,
        /// `Linear`: distance of the complete fade; `Exponential`: the distance over which
        /// the radiance keeps 1/e; scene units (≥ 0; 0: the full `opacity` at once).
        max: f64,
        /// How the blend weight grows with distance, default `Linear`.
        #[serde(default, skip_serializing_if = "FalloffDesc::is_linear")]
        falloff: FalloffDesc,
    },
}

/// How a `Fade` grows with the length `l` of a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename = "Falloff")]
pub enum FalloffDesc {
    /// `opacity · min(l / max, 1)` (mental ray's `mib_volume`).
    #[default]
    Linear,
    /// `opacity · (1 − e^(−l / max))` (RenderMan's standard `fog`).
    Exponential,
}

impl FalloffDesc {
    fn is_linear(&self) -> bool {
        *self == FalloffDesc::Linear
    }
}

fn one() -> f64 {
    1.0
}

fn is_one(x: &f64) -> bool {
    *x == 1.0
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// `samples:` in the options: a fixed count per pixel, or adaptive sampling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SamplesDesc {
    /// `samples: 16`.
    Fixed(u64),
    /// `samples: (min: 4, max: 64, contrast: (0.05, 0.05, 0.05))`.
    Adaptive {
        /// Samples every pixel takes, at least 1.
        min: u64,
        /// Most samples a pixel takes, at least `min`.
        max: u64,
        /// Per-channel threshold on the standard error of the pixel mean, default 0.1 each.
        contrast: V3,
    },
}

impl Default for SamplesDesc {
    fn default() -> Self {
        SamplesDesc::Fixed(4)
    }
}

/// Written back as the loader reads it: a bare count, or `(min: …, max: …, contrast: …)`.
impl Serialize for SamplesDesc {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match *self {
            SamplesDesc::Fixed(n) => s.serialize_u64(n),
            SamplesDesc::Adaptive { min, max, contrast } => {
                // Named, so RON written with struct names (`stagelight convert`) stays valid; the
                // name is optional on reading.
                let mut st = s.serialize_struct("Adaptive", 3)?;
                st.serialize_field("min", &min)?;
                st.serialize_field("max", &max)?;
                st.serialize_field("contrast", &contrast)?;
                st.end()
            }
        }
    }
}

/// The fields of adaptive `samples`, as `ron`'s unknown-field error lists them.
pub const ADAPTIVE_FIELDS: &[&str] = &["min", "max", "contrast"];

/// How messages name adaptive `samples`. `ron` names an unknown or missing field after the
/// nearest named struct (here `Options`), so the reader renames errors from this visitor.
pub const ADAPTIVE_NAME: &str = "adaptive samples";

impl<'de> Deserialize<'de> for SamplesDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(SamplesVisitor)
    }
}

struct SamplesVisitor;

impl<'de> Visitor<'de> for SamplesVisitor {
    type Value = SamplesDesc;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a sample count or `(min: N, max: N, contrast: (r, g, b))`")
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<SamplesDesc, E> {
        Ok(SamplesDesc::Fixed(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<SamplesDesc, E> {
        u64::try_from(v)
            .map(SamplesDesc::Fixed)
            .map_err(|_| E::invalid_value(de::Unexpected::Signed(v), &self))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<SamplesDesc, A::Error> {
        let (mut min, mut max, mut contrast) = (None, None, None);
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "min" if min.is_none() => min = Some(map.next_value::<u64>()?),
                "max" if max.is_none() => max = Some(map.next_value::<u64>()?),
                "contrast" if contrast.is_none() => contrast = Some(map.next_value::<V3>()?),
                "min" | "max" | "contrast" => {
                    return Err(de::Error::custom(format!(
                        "field \"{key}\" is given twice in {ADAPTIVE_NAME}"
                    )))
                }
                other => return Err(de::Error::unknown_field(other, ADAPTIVE_FIELDS)),
            }
        }
        Ok(SamplesDesc::Adaptive {
            min: min.ok_or_else(|| missing("min"))?,
            max: max.ok_or_else(|| missing("max"))?,
            contrast: contrast.unwrap_or((0.1, 0.1, 0.1)),
        })
    }
}

/// A required field of adaptive `samples` left out, named in the message.
fn missing<E: de::Error>(field: &str) -> E {
    E::custom(format!("missing field \"{field}\" in {ADAPTIVE_NAME}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize, Serialize)]
    struct Holder {
        samples: SamplesDesc,
    }

    fn parse(text: &str) -> Result<SamplesDesc, String> {
        ron::from_str::<Holder>(text)
            .map(|h| h.samples)
            .map_err(|e| e.to_string())
    }

    #[test]
    fn samples_read_as_a_count_or_adaptive() {
        assert_eq!(parse("(samples: 16)").unwrap(), SamplesDesc::Fixed(16));
        assert_eq!(
            parse("(samples: (min: 4, max: 64, contrast: (0.1, 0.2, 0.3)))").unwrap(),
            SamplesDesc::Adaptive {
                min: 4,
                max: 64,
                contrast: (0.1, 0.2, 0.3)
            }
        );
        assert_eq!(
            parse("(samples: (min: 1, max: 8))").unwrap(),
            SamplesDesc::Adaptive {
                min: 1,
                max: 8,
                contrast: (0.1, 0.1, 0.1)
            }
        );
        let e = parse("(samples: (min: 1, maxx: 8))").unwrap_err();
        assert!(e.contains("maxx"), "{e}");
        assert!(parse("(samples: -3)").is_err());
    }
}
