//! `rotor-rub sweep`: a bifurcation diagram, Poincaré points over a range of one parameter, in
//! parallel, optionally one shard of it.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use rotor_rub::{Options, Parameter, Problem, poincare};

use crate::error::{CliError, Result};
use crate::options::{MethodArgs, Survey, describe, parse_finite};
use crate::output::{CsvOut, ensure_dir};
use crate::plot::{self, scatter::BifurcationFigure};
use crate::problem::{ProblemArgs, parse_parameter};
use crate::trajectory;

/// Header of sweep files.
pub const HEADER: [&str; 6] = ["value", "period", "x", "y", "vx", "vy"];

/// One row: value, period index, x, y, vx, vy.
pub type Row = (f64, u64, f64, f64, f64, f64);

/// `I/N`: shard I of N (0 <= I < N).
pub fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{text}' is not a shard I/N with integers 0 <= I < N");
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// Bifurcation diagram over one parameter. Each value runs from the same initial state;
/// the Poincaré points are the states at τ = k·2π/η for the kept periods k.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    #[command(flatten)]
    pub method: MethodArgs<Survey>,

    /// Parameter to sweep (a --set name)
    #[arg(long, value_name = "NAME", default_value = "speed_ratio", value_parser = parse_parameter)]
    pub param: Parameter,

    /// First value
    #[arg(long, value_name = "VALUE", default_value_t = 1.0, value_parser = parse_finite, allow_hyphen_values = true)]
    pub from: f64,

    /// Last value
    #[arg(long, value_name = "VALUE", default_value_t = 3.5, value_parser = parse_finite, allow_hyphen_values = true)]
    pub to: f64,

    /// Number of values, evenly spaced from --from to --to inclusive (value_i = from + (to −
    /// from)·i/(steps − 1))
    #[arg(long, value_name = "N", default_value_t = 101, value_parser = crate::options::at_least(1))]
    pub steps: u64,

    /// Forcing periods skipped as transient before the Poincaré points are kept
    #[arg(long, value_name = "P", default_value_t = 200)]
    pub transient: u64,

    /// Forcing periods kept: Poincaré points per value
    #[arg(long, value_name = "P", default_value_t = 50, value_parser = crate::options::at_least(1))]
    pub keep: u64,

    /// Output CSV, header value,period,x,y,vx,vy, rows ordered by value (ascending) then
    /// period; the plot goes next to it (same name, .svg and .png)
    #[arg(long, value_name = "FILE.csv", default_value = "out/sweep.csv")]
    pub out: PathBuf,

    /// Run only shard I of N: the values whose index i (0-based, in --from..--to order) has
    /// i % N == I (round robin, so slow and fast regions spread over the shards). No plot is
    /// drawn for a shard; join the shards with `rotor-rub merge`
    #[arg(long, value_name = "I/N", value_parser = parse_shard, allow_hyphen_values = true)]
    pub shard: Option<(usize, usize)>,

    /// Leave out values whose propagation fails (reported on stderr) instead of stopping
    #[arg(long)]
    pub skip_errors: bool,

    /// Do not draw the plot
    #[arg(long)]
    pub no_plot: bool,
}

/// The swept values.
pub fn values(from: f64, to: f64, steps: usize) -> Vec<f64> {
    crate::trajectory::uniform_times(from, to, steps).collect()
}

/// The Poincaré rows of one parameter value.
fn section(
    problem: &Problem,
    options: &Options,
    transient: u64,
    keep: u64,
    value: f64,
) -> Result<Vec<Row>> {
    let mut propagator = trajectory::start(problem, options)?;
    let period = problem.params.forcing_period();
    rotor_rub::advance_to(&mut propagator, transient as f64 * period, |_| {})?;
    poincare(&mut propagator, problem.params.speed_ratio, keep as usize)
        .zip(transient..)
        .map(|(sample, k)| {
            let s = sample?.state;
            Ok((value, k, s.x, s.y, s.vx, s.vy))
        })
        .collect()
}

/// Sort rows into file order: value ascending, then period.
pub fn sort_rows<T>(rows: &mut [T], key: impl Fn(&T) -> (f64, u64)) {
    rows.sort_by(|a, b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.total_cmp(&kb.0).then(ka.1.cmp(&kb.1))
    });
}

/// A progress bar on stderr, hidden when stderr is not a terminal.
fn progress(len: usize) -> ProgressBar {
    let target = if std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(Some(len as u64), target);
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len} values, {elapsed} elapsed, ETA {eta}")
    {
        bar.set_style(style);
    }
    bar
}

/// Draw the bifurcation diagram of `rows` next to `csv`.
pub fn plot_rows(
    rows: &[Row],
    parameter: &str,
    subtitle: &str,
    csv: &Path,
) -> Result<[PathBuf; 2]> {
    let figure = BifurcationFigure {
        title: format!("Bifurcation diagram over {parameter}{subtitle}"),
        parameter: parameter.to_string(),
        points: rows.iter().map(|r| (r.0, r.2)).collect(),
    };
    plot::save_beside(&figure, csv)
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let base = args.problem.build()?;
    let options = args.method.options()?;
    let all = values(args.from, args.to, args.steps as usize);
    let (shard, shards) = args.shard.unwrap_or((0, 1));
    let mine: Vec<(usize, f64)> = all
        .iter()
        .copied()
        .enumerate()
        .filter(|(i, _)| i % shards == shard)
        .collect();
    // Check every value before anything runs or any file is created.
    let problems = mine
        .iter()
        .map(|&(_, v)| {
            let mut p = base;
            args.param.set(&mut p, v);
            p.validate()
                .map(|()| p)
                .map_err(|e| CliError::input(format!("--param {} = {v} (swept): {e}", args.param)))
        })
        .collect::<Result<Vec<Problem>>>()?;
    trajectory::start(&base, &options)?;
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        ensure_dir(dir)?;
    }
    let mut out = CsvOut::create(&args.out, &HEADER)?;

    let bar = progress(mine.len());
    let results: Vec<Result<Vec<Row>>> = mine
        .par_iter()
        .zip(&problems)
        .map(|(&(_, v), p)| {
            let r = section(p, &options, args.transient, args.keep, v)
                .map_err(|e| e.context(&format!("{} = {v}", args.param)));
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();

    let mut rows = Vec::new();
    for r in results {
        match r {
            Ok(r) => rows.extend(r),
            Err(e) if args.skip_errors => eprintln!("warning: skipped {e}"),
            Err(e) => return Err(e),
        }
    }
    sort_rows(&mut rows, |r| (r.0, r.1));
    for r in &rows {
        out.row(r)?;
    }
    let plotted = if args.shard.is_none() && !args.no_plot {
        let subtitle = format!(
            ", periods {}-{}, {}",
            args.transient,
            args.transient + args.keep,
            describe(&options)
        );
        Some(plot_rows(&rows, args.param.name(), &subtitle, &args.out)?)
    } else {
        None
    };
    out.commit()?;
    let slice = if shards > 1 {
        format!(
            "shard {shard}/{shards}: {} of {} values",
            mine.len(),
            all.len()
        )
    } else {
        format!("{} values", all.len())
    };
    println!(
        "{slice} of {} from {} to {}, {} Poincaré points written to {}",
        args.param,
        args.from,
        args.to,
        rows.len(),
        args.out.display()
    );
    if let Some([svg, png]) = plotted {
        println!("plot written to {} and {}", svg.display(), png.display());
    }
    Ok(())
}
