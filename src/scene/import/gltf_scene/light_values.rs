//! Checking a `KHR_lights_punctual` light's values before it becomes a scene light, against
//! the extension's ranges: `color` components in [0, 1], `intensity` at least 0, `range`
//! greater than 0, and for a spot light `0 < outerConeAngle ≤ π/2` and
//! `0 ≤ innerConeAngle < outerConeAngle`. Each problem is an error naming the light and the
//! value (at its line and column in a `.gltf`, at the start of a `.glb`), once however many
//! nodes use the light; nothing is clamped in silence, as for cameras ([`super::camera_values`]).

use super::json_positions::Step;
use super::{at_element, given, Walk};

/// The JSON path of light `index`'s member `keys`.
fn path<'a>(index: usize, keys: &[&'a str]) -> Vec<Step<'a>> {
    let mut path = vec![
        Step::Key("extensions"),
        Step::Key("KHR_lights_punctual"),
        Step::Key("lights"),
        Step::Index(index),
    ];
    path.extend(keys.iter().map(|k| Step::Key(k)));
    path
}

/// The light's label for messages: `extensions.KHR_lights_punctual.lights[0] ("lamp")`.
pub fn label(light: &gltf::khr_lights_punctual::Light<'_>) -> String {
    let at = format!("extensions.KHR_lights_punctual.lights[{}]", light.index());
    match given(light.name()) {
        Some(n) => format!("{at} (\"{n}\")"),
        None => at,
    }
}

/// Pushes an error at the light's `keys` (once).
fn error(w: &mut Walk<'_>, index: usize, keys: &[&str], message: String, help: &str) {
    if w.errors.iter().any(|e| e.message == message) {
        return;
    }
    let mut d = at_element(w, &path(index, keys), message);
    d.help = Some(help.into());
    w.errors.push(d);
}

/// Checks `light`'s values; `false` (with errors pushed) where one is outside the
/// extension's range.
pub fn check(w: &mut Walk<'_>, light: &gltf::khr_lights_punctual::Light<'_>) -> bool {
    use gltf::khr_lights_punctual::Kind;
    let errors = w.errors.len();
    let index = light.index();
    let label = label(light);
    let [r, g, b] = light.color();
    if ![r, g, b].iter().all(|c| (0.0..=1.0).contains(c)) {
        error(
            w,
            index,
            &["color"],
            format!("{label}: \"color\" [{r}, {g}, {b}] must have components from 0 to 1"),
            "\"color\" is the light's linear RGB tint; its brightness belongs in \"intensity\"",
        );
    }
    let intensity = light.intensity();
    if !(intensity.is_finite() && intensity >= 0.0) {
        error(
            w,
            index,
            &["intensity"],
            format!("{label}: \"intensity\" must be a finite number of at least 0, found {intensity}"),
            "\"intensity\" is in candela for point and spot lights and in lux for directional ones; 0 switches the light off",
        );
    }
    if let Some(range) = light.range().filter(|r| !(r.is_finite() && *r > 0.0)) {
        error(
            w,
            index,
            &["range"],
            format!("{label}: \"range\" must be greater than 0, found {range}"),
            "leave \"range\" out for a light without a cutoff (stagelight ignores the cutoff anyway)",
        );
    }
    if let Kind::Spot {
        inner_cone_angle: inner,
        outer_cone_angle: outer,
    } = light.kind()
    {
        let half_pi = std::f32::consts::FRAC_PI_2;
        let outer_ok = outer > 0.0 && outer <= half_pi;
        if !outer_ok {
            error(
                w,
                index,
                &["spot", "outerConeAngle"],
                format!(
                    "{label}: \"outerConeAngle\" must be greater than 0 and at most π/2 radians (90°), found {outer}"
                ),
                "\"outerConeAngle\" is the angle from the spot's axis to the edge of its cone, in radians: 0.785 is 45°",
            );
        }
        if outer_ok && !(inner >= 0.0 && inner < outer) {
            error(
                w,
                index,
                &["spot", "innerConeAngle"],
                format!(
                    "{label}: \"innerConeAngle\" must be at least 0 and less than \"outerConeAngle\" ({outer}), found {inner}"
                ),
                "\"innerConeAngle\" is where the falloff toward the outer cone begins, in radians; 0 fades across the whole cone",
            );
        }
    }
    w.errors.len() == errors
}
