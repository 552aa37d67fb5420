//! Checks a camera's `imager: (...)` and builds its [`Imager`] component.

use super::desc::ToneMapDesc;
use super::diagnostics::Sources;
use super::validate::{Checker, Item};
use crate::components::{Imager, ToneMap};

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
    Some(Imager {
        background,
        gain: gain as f32,
        tone_map: match d.tone_map {
            ToneMapDesc::None => ToneMap::None,
            ToneMapDesc::Reinhard => ToneMap::Reinhard,
        },
        gamma,
    })
}
