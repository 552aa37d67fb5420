//! Which surfaces cast and receive the photons of each map (mental ray `caustic` /
//! `globillum` flags), resolved per placed instance, and the bounds of the caustic casters
//! that aimed emission shoots at.
//!
//! **Defaults** (an instance without an explicit flag, see `docs/scene-format.md`):
//! - caustic map: a surface whose material can scatter specularly (mirror, glass,
//!   transparency, a mirror term) casts; every surface receives (a photon is stored only
//!   where the material has a non-specular lobe); a material's photon shader decides both
//!   instead (casts where it reflects or refracts, receives where it stores);
//! - global map: every surface casts and receives.
//!
//! A photon reaching a surface that does not cast for its map is absorbed there; one
//! reaching a surface that does not receive is not stored there.

use glam::Vec3;

use super::pass::MapKind;
use crate::components::{Material, PhotonFlags, PhotonRole, Shader};
use crate::geometry::SceneGeometry;

/// Whether `shader` has a specular (delta) lobe: mirror, refraction or pass-through.
pub fn scatters_specularly(shader: &Shader) -> bool {
    match shader {
        Shader::Opacity { .. } => true,
        other => makes_caustics(other),
    }
}

/// Whether `shader` has a specular lobe that changes a photon's direction (mirror or
/// refraction): a pass-through leaves it unchanged and makes no caustic (shadow rays carry
/// that light; see [`super::trace`]).
pub fn makes_caustics(shader: &Shader) -> bool {
    match shader {
        Shader::Mirror { .. }
        | Shader::Dielectric { .. }
        | Shader::ShinyMetal { .. }
        | Shader::Dgs { .. }
        | Shader::Local(_) => true,
        Shader::Opacity { input, .. } => makes_caustics(input),
        _ => false,
    }
}

/// The caustic role of a material without an explicit flag: with a photon shader, casts
/// where it reflects or refracts photons and receives where it stores them.
pub fn default_caustic_role(material: &Material) -> PhotonRole {
    if let Some(p) = &material.photon {
        return PhotonRole(u8::from(p.scatters()) | (u8::from(p.stores()) << 1));
    }
    if scatters_specularly(&material.shader) {
        PhotonRole::BOTH
    } else {
        PhotonRole::RECEIVES
    }
}

/// Each instance's role for each map, by instance slot of the scene geometry.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PhotonRoles {
    caustic: Vec<PhotonRole>,
    global: Vec<PhotonRole>,
    /// Whether the instance's caustic role comes from an explicit flag.
    explicit_caustic: Vec<bool>,
}

impl PhotonRoles {
    /// The roles of `geometry`'s instances; `flags(slot)` gives an instance's explicit flags.
    pub fn new(geometry: &SceneGeometry, flags: impl Fn(usize) -> Option<PhotonFlags>) -> Self {
        let mut roles = Self::default();
        for (slot, inst) in geometry.instances.iter().enumerate() {
            // An instance whose polygons have several materials casts when any of them does.
            let role = inst
                .material_slots()
                .into_iter()
                .map(|m| default_caustic_role(&geometry.materials[m as usize]))
                .max_by_key(|r| r.casts())
                .unwrap_or(PhotonRole::RECEIVES);
            let f = flags(slot).unwrap_or_default();
            roles.caustic.push(f.caustic.unwrap_or(role));
            roles.global.push(f.globillum.unwrap_or(PhotonRole::BOTH));
            roles.explicit_caustic.push(f.caustic.is_some());
        }
        roles
    }

    /// Roles of every instance for `kind`'s map (indexed by instance slot).
    pub fn for_map(&self, kind: MapKind) -> &[PhotonRole] {
        match kind {
            MapKind::Caustics => &self.caustic,
            MapKind::Global => &self.global,
        }
    }

    /// Instance slots where a caustic path can begin: explicit casters, and default casters
    /// whose material makes caustics.
    pub fn caustic_casters(&self, geometry: &SceneGeometry) -> Vec<usize> {
        (0..self.caustic.len())
            .filter(|&slot| {
                let inst = &geometry.instances[slot];
                self.caustic[slot].casts()
                    && (self.explicit_caustic[slot]
                        || inst.material_slots().into_iter().any(|m| {
                            let material = &geometry.materials[m as usize];
                            match &material.photon {
                                Some(p) => p.scatters(),
                                None => makes_caustics(&material.shader),
                            }
                        }))
            })
            .collect()
    }
}

/// A sphere around instance `slot`'s world triangles: the centre of their bounding box and
/// the largest distance of a vertex from it (tight for round shapes). `None` without
/// triangles.
pub fn instance_sphere(geometry: &SceneGeometry, slot: usize) -> Option<(Vec3, f32)> {
    let inst = &geometry.instances[slot];
    let first = inst.first_triangle;
    let count = inst.mesh.triangles.len() as u32;
    let corners = (first..first + count).flat_map(|prim| geometry.accel.triangle(prim));
    let (lo, hi) = corners.clone().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    if lo.cmpgt(hi).any() || !lo.is_finite() || !hi.is_finite() {
        return None;
    }
    let centre = 0.5 * (lo + hi);
    let radius = corners.fold(0.0f32, |r, p| r.max((p - centre).length()));
    // Rounding of the vertices' world positions: keep every vertex inside.
    Some((
        centre,
        radius * (1.0 + 1e-5) + 1e-6 * centre.abs().max_element(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::integrator::fixture::{self, Object};

    #[test]
    fn specular_materials_cast_caustics_and_flags_override_defaults() {
        let glass = fixture::material(Shader::Dielectric {
            ior: 1.5,
            ior_out: 1.0,
            col: Vec3::ONE,
        });
        let geometry = fixture::geometry(vec![
            Object {
                triangles: fixture::floor(2.0, 0.0),
                material: fixture::lambert(0.5),
            },
            Object {
                triangles: fixture::inward_cube(0.5),
                material: glass,
            },
        ]);
        let roles = PhotonRoles::new(&geometry, |_| None);
        assert_eq!(
            roles.for_map(MapKind::Caustics),
            &[PhotonRole::RECEIVES, PhotonRole::BOTH]
        );
        assert_eq!(roles.for_map(MapKind::Global), &[PhotonRole::BOTH; 2]);
        assert_eq!(roles.caustic_casters(&geometry), vec![1]);
        // caustic 0 on the glass, caustic 1 on the floor: the floor is aimed at instead.
        let flags = |slot: usize| {
            Some(PhotonFlags {
                caustic: Some(PhotonRole([1, 0][slot])),
                globillum: None,
            })
        };
        let roles = PhotonRoles::new(&geometry, flags);
        assert_eq!(roles.caustic_casters(&geometry), vec![0]);
        // The cube's sphere holds its corners: centre 0, radius √3·0.5.
        let (c, r) = instance_sphere(&geometry, 1).unwrap();
        assert!(
            c.length() < 1e-6 && (r - 0.75f32.sqrt()).abs() < 1e-4,
            "{c} {r}"
        );
    }
}
