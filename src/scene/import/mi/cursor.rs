//! A cursor over one file's tokens: typed reads with located errors, and the shader call
//! syntax every block shares: `"shader" ("param" value, …)`.
//!
//! A value is numbers (`1 0.5 0.5`: a scalar, colour or vector), a string, a boolean
//! (`on`/`off`/`true`/`false`), an array `[v, …]`, a shader reference `= "name"` or an
//! interface reference `= interface "name"`. Struct values `{…}` are skipped with a warning.

use std::path::PathBuf;

/// The types of a `color|scalar|vector texture "name" "file"` statement.
pub const TEXTURE_TYPES: &[&str] = &["color", "scalar", "vector"];

use super::super::located::{Located, LocatedProblem, Pos, Problem};
use super::lexer::{Tok, Token};

/// Deepest nesting of array values.
const MAX_ARRAY_DEPTH: usize = 32;

/// A parameter value as written.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// One or more numbers.
    Nums(Vec<f64>),
    /// A string.
    Str(String),
    /// `on`/`true` or `off`/`false`.
    Bool(bool),
    /// `[v, …]`.
    Array(Vec<Value>),
    /// `= "shader"`: the result of a named shader.
    Ref(String),
    /// `= interface "param"`: a phenomenon's interface parameter.
    Interface(String),
    /// `{…}`, not read.
    Struct,
}

impl Value {
    /// How a message names the kind of value.
    pub fn kind(&self) -> &'static str {
        match self {
            Value::Nums(n) if n.len() == 1 => "a number",
            Value::Nums(_) => "numbers",
            Value::Str(_) => "a string",
            Value::Bool(_) => "a boolean",
            Value::Array(_) => "an array",
            Value::Ref(_) => "a shader reference",
            Value::Interface(_) => "an interface reference",
            Value::Struct => "a struct",
        }
    }
}

/// One `"name" value` of a shader call.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    /// Parameter name.
    pub name: String,
    /// Where the name is.
    pub pos: Pos,
    /// The value.
    pub value: Value,
    /// Where the value starts.
    pub value_pos: Pos,
}

/// `"shader" (params)`: a shader and its parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ShaderCall {
    /// Shader name (`mib_illum_lambert`).
    pub name: String,
    /// Where the name is.
    pub pos: Pos,
    /// The parameters in written order.
    pub params: Vec<Param>,
}

/// One file's tokens being read.
pub struct Cursor {
    /// The file, as the user named it (includes joined to the including file's folder).
    pub file: PathBuf,
    tokens: Vec<Token>,
    at: usize,
    /// Problems found in this file.
    pub problems: Vec<LocatedProblem>,
}

impl Cursor {
    /// A cursor at the first of `tokens` of `file`.
    pub fn new(file: PathBuf, tokens: Vec<Token>) -> Self {
        Self {
            file,
            tokens,
            at: 0,
            problems: Vec::new(),
        }
    }

    /// The next token, not consumed.
    pub fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.at)
    }

    /// The token after the next one, not consumed.
    pub fn peek2(&self) -> Option<&Token> {
        self.tokens.get(self.at + 1)
    }

    /// Consumes the next token.
    pub fn advance(&mut self) -> Option<Token> {
        let t = self.tokens.get(self.at).cloned();
        if t.is_some() {
            self.at += 1;
        }
        t
    }

    /// Where the next token is (the last token's position at the end of the file).
    pub fn pos(&self) -> Pos {
        self.peek()
            .or(self.tokens.last())
            .map(|t| t.pos)
            .unwrap_or_default()
    }

    /// The position `pos` in this file.
    pub fn located(&self, pos: Pos) -> Located {
        Located {
            file: self.file.clone(),
            pos,
        }
    }

    /// Records a problem.
    pub fn report(&mut self, problem: Problem) {
        self.problems.push(LocatedProblem {
            file: self.file.clone(),
            problem,
        });
    }

    /// Records an error at `pos`.
    pub fn error(&mut self, pos: Pos, message: impl Into<String>) {
        self.report(Problem::error(pos, message));
    }

    /// Records a warning at `pos`.
    pub fn warn(&mut self, pos: Pos, message: impl Into<String>) {
        self.report(Problem::warning(pos, message));
    }

    /// Whether the next token is the word `w`.
    pub fn at_word(&self, w: &str) -> bool {
        matches!(self.peek(), Some(Token { tok: Tok::Word(x), .. }) if x == w)
    }

    /// Whether the next token starts a top-level statement (`camera space` and `object space` in options
    /// does not): the block before it was not closed.
    pub fn at_statement(&self) -> bool {
        let Some(Token {
            tok: Tok::Word(w), ..
        }) = self.peek()
        else {
            return false;
        };
        let space = matches!(self.peek2(), Some(Token { tok: Tok::Word(s), .. }) if s == "space");
        let texture =
            matches!(self.peek2(), Some(Token { tok: Tok::Word(s), .. }) if s == "texture");
        if texture && TEXTURE_TYPES.contains(&w.as_str()) {
            return true;
        }
        super::statements::STATEMENTS.contains(&w.as_str())
            && !((w == "camera" || w == "object") && space)
            && !(w == "material" && self.at_instance_material())
    }

    /// Whether the `material` at the cursor is an instance's material (`material ["a" …]`,
    /// or `material "m"` followed by an instance statement), not a `material` block (whose
    /// name is followed by `opaque`, a shader, `=`, a shader statement or `end material`).
    fn at_instance_material(&self) -> bool {
        let word = |k: usize| match self.tokens.get(self.at + k) {
            Some(Token {
                tok: Tok::Word(w), ..
            }) => Some(w.as_str()),
            _ => None,
        };
        let is_string = matches!(
            self.tokens.get(self.at + 1),
            Some(Token {
                tok: Tok::Str(_),
                ..
            })
        );
        if matches!(
            self.tokens.get(self.at + 1),
            Some(Token {
                tok: Tok::Punct('['),
                ..
            })
        ) {
            return true;
        }
        // A material's `shadow` names a shader; an instance's is a switch.
        let shader_follows = matches!(
            self.tokens.get(self.at + 3),
            Some(Token {
                tok: Tok::Str(_) | Tok::Punct('='),
                ..
            })
        );
        is_string
            && match word(2) {
                Some("end") => word(3) == Some("instance"),
                Some("shadow") => !shader_follows,
                Some(w) => [
                    "transform",
                    "visible",
                    "trace",
                    "hide",
                    "tag",
                    "motion",
                    "caustic",
                    "globillum",
                    "material",
                ]
                .contains(&w),
                None => false,
            }
    }

    /// The next token of a `kind` block opened at `open`, not consumed; `None` (reported:
    /// the block is not closed) at the end of the file or at a top-level statement.
    pub fn block_token(&mut self, kind: &str, open: Pos) -> Option<Token> {
        if self.peek().is_none() || self.at_statement() {
            self.error(
                open,
                format!("\"{kind}\" block is not closed (expected \"end {kind}\")"),
            );
            return None;
        }
        self.peek().cloned()
    }

    /// Whether the next token is the punctuation `c`.
    pub fn at_punct(&self, c: char) -> bool {
        matches!(self.peek(), Some(Token { tok: Tok::Punct(x), .. }) if *x == c)
    }

    /// Whether the next token is a number.
    pub fn at_number(&self) -> bool {
        matches!(
            self.peek(),
            Some(Token {
                tok: Tok::Num(_),
                ..
            })
        )
    }

    /// Whether the next token is a string.
    pub fn at_string(&self) -> bool {
        matches!(
            self.peek(),
            Some(Token {
                tok: Tok::Str(_),
                ..
            })
        )
    }

    /// Consumes the word `w` if it is next.
    pub fn eat_word(&mut self, w: &str) -> bool {
        let yes = self.at_word(w);
        if yes {
            self.at += 1;
        }
        yes
    }

    /// Consumes the punctuation `c` if it is next.
    pub fn eat_punct(&mut self, c: char) -> bool {
        let yes = self.at_punct(c);
        if yes {
            self.at += 1;
        }
        yes
    }

    fn found(&self) -> String {
        self.peek()
            .map_or_else(|| "the end of the file".into(), |t| t.tok.describe())
    }

    /// Reads a string for `what`, or reports `expected a string for what, found …`.
    pub fn string(&mut self, what: &str) -> Option<(String, Pos)> {
        match self.peek().cloned() {
            Some(Token {
                tok: Tok::Str(s),
                pos,
            }) => {
                self.at += 1;
                Some((s, pos))
            }
            _ => {
                let (pos, found) = (self.pos(), self.found());
                self.error(pos, format!("expected a string for {what}, found {found}"));
                None
            }
        }
    }

    /// Reads a number for `what`, or reports `expected a number for what, found …`.
    pub fn number(&mut self, what: &str) -> Option<f64> {
        match self.peek().cloned() {
            Some(Token {
                tok: Tok::Num(v), ..
            }) => {
                self.at += 1;
                Some(v)
            }
            _ => {
                let (pos, found) = (self.pos(), self.found());
                self.error(pos, format!("expected a number for {what}, found {found}"));
                None
            }
        }
    }

    /// Reads `n` numbers for `what`.
    pub fn numbers(&mut self, n: usize, what: &str) -> Option<Vec<f64>> {
        (0..n).map(|_| self.number(what)).collect()
    }

    /// Reads a whole non-negative number for `what`.
    pub fn count(&mut self, what: &str) -> Option<u32> {
        let pos = self.pos();
        let v = self.number(what)?;
        if v < 0.0 || v.fract() != 0.0 || v > f64::from(u32::MAX) {
            self.error(pos, format!("{what} must be a whole number ≥ 0, found {v}"));
            return None;
        }
        Some(v as u32)
    }

    /// Reads an optional `on`/`off`/`true`/`false` (absent: `true`).
    pub fn switch(&mut self) -> bool {
        for (w, v) in [
            ("on", true),
            ("true", true),
            ("off", false),
            ("false", false),
        ] {
            if self.eat_word(w) {
                return v;
            }
        }
        true
    }

    /// Skips numbers, strings and `on`/`off` words (the arguments of a statement that is
    /// not read).
    pub fn skip_arguments(&mut self) {
        while let Some(t) = self.peek() {
            match &t.tok {
                Tok::Num(_) | Tok::Str(_) => self.at += 1,
                Tok::Word(w) if matches!(w.as_str(), "on" | "off" | "true" | "false") => {
                    self.at += 1
                }
                _ => break,
            }
        }
    }

    /// Skips to just after `end kind` (error recovery, and statements not read). Reports an
    /// error at `open` when the file ends first.
    pub fn skip_to_end(&mut self, kind: &str, open: Pos) {
        while let Some(t) = self.advance() {
            if matches!(&t.tok, Tok::Word(w) if w == "end") && self.eat_word(kind) {
                return;
            }
        }
        self.error(
            open,
            format!("\"{kind}\" block is not closed (expected \"end {kind}\")"),
        );
    }

    /// Expects `end kind`; on anything else reports it and skips to the matching end.
    pub fn expect_end(&mut self, kind: &str, open: Pos) {
        if self.at_word("end")
            && matches!(self.peek2(), Some(Token { tok: Tok::Word(w), .. }) if w == kind)
        {
            self.at += 2;
            return;
        }
        let (pos, found) = (self.pos(), self.found());
        self.error(
            pos,
            format!("unexpected {found} in {kind} (expected \"end {kind}\")"),
        );
        self.skip_to_end(kind, open);
    }

    /// Reads `"shader" ( params )`.
    pub fn shader_call(&mut self, what: &str) -> Option<ShaderCall> {
        let (name, pos) = self.string(what)?;
        let params = self.params(&name)?;
        Some(ShaderCall { name, pos, params })
    }

    /// [`Self::shader_call`], or a named shader given by reference (`= "name"`, as Maya's
    /// exporter writes `material "m" = "sh1"`): the call that `shader "name" "type" (…)`
    /// defined in `named`, located at the reference. An unknown name is an error with a
    /// suggestion among the named shaders.
    pub fn shader_call_or_named(
        &mut self,
        what: &str,
        named: &std::collections::HashMap<String, ShaderCall>,
    ) -> Option<ShaderCall> {
        if !self.eat_punct('=') {
            return self.shader_call(what);
        }
        let (name, pos) = self.string(&format!("the shader named for {what}"))?;
        match named.get(&name) {
            Some(call) => Some(ShaderCall {
                pos,
                ..call.clone()
            }),
            None => {
                let mut p = Problem::error(
                    pos,
                    format!("no shader named \"{name}\" is defined before {what}"),
                );
                let known = named.keys().map(String::as_str);
                p = match crate::scene::suggest::closest(&name, known) {
                    Some(s) => p.with_help(format!("did you mean \"{s}\"?")),
                    None => p.with_help(format!(
                        "define it first: shader \"{name}\" \"mib_illum_lambert\" (…)"
                    )),
                };
                self.report(p);
                None
            }
        }
    }

    /// Reads `( "name" value, … )` of shader `shader`.
    pub fn params(&mut self, shader: &str) -> Option<Vec<Param>> {
        let open = self.pos();
        if !self.eat_punct('(') {
            let found = self.found();
            self.error(
                open,
                format!("expected '(' after shader \"{shader}\", found {found}"),
            );
            return None;
        }
        let mut params = Vec::new();
        loop {
            if self.eat_punct(')') {
                return Some(params);
            }
            if self.peek().is_none() {
                self.error(open, format!("unclosed '(' of shader \"{shader}\""));
                return None;
            }
            let (name, pos) = self.string(&format!("a parameter name of \"{shader}\""))?;
            let value_pos = self.pos();
            let value = self.value(&name, 0)?;
            params.push(Param {
                name,
                pos,
                value,
                value_pos,
            });
            if !self.eat_punct(',') && !self.at_punct(')') {
                let (at, found) = (self.pos(), self.found());
                self.error(
                    at,
                    format!("expected ',' or ')' after parameter, found {found}"),
                );
                return None;
            }
        }
    }

    fn value(&mut self, param: &str, depth: usize) -> Option<Value> {
        let Some(t) = self.peek().cloned() else {
            self.error(
                self.pos(),
                format!("missing value of parameter \"{param}\""),
            );
            return None;
        };
        match t.tok {
            Tok::Num(_) => {
                let mut nums = Vec::new();
                while let Some(Token {
                    tok: Tok::Num(v), ..
                }) = self.peek()
                {
                    nums.push(*v);
                    self.at += 1;
                }
                Some(Value::Nums(nums))
            }
            Tok::Str(s) => {
                self.at += 1;
                Some(Value::Str(s))
            }
            Tok::Word(w) if matches!(w.as_str(), "on" | "true") => {
                self.at += 1;
                Some(Value::Bool(true))
            }
            Tok::Word(w) if matches!(w.as_str(), "off" | "false") => {
                self.at += 1;
                Some(Value::Bool(false))
            }
            Tok::Punct('=') => {
                self.at += 1;
                if self.eat_word("interface") {
                    let (s, _) = self.string("an interface parameter")?;
                    return Some(Value::Interface(s));
                }
                let (s, _) = self.string("a shader reference")?;
                Some(Value::Ref(s))
            }
            Tok::Punct('[') if depth >= MAX_ARRAY_DEPTH => {
                self.error(
                    t.pos,
                    format!("arrays in parameter \"{param}\" nest deeper than {MAX_ARRAY_DEPTH}"),
                );
                None
            }
            Tok::Punct('[') => {
                self.at += 1;
                let mut items = Vec::new();
                loop {
                    if self.eat_punct(']') {
                        return Some(Value::Array(items));
                    }
                    items.push(self.value(param, depth + 1)?);
                    self.eat_punct(',');
                }
            }
            Tok::Punct('{') => {
                let mut depth = 0usize;
                while let Some(t) = self.advance() {
                    match t.tok {
                        Tok::Punct('{') => depth += 1,
                        Tok::Punct('}') => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                self.warn(t.pos, format!("struct value of \"{param}\" is not read"));
                Some(Value::Struct)
            }
            other => {
                self.error(
                    t.pos,
                    format!(
                        "expected a value for parameter \"{param}\", found {}",
                        other.describe()
                    ),
                );
                None
            }
        }
    }
}
