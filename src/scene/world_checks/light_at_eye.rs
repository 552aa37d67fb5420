//! A point or spot light at the eye of a camera whose atmosphere scatters light: every camera
//! ray starts at the light, so the light it scatters toward the eye, `∫ σs·I / t² dt` from
//! `t = 0`, is infinite — the image is noise that no sample count converges (the seeds put
//! point lights at the eye; adding fog to such a scene is easy). The scene still loads; the
//! light gets a located warning.

use hecs::World;

use crate::components::{Atmosphere, Camera, Emitter, LightShape, Name, SourceLink};

/// `file:line:col: warning: …` texts, one per light at the eye of a foggy camera (entity
/// order of the lights, then of the cameras).
pub fn warnings(world: &World) -> Vec<String> {
    let eyes: Vec<(String, glam::Vec3)> = world
        .query::<(&Camera, &Atmosphere, Option<&Name>)>()
        .iter()
        .filter(|(_, a, _)| a.0.sigma_s.max_element() > 0.0)
        .map(|(c, _, n)| (name(n), c.world_from_camera.translation.into()))
        .collect();
    let mut found = Vec::new();
    for (e, link, n) in world
        .query::<(&Emitter, Option<&SourceLink>, Option<&Name>)>()
        .iter()
    {
        let position = match e.shape {
            LightShape::Point { position } | LightShape::Spot { position, .. } => position,
            _ => continue,
        };
        for (camera, eye) in &eyes {
            let scale = eye
                .abs()
                .max_element()
                .max(position.abs().max_element())
                .max(1.0);
            if position.distance(*eye) > 1e-5 * scale {
                continue;
            }
            let at = link.map_or_else(String::new, |l| {
                format!("{}:{}:{}: ", l.file.display(), l.line, l.column)
            });
            found.push(format!(
                "{at}warning: light \"{}\" is at the eye of camera \"{camera}\", whose atmosphere scatters light: \
                 the light scattered toward the eye is infinite, and the image will not converge\n  \
                 help: move the light off the eye (a small offset is enough), or use an area light",
                name(n)
            ));
        }
    }
    found
}

fn name(n: Option<&Name>) -> String {
    n.map_or_else(|| "?".to_string(), |n| n.0.clone())
}
