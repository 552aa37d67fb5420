//! The sweep table (one row per knob value) and its summary: log–log fit of relMSE against
//! seconds, bias-plateau flag, and the measured time to reach relMSE 1e-2 and 1e-3 — of the
//! crop's error when the sweep has a crop, else of the whole image's.
//!
//! The summary draws no conclusion the rows cannot carry: no fit from fewer than
//! [`MIN_FIT_POINTS`] points or from times that do not rise with the knob's cost (runs too
//! short to time), no plateau verdict from such disordered times (two rows in cost order do
//! carry one: the costlier's error fell by less than 10 % for 1.5× the time, or not), and no
//! time to reach an error that no row reached (the smallest measured error is given
//! instead; nothing is extrapolated).

use serde::Serialize;

use crate::sweep::crop::Crop;
use crate::sweep::metrics::ErrorMetrics;

/// One knob value's measurements.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// Knob value as text.
    pub value: String,
    /// Seconds per stage (mean over seeds), in table order: `(stage, seconds)`; skipped
    /// stages are listed with 0.
    pub stage_seconds: Vec<(String, f64)>,
    /// Total seconds of the pipeline (mean over seeds).
    pub seconds: f64,
    /// Errors of the whole image against the reference.
    pub error: ErrorMetrics,
    /// Errors of the crop (`--crop`) against the reference's crop.
    pub crop_error: Option<ErrorMetrics>,
    /// Seeds rendered.
    pub seeds: u32,
}

impl SweepRow {
    /// The error the summary fits and the plot draws: the crop's, else the whole image's.
    pub fn fitted(&self) -> &ErrorMetrics {
        self.crop_error.as_ref().unwrap_or(&self.error)
    }
}

/// Fewest points (rows with a positive time and error) a slope is fitted to: a line through
/// two noisy points is exact and says nothing about the trend.
pub const MIN_FIT_POINTS: usize = 3;

/// Fit and conclusions over all rows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepSummary {
    /// Knob name.
    pub knob: String,
    /// Scene file.
    pub scene: String,
    /// The crop whose error is fitted (`None`: the whole image).
    pub crop: Option<Crop>,
    /// What the rows are compared with: `FILE (--reference)`, or the rendered reference's
    /// integrator, samples and knob setting (`path tracer, 1024 samples, max_depth=16`).
    pub reference: Option<String>,
    /// Slope of log10(relMSE) against log10(seconds) (−1 for unbiased Monte Carlo); `None`
    /// when the rows cannot carry a fit (`no_fit` says why).
    pub slope: Option<f64>,
    /// Intercept of that fit.
    pub intercept: Option<f64>,
    /// Why there is no fit: too few points, or times that do not rise with the knob's cost.
    pub no_fit: Option<String>,
    /// True when the error stops falling although time grows (bias dominates); `None` when
    /// the times cannot tell (they do not rise with the knob's cost, or there is one row of
    /// one seed).
    pub bias_plateau: Option<bool>,
    /// Seconds of the quickest row whose relMSE is at most 1e-2 (`None`: no row reached it;
    /// never extrapolated).
    pub seconds_to_rel_mse_1e2: Option<f64>,
    /// Same for relMSE 1e-3.
    pub seconds_to_rel_mse_1e3: Option<f64>,
    /// The smallest relMSE any row measured (what an unreached target is compared with).
    pub smallest_rel_mse: Option<f64>,
    /// The rows.
    pub rows: Vec<SweepRow>,
}

impl SweepSummary {
    /// Fits the rows (their [`SweepRow::fitted`] error; `crop` says which region that is)
    /// and draws the conclusions. `cost_order` lists the row indices from the cheapest
    /// setting to the costliest when the knob implies one ([`crate::sweep::Knob::cost_order`]):
    /// the rows' times must rise along it for a fit or a plateau verdict.
    pub fn new(
        knob: &str,
        scene: &str,
        crop: Option<Crop>,
        rows: Vec<SweepRow>,
        cost_order: Option<&[usize]>,
    ) -> Self {
        let disorder = cost_order.and_then(|order| timing_disorder(knob, &rows, order));
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.seconds > 0.0 && r.fitted().rel_mse > 0.0)
            .map(|r| (r.seconds.log10(), r.fitted().rel_mse.log10()))
            .collect();
        let (fit, no_fit) = match (points.len(), &disorder) {
            (n, _) if n < MIN_FIT_POINTS => (
                None,
                Some(format!(
                    "{n} {} with a measured time and error; a fit needs {MIN_FIT_POINTS} or more",
                    if n == 1 { "value" } else { "values" }
                )),
            ),
            (_, Some(why)) => (None, Some(why.clone())),
            (_, None) => match fit_line(&points) {
                Some(f) => (Some(f), None),
                None => (None, Some("every value took the same time".to_string())),
            },
        };
        let bias_plateau = if disorder.is_some() {
            None
        } else {
            plateau(&rows)
        };
        let reach = |target: f64| -> Option<f64> {
            rows.iter()
                .filter(|r| r.fitted().rel_mse <= target)
                .map(|r| r.seconds)
                .min_by(f64::total_cmp)
        };
        let smallest_rel_mse = rows
            .iter()
            .map(|r| r.fitted().rel_mse)
            .filter(|e| e.is_finite())
            .min_by(f64::total_cmp);
        Self {
            knob: knob.to_string(),
            scene: scene.to_string(),
            crop,
            reference: None,
            slope: fit.map(|f| f.1),
            intercept: fit.map(|f| f.0),
            no_fit,
            bias_plateau,
            seconds_to_rel_mse_1e2: reach(1e-2),
            seconds_to_rel_mse_1e3: reach(1e-3),
            smallest_rel_mse,
            rows,
        }
    }

    /// The same summary, saying what its rows were compared with.
    pub fn with_reference(mut self, reference: String) -> Self {
        self.reference = Some(reference);
        self
    }

    /// The line `sweep` prints under the table: the region, the slope (or why there is
    /// none), the plateau verdict and the measured times to relMSE 1e-2 and 1e-3.
    pub fn conclusion(&self) -> String {
        let fit = match (self.slope, &self.no_fit) {
            (Some(s), _) => format!("slope {s:.2}"),
            (None, Some(why)) => format!("no fit ({why})"),
            (None, None) => "no fit".to_string(),
        };
        let plateau = match self.bias_plateau {
            Some(true) => "yes",
            Some(false) => "no",
            None => "n/a",
        };
        let reached = |s: Option<f64>| match (s, self.smallest_rel_mse) {
            (Some(s), _) => format!("after {s:.3} s"),
            (None, Some(e)) => format!("not reached (the smallest measured relMSE is {e:.2e})"),
            (None, None) => "not reached".to_string(),
        };
        format!(
            "{}: {fit}; bias plateau: {plateau}; relMSE 1e-2 {}; 1e-3 {}",
            self.region(),
            reached(self.seconds_to_rel_mse_1e2),
            reached(self.seconds_to_rel_mse_1e3)
        )
    }

    /// The region the fit is of, for titles: `crop X0,Y0,X1,Y1` or `whole image`.
    pub fn region(&self) -> String {
        self.crop
            .map_or_else(|| "whole image".to_string(), |c| format!("crop {c}"))
    }

    /// The table as CSV: value, seconds per stage, total seconds, the whole image's error
    /// metrics, and with a crop the crop's relMSE, bias² and variance. Bias² and variance
    /// are empty in rows of one seed, which cannot estimate them.
    pub fn to_csv(&self) -> String {
        let stages: Vec<&str> = self
            .rows
            .first()
            .map(|r| r.stage_seconds.iter().map(|(s, _)| s.as_str()).collect())
            .unwrap_or_default();
        let mut out = format!("{},", self.knob);
        for s in &stages {
            out.push_str(&format!("{s}_seconds,"));
        }
        out.push_str("total_seconds,mse,rel_mse,max_error,non_finite,bias2,variance,seeds");
        if self.crop.is_some() {
            out.push_str(",crop_rel_mse,crop_bias2,crop_variance");
        }
        out.push('\n');
        for r in &self.rows {
            out.push_str(&format!("{},", r.value));
            for (_, s) in &r.stage_seconds {
                out.push_str(&format!("{s:.6},"));
            }
            let e = &r.error;
            out.push_str(&format!(
                "{:.6},{:.6e},{:.6e},{:.6e},{},{},{},{}",
                r.seconds,
                e.mse,
                e.rel_mse,
                e.max_error,
                e.non_finite,
                estimate(e.bias2),
                estimate(e.variance),
                r.seeds
            ));
            if let Some(c) = &r.crop_error {
                out.push_str(&format!(
                    ",{:.6e},{},{}",
                    c.rel_mse,
                    estimate(c.bias2),
                    estimate(c.variance)
                ));
            }
            out.push('\n');
        }
        out
    }
}

/// A bias² or variance cell: empty when one seed could not estimate it.
fn estimate(value: Option<f64>) -> String {
    value.map_or_else(String::new, |v| format!("{v:.6e}"))
}

/// Least-squares line `y = a + b·x`; `None` with fewer than two distinct x.
pub fn fit_line(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx <= 1e-12 {
        return None;
    }
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let b = sxy / sxx;
    Some((my - b * mx, b))
}

/// The first pair of settings, in the knob's cost order, whose costlier one took no longer:
/// the times are noise (runs too short to time), so neither a fit nor a plateau verdict.
fn timing_disorder(knob: &str, rows: &[SweepRow], order: &[usize]) -> Option<String> {
    order.windows(2).find_map(|w| {
        let (cheap, costly) = (rows.get(w[0])?, rows.get(w[1])?);
        (costly.seconds <= cheap.seconds).then(|| {
            format!(
                "the times do not rise with the knob's cost: {knob} = {} took {:.3} s, {knob} = {} {:.3} s; runs this short are timed by noise, sweep costlier values",
                costly.value, costly.seconds, cheap.value, cheap.seconds
            )
        })
    })
}

/// A bias plateau: the costliest row took at least 1.5× the time of the one before it but its
/// relMSE fell by less than 10 %, or (with several seeds) bias² exceeds the variance there.
/// `None` from one row of one seed.
fn plateau(rows: &[SweepRow]) -> Option<bool> {
    let mut sorted: Vec<&SweepRow> = rows.iter().collect();
    sorted.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    let last = sorted.last()?;
    let e = last.fitted();
    if let (Some(bias2), Some(variance)) = (e.bias2, e.variance) {
        if bias2 > variance && bias2 > 0.0 {
            return Some(true);
        }
    }
    if sorted.len() < 2 {
        return (last.seeds > 1).then_some(false);
    }
    let prev = sorted[sorted.len() - 2];
    Some(last.seconds >= 1.5 * prev.seconds && e.rel_mse > 0.9 * prev.fitted().rel_mse)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(seconds: f64, rel_mse: f64) -> SweepRow {
        SweepRow {
            value: seconds.to_string(),
            stage_seconds: vec![("shade".into(), seconds)],
            seconds,
            error: ErrorMetrics {
                rel_mse,
                ..Default::default()
            },
            crop_error: None,
            seeds: 1,
        }
    }

    /// Rows of an increasing knob: index order is cost order.
    const RISING: Option<&[usize]> = Some(&[0, 1, 2]);

    #[test]
    fn monte_carlo_convergence_fits_slope_minus_one() {
        let rows = vec![row(1.0, 1e-1), row(4.0, 2.5e-2), row(16.0, 6.25e-3)];
        let s = SweepSummary::new("spp", "x.ron", None, rows, RISING);
        assert!((s.slope.unwrap() + 1.0).abs() < 1e-9);
        assert_eq!((s.bias_plateau, s.no_fit.as_deref()), (Some(false), None));
        // relMSE 1e-2 is reached (measured) at 16 s; 1e-3 by no row: not extrapolated.
        assert_eq!(s.seconds_to_rel_mse_1e2, Some(16.0));
        assert_eq!(s.seconds_to_rel_mse_1e3, None);
        assert_eq!(
            s.conclusion(),
            "whole image: slope -1.00; bias plateau: no; relMSE 1e-2 after 16.000 s; 1e-3 not reached (the smallest measured relMSE is 6.25e-3)"
        );
        assert!(s.to_csv().starts_with("spp,shade_seconds,total_seconds,"));
    }

    #[test]
    fn a_target_below_every_measured_error_is_not_reached() {
        // A steep fit (slope ≈ −6) would put 1e-3 inside the measured times; no row reached it.
        let rows = vec![row(1.0, 2e-2), row(1.1, 1e-2), row(1.2, 4.6e-3)];
        let s = SweepSummary::new("spp", "x.ron", None, rows, RISING);
        assert!(s.slope.unwrap() < -5.0);
        assert_eq!(s.seconds_to_rel_mse_1e2, Some(1.1));
        assert_eq!(s.seconds_to_rel_mse_1e3, None);
        assert_eq!(s.smallest_rel_mse, Some(4.6e-3));
    }

    #[test]
    fn times_that_do_not_rise_with_the_knob_give_no_fit_and_no_plateau_verdict() {
        // `--knob spp=4,1,16`: the 4-spp run was timed quicker than the 1-spp run.
        let mut rows = vec![row(0.010, 4.6e-3), row(0.012, 5.0e-3), row(0.04, 4.5e-3)];
        for (r, v) in rows.iter_mut().zip(["4", "1", "16"]) {
            r.value = v.into();
        }
        let s = SweepSummary::new("spp", "x.ron", None, rows, Some(&[1, 0, 2]));
        assert_eq!((s.slope, s.bias_plateau), (None, None));
        assert_eq!(
            s.conclusion(),
            "whole image: no fit (the times do not rise with the knob's cost: spp = 4 took 0.010 s, spp = 1 0.012 s; runs this short are timed by noise, sweep costlier values); bias plateau: n/a; relMSE 1e-2 after 0.010 s; 1e-3 not reached (the smallest measured relMSE is 4.50e-3)"
        );
        // A knob without a cost order is fitted whatever its times.
        let rows = vec![row(1.4, 1e-2), row(1.0, 2e-2), row(1.2, 1.5e-2)];
        let s = SweepSummary::new("filter", "x.ron", None, rows, None);
        assert!(s.slope.is_some() && s.no_fit.is_none());
    }

    #[test]
    fn two_points_are_not_fitted() {
        let rows = vec![row(1.0, 1e-1), row(4.0, 2.5e-2)];
        let s = SweepSummary::new("spp", "x.ron", None, rows, Some(&[0, 1]));
        assert_eq!(s.slope, None);
        assert_eq!(
            s.no_fit.as_deref(),
            Some("2 values with a measured time and error; a fit needs 3 or more")
        );
        assert_eq!(s.bias_plateau, Some(false));
        let s = SweepSummary::new("spp", "x.ron", None, vec![row(1.0, 1e-1)], Some(&[0]));
        assert_eq!(s.bias_plateau, None);
        assert!(s.conclusion().starts_with(
            "whole image: no fit (1 value with a measured time and error; a fit needs 3 or more); bias plateau: n/a;"
        ));
    }

    #[test]
    fn flat_error_is_a_plateau() {
        let rows = vec![row(1.0, 1e-1), row(4.0, 5e-2), row(16.0, 4.9e-2)];
        let s = SweepSummary::new("spp", "x.ron", None, rows, RISING);
        assert_eq!(s.bias_plateau, Some(true));
        assert_eq!(s.seconds_to_rel_mse_1e3, None);
    }

    #[test]
    fn a_crop_s_error_is_what_is_fitted_and_tabulated() {
        // The whole image is flat (a plateau) while the crop falls as 1/time.
        let rows: Vec<SweepRow> = [(1.0, 1e-1), (4.0, 2.5e-2), (16.0, 6.25e-3)]
            .into_iter()
            .map(|(t, crop)| SweepRow {
                crop_error: Some(ErrorMetrics {
                    rel_mse: crop,
                    ..Default::default()
                }),
                ..row(t, 5e-2)
            })
            .collect();
        let crop = crate::sweep::crop::Crop::parse("1,2,3,4").ok();
        let s = SweepSummary::new("photons", "x.ron", crop, rows.clone(), RISING);
        assert!((s.slope.unwrap() + 1.0).abs() < 1e-9);
        assert_eq!(s.bias_plateau, Some(false));
        assert_eq!(s.seconds_to_rel_mse_1e2, Some(16.0));
        assert_eq!(s.region(), "crop 1,2,3,4");
        let csv = s.to_csv();
        let mut lines = csv.lines();
        assert!(lines
            .next()
            .unwrap()
            .ends_with(",seeds,crop_rel_mse,crop_bias2,crop_variance"));
        assert!(lines.next().unwrap().ends_with(",,,1,1.000000e-1,,"));
        // One seed estimates neither bias² nor variance: null in the JSON, not 0.
        let json = serde_json::to_value(&s).unwrap();
        assert_eq!(json["rows"][0]["error"]["bias2"], serde_json::Value::Null);
        assert_eq!(
            json["rows"][0]["crop_error"]["variance"],
            serde_json::Value::Null
        );
        let whole = SweepSummary::new(
            "photons",
            "x.ron",
            None,
            {
                let mut r = rows;
                r.iter_mut().for_each(|r| r.crop_error = None);
                r
            },
            RISING,
        );
        assert_eq!(whole.bias_plateau, Some(true));
        assert_eq!(whole.region(), "whole image");
    }
}
