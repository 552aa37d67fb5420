//! The run report: what the stage runner recorded for each stage (ran or skipped, why, wall
//! time, work items, rays) and the files the run wrote, with its `--stats` and `bench`
//! tables. Only the runner (`crate::schedule`) writes it.

use std::path::PathBuf;

use serde::Serialize;

/// What the runner recorded for one stage.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageReport {
    /// Stage name.
    pub stage: &'static str,
    /// Whether it ran.
    pub ran: bool,
    /// Why it ran or was skipped.
    pub reason: String,
    /// Wall time of the stage body (0 when skipped).
    pub seconds: f64,
    /// Items processed.
    pub items: u64,
    /// Unit of `items`.
    pub unit: &'static str,
    /// Items per second (0 when skipped).
    pub items_per_second: f64,
    /// Items per second per worker thread.
    pub items_per_second_per_thread: f64,
    /// Closest-hit rays the stage traced (counted by the accelerator).
    pub rays_closest: u64,
    /// Occlusion (shadow, AO) rays the stage traced.
    pub rays_occlusion: u64,
    /// All rays the stage traced (`rays_closest + rays_occlusion`).
    pub rays: u64,
    /// Rays per second (0 when the stage traced none).
    pub rays_per_second: f64,
    /// Rays per second per worker thread (0 when the stage traced none).
    pub rays_per_second_per_thread: f64,
    /// Process CPU seconds (user + system, all threads) the stage body used; 0 when skipped
    /// or where the platform has no process CPU clock.
    pub cpu_seconds: f64,
    /// Items per CPU second (0 when `cpu_seconds` is 0): what one fully busy thread does, much
    /// less sensitive than the wall-clock rates to other work on the machine.
    pub items_per_cpu_second: f64,
    /// Rays per CPU second (0 when the stage traced none or `cpu_seconds` is 0).
    pub rays_per_cpu_second: f64,
    /// Files the stage wrote.
    pub files: Vec<PathBuf>,
    /// True when the stage's items were done by the parts a `merge` reads, in their own
    /// runs: no item rate is known (`items_per_second` 0; the `--stats` table says `n/a`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub merged_parts: bool,
}

impl StageReport {
    /// The entry of a stage that did not run.
    pub fn skipped(stage: &'static str, reason: String) -> Self {
        Self {
            stage,
            ran: false,
            reason,
            seconds: 0.0,
            items: 0,
            unit: "",
            items_per_second: 0.0,
            items_per_second_per_thread: 0.0,
            rays_closest: 0,
            rays_occlusion: 0,
            rays: 0,
            rays_per_second: 0.0,
            rays_per_second_per_thread: 0.0,
            cpu_seconds: 0.0,
            items_per_cpu_second: 0.0,
            rays_per_cpu_second: 0.0,
            files: Vec::new(),
            merged_parts: false,
        }
    }
}

/// The whole run's report.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RunReport {
    /// Worker threads used.
    pub threads: usize,
    /// One entry per stage of the table, in order.
    pub stages: Vec<StageReport>,
    /// Wall time of the whole schedule.
    pub total_seconds: f64,
    /// Every file the run wrote, in stage order (collected by the runner from each stage's
    /// `Work`).
    pub written: Vec<PathBuf>,
}

impl RunReport {
    /// The entry for a stage, if it is in the table.
    pub fn stage(&self, name: &str) -> Option<&StageReport> {
        self.stages.iter().find(|s| s.stage == name)
    }

    /// A fixed-width table for `--stats`.
    pub fn to_table(&self) -> String {
        let mut out = String::new();
        out.push_str(&format!(
            "{:<16} {:<4} {:>9} {:>12} {:<10} {:>14} {:>12}  reason\n",
            "stage", "ran", "seconds", "items", "unit", "items/s", "rays"
        ));
        for s in &self.stages {
            let rate = if s.merged_parts {
                "n/a".to_string()
            } else {
                format!("{:.0}", s.items_per_second)
            };
            out.push_str(&format!(
                "{:<16} {:<4} {:>9.4} {:>12} {:<10} {:>14} {:>12}  {}\n",
                s.stage,
                if s.ran { "yes" } else { "no" },
                s.seconds,
                s.items,
                s.unit,
                rate,
                s.rays,
                s.reason
            ));
        }
        out.push_str(&format!(
            "total {:.4} s on {} thread(s)\n",
            self.total_seconds, self.threads
        ));
        out
    }
}

impl RunReport {
    /// A throughput table for `stagelight bench`: items, seconds, items/s and items/s per
    /// thread for every stage that ran; skipped stages with their reason.
    pub fn to_throughput_table(&self) -> String {
        let mut out = format!(
            "{:<16} {:>12} {:<10} {:>10} {:>14} {:>16} {:>12} {:>12} {:>14} {:>10} {:>14} {:>14}\n",
            "stage",
            "items",
            "unit",
            "seconds",
            "items/s",
            "items/s/thread",
            "rays",
            "occlusion",
            "rays/s/thread",
            "cpu s",
            "items/cpu-s",
            "rays/cpu-s"
        );
        for s in &self.stages {
            if s.ran {
                out.push_str(&format!(
                    "{:<16} {:>12} {:<10} {:>10.4} {:>14.0} {:>16.0} {:>12} {:>12} {:>14.0} {:>10.4} {:>14.0} {:>14.0}\n",
                    s.stage,
                    s.items,
                    s.unit,
                    s.seconds,
                    s.items_per_second,
                    s.items_per_second_per_thread,
                    s.rays,
                    s.rays_occlusion,
                    s.rays_per_second_per_thread,
                    s.cpu_seconds,
                    s.items_per_cpu_second,
                    s.rays_per_cpu_second
                ));
            } else {
                out.push_str(&format!("{:<16} skipped: {}\n", s.stage, s.reason));
            }
        }
        out.push_str(&format!("total {:.4} s\n", self.total_seconds));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A merge's `shade` counts the samples its parts took: no rate in the table (`n/a`) or
    /// the JSON (`items_per_second` 0, `merged_parts: true`), where a run's stage has both.
    #[test]
    fn merged_parts_have_no_rate() {
        let stage = |merged_parts: bool| StageReport {
            ran: true,
            seconds: 0.001,
            items: 2_000_000,
            unit: "samples",
            items_per_second: if merged_parts { 0.0 } else { 2e9 },
            merged_parts,
            ..StageReport::skipped("shade", "render camera 4×4".into())
        };
        let report = |merged_parts| RunReport {
            threads: 1,
            stages: vec![stage(merged_parts)],
            ..RunReport::default()
        };
        let row = |merged_parts| {
            report(merged_parts)
                .to_table()
                .lines()
                .nth(1)
                .unwrap()
                .to_string()
        };
        let words = |r: String| -> Vec<String> {
            r.split_whitespace().take(6).map(str::to_string).collect()
        };
        assert_eq!(
            words(row(true)),
            ["shade", "yes", "0.0010", "2000000", "samples", "n/a"]
        );
        assert_eq!(
            words(row(false)),
            ["shade", "yes", "0.0010", "2000000", "samples", "2000000000"]
        );
        let json = |merged_parts| serde_json::to_value(report(merged_parts)).unwrap();
        assert_eq!(json(true)["stages"][0]["merged_parts"], true);
        assert_eq!(json(true)["stages"][0]["items_per_second"], 0.0);
        assert!(json(false)["stages"][0].get("merged_parts").is_none());
    }
}
