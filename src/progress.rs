//! Progress display: workers report finished rows through a crossbeam channel to one display
//! thread that owns the terminal progress bar, so the hot loops never touch the terminal.

use crossbeam::channel::{unbounded, Sender};
use std::thread::JoinHandle;

/// A running progress display (or a disabled one that ignores ticks).
pub struct Progress {
    sender: Option<Sender<u64>>,
    display: Option<JoinHandle<()>>,
}

/// A cheap, cloneable handle workers use to report finished work.
#[derive(Clone)]
pub struct ProgressTicker(Option<Sender<u64>>);

impl ProgressTicker {
    /// Reports `n` more items done.
    #[inline]
    pub fn tick(&self, n: u64) {
        if let Some(s) = &self.0 {
            // The display thread may already be gone when the run is cancelled.
            let _ = s.send(n);
        }
    }
}

impl Progress {
    /// Starts a progress bar on stderr for `total` items when `enabled`.
    pub fn start(enabled: bool, label: &str, unit: &str, total: u64) -> Self {
        if !enabled {
            return Self {
                sender: None,
                display: None,
            };
        }
        let (sender, receiver) = unbounded::<u64>();
        let template =
            format!("{label} [{{bar:40}}] {{pos}}/{{len}} {unit} {{elapsed_precise}} eta {{eta}}");
        let display = std::thread::spawn(move || {
            let bar = indicatif::ProgressBar::new(total);
            if let Ok(style) = indicatif::ProgressStyle::with_template(&template) {
                bar.set_style(style.progress_chars("=> "));
            }
            for n in receiver {
                bar.inc(n);
            }
            bar.finish_and_clear();
        });
        Self {
            sender: Some(sender),
            display: Some(display),
        }
    }

    /// A handle for workers.
    pub fn ticker(&self) -> ProgressTicker {
        ProgressTicker(self.sender.clone())
    }

    /// Closes the channel and waits for the display to clear its bar.
    pub fn finish(mut self) {
        self.sender = None;
        if let Some(d) = self.display.take() {
            let _ = d.join();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.sender = None;
        if let Some(d) = self.display.take() {
            let _ = d.join();
        }
    }
}
