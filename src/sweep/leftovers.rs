//! What a sweep writes before its result, and what is removed when the sweep is interrupted
//! (SIGINT or SIGTERM: exit 130, no output file) or fails: the bake runs' textures in
//! `OUT/scratch/` (the partial outputs of the runs, removed after every ending) and `OUT`
//! itself when this sweep created it and nothing else is in it.
//!
//! The reference a sweep rendered is expensive and complete once committed (written to a
//! temporary and renamed; the interrupt handler waits for a commit under way), so it is
//! kept, with its directory, whatever ends the sweep: the next sweep of the same scene and
//! reference settings reads it instead of rendering it again (its name is their hash,
//! `runner::reference_cache`).
//!
//! The result (`sweep.csv`, `sweep.json`, `sweep.svg`) is committed through
//! [`SweepFiles::commit_result`], which the interrupt handler waits for: once it is in
//! place the sweep ends as a finished one.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use crate::image_io::{commit_all, PendingFile};

/// The files and directories one sweep made, shared with its interrupt handler.
#[derive(Debug)]
pub struct SweepFiles {
    /// The output directory.
    out: PathBuf,
    /// The first directory of `out`'s path that was missing when the sweep started.
    created: Option<PathBuf>,
    /// Whether the result is in place; held while it is committed.
    result: Mutex<bool>,
}

impl SweepFiles {
    /// Notes, before anything is written, which directories of `out` exist.
    pub fn new(out: &Path) -> Self {
        let created = out
            .ancestors()
            .take_while(|a| !a.as_os_str().is_empty() && !a.exists())
            .last()
            .map(Path::to_path_buf);
        Self {
            out: out.to_path_buf(),
            created,
            result: Mutex::new(false),
        }
    }

    /// The directory the bake runs write their textures into.
    pub fn scratch(&self) -> PathBuf {
        self.out.join("scratch")
    }

    /// Removes the scratch directory.
    pub fn remove_scratch(&self) {
        let _ = std::fs::remove_dir_all(self.scratch());
    }

    /// Removes what an interrupted sweep leaves unfinished: the scratch directory, and the
    /// directories of `out` this sweep created, from `out` up, as long as they are empty. A
    /// reference it cached there is complete, so it stays, and so does its directory.
    pub fn remove_partial(&self) {
        self.remove_scratch();
        let Some(created) = &self.created else {
            return;
        };
        for dir in self.out.ancestors() {
            // `remove_dir` removes only an empty directory.
            if std::fs::remove_dir(dir).is_err() || dir == created {
                break;
            }
        }
    }

    /// Commits the result files together; the interrupt handler waits for it.
    pub fn commit_result(&self, files: &[PendingFile]) -> Result<(), (PathBuf, std::io::Error)> {
        let mut in_place = self.result.lock().unwrap_or_else(|e| e.into_inner());
        commit_all(files)?;
        *in_place = true;
        Ok(())
    }

    /// Whether the result is in place (waiting for a commit under way).
    pub fn result_in_place(&self) -> bool {
        *self.result.lock().unwrap_or_else(|e| e.into_inner())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn scratch_and_empty_created_directories_go_and_a_cached_reference_stays() {
        let root =
            std::env::temp_dir().join(format!("stagelight-leftovers-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        std::fs::write(root.join("mine.txt"), b"x").unwrap();
        // An existing output directory stays, with what was there before and the reference.
        let files = SweepFiles::new(&root);
        std::fs::create_dir_all(files.scratch().join("0_0")).unwrap();
        std::fs::write(root.join("reference_1.exr"), b"r").unwrap();
        files.remove_partial();
        assert_eq!(names(&root), ["mine.txt", "reference_1.exr"]);
        // A created one goes, from its first created directory down, when it is empty.
        let files = SweepFiles::new(&root.join("new/out"));
        std::fs::create_dir_all(files.scratch()).unwrap();
        files.remove_partial();
        assert!(!root.join("new").exists());
        // A created one that holds a cached reference stays, with the reference alone.
        let files = SweepFiles::new(&root.join("kept/out"));
        std::fs::create_dir_all(files.scratch()).unwrap();
        std::fs::write(root.join("kept/out/reference_2.exr"), b"r").unwrap();
        files.remove_partial();
        assert_eq!(names(&root.join("kept/out")), ["reference_2.exr"]);
        std::fs::remove_dir_all(&root).unwrap();
    }
}
