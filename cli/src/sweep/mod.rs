//! `rotor-rub sweep`: a bifurcation diagram, Poincaré points over a range of one parameter, in
//! parallel, optionally one shard of it.

use std::io::Write;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rotor_rub::{Options, Problem, State};

use crate::error::{CliError, Result, num};
use crate::limits::{Budget, LimitArgs, add_counts, fits_memory, reserve};
use crate::options::{MethodArgs, Survey, describe, parse_finite};
use crate::output::{AtomicFile, check_distinct, commit_all, ensure_parent};
use crate::plot::{self, scatter::BifurcationFigure};
use crate::problem::ProblemArgs;
use crate::shard::{ShardInfo, checksum};
use crate::stdio;
use crate::trajectory::{self, uniform_at};

mod matrix;
mod range;

pub use matrix::{ModelParam, SweepParam, parse_sweep_param};

pub use range::{DEFAULT_TO, last_value, parse_shard};
use range::{run_description, shard_len};

/// Header of sweep files.
pub const HEADER: [&str; 6] = ["value", "period", "x", "y", "vx", "vy"];

/// One row: value, period index, x, y, vx, vy.
pub type Row = (f64, u64, f64, f64, f64, f64);

/// Bifurcation diagram over one parameter. Each value runs from the same initial state;
/// the Poincaré points are the states at τ = k·2π/η for the kept periods k.
#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    pub problem: ProblemArgs,

    /// A rotor from matrices (TOML or .npz, SI units: docs/MODEL_FILES.md) instead of the
    /// paper's model: --param speed (Ω, rad/s; C and K re-evaluated per speed when the file
    /// lists them), clearance (m), contact_stiffness (N/m, K_c = k·I) or friction_coefficient;
    /// the points are the rub station's relative state (rub_x, rub_y, rub_vx, rub_vy, SI)
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

    /// Parameter to sweep: a --set name; with --model one of speed, clearance,
    /// contact_stiffness, friction_coefficient
    #[arg(long, value_name = "NAME", default_value = "speed_ratio", value_parser = parse_sweep_param)]
    pub param: SweepParam,

    /// First value
    #[arg(long, value_name = "VALUE", default_value_t = 1.0, value_parser = parse_finite, allow_hyphen_values = true)]
    pub from: f64,

    /// Last value, different from --from [default: 3.5]; with --steps 1 (--from alone) leave it
    /// out or give it equal to --from
    #[arg(long, value_name = "VALUE", value_parser = parse_finite, allow_hyphen_values = true)]
    pub to: Option<f64>,

    /// Number of values, evenly spaced from --from to --to inclusive (value_i = from + (to −
    /// from)·i/(steps − 1)); 1 runs --from alone
    #[arg(long, value_name = "N", default_value_t = 101, value_parser = crate::options::at_least(1))]
    pub steps: u64,

    /// Forcing periods skipped as transient before the Poincaré points are kept
    #[arg(long, value_name = "P", default_value_t = 200, value_parser = crate::options::at_least(0))]
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
    /// drawn for a shard; join the shards with `rotor-rub merge`. A shard file starts with one
    /// `# rotor-rub sweep shard I/N; …` metadata line (rows, checksum, the run) that merge checks
    #[arg(long, value_name = "I/N", value_parser = parse_shard, allow_hyphen_values = true)]
    pub shard: Option<(usize, usize)>,

    /// Leave out values whose propagation fails (reported on stderr) instead of stopping
    #[arg(long)]
    pub skip_errors: bool,

    /// Do not draw the plot
    #[arg(long)]
    pub no_plot: bool,
}

/// The Poincaré section of one problem: the states at the forcing-period boundaries
/// `transient .. transient + keep`, the work charged to `budget`.
pub fn section(
    problem: &Problem,
    options: &Options,
    transient: u64,
    keep: u64,
    budget: &Budget,
) -> Result<Vec<State>> {
    let mut propagator = trajectory::start(problem, options)?;
    let period = problem.params.forcing_period();
    let start = transient as f64 * period;
    let mut tracker = budget.run(problem.start_time, (transient + keep) as f64 * period);
    trajectory::advance_to(&mut propagator, start, &mut tracker, |_| Ok(()))?;
    let keep = usize::try_from(keep).unwrap_or(usize::MAX);
    let points = trajectory::section(
        &mut propagator,
        problem.params.speed_ratio,
        keep,
        &mut tracker,
    )?;
    Ok(points.iter().map(|sample| sample.state).collect())
}

/// [`section`] of every problem, in parallel (rayon's pool of the caller), one result per
/// problem in their order; `done` is called as each finishes (a progress bar). Each problem's
/// result depends on it alone: any split of `problems` gives the same bits.
pub fn sections<K: Sync>(
    problems: &[(K, Problem)],
    options: &Options,
    transient: u64,
    keep: u64,
    budget: &Budget,
    label: impl Fn(&K) -> String + Sync,
    done: impl Fn() + Sync,
) -> Vec<Result<Vec<State>>> {
    problems
        .par_iter()
        .map(|(key, problem)| {
            let r = section(problem, options, transient, keep, budget)
                .map_err(|e| e.context(&label(key)));
            done();
            r
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

/// Draw the bifurcation diagram of `rows` next to `csv` (uncommitted).
pub fn plot_rows(
    rows: &[Row],
    parameter: &str,
    subtitle: &str,
    csv: &Path,
) -> Result<[AtomicFile; 2]> {
    let figure = BifurcationFigure {
        title: format!("Bifurcation diagram over {parameter}{subtitle}"),
        parameter: parameter.to_string(),
        points: rows.iter().map(|r| (r.0, r.2)).collect(),
    };
    plot::render_beside(&figure, csv)
}

/// Run the command.
pub fn run(args: &Args) -> Result<()> {
    let base = match crate::model_file::target(args.model.as_deref(), &args.problem)? {
        crate::model_file::Target::Planar(problem) => problem,
        crate::model_file::Target::Matrix(subject) => {
            let to = last_value(args)?;
            return matrix::run(args, &subject, args.model.as_deref(), to);
        }
    };
    let param = match args.param {
        SweepParam::Table(p) => p,
        SweepParam::Model(p) => {
            return Err(CliError::input(format!(
                "--param {p} is a model-file parameter: give the model with --model FILE"
            )));
        }
    };
    if args.columns.is_some() {
        return Err(CliError::input(
            "--columns applies only to a model file (--model) or the stator ring with mass (stator_mass_ratio > 0)",
        ));
    }
    let options = args.method.options()?;
    let to = last_value(args)?;
    add_counts(("--transient", args.transient), ("--keep", args.keep))?;
    let (shard, shards) = args.shard.unwrap_or((0, 1));
    let (shard, shards) = (shard as u64, shards as u64);
    let count = shard_len(args.steps, shard, shards);
    fits_memory(
        "--steps (values run here)",
        count,
        std::mem::size_of::<Problem>(),
    )?;
    let rows_planned = count.saturating_mul(args.keep);
    // Rows are kept, then written out (about 120 bytes of CSV each) before the file is replaced.
    fits_memory(
        "--steps × --keep (rows)",
        rows_planned,
        std::mem::size_of::<Row>() + 120,
    )?;
    let budget = args.limits.budget();
    budget.plan("--steps × --keep", rows_planned)?;
    let plot = args.shard.is_none() && !args.no_plot;
    let [svg, png] = plot::beside(&args.out);
    let mut outputs = vec![("--out", args.out.as_path())];
    if plot {
        outputs.extend([("the plot", svg.as_path()), ("the plot", png.as_path())]);
    }
    check_distinct(&outputs, &args.problem.input_files())?;
    // Check every value before anything runs or any file is created.
    let mut problems: Vec<(f64, Problem)> = Vec::new();
    reserve(&mut problems, count as usize, "--steps (values run here)")?;
    for k in 0..count {
        let v = uniform_at(args.from, to, args.steps, shard + k * shards);
        let mut p = base;
        param.set(&mut p, v);
        p.validate()
            .map_err(|e| CliError::input(format!("--param {param} = {} (swept): {e}", num(v))))?;
        problems.push((v, p));
    }
    trajectory::start(&base, &options)?;
    ensure_parent(&args.out)?;
    let mut file = AtomicFile::create(&args.out)?;

    let bar = stdio::progress(
        problems.len() as u64,
        "{bar:40} {pos}/{len} values, {elapsed} elapsed, ETA {eta}",
    );
    let results = sections(
        &problems,
        &options,
        args.transient,
        args.keep,
        &budget,
        |v| format!("{param} = {}", num(*v)),
        || bar.inc(1),
    );
    bar.finish_and_clear();

    let mut rows = Vec::new();
    reserve(&mut rows, rows_planned as usize, "--steps × --keep (rows)")?;
    for ((v, _), r) in problems.iter().zip(results) {
        match r {
            Ok(points) => rows.extend(
                points
                    .iter()
                    .zip(args.transient..)
                    .map(|(s, k)| (*v, k, s.x, s.y, s.vx, s.vy)),
            ),
            // A refused run (over --max-work) stops the sweep even with --skip-errors.
            Err(e) if args.skip_errors && e.code != crate::error::EXIT_INPUT => {
                stdio::warn(&format!("skipped {e}"));
            }
            Err(e) => return Err(e),
        }
    }
    sort_rows(&mut rows, |r| (r.0, r.1));
    let body = csv_bytes(&rows)
        .map_err(|e| CliError::failure(format!("cannot write {}: {e}", args.out.display())))?;
    if args.shard.is_some() {
        let info = ShardInfo {
            index: shard,
            count: shards,
            rows: rows.len() as u64,
            checksum: checksum(&body),
            run: run_description(args, to, &base, &options),
        };
        file.write_all(info.line().as_bytes())
            .map_err(|e| CliError::failure(format!("cannot write {}: {e}", args.out.display())))?;
    }
    file.write_all(&body)
        .map_err(|e| CliError::failure(format!("cannot write {}: {e}", args.out.display())))?;
    let mut files = vec![file];
    if plot {
        let subtitle = format!(
            ", periods {}-{}, {}",
            args.transient,
            args.transient + args.keep,
            describe(&options)
        );
        files.extend(plot_rows(&rows, param.name(), &subtitle, &args.out)?);
    }
    commit_all(files)?;
    let slice = if shards > 1 {
        format!("shard {shard}/{shards}: {count} of {} values", args.steps)
    } else {
        format!("{} values", args.steps)
    };
    let mut report = format!(
        "{slice} of {} from {} to {}, {} Poincaré points written to {}\n",
        args.param,
        num(args.from),
        num(to),
        rows.len(),
        args.out.display()
    );
    if plot {
        report += &format!("plot written to {} and {}\n", svg.display(), png.display());
    }
    stdio::out(&report)
}

/// The CSV text of a sweep file: header, then `rows`.
pub fn csv_bytes(rows: &[Row]) -> std::result::Result<Vec<u8>, csv::Error> {
    let mut writer = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    writer.write_record(HEADER)?;
    for r in rows {
        writer.serialize(r)?;
    }
    writer.into_inner().map_err(|e| e.into_error().into())
}
