//! A material's `shadow:`, `environment:` and `photon:` shaders (mental ray's material
//! shadow, environment and photon shaders): checked and turned into `Material::shadow`,
//! `Material::environment` and `Material::photon`.

use std::sync::Arc;

use glam::Vec3;

use super::checker::Checker;
use super::desc::{DepthExceededDesc, MaterialEnvironmentDesc, PhotonShaderDesc, ShadowDesc};
use super::environment::source;
use crate::components::{DepthExceeded, MaterialEnvironment, PhotonShader};

/// The shadow transmittance of `shadow:` at `at` (`Ok(None)` when absent); `Err` after
/// recording an error.
pub fn shadow(ck: &mut Checker<'_>, at: &str, d: Option<&ShadowDesc>) -> Result<Option<Vec3>, ()> {
    let color = match d {
        None => return Ok(None),
        Some(ShadowDesc::Opaque) => return Ok(Some(Vec3::ZERO)),
        Some(ShadowDesc::Transparency { color }) => *color,
    };
    let path = format!("{at}.Transparency.color");
    let help = "a shadow shader can only dim light: 0 blocks, 1 lets all through";
    fraction(ck, &path, "shadow transparency", color, help)
        .map(Some)
        .ok_or(())
}

/// The colour `v` at `path` as a fraction per channel, each in [0, 1]; `None` after
/// recording an error (every channel above 1 located, with `help`).
fn fraction(
    ck: &mut Checker<'_>,
    path: &str,
    what: &str,
    v: super::desc_values::V3,
    help: &str,
) -> Option<Vec3> {
    let c = ck.colour(path, what, v)?;
    let mut ok = true;
    for (k, x) in c.to_array().into_iter().enumerate() {
        if x > 1.0 {
            ck.src.error(
                ck.file,
                &format!("{path}[{k}]"),
                format!("{what} must be at most 1, found {x}"),
                Some(help.into()),
            );
            ok = false;
        }
    }
    ok.then(|| c.as_vec3())
}

/// The material environment of `environment:` at `at` (`Ok(None)` when absent); `Err`
/// after recording an error.
pub fn environment(
    ck: &mut Checker<'_>,
    at: &str,
    d: Option<&MaterialEnvironmentDesc>,
) -> Result<Option<Arc<MaterialEnvironment>>, ()> {
    let Some(d) = d else {
        return Ok(None);
    };
    let intensity = ck.non_negative(&format!("{at}.intensity"), "intensity", d.intensity);
    let source = source(ck, at, &d.shader, intensity, false).ok_or(())?;
    Ok(Some(Arc::new(MaterialEnvironment {
        source,
        depth_exceeded: match d.depth_exceeded {
            DepthExceededDesc::Environment => DepthExceeded::Environment,
            DepthExceededDesc::Black => DepthExceeded::Black,
        },
    })))
}

/// The photon shader of `photon:` at `at` (`Ok(None)` when absent); `Err` after recording
/// an error.
pub fn photon(
    ck: &mut Checker<'_>,
    at: &str,
    d: Option<&PhotonShaderDesc>,
) -> Result<Option<PhotonShader>, ()> {
    let Some(PhotonShaderDesc::Caustic {
        specular,
        refraction,
        ior,
    }) = d
    else {
        return Ok(None);
    };
    let help = "it is the fraction of each photon's power that goes on";
    let mut colour =
        |field: &str, what: &str, v| fraction(ck, &format!("{at}.Caustic.{field}"), what, v, help);
    let specular = colour("specular", "photon specular colour", *specular);
    let refraction = colour("refraction", "photon refraction colour", *refraction);
    let ior_path = format!("{at}.Caustic.ior");
    let ior = ck
        .finite(&ior_path, "photon refraction index", *ior)
        .then_some(*ior);
    let ior = ior.filter(|&x| {
        if x <= 0.0 {
            ck.error(
                &ior_path,
                format!("photon refraction index must be above 0, found {x}"),
            );
        }
        x > 0.0
    });
    match (specular, refraction, ior) {
        (Some(specular), Some(refraction), Some(ior)) => Ok(Some(PhotonShader {
            specular,
            refraction,
            ior: ior as f32,
        })),
        _ => Err(()),
    }
}
