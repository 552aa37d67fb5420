//! Where the values of one scene element were written, kept beside the values themselves so
//! that the assembled description can locate each value, not only its element: a
//! validation error about `cameras[0].resolution[0]` then points at the `0` of `resolution
//! 0 16`, not at the camera's instance.
//!
//! Paths are description paths below the element (`.resolution[0]`,
//! `.contour.Simple.width`, `.kind.Spot.cone_angle`); a value that can land on several paths
//! (a light's `origin` is a point's or a spot's position) is recorded under each, as only the
//! path validation asks for is ever looked up.

use super::super::located::Located;

/// The positions of one element's values, by description path below the element.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ValuePositions {
    entries: Vec<(String, Located)>,
}

impl ValuePositions {
    /// Records that the value at `path` (below the element) was written at `at`; a later
    /// record of the same path wins.
    pub fn record(&mut self, path: impl Into<String>, at: Located) {
        let path = path.into();
        self.entries.retain(|(p, _)| *p != path);
        self.entries.push((path, at));
    }

    /// Where the value at `path` was written, if recorded.
    pub fn get(&self, path: &str) -> Option<&Located> {
        self.entries
            .iter()
            .find(|(p, _)| p == path)
            .map(|(_, at)| at)
    }

    /// Every recorded position as a full description path under `element`
    /// (`cameras[0]` + `.resolution[0]`), appended to `paths`.
    pub fn extend_under(&self, element: &str, paths: &mut Vec<(String, Located)>) {
        paths.extend(
            self.entries
                .iter()
                .map(|(p, at)| (format!("{element}{p}"), at.clone())),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::import::located::Pos;

    fn at(line: usize) -> Located {
        Located {
            file: "a.mi".into(),
            pos: Pos { line, column: 3 },
        }
    }

    #[test]
    fn a_later_record_wins_and_paths_go_under_the_element() {
        let mut v = ValuePositions::default();
        v.record(".aspect", at(1));
        v.record(".resolution[0]", at(2));
        v.record(".aspect", at(3));
        assert_eq!(v.get(".aspect"), Some(&at(3)));
        let mut paths = Vec::new();
        v.extend_under("cameras[1]", &mut paths);
        assert_eq!(
            paths,
            [
                ("cameras[1].resolution[0]".to_string(), at(2)),
                ("cameras[1].aspect".to_string(), at(3)),
            ]
        );
    }
}
