//! Checking shader graphs and compiling them: every material's `bind` entries and `bump`
//! (height, normal map or object-space normal), with the phenomena they call, become one flat [`Program`] per material
//! ([`MaterialGraph`]).
//!
//! Errors are located at the offending value: an unknown node (re-parsed from the source
//! text so `ron`'s own message and suggestion apply), a colour where a number is expected,
//! an unknown shader or interface parameter (with "did you mean"), an unknown phenomenon,
//! a phenomenon that uses itself, an unreadable image file. A phenomenon's body is checked
//! once, where it is declared; a call checks only its arguments.
//!
//! Phenomena are expanded inline at every call (their arguments compiled in the caller's
//! context, missing ones from the declared defaults), so a program never calls anything.

mod depth;
mod phenomena;
mod size;
mod textures;

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::desc::{MaterialDesc, V3};
use super::diagnostics::{suggestion, Sources};
use super::nodes_desc::{
    AxisWrapDesc, ColourSpaceDesc, EncodingDesc, InputDesc, NodeDesc, WrapDesc, EMISSION,
    NODE_NAMES,
};
use super::validate::Item;
use super::validate::Merged;
use crate::components::Material;
use crate::shading::texture::bind::{self, ParamType};
use crate::shading::texture::colour::ColourSpace;
use crate::shading::texture::image::{self, Encoding, Texture, UvWrap, Wrap};
use crate::shading::texture::noise::Fractal;
use crate::shading::texture::{
    Binding, BumpMap, MaterialGraph, NoiseKind, NormalMap, Op, Program, Reg,
};
pub use phenomena::{check_phenomena, Phenomena};
use phenomena::{ensure_checked, variant_name};
use size::Size;
pub use textures::DecodedTexture;

/// The type of a node's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ty {
    /// One number.
    Scalar,
    /// Three channels.
    Colour,
}

impl Ty {
    fn join(self, other: Ty) -> Ty {
        if self == Ty::Colour || other == Ty::Colour {
            Ty::Colour
        } else {
            Ty::Scalar
        }
    }
}

impl From<ParamType> for Ty {
    fn from(t: ParamType) -> Self {
        match t {
            ParamType::Colour => Ty::Colour,
            ParamType::Scalar => Ty::Scalar,
        }
    }
}

/// Where a value is: file and path.
#[derive(Clone, Copy)]
pub(super) struct At<'p> {
    /// File index in `Sources::files`.
    pub(super) file: usize,
    /// Path of the value in its file.
    pub(super) path: &'p str,
}

/// One compilation: the program being built, whether errors are reported.
pub(super) struct Compiler<'c, 'a> {
    /// Where errors go.
    pub(super) src: &'c mut Sources,
    /// The phenomena (and the texture cache).
    pub(super) ph: &'c mut Phenomena<'a>,
    /// The program being built.
    pub(super) prog: Program,
    /// Phenomena being expanded (innermost last).
    pub(super) stack: Vec<usize>,
    /// Whether errors are reported (off while re-expanding an already checked body).
    pub(super) report: bool,
    /// Whether the program has passed [`size::MAX_EXPANDED_NODES`].
    pub(super) size: Size,
}

/// Interface parameter values inside a phenomenon body.
pub(super) type Env = [(String, Ty, Reg)];

impl Compiler<'_, '_> {
    fn error(&mut self, at: At<'_>, message: impl Into<String>, help: Option<String>) {
        if self.report {
            self.src.error(at.file, at.path, message, help);
        }
    }

    fn constant(&mut self, v: Vec3) -> Reg {
        self.prog.push(Op::Const(v))
    }

    fn finite(&mut self, at: At<'_>, what: &str, x: f64) -> Option<f32> {
        if x.is_finite() && x.abs() <= f64::from(f32::MAX) {
            Some(x as f32)
        } else {
            self.error(
                at,
                format!("{what} must be a finite number, found {x}"),
                None,
            );
            None
        }
    }

    fn colour(&mut self, at: At<'_>, v: V3) -> Option<Vec3> {
        let mut ok = true;
        let mut out = [0.0; 3];
        for (k, x) in [v.0, v.1, v.2].into_iter().enumerate() {
            let p = format!("{}[{k}]", at.path);
            match self.finite(
                At {
                    file: at.file,
                    path: &p,
                },
                "a colour channel",
                x,
            ) {
                Some(x) => out[k] = x,
                None => ok = false,
            }
        }
        ok.then(|| Vec3::from(out))
    }

    /// Compiles an input; `env` holds the interface parameters when inside a phenomenon.
    pub(super) fn input(&mut self, at: At<'_>, d: &InputDesc, env: &Env) -> Option<(Reg, Ty)> {
        match d {
            InputDesc::Number(x) => {
                let x = self.finite(at, &number_name(at.path), *x)?;
                Some((self.constant(Vec3::splat(x)), Ty::Scalar))
            }
            InputDesc::Colour(v) => {
                let c = self.colour(at, *v)?;
                Some((self.constant(c), Ty::Colour))
            }
            InputDesc::Node(n) => self.node(at, n, env),
            InputDesc::Invalid(v) => {
                let node = self.reparse(at, v)?;
                self.node(at, &node, env)
            }
        }
    }

    /// Re-reads a value that is not a number, colour or node through its file's reader
    /// (`SourceMap::reread_node`): a node written with all defaults (`Fbm()`, `Uv`) parses
    /// there; a misspelt node gets the reader's message at the right position.
    fn reparse(&mut self, at: At<'_>, v: &ron::Value) -> Option<NodeDesc> {
        let name = match v {
            ron::Value::String(s) => Some(s.clone()),
            ron::Value::Map(m) if m.len() == 1 => match m.iter().next() {
                Some((ron::Value::String(s), _)) => Some(s.clone()),
                _ => None,
            },
            _ => None,
        };
        if let Some(name) = &name {
            if !NODE_NAMES.contains(&name.as_str()) {
                self.error(
                    at,
                    format!("unknown node \"{name}\""),
                    suggestion(name, NODE_NAMES, "nodes"),
                );
                return None;
            }
        }
        let reread = self
            .src
            .files
            .get(at.file)
            .and_then(|f| f.map.reread_node(at.path));
        match reread {
            Some(Ok(n)) => Some(n),
            Some(Err((pos, d))) if name.is_some() => {
                if self.report {
                    self.src.push(at.file, pos, d);
                }
                None
            }
            _ => {
                self.error(
                    at,
                    "expected a number, a colour (r, g, b) or a node such as Checker(…)",
                    None,
                );
                None
            }
        }
    }

    /// Compiles an input that must be a scalar.
    fn scalar(&mut self, at: At<'_>, d: &InputDesc, env: &Env, what: &str) -> Option<Reg> {
        let (reg, ty) = self.input(at, d, env)?;
        if ty == Ty::Colour {
            self.error(
                at,
                format!("{what} must be a number, but this gives a colour"),
                Some("take one channel with Channel(…, 0) or use Luminance(…)".into()),
            );
            return None;
        }
        Some(reg)
    }

    fn node(&mut self, at: At<'_>, n: &NodeDesc, env: &Env) -> Option<(Reg, Ty)> {
        let sub = |field: &str| format!("{}{field}", at.path);
        let file = at.file;
        macro_rules! input {
            ($field:expr, $d:expr) => {{
                let p = sub($field);
                self.input(At { file, path: &p }, $d, env)
            }};
        }
        macro_rules! scalar {
            ($field:expr, $d:expr, $what:expr) => {{
                let p = sub($field);
                self.scalar(At { file, path: &p }, $d, env, $what)
            }};
        }
        match n {
            NodeDesc::Uv => Some((self.prog.push(Op::Uv), Ty::Colour)),
            NodeDesc::Position => Some((self.prog.push(Op::Position), Ty::Colour)),
            NodeDesc::Normal => Some((self.prog.push(Op::Normal), Ty::Colour)),
            NodeDesc::VertexColor => Some((self.prog.push(Op::VertexColour), Ty::Colour)),
            NodeDesc::Checker { uv, scale, a, b } => {
                let uv = input!(".Checker.uv", uv);
                let scale = scalar!(".Checker.scale", scale, "scale");
                let a = input!(".Checker.a", a);
                let b = input!(".Checker.b", b);
                let ((uv, _), scale, (a, ta), (b, tb)) = (uv?, scale?, a?, b?);
                let r = self.prog.push(Op::Checker { uv, scale, a, b });
                Some((r, ta.join(tb)))
            }
            NodeDesc::Disk {
                uv,
                center,
                radius,
                fuzz,
                inside,
                outside,
            } => {
                let uv = input!(".Disk.uv", uv);
                let cp = sub(".Disk.center");
                let c0 = self.finite(At { file, path: &cp }, "center", center.0);
                let c1 = self.finite(At { file, path: &cp }, "center", center.1);
                let radius = scalar!(".Disk.radius", radius, "radius");
                let fuzz = scalar!(".Disk.fuzz", fuzz, "fuzz");
                let inside = input!(".Disk.inside", inside);
                let outside = input!(".Disk.outside", outside);
                let ((uv, _), c0, c1, radius, fuzz, (i, ti), (o, to)) =
                    (uv?, c0?, c1?, radius?, fuzz?, inside?, outside?);
                let r = self.prog.push(Op::Disk {
                    uv,
                    center: Vec2::new(c0, c1),
                    radius,
                    fuzz,
                    inside: i,
                    outside: o,
                });
                Some((r, ti.join(to)))
            }
            NodeDesc::Steps { uv, steps, fuzz } => {
                let uv = input!(".Steps.uv", uv);
                let steps = scalar!(".Steps.steps", steps, "steps");
                let fuzz = scalar!(".Steps.fuzz", fuzz, "fuzz");
                let ((uv, _), steps, fuzz) = (uv?, steps?, fuzz?);
                Some((self.prog.push(Op::Steps { uv, steps, fuzz }), Ty::Scalar))
            }
            NodeDesc::Repeat { uv, scale } => {
                let uv = input!(".Repeat.uv", uv);
                let scale = scalar!(".Repeat.scale", scale, "scale");
                let ((uv, _), scale) = (uv?, scale?);
                Some((self.prog.push(Op::Repeat { uv, scale }), Ty::Colour))
            }
            NodeDesc::Noise { p, frequency, seed } => {
                let p = input!(".Noise.p", p);
                let fp = sub(".Noise.frequency");
                let f = self.finite(At { file, path: &fp }, "frequency", *frequency);
                let ((p, _), frequency) = (p?, f?);
                let fractal = Fractal {
                    frequency,
                    octaves: 1,
                    lacunarity: 2.0,
                    gain: 0.5,
                    seed: *seed,
                };
                let op = Op::Noise {
                    p,
                    kind: NoiseKind::Perlin,
                    fractal,
                };
                Some((self.prog.push(op), Ty::Scalar))
            }
            NodeDesc::Fbm {
                p,
                frequency,
                octaves,
                lacunarity,
                gain,
                seed,
            }
            | NodeDesc::Turbulence {
                p,
                frequency,
                octaves,
                lacunarity,
                gain,
                seed,
            } => {
                let (v, kind) = if matches!(n, NodeDesc::Fbm { .. }) {
                    ("Fbm", NoiseKind::Fbm)
                } else {
                    ("Turbulence", NoiseKind::Turbulence)
                };
                let p = input!(&format!(".{v}.p"), p);
                let mut num = |field: &str, x: f64| {
                    let fp = sub(&format!(".{v}.{field}"));
                    self.finite(At { file, path: &fp }, field, x)
                };
                let (f, l, g) = (
                    num("frequency", *frequency),
                    num("lacunarity", *lacunarity),
                    num("gain", *gain),
                );
                let op = sub(&format!(".{v}.octaves"));
                let oct_ok = (1..=12).contains(octaves);
                if !oct_ok {
                    self.error(
                        At { file, path: &op },
                        format!("octaves must be in 1…12, found {octaves}"),
                        None,
                    );
                }
                let ((p, _), frequency, lacunarity, gain) = (p?, f?, l?, g?);
                if !oct_ok {
                    return None;
                }
                let fractal = Fractal {
                    frequency,
                    octaves: *octaves,
                    lacunarity,
                    gain,
                    seed: *seed,
                };
                Some((self.prog.push(Op::Noise { p, kind, fractal }), Ty::Scalar))
            }
            NodeDesc::Image {
                file: name,
                uv,
                wrap,
                color_space,
            } => {
                let uv = input!(".Image.uv", uv);
                let fp = sub(".Image.file");
                let texture = self.texture(At { file, path: &fp }, name, *wrap, *color_space);
                let ((uv, _), texture) = (uv?, texture?);
                Some((self.prog.push(Op::Image { uv, texture }), Ty::Colour))
            }
            NodeDesc::Alpha {
                file: name,
                uv,
                wrap,
            } => {
                let uv = input!(".Alpha.uv", uv);
                let fp = sub(".Alpha.file");
                // Alpha is linear whatever the colour space: share the default decoding.
                let texture = self.texture(At { file, path: &fp }, name, *wrap, None);
                let ((uv, _), texture) = (uv?, texture?);
                Some((self.prog.push(Op::ImageAlpha { uv, texture }), Ty::Scalar))
            }
            NodeDesc::Mix { a, b, t } => {
                let a = input!(".Mix.a", a);
                let b = input!(".Mix.b", b);
                let t = scalar!(".Mix.t", t, "t");
                let ((a, ta), (b, tb), t) = (a?, b?, t?);
                Some((self.prog.push(Op::Mix { a, b, t }), ta.join(tb)))
            }
            NodeDesc::Smoothstep { edge0, edge1, x } => {
                let e0 = scalar!(".Smoothstep.edge0", edge0, "edge0");
                let e1 = scalar!(".Smoothstep.edge1", edge1, "edge1");
                let x = scalar!(".Smoothstep.x", x, "x");
                let (edge0, edge1, x) = (e0?, e1?, x?);
                let op = Op::Smoothstep { edge0, edge1, x };
                Some((self.prog.push(op), Ty::Scalar))
            }
            NodeDesc::Add(a, b) | NodeDesc::Sub(a, b) | NodeDesc::Mul(a, b) => {
                let v = variant_name(n);
                let a = input!(&format!(".{v}[0]"), a);
                let b = input!(&format!(".{v}[1]"), b);
                let ((a, ta), (b, tb)) = (a?, b?);
                let op = match n {
                    NodeDesc::Add(..) => Op::Add(a, b),
                    NodeDesc::Sub(..) => Op::Sub(a, b),
                    _ => Op::Mul(a, b),
                };
                Some((self.prog.push(op), ta.join(tb)))
            }
            NodeDesc::Channel(a, k) => {
                let a = input!(".Channel[0]", a);
                if *k > 2 {
                    let p = sub(".Channel[1]");
                    self.error(
                        At { file, path: &p },
                        format!("channel must be 0, 1 or 2, found {k}"),
                        None,
                    );
                    return None;
                }
                let (a, _) = a?;
                Some((self.prog.push(Op::Channel(a, *k as u8)), Ty::Scalar))
            }
            NodeDesc::Luminance(a) => {
                let (a, _) = input!(".Luminance[0]", a)?;
                Some((self.prog.push(Op::Luminance(a)), Ty::Scalar))
            }
            NodeDesc::Combine(a, b, c) => {
                let a = scalar!(".Combine[0]", a, "each Combine input");
                let b = scalar!(".Combine[1]", b, "each Combine input");
                let c = scalar!(".Combine[2]", c, "each Combine input");
                let (a, b, c) = (a?, b?, c?);
                Some((self.prog.push(Op::Combine(a, b, c)), Ty::Colour))
            }
            NodeDesc::Convert { input, from, to } => {
                let (input, _) = input!(".Convert.input", input)?;
                let op = Op::Convert {
                    input,
                    from: space(*from),
                    to: space(*to),
                };
                Some((self.prog.push(op), Ty::Colour))
            }
            NodeDesc::Param(name) => {
                if self.stack.is_empty() {
                    self.error(
                        at,
                        format!("Param(\"{name}\") is only allowed inside a phenomenon"),
                        Some(
                            "declare the graph under `phenomena` and call it with Graph(…)".into(),
                        ),
                    );
                    return None;
                }
                match env.iter().find(|(k, ..)| k == name) {
                    Some((_, ty, reg)) => Some((*reg, *ty)),
                    None => {
                        let names: Vec<&str> = env.iter().map(|(k, ..)| k.as_str()).collect();
                        let ph = &self.ph.items[*self.stack.last().unwrap_or(&0)].desc.name;
                        self.error(
                            at,
                            format!("phenomenon \"{ph}\" has no parameter \"{name}\""),
                            suggestion(name, &names, "parameters"),
                        );
                        None
                    }
                }
            }
            NodeDesc::Graph(name, args) => self.call(at, name, args, env),
        }
    }

    /// Expands a phenomenon call inline.
    fn call(
        &mut self,
        at: At<'_>,
        name: &str,
        args: &std::collections::BTreeMap<String, InputDesc>,
        env: &Env,
    ) -> Option<(Reg, Ty)> {
        let Some(&i) = self.ph.by_name.get(name) else {
            let names: Vec<&str> = self.ph.items.iter().map(|p| p.desc.name.as_str()).collect();
            let p = format!("{}.Graph[0]", at.path);
            self.error(
                At {
                    file: at.file,
                    path: &p,
                },
                format!("unknown phenomenon \"{name}\""),
                suggestion(name, &names, "phenomena"),
            );
            return None;
        };
        if self.ph.too_deep[i] {
            // Reported where the chain starts (`nodes_depth`).
            return None;
        }
        if !self.stack.contains(&i) {
            ensure_checked(self.src, self.ph, i);
        }
        let checked = self.ph.checked[i].clone()?;
        // Arguments, in the caller's context.
        let mut ok = true;
        let mut given = Vec::new();
        for (k, v) in args {
            let p = format!("{}.Graph[1].{k}", at.path);
            let here = At {
                file: at.file,
                path: &p,
            };
            let Some(&(_, want)) = checked.params.iter().find(|(n, _)| n == k) else {
                let names: Vec<&str> = checked.params.iter().map(|(n, _)| n.as_str()).collect();
                self.error(
                    here,
                    format!("phenomenon \"{name}\" has no parameter \"{k}\""),
                    suggestion(k, &names, "parameters"),
                );
                ok = false;
                continue;
            };
            match self.input(here, v, env) {
                Some((reg, ty)) => {
                    if want == Ty::Scalar && ty == Ty::Colour {
                        self.error(
                            here,
                            format!("parameter \"{k}\" of \"{name}\" is a number, but this gives a colour"),
                            Some("take one channel with Channel(…, 0) or use Luminance(…)".into()),
                        );
                        ok = false;
                    }
                    given.push((k.clone(), want, reg));
                }
                None => ok = false,
            }
        }
        let output = checked.output?;
        if !ok || self.ph.cyclic[i] || self.stack.contains(&i) {
            return None;
        }
        if self.past_size_limit() {
            self.refuse_oversized_call(at, name);
            return None;
        }
        // Defaults for the rest and the body, in the phenomenon's context (checked already).
        let item = &self.ph.items[i];
        let (file, desc, base) = (item.file, item.desc, item.path.clone());
        let report = std::mem::replace(&mut self.report, false);
        self.stack.push(i);
        let mut inner: Vec<(String, Ty, Reg)> = Vec::new();
        let mut defaults_ok = true;
        for (k, ty) in &checked.params {
            if let Some(g) = given.iter().find(|(n, ..)| n == k) {
                inner.push(g.clone());
            } else if let Some(d) = desc.params.get(k) {
                let p = format!("{base}.params.{k}");
                match self.input(At { file, path: &p }, d, &[]) {
                    Some((reg, _)) => inner.push((k.clone(), *ty, reg)),
                    None => defaults_ok = false,
                }
            }
        }
        let p = format!("{base}.output");
        // A default that failed (only past the size limit: the body was checked) leaves the
        // body unexpanded; `stack` and `report` are restored either way.
        let out = defaults_ok
            .then(|| self.input(At { file, path: &p }, &desc.output, &inner))
            .flatten();
        self.stack.pop();
        self.report = report;
        if self.past_size_limit() {
            self.refuse_oversized_call(at, name);
            return None;
        }
        out.map(|(r, _)| (r, output))
    }

    fn texture(
        &mut self,
        at: At<'_>,
        name: &str,
        wrap: WrapDesc,
        enc: Option<EncodingDesc>,
    ) -> Option<Arc<Texture>> {
        let path = self.src.files[at.file].dir().join(name);
        let axis = |a| match a {
            AxisWrapDesc::Repeat => Wrap::Repeat,
            AxisWrapDesc::Clamp => Wrap::Clamp,
            AxisWrapDesc::Mirror => Wrap::Mirror,
        };
        let (u, v) = wrap.axes();
        let wrap = UvWrap {
            u: axis(u),
            v: axis(v),
        };
        let key = (path.clone(), wrap, enc.map(|e| e == EncodingDesc::Srgb));
        if let Some(t) = self.ph.textures.get(&key) {
            return t.clone();
        }
        let enc = enc.map(|e| match e {
            EncodingDesc::Srgb => Encoding::Srgb,
            EncodingDesc::Linear => Encoding::Linear,
        });
        let embedded = crate::scene::mesh_files::gltf_file::image_reference(name);
        let exr = embedded.is_none() && image::is_exr(&path);
        let bytes = match embedded {
            Some((file, index)) => {
                let gltf = self.src.files[at.file].dir().join(file);
                crate::scene::mesh_files::gltf_file::image_bytes(&gltf, index)
            }
            None => std::fs::read(&path).map_err(|e| crate::scene::message::io_reason(&e)),
        };
        // Counted against the budget from the header, before anything is decoded.
        let size = bytes
            .as_deref()
            .map_err(Clone::clone)
            .and_then(|b| image::footprint(b, exr));
        if let Ok(size) = &size {
            if let Err((message, help)) = self.ph.textures.admit(name, size) {
                self.src.error(at.file, at.path, message, Some(help));
                self.ph.textures.insert(key, None);
                return None;
            }
        }
        let loaded = size.and_then(|_| {
            let bytes = bytes.unwrap_or_default();
            image::decode_file(&bytes, exr, enc, wrap)
        });
        let t = match loaded {
            Ok(t) => {
                let at = self.src.pos(at.file, at.path);
                self.ph.textures.list(name, at, &t);
                Some(Arc::new(t))
            }
            Err(e) => {
                // Reported whatever `report` says: the same file may be read first from a
                // body that was checked with other arguments.
                let (message, help) = match embedded {
                    Some((file, index)) => {
                        let gltf = self.src.files[at.file].dir().join(file);
                        let image = crate::scene::mesh_files::gltf_file::image_label(&gltf, index);
                        (
                            format!(
                                "cannot read {image} of glTF file \"{}\": {e}",
                                gltf.display()
                            ),
                            "glTF images are read as PNG: export the image as PNG",
                        )
                    }
                    None => (
                        format!("cannot read image file \"{}\": {e}", path.display()),
                        "image textures are PNG files, or EXR files with R, G and B, Y or a single channel, relative to the scene file",
                    ),
                };
                self.src.error(at.file, at.path, message, Some(help.into()));
                None
            }
        };
        self.ph.textures.insert(key, t.clone());
        t
    }
}

/// How a number input is named in a message: its field or `bind` key (`scale`, `albedo`),
/// else "a number" (an input given in order, `Add(1, NaN)`).
fn number_name(path: &str) -> String {
    let last = path.rsplit('.').next().unwrap_or_default();
    if !last.is_empty() && last.chars().all(|c| c.is_alphanumeric() || c == '_') {
        last.to_string()
    } else {
        "a number".into()
    }
}

fn space(s: ColourSpaceDesc) -> ColourSpace {
    match s {
        ColourSpaceDesc::Rgb => ColourSpace::Rgb,
        ColourSpaceDesc::Hsv => ColourSpace::Hsv,
        ColourSpaceDesc::Hsl => ColourSpace::Hsl,
    }
}

/// Compiles the `bind` and `bump` entries of every material into its [`MaterialGraph`].
/// `materials[i]` is `None` where the material itself failed validation (its graphs are
/// still checked, parameter names only against nothing).
pub fn attach(
    src: &mut Sources,
    m: &Merged<'_>,
    ph: &mut Phenomena<'_>,
    materials: &mut [Option<Material>],
) {
    for (item, mat) in m.materials.iter().zip(materials.iter_mut()) {
        let graph = compile_material(src, ph, item, mat.as_ref());
        if let (Some(mat), Some(g)) = (mat.as_mut(), graph) {
            mat.graph = g.map(Arc::new);
        }
    }
}

/// `Some(None)`: nothing to compile; `None`: errors.
fn compile_material(
    src: &mut Sources,
    ph: &mut Phenomena<'_>,
    item: &Item<'_, MaterialDesc>,
    mat: Option<&Material>,
) -> Option<Option<MaterialGraph>> {
    let d = item.desc;
    if d.bind.is_empty() && d.bump.is_none() {
        return Some(None);
    }
    let file = item.file;
    let mut c = Compiler {
        src,
        ph,
        prog: Program::default(),
        stack: Vec::new(),
        report: true,
        size: Size::Within,
    };
    let params = mat.map(|m| bind::names(&m.shader)).unwrap_or_default();
    let shader_name = mat
        .map(|m| {
            let s = format!("{:?}", m.shader);
            s.split([' ', '{', '('])
                .next()
                .unwrap_or_default()
                .to_string()
        })
        .unwrap_or_default();
    let mut ok = true;
    // The bump height first: its registers come first, so the finite differences run only
    // the start of the program.
    let mut bump = None;
    let mut normal_map = None;
    let mut object_normal = None;
    if let Some(b) = &d.bump {
        let sp = item.at(".bump.scale");
        let s = c.finite(At { file, path: &sp }, "bump scale", b.scale);
        ok &= s.is_some();
        match (&b.height, &b.normal_map, &b.object_normal) {
            (Some(height), None, None) => {
                let hp = item.at(".bump.height");
                let h = c.scalar(At { file, path: &hp }, height, &[], "bump height");
                match (h, s) {
                    (Some(height), Some(scale)) => bump = Some(BumpMap { height, scale }),
                    _ => ok = false,
                }
            }
            (None, Some(map), None) => {
                let np = item.at(".bump.normal_map");
                match (c.input(At { file, path: &np }, map, &[]), s) {
                    (Some((texel, _)), Some(scale)) => {
                        normal_map = Some(NormalMap { texel, scale });
                    }
                    _ => ok = false,
                }
            }
            (None, None, Some(normal)) => {
                let op = item.at(".bump.object_normal");
                match c.input(At { file, path: &op }, normal, &[]) {
                    Some((reg, _)) => object_normal = Some(reg),
                    None => ok = false,
                }
                if s.is_some_and(|s| s != 1.0) {
                    c.error(
                        At { file, path: &sp },
                        format!(
                            "a bump's `scale` does not apply to an `object_normal`, found {}",
                            b.scale
                        ),
                        Some("leave `scale` out: the object-space normal is used as given".into()),
                    );
                    ok = false;
                }
            }
            (height, map, normal) => {
                let bp = item.at(".bump");
                let given: Vec<&str> = [
                    (height.is_some(), "a `height`"),
                    (map.is_some(), "a `normal_map`"),
                    (normal.is_some(), "an `object_normal`"),
                ]
                .into_iter()
                .filter_map(|(g, name)| g.then_some(name))
                .collect();
                let what = match given.as_slice() {
                    [] => {
                        "a bump needs a `height`, a `normal_map` or an `object_normal`".to_string()
                    }
                    [a, b] => format!("a bump has both {a} and {b}"),
                    _ => "a bump has a `height`, a `normal_map` and an `object_normal`".to_string(),
                };
                c.error(
                    At { file, path: &bp },
                    what,
                    Some("give one: `height: <scalar node>` for a height map, `normal_map: <colour node>` for a tangent-space normal map, or `object_normal: <colour node>` for an object-space normal".into()),
                );
                ok = false;
            }
        }
    }
    // `emission` is the material's own field, not the shader's: its node multiplies it.
    let mut emission = None;
    if let Some(input) = d.bind.get(EMISSION) {
        let path = item.at(&format!(".bind.{EMISSION}"));
        match c.input(At { file, path: &path }, input, &[]) {
            Some((reg, _)) => emission = Some(reg),
            None => ok = false,
        }
    }
    let mut bindings = Vec::new();
    for (param, input) in d.bind.iter().filter(|(p, _)| *p != EMISSION) {
        let path = item.at(&format!(".bind.{param}"));
        let at = At { file, path: &path };
        let want = params.iter().find(|(n, _)| n == param).map(|(_, t)| *t);
        if mat.is_some() && want.is_none() {
            let names: Vec<&str> = params.iter().map(|(n, _)| n.as_str()).collect();
            c.error(
                at,
                format!("shader {shader_name} has no parameter \"{param}\""),
                suggestion(param, &names, "parameters"),
            );
            ok = false;
        }
        match c.input(at, input, &[]) {
            Some((reg, ty)) => {
                if want == Some(ParamType::Scalar) && ty == Ty::Colour {
                    c.error(
                        at,
                        format!("parameter \"{param}\" is a number, but this gives a colour"),
                        Some("take one channel with Channel(…, 0) or use Luminance(…)".into()),
                    );
                    ok = false;
                }
                bindings.push(Binding {
                    param: param.clone(),
                    reg,
                });
            }
            None => ok = false,
        }
    }
    c.count_expanded();
    ok.then_some(Some(MaterialGraph {
        program: c.prog,
        bindings,
        bump,
        normal_map,
        object_normal,
        emission,
    }))
}
