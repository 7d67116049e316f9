//! `rotor-rub compare`: the analytic method against a numerical reference for one parameter set.

use std::path::PathBuf;

use rotor_rub::{Event, EventKind, Method, Options};

use crate::analysis::switches::{MATCH_GAP, Matching};
use crate::error::Result;
use crate::options::{
    SchemeArgs, TimeArgs, describe, parse_positive, parse_reference, reference_help,
};
use crate::output::{CsvOut, ensure_dir};
use crate::plot::orbit::{Orbit, OrbitFigure, Panel};
use crate::plot::{self, ANALYTIC, ENTER, EXIT, LegendMark, REFERENCE};
use crate::problem::ProblemArgs;
use crate::trajectory::{self, dense_times};

/// Compare the analytic method with a numerical reference: switch table, largest differences,
/// both orbits in one plot.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub time: TimeArgs,

    #[command(flatten)]
    pub scheme: SchemeArgs,

    #[arg(long, value_name = "METHOD", default_value = "dop853", value_parser = parse_reference, help = reference_help())]
    pub reference: Method,

    /// Tolerance of the reference method, > 0 [default: 1e-10]
    #[arg(long, value_name = "TOL", value_parser = parse_positive, allow_hyphen_values = true)]
    pub reference_tol: Option<f64>,

    /// Directory for compare.csv (the switch table), compare.svg and compare.png (the orbits)
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out_dir: PathBuf,

    /// Plot the orbits from this forcing period on (0 = from the start)
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
    let problem = args.problem.build()?;
    let end = args.time.end_time(&problem.params);
    let analytic = args.scheme.options(Method::Analytic)?;
    let reference = Options {
        tol: args.reference_tol,
        ..Options::with_method(args.reference)
    };
    let pa = trajectory::start(&problem, &analytic)?;
    let pr = trajectory::start(&problem, &reference)?;
    let period = problem.params.forcing_period();
    let from = (args.plot_from * period).clamp(0.0, end);
    let (run_a, samples_a) = trajectory::run_collect(pa, end, dense_times(from, end, period, 100))?;
    let (run_r, samples_r) = trajectory::run_collect(pr, end, dense_times(from, end, period, 100))?;
    let matching = Matching::new(&run_a.events, &run_r.events, end);

    let (name_a, name_r) = ("analytic", args.reference.name());
    println!(
        "{:>5}  {:<5}  {:>22}  {:>22}  {:>10}  {:>10}",
        "#", "kind", name_a, name_r, "Δτ", "|Δstate|"
    );
    for (i, pair) in matching.pairs.iter().enumerate() {
        let kind = pair.a.or(pair.b).map_or("", |e| e.kind.name());
        let tau = |e: Option<Event>| e.map_or_else(|| "-".to_string(), |e| e.time.to_string());
        println!(
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
    println!(
        "switches: {name_a} {}, {name_r} {}; matched {} (same kind, less than {MATCH_GAP} apart), unmatched {}",
        run_a.events.len(),
        run_r.events.len(),
        matching.matched(),
        matching.unmatched()
    );
    println!(
        "largest differences: switch time {}, state at a switch {}, final state {final_diff:.3e}",
        fmt_opt(matching.max_dt()),
        fmt_opt(matching.max_dstate())
    );
    println!(
        "run time: {name_a} {:.3} ms, {name_r} {:.3} ms",
        run_a.elapsed.as_secs_f64() * 1e3,
        run_r.elapsed.as_secs_f64() * 1e3
    );

    ensure_dir(&args.out_dir)?;
    let csv_path = args.out_dir.join("compare.csv");
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
            "{name_a} vs {name_r}: η = {}, τ from {from:.4} to {end:.4}",
            problem.params.speed_ratio
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
    let [svg, png] = plot::save_beside(&figure, &csv_path)?;
    csv.commit()?;
    println!(
        "wrote {}, {}, {}",
        csv_path.display(),
        svg.display(),
        png.display()
    );
    Ok(())
}
