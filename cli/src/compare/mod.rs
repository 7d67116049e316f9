//! `rotor-rub compare`: the analytic method against a numerical reference for one parameter set.

use std::fmt::Write as _;
use std::path::PathBuf;

use rotor_rub::{Event, EventKind, Method, Options};

use crate::analysis::switches::{MATCH_GAP, Matching};
use crate::error::{CliError, Result, num};
use crate::limits::{LimitArgs, fits_memory};
use crate::options::{
    SchemeArgs, TimeArgs, describe, parse_positive, parse_reference, reference_help,
    reference_options,
};
use crate::output::{CsvOut, check_distinct, commit_all, ensure_dir};
use crate::plot::orbit::{Orbit, OrbitFigure, Panel};
use crate::plot::{self, ANALYTIC, ENTER, EXIT, LegendMark, REFERENCE};
use crate::problem::ProblemArgs;
use crate::stdio;
use crate::trajectory::{self, dense_count, dense_times};

mod matrix;

/// Compare the analytic method with a numerical reference: switch table, largest differences,
/// both orbits in one plot.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    /// A rotor from matrices (TOML or .npz, SI units: docs/MODEL_FILES.md) instead of the
    /// paper's model: --t-end in s, --periods of 2π/Ω, the rub station's switches and orbit
    #[arg(long, value_name = "FILE", conflicts_with_all = ["preset", "config", "set"])]
    pub model: Option<PathBuf>,

    #[command(flatten)]
    pub time: TimeArgs,

    #[command(flatten)]
    pub scheme: SchemeArgs,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[arg(long, value_name = "METHOD", default_value = "dop853", value_parser = parse_reference, help = reference_help())]
    pub reference: Method,

    /// Tolerance of the reference method, > 0 [default: 1e-10]
    #[arg(long, value_name = "TOL", value_parser = parse_positive, allow_hyphen_values = true)]
    pub reference_tol: Option<f64>,

    /// Directory for compare.csv (the switch table), compare.svg and compare.png (the orbits)
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out_dir: PathBuf,

    /// Plot the orbits from this forcing period on (0 = from the start), inside the run: in
    /// [0, the run's length in forcing periods)
    #[arg(long, value_name = "P", default_value_t = 0.0, value_parser = crate::options::parse_finite, allow_hyphen_values = true)]
    pub plot_from: f64,
}

/// Orbit points and switch markers of one run inside the plotted window.
pub fn orbit(
    samples: &[rotor_rub::Sample],
    events: &[Event],
    window: std::ops::RangeInclusive<f64>,
    color: plotters::style::RGBColor,
    dashed: bool,
) -> Orbit {
    let at = |kind| {
        events
            .iter()
            .filter(|e| e.kind == kind && window.contains(&e.time))
            .map(|e| (e.state.x, e.state.y))
            .collect()
    };
    Orbit {
        color,
        dashed,
        points: samples.iter().map(|s| (s.state.x, s.state.y)).collect(),
        enters: at(EventKind::Enter),
        exits: at(EventKind::Exit),
        marks: crate::friction_fig::friction_marks(events, &window),
    }
}

/// Legend of an analytic-vs-reference orbit figure.
pub fn legend(analytic: &Options, reference: &Options) -> Vec<(LegendMark, String)> {
    vec![
        (LegendMark::Line(ANALYTIC), describe(analytic)),
        (LegendMark::Dashed(REFERENCE), describe(reference)),
        (LegendMark::Line(plot::CLEARANCE), "clearance z = 1".into()),
        (LegendMark::Dot(ENTER), "contact start".into()),
        (LegendMark::Dot(EXIT), "contact end".into()),
        (LegendMark::Ring(ENTER), "(hollow: reference)".into()),
    ]
}

fn fmt_opt(x: Option<f64>) -> String {
    x.map_or_else(|| "-".to_string(), |v| format!("{v:.3e}"))
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let problem = match crate::model_file::target(args.model.as_deref(), &args.problem)? {
        crate::model_file::Target::Planar(problem) => problem,
        crate::model_file::Target::Matrix(subject) => {
            return matrix::run(args, &subject, args.model.as_deref());
        }
    };
    let end = args.time.end_time(&problem.params);
    let analytic = args.scheme.cli_options(Method::Analytic)?;
    let reference = reference_options(args.reference, args.reference_tol)?;
    let period = problem.params.forcing_period();
    let periods = (end - problem.start_time) / period;
    if !(0.0..periods).contains(&args.plot_from) {
        return Err(CliError::input(format!(
            "--plot-from {} is outside the run: it must be in [0, {}) (forcing periods)",
            num(args.plot_from),
            num(periods)
        )));
    }
    let from = problem.start_time + args.plot_from * period;
    let orbit_samples = dense_count(from, end, period, 100);
    // Both runs keep their orbit samples; the plot holds them again.
    fits_memory(
        "orbit samples (100 per plotted forcing period, two runs)",
        orbit_samples,
        4 * std::mem::size_of::<rotor_rub::Sample>(),
    )?;
    let budget = args.limits.budget();
    budget.plan("orbit samples (two runs)", orbit_samples.saturating_mul(2))?;
    let csv_path = args.out_dir.join("compare.csv");
    let [svg_path, png_path] = plot::beside(&csv_path);
    check_distinct(
        &[
            ("--out-dir", csv_path.as_path()),
            ("--out-dir", svg_path.as_path()),
            ("--out-dir", png_path.as_path()),
        ],
        &args.problem.input_files(),
    )?;
    let pa = trajectory::start(&problem, &analytic)?;
    let pr = trajectory::start(&problem, &reference)?;
    let (run_a, samples_a) = trajectory::run_collect(
        pa,
        end,
        dense_times(from, end, period, 100),
        &mut budget.run(problem.start_time, end),
    )?;
    let (run_r, samples_r) = trajectory::run_collect(
        pr,
        end,
        dense_times(from, end, period, 100),
        &mut budget.run(problem.start_time, end),
    )?;
    let resolution =
        rotor_rub::compare::contact_resolution(analytic.tolerance(), reference.tolerance());
    let ends = [&run_a.last, &run_r.last].map(|s| Some((s.time, s.state)));
    let matching = Matching::new(&run_a.events, &run_r.events, end).set_aside_shallow(
        &problem.params,
        resolution,
        ends,
    );

    let (name_a, name_r) = ("analytic", args.reference.name());
    let mut report = String::new();
    let _ = writeln!(
        report,
        "{:>5}  {:<5}  {:>22}  {:>22}  {:>10}  {:>10}",
        "#", "kind", name_a, name_r, "Δτ", "|Δstate|"
    );
    for (i, pair) in matching.pairs.iter().enumerate() {
        let kind = pair.a.or(pair.b).map_or("", |e| e.kind.name());
        let tau = |e: Option<Event>| e.map_or_else(|| "-".to_string(), |e| e.time.to_string());
        let _ = writeln!(
            report,
            "{:>5}  {:<5}  {:>22}  {:>22}  {:>10}  {:>10}",
            i + 1,
            kind,
            tau(pair.a),
            tau(pair.b),
            fmt_opt(pair.dt()),
            fmt_opt(pair.dstate())
        );
    }
    let (fa, fr) = (run_a.last.state.to_array(), run_r.last.state.to_array());
    let final_diff = (0..4).map(|i| (fa[i] - fr[i]).abs()).fold(0.0, f64::max);
    let _ = writeln!(
        report,
        "switches: {name_a} {}, {name_r} {}; matched {} (same kind, less than {MATCH_GAP} apart), unmatched {}",
        run_a.events.len(),
        run_r.events.len(),
        matching.matched(),
        matching.unmatched()
    );
    if matching.shallow > 0 {
        let _ = writeln!(
            report,
            "set aside: {} switches of contacts only one run has, shallower than both runs resolve (z − 1 < {resolution:.0e})",
            matching.shallow
        );
    }
    let _ = writeln!(
        report,
        "largest differences: switch time {}, state at a switch {}, final state {final_diff:.3e}",
        fmt_opt(matching.max_dt()),
        fmt_opt(matching.max_dstate())
    );
    let _ = writeln!(
        report,
        "run time: {name_a} {:.3} ms, {name_r} {:.3} ms",
        run_a.elapsed.as_secs_f64() * 1e3,
        run_r.elapsed.as_secs_f64() * 1e3
    );

    ensure_dir(&args.out_dir)?;
    let mut csv = CsvOut::create(
        &csv_path,
        &["kind", "tau_analytic", "tau_reference", "dtau", "dstate"],
    )?;
    for pair in &matching.pairs {
        let kind = pair.a.or(pair.b).map_or("", |e| e.kind.name());
        csv.row((
            kind,
            pair.a.map(|e| e.time),
            pair.b.map(|e| e.time),
            pair.dt(),
            pair.dstate(),
        ))?;
    }
    let figure = OrbitFigure {
        title: format!(
            "{name_a} vs {name_r}: η = {}, τ from {} to {}",
            num(problem.params.speed_ratio),
            num(from),
            num(end)
        ),
        legend: legend(&analytic, &reference),
        panels: vec![Panel {
            title: String::new(),
            offset: (problem.params.offset_x, problem.params.offset_y),
            orbits: vec![
                orbit(&samples_a, &run_a.events, from..=end, ANALYTIC, false),
                orbit(&samples_r, &run_r.events, from..=end, REFERENCE, true),
            ],
        }],
        columns: 1,
        panel: (1100, 1000),
    };
    let [svg_file, png_file] = plot::render(&figure, &svg_path, &png_path)?;
    commit_all([csv.finish()?, svg_file, png_file])?;
    let _ = writeln!(
        report,
        "wrote {}, {}, {}",
        csv_path.display(),
        svg_path.display(),
        png_path.display()
    );
    stdio::out(&report)
}
