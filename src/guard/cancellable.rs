//! Work the renderer cannot poll, made cancellable from the outside (issue 18, family 7).
//!
//! obvhs's BVH builder runs for seconds on large scenes and never looks at the run's cancel
//! flag. [`until_cancelled`] runs such a job on its own thread and waits for it, looking at
//! the flag every [`POLL`]; when the flag is set it stops waiting and returns `None`, so
//! the stage returns `Interrupted` at once and the process exits (which ends the abandoned
//! job). The job's result does not depend on the thread it runs on: the builder's parallel
//! parts use the same global pool either way, so bytes are unchanged.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

/// How often the waiting stage looks at the cancel flag.
pub const POLL: Duration = Duration::from_millis(10);

/// Stack of the job's thread: as large as a main thread's, so a deep recursion in the job
/// behaves as it did on the stage's thread.
const STACK_BYTES: usize = 64 << 20;

/// Runs `job` on a thread of its own and returns its result, or `Ok(None)` as soon as
/// `cancel` is set (the job is abandoned, its result dropped when it ends). A job that
/// panics re-raises the panic here, as if it had run on the calling thread. `Err` when no
/// thread could be started.
pub fn until_cancelled<T, F>(cancel: &AtomicBool, job: F) -> std::io::Result<Option<T>>
where
    T: Send + 'static,
    F: FnOnce() -> T + Send + 'static,
{
    if cancel.load(Ordering::Relaxed) {
        return Ok(None);
    }
    let (send, receive) = mpsc::channel();
    let handle = std::thread::Builder::new()
        .name("stagelight-job".into())
        .stack_size(STACK_BYTES)
        .spawn(move || {
            let _ = send.send(job());
        })?;
    loop {
        match receive.recv_timeout(POLL) {
            Ok(result) => return Ok(Some(result)),
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if cancel.load(Ordering::Relaxed) {
                    return Ok(None);
                }
            }
            // The job ended without sending: it panicked.
            Err(mpsc::RecvTimeoutError::Disconnected) => match handle.join() {
                Err(panic) => std::panic::resume_unwind(panic),
                Ok(()) => return Ok(None),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;
    use std::time::Instant;

    #[test]
    fn the_result_comes_back_when_not_cancelled() {
        let cancel = AtomicBool::new(false);
        assert_eq!(until_cancelled(&cancel, || 6 * 7).unwrap(), Some(42));
    }

    #[test]
    fn a_cancel_stops_the_wait_within_a_few_polls() {
        let cancel = Arc::new(AtomicBool::new(false));
        let setter = cancel.clone();
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(50));
            setter.store(true, Ordering::SeqCst);
        });
        let start = Instant::now();
        let got = until_cancelled(&cancel, || {
            std::thread::sleep(Duration::from_secs(5));
            1
        });
        assert_eq!(got.unwrap(), None);
        assert!(
            start.elapsed() < Duration::from_secs(2),
            "{:?}",
            start.elapsed()
        );
    }

    #[test]
    fn an_already_cancelled_run_starts_nothing() {
        let cancel = AtomicBool::new(true);
        let got = until_cancelled(&cancel, || -> u8 { panic!("must not run") });
        assert_eq!(got.unwrap(), None);
    }
}
