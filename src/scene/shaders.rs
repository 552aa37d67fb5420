//! Checking surface shader descriptions and building the [`Shader`] component data.
//!
//! Every error is reported at the offending value (`materials[2].shader.Plastic.roughness`);
//! all problems of one shader are collected before giving up on it.

use glam::{DVec3, Vec3};

use super::checker::Checker;
use super::desc::{LocalLobeDesc, ShaderDesc, V3};
use crate::components::{LocalLobe, LocalModel, Shader};

/// Checks one shader description at `path` (the path of the `shader` value itself).
pub fn shader(ck: &mut Checker<'_>, path: &str, desc: &ShaderDesc) -> Option<Shader> {
    // The parameters a `.mi` shader writes under names of its own: `mib_illum_*`'s
    // `"diffuse"` is the `Local` colour, the tutorial's `"Ka"`/`"Kd"` `DefaultSurface`'s.
    let syntax = ck.src.syntax(ck.file);
    let mut s = Fields { ck, path, ok: true };
    let shader = match desc {
        ShaderDesc::Lambert { albedo } => {
            let albedo = s.unit_colour("Lambert.albedo", "albedo", *albedo);
            Shader::Lambert { albedo }
        }
        ShaderDesc::Constant { color } => Shader::Constant {
            color: s.colour("Constant.color", "color", *color),
        },
        ShaderDesc::DefaultSurface { ka, kd, color } => Shader::DefaultSurface {
            ka: s.weight("DefaultSurface.ka", syntax.named("ka", "Ka", "Ka"), *ka),
            kd: s.weight("DefaultSurface.kd", syntax.named("kd", "Kd", "Kd"), *kd),
            color: s.colour("DefaultSurface.color", "color", *color),
        },
        ShaderDesc::Phong {
            ambient,
            diffuse,
            specular,
            spec_exp,
        } => Shader::Phong {
            ambient: s.colour("Phong.ambient", "ambient", *ambient),
            diffuse: s.colour("Phong.diffuse", "diffuse", *diffuse),
            specular: s.colour("Phong.specular", "specular", *specular),
            spec_exp: s.weight("Phong.spec_exp", "spec_exp", *spec_exp),
        },
        ShaderDesc::Blinn {
            ambient,
            diffuse,
            specular,
            roughness,
            ior,
        } => Shader::Blinn {
            ambient: s.colour("Blinn.ambient", "ambient", *ambient),
            diffuse: s.colour("Blinn.diffuse", "diffuse", *diffuse),
            specular: s.colour("Blinn.specular", "specular", *specular),
            roughness: s.positive("Blinn.roughness", "roughness", *roughness),
            ior: s.positive("Blinn.ior", "ior", *ior),
        },
        ShaderDesc::CookTorrance {
            ambient,
            diffuse,
            specular,
            roughness,
            ior,
        } => Shader::CookTorrance {
            ambient: s.colour("CookTorrance.ambient", "ambient", *ambient),
            diffuse: s.colour("CookTorrance.diffuse", "diffuse", *diffuse),
            specular: s.colour("CookTorrance.specular", "specular", *specular),
            roughness: s.positive("CookTorrance.roughness", "roughness", *roughness),
            ior: s.positive3("CookTorrance.ior", "ior", *ior),
        },
        ShaderDesc::Blong {
            ambient,
            diffuse,
            specular,
            spec_exp,
        } => Shader::Blong {
            ambient: s.colour("Blong.ambient", "ambient", *ambient),
            diffuse: s.colour("Blong.diffuse", "diffuse", *diffuse),
            specular: s.colour("Blong.specular", "specular", *specular),
            spec_exp: s.weight("Blong.spec_exp", "spec_exp", *spec_exp),
        },
        ShaderDesc::FresnelSpecular {
            ambient,
            diffuse,
            specular,
            spec_exp,
            ior_in,
            ior_out,
        } => Shader::FresnelSpecular {
            ambient: s.colour("FresnelSpecular.ambient", "ambient", *ambient),
            diffuse: s.colour("FresnelSpecular.diffuse", "diffuse", *diffuse),
            specular: s.colour("FresnelSpecular.specular", "specular", *specular),
            spec_exp: s.weight("FresnelSpecular.spec_exp", "spec_exp", *spec_exp),
            ior_in: s.positive("FresnelSpecular.ior_in", "ior_in", *ior_in),
            ior_out: s.positive("FresnelSpecular.ior_out", "ior_out", *ior_out),
        },
        ShaderDesc::Matte { ka, kd, color } => Shader::Matte {
            ka: s.weight("Matte.ka", "ka", *ka),
            kd: s.weight("Matte.kd", "kd", *kd),
            color: s.colour("Matte.color", "color", *color),
        },
        ShaderDesc::Plastic {
            ka,
            kd,
            ks,
            roughness,
            specularcolor,
            color,
        } => Shader::Plastic {
            ka: s.weight("Plastic.ka", "ka", *ka),
            kd: s.weight("Plastic.kd", "kd", *kd),
            ks: s.weight("Plastic.ks", "ks", *ks),
            roughness: s.positive("Plastic.roughness", "roughness", *roughness),
            specular_color: s.colour("Plastic.specularcolor", "specularcolor", *specularcolor),
            color: s.colour("Plastic.color", "color", *color),
        },
        ShaderDesc::Metal {
            ka,
            ks,
            roughness,
            color,
        } => Shader::Metal {
            ka: s.weight("Metal.ka", "ka", *ka),
            ks: s.weight("Metal.ks", "ks", *ks),
            roughness: s.positive("Metal.roughness", "roughness", *roughness),
            color: s.colour("Metal.color", "color", *color),
        },
        ShaderDesc::ShinyMetal {
            ka,
            ks,
            kr,
            roughness,
            color,
        } => Shader::ShinyMetal {
            ka: s.weight("ShinyMetal.ka", "ka", *ka),
            ks: s.weight("ShinyMetal.ks", "ks", *ks),
            kr: s.weight("ShinyMetal.kr", "kr", *kr),
            roughness: s.positive("ShinyMetal.roughness", "roughness", *roughness),
            color: s.colour("ShinyMetal.color", "color", *color),
        },
        ShaderDesc::PaintedPlastic {
            ka,
            kd,
            ks,
            roughness,
            specularcolor,
            color,
        } => Shader::PaintedPlastic {
            ka: s.weight("PaintedPlastic.ka", "ka", *ka),
            kd: s.weight("PaintedPlastic.kd", "kd", *kd),
            ks: s.weight("PaintedPlastic.ks", "ks", *ks),
            roughness: s.positive("PaintedPlastic.roughness", "roughness", *roughness),
            specular_color: s.colour(
                "PaintedPlastic.specularcolor",
                "specularcolor",
                *specularcolor,
            ),
            color: s.colour("PaintedPlastic.color", "color", *color),
        },
        ShaderDesc::MetallicRoughness {
            base_color,
            metallic,
            roughness,
        } => Shader::MetallicRoughness {
            base_color: s.unit_colour("MetallicRoughness.base_color", "base_color", *base_color),
            metallic: s.unit("MetallicRoughness.metallic", "metallic", *metallic),
            roughness: s.unit("MetallicRoughness.roughness", "roughness", *roughness),
        },
        ShaderDesc::Mirror { color } => Shader::Mirror {
            color: s.colour("Mirror.color", "color", *color),
        },
        ShaderDesc::Dielectric { ior, ior_out, col } => Shader::Dielectric {
            ior: s.positive("Dielectric.ior", "ior", *ior),
            ior_out: s.positive("Dielectric.ior_out", "ior_out", *ior_out),
            col: s.unit_colour("Dielectric.col", "col", *col),
        },
        ShaderDesc::Dgs {
            diffuse,
            glossy,
            specular,
            shiny,
        } => Shader::Dgs {
            diffuse: s.colour("Dgs.diffuse", "diffuse", *diffuse),
            glossy: s.colour("Dgs.glossy", "glossy", *glossy),
            specular: s.colour("Dgs.specular", "specular", *specular),
            shiny: s.weight("Dgs.shiny", "shiny", *shiny),
        },
        ShaderDesc::Local {
            color,
            ka,
            kd,
            specular,
            lobe,
            reflection,
            ambient,
        } => Shader::Local(LocalModel {
            color: s.colour(
                "Local.color",
                syntax.named("color", "diffuse", "Color"),
                *color,
            ),
            ka: s.weight("Local.ka", syntax.named("ka", "ka", "Ka"), *ka),
            kd: s.weight("Local.kd", syntax.named("kd", "kd", "Kd"), *kd),
            specular: s.colour("Local.specular", "specular", *specular),
            lobe: match lobe {
                LocalLobeDesc::RenderMan { roughness } => LocalLobe::RenderMan {
                    roughness: s.positive(
                        "Local.lobe.RenderMan.roughness",
                        "roughness",
                        *roughness,
                    ),
                },
                LocalLobeDesc::Phong { exponent } => LocalLobe::Phong {
                    exponent: s.weight("Local.lobe.Phong.exponent", "exponent", *exponent),
                },
                LocalLobeDesc::Blinn { roughness, ior } => LocalLobe::CookTorrance {
                    roughness: s.positive("Local.lobe.Blinn.roughness", "roughness", *roughness),
                    ior: Vec3::splat(s.positive("Local.lobe.Blinn.ior", "ior", *ior)),
                },
                LocalLobeDesc::CookTorrance { roughness, ior } => LocalLobe::CookTorrance {
                    roughness: s.positive(
                        "Local.lobe.CookTorrance.roughness",
                        "roughness",
                        *roughness,
                    ),
                    ior: s.positive3("Local.lobe.CookTorrance.ior", "ior", *ior),
                },
            },
            reflection: s.colour("Local.reflection", "reflection", *reflection),
            ambient: s.colour("Local.ambient", "ambient", *ambient),
        }),
        ShaderDesc::Opacity { opacity, input } => {
            let opacity = s.unit_colour("Opacity.opacity", "opacity", *opacity);
            let input_path = format!("{path}.Opacity.input");
            let input = shader(s.ck, &input_path, input);
            match input {
                Some(input) => Shader::Opacity {
                    opacity,
                    input: Box::new(input),
                },
                None => return None,
            }
        }
    };
    s.ok.then_some(shader)
}

/// Field checks that remember whether anything failed (values of failed fields are zero).
struct Fields<'c, 's, 'p> {
    ck: &'c mut Checker<'s>,
    path: &'p str,
    ok: bool,
}

impl Fields<'_, '_, '_> {
    fn at(&self, field: &str) -> String {
        format!("{}.{field}", self.path)
    }

    fn record<T: Default>(&mut self, v: Option<T>) -> T {
        self.ok &= v.is_some();
        v.unwrap_or_default()
    }

    /// A non-negative colour.
    fn colour(&mut self, field: &str, what: &str, v: V3) -> Vec3 {
        let path = self.at(field);
        let c = self.ck.colour(&path, what, v).map(DVec3::as_vec3);
        self.record(c)
    }

    /// A colour with every channel in [0, 1].
    fn unit_colour(&mut self, field: &str, what: &str, v: V3) -> Vec3 {
        let path = self.at(field);
        let Some(c) = self.ck.colour(&path, what, v) else {
            self.ok = false;
            return Vec3::ZERO;
        };
        for (k, x) in c.to_array().into_iter().enumerate() {
            if x > 1.0 {
                self.ck.src.error(
                    self.ck.file,
                    &format!("{path}[{k}]"),
                    format!("{what} must be at most 1 (energy conservation), found {x}"),
                    Some(fraction_help(what)),
                );
                self.ok = false;
            }
        }
        c.as_vec3()
    }

    /// A finite, non-negative number.
    fn weight(&mut self, field: &str, what: &str, x: f64) -> f32 {
        let path = self.at(field);
        let v = self.ck.non_negative(&path, what, x).map(|x| x as f32);
        self.record(v)
    }

    /// A finite number in [0, 1].
    fn unit(&mut self, field: &str, what: &str, x: f64) -> f32 {
        let v = self.weight(field, what, x);
        if x > 1.0 {
            let path = self.at(field);
            self.ck
                .error(&path, format!("{what} must be at most 1, found {x}"));
            self.ok = false;
        }
        v
    }

    /// A finite, positive number.
    fn positive(&mut self, field: &str, what: &str, x: f64) -> f32 {
        let path = self.at(field);
        if !self.ck.finite(&path, what, x) {
            self.ok = false;
            return 0.0;
        }
        if x <= 0.0 {
            self.ck
                .error(&path, format!("{what} must be positive, found {x}"));
            self.ok = false;
        }
        x as f32
    }

    /// A vector of finite, positive numbers.
    fn positive3(&mut self, field: &str, what: &str, v: V3) -> Vec3 {
        let path = self.at(field);
        let Some(c) = self.ck.v3(&path, what, v) else {
            self.ok = false;
            return Vec3::ZERO;
        };
        for (k, x) in c.to_array().into_iter().enumerate() {
            if x <= 0.0 {
                self.ck.error(
                    &format!("{path}[{k}]"),
                    format!("{what} must be positive, found {x}"),
                );
                self.ok = false;
            }
        }
        c.as_vec3()
    }
}

/// What a colour channel above 1 should be instead: opacity is coverage, the other
/// colours are the fraction of light sent on.
fn fraction_help(what: &str) -> String {
    if what == "opacity" {
        return "opacity is 0 (clear) to 1 (opaque) per channel".into();
    }
    format!(
        "{what} is the fraction of the light arriving that goes on, 0 to 1 per channel (0.8 is \
         a bright white): a surface that gives off light of its own needs an emission, not more \
         {what}"
    )
}
