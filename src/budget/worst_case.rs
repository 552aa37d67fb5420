//! The worst case of adaptive approximations, for `check`. A spatial or curvature
//! approximation's triangle count is known only once the surface is diced, but its bound is
//! known at load: every patch edge at `2^max_subdiv` segments, `2 · patches · 4^max_subdiv`
//! triangles. Adaptive rates usually stay far below it, so exceeding the budget there is a
//! located warning, not a refusal: the tessellator refuses the object (under the same
//! [`max_triangles`] limit) only if its rates do reach past the budget.
//!
//! Subdivision meshes and displaced polygon meshes are left out: their bound (every refined
//! face or every triangle diced at the finest rate) is past any budget for ordinary
//! scenes, so a warning would say nothing.

use hecs::{Entity, World};

use super::estimate::{
    approximation_at, approximation_of, max_triangles, surface_patches, BYTES_PER_TRIANGLE,
};
use super::{human, Budget};
use crate::components::{Instance, Name, Technique};
use crate::scene::import::syntax_of;
use crate::scene::syntax::Helps;
use crate::scene::Diagnostic;
use crate::tessellation::rates::MAX_LEVEL;

/// Triangles of `patches` patches with every edge at `2^level` segments.
fn worst(patches: u64, level: u32) -> u64 {
    patches
        .saturating_mul(2)
        .saturating_mul(1u64 << (2 * level))
}

/// A located warning for every placed object with an adaptive approximation whose worst
/// case exceeds the triangles the budget allows one object, in entity order.
pub fn warnings(world: &World, budget: &Budget) -> Vec<Diagnostic> {
    let limit = max_triangles(budget);
    let mut objects: Vec<Entity> = world
        .query::<&Instance>()
        .iter()
        .map(|i| i.object)
        .collect();
    objects.sort_by_key(|e| e.to_bits());
    objects.dedup();
    let mut out = Vec::new();
    for object in objects {
        let approx = approximation_of(world, object);
        if matches!(
            approx.technique,
            Technique::Parametric { .. } | Technique::Regular { .. }
        ) {
            continue;
        }
        let Some(patches) = surface_patches(world, object) else {
            continue;
        };
        // The tessellator's levels: `max_subdiv` clamped to `min_subdiv..=MAX_LEVEL`.
        let min_level = approx.min_subdiv.min(MAX_LEVEL);
        let level = approx.max_subdiv.clamp(min_level, MAX_LEVEL);
        let triangles = worst(patches, level);
        if triangles <= limit {
            continue;
        }
        let name = world
            .get::<&Name>(object)
            .map_or_else(|_| "?".to_string(), |n| n.0.clone());
        let (file, line, column) = approximation_at(world, object)
            .map_or((Default::default(), 1, 1), |l| (l.file, l.line, l.column));
        let segments = 1u64 << level;
        let fitting = (min_level..level)
            .rev()
            .find(|&l| worst(patches, l) <= limit);
        let syntax = syntax_of(&file);
        // The subdivision bound as the scene's format sets it: RON's `max_subdiv`, the `.mi`
        // `approximate` statement's max, the subdivisions a RIB `ShadingRate` allows.
        let at_level = syntax.help_each(Helps {
            ron: &format!("at max_subdiv {level}"),
            mi: &format!("at the `approximate` statement's max subdivision {level}"),
            rib: &format!("at the {level} subdivisions a `ShadingRate` allows"),
            gltf: &format!("at max_subdiv {level}"),
        });
        let help = match fitting {
            Some(l) => {
                let at_most = worst(patches, l);
                let min = approx.min_subdiv;
                let bound = syntax.help_each(Helps {
                    ron: &format!("set `max_subdiv: {l}` (at most {at_most} triangles)"),
                    mi: &format!("end the `approximate` technique with the subdivision bounds `{min} {l}` (at most {at_most} triangles)"),
                    rib: &format!("write the scene as RON and set `max_subdiv: {l}` there (at most {at_most} triangles; a RIB `ShadingRate` subdivides up to {level} times)"),
                    gltf: &format!("set `max_subdiv: {l}` (at most {at_most} triangles)"),
                });
                format!("adaptive rates usually stay far below this bound; to be sure it fits, {bound}, or raise the budget with --memory-limit BYTES")
            }
            None => "adaptive rates usually stay far below this bound; to be sure it fits, coarsen the approximation, or raise the budget with --memory-limit BYTES".to_string(),
        };
        out.push(Diagnostic {
            file,
            line,
            column,
            message: format!(
                "object \"{name}\": its adaptive approximation may make up to {triangles} triangles ({patches} patch(es) × {segments}² {at_level}, about {}), more than the {limit} the memory budget of {budget} allows one object; render refuses it if dicing makes more",
                human(triangles.saturating_mul(BYTES_PER_TRIANGLE))
            ),
            help: Some(help),
        });
    }
    out
}
