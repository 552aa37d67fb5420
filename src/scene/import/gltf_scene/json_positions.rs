//! Where a value sits in a `.gltf` file's JSON text, for messages: the line and column of
//! an element such as `images[2].uri` (the `gltf` crate keeps no positions). A `.glb` has no
//! lines; its messages name the element instead.
//!
//! The scanner only walks the path it is given, skipping every other value by counting
//! brackets outside strings, so it reads each byte at most once and never recurses; text
//! that is not JSON just yields `None`.

/// One step of a path into a JSON document.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step<'a> {
    /// A member of an object, by key (compared as written, without unescaping).
    Key(&'a str),
    /// An element of an array.
    Index(usize),
}

/// The 1-based line and column (in characters) of the value at `path` in `json`, or `None`
/// when it is not there.
pub fn value_position(json: &[u8], path: &[Step<'_>]) -> Option<(usize, usize)> {
    let mut s = Scanner { text: json, at: 0 };
    for step in path {
        s.skip_space();
        match *step {
            Step::Key(key) => s.enter_member(key)?,
            Step::Index(index) => s.enter_element(index)?,
        }
    }
    s.skip_space();
    (s.at < json.len()).then(|| line_column(json, s.at))
}

/// The steps of an element path as messages write it: `meshes[0].attributes["_ID"]` →
/// `meshes`, 0, `attributes`, `_ID`; `None` for text that is not such a path.
pub fn parse_path(path: &str) -> Option<Vec<Step<'_>>> {
    let mut steps = Vec::new();
    let mut rest = path;
    while !rest.is_empty() {
        rest = rest.strip_prefix('.').unwrap_or(rest);
        if let Some(quoted) = rest.strip_prefix("[\"") {
            let (key, after) = quoted.split_once("\"]")?;
            steps.push(Step::Key(key));
            rest = after;
        } else if let Some(index) = rest.strip_prefix('[') {
            let (index, after) = index.split_once(']')?;
            steps.push(Step::Index(index.parse().ok()?));
            rest = after;
        } else {
            let end = rest.find(['.', '[']).unwrap_or(rest.len());
            if end == 0 {
                return None;
            }
            steps.push(Step::Key(&rest[..end]));
            rest = &rest[end..];
        }
    }
    Some(steps)
}

/// The line and column of the element an error path names (`accessors[3].count`), or of
/// the nearest enclosing element that is in the file (a missing member's object); `None`
/// when the path is not one or not even its first step is there.
pub fn element_position(json: &[u8], path: &str) -> Option<(usize, usize)> {
    let steps = parse_path(path)?;
    (1..=steps.len())
        .rev()
        .find_map(|n| value_position(json, &steps[..n]))
}

/// Line and column of byte `at` (1-based; a byte that is not UTF-8 counts as a character).
fn line_column(text: &[u8], at: usize) -> (usize, usize) {
    let before = &text[..at];
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |p| p + 1);
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    (line, column)
}

struct Scanner<'a> {
    text: &'a [u8],
    at: usize,
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.text.get(self.at).copied()
    }

    fn skip_space(&mut self) {
        while self.peek().is_some_and(|b| b.is_ascii_whitespace()) {
            self.at += 1;
        }
    }

    fn expect(&mut self, byte: u8) -> Option<()> {
        self.skip_space();
        (self.peek() == Some(byte)).then(|| self.at += 1)
    }

    /// Reads a string starting at its opening quote; returns its raw bytes.
    fn string(&mut self) -> Option<&[u8]> {
        if self.peek() != Some(b'"') {
            return None;
        }
        let start = self.at + 1;
        let mut k = start;
        while let Some(&b) = self.text.get(k) {
            match b {
                b'\\' => k += 2,
                b'"' => {
                    self.at = k + 1;
                    return Some(&self.text[start..k]);
                }
                _ => k += 1,
            }
        }
        None
    }

    /// Skips one value (string, number, literal, object or array).
    fn skip_value(&mut self) -> Option<()> {
        self.skip_space();
        match self.peek()? {
            b'"' => self.string().map(|_| ()),
            b'{' | b'[' => {
                let mut depth = 0usize;
                loop {
                    match self.peek()? {
                        b'"' => {
                            self.string()?;
                            continue;
                        }
                        b'{' | b'[' => depth += 1,
                        b'}' | b']' => {
                            depth -= 1;
                            if depth == 0 {
                                self.at += 1;
                                return Some(());
                            }
                        }
                        _ => {}
                    }
                    self.at += 1;
                }
            }
            _ => {
                while self
                    .peek()
                    .is_some_and(|b| !matches!(b, b',' | b'}' | b']') && !b.is_ascii_whitespace())
                {
                    self.at += 1;
                }
                Some(())
            }
        }
    }

    /// Moves to the value of member `key` of the object here.
    fn enter_member(&mut self, key: &str) -> Option<()> {
        self.expect(b'{')?;
        loop {
            self.skip_space();
            let name = self.string()?;
            let found = name == key.as_bytes();
            self.expect(b':')?;
            if found {
                return Some(());
            }
            self.skip_value()?;
            self.expect(b',')?;
        }
    }

    /// Moves to element `index` of the array here.
    fn enter_element(&mut self, index: usize) -> Option<()> {
        self.expect(b'[')?;
        for _ in 0..index {
            self.skip_value()?;
            self.expect(b',')?;
        }
        self.skip_space();
        (self.peek() != Some(b']')).then_some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const JSON: &str = "{\n  \"asset\": {\"version\": \"2.0\", \"x\": [1, {\"uri\": \"no\"}]},\n  \"images\": [\n    {\"name\": \"a\\\"]\"},\n    {\"name\": \"b\", \"uri\": \"wood.png\"}\n  ]\n}\n";

    #[test]
    fn finds_an_element_past_nested_values_and_strings_with_brackets() {
        let path = [Step::Key("images"), Step::Index(1), Step::Key("uri")];
        assert_eq!(value_position(JSON.as_bytes(), &path), Some((5, 26)));
        let path = [Step::Key("images"), Step::Index(0)];
        assert_eq!(value_position(JSON.as_bytes(), &path), Some((4, 5)));
    }

    #[test]
    fn error_paths_are_parsed_and_located_at_their_nearest_element() {
        assert_eq!(
            parse_path("images[1].uri"),
            Some(vec![Step::Key("images"), Step::Index(1), Step::Key("uri")])
        );
        assert_eq!(
            parse_path("a[0][2][\"_X.y\"]"),
            Some(vec![
                Step::Key("a"),
                Step::Index(0),
                Step::Index(2),
                Step::Key("_X.y")
            ])
        );
        assert_eq!(parse_path("a[x]"), None);
        let json = JSON.as_bytes();
        assert_eq!(element_position(json, "images[1].uri"), Some((5, 26)));
        // images[0] has no uri: its object.
        assert_eq!(element_position(json, "images[0].uri"), Some((4, 5)));
        assert_eq!(element_position(json, "textures[0]"), None);
    }

    #[test]
    fn missing_elements_and_other_text_give_none() {
        let none = |json: &str, path: &[Step<'_>]| value_position(json.as_bytes(), path);
        assert_eq!(none(JSON, &[Step::Key("images"), Step::Index(2)]), None);
        assert_eq!(
            none(
                JSON,
                &[Step::Key("images"), Step::Index(0), Step::Key("uri")]
            ),
            None
        );
        assert_eq!(none(JSON, &[Step::Key("textures")]), None);
        assert_eq!(none("glTF\x02\0\0\0", &[Step::Key("images")]), None);
        assert_eq!(
            none("{\"images\": [", &[Step::Key("images"), Step::Index(3)]),
            None
        );
        assert_eq!(none("[[[[", &[Step::Index(0), Step::Index(9)]), None);
    }
}
