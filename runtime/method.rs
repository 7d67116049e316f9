//! Method selection: one entry point that builds any propagation method behind the same
//! [`Propagate`] interface, so every analysis and the CLI can switch methods by a value.

use crate::params::{Problem, State};
use crate::propagate::{Event, Propagate, PropagationError, Regime};

/// Which propagation method to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Piecewise analytical: exact free flight, re-linearized closed-form contact (the paper's
    /// family, `model.md` §8).
    Analytic,
    /// Exact free flight plus adaptive DOP853 on the nonlinear contact field (`model.md` §8).
    Hybrid,
    /// Adaptive Dormand–Prince 8(5,3) on the full piecewise equations.
    Dop853,
    /// Adaptive Dormand–Prince 5(4) (MATLAB's ode45) on the full piecewise equations.
    Rk45,
}

impl Method {
    /// Every method.
    pub const ALL: [Method; 4] = [
        Method::Analytic,
        Method::Hybrid,
        Method::Dop853,
        Method::Rk45,
    ];

    /// The method's command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            Method::Analytic => "analytic",
            Method::Hybrid => "hybrid",
            Method::Dop853 => "dop853",
            Method::Rk45 => "rk45",
        }
    }

    /// The method with the given name.
    pub fn from_name(name: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// The analytic method's contact scheme (`model.md` §8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactScheme {
    /// Exponential Rosenbrock–Euler: the paper's closed-form step re-linearized at every sub-step
    /// start, fixed sub-step, second order.
    Exprb2,
    /// Hochbruck–Ostermann exprb43: fourth order, embedded third-order estimate, adaptive.
    Exprb43,
}

impl ContactScheme {
    /// The scheme's command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            ContactScheme::Exprb2 => "exprb2",
            ContactScheme::Exprb43 => "exprb43",
        }
    }

    /// The scheme with the given name.
    pub fn from_name(name: &str) -> Option<ContactScheme> {
        [ContactScheme::Exprb2, ContactScheme::Exprb43]
            .into_iter()
            .find(|s| s.name() == name)
    }
}

/// How to propagate: the method and its accuracy settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The method.
    pub method: Method,
    /// The accuracy target; `None` takes the method's default (see [`Options::tolerance`]).
    pub tol: Option<f64>,
    /// The analytic method's contact scheme.
    pub contact_scheme: ContactScheme,
    /// A fixed contact sub-step for the analytic method (exprb2 always uses a fixed sub-step;
    /// exprb43 uses it instead of step control when given).
    pub step: Option<f64>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Analytic,
            tol: None,
            contact_scheme: ContactScheme::Exprb43,
            step: None,
        }
    }
}

impl Options {
    /// Default options for `method`.
    pub fn with_method(method: Method) -> Self {
        Options {
            method,
            ..Options::default()
        }
    }

    /// The tolerance in force: the given one or the method's default.
    pub fn tolerance(&self) -> f64 {
        self.tol.unwrap_or(match self.method {
            Method::Analytic => crate::analytic::DEFAULT_TOLERANCE,
            Method::Hybrid | Method::Dop853 | Method::Rk45 => crate::reference::DEFAULT_TOLERANCE,
        })
    }
}

/// Any method behind one type (no heap): build it with [`Propagator::new`].
pub struct Propagator(Inner);

#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
enum Inner {
    Analytic(crate::analytic::AnalyticPropagator),
    Dop853(crate::reference::Dop853Propagator),
    Rk45(crate::reference::Rk45Propagator),
    Hybrid(crate::hybrid::HybridPropagator),
}

impl Propagator {
    /// Validate `problem` and `options` and start the chosen method at the problem's start time.
    pub fn new(problem: &Problem, options: &Options) -> Result<Self, PropagationError> {
        problem.validate()?;
        let tol = options.tolerance();
        if !(tol.is_finite() && tol > 0.0) {
            return Err(PropagationError::InvalidOption {
                what: "tol",
                value: tol,
            });
        }
        let inner = match options.method {
            Method::Analytic => Inner::Analytic(crate::analytic::AnalyticPropagator::new(
                problem,
                options.contact_scheme,
                tol,
                options.step,
            )?),
            Method::Dop853 => Inner::Dop853(crate::reference::Dop853Propagator::new(problem, tol)?),
            Method::Rk45 => Inner::Rk45(crate::reference::Rk45Propagator::new(problem, tol)?),
            Method::Hybrid => Inner::Hybrid(crate::hybrid::HybridPropagator::new(problem, tol)?),
        };
        Ok(Propagator(inner))
    }
}

impl Propagate for Propagator {
    fn time(&self) -> f64 {
        match &self.0 {
            Inner::Analytic(p) => p.time(),
            Inner::Dop853(p) => p.time(),
            Inner::Rk45(p) => p.time(),
            Inner::Hybrid(p) => p.time(),
        }
    }
    fn state(&self) -> State {
        match &self.0 {
            Inner::Analytic(p) => p.state(),
            Inner::Dop853(p) => p.state(),
            Inner::Rk45(p) => p.state(),
            Inner::Hybrid(p) => p.state(),
        }
    }
    fn regime(&self) -> Regime {
        match &self.0 {
            Inner::Analytic(p) => p.regime(),
            Inner::Dop853(p) => p.regime(),
            Inner::Rk45(p) => p.regime(),
            Inner::Hybrid(p) => p.regime(),
        }
    }
    fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
        match &mut self.0 {
            Inner::Analytic(p) => p.advance(target),
            Inner::Dop853(p) => p.advance(target),
            Inner::Rk45(p) => p.advance(target),
            Inner::Hybrid(p) => p.advance(target),
        }
    }
}
