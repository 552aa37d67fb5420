//! Stopping on SIGINT and SIGTERM (issue 18, family 7).
//!
//! Both signals set the run's cancel flag, which stages poll between pixels, texels, photon
//! batches and inside each pixel's sample loop. Work the renderer cannot poll (obvhs's BVH
//! build, a long tessellation) is covered by a deadline: if the run has not stopped
//! [`GRACE`] after the signal, the process exits with status 130 itself. That is safe at any
//! point before the commit, because a run's files exist only in memory until then; during a
//! commit the exit waits for it to finish (or roll back), and a finished commit is
//! reported by the run as usual.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use crate::image_io::commit_state;
use crate::stage_error::{StageError, EXIT_INTERRUPTED};

/// How long a signalled run may take to stop by itself before the process exits.
pub const GRACE: Duration = Duration::from_millis(250);

/// Installs the SIGINT/SIGTERM handler for a run that polls `cancel` and commits its files
/// once, at its end.
pub fn install(cancel: Arc<AtomicBool>) {
    install_with(cancel, commit_state::committed, || {});
}

/// Installs the SIGINT/SIGTERM handler for a run that polls `cancel` and may write files of
/// its own before its result (a sweep's scratch textures and cached reference): if the run
/// has not stopped [`GRACE`] after the signal, and once a commit under way has finished,
/// `finished` says whether the result is in place; if it is not, `clean_up` removes what the
/// run wrote and the process exits with status 130.
///
/// The handler is installed even where the signal was ignored when the process started (a
/// background job of a script, `cmd &`): every command that runs stages stops on SIGINT.
pub fn install_with(
    cancel: Arc<AtomicBool>,
    finished: impl Fn() -> bool + Send + 'static,
    clean_up: impl Fn() + Send + 'static,
) {
    let _ = ctrlc::set_handler(move || {
        cancel.store(true, Ordering::SeqCst);
        std::thread::sleep(GRACE);
        while commit_state::committing() {
            std::thread::sleep(Duration::from_millis(5));
        }
        if !finished() {
            clean_up();
            // Not `eprintln!`, which panics when standard error is closed.
            let _ = writeln!(std::io::stderr(), "{}", StageError::Interrupted);
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
    });
}
