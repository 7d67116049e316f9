//! The C-visible types and constants (`#[repr(C)]`, mirrored in `include/rotor_rub.h`), and
//! their conversions to and from the Rust API.

use rotor_rub::stepper::{EVENT_CAPACITY, OnCap, StepReport, StepperConfig, SwitchStart};
use rotor_rub::{ContactScheme, EventKind, Params, Regime, State};

/// Success.
pub const ROTOR_RUB_OK: i32 = 0;
/// A required pointer argument was null.
pub const ROTOR_RUB_ERR_NULL: i32 = 1;
/// The stepper memory is not aligned to `rotor_rub_stepper_align()`.
pub const ROTOR_RUB_ERR_MISALIGNED: i32 = 2;
/// The stepper memory was not initialised by a successful `rotor_rub_stepper_init`.
pub const ROTOR_RUB_ERR_NOT_INITIALIZED: i32 = 3;
/// A parameter or initial-state value is invalid (not finite, outside its range, or a
/// cross-parameter rule broken).
pub const ROTOR_RUB_ERR_INVALID_PARAMS: i32 = 4;
/// A configuration value is invalid (scheme, sub-step counts).
pub const ROTOR_RUB_ERR_INVALID_CONFIG: i32 = 5;
/// The step length is not finite, not in (0, 1], or too small to advance the time.
pub const ROTOR_RUB_ERR_INVALID_STEP: i32 = 6;
/// The motion diverged (flutter): the stepper is left at the start of the failed step.
pub const ROTOR_RUB_ERR_DIVERGED: i32 = 7;
/// The linearized contact system is singular or resonant.
pub const ROTOR_RUB_ERR_SINGULAR_CONTACT: i32 = 8;
/// An argument has no such value: an enumeration (preset, scheme), a parameter index or name,
/// or a buffer capacity larger than any buffer can be.
pub const ROTOR_RUB_ERR_INVALID_ARGUMENT: i32 = 9;
/// An internal error was caught at the boundary (a bug: please report it).
pub const ROTOR_RUB_ERR_INTERNAL: i32 = 10;
/// A step would have exceeded its bounded work (`on_cap` = `ROTOR_RUB_ON_CAP_FAIL`): refused,
/// the stepper is unchanged.
pub const ROTOR_RUB_ERR_BUDGET_EXCEEDED: i32 = 11;
/// A value given to a setter is invalid (not finite or outside its range).
pub const ROTOR_RUB_ERR_INVALID_VALUE: i32 = 12;

/// On a cap: finish the step less accurately and flag it (`capped`, `search_capped`).
pub const ROTOR_RUB_ON_CAP_DEGRADE: u32 = 0;
/// On a cap: refuse the step with `ROTOR_RUB_ERR_BUDGET_EXCEEDED`.
pub const ROTOR_RUB_ON_CAP_FAIL: u32 = 1;

/// Switch refinement starts by Newton from the bracket's end (the default).
pub const ROTOR_RUB_SWITCH_START_NEWTON: u32 = 0;
/// Switch refinement starts at the bracket's cubic Hermite root: fewer evaluations per switch,
/// the same switch to rounding (a tighter worst-case step time).
pub const ROTOR_RUB_SWITCH_START_HERMITE: u32 = 1;

/// Contact scheme: exprb2 (second order, cheaper).
pub const ROTOR_RUB_SCHEME_EXPRB2: i32 = 0;
/// Contact scheme: exprb43 (fourth order, the default).
pub const ROTOR_RUB_SCHEME_EXPRB43: i32 = 1;

/// Regime: free flight (no contact).
pub const ROTOR_RUB_REGIME_FREE: i32 = 0;
/// Regime: contact with the stator (slipping on it under friction).
pub const ROTOR_RUB_REGIME_CONTACT: i32 = 1;
/// Regime: rolling on the stator without slip (friction only).
pub const ROTOR_RUB_REGIME_ROLLING: i32 = 2;

/// Event kind: contact starts.
pub const ROTOR_RUB_EVENT_ENTER: i32 = 1;
/// Event kind: contact ends.
pub const ROTOR_RUB_EVENT_EXIT: i32 = 2;
/// Event kind: the slip direction reverses in contact (friction).
pub const ROTOR_RUB_EVENT_REVERSE: i32 = 3;
/// Event kind: rolling starts (friction).
pub const ROTOR_RUB_EVENT_ROLL: i32 = 4;
/// Event kind: rolling ends, slipping resumes (friction).
pub const ROTOR_RUB_EVENT_SLIP: i32 = 5;

/// Preset: the Fig. 2 caption's stiffnesses with offset (0.3, -0.2) (the project's "paper").
pub const ROTOR_RUB_PRESET_PAPER: i32 = 0;
/// Preset: the paper text's stiffnesses with zero offset ("paper-text").
pub const ROTOR_RUB_PRESET_PAPER_TEXT: i32 = 1;
/// Preset: Coulomb friction, backward whirl ("friction").
pub const ROTOR_RUB_PRESET_FRICTION: i32 = 2;
/// Preset: sustained dry whip, rolling ("dry-whip").
pub const ROTOR_RUB_PRESET_DRY_WHIP: i32 = 3;
/// Preset: the paper's rotor with a stator ring of mass m̂ = 1 ("stator-mass"; the ring's
/// stepper: `rotor_rub_stepper_ring_state` reads the ring).
pub const ROTOR_RUB_PRESET_STATOR_MASS: i32 = 4;
/// Preset: friction drives full annular backward whirl on a ring of mass ("ring-whirl").
pub const ROTOR_RUB_PRESET_RING_WHIRL: i32 = 5;

/// Switches one step result holds; more are counted in `dropped_events`.
pub const ROTOR_RUB_EVENT_CAPACITY: usize = 4;
/// Size of `RotorRubStepper` in 64-bit words: 5120 (40 KiB) since the stator ring with mass
/// runs in it (its n = 4 matrix model and the method's solvers live inline, no heap; the
/// planar stepper alone needed 160).
pub const ROTOR_RUB_STEPPER_WORDS: usize = 5120;

const _: () = assert!(ROTOR_RUB_EVENT_CAPACITY == EVENT_CAPACITY);
// The scheme codes are the library's (`ContactScheme::code`, the scheme registry).
const _: () = assert!(ROTOR_RUB_SCHEME_EXPRB2 == ContactScheme::Exprb2.code());
const _: () = assert!(ROTOR_RUB_SCHEME_EXPRB43 == ContactScheme::Exprb43.code());
// One f64 per model parameter of the table: adding one to the table without adding it here
// fails to compile.
const _: () = assert!(size_of::<RotorRubParams>() == 8 * rotor_rub::Parameter::MODEL_COUNT);

/// Model parameters (dimensionless, as in the paper). Valid ranges: `rotor_rub_parameter_info`
/// (the Rust parameter table, listed by `rotor-rub params`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotorRubParams {
    /// η: running speed over natural frequency.
    pub speed_ratio: f64,
    /// ν: damping ratio.
    pub damping_ratio: f64,
    /// η_m: unbalance mass ratio.
    pub mass_ratio: f64,
    /// ρ̂: unbalance eccentricity over clearance.
    pub eccentricity_ratio: f64,
    /// φ0: unbalance phase at τ = 0 (radians).
    pub phase: f64,
    /// K̂xx.
    pub k_xx: f64,
    /// K̂xy (cross-coupling).
    pub k_xy: f64,
    /// K̂yx (cross-coupling).
    pub k_yx: f64,
    /// K̂yy.
    pub k_yy: f64,
    /// ε̂x: stator offset, x.
    pub offset_x: f64,
    /// ε̂y: stator offset, y.
    pub offset_y: f64,
    /// μ: Coulomb friction coefficient at contact (0: frictionless).
    pub friction_coefficient: f64,
    /// ρ_R: rotor radius over radial clearance.
    pub radius_ratio: f64,
    /// u_x: external input force, x (per unit mass); `rotor_rub_stepper_set_input_force`
    /// changes it cheaply between steps.
    pub force_x: f64,
    /// u_y: external input force, y.
    pub force_y: f64,
    /// m̂: stator ring mass over disk mass (0: the paper's massless ring).
    pub stator_mass_ratio: f64,
    /// k̂_c: rotor–ring contact stiffness (with a ring mass only).
    pub contact_stiffness: f64,
    /// ĉ: ring support damping (with a ring mass only).
    pub stator_damping: f64,
    /// x̃s0: initial ring position x (with a ring mass only).
    pub xs0: f64,
    /// ỹs0: initial ring position y (with a ring mass only).
    pub ys0: f64,
    /// x̃s0': initial ring velocity x (with a ring mass only).
    pub vxs0: f64,
    /// ỹs0': initial ring velocity y (with a ring mass only).
    pub vys0: f64,
}

/// A state (x, y, x', y').
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RotorRubState {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// x'.
    pub vx: f64,
    /// y'.
    pub vy: f64,
}

/// How the stepper takes its steps (`rotor_rub_config_default` fills the defaults).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotorRubConfig {
    /// Step length the free-flight transition is precomputed for (default 1e-3).
    pub dt: f64,
    /// `ROTOR_RUB_SCHEME_EXPRB43` (default) or `ROTOR_RUB_SCHEME_EXPRB2`.
    pub scheme: i32,
    /// Contact sub-steps per step, >= 1 (default 1).
    pub contact_substeps: u32,
    /// Cap on contact sub-steps in one step call, >= contact_substeps (default 8).
    pub max_substeps: u32,
    /// What a step does at a cap: `ROTOR_RUB_ON_CAP_DEGRADE` (default) or
    /// `ROTOR_RUB_ON_CAP_FAIL` (the step returns `ROTOR_RUB_ERR_BUDGET_EXCEEDED`).
    pub on_cap: u32,
    /// `ROTOR_RUB_SWITCH_START_NEWTON` (default) or `ROTOR_RUB_SWITCH_START_HERMITE`.
    pub switch_start: u32,
}

/// A contact switch.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RotorRubEvent {
    /// Switch time τ.
    pub time: f64,
    /// `ROTOR_RUB_EVENT_ENTER`, `_EXIT`, or under friction `_REVERSE`, `_ROLL`, `_SLIP`.
    pub kind: i32,
    /// The state at the switch (on z = 1).
    pub state: RotorRubState,
}

/// The result of one step.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RotorRubStepResult {
    /// Time at the step end.
    pub time: f64,
    /// State at the step end.
    pub state: RotorRubState,
    /// `ROTOR_RUB_REGIME_FREE`, `_CONTACT` or (friction) `_ROLLING` at the step end.
    pub regime: i32,
    /// Switches stored in `events` (<= ROTOR_RUB_EVENT_CAPACITY).
    pub event_count: u32,
    /// Switches inside the step that did not fit in `events` (0 unless it overflowed).
    pub dropped_events: u32,
    /// Contact sub-steps taken.
    pub substeps: u32,
    /// 1 when the per-step sub-step cap was hit (less accurate step), else 0.
    pub capped: u32,
    /// 1 when a switch search hit its evaluation or refinement cap, else 0.
    pub search_capped: u32,
    /// Largest exprb43 error estimate of the step's contact sub-steps (0 if none).
    pub error_estimate: f64,
    /// The first `event_count` switches inside the step, in time order.
    pub events: [RotorRubEvent; ROTOR_RUB_EVENT_CAPACITY],
}

/// Caller-owned storage for one stepper: place it anywhere (stack, static, pool), initialise it
/// with `rotor_rub_stepper_init`. No call allocates; nothing needs freeing.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RotorRubStepper {
    /// Opaque.
    pub _opaque: [u64; ROTOR_RUB_STEPPER_WORDS],
}

impl RotorRubParams {
    /// The fields in table order: `RotorRubParams` is `repr(C)` with one `f64` per model
    /// parameter in the table's order (its size is checked at compile time above, its field
    /// order against the table by `tests/header.rs`), so it is laid out as that array.
    fn to_values(self) -> [f64; rotor_rub::Parameter::MODEL_COUNT] {
        // SAFETY: a `repr(C)` struct of MODEL_COUNT `f64` fields has the layout of
        // `[f64; MODEL_COUNT]` (same size, asserted above; alignment of f64; no padding).
        unsafe {
            core::mem::transmute::<RotorRubParams, [f64; rotor_rub::Parameter::MODEL_COUNT]>(self)
        }
    }

    fn from_values(values: [f64; rotor_rub::Parameter::MODEL_COUNT]) -> Self {
        // SAFETY: as in `to_values`.
        unsafe {
            core::mem::transmute::<[f64; rotor_rub::Parameter::MODEL_COUNT], RotorRubParams>(values)
        }
    }
}

impl From<RotorRubParams> for Params {
    fn from(p: RotorRubParams) -> Self {
        Params::from_values(p.to_values())
    }
}

impl From<Params> for RotorRubParams {
    fn from(p: Params) -> Self {
        RotorRubParams::from_values(p.values())
    }
}

impl From<RotorRubState> for State {
    fn from(s: RotorRubState) -> Self {
        State::new(s.x, s.y, s.vx, s.vy)
    }
}

impl From<State> for RotorRubState {
    fn from(s: State) -> Self {
        RotorRubState {
            x: s.x,
            y: s.y,
            vx: s.vx,
            vy: s.vy,
        }
    }
}

impl From<StepperConfig> for RotorRubConfig {
    fn from(c: StepperConfig) -> Self {
        RotorRubConfig {
            dt: c.dt,
            scheme: c.scheme.code(),
            contact_substeps: c.contact_substeps,
            max_substeps: c.max_substeps,
            on_cap: match c.on_cap {
                OnCap::Degrade => ROTOR_RUB_ON_CAP_DEGRADE,
                OnCap::Fail => ROTOR_RUB_ON_CAP_FAIL,
            },
            switch_start: match c.switch_start {
                SwitchStart::Newton => ROTOR_RUB_SWITCH_START_NEWTON,
                SwitchStart::Hermite => ROTOR_RUB_SWITCH_START_HERMITE,
            },
        }
    }
}

impl TryFrom<RotorRubConfig> for StepperConfig {
    type Error = i32;

    /// Fails with `ROTOR_RUB_ERR_INVALID_CONFIG` for an unknown scheme, cap policy or switch start.
    fn try_from(c: RotorRubConfig) -> Result<Self, i32> {
        let scheme = ContactScheme::from_code(c.scheme).ok_or(ROTOR_RUB_ERR_INVALID_CONFIG)?;
        let on_cap = match c.on_cap {
            ROTOR_RUB_ON_CAP_DEGRADE => OnCap::Degrade,
            ROTOR_RUB_ON_CAP_FAIL => OnCap::Fail,
            _ => return Err(ROTOR_RUB_ERR_INVALID_CONFIG),
        };
        let switch_start = match c.switch_start {
            ROTOR_RUB_SWITCH_START_NEWTON => SwitchStart::Newton,
            ROTOR_RUB_SWITCH_START_HERMITE => SwitchStart::Hermite,
            _ => return Err(ROTOR_RUB_ERR_INVALID_CONFIG),
        };
        Ok(StepperConfig {
            dt: c.dt,
            scheme,
            contact_substeps: c.contact_substeps,
            max_substeps: c.max_substeps,
            on_cap,
            switch_start,
        })
    }
}

/// The C code of a regime.
pub fn regime_code(regime: Regime) -> i32 {
    match regime {
        Regime::Free => ROTOR_RUB_REGIME_FREE,
        Regime::Contact => ROTOR_RUB_REGIME_CONTACT,
        Regime::Rolling => ROTOR_RUB_REGIME_ROLLING,
    }
}

impl From<&StepReport> for RotorRubStepResult {
    fn from(r: &StepReport) -> Self {
        let mut out = RotorRubStepResult {
            time: r.time,
            state: r.state.into(),
            regime: regime_code(r.regime),
            event_count: 0,
            dropped_events: r.events.dropped(),
            substeps: r.substeps,
            capped: u32::from(r.capped),
            search_capped: u32::from(r.search_capped),
            error_estimate: r.error_estimate,
            events: [RotorRubEvent::default(); ROTOR_RUB_EVENT_CAPACITY],
        };
        for (slot, e) in out.events.iter_mut().zip(r.events.iter()) {
            *slot = RotorRubEvent {
                time: e.time,
                kind: match e.kind {
                    EventKind::Enter => ROTOR_RUB_EVENT_ENTER,
                    EventKind::Exit => ROTOR_RUB_EVENT_EXIT,
                    EventKind::Reverse => ROTOR_RUB_EVENT_REVERSE,
                    EventKind::Roll => ROTOR_RUB_EVENT_ROLL,
                    EventKind::Slip => ROTOR_RUB_EVENT_SLIP,
                },
                state: e.state.into(),
            };
            out.event_count += 1;
        }
        out
    }
}
