//! RIB values out of range are reported where the file writes them: a quadric's range
//! quoting the value as written (not as clamped).

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
fn a_sphere_range_quotes_z_max_as_written() {
    assert_eq!(
        errors(&format!("{HEAD}Sphere 1 0.5 -1 360\nWorldEnd\n")),
        "t.rib:5:14: error: object \"sphere_1\" (sphere): parameter `z_max` = -1 is out of range \
         (expected > z_min)"
    );
    assert_eq!(
        errors(&format!("{HEAD}Sphere 1 2 3.3 360\nWorldEnd\n")),
        "t.rib:5:12: error: object \"sphere_1\" (sphere): parameter `z_max` = 3.3 is out of range \
         (expected > z_min, both clamped to [-radius, radius])"
    );
    assert_eq!(
        errors(&format!("{HEAD}Sphere -0.3 -1 1 360\nWorldEnd\n")),
        "t.rib:5:8: error: object \"sphere_1\" (sphere): parameter `radius` = -0.3 is out of range \
         (expected > 0)"
    );
}
