//! The built-in mental ray shaders the reader knows, their parameters, and what each maps
//! onto: material shaders onto [`ShaderDesc`] kinds, light shaders onto a [`LightModel`]
//! with colour and falloff, environment shaders onto [`EnvironmentDesc`].
//!
//! Semantics follow mental ray's base and physics libraries (`docs/mi.md` relates them to
//! stagelight's physically based models):
//! - `mib_illum_lambert` = ambience·ambient + Σ diffuse·Cl·max(0, N·L), no 1/π: a `Local`
//!   model with `color = diffuse`, `kd = 1`, `ka = 0`, `ambient = ambience·ambient`;
//!   `mib_illum_phong` adds `specular·Cl·max(0, R·L)^exponent` (the `Phong` lobe),
//!   `mib_illum_cooktorr` `specular·Cl·F·D·G/(π N·V)` (the `CookTorrance` lobe: Cook and
//!   Torrance's specular term), `mib_illum_blinn` the same with one index (the `Blinn` lobe).
//! - `mib_light_point`/`mib_light_spot`/`mib_light_infinite`: `Cl = color`, no
//!   inverse-square law; `atten on` ramps linearly from `start` (1) to `stop` (0).
//! - `physical_light`: inverse-square; a point or spot of `color` radiates `color / 4π`
//!   W/sr, an area shape `color / (π·area)` W/(sr·m²) (the same power).
//! - A material shader's `"lights"` list is the material's light list; `"mode" 2` makes it
//!   exclusive (every other light).

use std::collections::{BTreeMap, HashMap};

use super::super::located::{Located, Pos, Problem};
use super::cursor::{Cursor, Param, ShaderCall, Value};
use super::model::LightModel;
use crate::scene::desc::{
    DepthExceededDesc, EnvironmentDesc, EnvironmentShaderDesc, InputDesc, LocalLobeDesc,
    ShaderDesc, V3,
};
use crate::scene::suggest::closest;

/// What a built-in shader is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// A material (surface) shader.
    Material,
    /// A light shader.
    Light,
    /// A texture / colour shader usable as a parameter value or environment.
    Texture,
    /// A photon shader: read, not yet mapped.
    Photon,
    /// A shadow shader (`mib_shadow_transparency`: the material's `shadow:`).
    Shadow,
}

/// One built-in shader: its name, role and parameter names.
#[derive(Debug, Clone, Copy)]
pub struct Builtin {
    /// Name in `.mi` files.
    pub name: &'static str,
    /// What it is for.
    pub role: Role,
    /// Its parameters.
    pub params: &'static [&'static str],
}

const ILLUM: &[&str] = &["ambience", "ambient", "diffuse", "mode", "lights"];

/// Every built-in shader.
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "mib_illum_lambert",
        role: Role::Material,
        params: ILLUM,
    },
    Builtin {
        name: "mib_illum_phong",
        role: Role::Material,
        params: &[
            "ambience", "ambient", "diffuse", "specular", "exponent", "mode", "lights",
        ],
    },
    Builtin {
        name: "mib_illum_blinn",
        role: Role::Material,
        params: &[
            "ambience",
            "ambient",
            "diffuse",
            "specular",
            "roughness",
            "ior",
            "mode",
            "lights",
        ],
    },
    Builtin {
        name: "mib_illum_cooktorr",
        role: Role::Material,
        params: &[
            "ambience",
            "ambient",
            "diffuse",
            "specular",
            "roughness",
            "ior",
            "mode",
            "lights",
        ],
    },
    Builtin {
        name: "mib_opacity",
        role: Role::Material,
        params: &["input", "opacity"],
    },
    Builtin {
        name: "dgs_material",
        role: Role::Material,
        params: &[
            "diffuse", "glossy", "specular", "shiny", "shiny_u", "shiny_v", "transp", "ior",
            "mode", "lights",
        ],
    },
    Builtin {
        name: "dielectric_material",
        role: Role::Material,
        params: &[
            "col",
            "ior",
            "col_out",
            "ior_out",
            "pcoef",
            "phong_coef",
            "ignore_normals",
            "mode",
            "lights",
        ],
    },
    Builtin {
        name: "mib_light_point",
        role: Role::Light,
        params: &["color", "shadow", "factor", "atten", "start", "stop"],
    },
    Builtin {
        name: "mib_light_spot",
        role: Role::Light,
        params: &[
            "color", "shadow", "factor", "atten", "start", "stop", "cone",
        ],
    },
    Builtin {
        name: "mib_light_infinite",
        role: Role::Light,
        params: &["color", "shadow", "factor"],
    },
    Builtin {
        name: "physical_light",
        role: Role::Light,
        params: &["color", "cone", "threshold", "cos_exp"],
    },
    Builtin {
        name: "dgs_material_photon",
        role: Role::Photon,
        params: &[
            "diffuse", "glossy", "specular", "shiny", "shiny_u", "shiny_v", "transp", "ior", "mode",
        ],
    },
    Builtin {
        name: "dielectric_material_photon",
        role: Role::Photon,
        params: &[
            "col",
            "ior",
            "col_out",
            "ior_out",
            "pcoef",
            "phong_coef",
            "ignore_normals",
        ],
    },
    Builtin {
        name: "mib_texture_lookup",
        role: Role::Texture,
        params: &["tex", "coord"],
    },
    Builtin {
        name: "mib_texture_vector",
        role: Role::Texture,
        params: &["select", "selspace", "vertex", "project"],
    },
    Builtin {
        name: "mib_texture_remap",
        role: Role::Texture,
        params: &[
            "input",
            "transform",
            "repeat",
            "alt_x",
            "alt_y",
            "alt_z",
            "torus_x",
            "torus_y",
            "torus_z",
            "min",
            "max",
            "offset",
        ],
    },
    Builtin {
        name: "mib_shadow_transparency",
        role: Role::Shadow,
        params: &["color", "transp", "mode", "light", "lights"],
    },
];

/// The built-in shader `name`.
pub fn builtin(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// Looks up the shader of `call` among the built-ins of `role`; reports an unknown one
/// (with a suggestion) or one of another role. Checks every parameter name.
pub fn check(
    c: &mut Cursor,
    call: &ShaderCall,
    role: Role,
    what: &str,
) -> Option<&'static Builtin> {
    let Some(b) = builtin(&call.name) else {
        let names = BUILTINS.iter().filter(|b| b.role == role).map(|b| b.name);
        let mut p = Problem::error(call.pos, format!("unknown {what} shader \"{}\"", call.name));
        p = match closest(&call.name, names.clone()) {
            _ if super::tutorial::is_tutorial(&call.name) => p.with_help(format!(
                "the tutorial's \"{0}\" is built in once its library is linked: link \"{0}.so\"",
                call.name
            )),
            Some(s) => p.with_help(format!("did you mean \"{s}\"?")),
            None => p.with_help(format!(
                "built in: {}",
                names.collect::<Vec<_>>().join(", ")
            )),
        };
        c.report(p);
        return None;
    };
    if b.role != role {
        c.error(
            call.pos,
            format!("\"{}\" is not a {what} shader", call.name),
        );
        return None;
    }
    let mut ok = true;
    for p in &call.params {
        if !b.params.contains(&p.name.as_str()) {
            let mut e = Problem::error(
                p.pos,
                format!("unknown parameter \"{}\" of shader \"{}\"", p.name, b.name),
            );
            if let Some(s) = closest(&p.name, b.params.iter().copied()) {
                e = e.with_help(format!("did you mean \"{s}\"?"));
            }
            c.report(e);
            ok = false;
        }
    }
    ok.then_some(b)
}

/// Typed parameter reads of one shader call, reporting wrong kinds.
pub struct Params<'a> {
    call: &'a ShaderCall,
    /// Parameters driven by a texture graph (read as their default, silently).
    bound: Vec<&'static str>,
}

impl<'a> Params<'a> {
    /// The parameters of `call`.
    pub fn new(call: &'a ShaderCall) -> Self {
        Self {
            call,
            bound: Vec::new(),
        }
    }

    fn get(&self, name: &str) -> Option<&'a Param> {
        self.call.params.iter().rev().find(|p| p.name == name)
    }

    fn wrong(&self, c: &mut Cursor, p: &Param, expected: &str) {
        c.error(
            p.value_pos,
            format!(
                "parameter \"{}\" of \"{}\" takes {expected}, found {}",
                p.name,
                self.call.name,
                describe(&p.value)
            ),
        );
    }

    /// A colour (3 numbers; a 4th, alpha, is dropped; 1 number is grey).
    pub fn color(&self, c: &mut Cursor, name: &str, default: V3) -> V3 {
        let Some(p) = self.get(name) else {
            return default;
        };
        if self.bound.contains(&name) {
            return default;
        }
        match &p.value {
            Value::Nums(n) if n.len() == 3 || n.len() == 4 => (n[0], n[1], n[2]),
            Value::Nums(n) if n.len() == 1 => (n[0], n[0], n[0]),
            Value::Ref(s) | Value::Interface(s) => {
                c.warn(
                    p.value_pos,
                    format!("parameter \"{name}\" of \"{}\" is driven by \"{s}\", which is not mapped; its default is used", self.call.name),
                );
                default
            }
            _ => {
                self.wrong(c, p, "a color (3 numbers)");
                default
            }
        }
    }

    /// A scalar.
    pub fn scalar(&self, c: &mut Cursor, name: &str, default: f64) -> f64 {
        let Some(p) = self.get(name) else {
            return default;
        };
        match &p.value {
            Value::Nums(n) if n.len() == 1 => n[0],
            _ => {
                self.wrong(c, p, "a number");
                default
            }
        }
    }

    /// A boolean (`on`/`off`, `true`/`false`, or 0/1).
    pub fn boolean(&self, c: &mut Cursor, name: &str, default: bool) -> bool {
        let Some(p) = self.get(name) else {
            return default;
        };
        match &p.value {
            Value::Bool(b) => *b,
            Value::Nums(n) if n.len() == 1 => n[0] != 0.0,
            _ => {
                self.wrong(c, p, "a boolean");
                default
            }
        }
    }

    /// Where parameter `name` is written.
    pub fn pos(&self, name: &str) -> Option<Pos> {
        self.get(name).map(|p| p.pos)
    }

    /// The raw value of `name`.
    pub fn value(&self, name: &str) -> Option<&'a Param> {
        self.get(name)
    }

    /// `"lights" ["a", …]` with where each name is.
    pub fn lights(&self, c: &mut Cursor) -> Option<Vec<(String, Located)>> {
        let p = self.get("lights")?;
        let Value::Array(items) = &p.value else {
            self.wrong(c, p, "an array of light names");
            return None;
        };
        let mut out = Vec::new();
        for item in items {
            match item {
                Value::Str(s) => out.push((s.clone(), c.located(p.value_pos))),
                other => {
                    c.error(
                        p.value_pos,
                        format!(
                            "\"lights\" of \"{}\" lists {}, expected light instance names",
                            self.call.name,
                            describe(other)
                        ),
                    );
                    return None;
                }
            }
        }
        Some(out)
    }
}

fn describe(v: &Value) -> String {
    match v {
        Value::Nums(n) => format!("{} number{}", n.len(), if n.len() == 1 { "" } else { "s" }),
        other => other.kind().to_string(),
    }
}

fn mul(a: V3, b: V3) -> V3 {
    (a.0 * b.0, a.1 * b.1, a.2 * b.2)
}

/// A material shader mapped: the shader, its light list, whether that is exclusive, and its
/// parameters driven by texture graphs (the material's `bind`).
pub type MappedMaterial = (
    ShaderDesc,
    Option<Vec<(String, Located)>>,
    bool,
    BTreeMap<String, InputDesc>,
);

/// The colour parameters of each material shader a texture may drive, with the parameter
/// of the shader kind it maps onto.
const TEXTURED: &[(&str, &[(&str, &str)])] = &[
    ("mib_illum_lambert", &[("diffuse", "color")]),
    (
        "mib_illum_phong",
        &[("diffuse", "color"), ("specular", "specular")],
    ),
    (
        "mib_illum_blinn",
        &[("diffuse", "color"), ("specular", "specular")],
    ),
    (
        "mib_illum_cooktorr",
        &[("diffuse", "color"), ("specular", "specular")],
    ),
    (
        "dgs_material",
        &[
            ("diffuse", "diffuse"),
            ("glossy", "glossy"),
            ("specular", "specular"),
        ],
    ),
];

/// Maps the material shader `call` (named shaders in `named` resolve `= "name"` inputs,
/// `textures` the `color texture` declarations that `mib_texture_lookup` names).
pub fn material(
    c: &mut Cursor,
    call: &ShaderCall,
    named: &HashMap<String, ShaderCall>,
    textures: &HashMap<String, (String, Located)>,
    depth: usize,
) -> Option<MappedMaterial> {
    let b = check(c, call, Role::Material, "material")?;
    let mut p = Params::new(call);
    let mut bind = BTreeMap::new();
    let scope = super::textures::Scope { named, textures };
    let textured = TEXTURED
        .iter()
        .find(|(n, _)| *n == b.name)
        .map_or(&[][..], |t| t.1);
    for &(mi, ours) in textured {
        let Some(param) = p.get(mi) else { continue };
        match super::textures::colour_input(c, param, &scope) {
            Some(Some(graph)) => {
                bind.insert(ours.to_string(), graph);
                p.bound.push(mi);
            }
            Some(None) => return None,
            None => {}
        }
    }
    let ambient = mul(
        p.color(c, "ambience", (0.0, 0.0, 0.0)),
        p.color(c, "ambient", (0.0, 0.0, 0.0)),
    );
    let zero = (0.0, 0.0, 0.0);
    let shader = match b.name {
        "mib_illum_lambert" => ShaderDesc::Local {
            color: p.color(c, "diffuse", zero),
            ka: 0.0,
            kd: 1.0,
            specular: zero,
            lobe: LocalLobeDesc::default(),
            reflection: zero,
            ambient,
        },
        "mib_illum_phong" => ShaderDesc::Local {
            color: p.color(c, "diffuse", zero),
            ka: 0.0,
            kd: 1.0,
            specular: p.color(c, "specular", zero),
            lobe: LocalLobeDesc::Phong {
                exponent: p.scalar(c, "exponent", 0.0).max(0.0),
            },
            reflection: zero,
            ambient,
        },
        "mib_illum_blinn" | "mib_illum_cooktorr" => {
            let roughness = p.scalar(c, "roughness", 0.2);
            let lobe = if b.name == "mib_illum_blinn" {
                LocalLobeDesc::Blinn {
                    roughness,
                    ior: p.scalar(c, "ior", 1.5),
                }
            } else {
                LocalLobeDesc::CookTorrance {
                    roughness,
                    ior: p.color(c, "ior", (1.5, 1.5, 1.5)),
                }
            };
            ShaderDesc::Local {
                color: p.color(c, "diffuse", zero),
                ka: 0.0,
                kd: 1.0,
                specular: p.color(c, "specular", zero),
                lobe,
                reflection: zero,
                ambient,
            }
        }
        "dgs_material" => {
            for name in ["shiny_u", "shiny_v", "transp"] {
                if let Some(at) = p.pos(name) {
                    c.warn(
                        at,
                        format!("parameter \"{name}\" of \"dgs_material\" is not mapped"),
                    );
                }
            }
            ShaderDesc::Dgs {
                diffuse: p.color(c, "diffuse", zero),
                glossy: p.color(c, "glossy", zero),
                specular: p.color(c, "specular", zero),
                shiny: p.scalar(c, "shiny", 20.0),
            }
        }
        "dielectric_material" => {
            for name in ["pcoef", "phong_coef", "col_out"] {
                if let Some(at) = p.pos(name) {
                    c.warn(
                        at,
                        format!("parameter \"{name}\" of \"dielectric_material\" is not mapped"),
                    );
                }
            }
            ShaderDesc::Dielectric {
                ior: p.scalar(c, "ior", 1.5),
                ior_out: p.scalar(c, "ior_out", 1.0),
                col: p.color(c, "col", (1.0, 1.0, 1.0)),
            }
        }
        "mib_opacity" => {
            let opacity = p.color(c, "opacity", (1.0, 1.0, 1.0));
            let input = match p.value("input").map(|x| &x.value) {
                Some(Value::Ref(name)) if depth < 8 => match named.get(name) {
                    Some(inner) => material(c, &inner.clone(), named, textures, depth + 1)?.0,
                    None => {
                        let at = p.value("input").map_or(call.pos, |x| x.value_pos);
                        c.error(at, format!("unknown shader \"{name}\""));
                        return None;
                    }
                },
                _ => ShaderDesc::Constant {
                    color: p.color(c, "input", zero),
                },
            };
            ShaderDesc::Opacity {
                opacity,
                input: Box::new(input),
            }
        }
        _ => return None,
    };
    let exclusive = p.scalar(c, "mode", 0.0) == 2.0;
    let lights = if b.params.contains(&"lights") {
        p.lights(c)
    } else {
        None
    };
    Some((shader, lights, exclusive, bind))
}

/// A light shader mapped.
#[derive(Debug, Clone, Copy)]
pub struct MappedLight {
    /// What it is.
    pub model: LightModel,
    /// Colour.
    pub color: V3,
    /// Casts shadows.
    pub shadows: bool,
    /// The shadow `factor`: the fraction of the light that passes occluders, in [0, 1].
    pub shadow_factor: f64,
    /// `physical_light`: inverse-square and power-normalised colour.
    pub physical: bool,
    /// `atten` `(start, stop)`.
    pub attenuation: Option<(f64, f64)>,
}

/// Maps the light shader `call`.
pub fn light(c: &mut Cursor, call: &ShaderCall) -> Option<MappedLight> {
    let b = check(c, call, Role::Light, "light")?;
    let p = Params::new(call);
    let color = p.color(c, "color", (1.0, 1.0, 1.0));
    if b.name == "physical_light" {
        for name in ["threshold", "cos_exp"] {
            if let Some(at) = p.pos(name) {
                c.warn(
                    at,
                    format!("parameter \"{name}\" of \"physical_light\" is not mapped"),
                );
            }
        }
        let cone = p.value("cone").map(|_| p.scalar(c, "cone", 0.0));
        return Some(MappedLight {
            model: LightModel::Spot { cone },
            color,
            shadows: true,
            shadow_factor: 0.0,
            physical: true,
            attenuation: None,
        });
    }
    let shadows = p.boolean(c, "shadow", false);
    let mut shadow_factor = if shadows {
        p.scalar(c, "factor", 0.0)
    } else {
        0.0
    };
    if !(0.0..=1.0).contains(&shadow_factor) {
        let at = p.pos("factor").unwrap_or(call.pos);
        c.report(
            Problem::error(
                at,
                format!("shadow \"factor\" must be between 0 and 1, found {shadow_factor}"),
            )
            .with_help("0 gives full shadows, 1 none"),
        );
        shadow_factor = 0.0;
    }
    let attenuation = (b.params.contains(&"atten") && p.boolean(c, "atten", false))
        .then(|| (p.scalar(c, "start", 0.0), p.scalar(c, "stop", 1.0)));
    let model = match b.name {
        "mib_light_point" => LightModel::Point,
        "mib_light_spot" => LightModel::Spot {
            cone: Some(p.scalar(c, "cone", 0.0)),
        },
        _ => LightModel::Infinite,
    };
    Some(MappedLight {
        model,
        color,
        shadows,
        shadow_factor,
        physical: false,
        attenuation,
    })
}

/// Maps an environment shader: a `mib_opacity` (directly, named, or a phenomenon's root)
/// with a constant `input` over black gives a constant environment of `input · opacity`.
pub fn environment(
    c: &mut Cursor,
    call: &ShaderCall,
    named: &HashMap<String, ShaderCall>,
) -> Option<EnvironmentDesc> {
    let mut call = call.clone();
    for _ in 0..8 {
        match named.get(&call.name) {
            Some(inner) if builtin(&call.name).is_none() => call = inner.clone(),
            _ => break,
        }
    }
    if call.name != "mib_opacity" {
        let mut p = Problem::error(
            call.pos,
            format!("environment shader \"{}\" is not mapped", call.name),
        );
        p = if super::tutorial::is_tutorial(&call.name) {
            p.with_help(format!(
                "the tutorial's \"{0}\" is built in once its library is linked: link \"{0}.so\"",
                call.name
            ))
        } else {
            p.with_help("a mib_opacity with a constant input (directly or as a phenomenon's root) maps onto a constant environment")
        };
        c.report(p);
        return None;
    }
    check(c, &call, Role::Material, "environment")?;
    let p = Params::new(&call);
    let color = mul(
        p.color(c, "input", (0.0, 0.0, 0.0)),
        p.color(c, "opacity", (1.0, 1.0, 1.0)),
    );
    Some(EnvironmentDesc {
        shader: EnvironmentShaderDesc::Constant { color },
        intensity: 1.0,
        samples: 16,
        depth_exceeded: DepthExceededDesc::Environment,
    })
}
