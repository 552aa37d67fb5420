//! `mib_volume` (mental ray's base library: `color "color"`, `scalar "max"`, `boolean
//! "lightrays"`) — "fades the result toward a fog colour by the ray length; beyond `max` the
//! fog is solid; `color`'s alpha limits the fog's opacity" — onto a camera atmosphere
//! `Fade(color: rgb, opacity: alpha, max:)` (`docs/mi.md`, *Volume shaders*). In a material
//! it warns: `Fade` is a camera atmosphere only.

use super::super::located::Problem;
use super::cursor::{Cursor, ShaderCall, Value};
use super::shaders::Params;
use crate::scene::desc::{FalloffDesc, VolumeDesc};
use crate::scene::suggest::closest;

/// The parameters of `mib_volume`.
const MIB_VOLUME: &[&str] = &["color", "max", "lightrays"];

/// The fade of a `mib_volume` call in a `where_` (`material` or `camera`), or `None`
/// (reported).
pub fn mib_volume(c: &mut Cursor, call: &ShaderCall, where_: &str) -> Option<VolumeDesc> {
    let mut ok = true;
    for p in &call.params {
        if !MIB_VOLUME.contains(&p.name.as_str()) {
            let mut e = Problem::error(
                p.pos,
                format!("unknown parameter \"{}\" of shader \"mib_volume\"", p.name),
            );
            if let Some(s) = closest(&p.name, MIB_VOLUME.iter().copied()) {
                e = e.with_help(format!("did you mean \"{s}\"?"));
            }
            c.report(e);
            ok = false;
        }
    }
    if where_ == "material" {
        c.report(
            Problem::warning(
                call.pos,
                "volume shader \"mib_volume\" in a material is not mapped (a fade is a camera atmosphere only): the material's interior stays empty",
            )
            .with_help("give the camera the mib_volume, or the material a parti_volume"),
        );
        return None;
    }
    let params = Params::new(call);
    let color = params.color(c, "color", (0.0, 0.0, 0.0));
    let opacity = match params.value("color").map(|p| &p.value) {
        Some(Value::Nums(n)) if n.len() == 4 => n[3],
        _ => 1.0,
    };
    let max = params.scalar(c, "max", 0.0);
    let mut bad = |c: &mut Cursor, name: &str, message: String| {
        let pos = params.value(name).map_or(call.pos, |p| p.value_pos);
        c.error(pos, format!("mib_volume: {message}"));
        ok = false;
    };
    if !(0.0..=1.0).contains(&opacity) {
        bad(
            c,
            "color",
            format!("the alpha of \"color\" must be between 0 and 1, found {opacity}"),
        );
    }
    if [color.0, color.1, color.2].iter().any(|&x| x < 0.0) {
        bad(
            c,
            "color",
            format!(
                "\"color\" must not be negative, found {} {} {}",
                color.0, color.1, color.2
            ),
        );
    }
    if max < 0.0 {
        bad(
            c,
            "max",
            format!("\"max\" must not be negative, found {max}"),
        );
    }
    if params.boolean(c, "lightrays", false) {
        let pos = params.pos("lightrays").unwrap_or(call.pos);
        c.warn(
            pos,
            "mib_volume: \"lightrays\" is not mapped: light (shadow) rays are not faded",
        );
    }
    ok.then_some(VolumeDesc::Fade {
        color,
        opacity,
        max,
        falloff: FalloffDesc::Linear,
    })
}
