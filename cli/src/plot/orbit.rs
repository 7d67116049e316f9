//! Orbit panels: trajectories in the (x, y) plane with the clearance circle and contact markers.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{
    CLEARANCE, ENTER, EXIT, Figure, LegendMark, clearance_circle, err, header, square_ranges,
};

/// One trajectory in a panel.
pub struct Orbit {
    /// Line colour.
    pub color: RGBColor,
    /// Dashed (the numerical reference) or solid.
    pub dashed: bool,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Where contacts start.
    pub enters: Vec<(f64, f64)>,
    /// Where contacts end.
    pub exits: Vec<(f64, f64)>,
    /// Further marked events (friction's reversals, rolling starts and ends).
    pub marks: Vec<Mark>,
}

/// Events of one kind marked on an orbit.
pub struct Mark {
    /// Where they happen.
    pub points: Vec<(f64, f64)>,
    /// Marker colour.
    pub color: RGBColor,
    /// Marker shape.
    pub shape: Shape,
}

/// A marker's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A triangle.
    Triangle,
    /// A cross.
    Cross,
    /// A square.
    Square,
}

/// One panel: its title, the stator centre and the trajectories.
pub struct Panel {
    /// Title above the panel.
    pub title: String,
    /// Stator centre (offset_x, offset_y).
    pub offset: (f64, f64),
    /// Trajectories, drawn in order.
    pub orbits: Vec<Orbit>,
}

/// A grid of orbit panels under a title line and a legend line.
pub struct OrbitFigure {
    /// Title line.
    pub title: String,
    /// Legend entries.
    pub legend: Vec<(LegendMark, String)>,
    /// Panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels per row.
    pub columns: usize,
    /// Size of one panel in pixels.
    pub panel: (u32, u32),
}
const HEADER: u32 = 70;
const LABEL_X: u32 = 40;
const LABEL_Y: u32 = 60;
const MARGIN: u32 = 12;
const CAPTION: u32 = 30;

impl Figure for OrbitFigure {
    fn size(&self) -> (u32, u32) {
        let columns = self.columns.max(1) as u32;
        let rows = self.panels.len().div_ceil(self.columns.max(1)).max(1) as u32;
        (self.panel.0 * columns, HEADER + self.panel.1 * rows)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let body = header(root, HEADER, &self.title, None, 50, &self.legend)?;
        let columns = self.columns.max(1);
        let rows = self.panels.len().div_ceil(columns).max(1);
        for (area, panel) in body.split_evenly((rows, columns)).iter().zip(&self.panels) {
            draw_panel(area, panel)?;
        }
        Ok(())
    }
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
) -> Result<(), String> {
    let circle = clearance_circle(panel.offset);
    let all = panel
        .orbits
        .iter()
        .flat_map(|o| o.points.iter().copied())
        .chain(circle.iter().copied());
    let (w, h) = area.dim_in_pixel();
    let plot_w = w.saturating_sub(LABEL_Y + 2 * MARGIN).max(1);
    let plot_h = h.saturating_sub(LABEL_X + CAPTION + 2 * MARGIN).max(1);
    let (xr, yr) = square_ranges(all, (plot_w, plot_h));
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 18))
        .margin(MARGIN)
        .x_label_area_size(LABEL_X)
        .y_label_area_size(LABEL_Y)
        .build_cartesian_2d(xr, yr)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("x")
        .y_desc("y")
        .x_labels(6)
        .y_labels(6)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(LineSeries::new(circle, CLEARANCE.stroke_width(2)))
        .map_err(err)?;
    for orbit in &panel.orbits {
        // The solid line is wider, so it shows between the dashes drawn over it.
        if orbit.dashed {
            let style = orbit.color.stroke_width(1);
            chart
                .draw_series(DashedLineSeries::new(
                    orbit.points.iter().copied(),
                    9,
                    6,
                    style,
                ))
                .map_err(err)?;
        } else {
            let style = orbit.color.stroke_width(2);
            chart
                .draw_series(LineSeries::new(orbit.points.iter().copied(), style))
                .map_err(err)?;
        }
    }
    for orbit in &panel.orbits {
        for (points, color) in [(&orbit.enters, ENTER), (&orbit.exits, EXIT)] {
            let marker = if orbit.dashed {
                color.stroke_width(1)
            } else {
                color.filled()
            };
            let size = if orbit.dashed { 5 } else { 3 };
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, size, marker)))
                .map_err(err)?;
        }
        for mark in &orbit.marks {
            let style = mark.color.stroke_width(2);
            match mark.shape {
                Shape::Triangle => chart
                    .draw_series(
                        mark.points
                            .iter()
                            .map(|&p| TriangleMarker::new(p, 7, mark.color.filled())),
                    )
                    .map(|_| ()),
                Shape::Cross => chart
                    .draw_series(mark.points.iter().map(|&p| Cross::new(p, 6, style)))
                    .map(|_| ()),
                Shape::Square => {
                    chart
                        .draw_series(mark.points.iter().map(|&p| {
                            EmptyElement::at(p) + Rectangle::new([(-5, -5), (5, 5)], style)
                        }))
                        .map(|_| ())
                }
            }
            .map_err(err)?;
        }
    }
    Ok(())
}
