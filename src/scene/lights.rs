//! Checks of the area-light shapes beyond `Rect` (disc, sphere, cylinder) and of the light
//! options `visible`, `attenuation` and the photon controls of an ambient light, each error
//! located at its value.

use glam::DVec3;

use super::checker::{Checker, Item};
use super::desc::{LightDesc, LightKindDesc};
use super::syntax::Syntax;
use crate::components::LightShape;

/// A radius: finite and positive.
fn radius(ck: &mut Checker<'_>, path: &str, r: f64) -> Option<f32> {
    if !ck.finite(path, "radius", r) {
        return None;
    }
    if r <= 0.0 {
        ck.src.error(
            ck.file,
            path,
            format!("radius must be positive, found {r}"),
            Some(
                "the radius is the light's size in scene units, above 0 (such as 0.5); a light \
                 with no size is a point light"
                    .into(),
            ),
        );
        return None;
    }
    Some(r as f32)
}

/// The shape of a `Disc`, `Sphere` or `Cylinder` light (`light`: the light's path).
pub fn area_shape(ck: &mut Checker<'_>, light: &str, kind: &LightKindDesc) -> Option<LightShape> {
    let at = |s: &str| format!("{light}.kind.{s}");
    match kind {
        LightKindDesc::Disc {
            center,
            normal,
            radius: r,
        } => {
            let c = ck.v3(&at("Disc.center"), "center", *center);
            let n = ck.v3(&at("Disc.normal"), "normal", *normal);
            let r = radius(ck, &at("Disc.radius"), *r);
            let n = n?.normalize_or_zero();
            if n == DVec3::ZERO {
                ck.error(&at("Disc.normal"), "normal must not be zero");
                return None;
            }
            Some(LightShape::Disc {
                center: c?.as_vec3(),
                normal: n.as_vec3(),
                radius: r?,
            })
        }
        LightKindDesc::Sphere { center, radius: r } => {
            let c = ck.v3(&at("Sphere.center"), "center", *center);
            let r = radius(ck, &at("Sphere.radius"), *r);
            Some(LightShape::Sphere {
                center: c?.as_vec3(),
                radius: r?,
            })
        }
        LightKindDesc::Cylinder {
            start,
            end,
            radius: r,
        } => {
            let s = ck.v3(&at("Cylinder.start"), "start", *start);
            let e = ck.v3(&at("Cylinder.end"), "end", *end);
            let r = radius(ck, &at("Cylinder.radius"), *r);
            let (s, e) = (s?, e?);
            if (e - s).as_vec3().length_squared() == 0.0 {
                ck.error(&at("Cylinder.end"), "end must differ from start");
                return None;
            }
            Some(LightShape::Cylinder {
                start: s.as_vec3(),
                end: e.as_vec3(),
                radius: r?,
            })
        }
        _ => None,
    }
}

/// `attenuation: (start, end)`: finite, `0 ≤ start < end`; not on directional or ambient
/// lights.
pub fn attenuation(ck: &mut Checker<'_>, item: &Item<'_, LightDesc>) -> Option<Option<(f32, f32)>> {
    let Some((start, end)) = item.desc.attenuation else {
        return Some(None);
    };
    let path = item.at(".attenuation");
    let what = match item.desc.kind {
        LightKindDesc::Directional { .. } => Some("a directional"),
        LightKindDesc::Ambient => Some("an ambient"),
        _ => None,
    };
    if let Some(what) = what {
        ck.src.error(
            ck.file,
            &path,
            format!("{what} light has no distance to attenuate over"),
            Some("remove `attenuation`, or use a point, spot or area light".into()),
        );
        return None;
    }
    // The two distances as the scene's format names them: a `.mi` light shader's `"start"`
    // and `"stop"`, the RIB tutorial light's `near` and `far`.
    let syntax = ck.src.syntax(ck.file);
    let (s, e) = (
        syntax.named("start", "start", "near"),
        syntax.named("end", "stop", "far"),
    );
    let (start_name, end_name) = match syntax {
        Syntax::Ron | Syntax::Gltf => (
            "attenuation start".to_string(),
            "attenuation end".to_string(),
        ),
        Syntax::Mi | Syntax::Rib => (s.to_string(), e.to_string()),
    };
    let ok_s = ck.finite(&format!("{path}[0]"), &start_name, start);
    let ok_e = ck.finite(&format!("{path}[1]"), &end_name, end);
    if ok_s && start < 0.0 {
        ck.error(
            &format!("{path}[0]"),
            format!("{start_name} must not be negative, found {start}"),
        );
        return None;
    }
    if !(ok_s && ok_e) {
        return None;
    }
    if end <= start {
        ck.src.error(
            ck.file,
            &format!("{path}[1]"),
            format!("{end_name} must be greater than {s} ({start}), found {end}"),
            Some(format!(
                "light falls off linearly from full at `{s}` to none at `{e}`"
            )),
        );
        return None;
    }
    Some(Some((start as f32, end as f32)))
}

/// `visible: true` only on area lights.
pub fn visible(ck: &mut Checker<'_>, item: &Item<'_, LightDesc>, is_area: bool) -> Option<bool> {
    if item.desc.visible && !is_area {
        ck.src.error(
            ck.file,
            &item.at(".visible"),
            "only area lights can be visible (a point, spot, directional or ambient light has no \
             surface)",
            Some("remove `visible`, or use a Rect, Disc, Sphere or Cylinder light".into()),
        );
        return None;
    }
    Some(item.desc.visible)
}

/// `energy`, `caustic_photons` and `globillum_photons` on an `Ambient` light, which emits no
/// photons: each refused at its value, as `attenuation` and `samples` are there. Values
/// that ask for no photons (`0`, `(0, 0, 0)`) pass.
pub fn ambient_photons(ck: &mut Checker<'_>, item: &Item<'_, LightDesc>) -> Option<()> {
    let l = item.desc;
    if !matches!(l.kind, LightKindDesc::Ambient) {
        return Some(());
    }
    let written = [
        ("energy", l.energy.is_some_and(|e| e != (0.0, 0.0, 0.0))),
        ("caustic_photons", l.caustic_photons.is_some_and(|n| n > 0)),
        (
            "globillum_photons",
            l.globillum_photons.is_some_and(|n| n > 0),
        ),
    ];
    let mut ok = true;
    for (field, _) in written.iter().filter(|(_, set)| *set) {
        ck.src.error(
            ck.file,
            &item.at(&format!(".{field}")),
            "an ambient light emits no photons",
            Some(format!(
                "remove `{field}`; photons leave point, spot, directional and area lights"
            )),
        );
        ok = false;
    }
    ok.then_some(())
}

/// The error of a light aimed nowhere, as the scene's format aims it: RON's spot `target` at
/// its `position` (`spot`) or a zero `direction`, a `.mi` light's zero `direction`, a RIB
/// spot or distant light whose `to` is its `from`.
pub fn aim_error(syntax: Syntax, spot: bool) -> &'static str {
    let ron = if spot {
        "target must differ from position"
    } else {
        "direction must not be zero"
    };
    syntax.named(
        ron,
        "direction must not be zero",
        "\"to\" must differ from \"from\"",
    )
}

/// What makes a light's radiant value, as the scene's format writes it: RON's `color ×
/// intensity`, a `.mi` light shader's `"color"` (`physical_light`'s power already spread over
/// its sphere or shape), a RIB light's `intensity` times its `lightcolor`.
pub fn radiant_name(syntax: Syntax) -> &'static str {
    syntax.named(
        "color × intensity",
        "the light's emitted \"color\"",
        "intensity × lightcolor",
    )
}
