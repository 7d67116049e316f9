//! The closed form of one free flight of a rotor from matrices, and the station's motion along
//! it with rigorous bounds: what the switch search (`search.rs`) evaluates and bounds.
//!
//! y(t) = y_p(t) + e^{A(t − t0)} (y0 − y_p(t0)), y_p(t) = Re(Y e^{iθ(t)}) + y_u with the one
//! forcing phase θ (`field::phasor`, generated `forcing_phase`). The station's relative
//! position P = B q splits the same way: P(s) = P_h(s) + P_p(t0 + s) with P_h = B e^{As} c
//! ([`ProjectedMotion`], c = S⁻¹(y0 − y_p(t0))) and P_p = Re(P̂ e^{iθ}) + P_u
//! ([`ProjectedHarmonic`]).

use super::super::model::MatrixModel;
use super::super::state::MatrixState;
use crate::analytic::free::harmonic_amplitude;
use crate::coefficients::{self as coef, Position, Velocity};
use crate::field;
use crate::linalg::{
    Complex, HarmonicResponse, LinalgError, ModalExponential, ProjectedHarmonic, ProjectedMotion,
    ProjectedPoint,
};
use crate::math;

/// The model's free-flight decomposition: made once, shared by every segment.
#[derive(Clone, Debug)]
pub(super) struct Decomposition<const CAP: usize> {
    /// e^{As}.
    pub(super) modal: ModalExponential<CAP>,
    /// y_p: the steady response to the unbalance (amplitude at θ = 0) and to the input force.
    pub(super) harmonic: HarmonicResponse<CAP>,
    /// B y_p.
    pub(super) station: ProjectedHarmonic,
    /// σ1 ≥ |Re(P̂ e^{iθ})| for every θ (the largest singular value of the 2 × 2 real map,
    /// with its rounding margin).
    pub(super) harmonic_reach: f64,
    /// |P_u − ε̂|: the station's constant offset from the stator centre.
    pub(super) constant_offset: f64,
    /// η.
    pub(super) speed: f64,
}

/// Bounds over an interval of |P − ε̂| (`radius`), |P'| (`speed`) and |P''| (`acceleration`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Reach {
    pub(super) radius: f64,
    pub(super) speed: f64,
    pub(super) acceleration: f64,
}

impl<const CAP: usize> Decomposition<CAP> {
    /// Decompose `model`: A's modal form, the harmonic and constant responses, the projection
    /// of the harmonic response on the station (rows `bx`, `by` of B over y).
    pub(super) fn new(
        model: &MatrixModel<CAP>,
        bx: &[f64],
        by: &[f64],
    ) -> Result<Self, LinalgError> {
        let modal = ModalExponential::new(model.first_order())?;
        // The unbalance forces η²·Re(f̂ e^{iθ}): η² is the generated unbalance force per m·e.
        let force = model.running().unbalance_force;
        let mut amplitude = [Complex::ZERO; CAP];
        for (a, f) in amplitude.iter_mut().zip(model.unbalance()) {
            *a = f.scale(force);
        }
        let n = model.dofs();
        let harmonic = HarmonicResponse::new(
            &model.second_order(),
            model.speed_ratio(),
            amplitude.get(..n).unwrap_or(&[]),
            model.input(),
        )?;
        let station = harmonic.project(bx, by)?;
        let [px, py] = station.amplitude();
        let harmonic_reach = harmonic_amplitude(px.re, -px.im, py.re, -py.im);
        let [ux, uy] = station.constant();
        let d = coef::stator_offset(model.running(), &Position { x: ux, y: uy });
        Ok(Decomposition {
            modal,
            harmonic,
            station,
            harmonic_reach,
            constant_offset: math::hypot(d.u, d.v),
            speed: model.speed_ratio(),
        })
    }

    /// y_p at absolute time `t` (m entries of `out`).
    pub(super) fn particular(&self, model: &MatrixModel<CAP>, t: f64, out: &mut [f64]) {
        self.harmonic.state_at_phase(phase(model, t), out);
    }
}

/// e^{iθ(t)}: the forcing phasor at absolute time `t` (`field::phasor`).
fn phase<const CAP: usize>(model: &MatrixModel<CAP>, t: f64) -> Complex {
    let p = field::phasor(model.running(), t);
    Complex::new(p.ct, p.st)
}

/// One free segment: its start and the station's homogeneous motion from there.
#[derive(Clone, Debug)]
pub(super) struct Flight<const CAP: usize> {
    /// Absolute start time.
    pub(super) t0: f64,
    /// The start state (returned exactly at s = 0).
    pub(super) y0: MatrixState<CAP>,
    /// P_h(s) = B e^{As} c with c = S⁻¹(y0 − y_p(t0)).
    pub(super) motion: ProjectedMotion<CAP>,
    /// e^{iθ(t0)}, the forcing phasor at the start (kept for the start's point).
    pub(super) phase0: Complex,
}

/// The station along a flight at one local time: h = z² − 1, h' and P' (whose norm tightens
/// the curvature bound locally: [`StationPoint::speed`], computed only where a bound needs it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct StationPoint {
    pub(super) h: f64,
    pub(super) dh: f64,
    pub(super) rate: [f64; 2],
}

impl StationPoint {
    /// |P'|.
    pub(super) fn speed(&self) -> f64 {
        math::hypot(self.rate[0], self.rate[1])
    }
}

impl<const CAP: usize> Flight<CAP> {
    /// Start at `(t0, y0)`: c = S⁻¹(y0 − y_p(t0)).
    pub(super) fn start(
        &mut self,
        model: &MatrixModel<CAP>,
        d: &Decomposition<CAP>,
        t0: f64,
        y0: MatrixState<CAP>,
    ) -> Result<(), LinalgError> {
        let m = d.modal.dim();
        let mut relative = [0.0; CAP];
        let phase0 = phase(model, t0);
        d.harmonic.state_at_phase(phase0, &mut relative);
        for (r, &y) in relative.iter_mut().zip(y0.as_slice()) {
            *r = y - *r;
        }
        self.motion
            .set_state(&d.modal, relative.get(..m).unwrap_or(&[]))?;
        self.t0 = t0;
        self.y0 = y0;
        self.phase0 = phase0;
        Ok(())
    }

    /// The state at local time `s` ≥ 0: y0 itself at s = 0, else
    /// Re(S e^{Js} c) + y_p(t0 + s) (O(m²); a conjugate pair's partner block is not evaluated:
    /// [`ProjectedMotion::state`]).
    pub(super) fn state(
        &self,
        model: &MatrixModel<CAP>,
        d: &Decomposition<CAP>,
        s: f64,
    ) -> MatrixState<CAP> {
        if s <= 0.0 {
            return self.y0;
        }
        let m = d.modal.dim();
        let mut y = self.y0;
        let mut particular = [0.0; CAP];
        d.particular(model, self.t0 + s, &mut particular);
        let out = y.as_mut_slice();
        self.motion
            .state(&d.modal, s, out.get_mut(..m).unwrap_or(&mut []));
        for (o, &p) in out.iter_mut().zip(&particular) {
            *o += p;
        }
        y
    }

    /// The station at local time `s` (O(m): one complex exponential per mode): P and P' from
    /// the projected homogeneous and harmonic parts (no P'': h and h' do not need it), h and h'
    /// by the generated `switching_function`.
    pub(super) fn point(
        &self,
        model: &MatrixModel<CAP>,
        d: &Decomposition<CAP>,
        s: f64,
    ) -> StationPoint {
        let (value, rate) = self.motion.value_and_rate(&d.modal, s);
        station_point(
            model,
            value,
            rate,
            d.station.at_phase(phase(model, self.t0 + s)),
        )
    }

    /// [`Self::point`] at s = 0, the same values without exponentials or a new phasor.
    pub(super) fn start_point(
        &self,
        model: &MatrixModel<CAP>,
        d: &Decomposition<CAP>,
    ) -> StationPoint {
        let (value, rate) = self.motion.value_and_rate_at_start(&d.modal);
        station_point(model, value, rate, d.station.at_phase(self.phase0))
    }

    /// Bounds of |P − ε̂|, |P'|, |P''| over local times [lo, hi]: the homogeneous part's
    /// ([`ProjectedMotion::bound`]) plus the harmonic part's (σ1, ησ1, η²σ1) plus |P_u − ε̂|
    /// (triangle inequality).
    pub(super) fn reach(&self, d: &Decomposition<CAP>, lo: f64, hi: f64) -> Reach {
        let b = self.motion.bound(&d.modal, lo, hi);
        combine(d, b.value, b.rate, b.acceleration)
    }

    /// [`Self::reach`] over every s ≥ lo (∞ when a mode the station sees grows, or does not
    /// decay beyond its leading term).
    pub(super) fn reach_after(&self, d: &Decomposition<CAP>, lo: f64) -> Reach {
        let b = self.motion.bound_after(&d.modal, lo);
        combine(d, b.value, b.rate, b.acceleration)
    }
}

/// The station from its homogeneous part's P, P' and the particular part.
#[inline(always)]
fn station_point<const CAP: usize>(
    model: &MatrixModel<CAP>,
    value: [f64; 2],
    rate: [f64; 2],
    p: ProjectedPoint,
) -> StationPoint {
    let at = Position {
        x: value[0] + p.value[0],
        y: value[1] + p.value[1],
    };
    let rate = Velocity {
        vx: rate[0] + p.rate[0],
        vy: rate[1] + p.rate[1],
    };
    let sw = coef::switching_function(model.running(), &at, &rate);
    StationPoint {
        h: sw.h,
        dh: sw.dh,
        rate: [rate.vx, rate.vy],
    }
}

/// The parts' bounds added. Each part carries its own relative margin for rounding (1e-12);
/// σ1 is capped by the Frobenius norm, which a rank-one amplitude meets with its last ulp
/// rounded either way, so the harmonic part gets 16ε more.
fn combine<const CAP: usize>(d: &Decomposition<CAP>, value: f64, rate: f64, acc: f64) -> Reach {
    let eta = d.speed;
    let sigma = d.harmonic_reach * (1.0 + 16.0 * f64::EPSILON);
    Reach {
        radius: value + sigma + d.constant_offset,
        speed: rate + eta * sigma,
        acceleration: acc + eta * eta * sigma,
    }
}
