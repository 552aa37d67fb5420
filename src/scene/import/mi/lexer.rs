//! The `.mi` lexer: mental ray scene text → tokens with their `line:column`.
//!
//! Tokens are words (keywords such as `options`, and `$include`), quoted strings (with `\n`,
//! `\t`, `\\` and `\"` escapes), numbers (integers and reals with exponents), library names
//! in angle brackets (`<base.mi>`, only after `$include`) and the punctuation `(` `)` `[`
//! `]` `{` `}` `,` `=`. `#` starts a comment that runs to the end of the line. Every lexical
//! error is collected; the lexer skips the offending character and goes on.

use super::super::located::{self, CharCursor, LexError, Pos};

/// What a token is.
#[derive(Debug, Clone, PartialEq)]
pub enum Tok {
    /// A keyword or bare word (`options`, `end`, `on`, `$include`).
    Word(String),
    /// A quoted string, escapes resolved.
    Str(String),
    /// A number.
    Num(f64),
    /// A library include name `<base.mi>` (without the brackets).
    Library(String),
    /// One of `( ) [ ] { } , =`.
    Punct(char),
}

impl Tok {
    /// How a message names the token: `"end"`, `a string`, `a number`, `'('`.
    pub fn describe(&self) -> String {
        match self {
            Tok::Word(w) => format!("\"{w}\""),
            Tok::Str(_) => "a string".into(),
            Tok::Num(_) => "a number".into(),
            Tok::Library(l) => format!("<{l}>"),
            Tok::Punct(c) => format!("'{c}'"),
        }
    }
}

/// A token and where it starts.
pub type Token = located::Token<Tok>;

/// Splits `text` into tokens; every lexical error is returned.
pub fn tokens(text: &str) -> (Vec<Token>, Vec<LexError>) {
    let mut lx = Lexer {
        src: CharCursor::new(text),
        out: Vec::new(),
        errors: Vec::new(),
    };
    lx.run();
    (lx.out, lx.errors)
}

struct Lexer {
    src: CharCursor,
    out: Vec<Token>,
    errors: Vec<LexError>,
}

impl Lexer {
    fn peek(&self) -> Option<char> {
        self.src.peek()
    }

    fn bump(&mut self) -> Option<char> {
        self.src.bump()
    }

    fn error(&mut self, pos: Pos, message: String) {
        self.errors.push(LexError { pos, message });
    }

    fn push(&mut self, tok: Tok, pos: Pos) {
        self.out.push(Token { tok, pos });
    }

    fn after_include(&self) -> bool {
        matches!(self.out.last(), Some(Token { tok: Tok::Word(w), .. }) if w == "$include")
    }

    fn run(&mut self) {
        while let Some(c) = self.peek() {
            let pos = self.src.pos();
            match c {
                c if c.is_whitespace() => {
                    self.bump();
                }
                '#' => {
                    while self.peek().is_some_and(|c| c != '\n') {
                        self.bump();
                    }
                }
                '(' | ')' | '[' | ']' | '{' | '}' | ',' | '=' => {
                    self.bump();
                    self.push(Tok::Punct(c), pos);
                }
                '<' if self.after_include() => self.library(pos),
                '"' => self.string(pos),
                c if c.is_ascii_digit() || matches!(c, '+' | '-' | '.') => self.number(pos),
                c if c.is_ascii_alphabetic() || c == '_' || c == '$' => {
                    let mut word = String::new();
                    while let Some(c) = self
                        .peek()
                        .filter(|c| c.is_ascii_alphanumeric() || matches!(*c, '_' | '$'))
                    {
                        word.push(c);
                        self.bump();
                    }
                    self.push(Tok::Word(word), pos);
                }
                c => {
                    self.bump();
                    if c.is_control() {
                        self.error(pos, format!("unexpected byte 0x{:02x}", u32::from(c)));
                    } else {
                        self.error(pos, format!("unexpected character '{c}'"));
                    }
                }
            }
        }
    }

    fn library(&mut self, pos: Pos) {
        self.bump();
        let mut name = String::new();
        loop {
            match self.peek() {
                Some('>') => {
                    self.bump();
                    self.push(Tok::Library(name), pos);
                    return;
                }
                Some(c) if c != '\n' => {
                    name.push(c);
                    self.bump();
                }
                _ => {
                    self.error(pos, "unterminated library name (expected '>')".into());
                    return;
                }
            }
        }
    }

    fn string(&mut self, pos: Pos) {
        self.bump();
        let mut s = String::new();
        loop {
            let Some(c) = self.bump() else {
                self.error(pos, "unterminated string".into());
                return;
            };
            match c {
                '"' => break,
                '\n' => {
                    self.error(
                        pos,
                        "unterminated string (a string ends on its line)".into(),
                    );
                    return;
                }
                '\\' => match self.bump() {
                    Some('n') => s.push('\n'),
                    Some('t') => s.push('\t'),
                    Some(other) => s.push(other),
                    None => {
                        self.error(pos, "unterminated string".into());
                        return;
                    }
                },
                c => s.push(c),
            }
        }
        self.push(Tok::Str(s), pos);
    }

    fn number(&mut self, pos: Pos) {
        let mut text = String::new();
        while let Some(c) = self
            .peek()
            .filter(|c| c.is_ascii_alphanumeric() || matches!(*c, '+' | '-' | '.'))
        {
            // A sign only starts the number or follows an exponent marker.
            if matches!(c, '+' | '-') && !text.is_empty() && !text.ends_with(['e', 'E']) {
                break;
            }
            text.push(c);
            self.bump();
        }
        match text.parse::<f64>() {
            Ok(v)
                if v.is_finite()
                    && !text
                        .contains(|c: char| c.is_ascii_alphabetic() && c != 'e' && c != 'E') =>
            {
                self.push(Tok::Num(v), pos)
            }
            _ => self.error(pos, format!("invalid number \"{text}\"")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<Tok> {
        let (t, e) = tokens(s);
        assert!(e.is_empty(), "{e:?}");
        t.into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn words_strings_numbers_and_punctuation() {
        assert_eq!(
            toks("light \"L\" ( \"color\" 1 -2.5e1, ) # c\n$include <base.mi>"),
            vec![
                Tok::Word("light".into()),
                Tok::Str("L".into()),
                Tok::Punct('('),
                Tok::Str("color".into()),
                Tok::Num(1.0),
                Tok::Num(-25.0),
                Tok::Punct(','),
                Tok::Punct(')'),
                Tok::Word("$include".into()),
                Tok::Library("base.mi".into()),
            ]
        );
    }

    #[test]
    fn errors_are_located() {
        let (_, e) = tokens("a\n  1.2.3 @");
        assert_eq!(e[0].pos, Pos { line: 2, column: 3 });
        assert_eq!(e[0].message, "invalid number \"1.2.3\"");
        assert_eq!(e[1].message, "unexpected character '@'");
    }

    #[test]
    fn a_byte_order_mark_before_the_first_token_is_skipped() {
        let (t, e) = tokens("\u{feff}options \"opt\"");
        assert_eq!(e, []);
        assert_eq!(t[0].tok, Tok::Word("options".into()));
        assert_eq!(t[0].pos, Pos { line: 1, column: 1 });
    }
}
