//! All-or-nothing file output: a run's files are committed together or not at all.
//!
//! [`commit_all`] works in three steps, and says exactly what each failure leaves:
//!
//! 1. **Temporaries.** Every file is written and synced under a hidden temporary name in its
//!    destination directory, `.<name>.<pid>.tmp`. A failure here removes every temporary
//!    and touches no destination.
//! 2. **Renames.** Each destination that already exists (a file from an earlier run) is
//!    first renamed aside to `.<name>.<pid>.bak`; then the temporary is renamed into place.
//!    A failure here (a destination that is a directory, a vanished directory) undoes every
//!    rename made so far: new files are removed and the previous files are renamed back, so
//!    every destination holds exactly what it held before the run.
//! 3. **Clean-up.** Only after every file is in place are the `.bak` files removed.
//!
//! A process killed (SIGKILL, power loss) in step 1 or 2 leaves hidden `.tmp`/`.bak` files;
//! the next commit into the same directory removes those whose process is gone
//! ([`remove_stale`]), and a `.bak` whose destination is missing is renamed back first.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Whether a commit is under way or has finished in this process, for the signal handler
/// ([`crate::guard::interrupt`]): it must not end the process in the middle of a commit.
pub mod commit_state {
    use std::sync::atomic::{AtomicBool, Ordering};

    static COMMITTING: AtomicBool = AtomicBool::new(false);
    static COMMITTED: AtomicBool = AtomicBool::new(false);

    /// A commit is running.
    pub fn committing() -> bool {
        COMMITTING.load(Ordering::SeqCst)
    }

    /// A commit has put its files in place.
    pub fn committed() -> bool {
        COMMITTED.load(Ordering::SeqCst)
    }

    /// Marks a commit as running until the guard drops.
    pub(super) fn start() -> Guard {
        COMMITTING.store(true, Ordering::SeqCst);
        Guard
    }

    pub(super) fn done() {
        COMMITTED.store(true, Ordering::SeqCst);
    }

    /// Clears [`committing`] when dropped.
    pub(super) struct Guard;

    impl Drop for Guard {
        fn drop(&mut self) {
            COMMITTING.store(false, Ordering::SeqCst);
        }
    }
}

/// An encoded file waiting to be written.
#[derive(Debug, Clone)]
pub struct PendingFile {
    /// Final destination.
    pub path: PathBuf,
    /// Encoded bytes.
    pub bytes: Vec<u8>,
}

fn sibling(path: &Path, pid: u32, ext: &str) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{pid}.{ext}"))
}

fn temp_path(path: &Path) -> PathBuf {
    sibling(path, std::process::id(), "tmp")
}

fn backup_path(path: &Path) -> PathBuf {
    sibling(path, std::process::id(), "bak")
}

/// `.<name>.<pid>.tmp` or `.<name>.<pid>.bak` → (`name`, pid, is backup).
fn parse_leftover(file_name: &str) -> Option<(&str, u32, bool)> {
    let rest = file_name.strip_prefix('.')?;
    let (rest, backup) = if let Some(r) = rest.strip_suffix(".tmp") {
        (r, false)
    } else {
        (rest.strip_suffix(".bak")?, true)
    };
    let (name, pid) = rest.rsplit_once('.')?;
    if name.is_empty() || pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some((name, pid.parse().ok()?, backup))
}

/// Whether process `pid` is running (Linux: `/proc/<pid>` exists). Where that cannot be
/// told, every process counts as running, so nothing is removed.
fn process_alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc_root = Path::new("/proc");
    if !proc_root.join("self").exists() {
        return true;
    }
    proc_root.join(pid.to_string()).exists()
}

/// Removes the leftovers of dead stagelight processes in `dir`: `.<name>.<pid>.tmp` files,
/// and `.<name>.<pid>.bak` files (renamed back to `name` when that is missing, since then
/// the process died between moving the old file aside and putting the new one in place).
/// Returns the paths removed or restored.
pub fn remove_stale(dir: &Path) -> Vec<PathBuf> {
    let mut done = Vec::new();
    let Ok(entries) = fs::read_dir(dir) else {
        return done;
    };
    for entry in entries.filter_map(Result::ok) {
        let file_name = entry.file_name();
        let Some(file_name) = file_name.to_str() else {
            continue;
        };
        let Some((name, pid, backup)) = parse_leftover(file_name) else {
            continue;
        };
        if process_alive(pid) || !entry.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        let path = entry.path();
        let original = dir.join(name);
        let ok = if backup && !original.exists() {
            fs::rename(&path, &original).is_ok()
        } else {
            fs::remove_file(&path).is_ok()
        };
        if ok {
            done.push(path);
        }
    }
    done
}

/// The error of making the directories of an output: where a file stands in the way (the
/// system's "File exists" or "Not a directory"), it names that file; else it names the
/// directory and the system's reason (`/proc/x` cannot be created: not "file not found").
fn not_a_directory(dir: &Path, e: std::io::Error) -> std::io::Error {
    let Some(blocker) = dir.ancestors().find(|a| a.is_file()) else {
        return std::io::Error::other(format!(
            "cannot create the directory {}: {}",
            dir.display(),
            os_reason(&e)
        ));
    };
    std::io::Error::new(
        std::io::ErrorKind::NotADirectory,
        format!("{} is a file, not a directory", blocker.display()),
    )
}

/// The system's reason for `e`, as a sentence fragment (`permission denied`, `no such file
/// or directory`, `read-only file system`), without its error number.
pub fn os_reason(e: &std::io::Error) -> String {
    let text = e.to_string();
    let text = text.split(" (os error").next().unwrap_or(&text);
    let mut chars = text.chars();
    match chars.next() {
        Some(first) => first.to_lowercase().chain(chars).collect(),
        None => text.to_string(),
    }
}

/// Writes every file to a temporary sibling, then renames all into place: either every
/// destination holds its new file, or every destination is as it was before (see the module
/// documentation for the exact steps). Leftovers of dead processes in the destination
/// directories are removed first.
pub fn commit_all(files: &[PendingFile]) -> Result<Vec<PathBuf>, (PathBuf, std::io::Error)> {
    let _running = commit_state::start();
    let mut dirs: Vec<PathBuf> = Vec::new();
    for f in files {
        let dir = f
            .path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .to_path_buf();
        if !dirs.contains(&dir) {
            remove_stale(&dir);
            dirs.push(dir);
        }
    }
    let mut temps = Vec::with_capacity(files.len());
    for f in files {
        let tmp = temp_path(&f.path);
        let result = (|| {
            if let Some(dir) = f.path.parent().filter(|d| !d.as_os_str().is_empty()) {
                fs::create_dir_all(dir).map_err(|e| not_a_directory(dir, e))?;
            }
            if f.path.is_dir() {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::IsADirectory,
                    "is a directory",
                ));
            }
            let mut file = fs::File::create(&tmp)?;
            file.write_all(&f.bytes)?;
            file.sync_all()
        })();
        if let Err(e) = result {
            let _ = fs::remove_file(&tmp);
            for t in &temps {
                let _ = fs::remove_file(t);
            }
            return Err((f.path.clone(), e));
        }
        temps.push(tmp);
    }
    // (destination, backup of its previous file if there was one), in rename order.
    let mut placed: Vec<(PathBuf, Option<PathBuf>)> = Vec::with_capacity(files.len());
    for (f, tmp) in files.iter().zip(&temps) {
        let result = (|| {
            let backup = if f.path.is_file() {
                let b = backup_path(&f.path);
                fs::rename(&f.path, &b)?;
                Some(b)
            } else {
                None
            };
            let renamed = fs::rename(tmp, &f.path);
            if let Err(e) = renamed {
                if let Some(b) = &backup {
                    let _ = fs::rename(b, &f.path);
                }
                return Err(e);
            }
            Ok(backup)
        })();
        match result {
            Ok(backup) => placed.push((f.path.clone(), backup)),
            Err(e) => {
                for (dest, backup) in placed.iter().rev() {
                    match backup {
                        Some(b) => {
                            let _ = fs::rename(b, dest);
                        }
                        None => {
                            let _ = fs::remove_file(dest);
                        }
                    }
                }
                for t in &temps {
                    let _ = fs::remove_file(t);
                }
                return Err((f.path.clone(), e));
            }
        }
    }
    commit_state::done();
    for (_, backup) in &placed {
        if let Some(b) = backup {
            let _ = fs::remove_file(b);
        }
    }
    Ok(placed.into_iter().map(|(dest, _)| dest).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("stagelight-atomic-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_files_and_leaves_no_temporaries() {
        let dir = scratch("ok");
        let files = vec![
            PendingFile {
                path: dir.join("a.bin"),
                bytes: vec![1, 2, 3],
            },
            PendingFile {
                path: dir.join("sub/b.bin"),
                bytes: vec![4],
            },
        ];
        commit_all(&files).unwrap();
        assert_eq!(fs::read(dir.join("a.bin")).unwrap(), vec![1, 2, 3]);
        assert_eq!(fs::read(dir.join("sub/b.bin")).unwrap(), vec![4]);
        assert_eq!(names(&dir), vec!["a.bin", "sub"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failing_second_file_leaves_the_first_as_it_was() {
        let dir = scratch("rollback");
        fs::write(dir.join("old.bin"), b"previous").unwrap();
        fs::create_dir_all(dir.join("taken.bin")).unwrap();
        let files = vec![
            PendingFile {
                path: dir.join("new.bin"),
                bytes: vec![1],
            },
            PendingFile {
                path: dir.join("old.bin"),
                bytes: vec![2],
            },
            PendingFile {
                path: dir.join("taken.bin"),
                bytes: vec![3],
            },
        ];
        let (path, _) = commit_all(&files).unwrap_err();
        assert_eq!(path, dir.join("taken.bin"));
        assert_eq!(names(&dir), vec!["old.bin", "taken.bin"]);
        assert_eq!(fs::read(dir.join("old.bin")).unwrap(), b"previous");
        fs::remove_dir_all(&dir).unwrap();
    }

    /// An output whose directory path runs through a file names that file (the system said
    /// "File exists (os error 17)" or "Not a directory (os error 20)").
    #[test]
    fn a_directory_that_cannot_be_created_is_named_with_the_reason() {
        let files = [PendingFile {
            path: PathBuf::from("/proc/stagelight-no-dir/a.png"),
            bytes: b"a".to_vec(),
        }];
        let (path, e) = commit_all(&files).unwrap_err();
        assert_eq!(path, files[0].path);
        assert_eq!(
            e.to_string(),
            "cannot create the directory /proc/stagelight-no-dir: no such file or directory"
        );
    }

    #[test]
    fn a_file_in_the_directory_path_is_named() {
        let dir = scratch("file_in_path");
        fs::write(dir.join("plain"), b"x").unwrap();
        for path in ["plain/a.bin", "plain/sub/a.bin"] {
            let files = vec![PendingFile {
                path: dir.join(path),
                bytes: vec![1],
            }];
            let (_, e) = commit_all(&files).unwrap_err();
            assert_eq!(
                e.to_string(),
                format!("{} is a file, not a directory", dir.join("plain").display())
            );
        }
        assert_eq!(fs::read(dir.join("plain")).unwrap(), b"x");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn leftovers_of_dead_processes_are_removed_and_live_ones_kept() {
        let dir = scratch("stale");
        // No Linux pid reaches 4,999,999 (the kernel's limit is 4,194,304).
        fs::write(dir.join(".out.png.4999999.tmp"), b"x").unwrap();
        fs::write(dir.join(".kept.png.4999999.bak"), b"old").unwrap();
        let mine = format!(".mine.png.{}.tmp", std::process::id());
        fs::write(dir.join(&mine), b"x").unwrap();
        fs::write(dir.join(".hidden.tmp"), b"x").unwrap();
        remove_stale(&dir);
        assert_eq!(
            names(&dir),
            vec![".hidden.tmp".to_string(), mine, "kept.png".into()]
        );
        assert_eq!(fs::read(dir.join("kept.png")).unwrap(), b"old");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn leftover_names_parse() {
        assert_eq!(parse_leftover(".a.png.12.tmp"), Some(("a.png", 12, false)));
        assert_eq!(parse_leftover(".a.png.12.bak"), Some(("a.png", 12, true)));
        assert_eq!(parse_leftover(".a.png.x12.tmp"), None);
        assert_eq!(parse_leftover("a.png.12.tmp"), None);
        assert_eq!(parse_leftover("..12.tmp"), None);
    }
}
