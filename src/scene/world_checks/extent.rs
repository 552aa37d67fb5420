//! The coordinate range the renderer supports (issue 18, family 1).
//!
//! Rays are traced in `f32` render space (world space less the scene origin, see
//! `scene::rebase`). The watertight triangle test multiplies three coordinate differences
//! (`t_scaled = e·z`, a cube of the scene extent) and the BVH builder sums products of two
//! (surface areas), so a render-space coordinate beyond [`MAX_COORDINATE`] makes those
//! overflow to infinity: hits are lost, and obvhs's CWBVH conversion indexes out of bounds.
//! Every placed triangle must therefore lie within `±MAX_COORDINATE` of the scene origin;
//! since far scenes are rebased, only the scene's *extent* counts (up to `2·MAX_COORDINATE`).
//!
//! Meshes known at load (inline, OBJ, PLY) are checked by [`check_world`] (so `check`
//! refuses them), generated objects by their transform there and by their triangles in
//! `build_accel` ([`out_of_range`]).

use std::collections::BTreeMap;

use glam::{Affine3A, Vec3};
use hecs::{Entity, World};

use crate::components::{Instance, Name, SourceLink, WorldFromObject};
use crate::scene::Diagnostic;

/// The largest render-space coordinate magnitude a placed vertex may have: (2·10¹²)³ ≈ 8·10³⁶
/// stays well below `f32::MAX` ≈ 3.4·10³⁸.
pub const MAX_COORDINATE: f32 = 1.0e12;

/// The largest coordinate magnitude among `points` (infinity when one is not finite).
pub fn reach(points: impl Iterator<Item = Vec3>) -> f32 {
    points.fold(0.0f32, |m, p| {
        if p.is_finite() {
            m.max(p.abs().max_element())
        } else {
            f32::INFINITY
        }
    })
}

/// Whether a reach is beyond what the renderer supports.
pub fn out_of_range(reach: f32) -> bool {
    reach.is_nan() || reach > MAX_COORDINATE
}

/// The error for an object whose placed geometry reaches `reach`, at the object's position.
pub fn diagnostic(object: &str, at: Option<&SourceLink>, reach: f32) -> Diagnostic {
    let reach = if reach.is_finite() {
        format!("{reach:.1e}")
    } else {
        "beyond the f32 range".to_string()
    };
    let (file, line, column) = at.map_or((Default::default(), 1, 1), |l| {
        (l.file.clone(), l.line, l.column)
    });
    Diagnostic {
        file,
        line,
        column,
        message: format!(
            "object \"{object}\": its placed geometry reaches {reach} units from the scene origin; \
             the supported scene extent is ±{MAX_COORDINATE:.0e} units around it"
        ),
        help: Some(
            "scale the scene down (far-away scenes are rebased automatically: only the extent \
             counts), or leave out the distant geometry"
                .into(),
        ),
    }
}

/// How far a generated object placed by `xf` reaches before it exists: its transform's
/// translation and scale (a unit of object space placed beyond the range is out of range).
fn transform_reach(xf: &Affine3A) -> f32 {
    let m = xf.matrix3;
    reach(
        [
            xf.translation.into(),
            m.x_axis.into(),
            m.y_axis.into(),
            m.z_axis.into(),
        ]
        .into_iter(),
    )
}

/// Checks every placed instance of the loaded world; one error per object, in entity order.
pub fn check_world(world: &World) -> Vec<Diagnostic> {
    let mut worst: BTreeMap<u64, (Entity, f32)> = BTreeMap::new();
    for (instance, xf) in world.query::<(&Instance, &WorldFromObject)>().iter() {
        let xf = xf.0;
        let r = if instance.mesh.positions.is_empty() {
            transform_reach(&xf)
        } else {
            reach(
                instance
                    .mesh
                    .positions
                    .iter()
                    .map(|&p| xf.transform_point3(p)),
            )
        };
        if out_of_range(r) {
            let e = worst
                .entry(instance.object.to_bits().get())
                .or_insert((instance.object, r));
            e.1 = e.1.max(r);
        }
    }
    worst
        .into_values()
        .map(|(object, r)| located(world, object, r))
        .collect()
}

/// The diagnostic for `object` (an entity with `Name` and `SourceLink`).
pub fn located(world: &World, object: Entity, reach: f32) -> Diagnostic {
    let name = world
        .get::<&Name>(object)
        .map_or_else(|_| "?".to_string(), |n| n.0.clone());
    let link = world.get::<&SourceLink>(object).ok().map(|l| (*l).clone());
    diagnostic(&name, link.as_ref(), reach)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reach_and_range() {
        let pts = [Vec3::new(1.0, -3.0, 2.0), Vec3::new(0.5, 0.0, -2.5)];
        assert_eq!(reach(pts.into_iter()), 3.0);
        assert!(!out_of_range(MAX_COORDINATE));
        assert!(out_of_range(1.0e13));
        assert!(out_of_range(f32::INFINITY));
        assert!(out_of_range(f32::NAN));
        assert_eq!(
            reach([Vec3::new(f32::INFINITY, 0.0, 0.0)].into_iter()),
            f32::INFINITY
        );
    }
}
