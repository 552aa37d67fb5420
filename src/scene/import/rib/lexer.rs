//! The RIB lexer: ASCII RIB text → tokens with their `line:column`.
//!
//! Tokens are request names (`WorldBegin`), quoted strings (with `\n`, `\t`, `\\`, `\"` and
//! octal escapes), numbers (integers and reals, with exponents), and the array brackets
//! `[` `]`. `#` starts a comment that runs to the end of the line (structural `##` comments
//! too). Binary RIB (bytes ≥ 0x80 outside strings and comments) is not supported and is
//! reported as such, naming the byte. A UTF-8 byte order mark before the first token is
//! skipped (by [`CharCursor`]).

use super::super::located::{self, CharCursor, LexError, Pos};
use super::text;

/// What a token is.
#[derive(Debug, Clone, PartialEq)]
pub enum Tok {
    /// A request name such as `Sphere`.
    Name(String),
    /// A quoted string, escapes resolved.
    Str(String),
    /// A number.
    Num(f64),
    /// `[`.
    Open,
    /// `]`.
    Close,
}

/// A token and where it starts.
pub type Token = located::Token<Tok>;

/// Splits `text` into tokens; every lexical error is returned (the lexer skips the
/// offending character or token and goes on).
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
                '[' => {
                    self.bump();
                    self.push(Tok::Open, pos);
                }
                ']' => {
                    self.bump();
                    self.push(Tok::Close, pos);
                }
                '"' => self.string(pos),
                c if c.is_ascii_digit() || matches!(c, '+' | '-' | '.') => self.number(pos),
                c if c.is_ascii_alphabetic() || c == '_' => {
                    let mut name = String::new();
                    while let Some(c) = self
                        .peek()
                        .filter(|c| c.is_ascii_alphanumeric() || *c == '_')
                    {
                        name.push(c);
                        self.bump();
                    }
                    self.push(Tok::Name(name), pos);
                }
                c if !c.is_ascii() || (c as u32) < 0x20 => {
                    self.bump();
                    self.error(
                        pos,
                        format!(
                            "unexpected byte 0x{:02x}: binary RIB is not supported",
                            text::first_byte(c)
                        ),
                    );
                    // One report per run of binary bytes.
                    while self
                        .peek()
                        .is_some_and(|c| !c.is_ascii() || ((c as u32) < 0x20 && !c.is_whitespace()))
                    {
                        self.bump();
                    }
                }
                c => {
                    self.bump();
                    self.error(pos, format!("unexpected character '{c}'"));
                }
            }
        }
    }

    fn push(&mut self, tok: Tok, pos: Pos) {
        self.out.push(Token { tok, pos });
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
                    Some('r') => s.push('\r'),
                    Some('b') => s.push('\u{8}'),
                    Some('f') => s.push('\u{c}'),
                    Some('\n') => {}
                    Some(d @ '0'..='7') => {
                        let mut v = d.to_digit(8).unwrap_or(0);
                        for _ in 0..2 {
                            match self.peek().and_then(|c| c.to_digit(8)) {
                                Some(x) => {
                                    v = v * 8 + x;
                                    self.bump();
                                }
                                None => break,
                            }
                        }
                        s.push(char::from_u32(v).unwrap_or('?'));
                    }
                    Some(other) => s.push(other),
                    None => {
                        self.error(pos, "unterminated string".into());
                        return;
                    }
                },
                c => s.push(text::shown(c)),
            }
        }
        self.push(Tok::Str(s), pos);
    }

    fn number(&mut self, pos: Pos) {
        let mut text = String::new();
        while let Some(c) = self
            .peek()
            .filter(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.'))
        {
            // A sign only starts the number or follows an exponent marker.
            if matches!(c, '+' | '-') && !text.is_empty() && !text.ends_with(['e', 'E']) {
                break;
            }
            text.push(c);
            self.bump();
        }
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() && !text.contains(['n', 'N', 'i', 'I']) => {
                self.push(Tok::Num(v), pos)
            }
            _ => self.error(pos, format!("invalid number \"{text}\"")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(line: usize, column: usize) -> Pos {
        Pos { line, column }
    }

    #[test]
    fn tokens_carry_positions() {
        let (t, e) = tokens("Sphere 1 -1.5e0 .5 [ \"a\\\"b\" ] # c\n  WorldEnd");
        assert!(e.is_empty());
        let kinds: Vec<_> = t.iter().map(|t| (t.tok.clone(), t.pos)).collect();
        assert_eq!(
            kinds,
            vec![
                (Tok::Name("Sphere".into()), p(1, 1)),
                (Tok::Num(1.0), p(1, 8)),
                (Tok::Num(-1.5), p(1, 10)),
                (Tok::Num(0.5), p(1, 17)),
                (Tok::Open, p(1, 20)),
                (Tok::Str("a\"b".into()), p(1, 22)),
                (Tok::Close, p(1, 29)),
                (Tok::Name("WorldEnd".into()), p(2, 3)),
            ]
        );
    }

    #[test]
    fn numbers_next_to_brackets_and_signs() {
        let (t, e) = tokens("[1-2]");
        assert!(e.is_empty());
        let v: Vec<_> = t.into_iter().map(|t| t.tok).collect();
        assert_eq!(
            v,
            vec![Tok::Open, Tok::Num(1.0), Tok::Num(-2.0), Tok::Close]
        );
    }

    #[test]
    fn errors_are_located() {
        let (_, e) = tokens("Color [1 2 3]\n  \"open\nx 1.2.3 @");
        let got: Vec<_> = e.iter().map(|e| (e.pos, e.message.as_str())).collect();
        assert_eq!(
            got,
            vec![
                (p(2, 3), "unterminated string (a string ends on its line)"),
                (p(3, 3), "invalid number \"1.2.3\""),
                (p(3, 9), "unexpected character '@'"),
            ]
        );
    }

    #[test]
    fn binary_bytes_are_named_by_their_value() {
        let (_, e) = tokens(&text::decode(
            b"\xef\xbb\xbfSphere \x89\x01 \xc3\xa9 \xef\xbb\xbf",
        ));
        let got: Vec<_> = e.iter().map(|e| (e.pos, e.message.as_str())).collect();
        assert_eq!(
            got,
            vec![
                (p(1, 8), "unexpected byte 0x89: binary RIB is not supported"),
                (
                    p(1, 11),
                    "unexpected byte 0xc3: binary RIB is not supported"
                ),
                (
                    p(1, 13),
                    "unexpected byte 0xef: binary RIB is not supported"
                ),
            ]
        );
    }

    #[test]
    fn a_string_keeps_a_byte_that_is_not_utf8_as_the_replacement_character() {
        let (t, _) = tokens(&text::decode(b"\"a\xe9\""));
        assert_eq!(t[0].tok, Tok::Str("a\u{fffd}".into()));
    }

    #[test]
    fn octal_escapes() {
        let (t, _) = tokens("\"\\101\\tB\"");
        assert_eq!(t[0].tok, Tok::Str("A\tB".into()));
    }
}
