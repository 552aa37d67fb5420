//! All-or-nothing file output: a run's files are committed together or not at all.
//!
//! [`commit_all`] works in three steps, and says exactly what each failure leaves:
//!
//! 1. **Temporaries.** Every file is written and synced under a hidden temporary name in its
//!    destination directory, `.<name>.<n>.<pid>.tmp` (`n` counts this process's
//!    temporaries, so threads committing the same file do not share one). A failure here
//!    removes every temporary and touches no destination.
//! 2. **Renames.** Each destination that already exists (a file from an earlier run) is
//!    first renamed aside to `.<name>.<pid>.bak`; then the temporary is renamed into place.
//!    A failure here (a destination that is a directory, a vanished directory) undoes every
//!    rename made so far: new files are removed and the previous files are renamed back, so
//!    every destination holds exactly what it held before the run. **Shared** files
//!    ([`PendingFile::shared`]: photon map files, which other processes may write at the same
//!    moment) come after every other file, each by one rename of its temporary over the
//!    destination: a reader sees the previous complete file or the new one, never a gap or
//!    a partial file, and any number of processes writing the same file all succeed (the
//!    last rename stays). A shared file that cannot be renamed undoes the other files as
//!    above; a shared file renamed before it in the same commit stays (it is complete, and
//!    another process may have written it too).
//! 3. **Clean-up.** Only after every file is in place are the `.bak` files removed.
//!
//! A process killed (SIGKILL, power loss) in step 1 or 2 leaves hidden `.tmp`/`.bak` files;
//! the next commit into the same directory removes those whose process is gone
//! ([`remove_stale`]), and a `.bak` whose destination is missing is renamed back first.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

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
    /// Replaced by one rename, after the other files, rather than moved aside and restored
    /// on failure (see the module documentation): a cache file that other processes may
    /// write at the same time and whose every complete version is valid to its readers.
    pub shared: bool,
}

impl PendingFile {
    /// A file of the run: in place with the others, or the previous file kept.
    pub fn new(path: PathBuf, bytes: Vec<u8>) -> Self {
        Self {
            path,
            bytes,
            shared: false,
        }
    }

    /// A cache file that concurrent runs may write too (a photon map file: farm parts share
    /// `--photon-cache DIR/<hash>.pmap`, and a reader checks the hash inside).
    pub fn shared(path: PathBuf, bytes: Vec<u8>) -> Self {
        Self {
            path,
            bytes,
            shared: true,
        }
    }
}

fn sibling(path: &Path, pid: u32, ext: &str) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{pid}.{ext}"))
}

/// `.<name>.<n>.<pid>.tmp`, `n` new on every call: unique among this process's threads too
/// (a leftover's `name` reads as `<name>.<n>`, which is only removed).
fn temp_path(path: &Path) -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{n}.{}.tmp", std::process::id()))
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

/// Removes the leftovers of dead stagelight processes in `dir`: `.<name>.<n>.<pid>.tmp` files
/// (`.<name>.<pid>.tmp` from earlier releases), and `.<name>.<pid>.bak` files (renamed back
/// to `name` when that is missing, since then the process died between moving the old file
/// aside and putting the new one in place).
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
    let pairs = || files.iter().zip(&temps);
    let own = pairs().filter(|(f, _)| !f.shared);
    let shared = pairs().filter(|(f, _)| f.shared);
    for (f, tmp) in own.chain(shared) {
        let result = if f.shared {
            fs::rename(tmp, &f.path).map(|()| None)
        } else {
            replace_keeping_backup(tmp, &f.path)
        };
        match result {
            Ok(backup) if !f.shared => placed.push((f.path.clone(), backup)),
            Ok(_) => {}
            Err(e) => {
                undo(&placed);
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
    Ok(files.iter().map(|f| f.path.clone()).collect())
}

/// Moves the file at `dest` (if any) aside to its `.bak`, then renames `tmp` into place;
/// a failing rename puts the previous file back. Returns the `.bak`.
fn replace_keeping_backup(tmp: &Path, dest: &Path) -> std::io::Result<Option<PathBuf>> {
    let backup = if dest.is_file() {
        let b = backup_path(dest);
        fs::rename(dest, &b)?;
        Some(b)
    } else {
        None
    };
    if let Err(e) = fs::rename(tmp, dest) {
        if let Some(b) = &backup {
            let _ = fs::rename(b, dest);
        }
        return Err(e);
    }
    Ok(backup)
}

/// Undoes the renames of `placed` (latest first): a new file is removed, a previous one
/// renamed back from its `.bak`.
fn undo(placed: &[(PathBuf, Option<PathBuf>)]) {
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
            PendingFile::new(dir.join("a.bin"), vec![1, 2, 3]),
            PendingFile::new(dir.join("sub/b.bin"), vec![4]),
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
            PendingFile::new(dir.join("new.bin"), vec![1]),
            PendingFile::new(dir.join("old.bin"), vec![2]),
            PendingFile::new(dir.join("taken.bin"), vec![3]),
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
        let files = [PendingFile::new(
            PathBuf::from("/proc/stagelight-no-dir/a.png"),
            b"a".to_vec(),
        )];
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
            let files = vec![PendingFile::new(dir.join(path), vec![1])];
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

    /// Eight writers at once, forty rounds: each commits its own output and the same shared
    /// cache file (identical bytes, as content-addressed entries are). Every commit
    /// succeeds, and a reader that polls the cache file meanwhile only ever finds it whole:
    /// never missing (it existed before the first round) and never part-written. Moving
    /// the file aside first, as an ordinary output is, made a second writer's rename fail
    /// with "file not found" and left a moment with no file.
    #[test]
    fn concurrent_commits_of_one_shared_file_all_succeed_and_it_stays_whole() {
        use std::sync::atomic::AtomicBool;
        use std::sync::{Arc, Barrier};
        const WRITERS: usize = 8;
        const ROUNDS: usize = 40;
        let dir = scratch("shared");
        let cache = dir.join("cache/e904a1777226d411.pmap");
        let bytes: Vec<u8> = (0..256 * 1024).map(|i| (i * 7 % 251) as u8).collect();
        commit_all(&[PendingFile::shared(cache.clone(), bytes.clone())]).unwrap();
        let barrier = Arc::new(Barrier::new(WRITERS));
        let stop = Arc::new(AtomicBool::new(false));
        let reader = {
            let (cache, bytes, stop) = (cache.clone(), bytes.clone(), stop.clone());
            std::thread::spawn(move || {
                let mut reads = 0u32;
                while !stop.load(Ordering::SeqCst) {
                    let read = fs::read(&cache).map_err(|e| e.to_string());
                    assert!(
                        read.as_ref() == Ok(&bytes),
                        "read {:?}",
                        read.map(|b| b.len())
                    );
                    reads += 1;
                }
                reads
            })
        };
        let writers: Vec<_> = (0..WRITERS)
            .map(|k| {
                let (dir, cache, bytes, barrier) =
                    (dir.clone(), cache.clone(), bytes.clone(), barrier.clone());
                std::thread::spawn(move || {
                    let mut failures = Vec::new();
                    for round in 0..ROUNDS {
                        let files = [
                            PendingFile::new(dir.join(format!("p{k}.exr")), vec![k as u8; 64]),
                            PendingFile::shared(cache.clone(), bytes.clone()),
                        ];
                        barrier.wait();
                        if let Err((p, e)) = commit_all(&files) {
                            failures
                                .push(format!("writer {k}, round {round}: {}: {e}", p.display()));
                        }
                    }
                    failures
                })
            })
            .collect();
        let failures: Vec<String> = writers
            .into_iter()
            .flat_map(|w| w.join().unwrap())
            .collect();
        stop.store(true, Ordering::SeqCst);
        let reads = reader.join().expect("the reader saw the cache file whole");
        assert_eq!(failures, Vec::<String>::new(), "every commit succeeds");
        assert!(reads > 0);
        assert_eq!(fs::read(&cache).unwrap(), bytes);
        assert_eq!(names(&dir.join("cache")), vec!["e904a1777226d411.pmap"]);
        for k in 0..WRITERS {
            assert_eq!(
                fs::read(dir.join(format!("p{k}.exr"))).unwrap(),
                vec![k as u8; 64]
            );
        }
        fs::remove_dir_all(&dir).unwrap();
    }

    /// A shared file is renamed after the other files: when one of those fails, the shared
    /// file still holds what it held (here, listed first, it would have been in place).
    #[test]
    fn a_failing_output_leaves_a_shared_file_as_it_was() {
        let dir = scratch("shared_rollback");
        fs::write(dir.join("maps.pmap"), b"previous maps").unwrap();
        fs::write(dir.join("old.exr"), b"previous image").unwrap();
        fs::create_dir_all(dir.join("taken.exr")).unwrap();
        fs::write(dir.join("taken.exr/x"), b"x").unwrap();
        let files = vec![
            PendingFile::shared(dir.join("maps.pmap"), b"new maps".to_vec()),
            PendingFile::new(dir.join("old.exr"), b"new image".to_vec()),
            PendingFile::new(dir.join("taken.exr"), b"y".to_vec()),
        ];
        let (path, _) = commit_all(&files).unwrap_err();
        assert_eq!(path, dir.join("taken.exr"));
        assert_eq!(names(&dir), vec!["maps.pmap", "old.exr", "taken.exr"]);
        assert_eq!(fs::read(dir.join("maps.pmap")).unwrap(), b"previous maps");
        assert_eq!(fs::read(dir.join("old.exr")).unwrap(), b"previous image");
        let placed = commit_all(&files[..2]).unwrap();
        assert_eq!(placed, vec![dir.join("maps.pmap"), dir.join("old.exr")]);
        assert_eq!(fs::read(dir.join("maps.pmap")).unwrap(), b"new maps");
        assert_eq!(names(&dir), vec!["maps.pmap", "old.exr", "taken.exr"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn temporaries_are_unique_and_read_as_leftovers_of_this_process() {
        let (a, b) = (
            temp_path(Path::new("d/a.pmap")),
            temp_path(Path::new("d/a.pmap")),
        );
        assert_ne!(a, b);
        let name = a.file_name().unwrap().to_str().unwrap();
        let (stem, pid, backup) = parse_leftover(name).unwrap();
        assert!(stem.starts_with("a.pmap."), "{stem}");
        assert_eq!((pid, backup), (std::process::id(), false));
    }

    #[test]
    fn leftover_names_parse() {
        assert_eq!(parse_leftover(".a.png.12.tmp"), Some(("a.png", 12, false)));
        assert_eq!(
            parse_leftover(".a.png.3.12.tmp"),
            Some(("a.png.3", 12, false))
        );
        assert_eq!(parse_leftover(".a.png.12.bak"), Some(("a.png", 12, true)));
        assert_eq!(parse_leftover(".a.png.x12.tmp"), None);
        assert_eq!(parse_leftover("a.png.12.tmp"), None);
        assert_eq!(parse_leftover("..12.tmp"), None);
    }
}
