//! Checks volume shaders (`atmosphere` on a camera, `interior` on a material) and builds
//! their [`Fog`].

use super::desc::{CameraDesc, MaterialDesc, VolumeDesc};
use super::diagnostics::Sources;
use super::validate::{Checker, Item};
use crate::components::Fog;

/// The camera's atmosphere, if it has a valid one (errors recorded).
pub fn atmosphere(src: &mut Sources, item: &Item<'_, CameraDesc>) -> Option<Fog> {
    let d = item.desc.atmosphere.as_ref()?;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    fog(&mut ck, &item.at(".atmosphere"), d)
}

/// The material's interior, if it has a valid one (errors recorded).
pub fn interior(src: &mut Sources, item: &Item<'_, MaterialDesc>) -> Option<Fog> {
    let d = item.desc.interior.as_ref()?;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    fog(&mut ck, &item.at(".interior"), d)
}

fn fog(ck: &mut Checker<'_>, path: &str, d: &VolumeDesc) -> Option<Fog> {
    let VolumeDesc::Fog {
        sigma_a,
        sigma_s,
        g,
    } = *d;
    let p = format!("{path}.Fog");
    let a = ck.colour(&format!("{p}.sigma_a"), "sigma_a", sigma_a);
    let s = ck.colour(&format!("{p}.sigma_s"), "sigma_s", sigma_s);
    let g_path = format!("{p}.g");
    let g_ok = ck.finite(&g_path, "g", g);
    if g_ok && !(g > -1.0 && g < 1.0) {
        ck.error(
            &g_path,
            format!("g must be between -1 and 1 (exclusive), found {g}"),
        );
        return None;
    }
    let (a, s) = (a?, s?);
    g_ok.then(|| Fog {
        sigma_a: a.as_vec3(),
        sigma_s: s.as_vec3(),
        g: g as f32,
    })
}
