//! mental ray area shapes on lights without distance falloff (`mib_light_point`): each
//! light sample is a point light of `Cl = color` on the shape and the samples are averaged
//! (seed 001, §3.2.2), so the area light is as bright as its point light — it was divided
//! by π·area and made inverse-square, 10–100× too dark — and a shape facing away from the
//! scene still lights it.

use glam::Vec3;

use crate::common::cli::{run_in, scratch, stderr_of};
use crate::common::read_exr_texels;

/// A 2 × 2 quad (Lambert 0.8, mental ray's `mib_illum_lambert`: no 1/π) at z = 0 seen from
/// z = −4, lit by a `mib_light_point` of colour 1 at z = −`distance` with `shape` (empty for
/// the point light).
fn scene(distance: f64, shape: &str) -> String {
    format!(
        r#"link "base.so"
$include <base.mi>
options "opt" object space samples 0 0 end options
camera "cam" output "rgba" "exr" "out.exr" focal 1 aperture 1 aspect 1 resolution 16 16 end camera
instance "cam_i" "cam" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -4 1 end instance
light "L" "mib_light_point" ("color" 1 1 1) origin 0 0 0 {shape} end light
instance "L_i" "L" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -{distance} 1 end instance
material "m" opaque "mib_illum_lambert" ("diffuse" 0.8 0.8 0.8, "lights" ["L_i"]) end material
object "q" group
1 1 0
1 -1 0
-1 -1 0
-1 1 0
v 0 v 1 v 2 v 3
p "m" 0 3 2 1
end group end object
instance "q_i" "q" end instance
instgroup "root" "cam_i" "L_i" "q_i" end instgroup
render "root" "cam_i" "opt"
"#
    )
}

/// The beauty's pixels of `scene` rendered to EXR, and the stderr.
fn render(name: &str, text: &str) -> (Vec<Vec3>, String) {
    let dir = scratch(name);
    std::fs::write(dir.join("s.mi"), text).unwrap();
    let o = run_in(&dir, &["render", "s.mi", "--threads", "1"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let (_, px) = read_exr_texels(&dir.join("out.exr"));
    let _ = std::fs::remove_dir_all(&dir);
    (px, stderr_of(&o))
}

/// Every shape (a 0.2 × 0.2 rectangle — facing toward and away from the quad — a disc and
/// a sphere of radius 0.1) gives the point light's pixels at distances 2, 5 and 10 to
/// within the change of `N·L` across the shape (below 1 %), where the old reading gave
/// 71/255, 26/255 and 8/255 of the point light's 231/255 at the centre.
#[test]
fn an_area_shape_on_a_point_light_shader_keeps_its_brightness() {
    for distance in [2.0, 5.0, 10.0] {
        let (point, _) = render("mi-area-point", &scene(distance, ""));
        // The centre: 0.8 · 1 · cos 0 (no falloff), whatever the distance.
        let centre = point[8 * 16 + 8];
        assert!(
            (centre.x - 0.8).abs() < 0.02,
            "point light at {distance}: {centre}"
        );
        for shape in [
            "rectangle 0 0.2 0 0.2 0 0 4 4",
            "rectangle 0.2 0 0 0 0.2 0 4 4",
            "disc 0 0 -1 0.1 4 4",
            "sphere 0.1 4 4",
        ] {
            let (area, _) = render("mi-area-shape", &scene(distance, shape));
            for (k, (a, p)) in area.iter().zip(&point).enumerate() {
                assert!(
                    (a.x - p.x).abs() <= 0.01 * p.x + 1e-4,
                    "{shape} at {distance}, pixel {k}: {a} against the point light's {p}"
                );
            }
        }
    }
}

/// `visible` on such a light is a warning: rays do not meet point lights.
#[test]
fn a_visible_non_physical_area_light_warns() {
    let text = scene(2.0, "rectangle 0 0.2 0 0.2 0 0 4 4 visible");
    let (_, stderr) = render("mi-area-visible", &text);
    assert!(
        stderr.contains("`visible` is not drawn: an area shape on a light shader without distance falloff lights the scene as point lights spread over the shape"),
        "{stderr}"
    );
}
