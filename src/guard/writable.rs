//! Whether a run could write an output path, found before the first stage instead of at the
//! commit after the last one: the path is a directory, a directory on its way is a file, its
//! directory takes no new file (read-only), or a missing directory on its way cannot be
//! created (`/proc/x`). The directory is tried, not guessed from its mode bits (root writes
//! into a mode-555 directory; nobody creates one in `/proc`): a hidden file is created and
//! removed again in an existing directory, and a hidden directory beside the first missing
//! one (never that name itself, which a run started at the same time may be creating);
//! nothing stays.

use std::fs;
use std::path::{Path, PathBuf};

use crate::image_io::os_reason;

/// Why a path could not be written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PathProblem {
    /// The file to write is a directory.
    IsADirectory,
    /// This directory on the way is a file.
    ThroughFile(PathBuf),
    /// This existing directory takes no new file, for the given reason.
    CannotWriteInto(PathBuf, String),
    /// This missing directory on the way cannot be created, for the given reason.
    CannotCreate(PathBuf, String),
}

/// The help line for a directory that cannot be written or created.
pub const WRITE_HELP: &str =
    "give a path in a directory you can write (missing directories are created)";

impl PathProblem {
    /// What is wrong, after `subject` (`-o out/x.png`, `camera "cam" output 1 ("x.png")`),
    /// with its `help:` line.
    pub fn text(&self, subject: &str) -> String {
        match self {
            PathProblem::IsADirectory => format!(
                "{subject} is a directory\n  help: give the path of a file, not of a directory"
            ),
            PathProblem::ThroughFile(file) => format!(
                "{subject}: {} is a file, not a directory\n  help: give a path whose directories are directories (they are created when missing)",
                file.display()
            ),
            PathProblem::CannotWriteInto(dir, reason) => format!(
                "{subject}: cannot write into {}: {reason}\n  help: {WRITE_HELP}",
                dir.display()
            ),
            PathProblem::CannotCreate(dir, reason) => format!(
                "{subject}: cannot create the directory {}: {reason}\n  help: {WRITE_HELP}",
                dir.display()
            ),
        }
    }
}

/// Why the file `file` could not be written, or `None` when it can be.
pub fn file_problem(file: &Path) -> Option<PathProblem> {
    if file.is_dir() {
        return Some(PathProblem::IsADirectory);
    }
    let dir = file.parent().filter(|d| !d.as_os_str().is_empty());
    dir_problem(dir.unwrap_or(Path::new(".")))
}

/// Why files could not be written into the directory `dir` (created when missing), or
/// `None` when they can be.
pub fn dir_problem(dir: &Path) -> Option<PathProblem> {
    if let Some(file) = dir.ancestors().find(|a| a.is_file()) {
        return Some(PathProblem::ThroughFile(file.to_path_buf()));
    }
    // The first missing directory on the way, if any: its parent exists.
    let missing = dir
        .ancestors()
        .take_while(|a| !a.as_os_str().is_empty() && !a.is_dir())
        .last();
    match missing {
        None => try_file_in(dir)
            .err()
            .map(|reason| PathProblem::CannotWriteInto(dir.to_path_buf(), reason)),
        Some(first) => try_dir_in(first.parent().filter(|p| !p.as_os_str().is_empty()))
            .err()
            .map(|reason| PathProblem::CannotCreate(first.to_path_buf(), reason)),
    }
}

/// Creates and removes a hidden file in `dir`, named as a commit's temporary
/// (`.<name>.<pid>.tmp`), so that one a killed process left is cleared by the next commit.
fn try_file_in(dir: &Path) -> Result<(), String> {
    let probe = dir.join(probe_name());
    fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
        .map_err(|e| os_reason(&e))?;
    let _ = fs::remove_file(&probe);
    Ok(())
}

/// Creates and removes a hidden directory in `parent` (the working directory when `None`).
fn try_dir_in(parent: Option<&Path>) -> Result<(), String> {
    let probe = parent.unwrap_or(Path::new(".")).join(probe_name());
    fs::create_dir(&probe).map_err(|e| os_reason(&e))?;
    let _ = fs::remove_dir(&probe);
    Ok(())
}

/// This process's probe: `.stagelight-probe.<pid>.tmp`.
fn probe_name() -> String {
    format!(".stagelight-probe.{}.tmp", std::process::id())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn problems_are_found_and_nothing_is_left() {
        let dir = std::env::temp_dir().join(format!("stagelight-writable-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("sub")).unwrap();
        fs::write(dir.join("plain"), b"x").unwrap();
        assert_eq!(file_problem(&dir.join("a.png")), None);
        assert_eq!(file_problem(&dir.join("new/deeper/a.png")), None);
        assert_eq!(dir_problem(&dir.join("new/deeper")), None);
        assert_eq!(
            file_problem(&dir.join("sub")),
            Some(PathProblem::IsADirectory)
        );
        assert_eq!(
            file_problem(&dir.join("plain/a.png")),
            Some(PathProblem::ThroughFile(dir.join("plain")))
        );
        assert_eq!(
            dir_problem(Path::new("/proc/stagelight-x/y")),
            Some(PathProblem::CannotCreate(
                PathBuf::from("/proc/stagelight-x"),
                "no such file or directory".into()
            ))
        );
        let mut names: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["plain", "sub"]);
        fs::remove_dir_all(&dir).unwrap();
    }
}
