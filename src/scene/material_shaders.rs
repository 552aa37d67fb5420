//! A material's `shadow:` and `environment:` shaders (mental ray's material shadow and
//! environment shaders): checked and turned into `Material::shadow` and
//! `Material::environment`.

use std::sync::Arc;

use glam::Vec3;

use super::checker::Checker;
use super::desc::{DepthExceededDesc, MaterialEnvironmentDesc, ShadowDesc};
use super::environment::source;
use crate::components::{DepthExceeded, MaterialEnvironment};

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
