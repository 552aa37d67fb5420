//! Rebasing scenes far from the origin (hard case H5): everything the renderer traces is in
//! *render space*, world space shifted by a scene origin chosen at load time, so that the
//! f32 hot path never sees large coordinates.
//!
//! * **The origin** is the centre of the scene bounds: the world-space bounding box of every
//!   placed mesh (generated geometry, which does not exist yet at load time, counts by its
//!   object origin), computed in f64 and rounded to a multiple of the smallest power of two
//!   at least twice the bounds' extent ([`snap`]). A scene near the world origin therefore
//!   keeps origin zero and is loaded exactly as written; a far one is shifted by a round
//!   number, so that translating a scene by a multiple of that power of two renders the very
//!   same image.
//! * **Instance transforms** are composed along the DAG in f64 ([`super::dag`]); the origin is
//!   subtracted from the composed f64 translation, and only then is the transform rounded to
//!   f32.
//! * **Mesh vertices** given far from their object's origin (inline or OBJ meshes whose
//!   bounding box is not within its own size of the object origin) are re-centred in f64 by
//!   the [`snap`]ped centre of their bounds before rounding to f32; the centre moves into the instance
//!   transforms, again in f64. Meshes used by scatters (as surface or prototype) keep their
//!   object space, since scatter placements are made in it.
//! * **Cameras and lights**: eye, target, camera-matrix translation, light positions, spot
//!   targets, rect corners, disc and sphere centres and cylinder end points are shifted in
//!   f64 before validation rounds them.
//!
//! The origin is kept in the world as a [`crate::components::SceneOrigin`] entity; outputs that
//! expose absolute positions (the bake `positions` kind) add it back. Directions, distances
//! (`depth`) and normals are unaffected. Shading sees render-space positions.

use glam::{Affine3A, DVec3, Vec3};

use super::dag::Leaf;
use super::desc::{CameraDesc, LightDesc, LightKindDesc, PlacementDesc, V3};

/// Positions of a mesh in f64 → object-space f32 positions and the object-space offset that
/// was subtracted ([`snap`] of the bounds centre: zero when the mesh lies near its origin).
pub fn centre_positions(positions: &[DVec3]) -> (Vec<Vec3>, DVec3) {
    // Only points that fit in f32 count: a hostile vertex (1e300) is dropped later anyway and
    // must not drag the centre away from the rest.
    let fits = positions
        .iter()
        .copied()
        .filter(|p| p.as_vec3().is_finite());
    let offset = bounds(fits).map_or(DVec3::ZERO, |(lo, hi)| snap(lo, hi));
    let rounded = positions.iter().map(|&p| (p - offset).as_vec3()).collect();
    (rounded, offset)
}

/// The origin for a bounding box: its centre rounded to the nearest multiple of `G`, the
/// smallest power of two at least twice the box's largest extent (at least 2⁻²⁰ of the
/// centre's magnitude, for a box that is a point). So a box within `G/2` of zero keeps
/// origin zero (a scene near the origin is left exactly as it is), coordinates relative to
/// the origin stay within about twice the extent, and translating the box by a multiple of
/// `G` translates the origin by exactly as much. Zero for non-finite input.
pub fn snap(lo: DVec3, hi: DVec3) -> DVec3 {
    let centre = (lo + hi) * 0.5;
    let size = (2.0 * (hi - lo).max_element()).max(centre.abs().max_element() * 2f64.powi(-20));
    if !centre.is_finite() || !size.is_finite() || size <= 0.0 {
        return DVec3::ZERO;
    }
    let grid = 2f64.powi(size.log2().ceil() as i32);
    let snapped = (centre / grid).round() * grid;
    if snapped.is_finite() {
        snapped
    } else {
        DVec3::ZERO
    }
}

/// Object-space bounding box of a mesh's positions (`None` when it has none).
pub fn mesh_bounds(mesh: &crate::components::TriMesh) -> Option<(DVec3, DVec3)> {
    bounds(mesh.positions.iter().map(|p| p.as_dvec3()))
}

/// Bounding box of the finite points, if any.
fn bounds(points: impl Iterator<Item = DVec3>) -> Option<(DVec3, DVec3)> {
    points
        .filter(|p| p.is_finite())
        .fold(None, |acc, p| match acc {
            None => Some((p, p)),
            Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
        })
}

/// The scene origin: the centre of the world bounds of the placed leaves, [`snap`]ped.
/// `object_bounds[o]` is object `o`'s
/// object-space bounding box, `None` for generated geometry (counted as its origin point).
/// Zero when there is nothing placed, the bounds are not finite, or the scene lies near the
/// origin.
pub fn scene_origin(leaves: &[Leaf], object_bounds: &[Option<(DVec3, DVec3)>]) -> DVec3 {
    let mut boxes = Vec::with_capacity(leaves.len() * 2);
    for leaf in leaves {
        let (lo, hi) = object_bounds
            .get(leaf.object)
            .copied()
            .flatten()
            .unwrap_or((DVec3::ZERO, DVec3::ZERO));
        let c = (lo + hi) * 0.5;
        let h = (hi - lo) * 0.5;
        let m = leaf.world.matrix3;
        let wc = leaf.world.transform_point3(c);
        let wh = m.x_axis.abs() * h.x + m.y_axis.abs() * h.y + m.z_axis.abs() * h.z;
        boxes.push(wc - wh);
        boxes.push(wc + wh);
    }
    bounds(boxes.into_iter()).map_or(DVec3::ZERO, |(lo, hi)| snap(lo, hi))
}

/// Rounds every leaf's f64 transform, less `origin`, to its f32 `world_from_object`. Returns
/// false, changing nothing, when some rebased transform does not fit in f32 or is singular
/// there.
pub fn rebase_leaves(leaves: &mut [Leaf], origin: DVec3) -> bool {
    let rebased: Option<Vec<Affine3A>> = leaves
        .iter()
        .map(|leaf| {
            let t = leaf.world.translation - origin;
            let a = Affine3A::from_mat3_translation(leaf.world.matrix3.as_mat3(), t.as_vec3());
            (a.is_finite() && a.matrix3.determinant() != 0.0).then_some(a)
        })
        .collect();
    let Some(rebased) = rebased else {
        return false;
    };
    for (leaf, a) in leaves.iter_mut().zip(rebased) {
        leaf.world_from_object = a;
    }
    true
}

/// `v − origin` for a finite point; a non-finite one is left as written (validation reports
/// it with the value the user wrote).
fn shift(v: V3, origin: DVec3) -> V3 {
    let p = DVec3::new(v.0, v.1, v.2);
    if !p.is_finite() {
        return v;
    }
    let q = p - origin;
    (q.x, q.y, q.z)
}

/// The camera with its position (and look-at target) moved into render space.
pub fn camera(desc: &CameraDesc, origin: DVec3) -> CameraDesc {
    let mut out = desc.clone();
    out.placement = match &desc.placement {
        PlacementDesc::LookAt { eye, target, up } => PlacementDesc::LookAt {
            eye: shift(*eye, origin),
            target: shift(*target, origin),
            up: *up,
        },
        PlacementDesc::Matrix(m) => {
            let mut m = *m;
            let t = shift((m[0][3], m[1][3], m[2][3]), origin);
            (m[0][3], m[1][3], m[2][3]) = t;
            PlacementDesc::Matrix(m)
        }
    };
    out
}

/// The light with its positions moved into render space (directions are unchanged).
pub fn light(desc: &LightDesc, origin: DVec3) -> LightDesc {
    let mut out = desc.clone();
    match &mut out.kind {
        LightKindDesc::Point { position } => *position = shift(*position, origin),
        LightKindDesc::Spot {
            position, target, ..
        } => {
            *position = shift(*position, origin);
            *target = shift(*target, origin);
        }
        LightKindDesc::Directional { .. } | LightKindDesc::Ambient => {}
        LightKindDesc::Rect { corner, .. } => *corner = shift(*corner, origin),
        LightKindDesc::Disc { center, .. } | LightKindDesc::Sphere { center, .. } => {
            *center = shift(*center, origin);
        }
        LightKindDesc::Cylinder { start, end, .. } => {
            *start = shift(*start, origin);
            *end = shift(*end, origin);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DAffine3;

    #[test]
    fn near_meshes_keep_their_object_space() {
        let p = [
            DVec3::ZERO,
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(2.0, 0.0, 0.0),
        ];
        let (rounded, offset) = centre_positions(&p);
        assert_eq!(offset, DVec3::ZERO);
        assert_eq!(rounded[1], Vec3::ONE);
    }

    #[test]
    fn far_meshes_are_centred_in_f64() {
        let t = 1e6 + 0.1;
        let p = [
            DVec3::splat(t),
            DVec3::splat(t + 1.0),
            DVec3::new(t, t + 0.5, t),
        ];
        let (rounded, offset) = centre_positions(&p);
        assert_eq!(offset, DVec3::splat(1e6));
        assert_eq!(rounded[0], Vec3::splat(0.1));
        assert_eq!(
            rounded[2],
            Vec3::new((t - 1e6) as f32, (t + 0.5 - 1e6) as f32, 0.1)
        );
    }

    #[test]
    fn origin_moves_exactly_with_a_round_translation() {
        let leaf = |t: f64| Leaf {
            path: "root/a".into(),
            instance: 0,
            object: 0,
            world_from_object: Affine3A::IDENTITY,
            world: DAffine3::from_translation(DVec3::splat(t)),
            material: None,
            photon: Default::default(),
            rays: Default::default(),
        };
        let b = [Some((DVec3::ZERO, DVec3::new(1.0, 0.75, 1.0)))];
        assert_eq!(scene_origin(&[leaf(0.0)], &b), DVec3::ZERO);
        for t in [1e3, 1e4, 1e5, 1e6] {
            assert_eq!(scene_origin(&[leaf(t)], &b), DVec3::splat(t));
        }
        assert_eq!(scene_origin(&[], &b), DVec3::ZERO);
        // A point far away (generated geometry) still moves the origin.
        let point = [None];
        assert_eq!(scene_origin(&[leaf(1e6)], &point), DVec3::splat(1e6));
        assert_eq!(snap(DVec3::NAN, DVec3::ONE), DVec3::ZERO);
    }
}
