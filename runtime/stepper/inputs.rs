//! What a fixed-rate loop changes between steps, cheaply: the external input force u
//! (`docs/MODEL.md` §15; a magnetic bearing or a controller, held constant over each step) and
//! the running speed with a continuous forcing phase; and the stepper's state as plain words, so
//! a rig can save it and roll back to it (FMI's get/set/serialize FMU state).

use super::friction::Slip;
use super::{FreeTransition, OnCap, Stepper, StepperConfig, StepperError, SwitchStart};
use crate::analytic::free::FreeConstants;
use crate::coefficients::{self as coef, ModelParams, Time};
use crate::math;
use crate::params::{Parameter, Params, Problem, State};
use crate::propagate::Regime;
use crate::registration::ContactScheme;

impl Stepper {
    /// Apply the input force u = (`fx`, `fy`) from the current time on (held until the next
    /// call). Each component must be finite and within its table range (`force_x`, `force_y`);
    /// on error nothing changes. Cost: one generated call and 16 multiplications (the free map
    /// gains the static deflection's offset, `FreeTransition::set_input`); Φ is kept. With
    /// u = 0 every step is bit for bit the step without an input force.
    pub fn set_input_force(&mut self, fx: f64, fy: f64) -> Result<(), StepperError> {
        Parameter::ForceX.check(fx)?;
        Parameter::ForceY.check(fy)?;
        if (fx, fy) == (self.params.force_x, self.params.force_y) {
            return Ok(());
        }
        self.params.force_x = fx;
        self.params.force_y = fy;
        let free = self.transition.constants().with_input((fx, fy));
        self.transition.set_input(&free);
        Ok(())
    }

    /// The input force in force.
    pub fn input_force(&self) -> (f64, f64) {
        (self.params.force_x, self.params.force_y)
    }

    /// Change the running speed η from the current time on, keeping the forcing phase θ
    /// continuous: the phase φ0 is re-based so that η'τ + φ0' = θ(τ) (wrapped to [0, 2π)).
    /// The unbalance amplitude follows η² (F = η_m ρ̂ η²). Costs a [`Stepper::set_params`]
    /// (G recomputed, Φ kept) when η changes, nothing otherwise. On error (η not finite or outside
    /// its range) nothing changes.
    pub fn set_speed_ratio(&mut self, eta: f64) -> Result<(), StepperError> {
        match at_speed(&self.params, self.time, eta)? {
            Some(params) => self.set_params(&params),
            None => Ok(()),
        }
    }

    /// The stepper's state as plain data ([`Snapshot`]); [`Stepper::restore`] rebuilds it.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            params: self.params,
            config: self.config,
            dt: self.transition.dt(),
            time: self.time,
            anchor_time: self.anchor_time,
            anchor_steps: self.anchor_steps,
            state: self.state,
            regime: self.regime,
            slip: self.slip,
            phasor: self.phasor,
        }
    }

    /// The stepper a [`Snapshot`] was taken of: its derived data (free constants, Φ) is
    /// recomputed by the same code from the same inputs, so stepping on gives the same bits as
    /// the original would have. Fails (nothing built) when the snapshot's parameters,
    /// configuration, step or state are invalid.
    pub fn restore(snapshot: &Snapshot) -> Result<Stepper, StepperError> {
        let s = snapshot;
        s.params.validate()?;
        s.params.planar()?;
        s.config.validate()?;
        super::check_dt(s.dt, s.time)?;
        let numbers = [
            s.time,
            s.anchor_time,
            s.slip.sigma,
            s.slip.offset,
            s.slip.scale,
            s.phasor.0,
            s.phasor.1,
        ];
        if numbers.iter().any(|v| !v.is_finite()) {
            return Err(StepperError::InvalidStep {
                dt: s.dt,
                time: s.time,
            });
        }
        super::check_bounded(s.time, s.state)?;
        let free = FreeConstants::new(&s.params);
        Ok(Stepper {
            params: s.params,
            config: s.config,
            transition: FreeTransition::new(&s.params, &free, s.dt),
            time: s.time,
            anchor_time: s.anchor_time,
            anchor_steps: s.anchor_steps,
            state: s.state,
            regime: s.regime,
            slip: s.slip,
            phasor: s.phasor,
        })
    }
}

/// Everything a [`Stepper`] is made of apart from what it recomputes: parameters (the input
/// force included), configuration, the step length Φ is precomputed for, the time and its
/// anchor, state, regime, slip and forcing phasor. [`Snapshot::to_words`] and
/// [`Snapshot::from_words`] write and read it as [`Snapshot::WORDS`] 64-bit words (f64 bits),
/// independent of the memory layout.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Snapshot {
    params: Params,
    config: StepperConfig,
    dt: f64,
    time: f64,
    anchor_time: f64,
    anchor_steps: u64,
    state: State,
    regime: Regime,
    slip: Slip,
    phasor: (f64, f64),
}

/// The words after the model parameters.
const TAIL: usize = 21;

impl Snapshot {
    /// Length of the serialized form in 64-bit words.
    pub const WORDS: usize = Parameter::MODEL_COUNT + TAIL;

    /// The snapshot as words: the model parameters in table order, then the rest.
    pub fn to_words(&self) -> [u64; Snapshot::WORDS] {
        let mut out = [0u64; Snapshot::WORDS];
        let problem = Problem {
            params: self.params,
            ..Problem::DEFAULT
        };
        let model = Parameter::ALL.iter().filter(|p| p.is_model());
        let c = &self.config;
        let tail: [u64; TAIL] = [
            c.dt.to_bits(),
            c.scheme.code() as u64,
            u64::from(c.contact_substeps),
            u64::from(c.max_substeps),
            match c.on_cap {
                OnCap::Degrade => 0,
                OnCap::Fail => 1,
            },
            match c.switch_start {
                SwitchStart::Newton => 0,
                SwitchStart::Hermite => 1,
            },
            self.dt.to_bits(),
            self.time.to_bits(),
            self.anchor_time.to_bits(),
            self.anchor_steps,
            self.state.x.to_bits(),
            self.state.y.to_bits(),
            self.state.vx.to_bits(),
            self.state.vy.to_bits(),
            match self.regime {
                Regime::Free => 0,
                Regime::Contact => 1,
                Regime::Rolling => 2,
            },
            self.slip.sigma.to_bits(),
            self.slip.offset.to_bits(),
            self.slip.scale.to_bits(),
            self.phasor.0.to_bits(),
            self.phasor.1.to_bits(),
            0x726f_746f_7272_7562,
        ];
        let values = model.map(|p| p.get(&problem).to_bits()).chain(tail);
        for (o, v) in out.iter_mut().zip(values) {
            *o = v;
        }
        out
    }

    /// The snapshot written by [`Snapshot::to_words`]. Fails on a wrong marker word or an
    /// unknown scheme, regime or cap policy; the values themselves are checked by
    /// [`Stepper::restore`].
    pub fn from_words(words: &[u64; Snapshot::WORDS]) -> Result<Snapshot, StepperError> {
        let invalid = |what, value: u64| StepperError::InvalidConfig {
            what,
            value: value as f64,
        };
        let (problem, t) = problem_and_tail::<TAIL>(words);
        let f = f64::from_bits;
        let [
            dt0,
            scheme,
            substeps,
            max_substeps,
            on_cap,
            switch_start,
            dt,
            time,
            anchor_time,
            anchor_steps,
            x,
            y,
            vx,
            vy,
            regime,
            sigma,
            offset,
            scale,
            c,
            s,
            marker,
        ] = t;
        if marker != 0x726f_746f_7272_7562 {
            return Err(invalid("snapshot marker", marker));
        }
        let scheme = i32::try_from(scheme)
            .ok()
            .and_then(ContactScheme::from_code)
            .ok_or(invalid("snapshot scheme", scheme))?;
        let count = |what, v: u64| u32::try_from(v).map_err(|_| invalid(what, v));
        Ok(Snapshot {
            params: problem.params,
            config: StepperConfig {
                dt: f(dt0),
                scheme,
                contact_substeps: count("contact_substeps", substeps)?,
                max_substeps: count("max_substeps", max_substeps)?,
                on_cap: match on_cap {
                    0 => OnCap::Degrade,
                    1 => OnCap::Fail,
                    other => return Err(invalid("snapshot on_cap", other)),
                },
                switch_start: match switch_start {
                    0 => SwitchStart::Newton,
                    1 => SwitchStart::Hermite,
                    other => return Err(invalid("snapshot switch_start", other)),
                },
            },
            dt: f(dt),
            time: f(time),
            anchor_time: f(anchor_time),
            anchor_steps,
            state: State::new(f(x), f(y), f(vx), f(vy)),
            regime: match regime {
                0 => Regime::Free,
                1 => Regime::Contact,
                2 => Regime::Rolling,
                other => return Err(invalid("snapshot regime", other)),
            },
            slip: Slip {
                sigma: f(sigma),
                offset: f(offset),
                scale: f(scale),
            },
            phasor: (f(c), f(s)),
        })
    }
}

/// The parameters a snapshot's words start with (the table's model entries, as bits) and the
/// `N` words after them: the common layout of a planar and a ring stepper's words.
pub(super) fn problem_and_tail<const N: usize>(
    words: &[u64; Snapshot::WORDS],
) -> (Problem, [u64; N]) {
    let (model, tail) = words.split_at(Parameter::MODEL_COUNT);
    let mut problem = Problem::DEFAULT;
    for (p, w) in Parameter::ALL.iter().filter(|p| p.is_model()).zip(model) {
        p.set(&mut problem, f64::from_bits(*w));
    }
    let mut t = [0u64; N];
    for (o, w) in t.iter_mut().zip(tail) {
        *o = *w;
    }
    (problem, t)
}

/// `params` running at speed `eta` from `time` on with the forcing phase θ continuous there: the
/// phase φ0 re-based so that η τ + φ0 = θ(τ), wrapped to [0, 2π) (the planar and the ring
/// stepper's speed input); `None` when `eta` is the speed already.
///
/// # Errors
/// η not finite or out of its range.
pub(super) fn at_speed(
    params: &Params,
    time: f64,
    eta: f64,
) -> Result<Option<Params>, StepperError> {
    Parameter::SpeedRatio.check(eta)?;
    if eta == params.speed_ratio {
        return Ok(None);
    }
    let model = ModelParams::of(params);
    let theta = math::wrap_angle(coef::forcing_phase(&model, &Time { t: time }).theta);
    let phase = math::wrap_angle(theta - math::wrap_angle(eta * time));
    Ok(Some(Params {
        speed_ratio: eta,
        phase,
        ..*params
    }))
}
