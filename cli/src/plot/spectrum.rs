//! Amplitude spectra against frequency in multiples of the running speed (log amplitude).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{Figure, LegendMark, err, legend};

/// One spectrum line.
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// Line colour.
    pub color: RGBColor,
    /// (order, amplitude) points.
    pub points: Vec<(f64, f64)>,
}

/// Spectrum lines against order.
pub struct SpectrumFigure {
    /// Title.
    pub title: String,
    /// The curves.
    pub curves: Vec<Curve>,
    /// Shown order range.
    pub orders: std::ops::Range<f64>,
}

/// Colour of the second curve (y).
pub const SECOND: RGBColor = RGBColor(230, 120, 20);

impl Figure for SpectrumFigure {
    fn size(&self) -> (u32, u32) {
        (1000, 600)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let shown = |(o, a): &(f64, f64)| self.orders.contains(o) && *a > 0.0 && a.is_finite();
        let top = self
            .curves
            .iter()
            .flat_map(|c| c.points.iter().filter(|p| shown(p)).map(|p| p.1))
            .fold(f64::MIN_POSITIVE, f64::max);
        let floor = top * 1e-7;
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(self.orders.clone(), (floor..top * 2.0).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("frequency / running speed (order)")
            .y_desc("amplitude (clearances)")
            .x_labels(17)
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(err)?;
        let mut entries = Vec::new();
        for Curve {
            label,
            color,
            points,
        } in &self.curves
        {
            let line: Vec<(f64, f64)> = points
                .iter()
                .filter(|(o, _)| self.orders.contains(o))
                .map(|&(o, a)| (o, a.max(floor)))
                .collect();
            chart
                .draw_series(LineSeries::new(line, color.stroke_width(1)))
                .map_err(err)?;
            entries.push((LegendMark::Line(*color), label.as_str()));
        }
        if entries.len() > 1 {
            legend(root, (100, 60), &entries)?;
        }
        Ok(())
    }
}
