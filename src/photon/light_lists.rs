//! Light lists in the photon pass: a surface whose material names the only lights that light
//! it (`lights: [...]`, mental ray's `"lights"`) receives photons from those lights only — the
//! rule the light loop applies ([`crate::components::Material::sees_light`]), so a material
//! that leaves a light out gets neither its direct light nor its caustic or global photons.
//!
//! The list decides what the surface *receives*, not what passes through it: a photon from a
//! listed-out light is not stored there but scatters on as before (mirror and glass paths
//! through such a material are not limited by its list in shading either). Every other
//! surface therefore stores exactly the photons it stores without the list.
//!
//! The emitting light is known where the photon is emitted
//! ([`super::emit::Emission::light_index`] for the sample's `u[0]`); the deposit names the
//! triangle it landed on ([`super::trace::Deposit::prim`]); the pass keeps the deposit when
//! [`ReceiverLights::admits`] says so.

use crate::geometry::SceneGeometry;

/// Which surfaces receive photons from which lights.
#[derive(Clone, Copy)]
pub struct ReceiverLights<'a> {
    geometry: &'a SceneGeometry,
    /// Whether some material has a light list (otherwise every deposit is kept, no lookup).
    any_list: bool,
}

impl<'a> ReceiverLights<'a> {
    /// The light lists of `geometry`'s materials.
    pub fn new(geometry: &'a SceneGeometry) -> Self {
        Self {
            geometry,
            any_list: geometry.materials.iter().any(|m| m.lights.is_some()),
        }
    }

    /// Whether world triangle `prim` receives photons from light `light` (index in the light
    /// set).
    pub fn admits(&self, prim: u32, light: usize) -> bool {
        !self.any_list || self.geometry.material_of(prim).sees_light(light)
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::shading::integrator::fixture::{self, Object};

    #[test]
    fn a_listed_material_admits_only_its_lights_and_others_admit_all() {
        let mut listed = fixture::lambert(0.5);
        listed.lights = Some(Arc::from(vec![0u32, 2]));
        let geometry = fixture::geometry(vec![
            Object {
                triangles: fixture::floor(1.0, 0.0),
                material: listed,
            },
            Object {
                triangles: fixture::floor(1.0, 1.0),
                material: fixture::lambert(0.5),
            },
        ]);
        let lists = ReceiverLights::new(&geometry);
        let (first, second) = (0u32, geometry.triangle_count() as u32 - 1);
        assert!(geometry.material_of(first).lights.is_some());
        assert_eq!(
            (0..4).map(|l| lists.admits(first, l)).collect::<Vec<_>>(),
            [true, false, true, false]
        );
        assert!((0..4).all(|l| lists.admits(second, l)));
        let plain = fixture::geometry(vec![Object {
            triangles: fixture::floor(1.0, 0.0),
            material: fixture::lambert(0.5),
        }]);
        assert!(!ReceiverLights::new(&plain).any_list);
    }
}
