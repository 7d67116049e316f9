//! `rotor-rub poincare`: the Poincaré section (the state once per forcing period) as CSV and a
//! scatter plot, with the response class.

use std::fmt::Write as _;
use std::path::PathBuf;

use rotor_rub::{Options, Problem, State};

use crate::analysis::classify::{POINT_TOLERANCE, Response, classify, distinct_points};
use crate::analysis::lyapunov::largest_exponent_checked;
use crate::error::{Result, num};
use crate::limits::{Budget, LimitArgs, add_counts, fits_memory};
use crate::options::{MethodArgs, Survey, describe};
use crate::output::{CsvOut, check_distinct, commit_all, ensure_parent};
use crate::plot::{self, scatter::SectionFigure};
use crate::problem::ProblemArgs;
use crate::stdio;
use crate::trajectory;

/// Poincaré section: the state at τ = k·2π/η for the kept forcing periods k.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub method: MethodArgs<Survey>,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// Forcing periods skipped as transient
    #[arg(long, value_name = "P", default_value_t = 200, value_parser = crate::options::at_least(0))]
    pub transient: u64,

    /// Forcing periods kept (section points), >= 1
    #[arg(long, value_name = "P", default_value_t = 100, value_parser = crate::options::at_least(1))]
    pub keep: u64,

    /// Also estimate the largest Lyapunov exponent over the kept periods (Benettin), to tell
    /// quasi-periodic from chaotic motion
    #[arg(long)]
    pub lyapunov: bool,

    /// Output CSV, header period,x,y,vx,vy; the plot goes next to it (.svg and .png)
    #[arg(long, value_name = "FILE.csv", default_value = "out/poincare.csv")]
    pub out: PathBuf,
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let problem = args.problem.build()?;
    let options = args.method.options()?;
    let end_period = add_counts(("--transient", args.transient), ("--keep", args.keep))?;
    let keep = fits_memory("--keep", args.keep, std::mem::size_of::<State>() * 2)?;
    let budget = args.limits.budget();
    let lyapunov_work = if args.lyapunov { args.keep } else { 0 };
    budget.plan("--keep", args.keep.saturating_add(lyapunov_work))?;
    let [svg, png] = plot::beside(&args.out);
    check_distinct(
        &[
            ("--out", args.out.as_path()),
            ("the plot", svg.as_path()),
            ("the plot", png.as_path()),
        ],
        &args.problem.input_files(),
    )?;
    ensure_parent(&args.out)?;
    let mut out = CsvOut::create(&args.out, &["period", "x", "y", "vx", "vy"])?;
    let Section {
        points,
        lyapunov,
        response,
    } = section(
        &problem,
        &options,
        args.transient,
        keep,
        args.lyapunov,
        &budget,
    )?;
    for (s, k) in points.iter().zip(args.transient..) {
        out.row((k, s.x, s.y, s.vx, s.vy))?;
    }
    let figure = SectionFigure {
        title: format!(
            "Poincaré section, η = {}, periods {}-{end_period}: {response}",
            num(problem.params.speed_ratio),
            args.transient,
        ),
        offset: (problem.params.offset_x, problem.params.offset_y),
        points: points.iter().map(|s| (s.x, s.y)).collect(),
    };
    let [svg_file, png_file] = plot::render(&figure, &svg, &png)?;
    commit_all([out.finish()?, svg_file, png_file])?;
    let mut report = String::new();
    let _ = writeln!(report, "method: {}", describe(&options));
    let _ = writeln!(
        report,
        "section: {} points over forcing periods {}-{end_period}, {} distinct (tolerance {POINT_TOLERANCE:e})",
        points.len(),
        args.transient,
        distinct_points(&points)
    );
    if let Some(l) = lyapunov {
        let _ = writeln!(report, "largest Lyapunov exponent: {l:.5} per unit τ");
    }
    let _ = writeln!(report, "response: {response}");
    let _ = writeln!(
        report,
        "wrote {}, {}, {}",
        args.out.display(),
        svg.display(),
        png.display()
    );
    stdio::out(&report)
}

/// A Poincaré section and what it says.
pub struct Section {
    /// The states at the forcing-period boundaries kept.
    pub points: Vec<State>,
    /// The largest Lyapunov exponent over the kept periods, when asked for.
    pub lyapunov: Option<f64>,
    /// The response class.
    pub response: Response,
}

/// The section of `problem` over `keep` forcing periods after `transient` ones, with the largest
/// Lyapunov exponent over the same periods when `lyapunov` is set (from the first kept point);
/// the work is charged to `budget` (which the caller has planned).
pub fn section(
    problem: &Problem,
    options: &Options,
    transient: u64,
    keep: usize,
    lyapunov: bool,
    budget: &Budget,
) -> Result<Section> {
    let mut propagator = trajectory::start(problem, options)?;
    let period = problem.params.forcing_period();
    let from = transient as f64 * period;
    let end_period = transient.saturating_add(keep as u64);
    let mut tracker = budget.run(problem.start_time, end_period as f64 * period);
    trajectory::advance_to(&mut propagator, from, &mut tracker, |_| Ok(()))?;
    let samples = trajectory::section(
        &mut propagator,
        problem.params.speed_ratio,
        keep,
        &mut tracker,
    )?;
    let points: Vec<State> = samples.iter().map(|s| s.state).collect();
    let lyapunov = match (lyapunov, points.first()) {
        (true, Some(&initial)) => {
            let start = Problem {
                initial,
                start_time: from,
                ..*problem
            };
            Some(largest_exponent_checked(
                &start,
                options,
                period,
                keep,
                |t| budget.check(t),
            )?)
        }
        _ => None,
    };
    let response = classify(&points, lyapunov);
    Ok(Section {
        points,
        lyapunov,
        response,
    })
}
