//! Object (and instance) names, chosen once every primitive is read: a name set by
//! `Attribute "identifier" "name"` is kept (its first use; `world` is the group's), and
//! every other primitive gets its base — the identifier, or the request in lower case —
//! with the next number that no object uses or is given anywhere in the file: `sphere_1`,
//! `sphere_2`, or `ball_2` for a second `ball`, skipping a `sphere_1` the file names itself,
//! before or after.

use std::collections::{HashMap, HashSet};

/// What a primitive asks to be called.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Requested {
    /// The identifier, or the request in lower case.
    pub base: String,
    /// Whether `base` was set by `Attribute "identifier" "name"`.
    pub given: bool,
}

/// The name the group takes; no object may take it.
const GROUP: &str = "world";

/// One distinct name per primitive, in order.
pub fn object_names(requested: &[Requested]) -> Vec<String> {
    let given: HashSet<&str> = requested
        .iter()
        .filter(|r| r.given && r.base != GROUP)
        .map(|r| r.base.as_str())
        .collect();
    let mut used: HashSet<String> = HashSet::new();
    let mut last: HashMap<&str, usize> = HashMap::new();
    requested
        .iter()
        .map(|r| {
            let base = r.base.as_str();
            let name = if r.given && base != GROUP && !used.contains(base) {
                let n = last.entry(base).or_insert(0);
                *n = (*n).max(1);
                base.to_string()
            } else {
                let n = last.entry(base).or_insert(0);
                loop {
                    *n += 1;
                    let name = format!("{base}_{n}");
                    if !given.contains(name.as_str()) && !used.contains(&name) {
                        break name;
                    }
                }
            };
            used.insert(name.clone());
            name
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(requested: &[(&str, bool)]) -> Vec<String> {
        let requested: Vec<Requested> = requested
            .iter()
            .map(|&(base, given)| Requested {
                base: base.into(),
                given,
            })
            .collect();
        object_names(&requested)
    }

    #[test]
    fn generated_names_count_per_request() {
        assert_eq!(
            names(&[("sphere", false), ("patch", false), ("sphere", false)]),
            ["sphere_1", "patch_1", "sphere_2"]
        );
    }

    #[test]
    fn a_repeated_identifier_is_numbered_from_2() {
        assert_eq!(
            names(&[("ball", true), ("ball", true), ("world", true)]),
            ["ball", "ball_2", "world_1"]
        );
    }

    #[test]
    fn generated_names_skip_a_given_name_before_or_after() {
        assert_eq!(
            names(&[("sphere", false), ("sphere_1", true)]),
            ["sphere_2", "sphere_1"]
        );
        assert_eq!(
            names(&[("sphere_1", true), ("sphere", false)]),
            ["sphere_1", "sphere_2"]
        );
        assert_eq!(
            names(&[("ball", true), ("ball", true), ("ball_2", true)]),
            ["ball", "ball_3", "ball_2"]
        );
    }
}
