//! The run-up diagram: the orbit's largest (and, thin, smallest) radius per forcing period
//! against the speed, run-up and coast-down in two colours on one chart, the speeds where each
//! rubs shaded in its colour, and the jumps marked.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{ANALYTIC, Figure, LegendMark, err, header, padded_range};

/// Colour of the run-up.
pub const RUN_UP: RGBColor = ANALYTIC;
/// Colour of the coast-down.
pub const COAST_DOWN: RGBColor = RGBColor(230, 110, 0);

/// One direction of the run.
pub struct Curve {
    /// Its colour.
    pub color: RGBColor,
    /// (speed, largest radius, smallest radius) per forcing period, in run order.
    pub points: Vec<(f64, f64, f64)>,
    /// Speed intervals where it rubs.
    pub contact: Vec<(f64, f64)>,
    /// (speed, radius before, radius after) of each jump.
    pub jumps: Vec<(f64, f64, f64)>,
}

/// The whole figure.
pub struct RunupFigure {
    /// First title line.
    pub title: String,
    /// Second title line (method, rate).
    pub subtitle: String,
    /// The legend entries.
    pub legend: Vec<(LegendMark, String)>,
    /// The curves, drawn in order.
    pub curves: Vec<Curve>,
    /// The axes' labels (x, y) when not the paper model's (η, |q| in clearances).
    pub axes: Option<(String, String)>,
}

const HEADER: u32 = 92;

impl Figure for RunupFigure {
    fn size(&self) -> (u32, u32) {
        (1100, 720)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let body = header(
            root,
            HEADER,
            &self.title,
            Some(&self.subtitle),
            74,
            &self.legend,
        )?;

        let points = self.curves.iter().flat_map(|c| c.points.iter());
        let xr = padded_range(points.clone().map(|p| p.0));
        let nudge = 0.008 * (xr.end - xr.start);
        let top = points.map(|p| p.1).fold(0.0_f64, f64::max);
        let yr = 0.0..(1.06 * top).max(1e-3);
        let mut chart = ChartBuilder::on(&body)
            .margin(14)
            .x_label_area_size(46)
            .y_label_area_size(66)
            .build_cartesian_2d(xr, yr.clone())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(self.axes.as_ref().map_or(
                "speed ratio η = Ω/ω_n (mean over each forcing period)",
                |a| a.0.as_str(),
            ))
            .y_desc(
                self.axes
                    .as_ref()
                    .map_or("orbit radius |q| per forcing period (clearances)", |a| {
                        a.1.as_str()
                    }),
            )
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(err)?;
        for curve in &self.curves {
            chart
                .draw_series(curve.contact.iter().map(|&(lo, hi)| {
                    Rectangle::new(
                        [(lo, yr.start), (hi, yr.end)],
                        curve.color.mix(0.12).filled(),
                    )
                }))
                .map_err(err)?;
        }
        for curve in &self.curves {
            chart
                .draw_series(LineSeries::new(
                    curve.points.iter().map(|p| (p.0, p.2)),
                    curve.color.mix(0.55).stroke_width(1),
                ))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(
                    curve.points.iter().map(|p| (p.0, p.1)),
                    curve.color.stroke_width(2),
                ))
                .map_err(err)?;
        }
        for curve in &self.curves {
            for &(speed, before, after) in &curve.jumps {
                chart
                    .draw_series(DashedLineSeries::new(
                        [(speed, before), (speed, after)],
                        6,
                        4,
                        curve.color.stroke_width(2),
                    ))
                    .map_err(err)?;
                chart
                    .draw_series([TriangleMarker::new((speed, after), 8, curve.color.filled())])
                    .map_err(err)?;
                let label = format!("jump η = {speed:.3}");
                chart
                    .draw_series([Text::new(
                        label,
                        (speed + nudge, 0.5 * (before + after)),
                        ("sans-serif", 15).into_font().color(&curve.color),
                    )])
                    .map_err(err)?;
            }
        }
        Ok(())
    }
}
