//! Point clouds: the Poincaré section in the (x, y) plane and the bifurcation diagram.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{ANALYTIC, CLEARANCE, Figure, clearance_circle, err, padded_range, square_ranges};

/// Poincaré section points in the (x, y) plane with the clearance circle.
pub struct SectionFigure {
    /// Title.
    pub title: String,
    /// Stator centre.
    pub offset: (f64, f64),
    /// Section points (x, y).
    pub points: Vec<(f64, f64)>,
}

impl Figure for SectionFigure {
    fn size(&self) -> (u32, u32) {
        (720, 720)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let circle = clearance_circle(self.offset);
        let (xr, yr) = square_ranges(
            self.points.iter().copied().chain(circle.iter().copied()),
            (620, 600),
        );
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(16)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(xr, yr)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("x (clearances)")
            .y_desc("y (clearances)")
            .draw()
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(circle, CLEARANCE.stroke_width(2)))
            .map_err(err)?;
        chart
            .draw_series(
                self.points
                    .iter()
                    .map(|&p| Circle::new(p, 2, ANALYTIC.filled())),
            )
            .map_err(err)?;
        Ok(())
    }
}

/// Bifurcation diagram: x of the Poincaré points against the swept parameter.
pub struct BifurcationFigure {
    /// Title.
    pub title: String,
    /// The swept parameter's name (x axis).
    pub parameter: String,
    /// (parameter value, x) points.
    pub points: Vec<(f64, f64)>,
}

impl Figure for BifurcationFigure {
    fn size(&self) -> (u32, u32) {
        (1000, 640)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let xr = padded_range(self.points.iter().map(|p| p.0));
        let yr = padded_range(self.points.iter().map(|p| p.1));
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(xr, yr)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(self.parameter.as_str())
            .y_desc("x at the Poincaré section (clearances)")
            .draw()
            .map_err(err)?;
        chart
            .draw_series(
                self.points
                    .iter()
                    .map(|&p| Circle::new(p, 1, ANALYTIC.filled())),
            )
            .map_err(err)?;
        Ok(())
    }
}
