//! The sweep plot: relMSE (of the crop when the sweep has one) against seconds on log–log
//! axes (SVG, via `plotters`), with the measured points, the fitted line and its slope.

use plotters::prelude::*;

use crate::sweep::report::SweepSummary;

/// Renders the summary as an SVG document.
pub fn svg(summary: &SweepSummary) -> Result<String, String> {
    let points: Vec<(f64, f64)> = summary
        .rows
        .iter()
        .filter(|r| r.seconds > 0.0 && r.fitted().rel_mse > 0.0)
        .map(|r| (r.seconds, r.fitted().rel_mse))
        .collect();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (720, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &(x, y) in &points {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if points.is_empty() {
            (x0, x1, y0, y1) = (1e-3, 1.0, 1e-4, 1.0);
        }
        let (x0, x1) = (x0 / 2.0, x1 * 2.0);
        let (y0, y1) = ((y0 / 3.0).min(5e-4), (y1 * 3.0).max(2e-2));
        let title = match summary.slope {
            Some(s) => format!(
                "{} — {}: relMSE ({}) vs time (slope {s:.2})",
                summary.scene,
                summary.knob,
                summary.region()
            ),
            None => format!(
                "{} — {}: relMSE ({}) vs time",
                summary.scene,
                summary.knob,
                summary.region()
            ),
        };
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("seconds")
            .y_desc("relMSE")
            .x_label_formatter(&|v| format!("{v:.2e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(|e| e.to_string())?;
        for target in [1e-2, 1e-3] {
            if (y0..y1).contains(&target) {
                chart
                    .draw_series(LineSeries::new(
                        [(x0, target), (x1, target)],
                        BLACK.mix(0.25),
                    ))
                    .map_err(|e| e.to_string())?;
            }
        }
        if let (Some(a), Some(b)) = (summary.intercept, summary.slope) {
            let line = [x0, x1].map(|x| (x, 10f64.powf(a + b * x.log10())));
            chart
                .draw_series(LineSeries::new(line, RED.mix(0.6)))
                .map_err(|e| e.to_string())?
                .label(format!("fit: slope {b:.2}"))
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], RED));
        }
        chart
            .draw_series(LineSeries::new(points.clone(), BLUE))
            .map_err(|e| e.to_string())?
            .label(summary.knob.clone())
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLUE));
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 4, BLUE.filled())))
            .map_err(|e| e.to_string())?;
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(out)
}
