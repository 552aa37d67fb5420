//! Stopping on SIGINT and SIGTERM (issue 18, family 7).
//!
//! Both signals set the run's cancel flag, which stages poll between pixels, texels, photon
//! batches and inside each pixel's sample loop. Work the renderer cannot poll (obvhs's BVH
//! build, a long tessellation) is covered by a deadline: if the run has not stopped
//! [`GRACE`] after the signal, the process exits with status 130 itself. That is safe at any
//! point before the commit, because a run's files exist only in memory until then; during a
//! commit the exit waits for it to finish (or roll back), and a finished commit is
//! reported by the run as usual.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use crate::image_io::commit_state;
use crate::stage_error::{StageError, EXIT_INTERRUPTED};

/// How long a signalled run may take to stop by itself before the process exits.
pub const GRACE: Duration = Duration::from_millis(250);

/// Installs the SIGINT/SIGTERM handler for a run that polls `cancel`.
pub fn install(cancel: Arc<AtomicBool>) {
    let _ = ctrlc::set_handler(move || {
        cancel.store(true, Ordering::SeqCst);
        std::thread::sleep(GRACE);
        while commit_state::committing() {
            std::thread::sleep(Duration::from_millis(5));
        }
        if !commit_state::committed() {
            eprintln!("{}", StageError::Interrupted);
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
    });
}
