//! The FMU's model, shared by the FMI 2.0 and 3.0 layers and by both unit systems: the values
//! the importer set (in its units), the stepper after initialization, and the outputs. Plain
//! data (`Clone`, no heap inside: the ring's stepper holds its model inline): a saved FMU state
//! is a copy; no call after instantiation allocates. The
//! communication step is in `step.rs`; setting values, and when they take effect, in `set.rs`.

mod set;

use rotor_rub::params::Number;
use rotor_rub::stepper::RingState;
use rotor_rub::stepper::{AnyStepper, OnCap, StepperConfig};
use rotor_rub::{Parameter, Problem, Regime, State, field};

use crate::file::FileModel;
use crate::file::run::FileRun;
use crate::message::Message;
use crate::msg;
use crate::units::{Dimension, Scales, Units};
use crate::variables::{self, Output, Setting, Target, Variable, dimension};

/// The FMU's settings (`variables::settings`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Longest internal step in the importer's time unit (SI: 0 means 1e-3/ω_n).
    pub internal_step: f64,
    /// Accepted error estimate.
    pub tolerance: f64,
    /// Most internal steps in one communication step.
    pub max_internal_steps: u32,
    /// ω_n, δ, M (all 1 in the dimensionless FMU).
    pub scales: Scales,
}

/// The model of one FMU instance.
#[derive(Clone, Debug)]
pub struct Model {
    /// The unit system of the instance.
    pub units: Units,
    /// Every table entry as the importer set it, in the importer's units (`start_time` unused).
    pub requested: Problem,
    /// The experiment's start time, in the importer's units.
    pub start_time: f64,
    /// The settings.
    pub settings: Settings,
    /// The stepper, from the end of initialization on: the planar one, or the ring's when
    /// `stator_mass_ratio` > 0 (the problem decides).
    pub stepper: Option<AnyStepper>,
    /// Tunable parameters were set since the last step: the next step applies them as a set.
    pub pending: bool,
    /// Contact entries so far.
    pub contact_count: u64,
    /// The next internal step length in model time (step control).
    pub next_step: f64,
    /// The model-file FMU's model (`cargo xtask fmu --model`): when present, every call goes
    /// to it (`crate::file`) and the fields above are unused.
    pub file: Option<Box<FileRun>>,
}

impl Model {
    /// A model with every value at its default.
    pub fn new(units: Units) -> Model {
        let scales = variables::default_scales(units);
        let mut requested = Problem::DEFAULT;
        for p in Parameter::ALL {
            let value = p.get(&Problem::DEFAULT);
            p.set(&mut requested, scales.to_importer(dimension(p), value));
        }
        let internal_step = match units {
            Units::Dimensionless => variables::INTERNAL_STEP,
            Units::Si => 0.0,
        };
        Model {
            units,
            requested,
            start_time: 0.0,
            settings: Settings {
                internal_step,
                tolerance: variables::TOLERANCE,
                max_internal_steps: variables::MAX_INTERNAL_STEPS,
                scales,
            },
            stepper: None,
            pending: false,
            contact_count: 0,
            next_step: variables::INTERNAL_STEP,
            file: None,
        }
    }

    /// The model of the FMU built for a model file (SI), every value at its start.
    pub fn for_file(file: FileModel) -> Model {
        Model {
            file: Some(Box::new(FileRun::new(file))),
            ..Model::new(Units::Si)
        }
    }

    /// A fresh model of the same FMU (fmiReset): the model file's, or the planar one's.
    pub fn reset(&self) -> Model {
        match &self.file {
            Some(f) => Model::for_file(f.file.clone()),
            None => Model::new(self.units),
        }
    }

    /// The scales in force.
    pub fn scales(&self) -> Scales {
        self.settings.scales
    }

    /// The longest internal step in model time.
    pub fn model_internal_step(&self) -> f64 {
        match self.units {
            Units::Si if self.settings.internal_step == 0.0 => variables::INTERNAL_STEP,
            _ => self
                .scales()
                .to_model(Dimension::Time, self.settings.internal_step),
        }
    }

    /// The problem the requested values describe, in model units, from the start time.
    pub fn requested_problem(&self) -> Problem {
        let scales = self.scales();
        let mut problem = Problem::DEFAULT;
        // Entries the FMU does not offer (`start_time`) keep their defaults in model units.
        let offered = Parameter::ALL
            .into_iter()
            .filter(|&p| variables::of_parameter(p, self.units).is_some());
        for p in offered {
            p.set(&mut problem, self.model_value(p));
        }
        problem.start_time = scales.to_model(Dimension::Time, self.start_time);
        problem
    }

    /// Whether table entry `p` holds its declared start value (the table's default, converted
    /// at the SI FMU's default scales).
    fn at_start(&self, p: Parameter) -> bool {
        variables::of_parameter(p, self.units).and_then(|v| v.start) == Some(p.get(&self.requested))
    }

    /// Table entry `p` in model units. An entry at its declared start value is the table's
    /// default exactly, whatever the scales: the SI start values are the defaults at the default
    /// scales, and an entry left there means "the default" (so an untouched `contact_stiffness`
    /// stays k̂_c = 50 when ω_n, δ or M change, and the massless ring's entries stay at their
    /// defaults, which a ring-less model requires). Any other value is converted.
    pub fn model_value(&self, p: Parameter) -> f64 {
        if self.at_start(p) {
            p.info().default
        } else {
            self.scales().to_model(dimension(p), p.get(&self.requested))
        }
    }

    /// Table entry `p` in the importer's units: as set, or for an entry at its start value the
    /// table's default in the current scales ([`Model::model_value`]).
    pub fn importer_value(&self, p: Parameter) -> f64 {
        if self.at_start(p) {
            self.scales().to_importer(dimension(p), p.info().default)
        } else {
            p.get(&self.requested)
        }
    }

    /// The FMU's time in the importer's units.
    pub fn time(&self) -> f64 {
        if let Some(f) = &self.file {
            return f.time();
        }
        match &self.stepper {
            Some(s) => self.scales().to_importer(Dimension::Time, s.time()),
            None => self.start_time,
        }
    }

    /// Build the stepper at the start time (end of initialization): the scales, the internal
    /// step and the whole parameter set are validated here, in the importer's units.
    pub fn initialize(&mut self) -> Result<(), Message> {
        if let Some(f) = &mut self.file {
            f.start_time = self.start_time;
            return f.initialize().map_err(|e| msg!("{e}"));
        }
        self.scales().check().map_err(|(name, value, (lo, hi))| {
            msg!("{name} = {value} is out of range: it must be in [{lo}, {hi}]")
        })?;
        let dt = self.model_internal_step();
        let (lo, hi) = variables::INTERNAL_STEP_RANGE;
        if !(dt.is_finite() && (lo..=hi).contains(&dt)) {
            let to = |x| self.scales().to_importer(Dimension::Time, x);
            return Err(msg!(
                "internal_step = {} is out of range: it must be in [{}, {}] (or 0 for 1e-3/ω_n in the SI FMU)",
                Number(self.settings.internal_step),
                Number(to(lo)),
                Number(to(hi))
            ));
        }
        let problem = self.requested_problem();
        if let Err(e) = problem.validate() {
            return Err(self.refusal("cannot initialize", e, &problem.params));
        }
        let config = StepperConfig {
            on_cap: OnCap::Degrade,
            ..StepperConfig::with_dt(dt)
        };
        let stepper = AnyStepper::new(&problem, config)
            .map_err(|e| msg!("cannot initialize at start time {}: {e}", self.start_time))?;
        self.stepper = Some(stepper);
        self.next_step = dt;
        self.contact_count = 0;
        self.pending = false;
        Ok(())
    }

    /// The variable `vr` of this instance's unit system.
    pub fn variable(&self, vr: u32) -> Result<Variable, Message> {
        variables::find(vr, self.units)
            .ok_or_else(|| msg!("unknown value reference {vr} (see modelDescription.xml)"))
    }

    /// The value of variable `vr` as f64 in the importer's units (booleans 0/1, counts exact up
    /// to 2⁵³). A parameter reads as last set (a tunable one takes effect at the next step);
    /// the phase reads as in force (re-based when the speed changes).
    pub fn get(&self, vr: u32) -> Result<f64, Message> {
        if let Some(f) = &self.file {
            return f.get(vr).map_err(|e| msg!("{e}"));
        }
        let var = self.variable(vr)?;
        Ok(match var.target {
            Target::Table(Parameter::Phase) => self
                .stepper
                .as_ref()
                .map_or(self.requested.params.phase, |s| s.params().phase),
            Target::Table(p) => self.importer_value(p),
            Target::Setting(s) => self.setting(s),
            Target::Output(o) => self.output(o),
        })
    }

    fn setting(&self, s: Setting) -> f64 {
        let st = &self.settings;
        match s {
            Setting::InternalStep => st.internal_step,
            Setting::Tolerance => st.tolerance,
            Setting::MaxInternalSteps => f64::from(st.max_internal_steps),
            Setting::NaturalFrequency => st.scales.natural_frequency,
            Setting::Clearance => st.scales.clearance,
            Setting::Mass => st.scales.mass,
        }
    }

    fn output(&self, o: Output) -> f64 {
        let scales = self.scales();
        let (problem, time, state, regime, sigma, ring) = match &self.stepper {
            Some(s) => {
                let problem = Problem {
                    params: *s.params(),
                    ..Problem::DEFAULT
                };
                let ring = s.ring_state();
                (
                    problem,
                    s.time(),
                    s.state(),
                    s.regime(),
                    s.slip_direction(),
                    ring,
                )
            }
            None => {
                let p = self.requested_problem();
                let ring = if p.params.stator_mass_ratio > 0.0 {
                    RingState {
                        xs: p.params.xs0,
                        ys: p.params.ys0,
                        vxs: p.params.vxs0,
                        vys: p.params.vys0,
                    }
                } else {
                    RingState::default()
                };
                // The planar rule decides the displayed regime before initialization (for a
                // ring with mass: from the rotor against the ring's start).
                let mut planar = p.params;
                planar.offset_x += ring.xs;
                planar.offset_y += ring.ys;
                let regime = field::regime_of(&planar, p.start_time, &p.initial);
                (p, p.start_time, p.initial, regime, 0.0, ring)
            }
        };
        let in_contact = regime != Regime::Free;
        let to = |d, v| scales.to_importer(d, v);
        match o {
            Output::Time => self.time(),
            Output::X => to(Dimension::Length, state.x),
            Output::Y => to(Dimension::Length, state.y),
            Output::Vx => to(Dimension::Velocity, state.vx),
            Output::Vy => to(Dimension::Velocity, state.vy),
            Output::InContact => f64::from(u8::from(in_contact)),
            Output::NormalForce if in_contact => to(
                Dimension::Force,
                normal_force(&problem, time, &state, &ring),
            ),
            Output::NormalForce => 0.0,
            Output::ContactCount => self.contact_count as f64,
            Output::SlipRegime => match regime {
                Regime::Free => 0.0,
                Regime::Rolling => 4.0,
                Regime::Contact if sigma > 0.0 => 2.0,
                Regime::Contact if sigma < 0.0 => 3.0,
                Regime::Contact => 1.0,
            },
            Output::Xs => to(Dimension::Length, ring.xs),
            Output::Ys => to(Dimension::Length, ring.ys),
            Output::Vxs => to(Dimension::Velocity, ring.vxs),
            Output::Vys => to(Dimension::Velocity, ring.vys),
        }
    }
}

/// The normal contact force at `state`: the planar model's (n'K_s g), or for the ring with
/// mass k̂_c (z − 1) with z the distance from the ring's centre (`docs/MODEL.md` §17).
fn normal_force(problem: &Problem, time: f64, state: &State, ring: &RingState) -> f64 {
    let p = &problem.params;
    if p.stator_mass_ratio > 0.0 {
        let z = (state.x - ring.xs - p.offset_x).hypot(state.y - ring.ys - p.offset_y);
        (p.contact_stiffness * (z - 1.0)).max(0.0)
    } else {
        field::friction_at(p, time, state).normal
    }
}
