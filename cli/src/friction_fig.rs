//! `rotor-rub friction`: what Coulomb friction does to a rub (`docs/MODEL.md` §10). For each
//! preset, the orbit with friction beside its frictionless twin (the same parameters with
//! μ = 0), slip reversals and rolling episodes marked; out/friction.svg and out/friction.png.

use std::fmt::Write as _;
use std::path::PathBuf;

use plotters::style::RGBColor;
use rotor_rub::{Event, EventKind, Options, Preset, Problem, Sample};

use crate::error::{CliError, Result, num};
use crate::limits::{Budget, LimitArgs, fits_memory};
use crate::options::{MethodArgs, Survey, describe};
use crate::output::{check_distinct, ensure_dir};
use crate::plot::orbit::{Mark, OrbitFigure, Panel, Shape};
use crate::plot::{self, ANALYTIC, ENTER, EXIT, LegendMark, REFERENCE};
use crate::stdio;
use crate::trajectory;

/// Marker colour of slip reversals.
pub const REVERSE: RGBColor = RGBColor(230, 130, 0);
/// Marker colour of rolling starts.
pub const ROLL: RGBColor = RGBColor(140, 40, 170);
/// Marker colour of rolling ends.
pub const SLIP: RGBColor = RGBColor(0, 150, 160);

/// Draw orbits with and without friction for friction presets.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Presets drawn, one panel each with its μ = 0 twin (comma-separated; friction and
    /// dry-whip by default; any preset with friction_coefficient > 0)
    #[arg(
        long,
        value_name = "NAME,...",
        value_delimiter = ',',
        default_value = "friction,dry-whip"
    )]
    pub presets: Vec<String>,

    #[command(flatten)]
    pub method: MethodArgs<Survey>,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// First forcing period plotted (0: from the start, where dry whip sets in)
    #[arg(long, value_name = "P", default_value_t = 0, value_parser = crate::options::at_least(0))]
    pub plot_from: u64,

    /// Last forcing period plotted
    #[arg(long, value_name = "P", default_value_t = 25, value_parser = crate::options::at_least(0))]
    pub plot_to: u64,

    /// Directory for friction.svg and friction.png
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out_dir: PathBuf,
}

/// Friction's events of a run inside `window`, as orbit marks: reversals (triangles), rolling
/// starts (crosses) and ends (squares).
pub fn friction_marks(events: &[Event], window: &std::ops::RangeInclusive<f64>) -> Vec<Mark> {
    [
        (EventKind::Reverse, REVERSE, Shape::Triangle),
        (EventKind::Roll, ROLL, Shape::Cross),
        (EventKind::Slip, SLIP, Shape::Square),
    ]
    .into_iter()
    .map(|(kind, color, shape)| Mark {
        points: events
            .iter()
            .filter(|e| e.kind == kind && window.contains(&e.time))
            .map(|e| (e.state.x, e.state.y))
            .collect(),
        color,
        shape,
    })
    .filter(|m| !m.points.is_empty())
    .collect()
}

/// Orbit samples per plotted forcing period.
const SAMPLES_PER_PERIOD: u64 = 200;

/// The orbit samples of one run over the plotted window, `n` + 1 of them (`n` =
/// [`SAMPLES_PER_PERIOD`] × the plotted periods, checked by the caller), and its events.
fn run_one(
    problem: &Problem,
    options: &Options,
    args: &Args,
    n: u64,
    budget: &Budget,
) -> Result<(Vec<Sample>, Vec<Event>)> {
    let period = problem.params.forcing_period();
    let (from, to) = (args.plot_from as f64 * period, args.plot_to as f64 * period);
    budget.plan("orbit samples", n)?;
    let times = (0..=n).map(|k| from + (to - from) * k as f64 / n as f64);
    let propagator = trajectory::start(problem, options)?;
    let mut tracker = budget.run(problem.start_time, to);
    let (pass, samples) = trajectory::run_collect(propagator, to, times, &mut tracker)?;
    Ok((samples, pass.events))
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    if args.plot_to <= args.plot_from {
        return Err(CliError::input(format!(
            "--plot-to ({}) must be after --plot-from ({})",
            args.plot_to, args.plot_from
        )));
    }
    let periods = args.plot_to - args.plot_from;
    let n = periods
        .checked_mul(SAMPLES_PER_PERIOD)
        .filter(|n| *n < u64::MAX)
        .ok_or_else(|| {
            CliError::input(format!(
                "--plot-from {} to --plot-to {} is {periods} forcing periods, more than can be \
                 sampled at {SAMPLES_PER_PERIOD} per period; plot fewer",
                args.plot_from, args.plot_to
            ))
        })?;
    // Every run's samples and events are kept until the figure is drawn.
    fits_memory(
        "orbit samples (200 per plotted forcing period, two runs per preset)",
        (n + 1).saturating_mul(2 * args.presets.len() as u64),
        std::mem::size_of::<Sample>() + 16,
    )?;
    let options = args.method.options()?;
    let svg = args.out_dir.join("friction.svg");
    let png = args.out_dir.join("friction.png");
    check_distinct(&[("--out-dir", &svg), ("--out-dir", &png)], &[])?;
    let budget = args.limits.budget();
    let mut report = String::new();
    let _ = writeln!(report, "method: {}", describe(&options));
    let mut panels = Vec::new();
    for name in &args.presets {
        let preset = Preset::from_name(name).ok_or_else(|| {
            CliError::input(format!(
                "unknown preset {name:?} (one of {})",
                Preset::ALL.map(Preset::name).join(", ")
            ))
        })?;
        let with = preset.problem();
        let mu = with.params.friction_coefficient;
        if mu <= 0.0 {
            return Err(CliError::input(format!(
                "preset {name} has no friction (friction_coefficient = 0): nothing to compare"
            )));
        }
        let mut without = with;
        without.params.friction_coefficient = 0.0;
        let period = with.params.forcing_period();
        let window = args.plot_from as f64 * period..=args.plot_to as f64 * period;
        let mut orbits = Vec::new();
        for (problem, color, dashed, label) in [
            (&without, REFERENCE, true, "μ = 0"),
            (&with, ANALYTIC, false, "with friction"),
        ] {
            let (samples, events) =
                run_one(problem, &options, args, n, &budget).map_err(|e| e.context(name))?;
            let count = |k: EventKind| events.iter().filter(|e| e.kind == k).count();
            let _ = writeln!(
                report,
                "{name}, {label}: {} contacts, {} reversals, {} rolling episodes over {} periods",
                count(EventKind::Enter),
                count(EventKind::Reverse),
                count(EventKind::Roll),
                args.plot_to
            );
            let mut orbit = crate::compare::orbit(&samples, &events, window.clone(), color, dashed);
            if dashed {
                orbit.marks.clear();
            }
            orbits.push(orbit);
        }
        panels.push(Panel {
            title: format!(
                "{name}: μ = {}, R/δ = {}, η = {}",
                num(mu),
                num(with.params.radius_ratio),
                num(with.params.speed_ratio)
            ),
            offset: (with.params.offset_x, with.params.offset_y),
            orbits,
        });
    }
    let figure = OrbitFigure {
        title: format!(
            "Coulomb friction: orbits over forcing periods {}-{} (x, y in clearances)",
            args.plot_from, args.plot_to
        ),
        legend: vec![
            (LegendMark::Line(ANALYTIC), "with friction".to_string()),
            (LegendMark::Dashed(REFERENCE), "μ = 0".to_string()),
            (LegendMark::Dot(ENTER), "contact starts".to_string()),
            (LegendMark::Dot(EXIT), "contact ends".to_string()),
            (LegendMark::Triangle(REVERSE), "slip reverses".to_string()),
            (LegendMark::Cross(ROLL), "rolling starts".to_string()),
            (LegendMark::Square(SLIP), "rolling ends".to_string()),
        ],
        columns: panels.len().clamp(1, 3),
        panels,
        panel: (560, 560),
    };
    ensure_dir(&args.out_dir)?;
    plot::save(&figure, &svg, &png)?;
    let _ = writeln!(
        report,
        "figures written to {} and {}",
        svg.display(),
        png.display()
    );
    stdio::out(&report)
}
