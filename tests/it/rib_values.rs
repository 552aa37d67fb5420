//! RIB values out of range are reported where the file writes them: `Color` and `Opacity`
//! once per request, at the first channel out of range (not at the `Surface` or the
//! primitive, not once per channel), a primitive's constant `Cs`/`Os` at the parameter, and
//! a quadric's range quoting the value as written (not as clamped).

use std::path::Path;

use stagelight::scene::load_scene_str;

/// Every message of a refused file.
fn errors(text: &str) -> String {
    match load_scene_str(text, Path::new("t.rib")) {
        Ok(_) => "ok".into(),
        Err(e) => e.to_string(),
    }
}

const HEAD: &str = "Format 32 24 1\nWorldBegin\nLightSource \"pointlight\" 1 \"intensity\" [4]\n\
                    Translate 0 0 3\n";

#[test]
fn color_and_opacity_errors_are_at_their_values_once_per_request() {
    assert_eq!(
        errors(&format!(
            "{HEAD}Color [-1 0 0]\nSphere 1 -1 1 360\nWorldEnd\n"
        )),
        "t.rib:5:8: error: Color must not be negative, found -1 0 0"
    );
    assert_eq!(
        errors(&format!(
            "{HEAD}Surface \"plastic\"\n  Color [0.2 -0.1 0.5]\n  Opacity [1 1 1.2]\n\
             Sphere 1 -1 1 360\nWorldEnd\n"
        )),
        "t.rib:6:14: error: Color must not be negative, found 0.2 -0.1 0.5\n\
         t.rib:7:16: error: Opacity must be between 0 and 1 in every channel, found 1 1 1.2\n  \
         help: an opacity is the fraction of light a surface stops: 1 is opaque, 0 invisible"
    );
    assert_eq!(
        errors(&format!(
            "{HEAD}Opacity 2 2 2\nSphere 1 -1 1 360\nWorldEnd\n"
        )),
        "t.rib:5:9: error: Opacity must be between 0 and 1 in every channel, found 2 2 2\n  \
         help: an opacity is the fraction of light a surface stops: 1 is opaque, 0 invisible"
    );
    assert_eq!(
        errors(&format!(
            "{HEAD}Sphere 1 -1 1 360 \"constant color Cs\" [0.5 0.5 -2]\nWorldEnd\n"
        )),
        "t.rib:5:48: error: parameter \"Cs\" of Sphere must not be negative, found 0.5 0.5 -2"
    );
    assert_eq!(
        errors(&format!(
            "{HEAD}Color [2 0.5 0]\nOpacity [1 0 0.5]\nSphere 1 -1 1 360\nWorldEnd\n"
        )),
        "ok",
        "a colour above 1 and an opacity in [0, 1] are fine"
    );
}

#[test]
fn a_sphere_range_quotes_zmax_as_written() {
    assert_eq!(
        errors(&format!("{HEAD}Sphere 1 0.5 -1 360\nWorldEnd\n")),
        "t.rib:5:14: error: object \"sphere_1\" (sphere): parameter `zmax` = -1 is out of range \
         (expected > zmin)"
    );
    assert_eq!(
        errors(&format!("{HEAD}Sphere 1 2 3.3 360\nWorldEnd\n")),
        "t.rib:5:12: error: object \"sphere_1\" (sphere): parameter `zmax` = 3.3 is out of range \
         (expected > zmin, both clamped to [-radius, radius])"
    );
    assert_eq!(
        errors(&format!("{HEAD}Sphere -0.3 -1 1 360\nWorldEnd\n")),
        "t.rib:5:8: error: object \"sphere_1\" (sphere): parameter `radius` = -0.3 is out of range \
         (expected > 0)"
    );
}
