//! Checks volume shaders (`atmosphere` on a camera, `interior` on a material) and builds
//! their [`Fog`] (or the camera's [`Fade`]).

use super::desc::{CameraDesc, FalloffDesc, MaterialDesc, VolumeDesc};
use super::diagnostics::Sources;
use super::validate::{Checker, Item};
use crate::components::{DensityNoise, Fade, Falloff, Fog};

/// A camera's atmosphere: fog or a fade.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Atmosphere {
    /// A medium.
    Fog(Fog),
    /// mental ray's `mib_volume`.
    Fade(Fade),
}

/// The camera's atmosphere, if it has a valid one (errors recorded).
pub fn atmosphere(src: &mut Sources, item: &Item<'_, CameraDesc>) -> Option<Atmosphere> {
    let d = item.desc.atmosphere.as_ref()?;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let path = item.at(".atmosphere");
    match *d {
        VolumeDesc::Fade {
            color,
            opacity,
            max,
            falloff,
        } => fade(&mut ck, &path, color, opacity, max).map(|f| {
            Atmosphere::Fade(Fade {
                falloff: match falloff {
                    FalloffDesc::Linear => Falloff::Linear,
                    FalloffDesc::Exponential => Falloff::Exponential,
                },
                ..f
            })
        }),
        VolumeDesc::Fog { .. } => fog(&mut ck, &path, d).map(Atmosphere::Fog),
    }
}

/// The material's interior, if it has a valid one (errors recorded).
pub fn interior(src: &mut Sources, item: &Item<'_, MaterialDesc>) -> Option<Fog> {
    let d = item.desc.interior.as_ref()?;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let path = item.at(".interior");
    if let VolumeDesc::Fade { .. } = d {
        ck.error(
            &format!("{path}.Fade"),
            "Fade is a camera atmosphere only: a material's interior must be a Fog",
        );
        return None;
    }
    fog(&mut ck, &path, d)
}

fn fade(
    ck: &mut Checker<'_>,
    path: &str,
    color: crate::scene::desc::V3,
    opacity: f64,
    max: f64,
) -> Option<Fade> {
    let p = format!("{path}.Fade");
    let color = ck.colour(&format!("{p}.color"), "color", color);
    let opacity = Some(opacity)
        .filter(|&o| ck.finite(&format!("{p}.opacity"), "opacity", o))
        .filter(|&o| {
            let ok = (0.0..=1.0).contains(&o);
            if !ok {
                ck.error(
                    &format!("{p}.opacity"),
                    format!("opacity must be between 0 and 1, found {o}"),
                );
            }
            ok
        });
    let max = ck.non_negative(&format!("{p}.max"), "max", max);
    Some(Fade {
        color: color?.as_vec3(),
        opacity: opacity? as f32,
        max: max? as f32,
        falloff: Falloff::Linear,
    })
}

fn fog(ck: &mut Checker<'_>, path: &str, d: &VolumeDesc) -> Option<Fog> {
    let VolumeDesc::Fog {
        sigma_a,
        sigma_s,
        g,
        height,
        nonuniform,
        noise_scale,
    } = *d
    else {
        return None;
    };
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
    let height_ok = height.is_none_or(|h| ck.finite(&format!("{p}.height"), "height", h));
    let amount_path = format!("{p}.nonuniform");
    let amount = Some(nonuniform)
        .filter(|&k| ck.finite(&amount_path, "nonuniform", k))
        .filter(|&k| {
            let ok = (0.0..=1.0).contains(&k);
            if !ok {
                ck.error(
                    &amount_path,
                    format!("nonuniform must be between 0 and 1, found {k}"),
                );
            }
            ok
        });
    let scale_path = format!("{p}.noise_scale");
    let scale_ok = ck.finite(&scale_path, "noise_scale", noise_scale);
    if scale_ok && noise_scale <= 0.0 {
        ck.error(
            &scale_path,
            format!("noise_scale must be positive, found {noise_scale}"),
        );
        return None;
    }
    let (a, s, amount) = (a?, s?, amount?);
    let density = (amount > 0.0).then_some(DensityNoise {
        amount: amount as f32,
        scale: noise_scale as f32,
    });
    (g_ok && height_ok && scale_ok).then(|| Fog {
        sigma_a: a.as_vec3(),
        sigma_s: s.as_vec3(),
        g: g as f32,
        height: height.map(|h| h as f32),
        density,
    })
}
