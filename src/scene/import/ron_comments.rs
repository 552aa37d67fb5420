//! Comments written the way other formats write them, which `ron` misnames: a `#` line
//! (`ron`: "expected identifier", or a call in the wrong style at the enclosing `(`) and a
//! block comment that never closes — often one with a `/*` inside it, since RON block
//! comments nest (`ron`: "the file ends inside an unclosed `(`"). Each is reported where it
//! starts.

use super::located::Pos;
use super::ron_brackets::scan;
use super::ron_hints::Hint;

/// A message for the error `ron` reported at `at` of `text` when a comment written wrong
/// at or before `at` caused it; `None` keeps `ron`'s.
pub fn explain(text: &str, at: Pos) -> Option<Hint> {
    let whole = scan(text, usize::MAX);
    if let Some(comment) = whole.open_comment.filter(|c| c.pos <= at) {
        let help = match comment.inner.first() {
            Some(inner) => format!(
                "RON block comments nest: the `/*` at {}:{} opens a comment inside this one, \
                 and a `*/` closes only the innermost open comment; remove that `/*` or \
                 give it its own `*/`",
                inner.line, inner.column
            ),
            None => "close it with `*/` (RON block comments nest: each `/*` inside it \
                     needs its own `*/`)"
                .into(),
        };
        return Some(Hint {
            at: comment.pos,
            message: "unclosed block comment: the file ends inside it".into(),
            help,
        });
    }
    let hash = whole.hash.filter(|&h| h <= at)?;
    Some(Hint {
        at: hash,
        message: "`#` does not start a comment in RON".into(),
        help: "RON comments are `// …` (to the end of the line) and `/* … */`: write `//` \
               instead of `#`"
            .into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pos(line: usize, column: usize) -> Pos {
        Pos { line, column }
    }

    #[test]
    fn a_comment_written_wrong_is_reported_where_it_starts() {
        let hash = "Scene(\n    # main camera\n    cameras: [],\n)";
        let h = explain(hash, pos(2, 5)).unwrap();
        assert_eq!(
            (h.at, h.message.as_str()),
            (pos(2, 5), "`#` does not start a comment in RON")
        );
        // An error before the `#` is `ron`'s to report.
        assert_eq!(explain(hash, pos(1, 7)), None);
        let nested = "Scene(\n    /* a /* b */ c\n    cameras: [],\n)";
        let h = explain(nested, pos(4, 2)).unwrap();
        assert_eq!(h.at, pos(2, 5));
        assert!(h.help.contains("the `/*` at 2:10"), "{}", h.help);
        // `#` inside strings, comments and raw identifiers is no comment.
        assert_eq!(explain("(a: \"#\", /* # */ b: r#c)", pos(1, 99)), None);
    }
}
