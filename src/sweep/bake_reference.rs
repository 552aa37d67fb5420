//! What a bake sweep's rendered reference is, in words (the progress line and `sweep.json`'s
//! `"reference"`): the scene's own bakes at `--reference-spp` rays (ambient occlusion) or
//! gather paths (indirect lightmaps) per texel — not a path-traced image.

use hecs::World;

use crate::components::{BakeKind, BakeRequest};
use crate::settings::Integrator;

/// `AO bake, 256 rays per texel`; `lightmap bake, 256 gather paths per texel, indirect light
/// path-traced`; or both kinds, as the bake requests of `world` have them.
pub fn describe(world: &World, samples: u32, integrator: Integrator) -> String {
    let (mut ao, mut lightmap) = (false, false);
    for request in world.query::<&BakeRequest>().iter() {
        for t in &request.targets {
            match t.kind {
                BakeKind::AmbientOcclusion { .. } => ao = true,
                BakeKind::Lightmap { indirect: true, .. } => lightmap = true,
                _ => {}
            }
        }
    }
    let traced = match integrator {
        Integrator::Path => ", indirect light path-traced",
        Integrator::Direct => "",
    };
    match (ao, lightmap) {
        (true, false) => format!("AO bake, {samples} rays per texel"),
        (false, true) => format!("lightmap bake, {samples} gather paths per texel{traced}"),
        _ => format!(
            "AO and lightmap bakes, {samples} rays (AO) and gather paths (lightmaps) per texel{traced}"
        ),
    }
}
