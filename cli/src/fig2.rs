//! The main job (no subcommand, or `fig2`): the paper's Fig. 2, analytic and numerical orbits
//! for six speed ratios side by side, with a table of switch agreement, response class,
//! largest Lyapunov exponent and run times.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Duration;

use rayon::prelude::*;
use rotor_rub::{Event, Method, Options, Parameter, Problem, Sample, State};

use crate::analysis::classify::{Response, classify, distinct_points};
use crate::analysis::lyapunov::largest_exponent;
use crate::analysis::switches::Matching;
use crate::compare::{legend, orbit};
use crate::error::{CliError, Result, num};
use crate::limits::{Budget, LimitArgs, add_counts, fits_memory};
use crate::options::{
    SchemeArgs, describe, parse_positive, parse_reference, reference_help, reference_options,
};
use crate::output::{check_distinct, ensure_dir};
use crate::plot::orbit::{OrbitFigure, Panel};
use crate::plot::{self, ANALYTIC, REFERENCE};
use crate::problem::ProblemArgs;
use crate::stdio;
use crate::trajectory::{self, dense_times, period_times};

/// Options of the main job. The defaults reproduce Fig. 2; smaller values give a quick check.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub scheme: SchemeArgs,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[arg(long, value_name = "METHOD", default_value = "dop853", value_parser = parse_reference, help = reference_help())]
    pub reference: Method,

    /// Tolerance of the reference method, > 0 [default: 1e-10]
    #[arg(long, value_name = "TOL", value_parser = parse_positive, allow_hyphen_values = true)]
    pub reference_tol: Option<f64>,

    /// Speed ratios η = Ω/ω_n, one panel each (comma-separated; each replaces speed_ratio)
    #[arg(long, value_name = "η,...", value_delimiter = ',', value_parser = parse_positive, allow_hyphen_values = true,
          default_value = "1,1.5,2,2.5,3,3.5")]
    pub speeds: Vec<f64>,

    /// First forcing period plotted (the transient before it is not shown)
    #[arg(long, value_name = "P", default_value_t = 200, value_parser = crate::options::at_least(0))]
    pub plot_from: u64,

    /// Last forcing period plotted
    #[arg(long, value_name = "P", default_value_t = 260, value_parser = crate::options::at_least(0))]
    pub plot_to: u64,

    /// Poincaré section length in forcing periods, from --plot-from on (classifies the response)
    #[arg(long, value_name = "P", default_value_t = 100, value_parser = crate::options::at_least(1))]
    pub section: u64,

    /// Forcing periods of the Lyapunov estimate (renormalised once per period), from --plot-from
    #[arg(long, value_name = "P", default_value_t = 100, value_parser = crate::options::at_least(1))]
    pub lyapunov: u64,

    /// Switch times are compared over the first this many forcing periods (before chaos
    /// separates the two runs)
    #[arg(long, value_name = "P", default_value_t = 20, value_parser = crate::options::at_least(0))]
    pub match_periods: u64,

    /// Directory for fig2.svg and fig2.png
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out_dir: PathBuf,
}

/// One method's results at one speed.
struct MethodResult {
    events: Vec<Event>,
    orbit: Vec<Sample>,
    response: Response,
    distinct: usize,
    lyapunov: f64,
    elapsed: Duration,
}

/// Both methods at one speed.
struct SpeedResult {
    eta: f64,
    offset: (f64, f64),
    analytic: MethodResult,
    reference: MethodResult,
    matching: Matching,
}

fn run_method(
    problem: &Problem,
    options: &Options,
    args: &Args,
    budget: &Budget,
) -> Result<MethodResult> {
    let eta = problem.params.speed_ratio;
    let context = format!("{} at η = {eta}", options.method.name());
    let wrap = |e: CliError| e.context(&context);
    let period = problem.params.forcing_period();
    let end_period = args
        .plot_to
        .max(args.plot_from.saturating_add(args.section));
    let end = end_period as f64 * period;
    let (from, to) = (args.plot_from as f64 * period, args.plot_to as f64 * period);
    // Orbit samples and section points in one time-ordered list, tagged.
    let mut times: Vec<(f64, bool)> = dense_times(from, to, period, 100)
        .map(|t| (t, false))
        .chain(period_times(args.plot_from, period, args.section).map(|t| (t, true)))
        .collect();
    times.sort_by(|a, b| a.0.total_cmp(&b.0));
    let propagator = trajectory::start(problem, options).map_err(wrap)?;
    let mut tracker = budget.run(problem.start_time, end);
    let (pass, samples) =
        trajectory::run_collect(propagator, end, times.iter().map(|t| t.0), &mut tracker)
            .map_err(wrap)?;
    let (mut orbit, mut section) = (Vec::new(), Vec::<State>::new());
    for (sample, &(_, is_section)) in samples.iter().zip(&times) {
        if is_section {
            section.push(sample.state);
        } else {
            orbit.push(*sample);
        }
    }
    let start = Problem {
        initial: section.first().copied().unwrap_or(problem.initial),
        start_time: from,
        ..*problem
    };
    let lyapunov = largest_exponent(&start, options, period, args.lyapunov as usize)
        .map_err(|e| wrap(CliError::propagation("", e)))?;
    Ok(MethodResult {
        events: pass.events,
        orbit,
        response: classify(&section, Some(lyapunov)),
        distinct: distinct_points(&section),
        lyapunov,
        elapsed: pass.elapsed,
    })
}

fn run_speed(
    problem: &Problem,
    args: &Args,
    options: [&Options; 2],
    budget: &Budget,
) -> Result<SpeedResult> {
    let eta = problem.params.speed_ratio;
    let analytic = run_method(problem, options[0], args, budget)?;
    let reference = run_method(problem, options[1], args, budget)?;
    let window = args.match_periods as f64 * problem.params.forcing_period();
    let matching = Matching::new(&analytic.events, &reference.events, window);
    Ok(SpeedResult {
        eta,
        offset: (problem.params.offset_x, problem.params.offset_y),
        analytic,
        reference,
        matching,
    })
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

fn print_table(results: &[SpeedResult], args: &Args, options: [&Options; 2]) -> String {
    let mut report = String::new();
    let _ = writeln!(
        report,
        "Fig. 2: A = {}, N = {}; {} forcing periods per run",
        describe(options[0]),
        describe(options[1]),
        args.plot_to
            .max(args.plot_from.saturating_add(args.section))
    );
    let _ = writeln!(
        report,
        "switch times: matched switches over forcing periods 0-{}; class: Poincaré section over periods {}-{} (points = distinct points) and largest Lyapunov exponent λ per unit τ (Benettin, {} periods from period {}); times: propagation wall time (speeds run in parallel)",
        args.match_periods,
        args.plot_from,
        args.plot_from + args.section,
        args.lyapunov,
        args.plot_from
    );
    let mut row = |cells: [&str; 12]| {
        let _ = writeln!(
            report,
            "{:>5} | {:>11} | {:>9} | {:>9} | {:<22} {:>6} {:>8} | {:<22} {:>6} {:>8} | {:>10} {:>10}",
            cells[0],
            cells[1],
            cells[2],
            cells[3],
            cells[4],
            cells[5],
            cells[6],
            cells[7],
            cells[8],
            cells[9],
            cells[10],
            cells[11]
        );
    };
    row([
        "η",
        "switches",
        "matched",
        "max |Δτ|",
        "class A",
        "points",
        "λ A",
        "class N",
        "points",
        "λ N",
        "time A",
        "time N",
    ]);
    for s in results {
        let m = &s.matching;
        let (a, n) = (&s.analytic, &s.reference);
        row([
            &num(s.eta),
            &format!("{}/{}", a.events.len(), n.events.len()),
            &format!("{}/{}", m.matched(), m.pairs.len()),
            &m.max_dt()
                .map_or_else(|| "-".into(), |d| format!("{d:.2e}")),
            &a.response.to_string(),
            &a.distinct.to_string(),
            &format!("{:.4}", a.lyapunov),
            &n.response.to_string(),
            &n.distinct.to_string(),
            &format!("{:.4}", n.lyapunov),
            &ms(a.elapsed),
            &ms(n.elapsed),
        ]);
    }
    report
}

/// Run the main job.
pub fn run(args: &Args) -> Result<()> {
    if args.plot_to <= args.plot_from {
        return Err(CliError::input(format!(
            "--plot-to {} is invalid: it must be > --plot-from ({})",
            args.plot_to, args.plot_from
        )));
    }
    let end_period =
        add_counts(("--plot-from", args.plot_from), ("--section", args.section))?.max(args.plot_to);
    if args.match_periods > end_period {
        return Err(CliError::input(format!(
            "--match-periods {} is past the end of the runs ({end_period} forcing periods): it \
             must be at most {end_period}",
            args.match_periods
        )));
    }
    add_counts(
        ("--plot-from", args.plot_from),
        ("--lyapunov", args.lyapunov),
    )?;
    let runs = 2 * args.speeds.len() as u64;
    let orbit_samples = (args.plot_to - args.plot_from)
        .saturating_mul(100)
        .saturating_add(1);
    let per_run = orbit_samples
        .saturating_add(args.section)
        .saturating_add(args.lyapunov);
    fits_memory(
        "orbit samples and section points (100 per plotted period, per speed and method)",
        per_run.saturating_mul(runs),
        2 * std::mem::size_of::<rotor_rub::Sample>(),
    )?;
    let budget = args.limits.budget();
    budget.plan(
        "--plot-from..--plot-to, --section and --lyapunov over all speeds",
        per_run.saturating_mul(runs),
    )?;
    let svg = args.out_dir.join("fig2.svg");
    let png = args.out_dir.join("fig2.png");
    check_distinct(
        &[("--out-dir", &svg), ("--out-dir", &png)],
        &args.problem.input_files(),
    )?;
    let base = args.problem.build()?;
    let analytic = args.scheme.cli_options(Method::Analytic)?;
    let reference = reference_options(args.reference, args.reference_tol)?;
    let options = [&analytic, &reference];
    let problems = args
        .speeds
        .iter()
        .map(|&eta| {
            let mut problem = base;
            Parameter::SpeedRatio.set(&mut problem, eta);
            problem.validate().map(|()| problem).map_err(|e| {
                CliError::input(format!("invalid parameters at --speeds {}: {e}", num(eta)))
            })
        })
        .collect::<Result<Vec<Problem>>>()?;
    for options in options {
        trajectory::start(&base, options)?;
    }
    let results: Vec<SpeedResult> = problems
        .par_iter()
        .map(|problem| run_speed(problem, args, options, &budget))
        .collect::<Result<_>>()?;
    let mut report = print_table(&results, args, options);

    let letters = "abcdefghijklmnopqrstuvwxyz";
    let panels = results
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let period = std::f64::consts::TAU / s.eta;
            let window = args.plot_from as f64 * period..=args.plot_to as f64 * period;
            Panel {
                title: format!(
                    "({}) η = {}: {}",
                    letters.chars().nth(i % 26).unwrap_or('?'),
                    num(s.eta),
                    s.analytic.response
                ),
                offset: s.offset,
                orbits: vec![
                    orbit(
                        &s.analytic.orbit,
                        &s.analytic.events,
                        window.clone(),
                        ANALYTIC,
                        false,
                    ),
                    orbit(
                        &s.reference.orbit,
                        &s.reference.events,
                        window,
                        REFERENCE,
                        true,
                    ),
                ],
            }
        })
        .collect();
    let figure = OrbitFigure {
        title: format!(
            "Orbits over forcing periods {}-{} (x, y in clearances)",
            args.plot_from, args.plot_to
        ),
        legend: legend(&analytic, &reference),
        panels,
        columns: 3.min(results.len()).max(1),
        panel: (520, 520),
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
