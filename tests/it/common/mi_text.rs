//! The `.mi` text the `.mi` tests share: library links, an options block and the camera most
//! of them look through (at the origin, down −z, focal 12, aperture 32, aspect 4/3, 160 × 120:
//! the image plane spans ±4/3 by ±1 at distance 1), and a point lamp at the eye.

/// Links and includes mental ray's base library.
pub const BASE: &str = "link \"base.so\"\n$include <base.mi>\n";

/// Links and includes mental ray's physics library.
pub const PHYSICS: &str = "link \"physics.so\"\n$include <physics.mi>\n";

/// `links`, an options block (`samples 0 0`, `object space`) and the camera `Camera` with
/// its instance `Camera_inst`; `camera_extra` (whole lines) goes before `end camera`.
pub fn mi_preamble(links: &str, camera_extra: &str) -> String {
    format!(
        r#"{links}options "opt"
samples 0 0
object space
end options
camera "Camera"
frame 1
output "rgb" "png" "out.png"
focal 12.0
aperture 32.0
aspect 1.33333333333
resolution 160 120
{camera_extra}end camera
instance "Camera_inst" "Camera"
end instance
"#
    )
}

/// The light `Lamp`, a `mib_light_point` with `params` at the origin, and its instance
/// `Lamp_inst`.
pub fn mi_point_lamp(params: &str) -> String {
    format!(
        r#"light "Lamp"
"mib_light_point" ({params})
origin 0.0 0.0 0.0
end light
instance "Lamp_inst" "Lamp"
end instance
"#
    )
}
