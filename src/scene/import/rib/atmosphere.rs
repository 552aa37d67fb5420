//! `Atmosphere "fog"`: RISpec 3.2's standard volume shader onto the camera's atmosphere.
//!
//! RenderMan's `fog` blends the colour of each surface seen toward `background`:
//! `Ci = mix(Ci, background, 1 − exp(−length(I) / distance))`, `length(I)` the distance from
//! the eye in camera space. stagelight's exponential `Fade` does exactly that on every
//! camera-side segment (`L' = (1 − f)·L + f·color`, `f = 1 − e^(−d / max)`), leaving the
//! background (no surface) and the light that reaches surfaces as they are, as `fog` does;
//! so `background` becomes `color` and `distance` becomes `max`, in world units (the world
//! length of a camera-space unit: the camera transformation may scale).
//!
//! The atmosphere is an attribute in RenderMan and the camera's in stagelight: it is mapped
//! when every primitive has the same one, and otherwise ignored with a warning. Other volume
//! shaders are ignored with a warning.

use super::super::located::{Pos, Problem};
use super::build::{Builder, PendingInstance};
use super::params::{Args, ParamOwner};
use super::parse::Request;
use super::shaders::{self, FogValues};
use super::state::ShaderCall;
use crate::scene::desc::{FalloffDesc, VolumeDesc};
use crate::scene::suggest::suggestion;

/// An `Atmosphere "fog"` in effect, and where it was written (file, request).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RiFog {
    /// Its values.
    pub values: FogValues,
    /// File index and position of the request.
    pub at: (usize, Pos),
}

impl Builder {
    /// `Atmosphere name …`: the volume shader of the primitives that follow.
    pub(super) fn atmosphere(
        &mut self,
        r: &Request,
        mut a: Args<'_>,
        problems: &mut Vec<Problem>,
    ) -> Result<(), Problem> {
        let (name, npos) = a.string("shader name")?;
        let known = shaders::parameter_names("Atmosphere", &name);
        let owner = known.as_ref().map(|(what, names)| ParamOwner {
            what: what.clone(),
            names,
        });
        let params = a.params_of(&self.decls, owner.as_ref(), problems);
        self.gs.attrs.atmosphere = None;
        if name != "fog" {
            let mut w = Problem::warning(
                npos,
                format!("ignored atmosphere shader \"{name}\": only \"fog\" is mapped"),
            );
            w.help = suggestion(&name, &["fog"], "shaders").filter(|h| h.starts_with("did"));
            problems.push(w);
            return Ok(());
        }
        let call = ShaderCall {
            name,
            pos: r.pos,
            file: self.file,
            params,
        };
        self.gs.attrs.atmosphere = shaders::fog(&call, problems).map(|values| RiFog {
            values,
            at: (self.file, r.pos),
        });
        Ok(())
    }
}

/// The camera's atmosphere made of the primitives' fog, with the fog it comes from:
/// `None` when no primitive has one, or (with a warning in `problems`) when they do not all
/// have the same. `world_per_camera` is the world length of a camera-space unit.
pub(super) fn camera_atmosphere(
    instances: &[PendingInstance],
    world_per_camera: f64,
    problems: &mut Vec<(usize, Problem)>,
) -> Option<(VolumeDesc, RiFog)> {
    let first = instances.iter().find_map(|i| i.atmosphere)?;
    let with = instances.iter().filter(|i| i.atmosphere.is_some()).count();
    let why = if with < instances.len() {
        format!(
            "it applies to {with} of the {} primitives, and stagelight's atmosphere fills the \
             whole scene",
            instances.len()
        )
    } else if instances.iter().any(|i| {
        i.atmosphere
            .is_some_and(|f| !f.values.same_fog(&first.values))
    }) {
        "the primitives have fogs of different distance or background, and stagelight's \
         atmosphere is one for the whole scene"
            .to_string()
    } else {
        let (color, _) = first.values.background;
        let (distance, _) = first.values.distance;
        return Some((
            VolumeDesc::Fade {
                color,
                opacity: 1.0,
                max: distance * world_per_camera,
                falloff: FalloffDesc::Exponential,
            },
            first,
        ));
    };
    problems.push((
        first.at.0,
        Problem::warning(first.at.1, format!("ignored Atmosphere \"fog\": {why}"))
            .with_help("write one Atmosphere before the first primitive, for all of them"),
    ));
    None
}
