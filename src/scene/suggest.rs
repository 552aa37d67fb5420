//! "Did you mean …?": the closest known name to a misspelt one.
//!
//! Distance is optimal-string-alignment (Damerau–Levenshtein without repeated edits of a
//! substring): insertions, deletions, substitutions and swaps of neighbours each cost one.
//! Case differences cost nothing extra beyond a substitution, but an exact case-insensitive
//! match always wins.

/// Edit distance between `a` and `b` (characters, adjacent transpositions count once).
pub fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let width = b.len() + 1;
    let mut d = vec![0usize; (a.len() + 1) * width];
    for (i, cell) in d.iter_mut().step_by(width).enumerate() {
        *cell = i;
    }
    for (j, cell) in d.iter_mut().take(width).enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (d[(i - 1) * width + j] + 1)
                .min(d[i * width + j - 1] + 1)
                .min(d[(i - 1) * width + j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[(i - 2) * width + j - 2] + 1);
            }
            d[i * width + j] = best;
        }
    }
    d[a.len() * width + b.len()]
}

/// The candidate closest to `wrong`, if it is close enough to be a likely typo: at most one
/// edit for short names, about a third of the length for longer ones. Ties go to the first
/// candidate.
pub fn closest<'a, I>(wrong: &str, candidates: I) -> Option<&'a str>
where
    I: IntoIterator<Item = &'a str>,
{
    let lower = wrong.to_lowercase();
    let limit = (wrong.chars().count() / 3).max(1);
    let mut best: Option<(usize, &'a str)> = None;
    for candidate in candidates {
        if candidate == wrong {
            continue;
        }
        let d = if candidate.to_lowercase() == lower {
            0
        } else {
            distance(wrong, candidate)
        };
        if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, candidate));
        }
    }
    best.map(|(_, c)| c)
}

/// `"a", "b" or "c"` for help texts.
pub fn quoted_list<'a, I>(names: I) -> String
where
    I: IntoIterator<Item = &'a str>,
{
    let names: Vec<String> = names.into_iter().map(|n| format!("\"{n}\"")).collect();
    match names.len() {
        0 => String::new(),
        1 => names[0].clone(),
        n => format!("{} or {}", names[..n - 1].join(", "), names[n - 1]),
    }
}

/// `"did you mean …?"` for `wrong` among `candidates`, else a list of what is expected.
pub fn suggestion(wrong: &str, candidates: &[&str], what: &str) -> Option<String> {
    if let Some(best) = closest(wrong, candidates.iter().copied()) {
        return Some(format!("did you mean \"{best}\"?"));
    }
    match candidates.len() {
        0 => Some(format!("no {what} are defined")),
        1..=8 => Some(format!(
            "expected {}",
            quoted_list(candidates.iter().copied())
        )),
        // Long lists too (Camera, Options): a user who typed an unknown name needs them.
        _ => Some(format!(
            "expected one of {}",
            quoted_list(candidates.iter().copied())
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(distance("", "abc"), 3);
        assert_eq!(distance("chrom", "chrome"), 1);
        assert_eq!(distance("colour", "color"), 1);
        assert_eq!(distance("ab", "ba"), 1);
        assert_eq!(distance("kitten", "sitting"), 3);
    }

    #[test]
    fn closest_picks_likely_typos_only() {
        let names = ["chrome", "white", "red"];
        assert_eq!(closest("chrom", names), Some("chrome"));
        assert_eq!(closest("whtie", names), Some("white"));
        assert_eq!(closest("RED", names), Some("red"));
        assert_eq!(closest("blue", names), None);
        assert_eq!(closest("red", names), None);
    }

    #[test]
    fn lists() {
        assert_eq!(quoted_list(["a"]), "\"a\"");
        assert_eq!(quoted_list(["a", "b", "c"]), "\"a\", \"b\" or \"c\"");
    }

    #[test]
    fn suggestions_fall_back_to_lists() {
        assert_eq!(
            suggestion("colour", &["color", "name"], "fields").as_deref(),
            Some("did you mean \"color\"?")
        );
        assert_eq!(
            suggestion("zzz", &["albedo"], "fields").as_deref(),
            Some("expected \"albedo\"")
        );
        assert_eq!(
            suggestion("zzz", &[], "materials").as_deref(),
            Some("no materials are defined")
        );
    }
}
