//! What a sweep writes before its result, and removing it when the sweep is interrupted
//! (SIGINT or SIGTERM: exit 130, no output file) or fails: the bake runs' textures in
//! `OUT/scratch/` (removed after every ending), and the reference it rendered and cached in
//! `OUT` and `OUT` itself when this sweep created them (removed when interrupted).
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
    /// The reference this sweep rendered and cached.
    reference: Mutex<Option<PathBuf>>,
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
            reference: Mutex::new(None),
            result: Mutex::new(false),
        }
    }

    /// The directory the bake runs write their textures into.
    pub fn scratch(&self) -> PathBuf {
        self.out.join("scratch")
    }

    /// Records the reference this sweep cached at `path`.
    pub fn cached_reference(&self, path: &Path) {
        if let Ok(mut r) = self.reference.lock() {
            *r = Some(path.to_path_buf());
        }
    }

    /// Removes the scratch directory.
    pub fn remove_scratch(&self) {
        let _ = std::fs::remove_dir_all(self.scratch());
    }

    /// Removes everything this sweep wrote: the scratch directory, the reference it cached,
    /// and the output directory when the sweep created it.
    pub fn remove_all(&self) {
        self.remove_scratch();
        if let Some(path) = self.reference.lock().ok().and_then(|r| r.clone()) {
            let _ = std::fs::remove_file(path);
        }
        if let Some(dir) = &self.created {
            let _ = std::fs::remove_dir_all(dir);
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

    #[test]
    fn only_what_the_sweep_made_is_removed() {
        let root =
            std::env::temp_dir().join(format!("stagelight-leftovers-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        std::fs::write(root.join("mine.txt"), b"x").unwrap();
        // An existing output directory stays, with what was there before.
        let files = SweepFiles::new(&root);
        std::fs::create_dir_all(files.scratch().join("0_0")).unwrap();
        std::fs::write(root.join("reference_1.exr"), b"r").unwrap();
        files.cached_reference(&root.join("reference_1.exr"));
        files.remove_all();
        let names: Vec<_> = std::fs::read_dir(&root)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names, ["mine.txt"]);
        // A created one goes, from its first created directory down.
        let files = SweepFiles::new(&root.join("new/out"));
        std::fs::create_dir_all(files.scratch()).unwrap();
        files.remove_all();
        assert!(!root.join("new").exists());
        std::fs::remove_dir_all(&root).unwrap();
    }
}
