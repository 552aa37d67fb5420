//! Volume shaders of materials and cameras (`volume "shader" (…)`) onto homogeneous fog
//! (`docs/mi.md`, *Volume shaders*): `parti_volume` (mental ray's `physics` library)
//! becomes `Fog(sigma_a, sigma_s, g)` — a material's `interior`, a camera's
//! `atmosphere`. What `Fog` cannot hold (height-limited or non-uniform density, several
//! lights lists) warns; step lengths and levels are controls of mental ray's ray marching,
//! which the closed-form transmittance does not need. Any other volume shader warns.

use super::super::rib::Problem;
use super::cursor::{Cursor, ShaderCall};
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
    if call.name != "parti_volume" {
        let what = if call.name == "mib_volume" {
            "a linear fade to \"color\" over \"max\", not a physical medium"
        } else {
            "not a built-in volume shader"
        };
        let nothing = if where_ == "material" {
            "the material's interior stays empty"
        } else {
            "the camera sees no atmosphere"
        };
        c.report(
            Problem::warning(
                call.pos,
                format!(
                    "volume shader \"{}\" is not mapped ({what}): {nothing}",
                    call.name
                ),
            )
            .with_help("parti_volume maps onto homogeneous fog"),
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
    let warn = |c: &mut Cursor, name: &str, message: &str| {
        let pos = params.pos(name).unwrap_or(call.pos);
        c.warn(pos, format!("parti_volume: {message}"));
    };
    if mode != 0.0 {
        warn(
            c,
            "mode",
            "mode 1 (fog below \"height\") is not mapped: the medium fills the whole volume",
        );
    }
    if nonuniform != 0.0 {
        warn(
            c,
            "nonuniform",
            "non-uniform density is not mapped: the medium is homogeneous",
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
    })
}
