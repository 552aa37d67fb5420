//! OBJ logical lines: physical lines joined where one ends in a backslash (`\`, the OBJ
//! specification's line continuation), with every byte offset of the joined line mapped back
//! to the `line:column` of the file where it was written.
//!
//! The backslash becomes a space, so a word never runs across the join. A backslash that
//! ends a comment (from a word starting with `#` to the end of the line) does not continue
//! it: comments often end in one (a Windows directory), and joining would swallow the
//! statement below. A backslash on the last line of the file continues into nothing.

use std::borrow::Cow;

/// One statement of an OBJ file, as read after joining continued lines.
pub struct LogicalLine<'a> {
    /// The joined bytes (each continuing backslash replaced by a space); borrowed from the
    /// file when the statement is one physical line.
    pub text: Cow<'a, [u8]>,
    /// The first physical piece: its 1-based line number and its bytes as written (for
    /// columns, counted in characters).
    first: (usize, &'a [u8]),
    /// The continuing pieces: each one's first byte's offset in `text`, line and bytes.
    more: Vec<(usize, usize, &'a [u8])>,
}

impl LogicalLine<'_> {
    /// The 1-based line and column in the file of byte `offset` of [`Self::text`] (past
    /// the end of the last piece for offsets beyond it).
    pub fn at(&self, offset: usize) -> (usize, usize) {
        let (start, line, bytes) = match self.more.partition_point(|p| p.0 <= offset) {
            0 => (0, self.first.0, self.first.1),
            k => self.more[k - 1],
        };
        (line, super::column(bytes, offset - start))
    }

    /// The 1-based line number the statement starts on.
    pub fn first_line(&self) -> usize {
        self.first.0
    }
}

/// The logical lines of `bytes`, in order (a final empty line included, as splitting at
/// every newline gives); one at a time, so a large file is not held twice.
pub fn logical_lines(bytes: &[u8]) -> LogicalLines<'_> {
    LogicalLines {
        rest: Some(bytes),
        line: 0,
    }
}

/// The iterator of [`logical_lines`].
pub struct LogicalLines<'a> {
    /// What is left to read (`None` after the last line).
    rest: Option<&'a [u8]>,
    /// Physical lines read so far.
    line: usize,
}

impl<'a> LogicalLines<'a> {
    /// The next physical line without its line ending.
    fn physical(&mut self) -> Option<&'a [u8]> {
        let rest = self.rest?;
        let (line, rest) = match rest.iter().position(|&b| b == b'\n') {
            Some(k) => (&rest[..k], Some(&rest[k + 1..])),
            None => (rest, None),
        };
        self.rest = rest;
        self.line += 1;
        Some(line.strip_suffix(b"\r").unwrap_or(line))
    }
}

impl<'a> Iterator for LogicalLines<'a> {
    type Item = LogicalLine<'a>;

    fn next(&mut self) -> Option<LogicalLine<'a>> {
        let first = self.physical()?;
        let mut logical = LogicalLine {
            text: Cow::Borrowed(first),
            first: (self.line, first),
            more: Vec::new(),
        };
        while continues(&logical.text) {
            // The backslash becomes the space that separates the pieces' words.
            let text = logical.text.to_mut();
            *text
                .last_mut()
                .expect("a continued line ends in a backslash") = b' ';
            let Some(next) = self.physical() else { break };
            logical.more.push((text.len(), self.line, next));
            text.extend_from_slice(next);
        }
        Some(logical)
    }
}

/// Whether `text` ends in a backslash that is not inside a comment.
fn continues(text: &[u8]) -> bool {
    text.ends_with(b"\\")
        && !text
            .split(|b| b.is_ascii_whitespace())
            .any(|word| word.starts_with(b"#"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trailing_backslash_joins_the_next_line_and_offsets_map_back() {
        let lines: Vec<_> = logical_lines(b"v 1 \\\n  2 3\nf 1 2 3\n").collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(&*lines[0].text, b"v 1    2 3");
        // "2" is the third character of line 2.
        assert_eq!(lines[0].at(7), (2, 3));
        assert_eq!(lines[0].at(2), (1, 3));
        assert_eq!(lines[0].first_line(), 1);
        assert_eq!(
            (&*lines[1].text, lines[1].first_line()),
            (&b"f 1 2 3"[..], 3)
        );
        assert_eq!((&*lines[2].text, lines[2].first_line()), (&b""[..], 4));
    }

    #[test]
    fn comments_are_not_continued_and_a_last_backslash_ends_the_file() {
        let lines: Vec<_> =
            logical_lines(b"# C:\\dir\\\r\nv 0 0 0 # at C:\\\nv 1 0 0 \\").collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(&*lines[0].text, b"# C:\\dir\\");
        assert_eq!(&*lines[1].text, b"v 0 0 0 # at C:\\");
        assert_eq!(&*lines[2].text, b"v 1 0 0  ");
        assert_eq!(lines[2].first_line(), 3);
    }
}
