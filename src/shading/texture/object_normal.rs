//! Object-space shading normals (`bump: (object_normal: …)`): a node graph gives the
//! shading normal in the object's own space, as a RenderMan shader does that sets
//! `Nf = ntransform("object", "current", normal(…))` (the seed's `stairs`, §4.2).
//!
//! The normal is a direction, not a side: it is transformed like the object's normals (the
//! instance's inverse transpose), normalised and turned onto the side of the geometric
//! normal, as interpolated vertex normals are, so the shading step turns it toward the
//! viewer with the rest (a two-sided surface seen from behind is shaded with its
//! negation). A value that gives no direction — zero, not finite, or in the surface's
//! tangent plane — keeps the unperturbed normal.
//!
//! Under a local illumination model (`Local`, alone or under `Opacity`) the normal is used
//! exactly as given ([`is_local`]): the model evaluates its formula for any normal, as the
//! shading language does. Under a BSDF it is made safe like every bent normal (hard case
//! H11: rotated toward the geometric normal until the view's mirror direction is above the
//! surface), so no point renders black.

use glam::{Mat3A, Vec3, Vec3A};

use crate::components::Shader;

/// Whether `shader` is a local illumination model (alone or under `Opacity`), which shades
/// with an object-space normal exactly as given.
pub fn is_local(shader: &Shader) -> bool {
    match shader {
        Shader::Local(_) => true,
        Shader::Opacity { input, .. } => matches!(**input, Shader::Local(_)),
        _ => false,
    }
}

/// The world-space shading normal of the object-space `object` under `normal_from_object`,
/// on the side of the unit geometric normal `ng`; `n` (the unperturbed normal) where it
/// gives no direction.
pub fn to_world(normal_from_object: Mat3A, object: Vec3, ng: Vec3, n: Vec3) -> Vec3 {
    let m = Vec3::from((normal_from_object * Vec3A::from(object)).normalize_or_zero());
    let side = m.dot(ng);
    if m == Vec3::ZERO || !m.is_finite() || side == 0.0 || !side.is_finite() {
        n
    } else if side < 0.0 {
        -m
    } else {
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_normal_is_transformed_normalised_and_kept_on_the_geometric_side() {
        // A non-uniform scale: object normals go by the inverse transpose.
        let normal_from_object = Mat3A::from_diagonal(glam::Vec3::new(0.5, 1.0, 1.0));
        let m = to_world(
            normal_from_object,
            Vec3::new(2.0, 0.0, 2.0),
            Vec3::Z,
            Vec3::Z,
        );
        assert!(
            (m - Vec3::new(1.0, 0.0, 2.0).normalize()).length() < 1e-6,
            "{m}"
        );
        // Facing away from the geometric normal: turned onto its side.
        let m = to_world(
            Mat3A::IDENTITY,
            Vec3::new(0.0, -1.0, -1.0),
            Vec3::Z,
            Vec3::Z,
        );
        assert!(
            (m - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6,
            "{m}"
        );
    }

    #[test]
    fn no_direction_keeps_the_unperturbed_normal() {
        let n = Vec3::new(0.0, 0.6, 0.8);
        assert_eq!(to_world(Mat3A::IDENTITY, Vec3::ZERO, Vec3::Z, n), n);
        assert_eq!(to_world(Mat3A::IDENTITY, Vec3::X, Vec3::Z, n), n);
        let nan = Vec3::new(f32::NAN, 0.0, 1.0);
        assert_eq!(to_world(Mat3A::IDENTITY, nan, Vec3::Z, n), n);
    }
}
