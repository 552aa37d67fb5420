//! Where the standalone baked glTF ([`super::gltf_export`]) puts an instance's vertices:
//! in world space under a node without a transform, or — when f32 world coordinates would
//! not keep the shape the bake traced — in render space under a node translated by the scene
//! origin.
//!
//! The renderer traces every scene in render space, world space less the scene origin
//! ([`crate::scene::rebase`]), in f32. World coordinates are render space plus the origin in
//! f64, rounded once to f32: the traced bits when the scene was not rebased (origin zero),
//! otherwise only as fine as f32 is at the instance's distance from the world origin — a
//! 1 cm patch at x = 10⁶, where f32 steps by 1/16, would round to a line or a point. The rule:
//!
//! * a scene that was not rebased is written in world space (the traced coordinates);
//! * an instance of a rebased scene is written in world space when rounding cannot change
//!   its shape: the smallest height of every traced triangle spans at least
//!   [`HEIGHT_STEPS`] (1024) f32 steps at the instance's largest world coordinate, so
//!   rounding moves a corner by less than 1/1000 of any height (a scene near the origin,
//!   rebased by a few units, keeps the file it always had);
//! * any other instance gets the node `translation` = the scene origin (a multiple of a
//!   power of two that f32 holds exactly) and its mesh the vertices less that translation
//!   — the traced render-space coordinates bit for bit: translation + vertex is the traced
//!   world position, the written triangles are the triangles the bake used, and nothing the
//!   renderer traced collapses (a glTF reader composing the two in f64, as stagelight's does,
//!   gets them back exactly).

use glam::{DVec3, Vec3};

/// The f32 steps the smallest traced triangle height must span at an instance's largest
/// world coordinate for the instance to be written in world space (2¹⁰).
pub const HEIGHT_STEPS: f64 = 1024.0;

/// The translation of the node of an instance whose traced triangles (render-space corners)
/// are `triangles`, in a scene whose origin is `origin`: zero (world coordinates) or the
/// origin rounded to f32 (which holds it exactly), by the rule of the module header.
pub fn node_translation(origin: DVec3, triangles: &[[Vec3; 3]]) -> DVec3 {
    if origin == DVec3::ZERO || keeps_shape_in_world(origin, triangles) {
        DVec3::ZERO
    } else {
        origin.as_vec3().as_dvec3()
    }
}

/// A written vertex: render-space `render` plus `origin` less the node's `translation`, in
/// f64, rounded once to f32 (the world position when the translation is zero, the
/// render-space position itself when it is the origin).
pub fn written_position(render: Vec3, origin: DVec3, translation: DVec3) -> Vec3 {
    (render.as_dvec3() + (origin - translation)).as_vec3()
}

/// Whether rounding `triangles` (render space) plus `origin` to f32 keeps their shape: every
/// triangle with area has its smallest height at least [`HEIGHT_STEPS`] f32 steps at the
/// largest world coordinate. True without a triangle with area.
fn keeps_shape_in_world(origin: DVec3, triangles: &[[Vec3; 3]]) -> bool {
    let mut reach = 0f64;
    let mut lowest = f64::INFINITY;
    for tri in triangles {
        let p = tri.map(Vec3::as_dvec3);
        for c in p {
            reach = reach.max((c + origin).abs().max_element());
        }
        let twice_area = (p[1] - p[0]).cross(p[2] - p[0]).length();
        let longest = (p[1] - p[0])
            .length()
            .max((p[2] - p[1]).length())
            .max((p[0] - p[2]).length());
        if twice_area > 0.0 && longest > 0.0 {
            lowest = lowest.min(twice_area / longest);
        }
    }
    lowest == f64::INFINITY || f32_step(reach) * HEIGHT_STEPS <= lowest
}

/// The spacing of f32 values at magnitude `x`: 2^(⌊log₂ x⌋ − 23) for a normal f32, the
/// subnormal spacing 2⁻¹⁴⁹ below.
fn f32_step(x: f64) -> f64 {
    if x < f64::from(f32::MIN_POSITIVE) {
        return 2f64.powi(-149);
    }
    2f64.powi(x.log2().floor() as i32 - 23)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square of side `side` centred on render-space `(x, 0, 0)`, as two triangles.
    fn square(x: f32, side: f32) -> Vec<[Vec3; 3]> {
        let h = side / 2.0;
        let c = |dx: f32, dy: f32| Vec3::new(x + dx, dy, 0.0);
        vec![
            [c(-h, -h), c(h, -h), c(h, h)],
            [c(-h, -h), c(h, h), c(-h, h)],
        ]
    }

    #[test]
    fn f32_steps() {
        assert_eq!(f32_step(1e6), 0.0625);
        assert_eq!(f32_step(3.75), 2f64.powi(-22));
        assert_eq!(f32_step(1.0), f64::from(f32::EPSILON));
        assert_eq!(f32_step(0.0), 2f64.powi(-149));
    }

    #[test]
    fn a_centimetre_patch_at_a_million_is_translated_by_the_origin() {
        let origin = DVec3::new(1e6, 0.0, 0.0);
        let patch = square(0.0, 0.01);
        assert_eq!(node_translation(origin, &patch), origin);
        // Its vertices are the render-space ones, bit for bit.
        let p = patch[0][0];
        assert_eq!(written_position(p, origin, origin), p);
    }

    #[test]
    fn a_floor_near_a_small_origin_stays_in_world_space() {
        // The floor of tests/it/gltf_export.rs: 1.5 wide at x = 3, rebased by 4.
        let origin = DVec3::new(4.0, 0.0, 0.0);
        let floor = square(-1.0, 1.5);
        assert_eq!(node_translation(origin, &floor), DVec3::ZERO);
        let p = floor[0][0];
        assert_eq!(
            written_position(p, origin, DVec3::ZERO),
            (p.as_dvec3() + origin).as_vec3()
        );
    }

    #[test]
    fn a_sliver_under_1024_steps_high_is_translated() {
        // A metre-wide triangle at x = 3 whose height is 500 f32 steps at 3.5 (2⁻²²):
        // rounding to world coordinates could bend it, so it keeps render space.
        let origin = DVec3::new(4.0, 0.0, 0.0);
        let step = 2f32.powi(-22);
        let sliver = [[
            Vec3::new(-1.5, 0.0, 0.0),
            Vec3::new(-0.5, 0.0, 0.0),
            Vec3::new(-1.0, 500.0 * step, 0.0),
        ]];
        assert_eq!(node_translation(origin, &sliver), origin);
        let tall = [[
            Vec3::new(-1.5, 0.0, 0.0),
            Vec3::new(-0.5, 0.0, 0.0),
            Vec3::new(-1.0, 2000.0 * step, 0.0),
        ]];
        assert_eq!(node_translation(origin, &tall), DVec3::ZERO);
    }

    #[test]
    fn a_scene_that_was_not_rebased_is_always_in_world_space() {
        assert_eq!(
            node_translation(DVec3::ZERO, &square(1e6, 0.01)),
            DVec3::ZERO
        );
        // Nothing with area: nothing to keep.
        let point = [[Vec3::ONE; 3]];
        assert_eq!(
            node_translation(DVec3::new(1e6, 0.0, 0.0), &point),
            DVec3::ZERO
        );
    }
}
