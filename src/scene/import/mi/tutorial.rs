//! The tutorial's native shaders (seed 001 prints their C source), built in once their
//! library is linked (`link "myLight.so"`, …): `myLight` (§3.2.2), `mySurface` (§3.2.2),
//! `myDefaultSurface` (§4.1), `myEnvironment` (§4.3) — and `myDisplacement` (§4.4,
//! [`super::displace`]). Each maps onto the stagelight model that computes what its C source
//! computes (`docs/mi.md`, *The tutorial's shaders*). A parameter the C source reads but the
//! scene leaves out is mental ray's zero.

use super::super::located::Problem;
use super::cursor::{Cursor, ShaderCall};
use super::model::LightModel;
use super::shaders::{MappedLight, MappedMaterial, Params};
use crate::scene::desc::{
    DepthExceededDesc, EnvironmentDesc, EnvironmentShaderDesc, LocalLobeDesc, ShaderDesc,
};
use crate::scene::suggest::closest;

/// The tutorial's shaders, each with its library's stem and its parameters (the `.mi`
/// declarations the tutorial prints).
const SHADERS: &[(&str, &[&str])] = &[
    ("myLight", &["color"]),
    (
        "mySurface",
        &[
            "ambient", "diffuse", "specular", "spec_exp", "mode", "lights",
        ],
    ),
    ("myDefaultSurface", &["Ka", "Kd"]),
    ("myEnvironment", &["color"]),
    ("myDisplacement", &["factor"]),
];

/// Whether `name` is one of the tutorial's shaders (its library is `name.so`).
pub fn is_tutorial(name: &str) -> bool {
    SHADERS.iter().any(|(n, _)| *n == name)
}

/// The tutorial's libraries, by shader name (each library holds one shader).
pub fn library_names() -> Vec<&'static str> {
    SHADERS.iter().map(|(n, _)| *n).collect()
}

/// The tutorial shader whose library stem (`mylight` of `myLight.so`) is `stem`.
pub fn library(stem: &str) -> Option<&'static str> {
    SHADERS
        .iter()
        .map(|(n, _)| *n)
        .find(|n| n.to_ascii_lowercase() == stem)
}

/// Whether `call` names the tutorial shader `name` and its library is linked.
fn linked_call(call: &ShaderCall, linked: &[String], name: &str) -> bool {
    call.name == name && linked.iter().any(|l| l == name)
}

/// Checks the parameter names of a tutorial shader call (each unknown one reported).
fn check_params(c: &mut Cursor, call: &ShaderCall) -> bool {
    let known = SHADERS
        .iter()
        .find(|(n, _)| *n == call.name)
        .map_or(&[][..], |s| s.1);
    let mut ok = true;
    for p in &call.params {
        if !known.contains(&p.name.as_str()) {
            let mut e = Problem::error(
                p.pos,
                format!(
                    "unknown parameter \"{}\" of shader \"{}\"",
                    p.name, call.name
                ),
            );
            e = match closest(&p.name, known.iter().copied()) {
                Some(s) => e.with_help(format!("did you mean \"{s}\"?")),
                None => e.with_help(format!(
                    "its parameters are {}",
                    known
                        .iter()
                        .map(|k| format!("\"{k}\""))
                        .collect::<Vec<_>>()
                        .join(", ")
                )),
            };
            c.report(e);
            ok = false;
        }
    }
    ok
}

/// `light "…" "myLight" ("color" c)` after `link "myLight.so"`: the C source returns `color`
/// as the light's contribution everywhere — no distance falloff, no shadow rays (it never
/// calls `mi_trace_shadow`). `None` when `call` is not that shader (`Some(None)`: reported).
pub fn light(c: &mut Cursor, call: &ShaderCall, linked: &[String]) -> Option<Option<MappedLight>> {
    if !linked_call(call, linked, "myLight") {
        return None;
    }
    if !check_params(c, call) {
        return Some(None);
    }
    let color = Params::new(call).color(c, "color", (0.0, 0.0, 0.0));
    Some(Some(MappedLight {
        model: LightModel::Point,
        color,
        shadows: false,
        shadow_factor: 0.0,
        physical: false,
        attenuation: None,
    }))
}

/// `mySurface` after `link "mySurface.so"`: `ambient + Σ over the listed lights of
/// Cl·(diffuse·N·L + specular·mi_phong_specular(spec_exp))` — `mib_illum_phong`'s loop with
/// `ambient` added as it is and the light list always inclusive (the C source ignores
/// `mode`; without `lights` no light is sampled). Its loop never advances the light pointer,
/// so each entry of the list samples the *first* light again: a list of `n` lights is the
/// first light with `n` times the diffuse and specular weight. `myDefaultSurface` after `link
/// "myDefaultSurface.so"`: `Ka + Kd·|N·D|` in every channel, alpha 1 (`DefaultSurface` of
/// white). `None` when `call` is neither.
pub fn material(
    c: &mut Cursor,
    call: &ShaderCall,
    linked: &[String],
) -> Option<Option<MappedMaterial>> {
    let surface = linked_call(call, linked, "mySurface");
    if !surface && !linked_call(call, linked, "myDefaultSurface") {
        return None;
    }
    if !check_params(c, call) {
        return Some(None);
    }
    let p = Params::new(call);
    let zero = (0.0, 0.0, 0.0);
    if !surface {
        let shader = ShaderDesc::DefaultSurface {
            ka: p.scalar(c, "Ka", 0.0),
            kd: p.scalar(c, "Kd", 0.0),
            color: (1.0, 1.0, 1.0),
        };
        return Some(Some((shader, None, false, Default::default())));
    }
    // The printed loop runs `n_light` times but never advances `light`: it samples the
    // first listed light once per entry of the list.
    let mut lights = p.lights(c).unwrap_or_default();
    let n = lights.len() as f64;
    lights.truncate(1);
    let specular = p.color(c, "specular", zero);
    let shader = ShaderDesc::Local {
        color: p.color(c, "diffuse", zero),
        ka: 0.0,
        kd: n,
        specular: (n * specular.0, n * specular.1, n * specular.2),
        lobe: LocalLobeDesc::Phong {
            exponent: p.scalar(c, "spec_exp", 0.0).max(0.0),
        },
        reflection: zero,
        ambient: p.color(c, "ambient", zero),
    };
    let _ = p.scalar(c, "mode", 0.0);
    Some(Some((shader, Some(lights), false, Default::default())))
}

/// `environment "myEnvironment" ("color" c)` after `link "myEnvironment.so"`: `color` for
/// the rays that leave the scene, black for the rays that exceed a trace depth
/// (`depth_exceeded: Black`). The C source also returns black for rays that leave the scene
/// at the last reflection or refraction level (`level ≥ depth − 1`); here they see `color`
/// (`docs/mi.md`). `None` when `call` is not that shader.
pub fn environment(
    c: &mut Cursor,
    call: &ShaderCall,
    linked: &[String],
) -> Option<Option<EnvironmentDesc>> {
    if !linked_call(call, linked, "myEnvironment") {
        return None;
    }
    if !check_params(c, call) {
        return Some(None);
    }
    let color = Params::new(call).color(c, "color", (0.0, 0.0, 0.0));
    Some(Some(EnvironmentDesc {
        shader: EnvironmentShaderDesc::Constant { color },
        intensity: 1.0,
        samples: 16,
        depth_exceeded: DepthExceededDesc::Black,
    }))
}
