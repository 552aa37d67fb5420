//! Volume shaders of materials and cameras (`volume "shader" (…)`) onto fog (`docs/mi.md`,
//! *Volume shaders*): `parti_volume` (mental ray's `physics` library) becomes
//! `Fog(sigma_a, sigma_s, g, height, nonuniform)` — a material's `interior`, a camera's
//! `atmosphere` (`mode 1` bounds it below `height`, `nonuniform` varies its density by a
//! noise). The `lights` list and two differing phase lobes warn; step lengths and levels are
//! controls of mental ray's ray marching, which the engine does not need. `mib_volume` is
//! `fade.rs`; any other volume shader warns.

use super::super::located::Problem;
use super::cursor::{Cursor, ShaderCall};
use super::fade::mib_volume;
use super::shaders::Params;
use crate::scene::desc::VolumeDesc;
use crate::scene::suggest::closest;

/// The parameters of `parti_volume`.
const PARTI_VOLUME: &[&str] = &[
    "mode",
    "scatter",
    "extinction",
    "r",
    "g1",
    "g2",
    "nonuniform",
    "height",
    "min_step_len",
    "max_step_len",
    "light_dist",
    "min_level",
    "no_globil_where_direct",
    "lights",
];

/// The fog of the volume shader `call` of a `where_` (`material` or `camera`), or `None`
/// (reported) when it is not mapped.
pub fn volume(c: &mut Cursor, call: &ShaderCall, where_: &str) -> Option<VolumeDesc> {
    if call.name == "mib_volume" {
        return mib_volume(c, call, where_);
    }
    if call.name != "parti_volume" {
        let nothing = if where_ == "material" {
            "the material's interior stays empty"
        } else {
            "the camera sees no atmosphere"
        };
        c.report(
            Problem::warning(
                call.pos,
                format!(
                    "volume shader \"{}\" is not mapped (not a built-in volume shader): {nothing}",
                    call.name
                ),
            )
            .with_help("parti_volume maps onto fog, mib_volume onto a camera Fade"),
        );
        return None;
    }
    let mut ok = true;
    for p in &call.params {
        if !PARTI_VOLUME.contains(&p.name.as_str()) {
            let mut e = Problem::error(
                p.pos,
                format!(
                    "unknown parameter \"{}\" of shader \"parti_volume\"",
                    p.name
                ),
            );
            if let Some(s) = closest(&p.name, PARTI_VOLUME.iter().copied()) {
                e = e.with_help(format!("did you mean \"{s}\"?"));
            }
            c.report(e);
            ok = false;
        }
    }
    let params = Params::new(call);
    let scatter = params.color(c, "scatter", (0.0, 0.0, 0.0));
    let extinction = params.scalar(c, "extinction", 0.0);
    let r = params.scalar(c, "r", 1.0);
    let g1 = params.scalar(c, "g1", 0.0);
    let g2 = params.scalar(c, "g2", 0.0);
    let mode = params.scalar(c, "mode", 0.0);
    let nonuniform = params.scalar(c, "nonuniform", 0.0);
    let height = params.scalar(c, "height", 0.0);
    let warn = |c: &mut Cursor, name: &str, message: &str| {
        let pos = params.pos(name).unwrap_or(call.pos);
        c.warn(pos, format!("parti_volume: {message}"));
    };
    let mut bad = |c: &mut Cursor, name: &str, message: String| {
        let pos = params.value(name).map_or(call.pos, |p| p.value_pos);
        c.error(pos, format!("parti_volume: {message}"));
        ok = false;
    };
    if mode != 0.0 && mode != 1.0 {
        bad(
            c,
            "mode",
            format!(
                "\"mode\" must be 0 (fog everywhere) or 1 (fog below \"height\"), found {mode}"
            ),
        );
    }
    if !(0.0..=1.0).contains(&nonuniform) {
        bad(
            c,
            "nonuniform",
            format!("\"nonuniform\" must be between 0 and 1, found {nonuniform}"),
        );
    }
    if params.value("lights").is_some() {
        warn(
            c,
            "lights",
            "the light list is not mapped: every light scatters",
        );
    }
    if r != 1.0 && r != 0.0 && g1 != g2 {
        warn(
            c,
            "r",
            "two phase lobes are mapped onto one with the mean asymmetry r·g1 + (1 − r)·g2",
        );
    }
    let absorb = |s: f64| (extinction - s).max(0.0);
    if [scatter.0, scatter.1, scatter.2]
        .iter()
        .any(|&s| s > extinction)
    {
        warn(
            c,
            "scatter",
            "\"scatter\" exceeds \"extinction\" (the total): no absorption in those channels",
        );
    }
    let g = (r * g1 + (1.0 - r) * g2).clamp(-0.99, 0.99);
    ok.then_some(VolumeDesc::Fog {
        sigma_a: (absorb(scatter.0), absorb(scatter.1), absorb(scatter.2)),
        sigma_s: scatter,
        g,
        height: (mode == 1.0).then_some(height),
        nonuniform,
        noise_scale: 1.0,
    })
}
