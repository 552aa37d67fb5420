//! Reading a request's arguments: positional values ([`Args`]) and the parameter list with
//! its types — inline declarations (`"color lightcolor"`, `"uniform float Kd"`,
//! `"float[2] st"`) or names made known by `Declare` and the RenderMan Interface's
//! predeclared table ([`Declarations`]).

use std::collections::HashMap;

use super::super::located::{Pos, Problem};
use super::parse::{Arg, Request, Value};
use crate::scene::suggest::suggestion;

/// The shader a parameter list belongs to, when it is one of ours: an undeclared name is then
/// reported as a parameter the shader does not take (declaring it would not help), with the
/// shader's own parameter it is closest to.
pub struct ParamOwner<'a> {
    /// How messages name the shader: `surface "plastic"`.
    pub what: String,
    /// The parameters the shader takes.
    pub names: &'a [&'a str],
}

/// Storage class of a primitive variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// One value for the whole primitive.
    Constant,
    /// One value per face or patch.
    Uniform,
    /// One value per corner of the parametric grid.
    Varying,
    /// One value per control vertex.
    Vertex,
    /// One value per face corner.
    FaceVarying,
}

/// Value type of a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ty {
    /// `float` (also `integer`).
    Float,
    /// A 3-component `point`, `vector`, `normal` or `color`.
    Triple,
    /// `hpoint` (4 components).
    HPoint,
    /// `matrix` (16 components).
    Matrix,
    /// `string`.
    Str,
}

impl Ty {
    fn size(self) -> usize {
        match self {
            Ty::Float | Ty::Str => 1,
            Ty::Triple => 3,
            Ty::HPoint => 4,
            Ty::Matrix => 16,
        }
    }
}

/// A parameter's declaration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Decl {
    /// Storage class.
    pub class: Class,
    /// Value type.
    pub ty: Ty,
    /// Array length (`float[2]`), 1 when not an array.
    pub count: usize,
    /// Whether the type names a point-like value that transforms with the current
    /// transformation (`point`, `vector`, `normal`).
    pub spatial: bool,
}

impl Decl {
    /// Numbers (or strings) per value.
    pub fn components(&self) -> usize {
        self.ty.size() * self.count
    }
}

/// Parses a declaration such as `"varying color"` or `"uniform float[2]"` (without the
/// name). `Err` says what is wrong.
pub fn parse_type(text: &str) -> Result<Decl, String> {
    let mut words: Vec<&str> = text.split_whitespace().collect();
    let mut class = Class::Uniform;
    let mut explicit_class = false;
    if let Some(&w) = words.first() {
        let c = match w {
            "constant" => Some(Class::Constant),
            "uniform" => Some(Class::Uniform),
            "varying" => Some(Class::Varying),
            "vertex" => Some(Class::Vertex),
            "facevarying" | "facevertex" => Some(Class::FaceVarying),
            _ => None,
        };
        if let Some(c) = c {
            class = c;
            explicit_class = true;
            words.remove(0);
        }
    }
    let [ty] = words.as_slice() else {
        return Err(format!("cannot read the type \"{text}\""));
    };
    let (base, count) = match ty.split_once('[') {
        Some((base, rest)) => {
            let n = rest
                .strip_suffix(']')
                .and_then(|n| n.trim().parse::<usize>().ok())
                .filter(|&n| (1..=1 << 16).contains(&n))
                .ok_or_else(|| format!("cannot read the array length in \"{text}\""))?;
            (base, n)
        }
        None => (*ty, 1),
    };
    let (ty, spatial) = match base {
        "float" | "integer" | "int" => (Ty::Float, false),
        "point" | "vector" | "normal" => (Ty::Triple, true),
        "color" => (Ty::Triple, false),
        "hpoint" => (Ty::HPoint, true),
        "matrix" => (Ty::Matrix, false),
        "string" => (Ty::Str, false),
        other => {
            return Err(format!(
                "unknown type \"{other}\": expected float, integer, point, vector, normal, \
                 color, hpoint, matrix or string"
            ))
        }
    };
    if !explicit_class && ty == Ty::Str {
        class = Class::Constant;
    }
    Ok(Decl {
        class,
        ty,
        count,
        spatial,
    })
}

/// The declared parameter names: the RI predeclared ones plus every `Declare`.
#[derive(Debug, Clone)]
pub struct Declarations(HashMap<String, Decl>);

/// The RenderMan Interface 3.2 predeclared parameters (and those of the standard shaders).
const PREDECLARED: &[(&str, &str)] = &[
    ("P", "vertex point"),
    ("Pz", "vertex float"),
    ("Pw", "vertex hpoint"),
    ("N", "varying normal"),
    ("Np", "uniform normal"),
    ("Cs", "varying color"),
    ("Os", "varying color"),
    ("s", "varying float"),
    ("t", "varying float"),
    ("st", "varying float[2]"),
    ("Ka", "uniform float"),
    ("Kd", "uniform float"),
    ("Ks", "uniform float"),
    ("Kr", "uniform float"),
    ("Km", "uniform float"),
    ("roughness", "uniform float"),
    ("specularcolor", "uniform color"),
    ("texturename", "uniform string"),
    ("intensity", "uniform float"),
    ("lightcolor", "uniform color"),
    ("from", "uniform point"),
    ("to", "uniform point"),
    ("coneangle", "uniform float"),
    ("conedeltaangle", "uniform float"),
    ("beamdistribution", "uniform float"),
    ("background", "uniform color"),
    ("distance", "uniform float"),
    ("fov", "uniform float"),
    ("amplitude", "uniform float"),
    ("factor", "uniform float"),
    ("axis", "uniform string"),
    ("sphere", "uniform float"),
    ("coordinatesystem", "uniform string"),
    ("name", "uniform string"),
    ("truedisplacement", "uniform integer"),
    ("shadows", "uniform string"),
    ("nphotons", "uniform integer"),
    ("ngather", "uniform integer"),
    ("maxpixeldist", "uniform float"),
    ("refractioncolor", "uniform color"),
    ("refractionindex", "uniform float"),
];

impl Default for Declarations {
    fn default() -> Self {
        let mut map = HashMap::new();
        for (name, ty) in PREDECLARED {
            if let Ok(d) = parse_type(ty) {
                map.insert((*name).to_string(), d);
            }
        }
        Self(map)
    }
}

impl Declarations {
    /// `Declare name type`.
    pub fn declare(&mut self, name: &str, decl: Decl) {
        self.0.insert(name.to_string(), decl);
    }

    /// The declaration of a parameter token: inline (`"color lightcolor"`) or by name.
    pub fn resolve(&self, token: &str) -> Result<(String, Decl), String> {
        let words: Vec<&str> = token.split_whitespace().collect();
        match words.as_slice() {
            [] => Err("empty parameter name".into()),
            [name] => match self.0.get(*name) {
                Some(d) => Ok(((*name).to_string(), *d)),
                None => Err(format!("undeclared parameter \"{name}\"")),
            },
            [ty @ .., name] => parse_type(&ty.join(" ")).map(|d| ((*name).to_string(), d)),
        }
    }
}

/// One entry of a parameter list.
#[derive(Debug, Clone)]
pub struct Param {
    /// The parameter name (without an inline type).
    pub name: String,
    /// Its declaration.
    pub decl: Decl,
    /// Where the name token is.
    pub name_pos: Pos,
    /// Its value.
    pub value: Arg,
}

impl Param {
    /// The numbers of the value.
    pub fn nums(&self) -> &[f64] {
        self.value.value.nums().unwrap_or(&[])
    }

    /// The first number (checked to exist by [`Args::params`]).
    pub fn num(&self) -> f64 {
        self.nums().first().copied().unwrap_or(0.0)
    }

    /// The first three numbers as a triple (checked by [`Args::params`] for triples).
    pub fn triple(&self) -> (f64, f64, f64) {
        let v = self.nums();
        match v {
            [a, b, c, ..] => (*a, *b, *c),
            [a] => (*a, *a, *a),
            _ => (0.0, 0.0, 0.0),
        }
    }

    /// The first string.
    pub fn str(&self) -> &str {
        self.value
            .value
            .strs()
            .and_then(|s| s.first())
            .map_or("", String::as_str)
    }

    /// Where the value is.
    pub fn pos(&self) -> Pos {
        self.value.pos
    }
}

/// A cursor over a request's arguments.
pub struct Args<'a> {
    req: &'a Request,
    /// Next argument.
    at: usize,
    /// Next element inside `args[at]` when it is a number array read number by number.
    inner: usize,
}

impl<'a> Args<'a> {
    /// A cursor at the first argument of `req`.
    pub fn new(req: &'a Request) -> Self {
        Self {
            req,
            at: 0,
            inner: 0,
        }
    }

    fn missing(&self, what: &str, kind: &str) -> Problem {
        Problem::error(
            self.req.pos,
            format!("{} needs {what} ({kind})", self.req.name),
        )
    }

    fn wrong(&self, arg: &Arg, what: &str, kind: &str) -> Problem {
        Problem::error(
            arg.pos,
            format!(
                "expected {kind} for {what} of {}, found {}",
                self.req.name,
                arg.value.kind()
            ),
        )
    }

    /// The next number (bare, or the next element of a number array).
    pub fn num(&mut self, what: &str) -> Result<(f64, Pos), Problem> {
        let Some(arg) = self.req.args.get(self.at) else {
            return Err(self.missing(what, "a number"));
        };
        match &arg.value {
            Value::Num(v) => {
                self.at += 1;
                Ok((*v, arg.pos))
            }
            Value::Nums(v) if self.inner < v.len() => {
                let out = (v[self.inner], arg.item(self.inner));
                self.inner += 1;
                if self.inner == v.len() {
                    self.at += 1;
                    self.inner = 0;
                }
                Ok(out)
            }
            _ => Err(self.wrong(arg, what, "a number")),
        }
    }

    /// The next number, rounded to an integer ≥ `min`.
    pub fn count(&mut self, what: &str, min: i64) -> Result<(usize, Pos), Problem> {
        let (v, pos) = self.num(what)?;
        if v.fract() != 0.0 || v < min as f64 || v > 1e9 {
            return Err(Problem::error(
                pos,
                format!(
                    "{what} of {} must be an integer ≥ {min}, found {v}",
                    self.req.name
                ),
            ));
        }
        Ok((v as usize, pos))
    }

    /// The next string.
    pub fn string(&mut self, what: &str) -> Result<(String, Pos), Problem> {
        self.align();
        let Some(arg) = self.req.args.get(self.at) else {
            return Err(self.missing(what, "a string"));
        };
        match &arg.value {
            Value::Str(s) => {
                self.at += 1;
                Ok((s.clone(), arg.pos))
            }
            Value::Strs(s) if s.len() == 1 => {
                self.at += 1;
                Ok((s[0].clone(), arg.item(0)))
            }
            _ => Err(self.wrong(arg, what, "a string")),
        }
    }

    /// The next whole number array (a bare number counts as a one-element array).
    pub fn array(&mut self, what: &str) -> Result<Arg, Problem> {
        self.align();
        let Some(arg) = self.req.args.get(self.at) else {
            return Err(self.missing(what, "an array of numbers"));
        };
        match &arg.value {
            Value::Nums(_) => {
                self.at += 1;
                Ok(arg.clone())
            }
            Value::Num(v) => {
                self.at += 1;
                Ok(Arg {
                    value: Value::Nums(vec![*v]),
                    pos: arg.pos,
                    items: vec![arg.pos],
                })
            }
            _ => Err(self.wrong(arg, what, "an array of numbers")),
        }
    }

    /// The next argument, whatever it is.
    pub fn any(&mut self, what: &str) -> Result<Arg, Problem> {
        self.align();
        let arg = self
            .req
            .args
            .get(self.at)
            .ok_or_else(|| self.missing(what, "a value"))?;
        self.at += 1;
        Ok(arg.clone())
    }

    /// The next argument if it is a string (a light handle may be a number or a string).
    pub fn peek_is_string(&self) -> bool {
        self.inner == 0
            && self
                .req
                .args
                .get(self.at)
                .is_some_and(|a| matches!(a.value, Value::Str(_)))
    }

    /// Whether every argument has been read.
    pub fn done(&self) -> bool {
        self.at >= self.req.args.len()
    }

    /// A number array read only in part cannot be followed by anything else.
    fn align(&mut self) {
        if self.inner > 0 {
            self.at += 1;
            self.inner = 0;
        }
    }

    /// The remaining arguments as a parameter list, each checked against its declaration.
    /// Errors are collected in `problems`; bad entries are left out.
    pub fn params(self, decls: &Declarations, problems: &mut Vec<Problem>) -> Vec<Param> {
        self.read_params(decls, problems, false, None)
    }

    /// [`Args::params`] for a call of a shader we have (`owner`): an undeclared name is
    /// `unknown parameter "roughnes" of surface "plastic"` with "did you mean" among the
    /// shader's parameters, the message the name gets once declared.
    pub fn params_of(
        self,
        decls: &Declarations,
        owner: Option<&ParamOwner<'_>>,
        problems: &mut Vec<Problem>,
    ) -> Vec<Param> {
        self.read_params(decls, problems, false, owner)
    }

    /// [`Args::params`] for requests whose parameters are renderer-specific (`Attribute`,
    /// `Option`): an undeclared name is not an error; its type is taken from its value (a
    /// string or a float per number), and the caller warns that it is ignored.
    pub fn params_lenient(self, decls: &Declarations, problems: &mut Vec<Problem>) -> Vec<Param> {
        self.read_params(decls, problems, true, None)
    }

    fn read_params(
        mut self,
        decls: &Declarations,
        problems: &mut Vec<Problem>,
        lenient: bool,
        owner: Option<&ParamOwner<'_>>,
    ) -> Vec<Param> {
        if self.inner > 0 {
            let arg = &self.req.args[self.at];
            problems.push(Problem::error(
                arg.item(self.inner),
                format!("too many values for {}", self.req.name),
            ));
            self.align();
        }
        let mut out = Vec::new();
        let args = &self.req.args[self.at.min(self.req.args.len())..];
        let mut i = 0;
        while i < args.len() {
            let name_arg = &args[i];
            let token = match &name_arg.value {
                Value::Str(s) => s.clone(),
                Value::Strs(s) if s.len() == 1 => s[0].clone(),
                other => {
                    problems.push(Problem::error(
                        name_arg.pos,
                        format!(
                            "expected a parameter name (a string) in the parameter list of {}, \
                             found {}",
                            self.req.name,
                            other.kind()
                        ),
                    ));
                    i += 1;
                    continue;
                }
            };
            let Some(value) = args.get(i + 1) else {
                problems.push(Problem::error(
                    name_arg.pos,
                    format!("parameter \"{token}\" of {} has no value", self.req.name),
                ));
                break;
            };
            i += 2;
            let (name, decl) = match decls.resolve(&token) {
                Ok(d) => d,
                Err(message) if lenient && message.starts_with("undeclared") => {
                    let ty = if value.value.strs().is_some() {
                        "string"
                    } else {
                        "float"
                    };
                    let decl = parse_type(ty).expect("a known type");
                    let decl = Decl {
                        count: value.value.nums().map_or(1, |v| v.len().max(1)),
                        ..decl
                    };
                    (token.clone(), decl)
                }
                Err(message)
                    if message.starts_with("undeclared")
                        && owner.is_some_and(|o| !o.names.contains(&token.as_str())) =>
                {
                    let Some(owner) = owner else { continue };
                    let mut e = Problem::error(
                        name_arg.pos,
                        format!("unknown parameter \"{token}\" of {}", owner.what),
                    );
                    e.help = suggestion(&token, owner.names, "parameters");
                    problems.push(e);
                    continue;
                }
                Err(message) => {
                    let help = message.starts_with("undeclared").then(|| {
                        format!(
                            "declare it first (Declare \"{token}\" \"float\") or write its type \
                             inline (\"float {token}\")"
                        )
                    });
                    problems.push(Problem {
                        help,
                        ..Problem::error(name_arg.pos, message)
                    });
                    continue;
                }
            };
            let ok = match (&value.value, decl.ty) {
                (Value::Str(_) | Value::Strs(_), Ty::Str) => true,
                (Value::Num(_) | Value::Nums(_), Ty::Str) => value.value.strs().is_some(),
                (Value::Num(_) | Value::Nums(_), _) => {
                    let n = value.value.nums().map_or(0, <[f64]>::len);
                    let per = decl.components();
                    // Per-vertex values may be none: the primitive says how many it needs.
                    let per_vertex = matches!(
                        decl.class,
                        Class::Vertex | Class::Varying | Class::FaceVarying
                    );
                    if n == 0 && !per_vertex || n % per != 0 {
                        problems.push(Problem::error(
                            value.pos,
                            format!(
                                "parameter \"{name}\" of {} takes a multiple of {per} number{}, \
                                 found {n}",
                                self.req.name,
                                if per == 1 { "" } else { "s" }
                            ),
                        ));
                        continue;
                    }
                    true
                }
                _ => false,
            };
            if !ok {
                problems.push(Problem::error(
                    value.pos,
                    format!(
                        "parameter \"{name}\" of {} takes {}, found {}",
                        self.req.name,
                        if decl.ty == Ty::Str {
                            "strings"
                        } else {
                            "numbers"
                        },
                        value.value.kind()
                    ),
                ));
                continue;
            }
            out.push(Param {
                name,
                decl,
                name_pos: name_arg.pos,
                value: value.clone(),
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::super::lexer::tokens;
    use super::super::parse::requests;
    use super::*;

    fn req(text: &str) -> Request {
        let (t, _) = tokens(text);
        requests(&t).0.remove(0)
    }

    #[test]
    fn declarations_inline_and_declared() {
        let mut d = Declarations::default();
        let (name, decl) = d.resolve("color lightcolor").unwrap();
        assert_eq!(name, "lightcolor");
        assert_eq!(
            (decl.ty, decl.class, decl.spatial),
            (Ty::Triple, Class::Uniform, false)
        );
        assert_eq!(d.resolve("varying float[2] st").unwrap().1.components(), 2);
        assert_eq!(
            d.resolve("near").unwrap_err(),
            "undeclared parameter \"near\""
        );
        d.declare("near", parse_type("float").unwrap());
        assert_eq!(d.resolve("near").unwrap().1.ty, Ty::Float);
        assert!(d.resolve("point from").unwrap().1.spatial);
        assert_eq!(
            parse_type("colour").unwrap_err(),
            "unknown type \"colour\": expected float, integer, point, vector, normal, color, \
             hpoint, matrix or string"
        );
    }

    #[test]
    fn positional_numbers_then_parameters() {
        let r = req("Sphere [1 -1] 1 360 \"Cs\" [1 0 0] \"float foo\" 2");
        let mut a = Args::new(&r);
        let v: Vec<f64> = (0..4).map(|_| a.num("x").unwrap().0).collect();
        assert_eq!(v, vec![1.0, -1.0, 1.0, 360.0]);
        let mut problems = Vec::new();
        let p = a.params(&Declarations::default(), &mut problems);
        assert!(problems.is_empty());
        assert_eq!(p.len(), 2);
        assert_eq!(p[0].triple(), (1.0, 0.0, 0.0));
        assert_eq!((p[1].name.as_str(), p[1].num()), ("foo", 2.0));
    }

    #[test]
    fn parameter_errors() {
        let r = req("Surface \"plastic\" \"Kd\" \"x\" \"color c\" [1 2] 3 \"Ks\"");
        let mut a = Args::new(&r);
        a.string("name").unwrap();
        let mut problems = Vec::new();
        let p = a.params(&Declarations::default(), &mut problems);
        assert!(p.is_empty());
        let got: Vec<_> = problems.iter().map(|p| p.message.as_str()).collect();
        assert_eq!(
            got,
            vec![
                "parameter \"Kd\" of Surface takes numbers, found a string",
                "parameter \"c\" of Surface takes a multiple of 3 numbers, found 2",
                "expected a parameter name (a string) in the parameter list of Surface, found a \
                 number",
                "parameter \"Ks\" of Surface has no value",
            ]
        );
    }
}
