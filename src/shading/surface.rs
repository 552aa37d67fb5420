//! Shaders that do not integrate light: what they return for a view direction.

use glam::Vec3;

use crate::components::Shader;

/// Radiance a shader returns without consulting lights (`None` for shaders that integrate
/// light: their result comes from their [`crate::shading::bsdf::Bsdf`]).
///
/// `cos_view` is `|N·I|`, the cosine between the shading normal and the view direction.
pub fn unlit_radiance(shader: &Shader, cos_view: f32) -> Option<Vec3> {
    match shader {
        Shader::Constant { color } => Some(*color),
        Shader::DefaultSurface { ka, kd, color } => Some(*color * (*ka + *kd * cos_view.abs())),
        _ => None,
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
    fn lambert_integrates_light() {
        let s = Shader::Lambert {
            albedo: Vec3::splat(0.8),
        };
        assert!(unlit_radiance(&s, 1.0).is_none());
    }
}
