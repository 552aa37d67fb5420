//! Local illumination models as a shading-language specification writes them (the RenderMan
//! Interface 3.2 standard surfaces; mental ray's base shaders can use the same terms): sums
//! over the lights of `Cl` times a cosine or a highlight lobe, plus ambient terms. They are
//! not physically based — the diffuse term has no 1/π, nothing conserves energy — and they
//! are evaluated as written, never clamped.

use glam::Vec3;

/// The specular highlight of a [`LocalModel`], per light: `Cl · lobe(N, L, V)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LocalLobe {
    /// The RenderMan Interface 3.2 `specularbrdf`: `max(0, N·H)^(1/roughness)` with the
    /// half vector `H = normalize(L + V)`.
    RenderMan {
        /// RenderMan roughness (> 0).
        roughness: f32,
    },
    /// mental ray's `mib_illum_phong`: `max(0, R·L)^exponent` with `R` the viewer's direction
    /// mirrored about the normal.
    Phong {
        /// Phong exponent (≥ 0).
        exponent: f32,
    },
}

impl LocalLobe {
    /// The lobe for the unit directions `wo` (toward the viewer) and `wi` (toward the light)
    /// in the local frame whose +Z is the shading normal.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        match *self {
            LocalLobe::RenderMan { roughness } => {
                let h = (wo + wi).normalize_or_zero();
                let c = h.z.max(0.0);
                if c <= 0.0 {
                    0.0
                } else {
                    c.powf(1.0 / roughness.max(1e-4))
                }
            }
            LocalLobe::Phong { exponent } => {
                // The mirror direction of `wo` about +Z.
                let r = Vec3::new(-wo.x, -wo.y, wo.z).normalize_or_zero();
                let c = r.dot(wi);
                if c <= 0.0 {
                    0.0
                } else {
                    c.powf(exponent)
                }
            }
        }
    }
}

/// A local illumination model's terms. The radiance toward the viewer is
///
/// `color · (ka · A + kd · Σ Cl·max(0, N·L)) + ambient + specular · Σ Cl·lobe(N, L, V)
///  + reflection · (radiance along the mirror direction)`
///
/// where `A` is the scene's ambient light (the sum of its `Ambient` lights, RenderMan's
/// `ambient()`), `Cl` the light arriving from each light (a point light's `I/d²`) and `N` the
/// shading normal turned toward the viewer (RenderMan's `Nf`). RenderMan's `plastic` is
/// `color = Cs, specular = Ks·specularcolor`; `metal` is `kd = 0, specular = Ks·Cs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalModel {
    /// Surface colour `Cs` (linear RGB): multiplies the ambient-light and diffuse terms (a
    /// texture binds here: RenderMan's `paintedplastic`).
    pub color: Vec3,
    /// Weight of the scene's ambient light (`Ka`).
    pub ka: f32,
    /// Weight of the diffuse sum (`Kd`).
    pub kd: f32,
    /// Weight of the highlight sum per channel (`Ks · specularcolor`).
    pub specular: Vec3,
    /// The highlight lobe.
    pub lobe: LocalLobe,
    /// Weight of the perfect-mirror reflection, traced (`shinymetal`'s `Kr · Cs`).
    pub reflection: Vec3,
    /// Radiance added as it is, independent of lights (mental ray's `ambience · ambient`).
    pub ambient: Vec3,
}

impl LocalModel {
    /// The light-independent part: `color · ka · scene_ambient + ambient`.
    pub fn ambient_term(&self, scene_ambient: Vec3) -> Vec3 {
        self.color * (self.ka * scene_ambient) + self.ambient
    }

    /// What one light arriving from `wi` (local frame, `wi.z = N·L > 0`) with radiance `cl`
    /// adds toward `wo`: `cl · (color·kd·N·L + specular·lobe)`.
    pub fn per_light(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let cos = wi.z.max(0.0);
        self.color * (self.kd * cos) + self.specular * self.lobe.eval(wo, wi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renderman_lobe_is_the_half_vector_power() {
        let lobe = LocalLobe::RenderMan { roughness: 0.25 };
        // Mirror configuration: H = N, full highlight.
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let wi = Vec3::new(-0.6, 0.0, 0.8);
        assert!((lobe.eval(wo, wi) - 1.0).abs() < 1e-6);
        // V = N, L at 60°: H at 30°, cos 30°^4.
        let wi = Vec3::new(60f32.to_radians().sin(), 0.0, 0.5);
        let expected = 30f32.to_radians().cos().powi(4);
        assert!((lobe.eval(Vec3::Z, wi) - expected).abs() < 1e-6);
    }

    #[test]
    fn plastic_terms_add_without_normalisation() {
        let m = LocalModel {
            color: Vec3::new(1.0, 0.5, 0.25),
            ka: 1.0,
            kd: 0.5,
            specular: Vec3::splat(0.5),
            lobe: LocalLobe::RenderMan { roughness: 0.1 },
            reflection: Vec3::ZERO,
            ambient: Vec3::ZERO,
        };
        // Light and viewer along N: Kd·Cs + Ks (no 1/π, no clamp).
        let c = m.per_light(Vec3::Z, Vec3::Z);
        assert!((c - Vec3::new(1.0, 0.75, 0.625)).abs().max_element() < 1e-6);
        assert_eq!(m.ambient_term(Vec3::splat(0.2)), Vec3::new(0.2, 0.1, 0.05));
    }
}
