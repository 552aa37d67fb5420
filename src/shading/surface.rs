//! Surface shaders of scene format v1: what each returns for a view direction and, for
//! light-dependent shaders, their BRDF.

use std::f32::consts::FRAC_1_PI;

use glam::Vec3;

use crate::components::Shader;

/// Radiance a shader returns without consulting lights (`None` for shaders that integrate
/// light: their result comes from [`brdf`] and the light loop).
///
/// `cos_view` is `|N·I|`, the cosine between the shading normal and the view direction.
pub fn unlit_radiance(shader: &Shader, cos_view: f32) -> Option<Vec3> {
    match shader {
        Shader::Constant { color } => Some(*color),
        Shader::DefaultSurface { ka, kd, color } => Some(*color * (*ka + *kd * cos_view.abs())),
        Shader::Lambert { .. } => None,
    }
}

/// The BRDF value (constant for the diffuse shaders of v1), W/(sr·m²) per W/m².
pub fn brdf(shader: &Shader) -> Vec3 {
    match shader {
        Shader::Lambert { albedo } => *albedo * FRAC_1_PI,
        Shader::Constant { .. } | Shader::DefaultSurface { .. } => Vec3::ZERO,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_surface_matches_the_seed_formula() {
        let s = Shader::DefaultSurface {
            ka: 0.2,
            kd: 0.8,
            color: Vec3::new(1.0, 0.5, 0.25),
        };
        let c = unlit_radiance(&s, -0.5).unwrap();
        assert!((c - Vec3::new(1.0, 0.5, 0.25) * 0.6).length() < 1e-6);
    }

    #[test]
    fn lambert_brdf_integrates_to_albedo() {
        // ∫ f cosθ dω over the hemisphere = f · π.
        let f = brdf(&Shader::Lambert {
            albedo: Vec3::splat(0.8),
        });
        assert!((f.x * std::f32::consts::PI - 0.8).abs() < 1e-6);
    }
}
