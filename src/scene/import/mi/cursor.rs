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
    /// The file the parameters were written in (a named shader's: where it was defined).
    pub file: PathBuf,
}

/// One file's tokens being read, with the tokens of the files `$include`d inside its
/// blocks spliced in where each `$include` was (mental ray's include is textual).
pub struct Cursor {
    /// The file the cursor was made for, as the user named it (includes joined to the
    /// including file's folder).
    pub file: PathBuf,
    tokens: Vec<Token>,
    /// Per token, its file (an index into `files`).
    token_files: Vec<usize>,
    /// The cursor's file first, then every file spliced in, with the file that included it.
    files: Vec<(PathBuf, Option<usize>)>,
    at: usize,
    /// The files being read around the cursor's file, outermost first (an include of one of
    /// them is a cycle).
    pub outer: Vec<PathBuf>,
    /// Problems found in this file and the files spliced into it.
    pub problems: Vec<LocatedProblem>,
    /// Per token (and one past the last), whether a lexical error lies just before it: a
    /// value missing there was reported already, as the bad token.
    lex_error_before: Vec<bool>,
    /// The entries of `files` that only replayed tokens come from (not `$include`d here).
    replayed_files: Vec<usize>,
}

/// Tokens a block read, each with the file it was written in: what an `incremental`
/// definition of the element replays before its own statements.
#[derive(Debug, Clone, Default)]
pub struct Recorded {
    /// Runs of tokens written in one file, in reading order.
    runs: Vec<(PathBuf, Vec<Token>)>,
}

impl Cursor {
    /// A cursor at the first of `tokens` of `file`.
    pub fn new(file: PathBuf, tokens: Vec<Token>) -> Self {
        let n = tokens.len();
        Self {
            file: file.clone(),
            tokens,
            token_files: vec![0; n],
            files: vec![(file, None)],
            at: 0,
            outer: Vec::new(),
            problems: Vec::new(),
            lex_error_before: vec![false; n + 1],
            replayed_files: Vec::new(),
        }
    }

    /// Where the cursor is, for [`Self::record`] (and to tell replayed tokens, which lie
    /// before the end [`Self::replay`] returns, from the block's own).
    pub fn index(&self) -> usize {
        self.at
    }

    /// The tokens from `from` (an earlier [`Self::index`]) to the cursor, each with its
    /// file; the `$include "file"` statements among them are left out (their files' tokens
    /// follow them, spliced in).
    pub fn record(&self, from: usize) -> Recorded {
        let mut runs: Vec<(PathBuf, Vec<Token>)> = Vec::new();
        let mut k = from;
        while k < self.at.min(self.tokens.len()) {
            let t = &self.tokens[k];
            if matches!(&t.tok, Tok::Word(w) if w == "$include") {
                k += 2;
                continue;
            }
            let file = &self.files[self.token_files[k]].0;
            match runs.last_mut() {
                Some((f, run)) if f == file => run.push(t.clone()),
                _ => runs.push((file.clone(), vec![t.clone()])),
            }
            k += 1;
        }
        Recorded { runs }
    }

    /// Inserts `recorded` at the cursor: its tokens are read next, located in the files
    /// they were written in (the problems they raise again are the ones reported when they
    /// were first read, which the reader drops as repeats). Returns the index just past
    /// them.
    pub fn replay(&mut self, recorded: &Recorded) -> usize {
        let at = self.at;
        let mut k = at;
        for (file, run) in &recorded.runs {
            let index = match self.files.iter().position(|(f, _)| f == file) {
                Some(i) => i,
                None => {
                    self.files.push((file.clone(), None));
                    self.replayed_files.push(self.files.len() - 1);
                    self.files.len() - 1
                }
            };
            let n = run.len();
            self.tokens.splice(k..k, run.iter().cloned());
            self.token_files.splice(k..k, std::iter::repeat_n(index, n));
            self.lex_error_before
                .splice(k..k, std::iter::repeat_n(false, n));
            k += n;
        }
        k
    }

    /// Reports the lexical errors of the cursor's file, remembering that each broke the
    /// token after it.
    pub fn lex_errors(&mut self, errors: Vec<super::super::located::LexError>) {
        let before = after_errors(&self.tokens, &errors);
        for (flag, b) in self.lex_error_before.iter_mut().zip(before) {
            *flag |= b;
        }
        for e in errors {
            self.error(e.pos, e.message);
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

    /// The file of the next token (of the last one at the end), an index into `files`.
    fn current_index(&self) -> usize {
        let k = self.at.min(self.tokens.len().saturating_sub(1));
        self.token_files.get(k).copied().unwrap_or(0)
    }

    /// The file a position of a token near the cursor is in: the nearest token at or
    /// before the cursor written at `pos` (the position of a token just read or peeked),
    /// else the next token's file.
    fn file_of(&self, pos: Pos) -> PathBuf {
        if self.files.len() == 1 {
            return self.file.clone();
        }
        let here = self.at.min(self.tokens.len().saturating_sub(1));
        let f = (0..=here)
            .rev()
            .find(|&k| self.tokens.get(k).is_some_and(|t| t.pos == pos))
            .or(Some(here))
            .and_then(|k| self.token_files.get(k).copied())
            .unwrap_or(0);
        self.files[f].0.clone()
    }

    /// The position `pos` in the file it was written in.
    pub fn located(&self, pos: Pos) -> Located {
        Located {
            file: self.file_of(pos),
            pos,
        }
    }

    /// Records a problem (in the file its position is in).
    pub fn report(&mut self, problem: Problem) {
        self.problems.push(LocatedProblem {
            file: self.file_of(problem.pos),
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

    /// Every problem, by file (the cursor's file first, then the spliced files in reading
    /// order) and position.
    pub fn take_problems(&mut self) -> Vec<LocatedProblem> {
        let rank = |p: &LocatedProblem| {
            self.files
                .iter()
                .position(|(f, _)| *f == p.file)
                .unwrap_or(0)
        };
        let mut problems = std::mem::take(&mut self.problems);
        problems.sort_by_cached_key(|p| (rank(p), p.problem.pos));
        problems
    }

    /// The files spliced into the cursor's file, in reading order.
    pub fn spliced(&self) -> impl Iterator<Item = &PathBuf> {
        self.files
            .iter()
            .enumerate()
            .skip(1)
            .filter(|(i, _)| !self.replayed_files.contains(i))
            .map(|(_, (f, _))| f)
    }

    /// The include chain of the next token's file: the files around the cursor's file,
    /// the cursor's file, and the spliced files down to the next token's, outermost first.
    pub fn chain(&self) -> Vec<PathBuf> {
        let mut f = Some(self.current_index());
        let mut inner = Vec::new();
        while let Some(i) = f {
            inner.push(self.files[i].0.clone());
            f = self.files[i].1;
        }
        inner.reverse();
        let mut chain = self.outer.clone();
        chain.extend(inner);
        chain
    }

    /// Reads the `$include`s at the cursor in place (inside a block, where the block reads
    /// on from the included file's tokens).
    pub fn splice_includes(&mut self) {
        while self.at_word("$include") {
            self.splice_include();
        }
    }

    /// `$include` inside a block: reads the file the include names and splices its tokens
    /// in at the cursor (the `$include` and its file name consumed). Errors are reported at
    /// the file name; a library include needs nothing.
    fn splice_include(&mut self) {
        let chain = self.chain();
        let including = self.current_index();
        self.advance();
        let Some((file, bytes)) = super::include::target(self, &chain) else {
            return;
        };
        let index = self.files.len();
        self.files.push((file.clone(), Some(including)));
        let Ok(text) = std::str::from_utf8(&bytes) else {
            self.problems.push(LocatedProblem {
                file,
                problem: Problem::error(Pos::default(), "the file is not UTF-8 text"),
            });
            return;
        };
        let (toks, errors) = super::lexer::tokens(text);
        let before = after_errors(&toks, &errors);
        for e in errors {
            self.problems.push(LocatedProblem {
                file: file.clone(),
                problem: Problem::error(e.pos, e.message),
            });
        }
        let n = toks.len();
        let at = self.at;
        // The flag of the token after the include (index n of `before`) joins its own.
        let after = self.lex_error_before[at] || before[n];
        self.lex_error_before
            .splice(at..=at, before.into_iter().take(n).chain([after]));
        self.token_files
            .splice(at..at, std::iter::repeat_n(index, n));
        self.tokens.splice(at..at, toks);
    }

    /// Whether a lexical error lies just before the next token: a value or name missing
    /// there is the bad token the lexer reported, not a second problem.
    pub fn after_lex_error(&self) -> bool {
        self.lex_error_before.get(self.at).copied().unwrap_or(false)
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
    /// An `$include` there is read in place: its tokens are the block's next ones.
    pub fn block_token(&mut self, kind: &str, open: Pos) -> Option<Token> {
        self.splice_includes();
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
                if !self.after_lex_error() {
                    self.error(pos, format!("expected a string for {what}, found {found}"));
                }
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
                if !self.after_lex_error() {
                    self.error(pos, format!("expected a number for {what}, found {found}"));
                }
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
        let file = self.file_of(pos);
        let params = self.params(&name)?;
        Some(ShaderCall {
            name,
            pos,
            params,
            file,
        })
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
            let Some((name, pos)) = self.string(&format!("a parameter name of \"{shader}\""))
            else {
                self.skip_past_list();
                return None;
            };
            let value_pos = self.pos();
            let Some(value) = self.value(&name, 0) else {
                self.skip_past_list();
                return None;
            };
            params.push(Param {
                name,
                pos,
                value,
                value_pos,
            });
            if !self.eat_punct(',') && !self.at_punct(')') {
                let (at, found) = (self.pos(), self.found());
                if !self.after_lex_error() {
                    self.error(
                        at,
                        format!("expected ',' or ')' after parameter, found {found}"),
                    );
                }
                self.skip_past_list();
                return None;
            }
        }
    }

    /// Error recovery in a parameter list whose `(` was read: skips to just after its `)`
    /// (nested lists skipped whole), so that one bad parameter is one error and the rest of
    /// the list is not read as statements. Stops before `end` or a top-level statement
    /// when the `)` is missing.
    fn skip_past_list(&mut self) {
        let mut depth = 0usize;
        while let Some(t) = self.peek() {
            match &t.tok {
                Tok::Punct('(' | '[' | '{') => depth += 1,
                Tok::Punct(')' | ']' | '}') if depth > 0 => depth -= 1,
                Tok::Punct(')') => {
                    self.at += 1;
                    return;
                }
                Tok::Word(w) if w == "end" || self.at_statement() => return,
                _ => {}
            }
            self.at += 1;
        }
    }

    fn value(&mut self, param: &str, depth: usize) -> Option<Value> {
        let Some(t) = self.peek().cloned() else {
            if !self.after_lex_error() {
                self.error(
                    self.pos(),
                    format!("missing value of parameter \"{param}\""),
                );
            }
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
                if !self.after_lex_error() {
                    self.error(
                        t.pos,
                        format!(
                            "expected a value for parameter \"{param}\", found {}",
                            other.describe()
                        ),
                    );
                }
                None
            }
        }
    }
}

/// Per token of `tokens` (and one past the last), whether one of `errors` lies between the
/// token before it and it.
fn after_errors(tokens: &[Token], errors: &[super::super::located::LexError]) -> Vec<bool> {
    let mut before = vec![false; tokens.len() + 1];
    for e in errors {
        let k = tokens.partition_point(|t| t.pos <= e.pos);
        before[k] = true;
    }
    before
}
