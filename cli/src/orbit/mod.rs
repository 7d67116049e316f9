//! Periodic orbits, their stability and their branches (`docs/MODEL.md` §18), on top of the
//! runtime's shooting (`rotor_rub::orbit`): the start of a search from a simulated state,
//! pseudo-arclength continuation in any parameter of the table with the bifurcations located
//! (fold, period doubling with a switch to the period-2k branch, Neimark–Sacker, grazing), and
//! the `orbit` and `continue` commands with their files and plots.
//!
//! - `evaluate.rs`: the map, its monodromy and ∂R/∂p at u = (s, p); the bordered systems.
//! - `correct.rs`: the corrector (Newton with one constraint) and the branch points it gives.
//! - `continuation.rs`: following a branch, step control, the range's edges, the branches
//!   switched to at period doublings.
//! - `locate.rs`: test functions, location, branch switching.
//! - `start.rs`: where a search starts (`--start`: simulated, the free response, given).
//! - `command.rs` (`rotor-rub orbit`), `continue_command.rs` (`rotor-rub continue`),
//!   `files.rs` (the branch CSV); the plot is `crate::plot::branch`.

pub mod command;
pub mod continuation;
pub mod continue_command;
pub mod correct;
pub mod evaluate;
pub mod files;
pub mod locate;
pub mod start;

use rotor_rub::orbit::{MapSettings, Summary};
use rotor_rub::{Options, Parameter, Problem, State};

use crate::error::{CliError, Result, num};
use crate::limits::Budget;
use crate::trajectory;

pub use continuation::{Start, continuation};
pub use correct::Solution;
pub use evaluate::Evaluator;

/// What kind of bifurcation a located point is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// A real multiplier through +1: the branch turns back (a jump of a slow sweep).
    Fold,
    /// A real multiplier through −1: a period-2k branch is born.
    PeriodDoubling,
    /// A complex pair through the unit circle: a torus (quasi-periodic motion) is born.
    NeimarkSacker,
    /// A contact appears, vanishes or splits along the orbit (an extremum of z reaches 1).
    Grazing,
}

impl Kind {
    /// Every kind.
    pub const ALL: [Kind; 4] = [
        Kind::Fold,
        Kind::PeriodDoubling,
        Kind::NeimarkSacker,
        Kind::Grazing,
    ];

    /// `fold`, `period-doubling`, `neimark-sacker` or `grazing`, as written in files.
    pub const fn name(self) -> &'static str {
        match self {
            Kind::Fold => "fold",
            Kind::PeriodDoubling => "period-doubling",
            Kind::NeimarkSacker => "neimark-sacker",
            Kind::Grazing => "grazing",
        }
    }
}

/// One point of a branch: an orbit, and the bifurcation it is when it is one.
#[derive(Clone, Debug)]
pub struct BranchPoint {
    /// The branch it belongs to (index into [`Continuation::branches`]).
    pub branch: usize,
    /// The orbit with its multipliers and tangent.
    pub solution: Solution,
    /// The bifurcation located here, if any.
    pub kind: Option<Kind>,
}

impl BranchPoint {
    /// A point of `branch`.
    pub fn new(branch: usize, solution: Solution, kind: Option<Kind>) -> Self {
        BranchPoint {
            branch,
            solution,
            kind,
        }
    }

    /// The continued parameter's value.
    pub fn value(&self) -> f64 {
        self.solution.value()
    }

    /// The orbit's state on the section.
    pub fn state(&self) -> State {
        let u = self.solution.u();
        State::new(u[0], u[1], u[2], u[3])
    }

    /// k (forcing periods).
    pub fn periods(&self) -> u32 {
        self.solution.eval.point.periods
    }

    /// What the orbit does over its k periods.
    pub fn summary(&self) -> &Summary {
        &self.solution.eval.point.summary
    }

    /// Every multiplier inside the unit circle.
    pub fn stable(&self) -> bool {
        self.solution.stable()
    }
}

/// One branch: its period and where it came from and ended.
#[derive(Clone, Debug)]
pub struct Branch {
    /// Its index.
    pub id: usize,
    /// k of its orbits.
    pub periods: u32,
    /// The period doubling it was switched to from (index into [`Continuation::points`]).
    pub parent: Option<usize>,
    /// Why it ended.
    pub end: String,
}

/// The result of a continuation: every branch's points in order, bifurcations inserted.
#[derive(Clone, Debug)]
pub struct Continuation {
    /// The continued parameter.
    pub parameter: Parameter,
    /// The points, branch by branch, each branch in the order it was followed.
    pub points: Vec<BranchPoint>,
    /// The points that are bifurcations (indices into `points`).
    pub bifurcations: Vec<usize>,
    /// The branches.
    pub branches: Vec<Branch>,
    /// Map evaluations made.
    pub evaluations: u64,
    /// Starts left out because their orbit lies on a branch already followed: (start, branch).
    pub skipped: Vec<(usize, usize)>,
}

/// How a continuation runs.
#[derive(Clone, Debug)]
pub struct ContinuationSettings {
    /// The continued parameter (a model parameter of the table).
    pub parameter: Parameter,
    /// Where it starts.
    pub from: f64,
    /// The other end of the range.
    pub to: f64,
    /// k of the first branch.
    pub periods: u32,
    /// How the map is computed.
    pub map: MapSettings,
    /// The corrector's residual tolerance, relative to 1 + |s|∞.
    pub tolerance: f64,
    /// The first step (arclength in (s, p)).
    pub step: f64,
    /// The smallest step before a branch is given up.
    pub min_step: f64,
    /// The largest step.
    pub max_step: f64,
    /// Most points of one branch.
    pub max_points: usize,
    /// Branches are switched to at period doublings while their period 2k is at most this.
    pub max_period: u32,
    /// Whether to detect and locate bifurcations.
    pub locate: bool,
    /// How closely a bifurcation is located in the parameter (relative to max(1, |p|)).
    pub locate_tolerance: f64,
}

impl ContinuationSettings {
    /// The defaults for a range `from` → `to` of `parameter`, period k = `periods`.
    pub fn new(parameter: Parameter, from: f64, to: f64, periods: u32) -> Self {
        let span = (to - from).abs().max(1e-12);
        ContinuationSettings {
            parameter,
            from,
            to,
            periods,
            map: MapSettings::default(),
            tolerance: 1e-10,
            step: 0.01 * span,
            min_step: 1e-7 * span,
            max_step: 0.05 * span,
            max_points: 3000,
            max_period: 2 * periods,
            locate: true,
            locate_tolerance: 1e-11,
        }
    }

    /// Check the range and the parameter.
    ///
    /// # Errors
    /// An input error naming the value and the valid range.
    pub fn validate(&self) -> Result<()> {
        if self.parameter as usize >= Parameter::MODEL_COUNT {
            return Err(CliError::input(format!(
                "--param {}: only a model parameter can be continued (not the start state): one of {}",
                self.parameter.info().name,
                model_parameters()
            )));
        }
        let range = self.parameter.range();
        for (flag, v) in [("--from", self.from), ("--to", self.to)] {
            if !range.contains(v) {
                return Err(CliError::input(format!(
                    "{flag} = {} is out of range for {}: it must be in {range}",
                    num(v),
                    self.parameter.info().name
                )));
            }
        }
        if self.from == self.to {
            return Err(CliError::input(format!(
                "--to = {} equals --from: a continuation needs a range",
                num(self.to)
            )));
        }
        if self.periods == 0 || self.periods as usize > rotor_rub::orbit::MAX_PERIOD {
            return Err(CliError::input(format!(
                "--period = {} is out of range: it must be an integer in [1, {}]",
                self.periods,
                rotor_rub::orbit::MAX_PERIOD
            )));
        }
        Ok(())
    }
}

/// The model parameters' names, for messages.
pub fn model_parameters() -> String {
    Parameter::ALL[..Parameter::MODEL_COUNT]
        .iter()
        .map(|p| p.info().name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// A start for shooting: the state of a simulation of `problem` after `transient` forcing
/// periods (on the section τ = 0 mod the forcing period), the work charged to `budget`.
///
/// # Errors
/// What the propagation reports, or the budget's refusal.
pub fn simulated_start(
    problem: &Problem,
    options: &Options,
    transient: u64,
    budget: &Budget,
) -> Result<State> {
    let mut propagator = trajectory::start(problem, options)?;
    let period = problem.params.forcing_period();
    let end = problem.start_time + transient as f64 * period;
    let end = (end / period).ceil() * period;
    let mut tracker = budget.run(problem.start_time, end);
    let sample = trajectory::advance_to(&mut propagator, end, &mut tracker, |_| Ok(()))?;
    Ok(sample.state)
}
