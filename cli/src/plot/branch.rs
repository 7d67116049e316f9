//! The branch diagram of `rotor-rub continue`: over the continued parameter, the orbits' section
//! coordinate x (each of a period-k orbit's k section points) above and their largest radius |q|
//! below; stable orbits solid, unstable dashed, one colour per period; the bifurcations marked
//! and labelled; optionally a sweep's Poincaré points behind (grey), which the stable branches
//! run through.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{ANALYTIC, Figure, LegendMark, err, header, padded_range};

/// One run of a branch with the same stability, in branch order.
pub struct Curve {
    /// Its orbits' period (forcing periods).
    pub periods: u32,
    /// Stable (solid) or not (dashed).
    pub stable: bool,
    /// (value, section x, largest radius) per point.
    pub points: Vec<(f64, f64, f64)>,
}

/// A located bifurcation.
pub struct Mark {
    /// `F` fold, `PD`, `NS`, `G` grazing.
    pub label: &'static str,
    /// Where: value, section x, largest radius.
    pub at: (f64, f64, f64),
}

/// The whole figure.
pub struct BranchFigure {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// The continued parameter's axis label.
    pub x_label: String,
    /// A sweep's points (value, x), drawn first.
    pub sweep: Vec<(f64, f64)>,
    /// The branches' runs.
    pub curves: Vec<Curve>,
    /// The bifurcations.
    pub marks: Vec<Mark>,
}

/// The colour of period-k orbits.
pub fn period_color(periods: u32) -> RGBColor {
    match periods {
        1 => ANALYTIC,
        2 => RGBColor(230, 110, 0),
        4 => RGBColor(40, 150, 60),
        _ => RGBColor(150, 60, 170),
    }
}

/// The colour of a bifurcation's mark.
fn mark_color(label: &str) -> RGBColor {
    match label {
        "F" => RGBColor(200, 20, 20),
        "PD" => RGBColor(120, 40, 160),
        "NS" => RGBColor(0, 140, 140),
        _ => RGBColor(20, 20, 20),
    }
}

const HEADER: u32 = 96;

impl BranchFigure {
    fn legend(&self) -> Vec<(LegendMark, String)> {
        let mut entries = Vec::new();
        if !self.sweep.is_empty() {
            entries.push((LegendMark::Dot(RGBColor(170, 170, 170)), "sweep".to_owned()));
        }
        let mut periods: Vec<u32> = self.curves.iter().map(|c| c.periods).collect();
        periods.sort_unstable();
        periods.dedup();
        for k in periods {
            entries.push((
                LegendMark::Line(period_color(k)),
                format!("period-{k} stable"),
            ));
        }
        entries.push((
            LegendMark::Dashed(RGBColor(60, 60, 60)),
            "unstable".to_owned(),
        ));
        for (label, text) in [
            ("F", "fold"),
            ("PD", "period doubling"),
            ("NS", "Neimark-Sacker"),
            ("G", "grazing"),
        ] {
            if self.marks.iter().any(|m| m.label == label) {
                let mark = match label {
                    "F" => LegendMark::Dot(mark_color(label)),
                    "PD" => LegendMark::Triangle(mark_color(label)),
                    "NS" => LegendMark::Square(mark_color(label)),
                    _ => LegendMark::Cross(mark_color(label)),
                };
                entries.push((mark, text.to_owned()));
            }
        }
        entries
    }

    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        y_label: &str,
        pick: impl Fn((f64, f64, f64)) -> f64,
        with_sweep: bool,
    ) -> Result<(), String> {
        let values = self
            .curves
            .iter()
            .flat_map(|c| c.points.iter().map(|p| p.0));
        let sweep_values = self.sweep.iter().map(|p| p.0);
        let xr = padded_range(values.chain(sweep_values));
        let ys = self
            .curves
            .iter()
            .flat_map(|c| c.points.iter().map(|&p| pick(p)));
        let sweep_ys = self.sweep.iter().filter(|_| with_sweep).map(|p| p.1);
        let yr = padded_range(ys.chain(sweep_ys));
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(62)
            .build_cartesian_2d(xr.clone(), yr)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(y_label)
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(err)?;
        if with_sweep {
            let grey = RGBColor(170, 170, 170);
            chart
                .draw_series(
                    self.sweep
                        .iter()
                        .map(|&(v, x)| Circle::new((v, x), 1, grey.filled())),
                )
                .map_err(err)?;
        }
        for c in &self.curves {
            let color = period_color(c.periods);
            let line: Vec<(f64, f64)> = c.points.iter().map(|&p| (p.0, pick(p))).collect();
            if c.stable {
                chart
                    .draw_series(LineSeries::new(line, color.stroke_width(2)))
                    .map_err(err)?;
            } else {
                chart
                    .draw_series(DashedLineSeries::new(line, 5, 4, color.stroke_width(1)))
                    .map_err(err)?;
            }
        }
        for m in &self.marks {
            let at = (m.at.0, pick(m.at));
            let color = mark_color(m.label);
            match m.label {
                "F" => chart
                    .draw_series([Circle::new(at, 4, color.filled())])
                    .map(|_| ()),
                "PD" => chart
                    .draw_series([TriangleMarker::new(at, 6, color.filled())])
                    .map(|_| ()),
                "NS" => chart
                    .draw_series([EmptyElement::at(at)
                        + Rectangle::new([(-5, -5), (5, 5)], color.stroke_width(2))])
                    .map(|_| ()),
                _ => chart
                    .draw_series([Cross::new(at, 5, color.stroke_width(2))])
                    .map(|_| ()),
            }
            .map_err(err)?;
        }
        Ok(())
    }
}

impl Figure for BranchFigure {
    fn size(&self) -> (u32, u32) {
        (1200, 1000)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let body = header(
            root,
            HEADER,
            &self.title,
            Some(&self.subtitle),
            76,
            &self.legend(),
        )?;
        let (top, bottom) = body.split_vertically(body.dim_in_pixel().1 / 2);
        self.panel(
            &top,
            "x on the section tau = 0 mod 2 pi/eta (clearances)",
            |p| p.1,
            true,
        )?;
        self.panel(
            &bottom,
            "largest radius |q| of the orbit (clearances)",
            |p| p.2,
            false,
        )
    }
}
