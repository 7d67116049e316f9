//! `rotor-rub poincare`: the Poincaré section (the state once per forcing period) as CSV and a
//! scatter plot, with the response class.

use std::fmt::Write as _;
use std::path::PathBuf;

use rotor_rub::{Options, Problem, State};

use crate::analysis::classify::{POINT_TOLERANCE, Response, classify, distinct_points};
use crate::analysis::lyapunov::largest_exponent_checked;
use crate::error::{CliError, Result, num};
use crate::limits::{Budget, LimitArgs, add_counts, fits_memory};
use crate::model_file::{
    Subject, Target, chosen_columns, orbit_indices, orbit_state, planar_only, target,
};
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

    /// A rotor from matrices (TOML or .npz, SI units: docs/MODEL_FILES.md) instead of the
    /// paper's model: the section of the rub station's relative displacement and velocity
    /// (rub_x, rub_y, rub_vx, rub_vy, m and m/s) once per forcing period 2π/Ω
    #[arg(long, value_name = "FILE", conflicts_with_all = ["preset", "config", "set"])]
    pub model: Option<PathBuf>,

    /// The columns written for a model file or the ring with mass (comma-separated, or `all`):
    /// a model file's DOF names, `v` + a DOF name, rub_x, rub_y, rub_vx, rub_vy [default:
    /// rub_x,rub_y,rub_vx,rub_vy]; the ring's x, y, vx, vy, xs, ys, vxs, vys [default: all]
    #[arg(long, value_name = "NAMES")]
    pub columns: Option<String>,

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

    /// Output CSV, header period,x,y,vx,vy (the ring with mass: then xs,ys,vxs,vys; a model
    /// file: period then --columns, SI); the plot goes next to it (.svg and .png)
    #[arg(long, value_name = "FILE.csv", default_value = "out/poincare.csv")]
    pub out: PathBuf,
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let problem = match target(args.model.as_deref(), &args.problem)? {
        Target::Planar(problem) => problem,
        Target::Matrix(subject) => return run_matrix(args, &subject),
    };
    if args.columns.is_some() {
        return Err(CliError::input(
            "--columns applies only to a model file (--model) or the stator ring with mass (stator_mass_ratio > 0)",
        ));
    }
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

/// `poincare` on a model file or the ring with mass: the chosen columns once per forcing period
/// (SI for a model file), the station's (the rotor's) section plotted in clearances with the
/// clearance circle, the response class of the station's (the rotor's) planar state.
fn run_matrix(args: &Args, subject: &Subject) -> Result<()> {
    if args.lyapunov {
        return Err(planar_only("--lyapunov", subject));
    }
    let options = args.method.options()?;
    subject.check(&options)?;
    let end_period = add_counts(("--transient", args.transient), ("--keep", args.keep))?;
    let picked = chosen_columns(
        subject,
        "--columns",
        args.columns.as_deref(),
        &subject.section_columns(),
    )?;
    let width = subject.columns().len();
    let keep = fits_memory("--keep", args.keep, 8 * (width + 2))?;
    let budget = args.limits.budget();
    budget.plan("--keep", args.keep)?;
    let [svg, png] = plot::beside(&args.out);
    let mut inputs = args.problem.input_files();
    if let Some(m) = &args.model {
        inputs.push(("--model", m.as_path()));
    }
    check_distinct(
        &[
            ("--out", args.out.as_path()),
            ("the plot", svg.as_path()),
            ("the plot", png.as_path()),
        ],
        &inputs,
    )?;
    ensure_parent(&args.out)?;
    let all = subject.columns();
    let header: Vec<&str> = std::iter::once("period")
        .chain(
            picked
                .iter()
                .filter_map(|&i| all.get(i).map(String::as_str)),
        )
        .collect();
    let mut out = CsvOut::create(&args.out, &header)?;
    let period = subject.period();
    let times: Vec<f64> = trajectory::period_times(args.transient, period, keep as u64).collect();
    let mut tracker = budget.run(subject.start_time(), end_period as f64 * period);
    let table = subject.sample(&options, &times, &mut tracker)?;
    let orbit = orbit_indices(subject);
    let mut points = Vec::with_capacity(keep);
    for (row, k) in table.rows().zip(args.transient..) {
        let fields = picked
            .iter()
            .map(|&i| format!("{:?}", row.get(i).copied().unwrap_or(f64::NAN)));
        out.record(std::iter::once(k.to_string()).chain(fields))?;
        points.push(orbit_state(row, &orbit, subject.clearance()));
    }
    let response = classify(&points, None);
    let figure = SectionFigure {
        title: format!(
            "Poincaré section of {}, {}, periods {}-{end_period}: {response}",
            match subject {
                Subject::File { .. } => "the rub station",
                Subject::Ring(_) => "the rotor (ring with mass)",
            },
            subject.speed_label(),
            args.transient,
        ),
        offset: subject.offset(),
        points: points.iter().map(|s| (s.x, s.y)).collect(),
    };
    let [svg_file, png_file] = plot::render(&figure, &svg, &png)?;
    commit_all([out.finish()?, svg_file, png_file])?;
    let mut report = String::new();
    let _ = writeln!(report, "method: {}", describe(&options));
    let _ = writeln!(
        report,
        "section: {} points over forcing periods {}-{end_period} of {} ({}), {} distinct (tolerance {POINT_TOLERANCE:e} clearances)",
        points.len(),
        args.transient,
        crate::error::num(period),
        match subject {
            Subject::File { .. } => "s",
            Subject::Ring(_) => "τ",
        },
        distinct_points(&points)
    );
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
