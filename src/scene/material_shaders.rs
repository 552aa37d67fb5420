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
    let c = ck.colour(&path, "shadow transparency", color).ok_or(())?;
    let mut ok = true;
    for (k, x) in c.to_array().into_iter().enumerate() {
        if x > 1.0 {
            ck.src.error(
                ck.file,
                &format!("{path}[{k}]"),
                format!("shadow transparency must be at most 1, found {x}"),
                Some("a shadow shader can only dim light: 0 blocks, 1 lets all through".into()),
            );
            ok = false;
        }
    }
    ok.then_some(Some(c.as_vec3())).ok_or(())
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
    let source = source(ck, at, &d.shader, intensity).ok_or(())?;
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
    let mut fraction = |field: &str, what: &str, v| {
        let path = format!("{at}.Caustic.{field}");
        let c = ck.colour(&path, what, v)?;
        let mut ok = true;
        for (k, x) in c.to_array().into_iter().enumerate() {
            if x > 1.0 {
                ck.src.error(
                    ck.file,
                    &format!("{path}[{k}]"),
                    format!("{what} must be at most 1, found {x}"),
                    Some("it is the fraction of each photon's power that goes on".into()),
                );
                ok = false;
            }
        }
        ok.then(|| c.as_vec3())
    };
    let specular = fraction("specular", "photon specular colour", *specular);
    let refraction = fraction("refraction", "photon refraction colour", *refraction);
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
