//! Process CPU time (user + system, all threads), for the stage report's per-CPU-second
//! rates: on a shared machine wall-clock rates swing with the load, CPU-time rates much less.

/// CPU seconds this process has used so far, all threads; `None` where the platform has no
/// process CPU clock.
pub fn process_cpu_seconds() -> Option<f64> {
    #[cfg(unix)]
    {
        use nix::time::{clock_gettime, ClockId};
        clock_gettime(ClockId::CLOCK_PROCESS_CPUTIME_ID)
            .ok()
            .map(|t| t.tv_sec() as f64 + t.tv_nsec() as f64 * 1e-9)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_time_advances_with_work_and_never_goes_back() {
        let Some(t0) = process_cpu_seconds() else {
            return;
        };
        // Busy work the optimiser cannot remove.
        let mut x = 1u64;
        let start = std::time::Instant::now();
        while start.elapsed().as_secs_f64() < 0.05 {
            for i in 0..10_000u64 {
                x = std::hint::black_box(x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(i));
            }
        }
        let t1 = process_cpu_seconds().unwrap();
        // 50 ms of wall time spent computing on this thread: at least a few ms of CPU.
        assert!(t1 - t0 > 0.005, "cpu {t0} -> {t1}");
        assert!(process_cpu_seconds().unwrap() >= t1);
    }
}
