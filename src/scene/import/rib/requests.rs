//! The RenderMan Interface request names and what the reader does with each: the requests
//! it maps (handled in [`super::build`], [`super::retained`], [`super::geometry`] and
//! [`super::procedural`], which reads `Procedural "DelayedReadArchive"` as `ReadArchive` and
//! warns that the other procedurals' geometry is missing), the
//! standard requests of RISpec 3.2 and 3.4 (and PRMan's RIS requests) it reads and
//! deliberately leaves out — a located warning each, some saying what that means — and
//! `ArchiveRecord`, a comment, accepted silently. Any other name is an unknown request: a
//! located error with "did you mean".

use super::super::located::{Pos, Problem};
use super::geometry::PRIMITIVES;
use crate::scene::suggest::suggestion;

/// Requests the reader maps onto the description (the primitives are in [`PRIMITIVES`]).
pub const MAPPED: &[&str] = &[
    "version",
    "FrameBegin",
    "FrameEnd",
    "WorldBegin",
    "WorldEnd",
    "Format",
    "Projection",
    "ScreenWindow",
    "Clipping",
    "PixelSamples",
    "PixelFilter",
    "PixelVariance",
    "ShadingRate",
    "Exposure",
    "Imager",
    "Display",
    "DepthOfField",
    "AttributeBegin",
    "AttributeEnd",
    "TransformBegin",
    "TransformEnd",
    "Identity",
    "Translate",
    "Rotate",
    "Scale",
    "ConcatTransform",
    "Transform",
    "CoordinateSystem",
    "CoordSysTransform",
    "Color",
    "Opacity",
    "Sides",
    "Orientation",
    "ReverseOrientation",
    "ReadArchive",
    "Procedural",
    "Procedural2",
    "Surface",
    "Displacement",
    "LightSource",
    "AreaLightSource",
    "Atmosphere",
    "Illuminate",
    "Attribute",
    "Declare",
    "Basis",
    "ObjectBegin",
    "ObjectEnd",
    "ObjectInstance",
    "MotionBegin",
    "MotionEnd",
];

/// Requests accepted without a word: `ArchiveRecord` writes comments and structure hints
/// (`ArchiveRecord "comment" "…"`, `"structure"`, `"verbatim"`) that do not change the scene.
pub const SILENT: &[&str] = &["ArchiveRecord"];

/// Standard requests read and left out, with what leaving them out means where that is
/// more than "not rendered" (`None`: the plain warning).
const IGNORED: &[(&str, Option<&str>)] = &[
    // Options.
    ("FrameAspectRatio", None),
    ("CropWindow", None),
    ("ClippingPlane", None),
    ("Shutter", Some("motion blur is not rendered")),
    ("Quantize", None),
    ("Hider", None),
    ("ColorSamples", None),
    ("RelativeDetail", None),
    ("Option", None),
    ("DisplayChannel", None),
    ("Camera", None),
    ("PixelSampleImager", None),
    ("Perspective", None),
    ("Skew", None),
    ("Deformation", None),
    ("ScopedCoordinateSystem", None),
    // Attributes.
    ("TextureCoordinates", None),
    ("Interior", None),
    ("Exterior", None),
    ("Shader", None),
    ("ShadingInterpolation", None),
    ("Matte", None),
    ("Bound", None),
    ("Detail", None),
    ("DetailRange", None),
    ("GeometricApproximation", None),
    ("Resource", None),
    ("ResourceBegin", None),
    ("ResourceEnd", None),
    // Geometry we do not make.
    ("TrimCurve", Some("the surface is untrimmed")),
    ("Points", None),
    ("Curves", None),
    ("Blobby", None),
    ("Geometry", None),
    ("HierarchicalSubdivisionMesh", None),
    ("Volume", None),
    (
        "SolidBegin",
        Some("solids are not combined: the primitives inside are rendered as surfaces"),
    ),
    ("SolidEnd", None),
    // Textures and files.
    ("MakeTexture", None),
    ("MakeBump", None),
    ("MakeShadow", None),
    ("MakeCubeFaceEnvironment", None),
    ("MakeLatLongEnvironment", None),
    ("MakeBrickMap", None),
    ("ErrorHandler", None),
    ("System", None),
    (
        "IfBegin",
        Some("conditions are not evaluated: every branch is read"),
    ),
    ("ElseIf", None),
    ("Else", None),
    ("IfEnd", None),
    (
        "ArchiveBegin",
        Some("inline archives are not kept: what follows is read in place"),
    ),
    ("ArchiveEnd", None),
    // PRMan's RIS requests.
    ("Integrator", None),
    ("Bxdf", None),
    ("Pattern", None),
    ("Light", None),
    ("LightFilter", None),
    ("DisplayFilter", None),
    ("SampleFilter", None),
];

/// The warning for a request read and left out, `None` when `name` is not one of them.
pub fn ignored(name: &str, pos: Pos) -> Option<Problem> {
    let (_, why) = IGNORED.iter().find(|(n, _)| *n == name)?;
    Some(Problem::warning(
        pos,
        match why {
            Some(why) => format!("ignored request \"{name}\": {why}"),
            None => format!("ignored request \"{name}\""),
        },
    ))
}

/// The error for a request name the reader does not know, with the closest known name.
pub fn unknown(name: &str, pos: Pos) -> Problem {
    let mut all: Vec<&str> = MAPPED.to_vec();
    all.extend(PRIMITIVES);
    all.extend(SILENT);
    all.extend(IGNORED.iter().map(|(n, _)| *n));
    let mut e = Problem::error(pos, format!("unknown request \"{name}\""));
    e.help = suggestion(name, &all, "requests").filter(|h| h.starts_with("did"));
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_is_in_one_list() {
        let mut all: Vec<&str> = MAPPED.to_vec();
        all.extend(PRIMITIVES);
        all.extend(SILENT);
        all.extend(IGNORED.iter().map(|(n, _)| *n));
        let n = all.len();
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), n, "a request listed twice");
    }

    #[test]
    fn unknown_names_get_the_closest_request() {
        let p = Pos { line: 1, column: 1 };
        assert_eq!(
            unknown("ArchiveRecrod", p).help.as_deref(),
            Some("did you mean \"ArchiveRecord\"?")
        );
        assert_eq!(unknown("Frobnicate", p).help, None);
        assert_eq!(
            ignored("SolidBegin", p).map(|w| w.message).as_deref(),
            Some(
                "ignored request \"SolidBegin\": solids are not combined: the primitives inside \
                 are rendered as surfaces"
            )
        );
    }
}
