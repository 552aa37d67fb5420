//! The sweep table (one row per knob value) and its summary: log–log fit of relMSE against
//! seconds, bias-plateau flag, and time to reach relMSE 1e-2 and 1e-3 — of the crop's error
//! when the sweep has a crop, else of the whole image's.

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

/// Farthest an unreached error target is extrapolated along the fit: this many times the
/// longest run. Beyond it (a nearly flat fit, e.g. of a knob that trades blur for noise)
/// the target counts as not reached.
pub const MAX_EXTRAPOLATION: f64 = 100.0;

/// Fit and conclusions over all rows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepSummary {
    /// Knob name.
    pub knob: String,
    /// Scene file.
    pub scene: String,
    /// The crop whose error is fitted (`None`: the whole image).
    pub crop: Option<Crop>,
    /// Slope of log10(relMSE) against log10(seconds) (−1 for unbiased Monte Carlo).
    pub slope: Option<f64>,
    /// Intercept of that fit.
    pub intercept: Option<f64>,
    /// True when the error stops falling although time grows (bias dominates).
    pub bias_plateau: bool,
    /// Seconds to reach relMSE 1e-2 (measured if a row reached it, else extrapolated along
    /// the fit up to [`MAX_EXTRAPOLATION`] × the longest run; `None` when the fit does not
    /// fall that fast).
    pub seconds_to_rel_mse_1e2: Option<f64>,
    /// Same for relMSE 1e-3.
    pub seconds_to_rel_mse_1e3: Option<f64>,
    /// The rows.
    pub rows: Vec<SweepRow>,
}

impl SweepSummary {
    /// Fits the rows (their [`SweepRow::fitted`] error; `crop` says which region that is)
    /// and draws the conclusions.
    pub fn new(knob: &str, scene: &str, crop: Option<Crop>, rows: Vec<SweepRow>) -> Self {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.seconds > 0.0 && r.fitted().rel_mse > 0.0)
            .map(|r| (r.seconds.log10(), r.fitted().rel_mse.log10()))
            .collect();
        let fit = fit_line(&points);
        let bias_plateau = plateau(&rows);
        let reach = |target: f64| -> Option<f64> {
            let measured = rows
                .iter()
                .filter(|r| r.fitted().rel_mse <= target)
                .map(|r| r.seconds)
                .fold(None, |best: Option<f64>, s| {
                    Some(best.map_or(s, |b| b.min(s)))
                });
            measured.or_else(|| {
                let (a, b) = fit?;
                let longest = rows.iter().map(|r| r.seconds).fold(0.0, f64::max);
                let t = 10f64.powf((target.log10() - a) / b);
                (b < 0.0 && !bias_plateau && t.is_finite() && t <= MAX_EXTRAPOLATION * longest)
                    .then_some(t)
            })
        };
        Self {
            knob: knob.to_string(),
            scene: scene.to_string(),
            crop,
            slope: fit.map(|f| f.1),
            intercept: fit.map(|f| f.0),
            bias_plateau,
            seconds_to_rel_mse_1e2: reach(1e-2),
            seconds_to_rel_mse_1e3: reach(1e-3),
            rows,
        }
    }

    /// The region the fit is of, for titles: `crop X0,Y0,X1,Y1` or `whole image`.
    pub fn region(&self) -> String {
        self.crop
            .map_or_else(|| "whole image".to_string(), |c| format!("crop {c}"))
    }

    /// The table as CSV: value, seconds per stage, total seconds, the whole image's error
    /// metrics, and with a crop the crop's relMSE, bias² and variance.
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
                "{:.6},{:.6e},{:.6e},{:.6e},{},{:.6e},{:.6e},{}",
                r.seconds,
                e.mse,
                e.rel_mse,
                e.max_error,
                e.non_finite,
                e.bias2,
                e.variance,
                r.seeds
            ));
            if let Some(c) = &r.crop_error {
                out.push_str(&format!(
                    ",{:.6e},{:.6e},{:.6e}",
                    c.rel_mse, c.bias2, c.variance
                ));
            }
            out.push('\n');
        }
        out
    }
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

/// A bias plateau: the costliest row took at least 1.5× the time of the one before it but its
/// relMSE fell by less than 10 %, or (with several seeds) bias² exceeds the variance there.
fn plateau(rows: &[SweepRow]) -> bool {
    let mut sorted: Vec<&SweepRow> = rows.iter().collect();
    sorted.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    let Some(last) = sorted.last() else {
        return false;
    };
    let e = last.fitted();
    if last.seeds > 1 && e.bias2 > e.variance && e.bias2 > 0.0 {
        return true;
    }
    if sorted.len() < 2 {
        return false;
    }
    let prev = sorted[sorted.len() - 2];
    last.seconds >= 1.5 * prev.seconds && e.rel_mse > 0.9 * prev.fitted().rel_mse
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

    #[test]
    fn monte_carlo_convergence_fits_slope_minus_one() {
        let rows = vec![row(1.0, 1e-1), row(4.0, 2.5e-2), row(16.0, 6.25e-3)];
        let s = SweepSummary::new("spp", "x.ron", None, rows);
        assert!((s.slope.unwrap() + 1.0).abs() < 1e-9);
        assert!(!s.bias_plateau);
        // relMSE 1e-2 is reached (measured) at 16 s; 1e-3 extrapolates to 100 s.
        assert_eq!(s.seconds_to_rel_mse_1e2, Some(16.0));
        assert!((s.seconds_to_rel_mse_1e3.unwrap() - 100.0).abs() < 1e-6);
        assert!(s.to_csv().starts_with("spp,shade_seconds,total_seconds,"));
    }

    #[test]
    fn a_nearly_flat_fit_is_not_extrapolated_to_absurd_times() {
        // A knob that barely moves the error (slope ≈ −0.05, e.g. a photon filter): 1e-2 lies
        // ~27× past the longest run along the fit and is quoted; 1e-3 would take ~1e21 s,
        // so the summary says "not reached" instead of a number of that size.
        let rows = vec![row(1.0, 1.2e-2), row(1.2, 1.19e-2), row(1.4, 1.18e-2)];
        let s = SweepSummary::new("filter", "x.ron", None, rows);
        assert!(!s.bias_plateau);
        let slope = s.slope.unwrap();
        assert!(slope < 0.0 && slope > -0.1, "{slope}");
        let t = s.seconds_to_rel_mse_1e2.unwrap();
        assert!(t > 1.4 && t < MAX_EXTRAPOLATION * 1.4, "{t}");
        assert_eq!(s.seconds_to_rel_mse_1e3, None);
    }

    #[test]
    fn flat_error_is_a_plateau() {
        let rows = vec![row(1.0, 1e-1), row(4.0, 5e-2), row(16.0, 4.9e-2)];
        let s = SweepSummary::new("spp", "x.ron", None, rows);
        assert!(s.bias_plateau);
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
        let s = SweepSummary::new("photons", "x.ron", crop, rows.clone());
        assert!((s.slope.unwrap() + 1.0).abs() < 1e-9);
        assert!(!s.bias_plateau);
        assert_eq!(s.seconds_to_rel_mse_1e2, Some(16.0));
        assert_eq!(s.region(), "crop 1,2,3,4");
        let csv = s.to_csv();
        let mut lines = csv.lines();
        assert!(lines
            .next()
            .unwrap()
            .ends_with(",seeds,crop_rel_mse,crop_bias2,crop_variance"));
        assert!(lines
            .next()
            .unwrap()
            .ends_with(",1,1.000000e-1,0.000000e0,0.000000e0"));
        let whole = SweepSummary::new("photons", "x.ron", None, {
            let mut r = rows;
            r.iter_mut().for_each(|r| r.crop_error = None);
            r
        });
        assert!(whole.bias_plateau);
        assert_eq!(whole.region(), "whole image");
    }
}
