//! Cameras and lights of a glTF scene: every perspective camera met in the node walk, the first
//! being the render camera (or
//! a default framing of the scene's bounds), `KHR_lights_punctual` lights converted to
//! radiometric units, and the default light of a file that has none.
//!
//! Units: glTF gives point and spot intensities in candela (lm/sr) and directional ones in
//! lux (lm/m²); stagelight's lights are radiometric (W/sr, W/m²), so the reader divides by
//! 683 lm/W (the luminous efficacy at 555 nm, the definition of the candela).

use glam::{DMat4, DVec3};

use super::camera_values::{self, CameraValues};
use super::json_positions::Step;
use super::light_values;
use super::{at_element, given, m4, warn_once, Walk};
use crate::scene::desc::{
    CameraDesc, DepthExceededDesc, EnvironmentDesc, EnvironmentShaderDesc, LightDesc,
    LightKindDesc, OutputDesc, PlacementDesc,
};

/// Lumens per watt: photometric → radiometric.
pub const LUMENS_PER_WATT: f64 = 683.0;

/// Image width of a camera read from glTF (the height follows its aspect ratio).
pub const CAMERA_WIDTH: u32 = 640;

/// Vertical field of view of the default camera, degrees.
pub const DEFAULT_FOV_Y: f64 = 45.0;

/// Elevation of the default camera above the bounds' centre, degrees.
pub const DEFAULT_ELEVATION: f64 = 20.0;

/// Adds the light of `light` placed at `world`, unless one of its values is outside the
/// extension's range (errors from [`light_values::check`]).
pub fn light(w: &mut Walk<'_>, light: &gltf::khr_lights_punctual::Light<'_>, world: &DMat4) {
    use gltf::khr_lights_punctual::Kind;
    if !light_values::check(w, light) {
        return;
    }
    let name = match given(light.name()) {
        Some(given) => w.names.lights.take_given(given),
        None => w.names.lights.take(&format!("light{}", light.index())),
    };
    let position = world.transform_point3(DVec3::ZERO);
    let direction = world.transform_vector3(DVec3::NEG_Z).normalize_or_zero();
    let v3 = |v: DVec3| (v.x, v.y, v.z);
    let direction = if direction == DVec3::ZERO {
        DVec3::NEG_Z
    } else {
        direction
    };
    let kind = match light.kind() {
        Kind::Point => LightKindDesc::Point {
            position: v3(position),
        },
        Kind::Directional => LightKindDesc::Directional {
            direction: v3(direction),
        },
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            // In range: 0 ≤ inner < outer ≤ π/2 (light_values::check).
            let outer = (outer_cone_angle as f64).to_degrees();
            let inner = (inner_cone_angle as f64).to_degrees();
            LightKindDesc::Spot {
                position: v3(position),
                target: v3(position + direction),
                cone_angle: outer,
                penumbra: outer - inner,
                beam_distribution: 0.0,
            }
        }
    };
    if light.range().is_some() {
        let path = [
            Step::Key("extensions"),
            Step::Key("KHR_lights_punctual"),
            Step::Key("lights"),
            Step::Index(light.index()),
            Step::Key("range"),
        ];
        let d = at_element(
            w,
            &path,
            format!(
                "{}: ignored its range (lights fall off with the inverse square law only)",
                light_values::label(light)
            ),
        );
        warn_once(w, d);
    }
    let [r, g, b] = light.color();
    w.desc.lights.push(LightDesc {
        name,
        kind,
        color: (r as f64, g as f64, b as f64),
        intensity: light.intensity() as f64 / LUMENS_PER_WATT,
        shadows: true,
        shadow_factor: 0.0,
        samples: None,
        visible: false,
        attenuation: None,
        energy: None,
        caustic_photons: None,
        globillum_photons: None,
        inverse_square: true,
    });
}

/// A rigid camera-to-world matrix from a node's world matrix (scale and shear removed,
/// looking down −Z). Under a mirror (a negative determinant, as a parent scaled by −1 along
/// one axis gives) the camera keeps where the world matrix sends its view (−Z) and its up
/// (+Y), and its right is their cross product: a mirror cannot be a camera placement, and
/// keeping +X instead would turn the picture upside down.
fn rigid(world: &DMat4) -> DMat4 {
    let z = world.z_axis.truncate().normalize_or_zero();
    let z = if z == DVec3::ZERO { DVec3::Z } else { z };
    let mirrored = world.determinant() < 0.0;
    // The axis kept beside z: +X, or +Y under a mirror.
    let kept = if mirrored { world.y_axis } else { world.x_axis }.truncate();
    let k = (kept - z * kept.dot(z)).normalize_or_zero();
    let k = if k == DVec3::ZERO {
        z.any_orthonormal_vector()
    } else {
        k
    };
    let (x, y) = if mirrored {
        (k.cross(z), k)
    } else {
        (k, z.cross(k))
    };
    DMat4::from_cols(
        x.extend(0.0),
        y.extend(0.0),
        z.extend(0.0),
        world.w_axis.truncate().extend(1.0),
    )
}

/// Adds every perspective camera of the walk (the first is the render camera, writing
/// `<stem>.png`; the others `<stem>_<camera>.png`, for `render --camera NAME`), else the
/// default framing, and returns the render camera's name.
pub fn camera(w: &mut Walk<'_>) -> String {
    let stem = w
        .path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "gltf".into());
    let file = w.file;
    let mut found = Vec::new();
    let mut perspective = false;
    for (node, world) in w.cameras.clone() {
        let Some(node) = file.doc.nodes().nth(node) else {
            continue;
        };
        let Some(camera) = node.camera() else {
            continue;
        };
        let gltf::camera::Projection::Perspective(p) = camera.projection() else {
            continue;
        };
        perspective = true;
        let Some(values) = camera_values::check(w, &camera, &p) else {
            continue;
        };
        // The camera's own name, else a made-up one: its node's, or `camera<i>`.
        let label = match given(camera.name()) {
            Some(name) => Ok(name.to_string()),
            None => Err(given(node.name())
                .map(str::to_string)
                .unwrap_or_else(|| format!("camera{}", camera.index()))),
        };
        found.push((label, values, PlacementDesc::Matrix(m4(&rigid(&world)))));
    }
    if !perspective {
        let (lo, hi) = w.bounds.unwrap_or((DVec3::splat(-1.0), DVec3::splat(1.0)));
        let centre = (lo + hi) * 0.5;
        let radius = ((hi - lo).length() * 0.5).max(1e-3);
        let distance = radius / (DEFAULT_FOV_Y.to_radians() * 0.5).sin() * 1.05;
        let e = DEFAULT_ELEVATION.to_radians();
        let eye = centre + DVec3::new(0.0, e.sin(), e.cos()) * distance;
        let placement = PlacementDesc::LookAt {
            eye: (eye.x, eye.y, eye.z),
            target: (centre.x, centre.y, centre.z),
            up: (0.0, 1.0, 0.0),
        };
        let values = CameraValues {
            fov_y: DEFAULT_FOV_Y,
            height: CAMERA_WIDTH * 3 / 4,
        };
        let name = w.names.cameras.take("default_camera");
        return add_camera(w, name, &values, placement, &stem, true);
    }
    let mut first = None;
    for (label, values, placement) in found {
        let name = match label {
            Ok(given) => w.names.cameras.take_given(&given),
            Err(made_up) => w.names.cameras.take(&made_up),
        };
        let name = add_camera(w, name, &values, placement, &stem, first.is_none());
        first.get_or_insert(name);
    }
    first.unwrap_or_default()
}

/// Adds camera `name` (its output `<stem>.png` when `main`, else `<stem>_<name>.png`).
fn add_camera(
    w: &mut Walk<'_>,
    name: String,
    values: &CameraValues,
    placement: PlacementDesc,
    stem: &str,
    main: bool,
) -> String {
    let file = if main {
        format!("{stem}.png")
    } else {
        format!("{stem}_{name}.png")
    };
    w.desc.cameras.push(CameraDesc {
        name: name.clone(),
        fov_y: values.fov_y,
        resolution: (CAMERA_WIDTH, values.height),
        aspect: None,
        placement,
        outputs: vec![OutputDesc {
            file,
            format: None,
            passes: None,
            beauty_alpha: None,
        }],
        imager: None,
        lens: Vec::new(),
        atmosphere: None,
        space_scale: None,
    });
    name
}

/// A file without lights and without emitting materials is lit by a white environment of
/// radiance 1 (what glTF viewers do with a default light), so it never renders black.
pub fn default_light(w: &mut Walk<'_>) {
    let emits = w
        .desc
        .materials
        .iter()
        .any(|m| m.emission.0 > 0.0 || m.emission.1 > 0.0 || m.emission.2 > 0.0);
    if w.desc.lights.is_empty() && !emits {
        w.desc.environment = Some(EnvironmentDesc {
            shader: EnvironmentShaderDesc::Constant {
                color: (1.0, 1.0, 1.0),
            },
            intensity: 1.0,
            samples: 16,
            depth_exceeded: DepthExceededDesc::Environment,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scaled_camera_node_gives_a_rigid_placement() {
        let world = DMat4::from_scale_rotation_translation(
            DVec3::new(2.0, 3.0, 4.0),
            glam::DQuat::from_rotation_y(0.5),
            DVec3::new(1.0, 2.0, 3.0),
        );
        let r = rigid(&world);
        assert!((r.x_axis.length() - 1.0).abs() < 1e-12);
        assert!((r.z_axis.truncate() - world.z_axis.truncate().normalize()).length() < 1e-12);
        assert!(r.x_axis.dot(r.y_axis).abs() < 1e-12);
        assert_eq!(r.w_axis, world.w_axis);
    }

    #[test]
    fn a_mirrored_camera_keeps_its_view_and_its_up() {
        for (scale, up) in [
            (DVec3::new(-1.0, 1.0, 1.0), DVec3::Y),
            (DVec3::new(1.0, -1.0, 1.0), DVec3::NEG_Y),
            (DVec3::new(2.0, 2.0, -2.0), DVec3::Y),
        ] {
            let world = DMat4::from_scale(scale);
            let r = rigid(&world);
            let view = -world.z_axis.truncate().normalize();
            assert_eq!(r.transform_vector3(DVec3::NEG_Z), view, "{scale}");
            assert_eq!(r.y_axis.truncate(), up, "{scale}");
            assert!((r.determinant() - 1.0).abs() < 1e-12, "{scale}");
        }
    }
}
