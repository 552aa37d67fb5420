//! Paths given on the command line that a run would write into, refused before the scene is
//! read when they cannot be used: a directory flag (`bake -o DIR`, `sweep --out DIR`,
//! `farm --out DIR`, a bake merge's `-o DIR`) naming a file, or any output path
//! (`render -o FILE`, `--stats-json FILE`, `convert -o FILE`) that is a directory or whose
//! directory runs through a file, takes no new file (read-only) or cannot be created
//! (`/proc/x`; [`super::writable`]). Missing directories are fine: the run creates them.
//! `--photon-cache DIR` may be a directory that is only read: only a file in its way is
//! refused.

use std::path::Path;

use super::writable::{dir_problem, file_problem, PathProblem};

/// Refuses `flag DIR` when `dir` or a directory above it is a file, or when nothing can be
/// written into it: the message (without `error: `) names the flag, the path and the
/// problem.
pub fn usable_dir(flag: &str, dir: &Path) -> Result<(), String> {
    match dir_problem(dir) {
        None => Ok(()),
        Some(PathProblem::ThroughFile(file)) => Err(through_file(flag, dir, &file)),
        Some(problem) => Err(problem.text(&format!("{flag} {}", dir.display()))),
    }
}

/// Refuses `flag DIR` for a directory a run may only read (`--photon-cache`): when `dir` or
/// a directory above it is a file.
pub fn usable_cache_dir(flag: &str, dir: &Path) -> Result<(), String> {
    match dir.ancestors().find(|a| a.is_file()) {
        None => Ok(()),
        Some(file) => Err(through_file(flag, dir, file)),
    }
}

fn through_file(flag: &str, dir: &Path, file: &Path) -> String {
    format!(
        "{flag} {}: {} is a file, not a directory\n  help: give a directory (it is created when missing)",
        dir.display(),
        file.display()
    )
}

/// Refuses `flag FILE` when `file` is a directory, a directory above it is a file, or its
/// directory cannot be written or created; `example` is a file name the help suggests
/// inside that directory (`scene.ron`).
pub fn usable_file(flag: &str, file: &Path, example: &str) -> Result<(), String> {
    match file_problem(file) {
        None => Ok(()),
        Some(PathProblem::IsADirectory) => Err(format!(
            "{flag} {} is a directory\n  help: give the file to write, e.g. {flag} {}",
            file.display(),
            file.join(example).display()
        )),
        Some(problem) => Err(problem.text(&format!("{flag} {}", file.display()))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_in_the_way_is_named() {
        let dir = std::env::temp_dir().join(format!("stagelight-dir-flags-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let plain = dir.join("plain");
        std::fs::write(&plain, b"x").unwrap();
        assert_eq!(usable_dir("-o", &dir.join("new/sub")), Ok(()));
        assert_eq!(usable_dir("-o", &dir), Ok(()));
        assert_eq!(
            usable_dir("--out", &plain),
            Err(format!(
                "--out {0}: {0} is a file, not a directory\n  help: give a directory (it is created when missing)",
                plain.display()
            ))
        );
        assert!(usable_dir("--out", &plain.join("a/b"))
            .unwrap_err()
            .starts_with(&format!(
                "--out {}/a/b: {} is a file",
                plain.display(),
                plain.display()
            )));
        assert_eq!(usable_file("-o", &dir.join("x.ron"), "s.ron"), Ok(()));
        assert_eq!(usable_file("-o", &plain, "s.ron"), Ok(()));
        assert_eq!(
            usable_file("-o", &dir, "s.ron"),
            Err(format!(
                "-o {} is a directory\n  help: give the file to write, e.g. -o {}",
                dir.display(),
                dir.join("s.ron").display()
            ))
        );
        assert!(usable_file("-o", &plain.join("x.ron"), "s.ron")
            .unwrap_err()
            .contains(&format!("{} is a file, not a directory", plain.display())));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
