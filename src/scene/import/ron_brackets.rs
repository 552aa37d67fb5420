//! The bracket structure of RON text as written, for syntax messages: which `(` and `[`
//! are open at a position, where the value before a position ends, which bracket a file
//! that ends unbalanced most likely left open, a block comment still open at a position
//! and the first `#` written outside strings and comments. Strings, characters and
//! comments are skipped; nothing here needs the text to parse.

use super::located::Pos;

/// An opening bracket.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Open {
    /// `(`, `[` or `{`.
    pub bracket: char,
    /// Where it is.
    pub pos: Pos,
    /// Indentation (leading blanks) of its line.
    indent: usize,
}

/// The text's structure up to a position.
#[derive(Debug, Clone, Default)]
pub struct Scan {
    /// Brackets open there, outermost first (closers matched to the nearest opener).
    pub open: Vec<Open>,
    /// Just after the last character that is not blank or comment before the position.
    pub last_end: Option<Pos>,
    /// Position of that last character.
    pub last: Option<(Pos, char)>,
    /// Openers more indented than a later closer at the start of its line: an opener left
    /// unclosed there, whose closer the indentation says belongs to an outer opener.
    pub suspects: Vec<Open>,
    /// Openers minus closers.
    pub depth: isize,
    /// A block comment open at the position (the text ends inside it when the scan ran to
    /// the end).
    pub open_comment: Option<BlockComment>,
    /// The first `#` outside strings and comments that starts neither a raw identifier
    /// (`r#name`) nor an attribute (`#![…]`): RON has no `#` comments.
    pub hash: Option<Pos>,
}

/// A block comment `/* … */` not closed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BlockComment {
    /// Its `/*`.
    pub pos: Pos,
    /// The `/*` inside it, each opening a nested comment (RON block comments nest).
    pub inner: Vec<Pos>,
}

/// Character index of 1-based `line:column` in `text` (its end when past it).
pub fn char_offset(text: &str, line: usize, column: usize) -> usize {
    let mut at = 0;
    for (l, line_text) in text.split_inclusive('\n').enumerate() {
        let chars = line_text.chars().count();
        if l + 1 == line {
            return at + column.saturating_sub(1).min(chars);
        }
        at += chars;
    }
    at
}

/// The structure of `text` before character index `upto`.
pub fn scan(text: &str, upto: usize) -> Scan {
    let chars: Vec<char> = text.chars().collect();
    let upto = upto.min(chars.len());
    let mut out = Scan::default();
    let (mut line, mut column) = (1usize, 1usize);
    let mut indent = 0usize;
    let mut line_blank = true;
    let mut i = 0;
    // Moves past `n` characters, counting lines.
    let advance = |i: &mut usize, line: &mut usize, column: &mut usize, n: usize| {
        for _ in 0..n {
            if *i >= chars.len() {
                return;
            }
            if chars[*i] == '\n' {
                *line += 1;
                *column = 1;
            } else {
                *column += 1;
            }
            *i += 1;
        }
    };
    while i < upto {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '\n' {
            indent = 0;
            line_blank = true;
            advance(&mut i, &mut line, &mut column, 1);
            continue;
        }
        if c.is_whitespace() {
            if line_blank {
                indent += 1;
            }
            advance(&mut i, &mut line, &mut column, 1);
            continue;
        }
        if c == '/' && next == Some('/') {
            while i < upto && chars[i] != '\n' {
                advance(&mut i, &mut line, &mut column, 1);
            }
            continue;
        }
        if c == '/' && next == Some('*') {
            let mut comment = BlockComment {
                pos: Pos { line, column },
                inner: Vec::new(),
            };
            let mut nest = 0usize;
            while i < upto {
                match (chars[i], chars.get(i + 1).copied()) {
                    ('/', Some('*')) => {
                        if nest > 0 {
                            comment.inner.push(Pos { line, column });
                        }
                        nest += 1;
                        advance(&mut i, &mut line, &mut column, 2);
                    }
                    ('*', Some('/')) => {
                        nest -= 1;
                        advance(&mut i, &mut line, &mut column, 2);
                        if nest == 0 {
                            break;
                        }
                    }
                    _ => advance(&mut i, &mut line, &mut column, 1),
                }
            }
            if nest > 0 {
                out.open_comment = Some(comment);
            }
            continue;
        }
        let first_on_line = line_blank;
        line_blank = false;
        let pos = Pos { line, column };
        out.last = Some((pos, c));
        match c {
            '"' | '\'' => {
                // A string or character: up to the unescaped closing quote.
                advance(&mut i, &mut line, &mut column, 1);
                while i < upto {
                    let d = chars[i];
                    advance(&mut i, &mut line, &mut column, 1);
                    if d == '\\' {
                        advance(&mut i, &mut line, &mut column, 1);
                    } else if d == c {
                        break;
                    }
                }
            }
            'r' if matches!(next, Some('"' | '#')) && raw_string_at(&chars, i + 1) => {
                let hashes = chars[i + 1..].iter().take_while(|&&h| h == '#').count();
                advance(&mut i, &mut line, &mut column, 2 + hashes);
                while i < upto {
                    let closes =
                        chars[i] == '"' && (1..=hashes).all(|k| chars.get(i + k) == Some(&'#'));
                    advance(&mut i, &mut line, &mut column, 1);
                    if closes {
                        advance(&mut i, &mut line, &mut column, hashes);
                        break;
                    }
                }
            }
            '#' if out.hash.is_none() && !raw_identifier_or_attribute(&chars, i) => {
                out.hash = Some(pos);
                advance(&mut i, &mut line, &mut column, 1);
            }
            '(' | '[' | '{' => {
                out.open.push(Open {
                    bracket: c,
                    pos,
                    indent,
                });
                out.depth += 1;
                advance(&mut i, &mut line, &mut column, 1);
            }
            ')' | ']' | '}' => {
                out.depth -= 1;
                if first_on_line && out.open.len() >= 2 {
                    let top = out.open[out.open.len() - 1];
                    let below = out.open[out.open.len() - 2];
                    if indent < top.indent && below.indent <= indent {
                        out.suspects.push(top);
                        out.open.pop();
                    }
                }
                out.open.pop();
                advance(&mut i, &mut line, &mut column, 1);
            }
            _ => advance(&mut i, &mut line, &mut column, 1),
        }
        out.last_end = Some(Pos { line, column });
    }
    out
}

/// Whether the `#` at `at` is the `#` of a raw identifier `r#name` or starts an attribute
/// `#![…]`.
fn raw_identifier_or_attribute(chars: &[char], at: usize) -> bool {
    let word = |c: &char| c.is_alphanumeric() || *c == '_';
    let raw = at > 0
        && chars[at - 1] == 'r'
        && (at < 2 || !word(&chars[at - 2]))
        && chars.get(at + 1).is_some_and(word);
    raw || chars.get(at + 1) == Some(&'!')
}

/// Whether a raw string `r"…"` / `r#"…"#` starts with the quote or hashes at `at`.
fn raw_string_at(chars: &[char], at: usize) -> bool {
    let hashes = chars[at..].iter().take_while(|&&h| h == '#').count();
    chars.get(at + hashes) == Some(&'"')
}

/// The opener that a text ending with unclosed brackets most likely left open: one whose
/// closer the indentation gives to an outer bracket, else the innermost one still open;
/// `None` when every bracket is closed.
pub fn unclosed_at_end(text: &str) -> Option<Open> {
    let s = scan(text, usize::MAX);
    if s.depth <= 0 {
        return None;
    }
    s.suspects.last().or(s.open.last()).copied()
}

/// Where the file's last line that is not blank ends (just after its last character).
pub fn end_of_last_line(text: &str) -> Pos {
    let trimmed = text.trim_end();
    let line = 1 + trimmed.matches('\n').count();
    let column = 1 + trimmed.rsplit('\n').next().map_or(0, |l| l.chars().count());
    Pos { line, column }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pos(line: usize, column: usize) -> Pos {
        Pos { line, column }
    }

    #[test]
    fn skips_strings_and_comments_and_finds_the_value_end() {
        let text = "(a: \"(\", // [\n b: [1, /* ( */ 2] )";
        let s = scan(text, char_offset(text, 2, 19));
        assert_eq!(s.open.len(), 1);
        assert_eq!(s.last_end, Some(pos(2, 19)));
        assert_eq!(s.last, Some((pos(2, 18), ']')));
        let end = scan(text, usize::MAX);
        assert_eq!(end.depth, 0);
        assert!(end.open.is_empty());
        assert_eq!(unclosed_at_end(text), None);
    }

    #[test]
    fn an_unclosed_bracket_is_found_by_the_indentation_of_the_closers() {
        let text = "Scene(\n    render: (root: \"w\",\n)\n";
        let open = unclosed_at_end(text).unwrap();
        assert_eq!((open.bracket, open.pos), ('(', pos(2, 13)));
        // Without a misleading closer: the innermost open bracket.
        let open = unclosed_at_end("Scene(\n  a: [1, 2,\n").unwrap();
        assert_eq!((open.bracket, open.pos), ('[', pos(2, 6)));
        assert_eq!(end_of_last_line("a\n  bc \n\n"), pos(2, 5));
    }

    #[test]
    fn an_open_block_comment_and_a_stray_hash_are_found() {
        let text = "(a: \"#\", b: r#c, // #\n /* x /* y */ z\n";
        let s = scan(text, usize::MAX);
        assert_eq!(s.hash, None);
        let comment = s.open_comment.unwrap();
        assert_eq!((comment.pos, comment.inner), (pos(2, 2), vec![pos(2, 7)]));
        let s = scan(
            "#![enable(implicit_some)]\n(/* ok */ a: 1, # no\n)",
            usize::MAX,
        );
        assert_eq!((s.hash, s.open_comment), (Some(pos(2, 17)), None));
    }

    #[test]
    fn offsets_count_characters_and_stop_at_the_end() {
        assert_eq!(char_offset("é\nab", 2, 2), 3);
        assert_eq!(char_offset("ab", 9, 1), 2);
    }
}
