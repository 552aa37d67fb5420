//! Checks a camera's `imager: (...)` and builds its [`Imager`] component.

use glam::Vec2;

use super::desc::{ImagerPatternDesc, ToneMapDesc};
use super::diagnostics::Sources;
use super::validate::{Checker, Item};
use crate::components::{Imager, ImagerPattern, ToneMap};

/// The imager of a camera: `None` when it has none or it is invalid (errors recorded).
pub fn imager(src: &mut Sources, item: &Item<'_, super::desc::CameraDesc>) -> Option<Imager> {
    let d = item.desc.imager.as_ref()?;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let path = item.at(".imager");
    let background = match d.background {
        Some(b) => Some(
            ck.colour(&format!("{path}.background"), "background", b)?
                .as_vec3(),
        ),
        None => None,
    };
    let gain = ck.non_negative(&format!("{path}.gain"), "gain", d.gain)?;
    let gamma = match d.gamma {
        Some(g) => {
            let p = format!("{path}.gamma");
            if !ck.finite(&p, "gamma", g) {
                return None;
            }
            if g <= 0.0 {
                ck.error(&p, format!("gamma must be positive, found {g}"));
                return None;
            }
            Some(g as f32)
        }
        None => None,
    };
    let pattern = match &d.pattern {
        Some(p) => Some(pattern(&mut ck, &format!("{path}.pattern"), p)?),
        None => None,
    };
    Some(Imager {
        pattern,
        background,
        gain: gain as f32,
        tone_map: match d.tone_map {
            ToneMapDesc::None => ToneMap::None,
            ToneMapDesc::Reinhard => ToneMap::Reinhard,
        },
        gamma,
    })
}

/// The imager's `pattern` at `path`: `None` when a value is invalid (errors recorded).
fn pattern(ck: &mut Checker<'_>, path: &str, d: &ImagerPatternDesc) -> Option<ImagerPattern> {
    let ImagerPatternDesc::Disk {
        center,
        radius,
        fuzz,
        inside,
        outside,
    } = *d;
    let path = format!("{path}.Disk");
    let cx = ck.finite(&format!("{path}.center[0]"), "center", center.0);
    let cy = ck.finite(&format!("{path}.center[1]"), "center", center.1);
    let radius = ck.non_negative(&format!("{path}.radius"), "radius", radius);
    let fuzz = ck.non_negative(&format!("{path}.fuzz"), "fuzz", fuzz);
    let inside = ck.colour(&format!("{path}.inside"), "inside", inside);
    let outside = ck.colour(&format!("{path}.outside"), "outside", outside);
    if !(cx && cy) {
        return None;
    }
    Some(ImagerPattern::Disk {
        center: Vec2::new(center.0 as f32, center.1 as f32),
        radius: radius? as f32,
        fuzz: fuzz? as f32,
        inside: inside?.as_vec3(),
        outside: outside?.as_vec3(),
    })
}
