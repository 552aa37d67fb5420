//! Helps of the command line's refusals that say what to write in the scene, in the scene
//! file's own format: what RON, `.mi` and RIB write for it, and for what a format cannot
//! say, the `stagelight convert` to RON first.

use std::path::Path;

use crate::scene::syntax::{convert_command, Helps, Syntax};

/// How the scene file `scene`, written in `syntax`, turns a photon map on: RON's
/// `caustics:`/`global_illumination:` options, `.mi`'s `caustic on`/`globillum on`, RIB's
/// AIR caustic light; a glTF file has none, so its help converts the scene to RON.
pub fn photon_maps_help(syntax: Syntax, scene: &Path) -> String {
    let ron = "turn on `caustics: (…)` or `global_illumination: (…)` in the scene's options";
    syntax.help_each(Helps {
        ron,
        mi: "add `caustic on` or `globillum on` to the options block",
        rib: "add AIR's caustic light, `LightSource \"caustic\" 1`, which turns the caustic photon map on",
        gltf: &format!(
            "glTF has no photon maps: write the scene as RON (`{}`) and {ron} there",
            convert_command(scene)
        ),
    })
}
