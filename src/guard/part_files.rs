//! Part files are inputs of the merge (issue 18, family 5): no file a merge writes — its
//! `-o`, the render camera's outputs, a bake's textures and its `--write-gltf` copy — may be
//! one of the part files it reads, and `farm` checks the part files its array will write
//! against its merge job's outputs before it writes a script. Paths are compared as
//! [`super::outputs`] compares them ([`same_file_key`]).

use std::path::{Path, PathBuf};

use super::outputs::{refusal, same_file_key, Clash, Origin, PlannedOutput};

/// The part files of a merge.
pub enum PartFiles<'a> {
    /// The files given to `stagelight merge`.
    Given(&'a [PathBuf]),
    /// The files a farm's array writes into `dir` and its merge job reads: `part_K.exr`
    /// (a render) or `bake_part_K_of_N.exr` (a bake), K = 1 … `count`.
    Farm {
        /// The farm's `--out` directory.
        dir: &'a Path,
        /// Number of parts.
        count: u32,
        /// Bake parts instead of render parts.
        bake: bool,
    },
}

impl PartFiles<'_> {
    /// The part file (as the merge names it) and its part number K, when `key` (a
    /// [`same_file_key`]) is one; K is `None` for a file given to `merge`.
    fn find(&self, key: &Path) -> Option<(PathBuf, Option<u32>)> {
        match *self {
            PartFiles::Given(paths) => paths
                .iter()
                .find(|p| same_file_key(p) == key)
                .map(|p| (p.clone(), None)),
            PartFiles::Farm { dir, count, bake } => {
                let name = key.file_name()?.to_str()?;
                let k = if bake {
                    let tail = format!("_of_{count}.exr");
                    name.strip_prefix("bake_part_")?
                        .strip_suffix(tail.as_str())?
                } else {
                    name.strip_prefix("part_")?.strip_suffix(".exr")?
                };
                // The scripts write K in decimal without leading zeros.
                let k: u32 = k.parse().ok().filter(|n: &u32| n.to_string() == k)?;
                let file = if bake {
                    crate::farm::bake_part::part_file_name(k, count)
                } else {
                    format!("part_{k}.exr")
                };
                let part = dir.join(file);
                ((1..=count).contains(&k) && same_file_key(&part) == key).then_some((part, Some(k)))
            }
        }
    }

    /// How the help names the way out, for an output of `origin`.
    fn help(&self, origin: &Origin) -> &'static str {
        match (self, origin) {
            (PartFiles::Given(_), Origin::Flag(_)) => "write the merged output to a new file",
            (PartFiles::Given(_), Origin::Scene(..)) => {
                "keep the part files apart from the scene's outputs: render the parts into a directory of their own (`render --part K/N -o parts/part_K.exr`) and merge them from there"
            }
            (PartFiles::Farm { .. }, Origin::Flag(_)) => {
                "give -o a path apart from the part files in --out DIR"
            }
            (PartFiles::Farm { .. }, Origin::Scene(..)) => {
                "give --out a directory of its own for the part files, apart from the scene's outputs"
            }
        }
    }
}

/// Refuses every output in `outputs` that is one of the part files `parts`: located at the
/// scene element that names it, or a usage error of its flag.
pub fn clashes(parts: &PartFiles, outputs: &[PlannedOutput]) -> Vec<Clash> {
    let mut found = Vec::new();
    for out in outputs {
        let Some((part, k)) = parts.find(&same_file_key(&out.path)) else {
            continue;
        };
        let what = match (k, parts) {
            (Some(k), PartFiles::Farm { count, .. }) => format!(
                "the part file {} that part {k}/{count} writes and the merge job reads",
                part.display()
            ),
            _ => format!("the part file {} being merged", part.display()),
        };
        let described = match &out.origin {
            Origin::Flag(flag) => format!("{flag} {}", out.path.display()),
            Origin::Scene(_, element) => format!("{element} (\"{}\")", out.path.display()),
        };
        let text = format!(
            "{described} would overwrite {what}\n  help: {}",
            parts.help(&out.origin)
        );
        found.push(refusal(out, text));
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flagged(path: &str) -> PlannedOutput {
        PlannedOutput {
            path: path.into(),
            origin: Origin::Flag("-o"),
            surely_written: true,
        }
    }

    #[test]
    fn a_farm_part_file_is_found_by_its_number_only_within_the_count() {
        let dir = std::env::temp_dir().join("stagelight-part-files-test");
        let parts = PartFiles::Farm {
            dir: &dir,
            count: 3,
            bake: false,
        };
        let outputs: Vec<_> = ["part_2.exr", "part_4.exr", "part_02.exr", "part_3.png"]
            .iter()
            .map(|n| flagged(&dir.join(n).to_string_lossy()))
            .collect();
        let found = clashes(&parts, &outputs);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(
            found[0].text.contains("part 2/3 writes"),
            "{}",
            found[0].text
        );
        let bake = PartFiles::Farm {
            dir: &dir,
            count: 2,
            bake: true,
        };
        let outputs = [
            flagged(&dir.join("bake_part_1_of_2.exr").to_string_lossy()),
            flagged(&dir.join("bake_part_1_of_3.exr").to_string_lossy()),
        ];
        assert_eq!(clashes(&bake, &outputs).len(), 1);
    }
}
