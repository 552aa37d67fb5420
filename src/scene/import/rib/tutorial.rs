//! The tutorial's RenderMan shaders (seed 001 prints their RSL source), built in by name:
//! `Surface "mySurface"` (§3.3, the repeated soft disk lit as `plastic`), `Surface
//! "simplemirror"` (§4.4, the RAT's traced mirror), `Surface "stairs"` (§4.2, `plastic` with
//! an object-space normal that fakes steps), `LightSource "myLight"` (§3.3, a point
//! light fading linearly from `near` to `far`), `Displacement "myDisplacement"` (§3.3,
//! `0.1·sin(20πt) + 0.1·sin(20πs)` along the normal) and `Imager "myImager"` (§3.2.3, the
//! soft disk painted over every pixel in raster space). A RenderMan renderer loads a shader
//! compiled from its `.sl` file; stagelight compiles no RSL, so the name alone selects the
//! printed source (`docs/rib.md`, *The tutorial's shaders*). Where the tutorial prints a
//! shader of the same name more than once, the last version is the one built in.
//!
//! Each maps onto the stagelight component that computes what its RSL computes; parameters
//! written in the call override the RSL defaults, and a parameter the RSL does not declare is
//! a located error with "did you mean".

use std::collections::BTreeMap;

use super::super::located::{Pos, Problem};
use super::shaders::{Kind, LightShader, LightValues, Spec, Surface, Values};
use super::state::ShaderCall;
use crate::scene::desc::{AxisDesc, ImagerPatternDesc, LocalLobeDesc, ScalarDesc, ShaderDesc, V3};
use crate::scene::nodes_desc::{BumpDesc, InputDesc, NodeDesc};

/// The tutorial's surface shaders.
pub const SURFACES: &[&str] = &["mySurface", "simplemirror", "stairs"];

/// The tutorial's light shaders.
pub const LIGHTS: &[&str] = &["myLight"];

/// The tutorial's displacement shaders.
pub const DISPLACEMENTS: &[&str] = &["myDisplacement"];

/// The tutorial's imager shaders.
pub const IMAGERS: &[&str] = &["myImager"];

/// `mySurface(float Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1; color specularcolor = 1)`.
const MY_SURFACE: &[Spec] = &[
    ("Ka", Kind::Float, Some("ka")),
    ("Kd", Kind::Float, Some("kd")),
    ("Ks", Kind::Float, Some("specular")),
    ("roughness", Kind::Float, Some("lobe.RenderMan.roughness")),
    ("specularcolor", Kind::Color, Some("specular")),
];

/// `stairs(float Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1; color specularcolor = 1;
/// float steps = 4, fuzz = 0.05)` (§4.2's last version).
const STAIRS: &[Spec] = &[
    ("Ka", Kind::Float, Some("ka")),
    ("Kd", Kind::Float, Some("kd")),
    ("Ks", Kind::Float, Some("specular")),
    ("roughness", Kind::Float, Some("lobe.RenderMan.roughness")),
    ("specularcolor", Kind::Color, Some("specular")),
    ("steps", Kind::Float, None),
    ("fuzz", Kind::Float, None),
];

/// `simplemirror ( )`, `myDisplacement()` and `myImager()` take no parameters.
const NONE: &[Spec] = &[];

/// `myLight(float intensity = 1, near = 1, far = 10; color lightcolor = 1; point from =
/// point "shader" (0,0,0))`.
const MY_LIGHT: &[Spec] = &[
    ("intensity", Kind::Float, Some("intensity")),
    ("near", Kind::Float, Some("attenuation")),
    ("far", Kind::Float, Some("attenuation")),
    ("lightcolor", Kind::Color, Some("color")),
    ("from", Kind::Point, Some("kind.Point.position")),
];

/// The owner text and parameter names of the tutorial shader `name` for `request`
/// (`Surface`, `LightSource`, `Displacement`, `Imager`), for the reader's unknown-parameter message.
pub fn parameter_names(request: &str, name: &str) -> Option<(&'static str, Vec<&'static str>)> {
    let names = |specs: &[Spec]| specs.iter().map(|s| s.0).collect::<Vec<_>>();
    match request {
        "Surface" if name == "mySurface" => Some(("surface", names(MY_SURFACE))),
        "Surface" if name == "stairs" => Some(("surface", names(STAIRS))),
        "Surface" if SURFACES.contains(&name) => Some(("surface", names(NONE))),
        "LightSource" if LIGHTS.contains(&name) => Some(("light", names(MY_LIGHT))),
        "Displacement" if DISPLACEMENTS.contains(&name) => Some(("displacement", names(NONE))),
        "Imager" if IMAGERS.contains(&name) => Some(("imager", names(NONE))),
        _ => None,
    }
}

/// The `(path below the shader, position)` of each written parameter of `specs`.
fn written_paths(specs: &[Spec], v: &Values<'_>, prefix: &str) -> Vec<(String, Pos)> {
    specs
        .iter()
        .zip(&v.found)
        .filter_map(|(spec, p)| Some((format!("{prefix}.{}", spec.2?), p.as_ref()?.pos())))
        .collect()
}

/// The tutorial's surface `call` (one of [`SURFACES`]) with colour `cs` and opacity `os`:
///
/// - `mySurface`: `Ci = Os·(myCs·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·
///   specular(Nf, V, roughness))` with `myCs = Os·mix(red, yellow, 1 − smoothstep(0.3, 0.5,
///   distance((0.5, 0.5), (mod(10s, 1), mod(10t, 1)))))` — `plastic`'s `Local` with its colour
///   bound to `Disk(uv: Repeat(scale: 10), radius: 0.4, fuzz: 0.1, inside: (1, 1, 0),
///   outside: (1, 0, 0))` (times `Os`). `Cs` is not used: the RSL never reads it.
/// - `simplemirror`: `Ci = Os·trace(P, reflect(I, N))` — a `Local` with nothing but a white
///   traced mirror reflection.
/// - `stairs`: [`stairs`].
pub fn surface(call: &ShaderCall, cs: V3, os: V3, problems: &mut Vec<Problem>) -> Surface {
    let black = (0.0, 0.0, 0.0);
    if call.name == "stairs" {
        return stairs(call, cs, problems);
    }
    if call.name == "simplemirror" {
        Values::read(call, "surface", NONE, problems);
        return Surface {
            shader: ShaderDesc::Local {
                color: black,
                ka: 0.0,
                kd: 0.0,
                specular: black,
                lobe: LocalLobeDesc::RenderMan { roughness: 0.1 },
                reflection: (1.0, 1.0, 1.0),
                ambient: black,
            },
            paths: vec![(".Local".into(), call.pos)],
            texture: None,
            bind: BTreeMap::new(),
            bump: None,
            bump_paths: Vec::new(),
        };
    }
    let v = Values::read(call, "surface", MY_SURFACE, problems);
    let ks = v.num(2, 0.5);
    let sc = v.triple(4, (1.0, 1.0, 1.0));
    let shader = ShaderDesc::Local {
        color: (1.0, 1.0, 1.0),
        ka: v.num(0, 1.0),
        kd: v.num(1, 0.5),
        specular: (ks * sc.0, ks * sc.1, ks * sc.2),
        lobe: LocalLobeDesc::RenderMan {
            roughness: v.num(3, 0.1),
        },
        reflection: black,
        ambient: black,
    };
    let mut paths = vec![(".Local".to_string(), call.pos)];
    paths.extend(written_paths(MY_SURFACE, &v, ".Local"));
    let node = |n: NodeDesc| InputDesc::Node(Box::new(n));
    let mut disk = node(NodeDesc::Disk {
        uv: node(NodeDesc::Repeat {
            uv: node(NodeDesc::Uv),
            scale: InputDesc::Number(10.0),
        }),
        center: (0.5, 0.5),
        radius: InputDesc::Number(0.4),
        fuzz: InputDesc::Number(0.1),
        inside: InputDesc::Colour((1.0, 1.0, 0.0)),
        outside: InputDesc::Colour((1.0, 0.0, 0.0)),
    });
    if os != (1.0, 1.0, 1.0) {
        // `myCs = Os * mix(…)`: the opacity once more inside the bracket.
        disk = node(NodeDesc::Mul(InputDesc::Colour(os), disk));
    }
    Surface {
        shader,
        paths,
        texture: None,
        bind: BTreeMap::from([("color".to_string(), disk)]),
        bump: None,
        bump_paths: Vec::new(),
    }
}

/// `stairs` (§4.2, the version with `fuzz`): `Ci = Os·(Cs·(Ka·ambient() + Kd·diffuse(Nf)) +
/// specularcolor·Ks·specular(Nf, V, roughness))` — `plastic`'s formula — with `Nf` the
/// object-space riser normal `front = (0, −1, 0)` or tread normal `up = (0, 0, 1)` chosen by
/// `sv = mod(v·steps, 1)` and blended linearly within `fuzz` of each edge: `plastic`'s
/// `Local` with `bump: (object_normal: Mix(a: (0, −1, 0), b: (0, 0, 1), t: Steps(steps,
/// fuzz)))` (the blend weight is [`crate::shading::texture::pattern::steps`]).
fn stairs(call: &ShaderCall, cs: V3, problems: &mut Vec<Problem>) -> Surface {
    let black = (0.0, 0.0, 0.0);
    let v = Values::read(call, "surface", STAIRS, problems);
    let ks = v.num(2, 0.5);
    let sc = v.triple(4, (1.0, 1.0, 1.0));
    let shader = ShaderDesc::Local {
        color: cs,
        ka: v.num(0, 1.0),
        kd: v.num(1, 0.5),
        specular: (ks * sc.0, ks * sc.1, ks * sc.2),
        lobe: LocalLobeDesc::RenderMan {
            roughness: v.num(3, 0.1),
        },
        reflection: black,
        ambient: black,
    };
    let mut paths = vec![(".Local".to_string(), call.pos)];
    paths.extend(written_paths(STAIRS, &v, ".Local"));
    let steps = NodeDesc::Steps {
        uv: InputDesc::Node(Box::new(NodeDesc::Uv)),
        steps: InputDesc::Number(v.num(5, 4.0)),
        fuzz: InputDesc::Number(v.num(6, 0.05)),
    };
    let normal = NodeDesc::Mix {
        a: InputDesc::Colour((0.0, -1.0, 0.0)),
        b: InputDesc::Colour((0.0, 0.0, 1.0)),
        t: InputDesc::Node(Box::new(steps)),
    };
    let mut bump_paths = vec![
        (String::new(), call.pos),
        (".object_normal".to_string(), call.pos),
    ];
    for (i, field) in [(5, "steps"), (6, "fuzz")] {
        if let Some(p) = v.found[i] {
            bump_paths.push((format!(".object_normal.Mix.t.Steps.{field}"), p.pos()));
        }
    }
    Surface {
        shader,
        paths,
        texture: None,
        bind: BTreeMap::new(),
        bump: Some(BumpDesc {
            height: None,
            normal_map: None,
            object_normal: Some(InputDesc::Node(Box::new(normal))),
            scale: 1.0,
        }),
        bump_paths,
    }
}

/// `myLight`: `illuminate(from) Cl = intensity·lightcolor·brightness`, `brightness` 1 up to
/// `near`, 0 beyond `far` and `1 − (len − near)/(far − near)` between — a point light
/// without 1/d² (`inverse_square: false`) with `attenuation: (near, far)`.
pub fn light(call: &ShaderCall, problems: &mut Vec<Problem>) -> LightValues {
    let v = Values::read(call, "light", MY_LIGHT, problems);
    LightValues {
        shader: LightShader::Ramp {
            from: v.triple(4, (0.0, 0.0, 0.0)),
            near: v.num(1, 1.0),
            far: v.num(2, 10.0),
        },
        intensity: v.num(0, 1.0),
        color: v.triple(3, (1.0, 1.0, 1.0)),
        paths: written_paths(MY_LIGHT, &v, ""),
    }
}

/// `myDisplacement()`: `amp = 0.1·sin(t·20·π) + 0.1·sin(s·20·π); P += amp·normalize(N)` —
/// the sum of two `Sine(amplitude: 0.1, factor: 20)` over `t` (V) and `s` (U).
pub fn displacement(call: &ShaderCall, problems: &mut Vec<Problem>) -> Option<ScalarDesc> {
    Values::read(call, "displacement", NONE, problems);
    let sine = |axis| ScalarDesc::Sine {
        amplitude: 0.1,
        factor: 20.0,
        axis,
    };
    Some(ScalarDesc::Sum(vec![sine(AxisDesc::V), sine(AxisDesc::U)]))
}

/// `myImager()` (§3.2.3, the last version: the disk with the `fuzz` diff applied):
/// `here = (xcomp(P)/xres, ycomp(P)/yres, 0)`, `inDisk = 1 − smoothstep(radius − fuzz,
/// radius + fuzz, distance((0.5, 0.5, 0), here))` with `radius` 0.4 and `fuzz` 0.1,
/// `Ci = mix(red, yellow, inDisk)`, `Oi = 1`, `alpha = 1` — the imager's `Disk` pattern. Its
/// variables are locals of the RSL (its comment says some should be parameters), so a call
/// takes no parameters.
pub fn imager(call: &ShaderCall, problems: &mut Vec<Problem>) -> ImagerPatternDesc {
    Values::read(call, "imager", NONE, problems);
    ImagerPatternDesc::Disk {
        center: (0.5, 0.5),
        radius: 0.4,
        fuzz: 0.1,
        inside: (1.0, 1.0, 0.0),
        outside: (1.0, 0.0, 0.0),
    }
}
