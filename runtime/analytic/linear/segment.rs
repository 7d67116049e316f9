//! The linearized contact segment itself: [`Linearization`] plus an initial state and an extra
//! cubic forcing, evaluated in closed form (`docs/MODEL.md` §5, §8), with its acceleration and
//! a jerk bound for friction's switch (`docs/MODEL.md` §10).

use super::Linearization;
use crate::analytic::segment::Bounds;
use crate::analytic::series::{self, Series};
use crate::coefficients::{
    self as coef, ContactBasis, ContactModes, ContactParticular, Force, HomogeneousStart,
    LinearizedContact, LocalTime, ModelParams, Phasor, PolynomialParticular, Position, Velocity,
};
use crate::math;
use crate::params::State;

/// How the response to the extra cubic forcing is represented.
#[derive(Clone, Copy, Debug)]
#[allow(
    clippy::large_enum_variant,
    reason = "the runtime has no heap to box into"
)]
pub enum Response {
    /// No extra forcing.
    None,
    /// The generated cubic particular solution (its homogeneous complement is in q0, w0).
    Polynomial(PolynomialParticular),
    /// The zero-state response as a Taylor polynomial Σ c_m s^m (x and y coefficients), from
    /// the equations of motion: c0 = c1 = 0 and
    /// (m + 2)(m + 1) c_{m+2} = a_m − 2ν(m + 1) c_{m+1} − Kl c_m (`docs/MODEL.md` §3).
    Series(Series),
}

/// `unforced + q` componentwise (the last sum of [`LinearSegment::state_with`]).
#[inline]
pub(super) fn add_response(unforced: &State, q: &[f64; 4]) -> State {
    State::new(
        unforced.x + q[0],
        unforced.y + q[1],
        unforced.vx + q[2],
        unforced.vy + q[3],
    )
}

impl Linearization {
    /// The series length of a cubic forcing's response over `horizon` where the series form
    /// is used (‖Kl‖·horizon² ≤ 1), else `None` (the polynomial particular solution). One
    /// sub-step's stages share it ([`Linearization::segment_with`],
    /// [`Linearization::forced_state_with`]).
    pub fn cubic_terms(&self, horizon: f64) -> Option<usize> {
        (self.norm_kl * horizon * horizon <= 1.0)
            .then(|| series::series_len(self.norm_kl, self.nu, horizon))
    }

    /// The state at `s` of the segment from the same start with the extra cubic `forcing` over
    /// `horizon`, given `unforced`, the state at `s` of the segment without extra forcing — when
    /// that segment's response is a Taylor series or absent, so that both share their
    /// homogeneous and harmonic parts (`None` otherwise: build the segment). The same sums in
    /// the same order as [`LinearSegment::state_with`], so the same bits.
    pub fn forced_state(
        &self,
        unforced: &State,
        forcing: &[f64; 8],
        horizon: f64,
        s: f64,
    ) -> Option<State> {
        self.forced_state_with(unforced, forcing, self.cubic_terms(horizon), s)
    }

    /// [`Linearization::forced_state`] with [`Linearization::cubic_terms`] of the horizon given.
    pub fn forced_state_with(
        &self,
        unforced: &State,
        forcing: &[f64; 8],
        cubic_terms: Option<usize>,
        s: f64,
    ) -> Option<State> {
        if self.resonant {
            // The unforced segment's series holds the harmonic forcing: build the segment.
            return None;
        }
        if forcing.iter().all(|&a| a == 0.0) {
            return Some(*unforced);
        }
        let q = self.recurrence(forcing).value(cubic_terms?, s);
        Some(add_response(unforced, &q))
    }
}

/// What a segment adds to its [`Linearization`]: the response to its extra cubic forcing, its
/// homogeneous start and the forcing. Evaluated with its linearization by
/// [`Linearization::state_of`]; kept apart so that a sub-step builds the stages it only evaluates
/// without copying the linearization.
#[derive(Clone, Copy, Debug)]
pub struct Part {
    pub(super) response: Response,
    pub(super) start: HomogeneousStart,
    /// The extra cubic forcing `[a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y]`.
    pub(super) forcing: [f64; 8],
}

impl Part {
    /// No response, a zero start and no forcing (a slot for [`Linearization::fill`]).
    pub fn empty() -> Part {
        Part {
            response: Response::None,
            start: HomogeneousStart::default(),
            forcing: [0.0; 8],
        }
    }
}

impl Linearization {
    /// The state at `s` of the segment of this linearization with the part `part`, given
    /// precomputed scalars (see [`Linearization::scalars`]).
    pub fn state_of(&self, part: &Part, s: f64, scalars: &ContactBasis) -> State {
        let l = self;
        let h = coef::contact_homogeneous_eval(&l.model, &l.kl, &l.modes, &part.start, scalars);
        let p = l.particular_state(s);
        let q = match &part.response {
            Response::None => [0.0; 4],
            Response::Polynomial(b) => {
                let q = coef::polynomial_eval(&LocalTime { s }, b);
                [q.x, q.y, q.vx, q.vy]
            }
            Response::Series(c) => c.eval(s),
        };
        State::new(
            h.x + p[0] + q[0],
            h.y + p[1] + q[1],
            h.vx + p[2] + q[2],
            h.vy + p[3] + q[3],
        )
    }

    /// [`LinearSegment::state_from_unforced`] of the segment of this linearization with the
    /// part `part`.
    pub fn state_from_unforced(&self, part: &Part, s: f64, unforced: &State) -> Option<State> {
        if self.resonant {
            return None;
        }
        match &part.response {
            Response::None => Some(*unforced),
            Response::Series(c) => Some(add_response(unforced, &c.eval(s))),
            Response::Polynomial(_) => None,
        }
    }
}

/// A linearized contact segment: [`Linearization`] plus initial state and cubic forcing.
#[derive(Clone, Copy, Debug)]
pub struct LinearSegment {
    pub(super) lin: Linearization,
    pub(super) part: Part,
}

impl LinearSegment {
    /// The state at `s` given precomputed scalars (see [`Linearization::scalars`]).
    pub fn state_with(&self, s: f64, scalars: &ContactBasis) -> State {
        self.lin.state_of(&self.part, s, scalars)
    }

    /// The state at `s` given `unforced`, the state at `s` of the segment without extra forcing
    /// from the same start (see [`Linearization::forced_state`]), when this segment's response
    /// shares its homogeneous part (a series or none); `None` for a polynomial response.
    pub fn state_from_unforced(&self, s: f64, unforced: &State) -> Option<State> {
        self.lin.state_from_unforced(&self.part, s, unforced)
    }

    /// The linearization and the part, the part writable (to build a segment in place with
    /// [`Linearization::fill`] after writing the linearization with
    /// [`Linearization::slipping_with`]).
    pub fn split_mut(&mut self) -> (&mut Linearization, &mut Part) {
        (&mut self.lin, &mut self.part)
    }

    /// A segment with every coefficient zero (a slot to be filled by
    /// [`Linearization::segment_into`]).
    pub(crate) fn zeroed() -> LinearSegment {
        LinearSegment {
            lin: Linearization {
                kl: LinearizedContact::default(),
                modes: ContactModes::default(),
                particular: ContactParticular::default(),
                model: ModelParams::default(),
                nu: 0.0,
                eta: 0.0,
                phase0: (1.0, 0.0),
                norm_a: 0.0,
                norm_kl: 0.0,
                gains: (0.0, 0.0),
                harmonic_amplitude: 0.0,
                harmonic_shift: 0.0,
                resonant: false,
                slip: 0.0,
            },
            part: Part::empty(),
        }
    }

    /// The acceleration q″ at local time `s` of the segment whose state there is `state`: the
    /// generated `linearized_contact_field`, q″ = F(cos θ, sin θ) + u + a(s) − 2ν q′ − Kl q − Fd,
    /// with the extra cubic forcing a(s) of the segment.
    pub fn acceleration(&self, s: f64, state: &State) -> (f64, f64) {
        let l = &self.lin;
        let (ct, st) = l.phasor(s);
        let [a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y] = self.part.forcing;
        let load = Force {
            fx: a0x + s * (a1x + s * (a2x + s * a3x)),
            fy: a0y + s * (a1y + s * (a2y + s * a3y)),
        };
        let a = coef::linearized_contact_field(
            &l.model,
            &Position {
                x: state.x,
                y: state.y,
            },
            &Velocity {
                vx: state.vx,
                vy: state.vy,
            },
            &load,
            &Phasor { ct, st },
            &l.kl,
        );
        (a.ax, a.ay)
    }

    /// A bound of |q‴| on [lo, hi]: q‴ is the rate of [`Self::acceleration`],
    /// J_v q″ + J_q q′ + (the forcing's rate) + a′(s) with J_v, J_q the field's Jacobians in q′
    /// and q (generated `linear_field_jacobians`: the gains of the segment's bounds) and the
    /// forcing's rate of length F η at every phase (generated `forcing_rate`), so with the
    /// segment's speed and acceleration bounds `b` on the same interval
    /// ([`crate::analytic::segment::Segment::bounds`]):
    /// |q‴| ≤ g_v A + g_q V + F η + |a′|.
    pub fn jerk_bound(&self, hi: f64, b: &Bounds) -> f64 {
        let l = &self.lin;
        let [_, _, a1x, a1y, a2x, a2y, a3x, a3y] = self.part.forcing;
        let h = math::abs(hi);
        let extra = math::hypot(a1x, a1y)
            + 2.0 * h * math::hypot(a2x, a2y)
            + 3.0 * h * h * math::hypot(a3x, a3y);
        let rate = coef::forcing_rate(&l.model, &Phasor { ct: 1.0, st: 0.0 });
        l.gains.0 * b.accel + l.gains.1 * b.speed + math::hypot(rate.fx, rate.fy) + extra
    }

    /// The extra cubic forcing `[a0x, a0y, a1x, a1y, a2x, a2y, a3x, a3y]`.
    pub fn forcing(&self) -> &[f64; 8] {
        &self.part.forcing
    }

    /// The linearization this segment belongs to.
    pub fn linearization(&self) -> &Linearization {
        &self.lin
    }
}
