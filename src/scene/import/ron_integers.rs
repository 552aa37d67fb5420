//! Clear messages for whole numbers `ron` refuses: its bare "integer is out of bounds" (the
//! number as written, the field it was written for and the range that field takes) and a
//! decimal where a whole number belongs (`ron` reads `1.5` as `1` followed by `.5` and says
//! "expected comma"). Whole-number fields are `u32`, seeds `u64`; the range starts at the
//! least value the loader accepts for the field.

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
    let (what, range) = field_range(&text[..start]);
    Some((
        format!("integer {literal} is out of range for {what}"),
        format!("{what} takes a whole number {range}"),
    ))
}

/// A decimal number written where `ron` read a whole number and stopped at its fraction or
/// exponent ("expected comma" at `line:column`, 1-based): its start (`line`, `column`), the
/// message and the help; `None` when no decimal number ends there.
pub fn decimal(text: &str, line: usize, column: usize) -> Option<(usize, usize, String, String)> {
    let line_start: usize = text
        .split_inclusive('\n')
        .take(line.checked_sub(1)?)
        .map(str::len)
        .sum();
    let line_text = text.get(line_start..)?.lines().next()?;
    let at = line_start + line_text.char_indices().nth(column.checked_sub(1)?)?.0;
    let number_char =
        |c: char| c.is_ascii_digit() || matches!(c, '.' | '_' | 'e' | 'E' | '+' | '-');
    // Back over the digits `ron` took as the whole number (and its sign).
    let head = text[..at].trim_end_matches(|c: char| c.is_ascii_digit() || c == '_');
    let head = head.strip_suffix(['-', '+']).unwrap_or(head);
    if head.ends_with(|c: char| c.is_alphanumeric() || c == '.' || c == '_') {
        return None;
    }
    let start = head.len();
    let taken = &text[start..at];
    let rest: String = text[at..].chars().take_while(|&c| number_char(c)).collect();
    if !taken.chars().any(|c| c.is_ascii_digit()) || !rest.starts_with(['.', 'e', 'E']) {
        return None;
    }
    let literal = format!("{taken}{rest}");
    literal.replace('_', "").parse::<f64>().ok()?;
    let (what, range) = field_range(&text[..start]);
    let column = 1 + text[line_start..start].chars().count();
    Some((
        line,
        column,
        format!("expected a whole number, found {literal}"),
        format!("{what} takes a whole number {range}"),
    ))
}

/// How the field written before a number is named in a message and the range it takes
/// (`from 1 to 4294967295`).
fn field_range(before: &str) -> (String, String) {
    let field = field_before(before);
    let max = if field == Some("seed") {
        u64::MAX
    } else {
        u64::from(u32::MAX)
    };
    let least = field.map_or(0, least_value);
    let what = field
        .map(|f| format!("`{f}`"))
        .unwrap_or_else(|| "this value".into());
    (what, format!("from {least} to {max}"))
}

/// The least value the loader accepts for a whole-number field (the checks in `validate`,
/// `samples` and `environment`); 0 for the others.
fn least_value(field: &str) -> u64 {
    match field {
        "gather" => 2,
        "resolution" | "samples" | "min" | "max_depth" | "light_samples" | "photons"
        | "final_gather" => 1,
        _ => 0,
    }
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
                "`resolution` takes a whole number from 1 to 4294967295".to_string()
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

    #[test]
    fn a_decimal_is_named_from_its_first_digit() {
        let text = "Scene(\n  options: (seed: 1.5),\n  cameras: [(resolution: (-32.5e1, 4))],\n)";
        assert_eq!(
            decimal(text, 2, 20).unwrap(),
            (
                2,
                19,
                "expected a whole number, found 1.5".to_string(),
                "`seed` takes a whole number from 0 to 18446744073709551615".to_string()
            )
        );
        let (line, column, message, help) = decimal(text, 3, 30).unwrap();
        assert_eq!((line, column), (3, 27));
        assert_eq!(message, "expected a whole number, found -32.5e1");
        assert_eq!(
            help,
            "`resolution` takes a whole number from 1 to 4294967295"
        );
        // Not after a number, or not a number: `ron`'s own message stays.
        assert_eq!(decimal(text, 2, 12), None);
        assert_eq!(decimal("(a: 1.5.2)", 1, 8), None);
    }
}
