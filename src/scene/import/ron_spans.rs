//! Where values are in the RON source: a small, forgiving parser that records the
//! `line:column` of every value by its path (`instances[2].material`,
//! `objects[0].mesh.Inline.polygons[1][3]`).
//!
//! `ron` reports positions for syntax and type errors but not for the values it returns, so
//! semantic errors look their location up here. The index is built from text that `ron`
//! already accepted; on anything it does not understand it stops and keeps what it has, so
//! lookups degrade to the nearest enclosing value rather than failing.
//!
//! Path syntax: `.field` selects a struct field; `.Name` selects the named struct or enum
//! variant `Name(...)` itself (a no-op that documents the variant); `[i]` selects the i-th
//! item of a list or tuple (a newtype variant such as `Scale((1, 2, 3))` is a one-item
//! tuple: `Scale[0][2]` is the `3`). An implicit `Some(...)` wrapper is looked through.

pub use super::located::Pos;

/// One value of the source and what is inside it.
#[derive(Debug, Clone, Default)]
struct Node {
    pos: Pos,
    /// The identifier in front of `( … )`, or a bare identifier (`Box`, `true`).
    name: Option<String>,
    /// `field: value` entries of a struct-like value.
    fields: Vec<(String, Node)>,
    /// Items of a list, tuple or newtype variant.
    items: Vec<Node>,
    /// Position of the closing bracket, if the value has one.
    end: Option<Pos>,
    /// Character range `[start, end)` of the value in the text.
    range: (usize, usize),
}

/// Positions of every value in one RON text.
#[derive(Debug, Clone, Default)]
pub struct SpanIndex {
    root: Option<Node>,
    /// The indexed text, for [`SpanIndex::text_at`].
    chars: Vec<char>,
}

/// Deepest nesting the index follows (ron itself stops at 128).
const MAX_DEPTH: usize = 256;

impl SpanIndex {
    /// Indexes `text`. Never fails: unparsable parts are left out.
    pub fn new(text: &str) -> Self {
        let mut parser = Parser {
            chars: text.chars().collect(),
            at: 0,
            line: 1,
            column: 1,
        };
        parser.skip_attributes();
        let root = parser.value(0);
        Self {
            root,
            chars: parser.chars,
        }
    }

    /// Position of the value at `path`; if the path does not exist in the text (a defaulted
    /// field, say), the position of the deepest value on the path that does.
    pub fn locate(&self, path: &str) -> Pos {
        let Some(mut node) = self.root.as_ref() else {
            return Pos::default();
        };
        for seg in segments(path) {
            match step(node, &seg) {
                Some(next) => node = next,
                None => break,
            }
        }
        node.pos
    }

    /// The source text of the value at `path` and its position, only if the value is
    /// written in the text (used to re-parse a value for a precise error message).
    pub fn text_at(&self, path: &str) -> Option<(Pos, String)> {
        let mut node = self.root.as_ref()?;
        for seg in segments(path) {
            node = step(node, &seg)?;
        }
        let (a, b) = node.range;
        let text = self.chars.get(a..b)?.iter().collect();
        Some((node.pos, text))
    }

    /// Start of the bracketed value whose closing bracket is at `close` (`ron` reports a
    /// missing field at the closing parenthesis; the opening one reads better).
    pub fn opening_of(&self, close: Pos) -> Option<Pos> {
        let mut todo: Vec<&Node> = self.root.iter().collect();
        while let Some(node) = todo.pop() {
            if node.end == Some(close) {
                return Some(node.pos);
            }
            todo.extend(node.items.iter());
            todo.extend(node.fields.iter().map(|(_, v)| v));
        }
        None
    }

    /// The first value (in text order) written as `Name(field: …)` with one of `names`:
    /// its position and name.
    pub fn first_with_fields(&self, names: &[&str]) -> Option<(Pos, String)> {
        let mut todo: Vec<&Node> = self.root.iter().collect();
        let mut first: Option<(Pos, String)> = None;
        while let Some(node) = todo.pop() {
            if let Some(name) = node.name.as_deref() {
                let earlier = first.as_ref().is_none_or(|(p, _)| node.pos < *p);
                if !node.fields.is_empty() && names.contains(&name) && earlier {
                    first = Some((node.pos, name.to_string()));
                }
            }
            todo.extend(node.items.iter());
            todo.extend(node.fields.iter().map(|(_, v)| v));
        }
        first
    }

    /// Position of the value at `path`, only if it is written in the text.
    #[cfg(test)]
    pub fn find(&self, path: &str) -> Option<Pos> {
        let mut node = self.root.as_ref()?;
        for seg in segments(path) {
            node = step(node, &seg)?;
        }
        Some(node.pos)
    }
}

/// One step of a path.
#[derive(Debug, PartialEq)]
enum Seg {
    Field(String),
    Index(usize),
}

fn segments(path: &str) -> Vec<Seg> {
    let mut out = Vec::new();
    let mut word = String::new();
    let mut chars = path.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '.' => {
                if !word.is_empty() {
                    out.push(Seg::Field(std::mem::take(&mut word)));
                }
            }
            '[' => {
                if !word.is_empty() {
                    out.push(Seg::Field(std::mem::take(&mut word)));
                }
                let mut digits = String::new();
                for d in chars.by_ref() {
                    if d == ']' {
                        break;
                    }
                    digits.push(d);
                }
                out.push(Seg::Index(digits.parse().unwrap_or(usize::MAX)));
            }
            _ => word.push(c),
        }
    }
    if !word.is_empty() {
        out.push(Seg::Field(word));
    }
    out
}

fn step<'a>(node: &'a Node, seg: &Seg) -> Option<&'a Node> {
    match seg {
        Seg::Field(f) => {
            if let Some((_, v)) = node.fields.iter().find(|(k, _)| k == f) {
                return Some(v);
            }
            if node.name.as_deref() == Some(f.as_str()) {
                return Some(node);
            }
        }
        Seg::Index(i) => {
            if node.name.as_deref() != Some("Some") {
                return node.items.get(*i);
            }
        }
    }
    // Look through an implicit-some wrapper `Some(x)`.
    if node.name.as_deref() == Some("Some") && node.items.len() == 1 && node.fields.is_empty() {
        return step(&node.items[0], seg);
    }
    None
}

struct Parser {
    chars: Vec<char>,
    at: usize,
    line: usize,
    column: usize,
}

impl Parser {
    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }

    fn peek_at(&self, ahead: usize) -> Option<char> {
        self.chars.get(self.at + ahead).copied()
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.at += 1;
        if c == '\n' {
            self.line += 1;
            self.column = 1;
        } else {
            self.column += 1;
        }
        Some(c)
    }

    fn pos(&self) -> Pos {
        Pos {
            line: self.line,
            column: self.column,
        }
    }

    /// Skips whitespace and comments (`//`, nested `/* */`).
    fn skip_ws(&mut self) {
        loop {
            match (self.peek(), self.peek_at(1)) {
                (Some(c), _) if c.is_whitespace() => {
                    self.bump();
                }
                (Some('/'), Some('/')) => {
                    while let Some(c) = self.bump() {
                        if c == '\n' {
                            break;
                        }
                    }
                }
                (Some('/'), Some('*')) => {
                    self.bump();
                    self.bump();
                    let mut depth = 1usize;
                    while depth > 0 {
                        match (self.peek(), self.peek_at(1)) {
                            (None, _) => return,
                            (Some('*'), Some('/')) => {
                                self.bump();
                                self.bump();
                                depth -= 1;
                            }
                            (Some('/'), Some('*')) => {
                                self.bump();
                                self.bump();
                                depth += 1;
                            }
                            _ => {
                                self.bump();
                            }
                        }
                    }
                }
                _ => return,
            }
        }
    }

    /// Skips `#![enable(...)]` attributes.
    fn skip_attributes(&mut self) {
        loop {
            self.skip_ws();
            if self.peek() == Some('#') && self.peek_at(1) == Some('!') {
                let mut depth = 0usize;
                while let Some(c) = self.bump() {
                    match c {
                        '[' => depth += 1,
                        ']' => {
                            depth = depth.saturating_sub(1);
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                }
            } else {
                return;
            }
        }
    }

    /// Consumes the closing bracket `close` if it is next, returning where it was.
    fn close(&mut self, close: char) -> Option<Pos> {
        self.skip_ws();
        let pos = self.pos();
        self.eat(close).then_some(pos)
    }

    fn eat(&mut self, c: char) -> bool {
        self.skip_ws();
        if self.peek() == Some(c) {
            self.bump();
            true
        } else {
            false
        }
    }

    fn value(&mut self, depth: usize) -> Option<Node> {
        if depth > MAX_DEPTH {
            return None;
        }
        self.skip_ws();
        let pos = self.pos();
        let start = self.at;
        let c = self.peek()?;
        let mut node = Node {
            pos,
            ..Node::default()
        };
        match c {
            '(' => {
                self.bump();
                self.contents(&mut node, ')', depth);
            }
            '[' => {
                self.bump();
                self.contents(&mut node, ']', depth);
            }
            '{' => {
                self.bump();
                self.map(&mut node, depth);
            }
            '"' => self.string(),
            '\'' => self.char_literal(),
            'b' if self.peek_at(1) == Some('"') => {
                self.bump();
                self.string();
            }
            'b' if self.peek_at(1) == Some('\'') => {
                self.bump();
                self.char_literal();
            }
            'r' if matches!(self.peek_at(1), Some('"' | '#')) && !self.is_raw_ident() => {
                self.bump();
                self.raw_string();
            }
            'b' if self.peek_at(1) == Some('r') && matches!(self.peek_at(2), Some('"' | '#')) => {
                self.bump();
                self.bump();
                self.raw_string();
            }
            c if c.is_ascii_digit() || matches!(c, '+' | '-' | '.') => self.number(),
            c if c.is_alphabetic() || c == '_' => {
                let name = self.identifier();
                self.skip_ws();
                if self.peek() == Some('(') {
                    self.bump();
                    self.contents(&mut node, ')', depth);
                }
                node.name = Some(name);
            }
            _ => return None,
        }
        node.range = (start, self.at);
        Some(node)
    }

    fn is_raw_ident(&self) -> bool {
        self.peek_at(1) == Some('#')
            && self
                .peek_at(2)
                .is_some_and(|c| c.is_alphabetic() || c == '_')
    }

    /// Items or fields up to `close`.
    fn contents(&mut self, node: &mut Node, close: char, depth: usize) {
        loop {
            if let Some(end) = self.close(close) {
                node.end = Some(end);
                return;
            }
            self.skip_ws();
            let Some(c) = self.peek() else { return };
            // `field: value`?
            if close == ')' && (c.is_alphabetic() || c == '_') {
                let save = (self.at, self.line, self.column);
                let key = self.identifier();
                if self.eat(':') {
                    match self.value(depth + 1) {
                        Some(v) => node.fields.push((key, v)),
                        None => return,
                    }
                    if !self.eat(',') {
                        node.end = self.close(close);
                        return;
                    }
                    continue;
                }
                (self.at, self.line, self.column) = save;
            }
            match self.value(depth + 1) {
                Some(v) => node.items.push(v),
                None => return,
            }
            if !self.eat(',') {
                node.end = self.close(close);
                return;
            }
        }
    }

    /// `{ key: value, … }`; values are kept as items, and values under a string key also as
    /// fields named by the key (`bind: {"albedo": …}` is found at `.bind.albedo`).
    fn map(&mut self, node: &mut Node, depth: usize) {
        loop {
            if self.eat('}') {
                return;
            }
            self.skip_ws();
            let key_start = self.at;
            if self.value(depth + 1).is_none() || !self.eat(':') {
                return;
            }
            let key = self.string_key(key_start);
            match self.value(depth + 1) {
                Some(v) => {
                    if let Some(key) = key {
                        node.fields.push((key, v.clone()));
                    }
                    node.items.push(v)
                }
                None => return,
            }
            if !self.eat(',') {
                self.eat('}');
                return;
            }
        }
    }

    fn identifier(&mut self) -> String {
        let mut out = String::new();
        if self.peek() == Some('r') && self.is_raw_ident() {
            self.bump();
            self.bump();
        }
        while let Some(c) = self.peek() {
            if c.is_alphanumeric() || c == '_' {
                out.push(c);
                self.bump();
            } else {
                break;
            }
        }
        out
    }

    fn number(&mut self) {
        let mut prev = ' ';
        if matches!(self.peek(), Some('+' | '-')) {
            self.bump();
        }
        while let Some(c) = self.peek() {
            let exponent_sign = matches!(c, '+' | '-') && matches!(prev, 'e' | 'E');
            if c.is_alphanumeric() || c == '_' || c == '.' || exponent_sign {
                prev = c;
                self.bump();
            } else {
                break;
            }
        }
    }

    /// The contents of a plain `"…"` string starting at character `start` (escapes kept
    /// as written), or `None` if no such string starts there.
    fn string_key(&self, start: usize) -> Option<String> {
        if self.chars.get(start) != Some(&'"') {
            return None;
        }
        let mut out = String::new();
        for &c in self.chars.get(start + 1..)? {
            if c == '"' {
                return Some(out);
            }
            out.push(c);
        }
        None
    }

    /// A `"…"` string with escapes; the cursor is on the opening quote.
    fn string(&mut self) {
        self.bump();
        while let Some(c) = self.bump() {
            match c {
                '\\' => {
                    self.bump();
                }
                '"' => return,
                _ => {}
            }
        }
    }

    fn char_literal(&mut self) {
        self.bump();
        while let Some(c) = self.bump() {
            match c {
                '\\' => {
                    self.bump();
                }
                '\'' => return,
                _ => {}
            }
        }
    }

    /// `r#"…"#` with any number of hashes; the cursor is after the `r`.
    fn raw_string(&mut self) {
        let mut hashes = 0usize;
        while self.peek() == Some('#') {
            hashes += 1;
            self.bump();
        }
        if self.peek() != Some('"') {
            return;
        }
        self.bump();
        while let Some(c) = self.bump() {
            if c == '"' && (0..hashes).all(|k| self.peek_at(k) == Some('#')) {
                for _ in 0..hashes {
                    self.bump();
                }
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(index: &SpanIndex, path: &str) -> (usize, usize) {
        let p = index
            .find(path)
            .unwrap_or_else(|| panic!("{path} not found"));
        (p.line, p.column)
    }

    #[test]
    fn locates_fields_items_and_variants() {
        let text = "Scene(\n  objects: [\n    (name: \"q\", mesh: Inline(vertices: [(1, 1, 0)], polygons: [[0, 3, 2, 1]])),\n  ],\n)";
        let index = SpanIndex::new(text);
        assert_eq!(at(&index, "objects"), (2, 12));
        assert_eq!(at(&index, "objects[0]"), (3, 5));
        assert_eq!(at(&index, "objects[0].name"), (3, 12));
        assert_eq!(at(&index, "objects[0].mesh"), (3, 23));
        assert_eq!(at(&index, "objects[0].mesh.Inline"), (3, 23));
        assert_eq!(at(&index, "objects[0].mesh.Inline.polygons[0][3]"), (3, 74));
        assert_eq!(at(&index, "objects[0].mesh.vertices[0][2]"), (3, 48));
    }

    #[test]
    fn skips_comments_strings_and_raw_strings() {
        let text = "/* a /* nested */ ( */ // x: (\n(a: \"s\\\")(\", b: r#\"x\"(\"#, c: 'x', d: [1e-3, -inf], e: Scale((1, 2, 3)), f: Some(\"g\"))";
        let index = SpanIndex::new(text);
        assert_eq!(at(&index, "a"), (2, 5));
        assert_eq!(at(&index, "b"), (2, 17));
        assert_eq!(at(&index, "c"), (2, 30));
        assert_eq!(at(&index, "d[1]"), (2, 45));
        assert_eq!(at(&index, "e.Scale[0][2]"), (2, 68));
        assert_eq!(at(&index, "f"), (2, 76));
    }

    #[test]
    fn locate_falls_back_to_the_deepest_existing_value() {
        let index = SpanIndex::new("(a: (b: 1))");
        assert_eq!(index.locate("a.c.d"), Pos { line: 1, column: 5 });
        assert_eq!(index.find("a.c"), None);
    }

    #[test]
    fn finds_the_opening_of_a_closing_bracket() {
        let index = SpanIndex::new("(a: [(b: 1), Lambert(x: 2 )])");
        assert_eq!(
            index.opening_of(Pos {
                line: 1,
                column: 11
            }),
            Some(Pos { line: 1, column: 6 })
        );
        assert_eq!(
            index.opening_of(Pos {
                line: 1,
                column: 27
            }),
            Some(Pos {
                line: 1,
                column: 14
            })
        );
        assert_eq!(index.opening_of(Pos { line: 1, column: 3 }), None);
    }

    #[test]
    fn survives_garbage() {
        for text in [
            "", "(", "((((", "\"abc", "r#\"", "(a: ", "/*", "[1, 2", "{1: ",
        ] {
            let index = SpanIndex::new(text);
            let _ = index.locate("a[0].b");
        }
    }
}
