//! `rotor-rub continue`: the branches of periodic orbits over a range of one parameter
//! (`docs/MODEL.md` §18): the branch CSV ([`super::files`]), the diagram
//! ([`crate::plot::branch`]), optionally over a sweep's points, and a summary of the branches and
//! the bifurcations located.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rotor_rub::{Parameter, Problem};

use super::continuation::{Start, continuation};
use super::evaluate::Evaluator;
use super::start::{Orbits, StartSpec, map_settings, parse_start, start_state};
use super::{Continuation, ContinuationSettings, Kind, files};
use crate::error::{CliError, Result, num};
use crate::limits::{Budget, LimitArgs};
use crate::options::{MethodArgs, Survey, at_least, describe, parse_finite, parse_positive};
use crate::output::{check_distinct, commit_all, ensure_parent};
use crate::plot::branch::{BranchFigure, Curve, Mark};
use crate::plot::{self};
use crate::problem::{ProblemArgs, parse_parameter};
use crate::stdio;

/// Continue periodic orbits over a range of one parameter, with their stability and
/// bifurcations. Each map runs --method (default hybrid) at --tol (default 1e-12 here).
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub method: MethodArgs<Orbits>,

    #[command(flatten)]
    pub limits: LimitArgs,

    /// The parameter continued (a model parameter: a --set name)
    #[arg(long, value_name = "NAME", default_value = "speed_ratio", value_parser = parse_parameter)]
    pub param: Parameter,

    /// Where the range starts (the first branch starts here)
    #[arg(long, value_name = "VALUE", value_parser = parse_finite, allow_hyphen_values = true)]
    pub from: f64,

    /// Where the range ends
    #[arg(long, value_name = "VALUE", value_parser = parse_finite, allow_hyphen_values = true)]
    pub to: f64,

    /// The first branches' period k in forcing periods, in [1, 32]
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = super::command::parse_period)]
    pub period: u32,

    /// A branch start: `simulate` (after --transient periods from the initial state), `free`
    /// (the steady response without contact) or `x,y,vx,vy`, at --from or at `@VALUE`; may be
    /// given more than once (a start on a branch already followed is left out). A branch runs
    /// toward --to, or from a start at --to toward --from
    #[arg(long, value_name = "SPEC[@VALUE]", default_value = "simulate", value_parser = parse_start, allow_hyphen_values = true, action = clap::ArgAction::Append)]
    pub start: Vec<StartSpec>,

    /// Forcing periods simulated before a `simulate` start
    #[arg(long, value_name = "P", default_value_t = 200, value_parser = at_least(0))]
    pub transient: u64,

    /// Follow the period-2k branch born at each period doubling while 2k is at most this
    /// [default: twice --period; --period itself: none]
    #[arg(long, value_name = "K", value_parser = super::command::parse_period)]
    pub max_period: Option<u32>,

    /// Most points of one branch
    #[arg(long, value_name = "N", default_value_t = 3000, value_parser = at_least(2))]
    pub max_points: u64,

    /// The first arclength step, in (x, y, x', y', parameter) [default: 1 % of the range]
    #[arg(long, value_name = "H", value_parser = parse_positive)]
    pub arc_step: Option<f64>,

    /// The largest arclength step [default: 5 % of the range]
    #[arg(long, value_name = "H", value_parser = parse_positive)]
    pub max_arc_step: Option<f64>,

    /// Newton's residual |P^k(s) − s|∞ at which a point is on the branch, relative to
    /// 1 + |s|∞, in [1e-14, 1e-3]
    #[arg(long, value_name = "TOL", default_value = "1e-10", value_parser = parse_positive)]
    pub newton_tol: f64,

    /// Output CSV, one row per point of each branch (bifurcations as rows of their own), header
    /// value,period,max_radius,min_radius,contact_fraction,modulus_1..4,stable,bifurcation,branch,x,y,vx,vy,contacts,multiplier_1_re,multiplier_1_im,…;
    /// the plot goes next to it (.svg and .png)
    #[arg(long, value_name = "FILE.csv", default_value = "out/continuation.csv")]
    pub out: PathBuf,

    /// Draw a sweep file's Poincaré points (`rotor-rub sweep`'s CSV) behind the branches
    #[arg(long, value_name = "FILE.csv", conflicts_with = "sweep")]
    pub behind: Option<PathBuf>,

    /// Run a sweep of N values over the range (taylor, 200 transient and 50 kept periods, as
    /// `rotor-rub sweep`) and draw its points behind the branches
    #[arg(long, value_name = "N", value_parser = at_least(2))]
    pub sweep: Option<u64>,

    /// Do not draw the plot
    #[arg(long)]
    pub no_plot: bool,
}

/// The settings of `args` for `problem`, validated.
fn settings(args: &Args) -> Result<ContinuationSettings> {
    let mut s = ContinuationSettings::new(args.param, args.from, args.to, args.period);
    s.validate()?;
    let span = (args.to - args.from).abs();
    if let Some(h) = args.arc_step {
        s.step = h;
    }
    if let Some(h) = args.max_arc_step {
        s.max_step = h;
    }
    s.step = s.step.min(s.max_step);
    s.min_step = s.min_step.min(1e-7 * span.max(1e-300)).min(s.step);
    s.max_points = usize::try_from(args.max_points).unwrap_or(usize::MAX);
    s.max_period = args.max_period.unwrap_or(2 * args.period);
    if !(1e-14..=1e-3).contains(&args.newton_tol) {
        return Err(CliError::input(format!(
            "--newton-tol = {} is out of range: it must be in [1e-14, 1e-3]",
            num(args.newton_tol)
        )));
    }
    s.tolerance = args.newton_tol;
    Ok(s)
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let base = args.problem.build()?;
    let options = args.method.options()?;
    let mut s = settings(args)?;
    s.map = map_settings(&options);
    let [svg, png] = plot::beside(&args.out);
    let mut outputs = vec![("--out", args.out.as_path())];
    if !args.no_plot {
        outputs.push(("the plot", svg.as_path()));
        outputs.push(("the plot", png.as_path()));
    }
    let mut inputs = args.problem.input_files();
    if let Some(b) = &args.behind {
        inputs.push(("--behind", b.as_path()));
    }
    check_distinct(&outputs, &inputs)?;
    let budget = args.limits.budget();
    let behind = match (&args.behind, args.sweep) {
        (Some(path), _) => read_sweep(path)?,
        (None, Some(n)) => run_sweep(&base, args, n, &budget)?,
        (None, None) => Vec::new(),
    };
    let started = Instant::now();
    let starts = make_starts(&base, args, &options, &budget)?;
    let bar = stdio::progress(0, "{spinner} {pos} map evaluations, {msg} ({elapsed})");
    let name = args.param.info().name;
    let mut poll = |p: f64| {
        bar.inc(1);
        if bar.position().is_multiple_of(64) {
            bar.set_message(format!("{name} = {p:.6}"));
        }
        Ok(())
    };
    let mut ev = Evaluator {
        base: base.params,
        parameter: args.param,
        periods: args.period,
        map: s.map,
        poll: &mut poll,
        evaluations: 0,
    };
    let result = continuation(&mut ev, &starts, &s)?;
    bar.finish_and_clear();
    let elapsed = started.elapsed();
    ensure_parent(&args.out)?;
    let mut files = vec![files::write(&args.out, &result)?];
    if !args.no_plot {
        let figure = figure(&base, args, &options, &result, behind);
        files.extend(plot::render(&figure, &svg, &png)?);
    }
    commit_all(files)?;
    stdio::out(&report(args, &options, &result, elapsed, &svg, &png))
}

/// The starts of `args`, their states made for `base` at each start's value.
fn make_starts(
    base: &Problem,
    args: &Args,
    options: &rotor_rub::Options,
    budget: &Budget,
) -> Result<Vec<Start>> {
    let mut starts = Vec::new();
    for spec in &args.start {
        let value = spec.value.unwrap_or(args.from);
        let (lo, hi) = (args.from.min(args.to), args.from.max(args.to));
        if !(lo..=hi).contains(&value) {
            return Err(CliError::input(format!(
                "--start @{}: the start must lie in the range [{}, {}]",
                num(value),
                num(lo),
                num(hi)
            )));
        }
        let problem = base_at(base, args.param, value)?;
        let guess = start_state(&problem, options, spec.guess, args.transient, budget)?;
        starts.push(Start { guess, value });
    }
    Ok(starts)
}

/// `base` with `param` = `value`, validated.
fn base_at(base: &Problem, param: Parameter, value: f64) -> Result<Problem> {
    let mut p = *base;
    param.set(&mut p, value);
    p.validate().map_err(|e| {
        CliError::input(format!(
            "--param {} = {}: {e}",
            param.info().name,
            num(value)
        ))
    })?;
    Ok(p)
}

/// A sweep over the range: (value, x) of every Poincaré point.
fn run_sweep(base: &Problem, args: &Args, n: u64, budget: &Budget) -> Result<Vec<(f64, f64)>> {
    let options =
        rotor_rub::Options::with_method(<Survey as crate::options::DefaultMethod>::METHOD);
    let mut problems = Vec::new();
    for i in 0..n {
        let v = crate::trajectory::uniform_at(args.from, args.to, n, i);
        problems.push((v, base_at(base, args.param, v)?));
    }
    let results = crate::sweep::sections(
        &problems,
        &options,
        200,
        50,
        budget,
        |v| format!("{} = {}", args.param, num(*v)),
        || {},
    );
    let mut points = Vec::new();
    for ((v, _), r) in problems.iter().zip(results) {
        if let Ok(states) = r {
            points.extend(states.iter().map(|s| (*v, s.x)));
        }
    }
    Ok(points)
}

/// A sweep file's (value, x) points.
fn read_sweep(path: &Path) -> Result<Vec<(f64, f64)>> {
    let fail = |m: String| CliError::input(format!("--behind {}: {m}", path.display()));
    let text = std::fs::read_to_string(path).map_err(|e| fail(format!("cannot read it: {e}")))?;
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let headers = reader.headers().map_err(|e| fail(e.to_string()))?.clone();
    let column = |name: &str| headers.iter().position(|h| h == name);
    let (Some(v), Some(x)) = (column("value"), column("x")) else {
        return Err(fail(
            "not a sweep file: it needs the columns value and x".into(),
        ));
    };
    let mut points = Vec::new();
    for (line, record) in reader.records().enumerate() {
        let record = record.map_err(|e| fail(e.to_string()))?;
        let get = |i: usize| record.get(i).and_then(|t| t.parse::<f64>().ok());
        match (get(v), get(x)) {
            (Some(a), Some(b)) => points.push((a, b)),
            _ => return Err(fail(format!("row {} is not two numbers", line + 2))),
        }
    }
    Ok(points)
}

/// The diagram of `result`.
fn figure(
    base: &Problem,
    args: &Args,
    options: &rotor_rub::Options,
    result: &Continuation,
    sweep: Vec<(f64, f64)>,
) -> BranchFigure {
    let mut curves: Vec<Curve> = Vec::new();
    for branch in &result.branches {
        let points: Vec<_> = result
            .points
            .iter()
            .filter(|p| p.branch == branch.id)
            .collect();
        for j in 0..branch.periods as usize {
            let mut run: Option<Curve> = None;
            for p in &points {
                let x = if j == 0 {
                    p.state().x
                } else {
                    p.solution
                        .eval
                        .point
                        .sections()
                        .get(j - 1)
                        .map_or(f64::NAN, |s| s.x)
                };
                let at = (p.value(), x, p.summary().max_radius);
                match &mut run {
                    Some(c) if c.stable == p.stable() => c.points.push(at),
                    _ => {
                        // A new run starts at the last point of the one before (no gap).
                        let mut first = Vec::new();
                        if let Some(c) = run.take() {
                            first.extend(c.points.last().copied());
                            curves.push(c);
                        }
                        first.push(at);
                        run = Some(Curve {
                            periods: branch.periods,
                            stable: p.stable(),
                            points: first,
                        });
                    }
                }
            }
            curves.extend(run);
        }
    }
    let marks = result
        .bifurcations
        .iter()
        .map(|&i| {
            let p = &result.points[i];
            let label = match p.kind {
                Some(Kind::Fold) => "F",
                Some(Kind::PeriodDoubling) => "PD",
                Some(Kind::NeimarkSacker) => "NS",
                _ => "G",
            };
            Mark {
                label,
                at: (p.value(), p.state().x, p.summary().max_radius),
            }
        })
        .collect();
    let name = args.param.info();
    BranchFigure {
        title: format!(
            "Periodic orbits over {} ({}), preset values otherwise: {} branch(es), {} bifurcations",
            name.name,
            name.symbol,
            result.branches.len(),
            result.bifurcations.len()
        ),
        subtitle: format!(
            "{}; offset ({}, {}), K = ({}, {}, {}, {}), nu = {}",
            describe(&map_settings(options).options),
            num(base.params.offset_x),
            num(base.params.offset_y),
            num(base.params.k_xx),
            num(base.params.k_xy),
            num(base.params.k_yx),
            num(base.params.k_yy),
            num(base.params.damping_ratio)
        ),
        x_label: format!("{} ({})", name.name, name.symbol),
        sweep,
        curves,
        marks,
    }
}

fn report(
    args: &Args,
    options: &rotor_rub::Options,
    result: &Continuation,
    elapsed: std::time::Duration,
    svg: &Path,
    png: &Path,
) -> String {
    let name = args.param.info().name;
    let mut r = String::new();
    let _ = writeln!(
        r,
        "method: {}; monodromy from the segments (variational equations by DOP853, tol {:e})",
        describe(&map_settings(options).options),
        rotor_rub::orbit::DEFAULT_VARIATIONAL_TOL
    );
    for (n, b) in &result.skipped {
        let _ = writeln!(
            r,
            "start {}: on branch {b} already followed, left out",
            n + 1
        );
    }
    for b in &result.branches {
        let points: Vec<_> = result.points.iter().filter(|p| p.branch == b.id).collect();
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, c), p| {
                (a.min(p.value()), c.max(p.value()))
            });
        let from = match b.parent {
            Some(i) => format!(
                ", from the period doubling at {name} = {}",
                num(result.points[i].value())
            ),
            None => String::new(),
        };
        let _ = writeln!(
            r,
            "branch {}: period-{}{from}, {} points over {name} {} .. {}; ended: {}",
            b.id,
            b.periods,
            points.len(),
            num(lo),
            num(hi),
            b.end
        );
    }
    let _ = writeln!(r, "bifurcations located ({}):", result.bifurcations.len());
    for &i in &result.bifurcations {
        let p = &result.points[i];
        let largest = p
            .solution
            .multipliers
            .iter()
            .map(|m| m.abs())
            .fold(0.0, f64::max);
        let _ = writeln!(
            r,
            "  {:<16} {name} = {:.10}  branch {} (period-{}), largest |λ| {:.4}, {} contacts per orbit",
            p.kind.map_or("", |k| k.name()),
            p.value(),
            p.branch,
            p.periods(),
            largest,
            p.summary().count(rotor_rub::EventKind::Enter)
        );
    }
    let _ = writeln!(
        r,
        "{} points, {} map evaluations, {:.2} s",
        result.points.len(),
        result.evaluations,
        elapsed.as_secs_f64()
    );
    let _ = write!(r, "wrote {}", args.out.display());
    if !args.no_plot {
        let _ = write!(r, ", {}, {}", svg.display(), png.display());
    }
    r.push('\n');
    r
}
