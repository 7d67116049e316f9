//! Plots (plotters), each written as SVG and PNG. Text is rendered with an embedded font
//! (DejaVu Sans, registered with plotters' ab_glyph backend), so PNGs render the same on a
//! machine without system fonts.

pub mod branch;
pub mod orbit;
pub mod runup;
pub mod scatter;
pub mod spectrum;

use std::path::Path;
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use crate::error::{CliError, Result};
use crate::output::AtomicFile;

/// Colour of the analytic (or single) trajectory.
pub const ANALYTIC: RGBColor = RGBColor(31, 119, 180);
/// Colour of the numerical reference trajectory.
pub const REFERENCE: RGBColor = RGBColor(40, 40, 40);
/// Colour of the clearance circle.
pub const CLEARANCE: RGBColor = RGBColor(150, 150, 150);
/// Contact-start markers.
pub const ENTER: RGBColor = RGBColor(220, 30, 30);
/// Contact-end markers.
pub const EXIT: RGBColor = RGBColor(20, 160, 40);

/// Register the embedded font under the family name plotters uses for `"sans-serif"`.
pub fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        for (style, bytes) in [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
            (FontStyle::Italic, dejavu::sans::oblique()),
            (FontStyle::Oblique, dejavu::sans::oblique()),
        ] {
            register_font("sans-serif", style, bytes)
                .unwrap_or_else(|_| panic!("the embedded DejaVu font is valid"));
        }
    });
}

/// Something drawable on any plotters backend.
pub trait Figure {
    /// Size in pixels (SVG user units).
    fn size(&self) -> (u32, u32);
    /// Draw onto `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// A plotters error as a message.
pub fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// Write `figure` to `svg` and `png` (both atomically).
pub fn save(figure: &impl Figure, svg: &Path, png: &Path) -> Result<()> {
    crate::output::commit_all(render(figure, svg, png)?)
}

/// Draw `figure` into temporary files for `svg` and `png`, to be committed with the command's
/// other outputs.
pub fn render(figure: &impl Figure, svg: &Path, png: &Path) -> Result<[AtomicFile; 2]> {
    register_fonts();
    let size = figure.size();
    let svg_file = AtomicFile::create(svg)?;
    let png_file = AtomicFile::create(png)?;
    let failed =
        |dest: &Path, e: String| CliError::failure(format!("cannot draw {}: {e}", dest.display()));
    {
        let root = SVGBackend::new(svg_file.temp_path(), size).into_drawing_area();
        figure.draw(&root).map_err(|e| failed(svg, e))?;
        root.present().map_err(|e| failed(svg, err(e)))?;
    }
    {
        let root = BitMapBackend::new(png_file.temp_path(), size).into_drawing_area();
        figure.draw(&root).map_err(|e| failed(png, e))?;
        root.present().map_err(|e| failed(png, err(e)))?;
    }
    Ok([svg_file, png_file])
}

/// The plot paths next to `path`: `<stem>.svg` and `<stem>.png`.
pub fn beside(path: &Path) -> [std::path::PathBuf; 2] {
    [path.with_extension("svg"), path.with_extension("png")]
}

/// [`render`] as `<stem>.svg` and `<stem>.png` next to `path`.
pub fn render_beside(figure: &impl Figure, path: &Path) -> Result<[AtomicFile; 2]> {
    let [svg, png] = beside(path);
    render(figure, &svg, &png)
}

/// A range covering `values` with a 5 % margin (a unit range around a single value).
pub fn padded_range(values: impl IntoIterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return -1.0..1.0;
    }
    let pad = if hi > lo { 0.05 * (hi - lo) } else { 0.5 };
    (lo - pad)..(hi + pad)
}

/// Equal-scale x and y ranges covering `points` for a plotting area of `w`×`h` pixels.
pub fn square_ranges(
    points: impl IntoIterator<Item = (f64, f64)>,
    (w, h): (u32, u32),
) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
    let (xs, ys): (Vec<f64>, Vec<f64>) = points.into_iter().unzip();
    let (x, y) = (padded_range(xs), padded_range(ys));
    let (cx, cy) = ((x.start + x.end) / 2.0, (y.start + y.end) / 2.0);
    let per_pixel = ((x.end - x.start) / w as f64).max((y.end - y.start) / h as f64);
    let (hx, hy) = (per_pixel * w as f64 / 2.0, per_pixel * h as f64 / 2.0);
    ((cx - hx)..(cx + hx), (cy - hy)..(cy + hy))
}

/// The clearance circle z = 1 around the stator centre.
pub fn clearance_circle(offset: (f64, f64)) -> Vec<(f64, f64)> {
    (0..=360)
        .map(|k| {
            let a = (k as f64).to_radians();
            (offset.0 + a.cos(), offset.1 + a.sin())
        })
        .collect()
}

/// Fill `root` white and draw a figure's header in its top `height` pixels: the title, an
/// optional subtitle under it, and the legend at pixel row `legend_y`. Returns the area below.
pub fn header<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    height: u32,
    title: &str,
    subtitle: Option<&str>,
    legend_y: i32,
    entries: &[(LegendMark, String)],
) -> Result<DrawingArea<DB, Shift>, String> {
    root.fill(&WHITE).map_err(err)?;
    let (top, body) = root.split_vertically(height);
    top.draw(&Text::new(title, (12, 8), ("sans-serif", 20).into_font()))
        .map_err(err)?;
    if let Some(subtitle) = subtitle {
        top.draw(&Text::new(
            subtitle,
            (12, 36),
            ("sans-serif", 15).into_font(),
        ))
        .map_err(err)?;
    }
    let entries: Vec<(LegendMark, &str)> = entries.iter().map(|(m, s)| (*m, s.as_str())).collect();
    legend(&top, (12, legend_y), &entries)?;
    Ok(body)
}

/// Draw a one-line legend of (sample, label) entries at pixel `(x, y)` of `area`.
pub fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (mut x, y): (i32, i32),
    entries: &[(LegendMark, &str)],
) -> Result<(), String> {
    let font: TextStyle = ("sans-serif", 16).into();
    for (mark, label) in entries {
        match *mark {
            LegendMark::Line(c) => area
                .draw(&PathElement::new(
                    vec![(x, y), (x + 30, y)],
                    c.stroke_width(2),
                ))
                .map_err(err)?,
            LegendMark::Dashed(c) => {
                for k in 0..3 {
                    let s = x + k * 11;
                    area.draw(&PathElement::new(
                        vec![(s, y), (s + 6, y)],
                        c.stroke_width(2),
                    ))
                    .map_err(err)?;
                }
            }
            LegendMark::Dot(c) => area
                .draw(&Circle::new((x + 15, y), 4, c.filled()))
                .map_err(err)?,
            LegendMark::Ring(c) => area
                .draw(&Circle::new((x + 15, y), 4, c.stroke_width(1)))
                .map_err(err)?,
            LegendMark::Triangle(c) => area
                .draw(&TriangleMarker::new((x + 15, y), 7, c.filled()))
                .map_err(err)?,
            LegendMark::Cross(c) => area
                .draw(&Cross::new((x + 15, y), 6, c.stroke_width(2)))
                .map_err(err)?,
            LegendMark::Square(c) => area
                .draw(&Rectangle::new(
                    [(x + 10, y - 5), (x + 20, y + 5)],
                    c.stroke_width(2),
                ))
                .map_err(err)?,
            LegendMark::Shade(c) => area
                .draw(&Rectangle::new(
                    [(x + 4, y - 7), (x + 26, y + 7)],
                    c.mix(0.25).filled(),
                ))
                .map_err(err)?,
        }
        let text_x = x + 36;
        area.draw(&Text::new(label.to_string(), (text_x, y - 8), font.clone()))
            .map_err(err)?;
        let (w, _) = area.estimate_text_size(label, &font).map_err(err)?;
        x = text_x + w as i32 + 24;
    }
    Ok(())
}

/// A legend entry's sample.
#[derive(Clone, Copy)]
pub enum LegendMark {
    /// A solid line.
    Line(RGBColor),
    /// A dashed line.
    Dashed(RGBColor),
    /// A filled marker.
    Dot(RGBColor),
    /// A hollow marker.
    Ring(RGBColor),
    /// A filled triangle.
    Triangle(RGBColor),
    /// A cross.
    Cross(RGBColor),
    /// A hollow square.
    Square(RGBColor),
    /// A shaded area.
    Shade(RGBColor),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Text renders with the embedded font alone (the `ttf` feature, which would look for system
    /// fonts, is off): drawing a label into a bitmap darkens pixels.
    #[test]
    fn text_renders_with_the_embedded_font() {
        register_fonts();
        let (w, h) = (200u32, 40u32);
        let mut buffer = vec![255u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
            root.draw(&Text::new(
                "η = 1.5",
                (5, 5),
                ("sans-serif", 24).into_font(),
            ))
            .unwrap();
            root.present().unwrap();
        }
        let dark = buffer
            .chunks(3)
            .filter(|p| p.iter().all(|&c| c < 128))
            .count();
        assert!(dark > 50, "only {dark} dark pixels");
    }
}
