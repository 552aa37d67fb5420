//! RIB tokens → requests: a request name followed by its arguments (numbers, strings and
//! arrays of either), each with its position. What the arguments mean — positional values
//! and the `"name" value` parameter list — is read by [`Args`], on behalf of the request
//! handlers in [`super::build`].

use super::super::located::Pos;
use super::lexer::{Tok, Token};

/// One argument of a request.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A bare number.
    Num(f64),
    /// A bare string.
    Str(String),
    /// `[ numbers ]` (also the empty array).
    Nums(Vec<f64>),
    /// `[ strings ]`.
    Strs(Vec<String>),
}

impl Value {
    /// How the value is described in messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Value::Num(_) => "a number",
            Value::Str(_) => "a string",
            Value::Nums(_) => "an array of numbers",
            Value::Strs(_) => "an array of strings",
        }
    }

    /// The numbers of a number or a number array.
    pub fn nums(&self) -> Option<&[f64]> {
        match self {
            Value::Num(v) => Some(std::slice::from_ref(v)),
            Value::Nums(v) => Some(v),
            _ => None,
        }
    }

    /// The strings of a string or a string array.
    pub fn strs(&self) -> Option<&[String]> {
        match self {
            Value::Str(v) => Some(std::slice::from_ref(v)),
            Value::Strs(v) => Some(v),
            Value::Nums(v) if v.is_empty() => Some(&[]),
            _ => None,
        }
    }
}

/// An argument and where it (and each array element) is.
#[derive(Debug, Clone, PartialEq)]
pub struct Arg {
    /// The value.
    pub value: Value,
    /// Where it starts (the `[` of an array).
    pub pos: Pos,
    /// Where each array element is (empty for a bare value).
    pub items: Vec<Pos>,
}

impl Arg {
    /// Position of element `i` (the argument's own position for a bare value).
    pub fn item(&self, i: usize) -> Pos {
        self.items.get(i).copied().unwrap_or(self.pos)
    }
}

/// One request: its name, where the name is, and its arguments.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The request name (`Sphere`).
    pub name: String,
    /// Where the name is.
    pub pos: Pos,
    /// The arguments in order.
    pub args: Vec<Arg>,
    /// Whether a syntax error lies inside the request (it is then not read, so that one
    /// mistake gives one message).
    pub broken: bool,
}

/// A syntax error: where and what.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SyntaxError {
    /// Where.
    pub pos: Pos,
    /// What.
    pub message: String,
}

/// Groups tokens into requests. Every syntax error is returned; a request holding a
/// malformed array is marked [`Request::broken`] and parsing goes on.
pub fn requests(tokens: &[Token]) -> (Vec<Request>, Vec<SyntaxError>) {
    let mut out: Vec<Request> = Vec::new();
    let mut errors = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let t = &tokens[i];
        match &t.tok {
            Tok::Name(name) => {
                out.push(Request {
                    name: name.clone(),
                    pos: t.pos,
                    args: Vec::new(),
                    broken: false,
                });
                i += 1;
            }
            Tok::Open => {
                let (arg, next) = array(tokens, i, &mut errors);
                i = next;
                if let Some(r) = out.last_mut() {
                    match arg {
                        Some(arg) => r.args.push(arg),
                        None => r.broken = true,
                    }
                } else {
                    errors.push(SyntaxError {
                        pos: t.pos,
                        message: "an array before the first request".into(),
                    });
                }
            }
            Tok::Close => {
                errors.push(SyntaxError {
                    pos: t.pos,
                    message: "']' without a matching '['".into(),
                });
                if let Some(r) = out.last_mut() {
                    r.broken = true;
                }
                i += 1;
            }
            Tok::Num(_) | Tok::Str(_) => {
                let value = match &t.tok {
                    Tok::Num(v) => Value::Num(*v),
                    Tok::Str(s) => Value::Str(s.clone()),
                    _ => unreachable!("matched above"),
                };
                match out.last_mut() {
                    Some(r) => r.args.push(Arg {
                        value,
                        pos: t.pos,
                        items: Vec::new(),
                    }),
                    None => errors.push(SyntaxError {
                        pos: t.pos,
                        message: format!("{} before the first request", value.kind()),
                    }),
                }
                i += 1;
            }
        }
    }
    (out, errors)
}

/// Reads the array opening at `tokens[start]`; returns it (or `None` if malformed) and the
/// index after it.
fn array(tokens: &[Token], start: usize, errors: &mut Vec<SyntaxError>) -> (Option<Arg>, usize) {
    let open = tokens[start].pos;
    let mut nums = Vec::new();
    let mut strs = Vec::new();
    let mut items = Vec::new();
    let mut i = start + 1;
    let mut ok = true;
    loop {
        let Some(t) = tokens.get(i) else {
            errors.push(SyntaxError {
                pos: open,
                message: "unclosed '[': the file ends inside an array".into(),
            });
            return (None, i);
        };
        match &t.tok {
            Tok::Close => {
                i += 1;
                break;
            }
            Tok::Num(v) => nums.push(*v),
            Tok::Str(s) => strs.push(s.clone()),
            Tok::Open => {
                errors.push(SyntaxError {
                    pos: t.pos,
                    message: "arrays do not nest".into(),
                });
                ok = false;
            }
            Tok::Name(n) => {
                errors.push(SyntaxError {
                    pos: open,
                    message: format!("unclosed '[' before request \"{n}\""),
                });
                return (None, i);
            }
        }
        items.push(t.pos);
        i += 1;
    }
    if !nums.is_empty() && !strs.is_empty() {
        errors.push(SyntaxError {
            pos: open,
            message: "an array mixes numbers and strings".into(),
        });
        ok = false;
    }
    let value = if strs.is_empty() {
        Value::Nums(nums)
    } else {
        Value::Strs(strs)
    };
    (
        ok.then_some(Arg {
            value,
            pos: open,
            items,
        }),
        i,
    )
}

#[cfg(test)]
mod tests {
    use super::super::lexer::tokens;
    use super::*;

    fn parse(text: &str) -> (Vec<Request>, Vec<SyntaxError>) {
        let (t, e) = tokens(text);
        assert!(e.is_empty(), "{e:?}");
        requests(&t)
    }

    #[test]
    fn requests_with_arguments() {
        let (r, e) = parse("Sphere 1 -1 1 360 \"Cs\" [1 0 0]\nColor [0.5 0.5 0.5]");
        assert!(e.is_empty());
        assert_eq!(r.len(), 2);
        assert_eq!(r[0].name, "Sphere");
        assert_eq!(r[0].args.len(), 6);
        assert_eq!(r[0].args[4].value, Value::Str("Cs".into()));
        assert_eq!(r[0].args[5].value, Value::Nums(vec![1.0, 0.0, 0.0]));
        assert_eq!(
            r[0].args[5].items[2],
            Pos {
                line: 1,
                column: 29
            }
        );
        assert_eq!(r[1].pos, Pos { line: 2, column: 1 });
    }

    #[test]
    fn malformed_arrays_are_reported() {
        let (_, e) = parse("Color [1 \"a\"]\nColor [1 [2]]\nColor [1 2\nWorldEnd ]");
        let got: Vec<_> = e
            .iter()
            .map(|e| (e.pos.line, e.pos.column, e.message.as_str()))
            .collect();
        assert_eq!(
            got,
            vec![
                (1, 7, "an array mixes numbers and strings"),
                (2, 10, "arrays do not nest"),
                (2, 13, "']' without a matching '['"),
                (3, 7, "unclosed '[' before request \"WorldEnd\""),
                (4, 10, "']' without a matching '['"),
            ]
        );
    }
}
