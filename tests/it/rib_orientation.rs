//! RIB `Orientation` and `ReverseOrientation` (RISpec 3.2, "Orientation and Sides"): an
//! inside-out primitive shows its inside as its front with `Sides 1` (its other side culled); the orientation is an
//! attribute (restored by `AttributeEnd`, kept past `TransformEnd`), flips with the
//! coordinate system (a mirror alone turns nothing inside out; `"lh"` and `"rh"` compare
//! with the handedness relative to camera space) and is taken where an object is instanced.

use std::path::Path;

use stagelight::scene::import::rib::read_rib;
use stagelight::scene::load_scene_str;

/// The red value of the centre pixel of a 16 × 16 RIB image: a `matte` world lit by a point
/// light at the camera, `body` inside the world block after `pre_world` before it.
fn centre_with(pre_world: &str, body: &str) -> f32 {
    let text = format!(
        "Format 16 16 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 1 1\n\
         LightSource \"pointlight\" 1 \"from\" [0 0 0] \"intensity\" [20]\n{pre_world}\
         WorldBegin\nSurface \"matte\"\nSides 1\n{body}\nWorldEnd\n"
    );
    let mut scene =
        load_scene_str(&text, Path::new("t.rib")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let frame = crate::common::render(&mut scene.world, scene.settings.clone());
    let image = frame.outputs.image.expect("an image");
    image.beauty[(8 * 16 + 8) as usize].x
}

fn centre(body: &str) -> f32 {
    centre_with("", body)
}

/// A unit sphere 5 units in front of the camera.
const SPHERE: &str = "AttributeBegin\nTranslate 0 0 5\nSphere 1 -1 1 360\nAttributeEnd";
/// The far half of that sphere (z ≥ 0 in its object space): open toward the camera, which
/// sees its inside.
const DOME: &str = "AttributeBegin\nTranslate 0 0 5\nSphere 1 0 1 360\nAttributeEnd";

/// The centre pixel of an inside-out unit sphere 5 units away: its near half's back is
/// culled (`Sides 1`), the camera sees the inside of the far half, lit by the light at the
/// camera (RIB lights cast no shadows unless asked) from 6 units: `matte` `Kd·I/d²` = 20/36.
fn assert_far_inside(centre: f32) {
    assert!((centre - 20.0 / 36.0).abs() < 2e-3, "{centre}");
}

#[test]
fn an_inside_out_one_sided_sphere_shows_its_inside() {
    let outside = centre(SPHERE);
    assert!(outside > 0.0);
    // The near half shows its back, culled: the camera sees the inside of the far half.
    assert_far_inside(centre(&format!("ReverseOrientation\n{SPHERE}")));
    assert_far_inside(centre(&format!("Orientation \"inside\"\n{SPHERE}")));
    assert_eq!(
        centre(&format!(
            "ReverseOrientation\nOrientation \"outside\"\n{SPHERE}"
        )),
        outside
    );
    // Seen from inside, the dome is its back as modelled and its front inside out (lit by
    // the light at the camera).
    assert_eq!(centre(DOME), 0.0);
    assert!(centre(&format!("ReverseOrientation\n{DOME}")) > 0.0);
    assert!(centre(&format!("Orientation \"inside\"\n{DOME}")) > 0.0);
}

#[test]
fn a_one_sided_polygons_front_flips_with_the_orientation() {
    // Clockwise seen from the camera: the front (RenderMan's outside, left-handed).
    let clockwise = "Polygon \"P\" [-1 -1 5  -1 1 5  1 1 5  1 -1 5]";
    let counter = "Polygon \"P\" [-1 -1 5  1 -1 5  1 1 5  -1 1 5]";
    let lit = centre(clockwise);
    assert!(lit > 0.0);
    assert_eq!(centre(counter), 0.0);
    assert_eq!(centre(&format!("ReverseOrientation\n{clockwise}")), 0.0);
    let reversed = centre(&format!("ReverseOrientation\n{counter}"));
    assert!((reversed / lit - 1.0).abs() < 1e-5, "{reversed} vs {lit}");
    let indexed = "PointsPolygons [4] [0 1 2 3] \"P\" [-1 -1 5  1 -1 5  1 1 5  -1 1 5]";
    assert_eq!(centre(indexed), 0.0);
    assert!(centre(&format!("Orientation \"inside\"\n{indexed}")) > 0.0);
}

#[test]
fn the_orientation_is_an_attribute() {
    let outside = centre(SPHERE);
    // Restored by AttributeEnd (and WorldEnd's block) …
    let block = "AttributeBegin\nReverseOrientation\nAttributeEnd\n";
    assert_eq!(centre(&format!("{block}{SPHERE}")), outside);
    let block = "AttributeBegin\nOrientation \"inside\"\nAttributeEnd\n";
    assert_eq!(centre(&format!("{block}{SPHERE}")), outside);
    // … but not by TransformEnd, which restores the transformation only.
    let block = "TransformBegin\nReverseOrientation\nTransformEnd\n";
    assert_far_inside(centre(&format!("{block}{SPHERE}")));
    // Two reversals cancel.
    assert_eq!(
        centre(&format!("ReverseOrientation\nReverseOrientation\n{SPHERE}")),
        outside
    );
}

#[test]
fn the_orientation_flips_with_the_coordinate_system() {
    let outside = centre(SPHERE);
    let mirrored = |extra: &str| {
        centre(&format!(
            "AttributeBegin\nTranslate 0 0 5\nScale 1 1 -1\n{extra}Sphere 1 -1 1 360\nAttributeEnd"
        ))
    };
    // A mirror flips the orientation with the coordinate system: not inside out.
    let plain = mirrored("");
    assert!((plain / outside - 1.0).abs() < 1e-3, "{plain} vs {outside}");
    // The mirrored orientation reversed again is left-handed in a right-handed system.
    assert_far_inside(mirrored("ReverseOrientation\n"));
    assert_far_inside(mirrored("Orientation \"lh\"\n"));
    assert_eq!(mirrored("Orientation \"rh\"\n"), plain);
    // Set before the mirror, an orientation flips with it.
    let before = |o: &str| {
        centre(&format!(
            "AttributeBegin\nOrientation \"{o}\"\nTranslate 0 0 5\nScale 1 1 -1\n\
             Sphere 1 -1 1 360\nAttributeEnd"
        ))
    };
    assert_eq!(before("lh"), plain);
    assert_far_inside(before("rh"));
    // Unmirrored, the coordinate system is left-handed, as camera space.
    assert_eq!(centre(&format!("Orientation \"lh\"\n{SPHERE}")), outside);
    assert_far_inside(centre(&format!("Orientation \"rh\"\n{SPHERE}")));
    // A mirroring camera transformation makes the world right-handed.
    let sphere = "AttributeBegin\nTranslate 0 0 -5\nSphere 1 -1 1 360\nAttributeEnd";
    let world = |o: &str| centre_with("Scale 1 1 -1\n", &format!("{o}{sphere}"));
    let camera_mirrored = world("");
    assert!((camera_mirrored / outside - 1.0).abs() < 1e-3);
    assert_eq!(world("Orientation \"rh\"\n"), camera_mirrored);
    assert_far_inside(world("Orientation \"lh\"\n"));
}

#[test]
fn an_object_takes_the_orientation_where_it_is_instanced() {
    let text = "WorldBegin\nObjectBegin 1\nReverseOrientation\nSphere 1 -1 1 360\nObjectEnd\n\
                ObjectInstance 1\nAttributeBegin\nReverseOrientation\nObjectInstance 1\n\
                AttributeEnd\nObjectInstance 1\nWorldEnd\n";
    let s = read_rib(Path::new("t.rib"), text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"));
    let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        w,
        ["t.rib:3:1: warning: ignored \"ReverseOrientation\" inside ObjectBegin 1: an object takes its attributes where it is instanced"]
    );
    // One object per orientation, shared by the instances with it.
    let reversed: Vec<bool> = s
        .desc
        .objects
        .iter()
        .map(|o| o.reverse_orientation)
        .collect();
    assert_eq!(reversed, [false, true]);
    let of: Vec<&str> = s.desc.instances.iter().map(|i| i.of.as_str()).collect();
    assert_eq!(of[0], of[2]);
    assert_ne!(of[0], of[1]);
}

#[test]
fn orientation_requests_are_read_without_warnings_and_bad_tokens_are_located() {
    let text = "WorldBegin\nOrientation \"rh\"\nReverseOrientation\nSphere 1 -1 1 360\nWorldEnd\n";
    let s = read_rib(Path::new("t.rib"), text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"));
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert!(!s.desc.objects[0].reverse_orientation, "rh reversed is lh");
    let text = "WorldBegin\nOrientation \"sideways\"\nSphere 1 -1 1 360\nWorldEnd\n";
    let e = load_scene_str(text, Path::new("t.rib"))
        .err()
        .expect("an error");
    assert_eq!(
        e.to_string(),
        "t.rib:2:13: error: unknown orientation \"sideways\"\n  \
         help: expected \"outside\", \"inside\", \"lh\" or \"rh\""
    );
}

/// Every primitive the reader makes has RenderMan's outside as its front: each of these
/// faces the camera with its outside (quadrics out, `Disk` +z, patches `∂P/∂u × ∂P/∂v`,
/// polygons and subdivision faces clockwise in the left-handed camera frame), so with
/// `Sides 1` it is lit, and black once reversed.
#[test]
fn every_primitive_faces_out_as_the_specification_defines() {
    let square = "-1 -1 5  -1 1 5  1 1 5  1 -1 5";
    // Patch order: P00, P10 (+y: ∂P/∂u), P01 (+x: ∂P/∂v), P11; their cross product is −z.
    let patch = "-1 -1 5  -1 1 5  1 -1 5  1 1 5";
    let cases = [
        ("Translate 0 0 5\nSphere 1 -1 1 360".to_string(), "sphere"),
        (
            "Translate 0 0 5\nRotate 90 1 0 0\nCylinder 1 -1 1 360".into(),
            "cylinder",
        ),
        (
            "Translate 0 0 5\nRotate 180 1 0 0\nCone 1 1 360".into(),
            "cone",
        ),
        (
            "Translate 0 0 5\nRotate 180 1 0 0\nDisk 0 1 360".into(),
            "disk",
        ),
        ("Translate 1 0 5\nTorus 1 0.5 0 360 360".into(), "torus"),
        ("Translate 0 0 5\nParaboloid 1 0 1 360".into(), "paraboloid"),
        (
            "Translate 0 0 5\nRotate 90 1 0 0\nHyperboloid 1 0 -1 1 0 1 360".into(),
            "hyperboloid",
        ),
        (format!("Polygon \"P\" [{square}]"), "polygon"),
        (
            format!("GeneralPolygon [4] \"P\" [{square}]"),
            "general polygon",
        ),
        (format!("Patch \"bilinear\" \"P\" [{patch}]"), "patch"),
        (
            format!("PatchMesh \"bilinear\" 2 \"nonperiodic\" 2 \"nonperiodic\" \"P\" [{patch}]"),
            "patch mesh",
        ),
        (
            format!("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [{patch}]"),
            "nupatch",
        ),
        (
            format!("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] \"P\" [{square}]"),
            "subdivision mesh",
        ),
    ];
    for (body, name) in cases {
        let body = format!("AttributeBegin\n{body}\nAttributeEnd");
        assert!(centre(&body) > 0.0, "{name}: its outside faces the camera");
        // Reversed, its back faces the camera and is culled (`Sides 1`): the camera sees
        // the background or, for a closed or curved primitive, the inside of its far part,
        // farther from the light.
        let outside = centre(&body);
        let reversed = centre(&format!("ReverseOrientation\n{body}"));
        assert!(
            reversed < 0.9 * outside,
            "{name}: reversed, its back faces the camera ({reversed} vs {outside})"
        );
    }
}

/// `convert` keeps the orientation (`reverse_orientation: true` on the inside-out object):
/// the RON renders the same bytes, in which only the reversed dome's inside is lit.
#[test]
fn convert_keeps_the_orientation() {
    let dir = crate::common::cli::scratch_dir("rib-orientation-convert");
    let path = dir.join("dome.rib");
    let text = "Format 64 48 1\nProjection \"perspective\" \"fov\" [40]\n\
                LightSource \"pointlight\" 1 \"from\" [0 0 0] \"intensity\" [20]\n\
                WorldBegin\nSurface \"matte\"\nSides 1\nAttributeBegin\nTranslate -1 0 5\n\
                ReverseOrientation\nSphere 1 0 1 360\nAttributeEnd\nAttributeBegin\n\
                Translate 1.2 0 5\nSphere 1 0 1 360\nAttributeEnd\nWorldEnd\n";
    std::fs::write(&path, text).unwrap();
    let s = read_rib(&path, text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"));
    let reversed: Vec<bool> = s
        .desc
        .objects
        .iter()
        .map(|o| o.reverse_orientation)
        .collect();
    assert_eq!(reversed, [true, false]);
    crate::common::cli::convert_renders_the_same_png("rib-orientation-convert-png", &path);
}
