//! The model file's commands: `rotor-rub check-model FILE` (read, check, print n, the station,
//! the clearance and the modes) and `rotor-rub simulate --model FILE` (through
//! [`super::simulate_matrix`]; its CSV files are written by [`write_run`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use rotor_rub::Options;
use rotor_rub::linalg::Complex;

use super::read::load;
use super::run::{MatrixRun, MatrixRunError, end_time, simulate_matrix};
use super::spec::{ModelSpec, on_large_stack};
use crate::error::{CliError, Result, num};
use crate::output::{CsvOut, check_distinct, commit_all};
use crate::stdio;
use crate::trajectory::uniform_times;

/// `check-model`'s arguments.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// The model file: TOML (`docs/MODEL_FILES.md`) or a self-contained .npz
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
}

/// Read a model file as an input error (exit 2) naming the file.
pub fn read(path: &Path) -> Result<ModelSpec> {
    load(path).map_err(CliError::input)
}

/// `rotor-rub check-model FILE`.
pub fn check(args: &CheckArgs) -> Result<()> {
    let spec = read(&args.file)?;
    let fail = |e: super::ModelError| CliError::input(format!("{}: {e}", args.file.display()));
    let eigenvalues = spec.eigenvalues().map_err(fail)?;
    stdio::out(&report(&spec, &args.file, &eigenvalues))
}

fn dof_name(spec: &ModelSpec, i: usize) -> String {
    match spec.dofs.get(i) {
        Some(name) if *name != format!("q{i}") => format!("{name} (#{i})"),
        _ => format!("#{i}"),
    }
}

/// `check-model`'s report.
pub fn report(spec: &ModelSpec, path: &Path, eigenvalues: &[Complex]) -> String {
    let mut r = String::new();
    let n = spec.dofs();
    let name = if spec.name.is_empty() {
        String::new()
    } else {
        format!("{} ", spec.name)
    };
    let _ = writeln!(r, "model: {name}({}), SI units", path.display());
    let _ = writeln!(
        r,
        "degrees of freedom: n = {n} ({}); state 2n = {} entries",
        spec.dofs.join(", "),
        2 * n
    );
    let omega = spec.speed;
    let _ = writeln!(
        r,
        "running speed: Ω = {} rad/s ({} rpm, {} Hz); forcing period {} s; phase {} rad",
        num(omega),
        num(round6(omega * 60.0 / std::f64::consts::TAU)),
        num(round6(omega / std::f64::consts::TAU)),
        num(round6(std::f64::consts::TAU / omega)),
        num(spec.phase)
    );
    let symmetric = |d: &super::Dense| {
        let scale = d.data.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        (0..n).all(|i| (0..i).all(|j| (d.get(i, j) - d.get(j, i)).abs() <= 1e-12 * scale))
    };
    let nonzero = |d: &super::Dense| d.data.iter().any(|&x| x != 0.0);
    let _ = writeln!(
        r,
        "matrices: M symmetric positive definite; C {}; G {}; K {}",
        if nonzero(&spec.damping) {
            if symmetric(&spec.damping) {
                "symmetric"
            } else {
                "not symmetric"
            }
        } else {
            "zero"
        },
        if nonzero(&spec.gyroscopic) {
            "gyroscopic (multiplied by Ω)"
        } else {
            "zero"
        },
        if symmetric(&spec.stiffness) {
            "symmetric"
        } else {
            "not symmetric (cross-coupled bearings)"
        }
    );
    if let Some((lo, hi)) = spec.speed_range() {
        let _ = writeln!(
            r,
            "speed-dependent: C and K at {} speeds in [{}, {}] rad/s, linear in between",
            spec.speed_dependent.len(),
            num(lo),
            num(hi)
        );
    }
    if spec.unbalances.is_empty() {
        let _ = writeln!(r, "unbalance: none");
    }
    for (i, u) in spec.unbalances.iter().enumerate() {
        let _ = writeln!(
            r,
            "unbalance {i}: m·e = {} kg·m on ({}, {}), phase {} rad",
            num(u.m_e),
            dof_name(spec, u.dof_x),
            dof_name(spec, u.dof_y),
            num(u.phase)
        );
    }
    if !spec.force.is_empty() {
        let _ = writeln!(r, "constant force: {:?} N", spec.force);
    }
    let rub = &spec.rub;
    let stator = match rub.stator {
        None => "a fixed stator".to_string(),
        Some((x, y)) => format!(
            "the stator point ({}, {})",
            dof_name(spec, x),
            dof_name(spec, y)
        ),
    };
    let _ = writeln!(
        r,
        "rub station: the rotor point ({}, {}) against {stator}",
        dof_name(spec, rub.dof_x),
        dof_name(spec, rub.dof_y)
    );
    let delta = rub.clearance;
    let _ = writeln!(
        r,
        "clearance: δ = {} m (lengths inside are in clearances); stator centre offset ({}, {}) m = ({}, {}) δ",
        num(delta),
        num(rub.offset.0),
        num(rub.offset.1),
        num(rub.offset.0 / delta),
        num(rub.offset.1 / delta)
    );
    let k = rub.contact_stiffness;
    let _ = writeln!(
        r,
        "contact: K_c = [[{}, {}], [{}, {}]] N/m; friction μ = {}{}",
        num(k[0][0]),
        num(k[0][1]),
        num(k[1][0]),
        num(k[1][1]),
        num(rub.friction_coefficient),
        rub.radius
            .map(|radius| format!("; radius R = {} m ({} δ)", num(radius), num(radius / delta)))
            .unwrap_or_default()
    );
    let _ = writeln!(
        r,
        "initial state: {}",
        if spec.initial.is_some() {
            "given"
        } else {
            "rest"
        }
    );
    let _ = writeln!(
        r,
        "modes at Ω (eigenvalues λ of the first-order matrix; frequency |λ|/2π, damping ratio −Re λ/|λ|):"
    );
    let _ = writeln!(
        r,
        "  {:>3}  {:>14}  {:>14}  {:>13}  {:>24}",
        "#", "f (Hz)", "ω (rad/s)", "damping ratio", "λ (1/s)"
    );
    let mut shown = 0;
    for l in eigenvalues.iter().filter(|l| l.im >= 0.0) {
        shown += 1;
        let w = l.abs();
        let zeta = if w > 0.0 { -l.re / w } else { 0.0 };
        let lambda = if l.im == 0.0 {
            format!("{:.6e}", l.re)
        } else {
            format!("{:.6e} ± {:.6e}i", l.re, l.im)
        };
        let _ = writeln!(
            r,
            "  {shown:>3}  {:>14}  {:>14}  {:>13}  {lambda:>24}",
            format!("{:.6}", w / std::f64::consts::TAU),
            format!("{:.6}", w),
            format!("{:.6}", zeta)
        );
    }
    let unstable = eigenvalues.iter().filter(|l| l.re > 0.0).count();
    if unstable > 0 {
        let _ = writeln!(
            r,
            "warning: {unstable} eigenvalues have Re λ > 0: the free rotor is unstable at this speed (its motion grows until the run reports divergence)"
        );
    }
    r
}

fn round6(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let digits = 6 - x.abs().log10().ceil() as i32;
    let scale = 10f64.powi(digits);
    (x * scale).round() / scale
}

/// The simulate command's inputs for a model file.
pub struct SimulateModel<'a> {
    /// The model file.
    pub path: &'a Path,
    /// The method and its settings.
    pub options: Options,
    /// `--t-end` (s) and `--periods`.
    pub t_end: Option<f64>,
    /// `--periods`.
    pub periods: Option<f64>,
    /// `--events`.
    pub events: Option<&'a Path>,
    /// `--samples`.
    pub samples: Option<&'a Path>,
    /// The number of samples.
    pub sample_count: usize,
}

/// `rotor-rub simulate --model FILE`.
pub fn simulate(input: &SimulateModel<'_>) -> Result<()> {
    let spec = read(input.path)?;
    let end = end_time(&spec, input.t_end, input.periods).map_err(CliError::input)?;
    let mut outputs = Vec::new();
    if let Some(p) = input.events {
        outputs.push(("--events", p));
    }
    if let Some(p) = input.samples {
        outputs.push(("--samples", p));
    }
    check_distinct(&outputs, &[("--model", input.path)])?;
    let times: Vec<f64> = uniform_times(0.0, end, input.sample_count).collect();
    let run = on_large_stack(|| simulate_matrix(&spec, &input.options, end, &times, None));
    let run = run.map_err(|e| match e {
        MatrixRunError::Model(e) => CliError::input(format!("{}: {e}", input.path.display())),
        MatrixRunError::Input(m) => CliError::input(m),
        MatrixRunError::Propagation(e) => CliError::from(e),
    })?;
    write_run(&run, "t", input.events, input.samples)?;
    let mut r = String::new();
    let _ = writeln!(
        r,
        "t from 0 to {} s ({} forcing periods)",
        num(end),
        num(end * spec.speed / std::f64::consts::TAU)
    );
    let _ = writeln!(
        r,
        "switches: {} ({} contact starts, {} contact ends); contact fraction {}",
        run.events.len(),
        run.count(rotor_rub::EventKind::Enter),
        run.count(rotor_rub::EventKind::Exit),
        run.contact_fraction()
    );
    let _ = writeln!(r, "run time: {:.3} ms", run.elapsed.as_secs_f64() * 1e3);
    stdio::out(&r)
}

/// `rotor-rub simulate` of the paper's rotor with a ring of mass (`stator_mass_ratio` > 0):
/// the run from the problem's start to `end` (τ) with `count` uniform samples, the CSV files
/// (the planar columns, then `xs, ys, vxs, vys`), and the summary with the ring's largest
/// displacement.
///
/// # Errors
/// An output path that is an input, a refused option, a failed run, a file not written.
pub fn simulate_ring_command(
    problem: &rotor_rub::Problem,
    options: &Options,
    end: f64,
    count: usize,
    events: Option<&Path>,
    samples: Option<&Path>,
) -> Result<()> {
    let start = problem.start_time;
    let times: Vec<f64> = uniform_times(start, end, count).collect();
    let run = on_large_stack(|| super::ring::simulate_ring(problem, options, end, &times))
        .map_err(|e| match e {
            MatrixRunError::Model(e) => CliError::input(e.to_string()),
            MatrixRunError::Input(m) => CliError::input(m),
            MatrixRunError::Propagation(e) => CliError::from(e),
        })?;
    write_run(&run, "tau", events, samples)?;
    let mut r = String::new();
    let _ = writeln!(
        r,
        "method: {}; τ from {} to {} ({} forcing periods); stator ring with mass m̂ = {}",
        crate::options::describe(options),
        num(start),
        num(end),
        num((end - start) / problem.params.forcing_period()),
        num(problem.params.stator_mass_ratio)
    );
    let _ = writeln!(
        r,
        "switches: {} ({} contact starts, {} contact ends)",
        run.events.len(),
        run.count(rotor_rub::EventKind::Enter),
        run.count(rotor_rub::EventKind::Exit)
    );
    let _ = writeln!(r, "contact fraction: {}", run.contact_fraction());
    let _ = writeln!(
        r,
        "ring: largest displacement |(xs, ys)| = {} clearances",
        num(super::ring::largest_ring_displacement(&run))
    );
    let e = &run.end_state;
    let at = |i: usize| num(e.get(i).copied().unwrap_or(f64::NAN));
    let _ = writeln!(
        r,
        "final state: x = {}, y = {}, vx = {}, vy = {}; ring xs = {}, ys = {}, vxs = {}, vys = {}",
        at(0),
        at(1),
        at(2),
        at(3),
        at(4),
        at(5),
        at(6),
        at(7)
    );
    let _ = writeln!(r, "run time: {:.3} ms", run.elapsed.as_secs_f64() * 1e3);
    stdio::out(&r)
}

/// Write a matrix run's events (`<time>,kind,<columns>`) and samples
/// (`<time>,<columns>,contact,regime`) as CSV (`time`: the time column's name, `t` in s for a
/// model file, `tau` for the paper's dimensionless ring), each file whole or not at all.
pub fn write_run(
    run: &MatrixRun,
    time: &str,
    events: Option<&Path>,
    samples: Option<&Path>,
) -> Result<()> {
    let width = run.columns.len();
    let columns = run.columns.iter().map(String::as_str);
    let mut files = Vec::new();
    if let Some(path) = events {
        let header: Vec<&str> = [time, "kind"].into_iter().chain(columns.clone()).collect();
        let mut out = CsvOut::create(path, &header)?;
        for (i, (&t, &code)) in run.events.time.iter().zip(&run.events.code).enumerate() {
            let kind = rotor_rub::EventKind::ALL
                .get(code as usize)
                .map_or("?", |k| k.name());
            let state = run
                .events
                .state
                .get(i * width..(i + 1) * width)
                .unwrap_or(&[]);
            let fields = [ryu(t), kind.to_string()]
                .into_iter()
                .chain(state.iter().map(|&x| ryu(x)));
            out.record(fields)?;
        }
        files.push(out.finish()?);
    }
    if let Some(path) = samples {
        let header: Vec<&str> = [time]
            .into_iter()
            .chain(columns)
            .chain(["contact", "regime"])
            .collect();
        let mut out = CsvOut::create(path, &header)?;
        let names = ["free", "contact", "rolling"];
        for (i, (&t, &code)) in run.samples.time.iter().zip(&run.samples.code).enumerate() {
            let state = run
                .samples
                .state
                .get(i * width..(i + 1) * width)
                .unwrap_or(&[]);
            let fields = [ryu(t)]
                .into_iter()
                .chain(state.iter().map(|&x| ryu(x)))
                .chain([
                    u8::from(code != 0).to_string(),
                    names.get(code as usize).unwrap_or(&"?").to_string(),
                ]);
            out.record(fields)?;
        }
        files.push(out.finish()?);
    }
    commit_all(files)
}

/// A float in shortest round-trip form (as the other CSV files write them).
fn ryu(x: f64) -> String {
    format!("{x:?}")
}
