//! The RenderMan standard shaders as stagelight descriptions: `Surface` (`constant`,
//! `matte`, `metal`, `shinymetal`, `plastic`, `paintedplastic`, `defaultsurface`),
//! `Displacement` (stagelight's `sine`),
//! `LightSource` (`pointlight`, `spotlight`, `distantlight`, `ambientlight`) and
//! `Atmosphere` (`fog`).
//!
//! The tutorial's own shaders (`mySurface`, `simplemirror`, `stairs`, `myLight`,
//! `myDisplacement`) are in [`super::tutorial`].
//!
//! Every parameter a shader does not have is an error with a suggestion; parameters left
//! out take the defaults of the RenderMan Interface Specification 3.2.

use super::super::located::{Pos, Problem};
use super::params::{Param, Ty};
use super::state::ShaderCall;
use super::tutorial;
use crate::scene::desc::{AxisDesc, LocalLobeDesc, ScalarDesc, ShaderDesc, V3};
use crate::scene::nodes_desc::{BumpDesc, InputDesc};
use crate::scene::suggest::suggestion;
use std::collections::BTreeMap;

/// Kinds of shader parameter value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Float,
    Color,
    Point,
    Str,
}

/// One parameter a shader takes: name, kind, description path of its value (or `None`
/// when it has no field of its own; surfaces list their fields in [`surface`]).
pub(super) type Spec = (&'static str, Kind, Option<&'static str>);

const CONSTANT: &[Spec] = &[];
const MATTE: &[Spec] = &[("Ka", Kind::Float, None), ("Kd", Kind::Float, None)];
const DEFAULT_SURFACE: &[Spec] = MATTE;
const METAL: &[Spec] = &[
    ("Ka", Kind::Float, None),
    ("Ks", Kind::Float, None),
    ("roughness", Kind::Float, None),
];
const SHINY_METAL: &[Spec] = &[
    ("Ka", Kind::Float, None),
    ("Ks", Kind::Float, None),
    ("Kr", Kind::Float, None),
    ("roughness", Kind::Float, None),
    ("texturename", Kind::Str, None),
];
const PLASTIC: &[Spec] = &[
    ("Ka", Kind::Float, None),
    ("Kd", Kind::Float, None),
    ("Ks", Kind::Float, None),
    ("roughness", Kind::Float, None),
    ("specularcolor", Kind::Color, None),
];
const PAINTED_PLASTIC: &[Spec] = &[
    ("Ka", Kind::Float, None),
    ("Kd", Kind::Float, None),
    ("Ks", Kind::Float, None),
    ("roughness", Kind::Float, None),
    ("specularcolor", Kind::Color, None),
    ("texturename", Kind::Str, None),
];

/// The surface shaders we have.
pub const SURFACES: &[&str] = &[
    "constant",
    "matte",
    "metal",
    "shinymetal",
    "plastic",
    "paintedplastic",
    "defaultsurface",
];

/// The light shaders we have.
pub const LIGHTS: &[&str] = &["ambientlight", "pointlight", "spotlight", "distantlight"];

/// The displacement shaders we have.
pub const DISPLACEMENTS: &[&str] = &["sine"];

/// Looks up the parameters of a call: checks names against `specs` and kinds, returns the
/// values by spec index. Unknown parameters are errors.
pub(super) struct Values<'a> {
    pub(super) found: Vec<Option<&'a Param>>,
}

impl<'a> Values<'a> {
    pub(super) fn read(
        call: &'a ShaderCall,
        what: &str,
        specs: &[Spec],
        problems: &mut Vec<Problem>,
    ) -> Self {
        let mut found = vec![None; specs.len()];
        for p in &call.params {
            let Some(i) = specs.iter().position(|s| s.0 == p.name) else {
                let names: Vec<&str> = specs.iter().map(|s| s.0).collect();
                let mut e = Problem::error(
                    p.name_pos,
                    format!(
                        "unknown parameter \"{}\" of {what} \"{}\"",
                        p.name, call.name
                    ),
                );
                e.help = suggestion(&p.name, &names, "parameters");
                problems.push(e);
                continue;
            };
            let (name, kind, _) = specs[i];
            let ok = match kind {
                Kind::Float => p.decl.ty == Ty::Float && p.nums().len() == 1,
                Kind::Color | Kind::Point => p.decl.ty == Ty::Triple && p.nums().len() == 3,
                Kind::Str => p.decl.ty == Ty::Str,
            };
            if !ok {
                let want = match kind {
                    Kind::Float => "one float",
                    Kind::Color => "one color (3 numbers)",
                    Kind::Point => "one point (3 numbers)",
                    Kind::Str => "a string",
                };
                problems.push(Problem::error(
                    p.pos(),
                    format!(
                        "parameter \"{name}\" of {what} \"{}\" takes {want}",
                        call.name
                    ),
                ));
                continue;
            }
            found[i] = Some(p);
        }
        Self { found }
    }

    pub(super) fn num(&self, i: usize, default: f64) -> f64 {
        self.found[i].map_or(default, Param::num)
    }

    pub(super) fn triple(&self, i: usize, default: V3) -> V3 {
        self.found[i].map_or(default, Param::triple)
    }

    fn string(&self, i: usize) -> Option<&'a Param> {
        self.found[i]
    }
}

/// The parameters of the surface `name` (`defaultsurface`'s for a surface we do not have).
fn surface_specs(name: &str) -> &'static [Spec] {
    match name {
        "constant" => CONSTANT,
        "matte" => MATTE,
        "metal" => METAL,
        "shinymetal" => SHINY_METAL,
        "plastic" => PLASTIC,
        "paintedplastic" => PAINTED_PLASTIC,
        _ => DEFAULT_SURFACE,
    }
}

/// The parameters of the light `name` (`spotlight`'s for any other).
fn light_specs(name: &str) -> &'static [Spec] {
    match name {
        "ambientlight" => AMBIENT,
        "pointlight" => POINT,
        "distantlight" => DISTANT,
        _ => SPOT,
    }
}

/// How messages name a shader of ours called by `request` (`Surface`, `Displacement`,
/// `LightSource`, `AreaLightSource`, `Atmosphere`) and the parameters it takes; `None` for a
/// shader we do not have (its parameters are read as declared, and it is ignored).
pub fn parameter_names(request: &str, name: &str) -> Option<(String, Vec<&'static str>)> {
    if let Some((what, specs)) = tutorial::parameter_names(request, name) {
        return Some((format!("{what} \"{name}\""), specs));
    }
    let names = |specs: &[Spec]| specs.iter().map(|s| s.0).collect::<Vec<_>>();
    let (what, specs): (&str, Vec<&'static str>) = match request {
        "Surface" if SURFACES.contains(&name) => ("surface", names(surface_specs(name))),
        "Displacement" if DISPLACEMENTS.contains(&name) => ("displacement", names(SINE)),
        "LightSource" if LIGHTS.contains(&name) => ("light", names(light_specs(name))),
        "AreaLightSource" if name == "arealight" => ("light", vec!["intensity", "lightcolor"]),
        "Atmosphere" if name == "fog" => ("atmosphere", names(FOG)),
        _ => return None,
    };
    Some((format!("{what} \"{name}\""), specs))
}

/// A surface shader with the value paths of its parameters (relative to the shader).
pub struct Surface {
    /// The shader.
    pub shader: ShaderDesc,
    /// `(path below the shader, position)` of each written parameter.
    pub paths: Vec<(String, Pos)>,
    /// `paintedplastic`'s `texturename`, as written, with its position.
    pub texture: Option<(String, Pos)>,
    /// Parameters driven by node graphs (the tutorial's `mySurface` pattern).
    pub bind: BTreeMap<String, InputDesc>,
    /// The material's bump (the tutorial's `stairs` normal).
    pub bump: Option<BumpDesc>,
    /// `(path below the bump, position)` of the bump and its written parameters.
    pub bump_paths: Vec<(String, Pos)>,
}

/// Checks a colour written as `what` (`Color`, `Opacity`, `parameter "Cs" of Sphere`): every
/// channel finite and not negative, an opacity (`opacity`: true) at most 1. `Err`: one
/// located error for the whole value, at its first channel out of range (`at`: where each
/// channel is written).
pub fn check_colour(what: &str, opacity: bool, c: [f64; 3], at: [Pos; 3]) -> Result<(), Problem> {
    let bad = |x: f64| !x.is_finite() || x < 0.0 || opacity && x > 1.0;
    let Some(k) = c.iter().position(|&x| bad(x)) else {
        return Ok(());
    };
    let found = format!("{} {} {}", c[0], c[1], c[2]);
    Err(if !c[k].is_finite() {
        Problem::error(at[k], format!("{what} must be finite, found {found}"))
    } else if opacity {
        Problem::error(
            at[k],
            format!("{what} must be between 0 and 1 in every channel, found {found}"),
        )
        .with_help("an opacity is the fraction of light a surface stops: 1 is opaque, 0 invisible")
    } else {
        Problem::error(at[k], format!("{what} must not be negative, found {found}"))
    })
}

/// Checks the coefficients of a `Surface` or `AreaLightSource` call where it is written, so
/// that a bad one is reported under the parameter's RIB name (`Kd of "plastic" must not be
/// negative`), once, not as the description field it becomes (`Ks` and `specularcolor` are
/// multiplied into one `specular` colour): `Ka`, `Kd`, `Ks`, `Kr` and `intensity` not
/// negative and within f32, `roughness` positive, `specularcolor` and `lightcolor` colours.
pub fn check_coefficients(call: &ShaderCall, problems: &mut Vec<Problem>) {
    for p in &call.params {
        let name = p.name.as_str();
        let what = format!("{name} of \"{}\"", call.name);
        match (name, p.nums()) {
            ("Ka" | "Kd" | "Ks" | "Kr" | "intensity", &[x]) => {
                if !x.is_finite() || x.abs() > f64::from(f32::MAX) {
                    problems.push(Problem::error(
                        p.pos(),
                        format!("{what} {x:e} is beyond the f32 range"),
                    ));
                } else if x < 0.0 {
                    problems.push(Problem::error(
                        p.pos(),
                        format!("{what} must not be negative, found {x}"),
                    ));
                }
            }
            ("roughness", &[x]) if !(x > 0.0 && x <= f64::from(f32::MAX)) => {
                problems.push(Problem::error(
                    p.pos(),
                    format!("{what} must be positive, found {x}"),
                ));
            }
            ("specularcolor" | "lightcolor", &[r, g, b]) => {
                let at = [0, 1, 2].map(|k| p.value.item(k));
                if let Err(e) = check_colour(&what, false, [r, g, b], at) {
                    problems.push(e);
                }
            }
            _ => {}
        }
    }
}

/// The surface shader of `call` (`None`: `defaultsurface`) with colour `cs` and opacity
/// `os`; the tutorial's shaders are [`super::tutorial::surface`].
///
/// `constant` and `defaultsurface` are light-independent and map onto their own shaders;
/// `matte`, `metal`, `shinymetal`, `plastic` and `paintedplastic` become `Local` models with
/// the formulas of the RenderMan Interface Specification 3.2:
///
/// - `matte`: `Cs·(Ka·ambient() + Kd·diffuse(Nf))`;
/// - `metal`: `Cs·(Ka·ambient() + Ks·specular(Nf, V, roughness))`;
/// - `shinymetal`: `metal` `+ Cs·Kr·environment(texturename, R)` — the map is not read, a
///   traced mirror reflection stands in for it when `texturename` is given (an empty name
///   looks up nothing, as the specification's `environment("")`);
/// - `plastic`: `Cs·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V,
///   roughness)`;
/// - `paintedplastic`: `plastic` with `Cs` times `texture(texturename)`.
pub fn surface(call: Option<&ShaderCall>, cs: V3, os: V3, problems: &mut Vec<Problem>) -> Surface {
    if let Some(c) = call.filter(|c| tutorial::SURFACES.contains(&c.name.as_str())) {
        return tutorial::surface(c, cs, os, problems);
    }
    let name = call.map_or("defaultsurface", |c| c.name.as_str());
    let specs = surface_specs(name);
    let v = match call {
        Some(c) if SURFACES.contains(&name) => Values::read(c, "surface", specs, problems),
        _ => Values {
            found: vec![None; specs.len()],
        },
    };
    let white = (1.0, 1.0, 1.0);
    let black = (0.0, 0.0, 0.0);
    let scale = |k: f64, c: V3| (k * c.0, k * c.1, k * c.2);
    let local =
        |ka: f64, kd: f64, specular: V3, roughness: f64, reflection: V3| ShaderDesc::Local {
            color: cs,
            ka,
            kd,
            specular,
            lobe: LocalLobeDesc::RenderMan { roughness },
            reflection,
            ambient: black,
        };
    // Description fields of each RIB parameter, below `.Local` (or the shader's variant).
    let mut fields: Vec<(usize, &'static str)> = Vec::new();
    let mut texture = None;
    let shader = match name {
        "constant" => ShaderDesc::Constant { color: cs },
        "matte" => {
            fields = vec![(0, "ka"), (1, "kd")];
            local(v.num(0, 1.0), v.num(1, 1.0), black, 0.1, black)
        }
        "metal" => {
            fields = vec![(0, "ka"), (1, "specular"), (2, "lobe.RenderMan.roughness")];
            local(
                v.num(0, 1.0),
                0.0,
                scale(v.num(1, 1.0), cs),
                v.num(2, 0.1),
                black,
            )
        }
        "shinymetal" => {
            fields = vec![
                (0, "ka"),
                (1, "specular"),
                (2, "reflection"),
                (3, "lobe.RenderMan.roughness"),
            ];
            let map = v.string(4).filter(|t| !t.str().is_empty());
            if let Some(t) = map {
                problems.push(Problem::warning(
                    t.pos(),
                    format!(
                        "\"texturename\" \"{}\" of \"shinymetal\": a traced mirror reflection \
                         stands in for the environment map",
                        t.str()
                    ),
                ));
            }
            let kr = if map.is_some() { v.num(2, 1.0) } else { 0.0 };
            local(
                v.num(0, 1.0),
                0.0,
                scale(v.num(1, 1.0), cs),
                v.num(3, 0.1),
                scale(kr, cs),
            )
        }
        "plastic" | "paintedplastic" => {
            fields = vec![
                (0, "ka"),
                (1, "kd"),
                (2, "specular"),
                (3, "lobe.RenderMan.roughness"),
                (4, "specular"),
            ];
            if name == "paintedplastic" {
                texture = v
                    .string(5)
                    .filter(|t| !t.str().is_empty())
                    .map(|t| (t.str().to_string(), t.pos()));
            }
            local(
                v.num(0, 1.0),
                v.num(1, 0.5),
                scale(v.num(2, 0.5), v.triple(4, white)),
                v.num(3, 0.1),
                black,
            )
        }
        _ => {
            fields = vec![(0, "ka"), (1, "kd")];
            ShaderDesc::DefaultSurface {
                ka: v.num(0, 0.2),
                kd: v.num(1, 0.8),
                color: cs,
            }
        }
    };
    let variant = match shader {
        ShaderDesc::Constant { .. } => "Constant",
        ShaderDesc::DefaultSurface { .. } => "DefaultSurface",
        _ => "Local",
    };
    // Without a `Surface` request the material's own position (the primitive's) stands.
    let mut paths: Vec<(String, Pos)> = call
        .map(|c| (format!(".{variant}"), c.pos))
        .into_iter()
        .collect();
    for (i, field) in fields {
        if let Some(p) = v.found[i] {
            paths.push((format!(".{variant}.{field}"), p.pos()));
        }
    }
    Surface {
        shader,
        paths,
        texture,
        bind: BTreeMap::new(),
        bump: None,
        bump_paths: Vec::new(),
    }
}

const SINE: &[Spec] = &[
    ("amplitude", Kind::Float, None),
    ("factor", Kind::Float, None),
    ("axis", Kind::Str, None),
];

/// stagelight's `sine` displacement: `amplitude · sin(coord · factor · π)` along the
/// normal, over `s`, `t` or both (`"st"`: the sum) — the tutorial's `myDisplacement` with parameters
/// (defaults: amplitude 0.1, factor 20, axis "st").
pub fn displacement(call: &ShaderCall, problems: &mut Vec<Problem>) -> Option<ScalarDesc> {
    if call.name == "myDisplacement" {
        return tutorial::displacement(call, problems);
    }
    let v = Values::read(call, "displacement", SINE, problems);
    let amplitude = v.num(0, 0.1);
    let factor = v.num(1, 20.0);
    let sine = |axis| ScalarDesc::Sine {
        amplitude,
        factor,
        axis,
    };
    match v.string(2).map_or("st", Param::str) {
        "s" => Some(sine(AxisDesc::U)),
        "t" => Some(sine(AxisDesc::V)),
        "st" => Some(ScalarDesc::Sum(vec![sine(AxisDesc::V), sine(AxisDesc::U)])),
        other => {
            let p = v.string(2).expect("a value was read");
            problems.push(
                Problem::error(p.pos(), format!("unknown axis \"{other}\" of \"sine\""))
                    .with_help("expected \"s\", \"t\" or \"st\""),
            );
            None
        }
    }
}

const FOG: &[Spec] = &[
    ("distance", Kind::Float, None),
    ("background", Kind::Color, None),
];

/// The standard volume shader `fog` (RISpec 3.2, an `Atmosphere`):
/// `Ci = mix(Ci, background, 1 − exp(−length(I) / distance))`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FogValues {
    /// `distance` (default 1), camera-space units, above 0, and where it is written.
    pub distance: (f64, Option<Pos>),
    /// `background` (default black) and where it is written.
    pub background: (V3, Option<Pos>),
}

impl FogValues {
    /// The same distance and background (wherever they are written).
    pub fn same_fog(&self, other: &FogValues) -> bool {
        self.distance.0 == other.distance.0 && self.background.0 == other.background.0
    }
}

/// Reads an `Atmosphere "fog"` call: `None` when a value is wrong (reported).
pub fn fog(call: &ShaderCall, problems: &mut Vec<Problem>) -> Option<FogValues> {
    let before = problems.len();
    let v = Values::read(call, "atmosphere", FOG, problems);
    let distance = v.num(0, 1.0);
    if let Some(p) = v.found[0] {
        if !(distance > 0.0 && distance.is_finite()) {
            problems.push(Problem::error(
                p.pos(),
                format!("distance of \"fog\" must be above 0, found {distance}"),
            ));
        }
    }
    if let Some(p) = v.found[1] {
        let (r, g, b) = p.triple();
        let at = [0, 1, 2].map(|k| p.value.item(k));
        if let Err(e) = check_colour("background of \"fog\"", false, [r, g, b], at) {
            problems.push(e);
        }
    }
    (problems.len() == before).then(|| FogValues {
        distance: (distance, v.found[0].map(Param::pos)),
        background: (v.triple(1, (0.0, 0.0, 0.0)), v.found[1].map(Param::pos)),
    })
}

const AMBIENT: &[Spec] = &[
    ("intensity", Kind::Float, Some("intensity")),
    ("lightcolor", Kind::Color, Some("color")),
];
const POINT: &[Spec] = &[
    ("intensity", Kind::Float, Some("intensity")),
    ("lightcolor", Kind::Color, Some("color")),
    ("from", Kind::Point, Some("kind.Point.position")),
];
const DISTANT: &[Spec] = &[
    ("intensity", Kind::Float, Some("intensity")),
    ("lightcolor", Kind::Color, Some("color")),
    ("from", Kind::Point, Some("kind.Directional.direction")),
    ("to", Kind::Point, Some("kind.Directional.direction")),
];
const SPOT: &[Spec] = &[
    ("intensity", Kind::Float, Some("intensity")),
    ("lightcolor", Kind::Color, Some("color")),
    ("from", Kind::Point, Some("kind.Spot.position")),
    ("to", Kind::Point, Some("kind.Spot.target")),
    ("coneangle", Kind::Float, Some("kind.Spot.cone_angle")),
    ("conedeltaangle", Kind::Float, Some("kind.Spot.penumbra")),
    (
        "beamdistribution",
        Kind::Float,
        Some("kind.Spot.beam_distribution"),
    ),
];

/// A light shader's values, in the light's shader space (points untransformed).
#[derive(Debug, Clone, PartialEq)]
pub enum LightShader {
    /// `ambientlight`.
    Ambient,
    /// `pointlight`.
    Point {
        /// `from`.
        from: V3,
    },
    /// `distantlight`.
    Distant {
        /// `from`.
        from: V3,
        /// `to`.
        to: V3,
    },
    /// `spotlight`.
    Spot {
        /// `from`.
        from: V3,
        /// `to`.
        to: V3,
        /// `coneangle`, radians.
        cone: f64,
        /// `conedeltaangle`, radians.
        delta: f64,
        /// `beamdistribution`.
        beam: f64,
    },
    /// The tutorial's `myLight`: a point light whose `Cl` ramps linearly from full at `near`
    /// to none at `far`, with no 1/d² ([`super::tutorial::light`]).
    Ramp {
        /// `from`.
        from: V3,
        /// `near`.
        near: f64,
        /// `far`.
        far: f64,
    },
}

/// A light shader call read: shape, intensity, colour, and value paths (relative to the
/// light).
pub struct LightValues {
    /// The shape and its shader-space values.
    pub shader: LightShader,
    /// `intensity`.
    pub intensity: f64,
    /// `lightcolor`.
    pub color: V3,
    /// `(path below the light, position)` of each written parameter.
    pub paths: Vec<(String, Pos)>,
}

/// Reads a `LightSource` call of one of [`LIGHTS`].
pub fn light(call: &ShaderCall, problems: &mut Vec<Problem>) -> LightValues {
    if call.name == "myLight" {
        return tutorial::light(call, problems);
    }
    let specs = light_specs(&call.name);
    let v = Values::read(call, "light", specs, problems);
    let zero = (0.0, 0.0, 0.0);
    let default_cone = 30f64.to_radians();
    let spot = specs == SPOT;
    let mut cone = if spot { v.num(4, default_cone) } else { 0.0 };
    if let Some(p) = v.found.get(4).copied().flatten().filter(|_| spot) {
        if !(cone > 0.0 && cone <= std::f64::consts::FRAC_PI_2) {
            problems.push(
                Problem::error(
                    p.pos(),
                    format!(
                        "coneangle of \"spotlight\" must be above 0 and at most π/2 radians \
                         (90°), found {cone}"
                    ),
                )
                .with_help("light-shader angles are in radians: 0.5236 is 30°"),
            );
            cone = default_cone;
        }
    }
    let shader = match call.name.as_str() {
        "ambientlight" => LightShader::Ambient,
        "pointlight" => LightShader::Point {
            from: v.triple(2, zero),
        },
        "distantlight" => LightShader::Distant {
            from: v.triple(2, zero),
            to: v.triple(3, (0.0, 0.0, 1.0)),
        },
        _ => LightShader::Spot {
            from: v.triple(2, zero),
            to: v.triple(3, (0.0, 0.0, 1.0)),
            cone,
            delta: v.num(5, 5f64.to_radians()),
            beam: v.num(6, 2.0),
        },
    };
    let mut paths = Vec::new();
    for (spec, p) in specs.iter().zip(&v.found) {
        if let (Some(field), Some(p)) = (spec.2, p) {
            paths.push((format!(".{field}"), p.pos()));
        }
    }
    LightValues {
        shader,
        intensity: v.num(0, 1.0),
        color: v.triple(1, (1.0, 1.0, 1.0)),
        paths,
    }
}
