//! Every material's BSDF, seen from the front and from the back, made once per render.
//!
//! A hit on a material whose shader no texture drives has the BSDF of the material's own
//! shader ([`Bsdf::new`] of it and the face), the same at every point, so integrators read
//! it here instead of rebuilding it per vertex (collecting, clamping and weighting the
//! lobes). Textured hits still build theirs. The values are made by the same code, so
//! images are the same bit for bit.

use crate::geometry::SceneGeometry;
use crate::shading::bsdf::Bsdf;

/// The BSDF of each material slot of a scene, `[back, front]`.
#[derive(Debug, Clone)]
pub struct MaterialBsdfs(Vec<[Bsdf; 2]>);

impl MaterialBsdfs {
    /// The BSDFs of `g`'s materials (one that reflects nothing where [`Bsdf::new`] gives
    /// `None`, see [`Bsdf::set_shader`]).
    pub fn new(g: &SceneGeometry) -> Self {
        let face = |shader, front| {
            let mut b = Bsdf::empty();
            b.set_shader(shader, front);
            b
        };
        Self(
            g.materials
                .iter()
                .map(|m| [face(&m.shader, false), face(&m.shader, true)])
                .collect(),
        )
    }

    /// The BSDF of material slot `material` seen from the front (`front`) or back face.
    #[inline]
    pub fn get(&self, material: u32, front: bool) -> &Bsdf {
        &self.0[material as usize][usize::from(front)]
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::components::Shader;
    use crate::shading::integrator::fixture::{self, Object};

    #[test]
    fn kept_bsdfs_equal_built_ones() {
        let glass = fixture::material(Shader::Dielectric {
            ior: 1.5,
            ior_out: 1.0,
            col: Vec3::ONE,
        });
        let black = fixture::lambert(0.0);
        let materials = [fixture::lambert(0.5), glass, black];
        let g = fixture::geometry(
            materials
                .iter()
                .enumerate()
                .map(|(i, m)| Object {
                    triangles: fixture::floor(1.0, i as f32),
                    material: m.clone(),
                })
                .collect(),
        );
        let kept = MaterialBsdfs::new(&g);
        for (slot, m) in g.materials.iter().enumerate() {
            for front in [false, true] {
                let got = kept.get(slot as u32, front);
                match Bsdf::new(&m.shader, front) {
                    Some(b) => assert_eq!(*got, b, "slot {slot} front {front}"),
                    None => assert!(!got.reflects(), "slot {slot} front {front}"),
                }
            }
        }
        // The glass's faces differ (η inverted); the black material reflects nothing.
        assert_ne!(kept.get(1, true), kept.get(1, false));
        assert!(!kept.get(2, true).reflects());
    }
}
