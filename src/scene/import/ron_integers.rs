//! A clear message for `ron`'s bare "integer is out of bounds": the number as written, the
//! field it was written for and the range that field takes (whole-number fields are `u32`,
//! seeds `u64`).

/// The message and help for an out-of-range integer at 1-based `line:column` of `text`, or
/// `None` when no number is written there.
pub fn out_of_range(text: &str, line: usize, column: usize) -> Option<(String, String)> {
    let line_start: usize = text
        .split_inclusive('\n')
        .take(line.checked_sub(1)?)
        .map(str::len)
        .sum();
    let line_text = text.get(line_start..)?.lines().next()?;
    let start = line_start + line_text.char_indices().nth(column.checked_sub(1)?)?.0;
    // ron points at the digits of a negative number; the sign belongs to it.
    let start = if text[..start].ends_with('-') {
        start - 1
    } else {
        start
    };
    let literal: String = text[start..]
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '+' | '_'))
        .collect();
    if !literal.chars().any(|c| c.is_ascii_digit()) {
        return None;
    }
    let field = field_before(&text[..start]);
    let max = if field == Some("seed") {
        u64::MAX
    } else {
        u64::from(u32::MAX)
    };
    let what = field
        .map(|f| format!("`{f}`"))
        .unwrap_or_else(|| "this value".into());
    Some((
        format!("integer {literal} is out of range for {what}"),
        format!("{what} takes a whole number from 0 to {max}"),
    ))
}

/// The name of the last `name:` written before the end of `text`.
fn field_before(text: &str) -> Option<&str> {
    let colon = text.rfind(':')?;
    let head = text[..colon].trim_end();
    let name_start = head
        .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1);
    let name = &head[name_start..];
    (!name.is_empty()).then_some(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_the_number_the_field_and_its_range() {
        let text =
            "Scene(\n  cameras: [(resolution: (99999999999, 4))],\n  options: (seed: -3),\n)";
        assert_eq!(
            out_of_range(text, 2, 27).unwrap(),
            (
                "integer 99999999999 is out of range for `resolution`".to_string(),
                "`resolution` takes a whole number from 0 to 4294967295".to_string()
            )
        );
        let seed = out_of_range(text, 3, 20).unwrap();
        assert_eq!(seed.0, "integer -3 is out of range for `seed`");
        assert_eq!(
            seed.1,
            "`seed` takes a whole number from 0 to 18446744073709551615"
        );
        assert_eq!(out_of_range(text, 1, 1), None);
        assert_eq!(out_of_range(text, 9, 1), None);
    }
}
