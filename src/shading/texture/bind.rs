//! Shader parameters that texture nodes may drive: their names (as written in the scene
//! file), types and ranges, and how an evaluated value is written into a copy of the
//! material's [`Shader`].
//!
//! Values written at a shading point are clamped to the parameter's range (a colour below 0,
//! an albedo above 1, a roughness of 0, a NaN): a texture can never make a BSDF invalid.

use glam::Vec3;

use crate::components::{LocalLobe, Shader};

/// Whether a parameter holds a colour or a number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamType {
    /// Three channels.
    Colour,
    /// One number.
    Scalar,
}

/// The values a parameter accepts; evaluated values are clamped into it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Range {
    /// ≥ 0.
    NonNegative,
    /// In [0, 1].
    Unit,
    /// ≥ 10⁻⁴ (roughness, indices of refraction).
    Positive,
}

impl Range {
    fn clamp(self, x: f32) -> f32 {
        let x = if x.is_finite() { x } else { 0.0 };
        match self {
            Range::NonNegative => x.max(0.0),
            Range::Unit => x.clamp(0.0, 1.0),
            Range::Positive => x.max(1e-4),
        }
    }
}

/// A mutable view of one parameter.
pub enum Field<'a> {
    /// A colour parameter.
    Colour(&'a mut Vec3, Range),
    /// A scalar parameter.
    Scalar(&'a mut f32, Range),
}

impl Field<'_> {
    /// The parameter's type.
    pub fn ty(&self) -> ParamType {
        match self {
            Field::Colour(..) => ParamType::Colour,
            Field::Scalar(..) => ParamType::Scalar,
        }
    }

    /// Writes `v` (a scalar reads `v.x`), clamped to the range.
    pub fn set(self, v: Vec3) {
        match self {
            Field::Colour(c, r) => *c = Vec3::new(r.clamp(v.x), r.clamp(v.y), r.clamp(v.z)),
            Field::Scalar(s, r) => *s = r.clamp(v.x),
        }
    }
}

/// Calls `f` with every parameter of `shader` that nodes may drive (the `Opacity` input's
/// parameters are named `input.<name>`, handled by [`field`]).
pub fn visit(shader: &mut Shader, f: &mut dyn FnMut(&'static str, Field<'_>)) {
    use Field::{Colour as C, Scalar as S};
    use Range::{NonNegative as N, Positive as P, Unit as U};
    match shader {
        Shader::Constant { color } => f("color", C(color, N)),
        Shader::DefaultSurface { ka, kd, color } => {
            f("ka", S(ka, N));
            f("kd", S(kd, N));
            f("color", C(color, N));
        }
        Shader::Lambert { albedo } => f("albedo", C(albedo, U)),
        Shader::Phong {
            ambient,
            diffuse,
            specular,
            spec_exp,
        }
        | Shader::Blong {
            ambient,
            diffuse,
            specular,
            spec_exp,
        } => {
            f("ambient", C(ambient, N));
            f("diffuse", C(diffuse, N));
            f("specular", C(specular, N));
            f("spec_exp", S(spec_exp, N));
        }
        Shader::Blinn {
            ambient,
            diffuse,
            specular,
            roughness,
            ior,
        } => {
            f("ambient", C(ambient, N));
            f("diffuse", C(diffuse, N));
            f("specular", C(specular, N));
            f("roughness", S(roughness, P));
            f("ior", S(ior, P));
        }
        Shader::CookTorrance {
            ambient,
            diffuse,
            specular,
            roughness,
            ior,
        } => {
            f("ambient", C(ambient, N));
            f("diffuse", C(diffuse, N));
            f("specular", C(specular, N));
            f("roughness", S(roughness, P));
            f("ior", C(ior, P));
        }
        Shader::FresnelSpecular {
            ambient,
            diffuse,
            specular,
            spec_exp,
            ior_in,
            ior_out,
        } => {
            f("ambient", C(ambient, N));
            f("diffuse", C(diffuse, N));
            f("specular", C(specular, N));
            f("spec_exp", S(spec_exp, N));
            f("ior_in", S(ior_in, P));
            f("ior_out", S(ior_out, P));
        }
        Shader::Matte { ka, kd, color } => {
            f("ka", S(ka, N));
            f("kd", S(kd, N));
            f("color", C(color, N));
        }
        Shader::Plastic {
            ka,
            kd,
            ks,
            roughness,
            specular_color,
            color,
        }
        | Shader::PaintedPlastic {
            ka,
            kd,
            ks,
            roughness,
            specular_color,
            color,
        } => {
            f("ka", S(ka, N));
            f("kd", S(kd, N));
            f("ks", S(ks, N));
            f("roughness", S(roughness, P));
            f("specularcolor", C(specular_color, N));
            f("color", C(color, N));
        }
        Shader::Metal {
            ka,
            ks,
            roughness,
            color,
        } => {
            f("ka", S(ka, N));
            f("ks", S(ks, N));
            f("roughness", S(roughness, P));
            f("color", C(color, N));
        }
        Shader::ShinyMetal {
            ka,
            ks,
            kr,
            roughness,
            color,
        } => {
            f("ka", S(ka, N));
            f("ks", S(ks, N));
            f("kr", S(kr, N));
            f("roughness", S(roughness, P));
            f("color", C(color, N));
        }
        Shader::Mirror { color } => f("color", C(color, N)),
        Shader::MetallicRoughness {
            base_color,
            metallic,
            roughness,
        } => {
            f("base_color", C(base_color, U));
            f("metallic", S(metallic, U));
            f("roughness", S(roughness, U));
        }
        Shader::Dielectric { ior, ior_out, col } => {
            f("ior", S(ior, P));
            f("ior_out", S(ior_out, P));
            f("col", C(col, U));
        }
        Shader::Dgs {
            diffuse,
            glossy,
            specular,
            shiny,
        } => {
            f("diffuse", C(diffuse, N));
            f("glossy", C(glossy, N));
            f("specular", C(specular, N));
            f("shiny", S(shiny, N));
        }
        Shader::Local(m) => {
            f("color", C(&mut m.color, N));
            f("ka", S(&mut m.ka, N));
            f("kd", S(&mut m.kd, N));
            f("specular", C(&mut m.specular, N));
            match &mut m.lobe {
                LocalLobe::RenderMan { roughness } => f("roughness", S(roughness, P)),
                LocalLobe::Phong { exponent } => f("exponent", S(exponent, N)),
                LocalLobe::CookTorrance { roughness, ior } => {
                    f("roughness", S(roughness, P));
                    f("ior", C(ior, P));
                }
            }
            f("reflection", C(&mut m.reflection, N));
            f("ambient", C(&mut m.ambient, N));
        }
        Shader::Opacity { opacity, .. } => f("opacity", C(opacity, U)),
    }
}

/// Applies `f` to the parameter `name` of `shader` (`input.<name>` reaches into an
/// `Opacity` input); `None` when there is no such parameter.
pub fn field<R>(shader: &mut Shader, name: &str, f: impl FnOnce(Field<'_>) -> R) -> Option<R> {
    if let (Some(rest), Shader::Opacity { input, .. }) = (name.strip_prefix("input."), &mut *shader)
    {
        return field(input, rest, f);
    }
    let mut f = Some(f);
    let mut out = None;
    visit(shader, &mut |n, field| {
        if n == name {
            if let Some(f) = f.take() {
                out = Some(f(field));
            }
        }
    });
    out
}

/// Every parameter name of `shader` with its type (nested `input.` names included).
pub fn names(shader: &Shader) -> Vec<(String, ParamType)> {
    let mut s = shader.clone();
    let mut out = Vec::new();
    visit(&mut s, &mut |n, f| out.push((n.to_string(), f.ty())));
    if let Shader::Opacity { input, .. } = shader {
        out.extend(
            names(input)
                .into_iter()
                .map(|(n, t)| (format!("input.{n}"), t)),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_clamps_to_the_range() {
        let mut s = Shader::Lambert {
            albedo: Vec3::splat(0.5),
        };
        field(&mut s, "albedo", |f| f.set(Vec3::new(2.0, -1.0, f32::NAN))).unwrap();
        assert_eq!(
            s,
            Shader::Lambert {
                albedo: Vec3::new(1.0, 0.0, 0.0)
            }
        );
        assert!(field(&mut s, "albedoo", |_| ()).is_none());
    }

    #[test]
    fn opacity_input_is_reachable() {
        let mut s = Shader::Opacity {
            opacity: Vec3::ONE,
            input: Box::new(Shader::Metal {
                ka: 1.0,
                ks: 1.0,
                roughness: 0.1,
                color: Vec3::ONE,
            }),
        };
        field(&mut s, "input.roughness", |f| f.set(Vec3::ZERO)).unwrap();
        let Shader::Opacity { input, .. } = &s else {
            unreachable!()
        };
        assert!(matches!(**input, Shader::Metal { roughness, .. } if roughness == 1e-4));
        let n = names(&s);
        assert!(n.contains(&("input.color".into(), ParamType::Colour)));
        assert!(n.contains(&("opacity".into(), ParamType::Colour)));
    }
}
