//! Where the integration tests write: one directory per test process,
//! `$TMPDIR/stagelight-it-<pid>/`, removed when the process exits, so that a `cargo test` run
//! leaves nothing behind in the temporary directory (it left about a hundred directories,
//! 200 MB, per run before). The directory is kept when a test panicked (to look at its
//! files) or when `STAGELIGHT_KEEP_TEST_DIRS` is set. Directories of test processes that no
//! longer run (killed before they could exit) are removed when the next run starts.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

/// The name of every root: this prefix and the process id.
const PREFIX: &str = "stagelight-it-";

static ROOT: OnceLock<PathBuf> = OnceLock::new();
static A_TEST_PANICKED: AtomicBool = AtomicBool::new(false);

extern "C" {
    /// The C library's exit hook (`atexit(3)`): the test harness returns from `main` or
    /// calls `exit` when every test is done, and both run the hooks.
    fn atexit(callback: extern "C" fn()) -> std::os::raw::c_int;
}

/// This process's scratch root, made (empty) on first use.
pub fn scratch_root() -> &'static Path {
    ROOT.get_or_init(|| {
        let tmp = std::env::temp_dir();
        remove_roots_of_finished_runs(&tmp);
        let root = tmp.join(format!("{PREFIX}{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).expect("create the tests' scratch directory");
        let default_hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            A_TEST_PANICKED.store(true, Ordering::SeqCst);
            default_hook(info);
        }));
        // SAFETY: registers a plain `extern "C"` function, which runs once, at exit, and
        // neither panics nor unwinds.
        unsafe { atexit(remove_root) };
        root
    })
}

/// The exit hook: removes the root unless a test panicked or the caller asked to keep it.
extern "C" fn remove_root() {
    let keep = A_TEST_PANICKED.load(Ordering::SeqCst)
        || std::env::var_os("STAGELIGHT_KEEP_TEST_DIRS").is_some();
    if let (false, Some(root)) = (keep, ROOT.get()) {
        let _ = std::fs::remove_dir_all(root);
    }
}

/// Removes the roots left by test processes that are gone (Linux: no `/proc/<pid>`);
/// elsewhere nothing is removed.
fn remove_roots_of_finished_runs(tmp: &Path) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(tmp) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name
            .to_str()
            .and_then(|n| n.strip_prefix(PREFIX))
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}
