//! `sweep` on a matrix model: a model file (`--model FILE --param speed|clearance|
//! contact_stiffness|friction_coefficient`, SI) or the paper's rotor with a stator ring of mass
//! (any table entry, as the planar sweep). Each value runs from the model's start; its points
//! are the chosen columns once per forcing period (2π/Ω at that value's speed).

use std::fmt;
use std::path::Path;

use rayon::prelude::*;
use rotor_rub::Options;

use rotor_rub::Parameter;

use super::Args;
use crate::error::{CliError, Result, num};
use crate::limits::{Budget, add_counts, fits_memory};
use crate::model_file::{Subject, chosen_columns, orbit_indices, orbit_state, planar_only};
use crate::output::{CsvOut, check_distinct, commit_all, ensure_parent};
use crate::plot::{self, scatter::BifurcationFigure};
use crate::problem::parse_parameter;
use crate::stdio;
use crate::trajectory::{period_times, uniform_at};

/// What a sweep over a model file may vary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelParam {
    /// Ω, rad/s: the forcing, the gyroscopic term and, when the file lists them, C and K
    /// (interpolated between the listed speeds; values outside them are refused).
    Speed,
    /// δ, m: the radial clearance (the rub station's gap).
    Clearance,
    /// k, N/m: the contact stiffness, K_c = k·I (isotropic, replacing the file's K_c).
    ContactStiffness,
    /// μ: the friction coefficient (with μ > 0 the file must give the station's radius).
    FrictionCoefficient,
}

impl ModelParam {
    /// Every model-file parameter.
    pub const ALL: [ModelParam; 4] = [
        ModelParam::Speed,
        ModelParam::Clearance,
        ModelParam::ContactStiffness,
        ModelParam::FrictionCoefficient,
    ];

    /// Its name (the `--param` value).
    pub fn name(self) -> &'static str {
        match self {
            ModelParam::Speed => "speed",
            ModelParam::Clearance => "clearance",
            ModelParam::ContactStiffness => "contact_stiffness",
            ModelParam::FrictionCoefficient => "friction_coefficient",
        }
    }

    /// The parameter named `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        ModelParam::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Its axis label (with the unit).
    pub fn label(self) -> &'static str {
        match self {
            ModelParam::Speed => "speed Ω (rad/s)",
            ModelParam::Clearance => "clearance δ (m)",
            ModelParam::ContactStiffness => "contact stiffness k (N/m)",
            ModelParam::FrictionCoefficient => "friction coefficient μ",
        }
    }

    /// `spec` with this parameter set to `value`.
    fn set(self, spec: &mut crate::model_file::ModelSpec, value: f64) {
        match self {
            ModelParam::Speed => spec.speed = value,
            ModelParam::Clearance => spec.rub.clearance = value,
            ModelParam::ContactStiffness => {
                spec.rub.contact_stiffness = [[value, 0.0], [0.0, value]];
            }
            ModelParam::FrictionCoefficient => spec.rub.friction_coefficient = value,
        }
    }
}

impl fmt::Display for ModelParam {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What `--param` names: a table entry (the paper's model, the ring with mass) or a model-file
/// parameter ([`ModelParam`], with `--model`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SweepParam {
    /// A parameter-table entry.
    Table(Parameter),
    /// A model file's parameter.
    Model(ModelParam),
}

impl std::fmt::Display for SweepParam {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SweepParam::Table(p) => write!(f, "{p}"),
            SweepParam::Model(p) => write!(f, "{p}"),
        }
    }
}

/// `--param`: a table entry's name, or a model-file parameter's.
pub fn parse_sweep_param(name: &str) -> Result<SweepParam, String> {
    match parse_parameter(name) {
        Ok(p) => Ok(SweepParam::Table(p)),
        Err(table) => ModelParam::from_name(name.trim())
            .map(SweepParam::Model)
            .ok_or_else(|| format!("{table}; with --model one of {}", names())),
    }
}

/// The subject at each value of the sweep, each checked (an input error naming the value).
fn subjects(
    args: &Args,
    param: SweepParam,
    base: &Subject,
    to: f64,
    options: &Options,
) -> Result<Vec<(f64, Subject)>> {
    let mut out = Vec::new();
    for k in 0..args.steps {
        let v = uniform_at(args.from, to, args.steps, k);
        let subject = match (base, param) {
            (Subject::File { spec, label }, SweepParam::Model(p)) => {
                let mut spec = spec.clone();
                p.set(&mut spec, v);
                Subject::File {
                    spec,
                    label: label.clone(),
                }
            }
            (Subject::Ring(problem), SweepParam::Table(p)) => {
                let mut problem = *problem;
                p.set(&mut problem, v);
                problem.validate().map_err(|e| {
                    CliError::input(format!("--param {p} = {} (swept): {e}", num(v)))
                })?;
                if problem.params.stator_mass_ratio <= 0.0 {
                    return Err(CliError::input(format!(
                        "--param {p} = {} (swept) makes the ring massless (stator_mass_ratio = 0): \
                         a sweep of the ring with mass keeps stator_mass_ratio > 0 (sweep the \
                         massless paper model separately)",
                        num(v)
                    )));
                }
                Subject::Ring(problem)
            }
            (Subject::File { .. }, SweepParam::Table(p)) => {
                return Err(CliError::input(format!(
                    "--param {p} is a parameter of the paper's model; a model file sweeps one of {}",
                    names()
                )));
            }
            (Subject::Ring(_), SweepParam::Model(p)) => {
                return Err(CliError::input(format!(
                    "--param {p} is a model-file parameter (with --model); the ring with mass sweeps a table entry (`rotor-rub params`)"
                )));
            }
        };
        subject
            .check(options)
            .map_err(|e| e.context(&format!("--param {param} = {} (swept)", num(v))))?;
        out.push((v, subject));
    }
    // Rows in file order: value ascending (then period).
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

/// The model-file parameters' names, for messages.
pub fn names() -> String {
    ModelParam::ALL.map(ModelParam::name).join(", ")
}

/// One value's points: the chosen columns at the kept forcing-period boundaries.
fn points(
    subject: &Subject,
    options: &Options,
    args: &Args,
    budget: &Budget,
) -> Result<crate::model_file::Table> {
    let period = subject.period();
    let times: Vec<f64> = period_times(args.transient, period, args.keep).collect();
    let mut tracker = budget.run(
        subject.start_time(),
        (args.transient + args.keep) as f64 * period,
    );
    subject.sample(options, &times, &mut tracker)
}

/// Run a sweep of a model file or of the ring with mass (`to`: the last value, checked).
pub fn run(args: &Args, base: &Subject, model: Option<&Path>, to: f64) -> Result<()> {
    if args.shard.is_some() {
        return Err(planar_only("--shard", base));
    }
    let options = args.method.options()?;
    add_counts(("--transient", args.transient), ("--keep", args.keep))?;
    let picked = chosen_columns(
        base,
        "--columns",
        args.columns.as_deref(),
        &base.section_columns(),
    )?;
    let all = base.columns();
    let rows_planned = args.steps.saturating_mul(args.keep);
    fits_memory(
        "--steps × --keep (rows)",
        rows_planned,
        8 * (all.len() + 2) + 24 * picked.len(),
    )?;
    let budget = args.limits.budget();
    budget.plan("--steps × --keep", rows_planned)?;
    let plot = !args.no_plot;
    let [svg, png] = plot::beside(&args.out);
    let mut outputs = vec![("--out", args.out.as_path())];
    if plot {
        outputs.extend([("the plot", svg.as_path()), ("the plot", png.as_path())]);
    }
    let mut inputs = args.problem.input_files();
    if let Some(m) = model {
        inputs.push(("--model", m));
    }
    check_distinct(&outputs, &inputs)?;
    // contact_stiffness and friction_coefficient are also table names: with --model they are
    // the file's.
    let param = match (base, args.param) {
        (Subject::File { .. }, SweepParam::Table(p)) => {
            ModelParam::from_name(p.name()).map_or(args.param, SweepParam::Model)
        }
        (_, p) => p,
    };
    let values = subjects(args, param, base, to, &options)?;
    ensure_parent(&args.out)?;
    let header: Vec<&str> = ["value", "period"]
        .into_iter()
        .chain(
            picked
                .iter()
                .filter_map(|&i| all.get(i).map(String::as_str)),
        )
        .collect();
    let mut out = CsvOut::create(&args.out, &header)?;
    let bar = stdio::progress(
        values.len() as u64,
        "{bar:40} {pos}/{len} values, {elapsed} elapsed, ETA {eta}",
    );
    let results: Vec<Result<crate::model_file::Table>> = values
        .par_iter()
        .map(|(v, subject)| {
            let r = points(subject, &options, args, &budget)
                .map_err(|e| e.context(&format!("{param} = {}", num(*v))));
            bar.inc(1);
            r
        })
        .collect();
    bar.finish_and_clear();
    let orbit = orbit_indices(base);
    let mut drawn = Vec::new();
    let mut written = 0u64;
    for ((v, subject), r) in values.iter().zip(results) {
        let table = match r {
            Ok(t) => t,
            Err(e) if args.skip_errors && e.code != crate::error::EXIT_INPUT => {
                stdio::warn(&format!("skipped {e}"));
                continue;
            }
            Err(e) => return Err(e),
        };
        for (row, k) in table.rows().zip(args.transient..) {
            let fields = [format!("{v:?}"), k.to_string()].into_iter().chain(
                picked
                    .iter()
                    .map(|&i| format!("{:?}", row.get(i).copied().unwrap_or(f64::NAN))),
            );
            out.record(fields)?;
            drawn.push((*v, orbit_state(row, &orbit, subject.clearance()).x));
            written += 1;
        }
    }
    let mut files = vec![out.finish()?];
    if plot {
        let label = match param {
            SweepParam::Model(p) => p.label().to_string(),
            SweepParam::Table(p) => p.name().to_string(),
        };
        let figure = BifurcationFigure {
            title: format!(
                "Bifurcation diagram over {}, {} x, periods {}-{}, {}",
                param,
                match base {
                    Subject::File { .. } => "rub station",
                    Subject::Ring(_) => "rotor (ring with mass)",
                },
                args.transient,
                args.transient + args.keep,
                crate::options::describe(&options)
            ),
            parameter: label,
            points: drawn,
        };
        files.extend(plot::render_beside(&figure, &args.out)?);
    }
    commit_all(files)?;
    let mut report = format!(
        "{} values of {} from {} to {}, {written} Poincaré points written to {}\n",
        args.steps,
        param,
        num(args.from),
        num(to),
        args.out.display()
    );
    if plot {
        report += &format!("plot written to {} and {}\n", svg.display(), png.display());
    }
    stdio::out(&report)
}
