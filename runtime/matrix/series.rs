//! One Taylor expansion of a matrix model's contact regime about a state (`docs/MODEL.md` §16,
//! §17): the linear part is a matrix–series product, the station's law the generated
//! recurrences (`coefficients::station_contact_taylor`, `station_slipping_taylor`,
//! `station_rolling_taylor`), the forcing phasor carried by them. At each order N:
//!
//! 1. a_N = (A y_N)'s acceleration part + η² Re(M⁻¹f̂ (cos θ, sin θ)_N) (+ M⁻¹u at N = 0): the
//!    acceleration of every force but the contact's;
//! 2. the law's inputs at order N: P_N = B q_N (−ε̂ is the law's), P'_N = B q'_N, and while
//!    rolling the drive B a_N; then the law's order N (its restoring force r_N = −f_c,N, the
//!    switch functions, the phasor's order N + 1);
//! 3. y_{N+1} = (q'_N, a_N − M⁻¹Bᵀ r_N) / (N + 1).
//!
//! The order, the step (Jorba–Zou) and the switch polynomials are as for the planar model
//! (`crate::taylor`); the state's series are stored coefficient-major, so that each order's
//! matrix product and each evaluation run over contiguous entries.

use super::model::MatrixModel;
use crate::coefficients::{
    Slip, station_contact_taylor as contact, station_rolling_taylor as rolling,
    station_slipping_taylor as slipping,
};
use crate::math;
use crate::propagate::Regime;
use crate::refine::Knot;
pub use crate::taylor::expansion::Switch;
use crate::taylor::kernels::orders;
use crate::taylor::kernels::{self, CAPACITY, MAX_ORDER, StationSeries};

/// The station's law: which generated recurrences, with their constants.
#[derive(Clone, Copy, Debug)]
enum Law {
    Contact(contact::Constants),
    Slipping(slipping::Constants),
    Rolling(rolling::Constants),
}

/// Where a law's series are (every law stores P, P', the phasor first, in one order).
struct Layout {
    restoring: (usize, usize),
    boundary: usize,
}

const _: () = {
    assert!(
        contact::RELATIVE_X == slipping::RELATIVE_X && slipping::RELATIVE_X == rolling::RELATIVE_X
    );
    assert!(
        contact::RELATIVE_Y == slipping::RELATIVE_Y && slipping::RELATIVE_Y == rolling::RELATIVE_Y
    );
    assert!(
        contact::RELATIVE_VX == slipping::RELATIVE_VX
            && slipping::RELATIVE_VX == rolling::RELATIVE_VX
    );
    assert!(
        contact::RELATIVE_VY == slipping::RELATIVE_VY
            && slipping::RELATIVE_VY == rolling::RELATIVE_VY
    );
    assert!(contact::PHASOR_CT == slipping::PHASOR_CT && slipping::PHASOR_CT == rolling::PHASOR_CT);
    assert!(contact::PHASOR_ST == slipping::PHASOR_ST && slipping::PHASOR_ST == rolling::PHASOR_ST);
};

const RELATIVE: [usize; 4] = [
    contact::RELATIVE_X,
    contact::RELATIVE_Y,
    contact::RELATIVE_VX,
    contact::RELATIVE_VY,
];
const PHASOR: (usize, usize) = (contact::PHASOR_CT, contact::PHASOR_ST);

impl Law {
    fn layout(&self) -> Layout {
        match self {
            Law::Contact(_) => Layout {
                restoring: (contact::RESTORING_X, contact::RESTORING_Y),
                boundary: contact::BOUNDARY,
            },
            Law::Slipping(_) => Layout {
                restoring: (slipping::RESTORING_X, slipping::RESTORING_Y),
                boundary: slipping::BOUNDARY,
            },
            Law::Rolling(_) => Layout {
                restoring: (rolling::RESTORING_X, rolling::RESTORING_Y),
                boundary: rolling::BOUNDARY,
            },
        }
    }
}

/// The series of one step's expansion of a matrix model in contact.
#[derive(Clone)]
pub struct MatrixExpansion<const CAP: usize> {
    law: Law,
    /// σ while slipping (1 otherwise): the slip-velocity switch is σw.
    slip: f64,
    order: usize,
    /// Coefficient k of y = (q, q') at `state[k]` (2n entries used).
    state: [[f64; CAP]; CAPACITY],
    /// The law's series (inputs, phasor, law, switch functions).
    station: StationSeries,
}

impl<const CAP: usize> MatrixExpansion<CAP> {
    /// An expansion of order `order` (clamped to [2, [`MAX_ORDER`]]) for `model`'s
    /// frictionless contact.
    pub fn new(model: &MatrixModel<CAP>, order: usize) -> Self {
        MatrixExpansion {
            law: Law::Contact(contact::constants(model.running(), model.law())),
            slip: 1.0,
            order: order.clamp(2, MAX_ORDER),
            state: [[0.0; CAP]; CAPACITY],
            station: [[0.0; CAPACITY]; crate::coefficients::STATION_TAYLOR_SERIES_MAX],
        }
    }

    /// Switch to the law of `regime` (slipping in direction `slip` when `slip` ≠ 0).
    pub fn set_regime(&mut self, model: &MatrixModel<CAP>, regime: Regime, slip: f64) {
        self.slip = if slip < 0.0 { -1.0 } else { 1.0 };
        let m = model.running();
        self.law = match regime {
            Regime::Rolling => Law::Rolling(rolling::constants(m, model.law(), model.compliance())),
            _ if slip != 0.0 => {
                Law::Slipping(slipping::constants(m, &Slip { sigma: slip }, model.law()))
            }
            _ => Law::Contact(contact::constants(m, model.law())),
        };
    }

    /// The switch functions of the current law.
    pub fn switches(&self) -> &'static [Switch] {
        match self.law {
            Law::Contact(_) => &[Switch::Boundary],
            Law::Slipping(_) => &[Switch::Boundary, Switch::SlipVelocity],
            Law::Rolling(_) => &[Switch::Boundary, Switch::ConeUpper, Switch::ConeLower],
        }
    }

    /// The order of the expansion (the degree of its polynomials).
    pub fn order(&self) -> usize {
        self.order
    }

    /// Expand `model`'s current law about `y` (2n entries) with the forcing phasor
    /// (cos θ, sin θ): every series to the order.
    pub fn expand(&mut self, model: &MatrixModel<CAP>, y: &[f64], (ct, st): (f64, f64)) {
        if let Some(first) = self.state.first_mut() {
            *first = [0.0; CAP];
            for (c, &v) in first.iter_mut().zip(y) {
                *c = v;
            }
        }
        if let Some(c) = self.station.get_mut(PHASOR.0).and_then(|s| s.first_mut()) {
            *c = ct;
        }
        if let Some(c) = self.station.get_mut(PHASOR.1).and_then(|s| s.first_mut()) {
            *c = st;
        }
        let mut acc = [0.0; CAP];
        self.inputs(model, 0, &mut acc);
        match &self.law {
            Law::Contact(k) => contact::order0(k, &mut self.station),
            Law::Slipping(k) => slipping::order0(k, &mut self.station),
            Law::Rolling(k) => rolling::order0(k, &mut self.station),
        }
        self.feedback(model, 0, &acc);
        let p = self.order;
        orders!(p, |N| {
            self.inputs(model, N, &mut acc);
            match &self.law {
                Law::Contact(k) => contact::order::<N>(k, &mut self.station),
                Law::Slipping(k) => slipping::order::<N>(k, &mut self.station),
                Law::Rolling(k) => rolling::order::<N>(k, &mut self.station),
            }
            self.feedback(model, N, &acc);
        });
    }

    /// Order `n`'s acceleration without contact a_n into `acc`, and the law's inputs at `n`.
    #[inline]
    fn inputs(&mut self, model: &MatrixModel<CAP>, n: usize, acc: &mut [f64; CAP]) {
        // A model that fills its storage (the ring in CAP = 8): the same body with constant
        // lengths (as `MatrixModel::derivative`).
        if 2 * model.dofs() == CAP {
            self.inputs_of_size(CAP / 2, model, n, acc);
        } else {
            self.inputs_of_size(model.dofs(), model, n, acc);
        }
    }

    /// [`Self::inputs`] for `dofs` = the model's DOFs.
    #[inline(always)]
    fn inputs_of_size(
        &mut self,
        dofs: usize,
        model: &MatrixModel<CAP>,
        n: usize,
        acc: &mut [f64; CAP],
    ) {
        let y = self.state.get(n).copied().unwrap_or([0.0; CAP]);
        let coef = |s: usize| kernels::at(self.station.get(s).unwrap_or(&[0.0; CAPACITY]), n);
        let (ct, st) = (coef(PHASOR.0), coef(PHASOR.1));
        let force = model.running().unbalance_force;
        let a = model.linear();
        let (unbalance, input, _) = model.force_accelerations();
        let mut linear = [0.0; CAP];
        a.times(&y, linear.get_mut(..dofs).unwrap_or(&mut []));
        for (i, (out, &linear)) in acc.iter_mut().zip(&linear).enumerate().take(dofs) {
            let u = unbalance.get(i).copied().unwrap_or_default();
            let constant = if n == 0 {
                input.get(i).copied().unwrap_or(0.0)
            } else {
                0.0
            };
            *out = linear + force * (u.re * ct - u.im * st) + constant;
        }
        let (q, v) = y.split_at(dofs.min(CAP));
        let values = [
            model.station_component(q, 0),
            model.station_component(q, 1),
            model.station_component(v, 0),
            model.station_component(v, 1),
        ];
        for (&s, value) in RELATIVE.iter().zip(values) {
            if let Some(series) = self.station.get_mut(s) {
                kernels::set(series, n, value);
            }
        }
        if let Law::Rolling(_) = self.law {
            let drive = [
                (rolling::DRIVE_X, model.station_component(acc, 0)),
                (rolling::DRIVE_Y, model.station_component(acc, 1)),
            ];
            for (s, value) in drive {
                if let Some(series) = self.station.get_mut(s) {
                    kernels::set(series, n, value);
                }
            }
        }
    }

    /// y_{n+1} from order n: q_{n+1} = q'_n/(n+1), q'_{n+1} = (a_n − M⁻¹Bᵀ r_n)/(n+1).
    #[inline]
    fn feedback(&mut self, model: &MatrixModel<CAP>, n: usize, acc: &[f64; CAP]) {
        if 2 * model.dofs() == CAP {
            self.feedback_of_size(CAP / 2, model, n, acc);
        } else {
            self.feedback_of_size(model.dofs(), model, n, acc);
        }
    }

    /// [`Self::feedback`] for `dofs` = the model's DOFs.
    #[inline(always)]
    fn feedback_of_size(
        &mut self,
        dofs: usize,
        model: &MatrixModel<CAP>,
        n: usize,
        acc: &[f64; CAP],
    ) {
        let layout = self.law.layout();
        let coef = |s: usize| kernels::at(self.station.get(s).unwrap_or(&[0.0; CAPACITY]), n);
        let (rx, ry) = (coef(layout.restoring.0), coef(layout.restoring.1));
        let inverse = 1.0 / (n as f64 + 1.0);
        let y = self.state.get(n).copied().unwrap_or([0.0; CAP]);
        let (_, _, [cx, cy]) = model.force_accelerations();
        let (Some(cx), Some(cy)) = (cx.get(..dofs), cy.get(..dofs)) else {
            return;
        };
        let Some(next) = self.state.get_mut(n + 1) else {
            return;
        };
        *next = [0.0; CAP];
        let (dq, dv) = next.split_at_mut(dofs.min(CAP));
        for (d, &v) in dq.iter_mut().zip(y.iter().skip(dofs)) {
            *d = v * inverse;
        }
        for (((d, &a), &x), &yy) in dv.iter_mut().zip(acc.iter()).zip(cx).zip(cy) {
            *d = (a - x * rx - yy * ry) * inverse;
        }
    }

    /// The step the expansion is good for (Jorba–Zou, with heyoka's safety factors, as the
    /// planar model's `crate::taylor::expansion`): ρ = min over the last two orders n of
    /// (max(1, ‖x₀‖∞)/‖xₙ‖∞)^{1/n} over y's 2n entries and the phasor,
    /// h = ρ/e² · e^{−0.7/(p−1)}.
    pub fn step_size(&self, dofs: usize) -> f64 {
        let p = self.order;
        let norm = |k: usize| {
            let y = self.state.get(k).map_or(0.0, |c| {
                c.iter()
                    .take(2 * dofs)
                    .map(|x| math::abs(*x))
                    .fold(0.0, f64::max)
            });
            let phasor = [PHASOR.0, PHASOR.1]
                .iter()
                .map(|&s| {
                    math::abs(kernels::at(
                        self.station.get(s).unwrap_or(&[0.0; CAPACITY]),
                        k,
                    ))
                })
                .fold(0.0, f64::max);
            y.max(phasor)
        };
        let log_reference = math::ln(norm(0).max(1.0));
        let log_radius = |k: usize| {
            let v = norm(k);
            if v > 0.0 {
                (log_reference - math::ln(v)) / k as f64
            } else {
                f64::INFINITY
            }
        };
        let log_rho = log_radius(p - 1).min(log_radius(p));
        math::exp(log_rho - 2.0 - 0.7 / (p as f64 - 1.0))
    }

    /// y at local time `s` (degree p, Horner over the 2n entries).
    pub fn state_at(&self, s: f64) -> [f64; CAP] {
        let mut out = [0.0; CAP];
        for c in self.state.iter().take(self.order + 1).rev() {
            for (o, &ck) in out.iter_mut().zip(c) {
                *o = *o * s + ck;
            }
        }
        out
    }

    /// The positions at `s` with the position polynomials' derivative as the velocities: the
    /// state whose switching function's rate is the polynomial's own (for Newton on it).
    fn positions_with_rates(&self, s: f64, dofs: usize) -> [f64; CAP] {
        let mut value = [0.0; CAP];
        let mut rate = [0.0; CAP];
        for c in self.state.iter().take(self.order + 1).rev() {
            for ((v, d), &ck) in value.iter_mut().zip(rate.iter_mut()).zip(c).take(dofs) {
                *d = *d * s + *v;
                *v = *v * s + ck;
            }
        }
        for (v, &d) in value.iter_mut().skip(dofs).zip(rate.iter()).take(dofs) {
            *v = d;
        }
        value
    }

    /// The forcing phasor (cos θ, sin θ) at local time `s`, from its series.
    pub fn phasor_at(&self, s: f64) -> (f64, f64) {
        let value = |i: usize| {
            self.station
                .get(i)
                .map_or(0.0, |c| kernels::evaluate(c, self.order, s))
        };
        (value(PHASOR.0), value(PHASOR.1))
    }

    /// The switch function's polynomial coefficients (positive inside the regime).
    pub fn switch_polynomial(&self, switch: Switch) -> [f64; CAPACITY] {
        let (index, sign) = match (switch, &self.law) {
            (Switch::Boundary, law) => (law.layout().boundary, 1.0),
            (Switch::SlipVelocity, _) => (slipping::SLIP_VELOCITY, self.slip),
            (Switch::ConeUpper, _) => (rolling::CONE_UPPER, 1.0),
            (Switch::ConeLower, _) => (rolling::CONE_LOWER, 1.0),
        };
        let mut c = self.station.get(index).copied().unwrap_or([0.0; CAPACITY]);
        for ck in &mut c {
            *ck *= sign;
        }
        c
    }

    /// The size of the terms a switch function's value at the expansion point is computed from:
    /// 1 for z² − 1, |P'| + ρ_R η for w, μN + |λ| for the friction cone.
    pub fn rounding_scale(&self, switch: Switch, model: &MatrixModel<CAP>) -> f64 {
        let at0 = |i: usize| {
            self.station
                .get(i)
                .map_or(0.0, |c| math::abs(kernels::at(c, 0)))
        };
        match switch {
            Switch::Boundary => 1.0,
            Switch::SlipVelocity => {
                let r = model.running();
                at0(RELATIVE[2]).max(at0(RELATIVE[3])) + math::abs(r.radius_ratio * r.speed_ratio)
            }
            Switch::ConeUpper | Switch::ConeLower => {
                at0(rolling::CONE_UPPER).max(at0(rolling::CONE_LOWER))
            }
        }
    }

    /// Put the exit through z = 1 near local time `s` (the switch polynomial's root) onto the
    /// surface of the step's polynomial state: h = z² − 1 of the polynomial state
    /// (`MatrixModel::switching`, the velocities the position polynomials' derivative)
    /// bracketed about `s` within [0, `h`] and refined by the one refinement; `s` itself when no
    /// bracket is found.
    pub fn polish_boundary(&self, model: &MatrixModel<CAP>, s: f64, h: f64) -> f64 {
        let dofs = model.dofs();
        let knot = |t: f64| {
            let p = model.switching(&self.positions_with_rates(t, dofs));
            Knot {
                s: t,
                g: -p.h,
                dg: -p.dh,
                point: (),
            }
        };
        crate::refine::polish_about(knot, s, h)
    }
}
