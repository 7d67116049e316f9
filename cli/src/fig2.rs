//! The main job (no subcommand, or `fig2`): the paper's Fig. 2, analytic and numerical orbits
//! for six speed ratios side by side, with a table of switch agreement, response class,
//! largest Lyapunov exponent and run times.

use std::path::PathBuf;
use std::time::Duration;

use rayon::prelude::*;
use rotor_rub::{Event, Method, Options, Parameter, Problem, Sample, State};

use crate::analysis::classify::{Response, classify, distinct_points};
use crate::analysis::lyapunov::largest_exponent;
use crate::analysis::switches::Matching;
use crate::compare::{legend, orbit};
use crate::error::{CliError, Result};
use crate::options::{SchemeArgs, describe, parse_positive, parse_reference, reference_help};
use crate::output::ensure_dir;
use crate::plot::orbit::{OrbitFigure, Panel};
use crate::plot::{self, ANALYTIC, REFERENCE};
use crate::problem::ProblemArgs;
use crate::trajectory::{self, dense_times, period_times};

/// Options of the main job. The defaults reproduce Fig. 2; smaller values give a quick check.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub scheme: SchemeArgs,

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
    #[arg(long, value_name = "P", default_value_t = 200)]
    pub plot_from: u64,

    /// Last forcing period plotted
    #[arg(long, value_name = "P", default_value_t = 260)]
    pub plot_to: u64,

    /// Poincaré section length in forcing periods, from --plot-from on (classifies the response)
    #[arg(long, value_name = "P", default_value_t = 100, value_parser = crate::options::at_least(1))]
    pub section: u64,

    /// Forcing periods of the Lyapunov estimate (renormalised once per period), from --plot-from
    #[arg(long, value_name = "P", default_value_t = 100, value_parser = crate::options::at_least(1))]
    pub lyapunov: u64,

    /// Switch times are compared over the first this many forcing periods (before chaos
    /// separates the two runs)
    #[arg(long, value_name = "P", default_value_t = 20)]
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

fn run_method(problem: &Problem, options: &Options, args: &Args) -> Result<MethodResult> {
    let eta = problem.params.speed_ratio;
    let context = format!("{} at η = {eta}", options.method.name());
    let wrap = |e: CliError| e.context(&context);
    let period = problem.params.forcing_period();
    let end_period = args.plot_to.max(args.plot_from + args.section);
    let end = end_period as f64 * period;
    let (from, to) = (args.plot_from as f64 * period, args.plot_to as f64 * period);
    // Orbit samples and section points in one time-ordered list, tagged.
    let mut times: Vec<(f64, bool)> = dense_times(from, to, period, 100)
        .map(|t| (t, false))
        .chain(period_times(args.plot_from, period, args.section).map(|t| (t, true)))
        .collect();
    times.sort_by(|a, b| a.0.total_cmp(&b.0));
    let propagator = trajectory::start(problem, options).map_err(wrap)?;
    let (pass, samples) =
        trajectory::run_collect(propagator, end, times.iter().map(|t| t.0)).map_err(wrap)?;
    let (mut orbit, mut section) = (Vec::new(), Vec::<State>::new());
    for (sample, &(_, is_section)) in samples.iter().zip(&times) {
        if is_section {
            section.push(sample.state);
        } else {
            orbit.push(*sample);
        }
    }
    let start = Problem {
        initial: section[0],
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

fn run_speed(problem: &Problem, args: &Args, options: [&Options; 2]) -> Result<SpeedResult> {
    let eta = problem.params.speed_ratio;
    let analytic = run_method(problem, options[0], args)?;
    let reference = run_method(problem, options[1], args)?;
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

fn print_table(results: &[SpeedResult], args: &Args, options: [&Options; 2]) {
    println!(
        "Fig. 2: A = {}, N = {}; {} forcing periods per run",
        describe(options[0]),
        describe(options[1]),
        args.plot_to.max(args.plot_from + args.section)
    );
    println!(
        "switch times: matched switches over forcing periods 0-{}; class: Poincaré section over periods {}-{} (points = distinct points) and largest Lyapunov exponent λ per unit τ (Benettin, {} periods from period {}); times: propagation wall time (speeds run in parallel)",
        args.match_periods,
        args.plot_from,
        args.plot_from + args.section,
        args.lyapunov,
        args.plot_from
    );
    let row = |cells: [&str; 12]| {
        println!(
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
            &s.eta.to_string(),
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
}

/// Run the main job.
pub fn run(args: &Args) -> Result<()> {
    if args.plot_to <= args.plot_from {
        return Err(CliError::input(format!(
            "--plot-to {} is invalid: it must be > --plot-from ({})",
            args.plot_to, args.plot_from
        )));
    }
    let base = args.problem.build()?;
    let analytic = args.scheme.options(Method::Analytic)?;
    let reference = Options {
        tol: args.reference_tol,
        ..Options::with_method(args.reference)
    };
    let options = [&analytic, &reference];
    let problems =
        args.speeds
            .iter()
            .map(|&eta| {
                let mut problem = base;
                Parameter::SpeedRatio.set(&mut problem, eta);
                problem.validate().map(|()| problem).map_err(|e| {
                    CliError::input(format!("invalid parameters at --speeds {eta}: {e}"))
                })
            })
            .collect::<Result<Vec<Problem>>>()?;
    for options in options {
        trajectory::start(&base, options)?;
    }
    let results: Vec<SpeedResult> = problems
        .par_iter()
        .map(|problem| run_speed(problem, args, options))
        .collect::<Result<_>>()?;
    print_table(&results, args, options);

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
                    s.eta,
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
    let svg = args.out_dir.join("fig2.svg");
    let png = args.out_dir.join("fig2.png");
    plot::save(&figure, &svg, &png)?;
    println!("figures written to {} and {}", svg.display(), png.display());
    Ok(())
}
