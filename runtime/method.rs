//! The method registry (`docs/MODEL.md` §13): every propagation method, its name, description,
//! default tolerance and valid tolerance range, listed once in `registry!`'s invocation below.
//! [`Method`], [`Method::ALL`], [`Propagator`] and the option validation follow from that list,
//! and so do the CLI's `--method` values and help and the benches' method lists.
//!
//! Adding a method: write its module (a type implementing [`Propagate`], usually a
//! [`crate::driver::Piecewise`] over its segment solvers, plus [`Registered`] from
//! `registration.rs`, which is all a method knows of the registry), then add one line to the list.

pub use crate::params::ValidRange;
use crate::params::{Problem, State};
use crate::propagate::{Event, Propagate, PropagationError, Regime};
pub use crate::registration::{ContactScheme, MethodInfo, Registered, STEP_RANGE, Settings};

macro_rules! registry {
    ($($(#[$doc:meta])* $variant:ident => $ty:ty,)+) => {
        /// Which propagation method to use (the registry's list, `docs/MODEL.md` §13).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Method {
            $($(#[$doc])* $variant,)+
        }

        impl Method {
            /// Every method, in the registry's order.
            pub const ALL: &'static [Method] = &[$(Method::$variant,)+];

            /// The method's facts.
            pub const fn info(self) -> &'static MethodInfo {
                match self {
                    $(Method::$variant => &<$ty as Registered>::INFO,)+
                }
            }
        }

        #[allow(
            clippy::large_enum_variant,
            reason = "the runtime has no heap to box into"
        )]
        enum Inner {
            $($variant($ty),)+
        }

        impl Inner {
            fn build(problem: &Problem, options: &Options) -> Result<Self, PropagationError> {
                let settings = options.settings();
                Ok(match options.method {
                    $(Method::$variant => Inner::$variant(<$ty>::build(problem, &settings)?),)+
                })
            }

            fn resume(problem: &Problem, options: &Options) -> Result<Self, PropagationError> {
                let settings = options.settings();
                Ok(match options.method {
                    $(Method::$variant => Inner::$variant(<$ty>::resume(problem, &settings)?),)+
                })
            }

        }

        // Static dispatch (a match, each arm inlinable) rather than through `&dyn Propagate`:
        // `advance_to` asks for the time, state and regime after every advance.
        impl Propagate for Inner {
            #[inline]
            fn time(&self) -> f64 {
                match self {
                    $(Inner::$variant(p) => p.time(),)+
                }
            }

            #[inline]
            fn state(&self) -> State {
                match self {
                    $(Inner::$variant(p) => p.state(),)+
                }
            }

            #[inline]
            fn regime(&self) -> Regime {
                match self {
                    $(Inner::$variant(p) => p.regime(),)+
                }
            }

            fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
                match self {
                    $(Inner::$variant(p) => p.advance(target),)+
                }
            }
        }
    };
}

registry! {
    /// Piecewise analytical: exact free flight, re-linearized closed-form contact (the paper's
    /// family, `docs/MODEL.md` §8).
    Analytic => crate::analytic::AnalyticPropagator,
    /// Exact free flight plus adaptive DOP853 on the nonlinear contact field (`docs/MODEL.md` §8).
    Hybrid => crate::hybrid::HybridPropagator,
    /// Exact free flight plus a Taylor integrator on the nonlinear contact field, its
    /// recurrences generated from the model, switches as polynomial roots (`docs/MODEL.md` §16).
    Taylor => crate::taylor::TaylorPropagator,
    /// Adaptive Dormand–Prince 8(5,3) on the full piecewise equations.
    Dop853 => crate::reference::Dop853Propagator,
    /// Adaptive Dormand–Prince 5(4) (MATLAB's ode45) on the full piecewise equations.
    Rk45 => crate::reference::Rk45Propagator,
}

impl Method {
    /// The method's command-line name.
    pub const fn name(self) -> &'static str {
        self.info().name
    }

    /// One line describing the method.
    pub const fn description(self) -> &'static str {
        self.info().description
    }

    /// The tolerance used when none is given.
    pub const fn default_tolerance(self) -> f64 {
        self.info().default_tolerance
    }

    /// The valid tolerances.
    pub const fn tolerance_range(self) -> ValidRange {
        self.info().tolerance_range
    }

    /// The method with the given name.
    pub fn from_name(name: &str) -> Option<Method> {
        Method::ALL.iter().copied().find(|m| m.name() == name)
    }

    /// The one tolerance validation ([`MethodInfo::check_tolerance`]): `tol` in
    /// [`Method::tolerance_range`], else [`PropagationError::InvalidOption`] naming the value
    /// and the range.
    pub fn check_tolerance(self, tol: f64) -> Result<(), PropagationError> {
        self.info().check_tolerance(tol)
    }
}

/// How to propagate: the method and its accuracy settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The method.
    pub method: Method,
    /// The accuracy target; `None` takes the method's default (see [`Options::tolerance`]).
    pub tol: Option<f64>,
    /// The contact scheme of a method that takes one (see [`MethodInfo::contact_scheme`]).
    pub contact_scheme: ContactScheme,
    /// A fixed contact sub-step in [`STEP_RANGE`] (exprb2 always uses a fixed sub-step; exprb43
    /// uses it instead of step control when given).
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
        self.tol.unwrap_or(self.method.default_tolerance())
    }

    /// Check the tolerance and the fixed sub-step against their ranges.
    ///
    /// # Errors
    /// [`PropagationError::InvalidOption`] naming the value and its range.
    pub fn validate(&self) -> Result<(), PropagationError> {
        self.method.check_tolerance(self.tolerance())?;
        match self.step {
            Some(step) => Method::Analytic.info().check_step(step),
            None => Ok(()),
        }
    }

    /// What the method is built with: the tolerance in force, the contact scheme and the fixed
    /// sub-step.
    pub fn settings(&self) -> Settings {
        Settings {
            tol: self.tolerance(),
            contact_scheme: self.contact_scheme,
            step: self.step,
        }
    }
}

/// Any method behind one type (no heap): build it with [`Propagator::new`].
pub struct Propagator(Inner);

impl Propagator {
    /// Validate `problem` and `options` and start the chosen method at the problem's start time.
    // Inlined into the caller so that the method is built in the caller's slot: a `Propagator`
    // is as large as its largest method (the taylor method's series, ≈ 10 KB), and returning
    // it through one more frame copied all of it.
    #[inline(always)]
    pub fn new(problem: &Problem, options: &Options) -> Result<Self, PropagationError> {
        problem.validate()?;
        options.validate()?;
        Inner::build(problem, options).map(Propagator)
    }

    /// Continue a run at a state it reached (see [`Registered::resume`]): validates the
    /// parameters and the options, not the state against the table's start ranges.
    pub fn resume(problem: &Problem, options: &Options) -> Result<Self, PropagationError> {
        problem.params.validate()?;
        options.validate()?;
        Inner::resume(problem, options).map(Propagator)
    }
}

impl Propagate for Propagator {
    #[inline]
    fn time(&self) -> f64 {
        self.0.time()
    }
    #[inline]
    fn state(&self) -> State {
        self.0.state()
    }
    #[inline]
    fn regime(&self) -> Regime {
        self.0.regime()
    }
    fn advance(&mut self, target: f64) -> Result<Option<Event>, PropagationError> {
        self.0.advance(target)
    }
}
