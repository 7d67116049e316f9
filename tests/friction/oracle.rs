//! An independent reference for Coulomb friction (`docs/MODEL.md` §10), built for the tests
//! only: the 4-state field of each regime written out here by hand (nothing of
//! `rotor_rub::field`, the generated code or the production integrators is used), integrated by
//! the `differential-equations` crate's DOP853 at rtol = atol = 1e-13.
//!
//! How a run proceeds: the current regime's field is integrated sample to sample, every
//! [`SPACING`] (each an integration ending exactly there, in windows of [`WINDOW`]); the samples are scanned for the first sign change of the
//! regime's switch functions (z = 1; σw while slipping; μN − |λ| while rolling), each measured
//! from its value at the segment start when that is negative by rounding (so a start on the
//! switch, after `slip` or `reverse`, is not found again). The crossing is then bisected to
//! ~1e-15 relative, every trial state integrated afresh from the last sample before it (at most
//! one spacing away). At a zero of w the friction law decides (|λ| ≤ μN: roll; sign λ ≠ σ:
//! reverse; else a touch, and the search goes on). Limits, stated: a crossing and return of a
//! switch function within one sample spacing is not seen (the cases have none; the
//! production methods' searches are rigorous there, this oracle is not).

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use rotor_rub::{Params, State};

/// Integration tolerance (rtol = atol).
pub const TOL: f64 = 1e-13;
/// Sample spacing of the event scan.
pub const SPACING: f64 = 1e-3;
/// Length of one integration window.
pub const WINDOW: f64 = 0.25;

/// The regime of the oracle's motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// z < 1.
    Free,
    /// Slipping contact with slip direction σ = ±1 (σ = 0: frictionless contact, μ = 0).
    Slipping(f64),
    /// Rolling contact (w ≡ 0).
    Rolling,
}

/// One event of the oracle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OracleEvent {
    /// Time.
    pub time: f64,
    /// `enter`, `exit`, `reverse`, `roll` or `slip`.
    pub kind: &'static str,
    /// State there.
    pub state: [f64; 4],
}

/// A run of the oracle.
#[derive(Clone, Debug)]
pub struct OracleRun {
    /// The events, in order.
    pub events: Vec<OracleEvent>,
    /// Samples (time, state, phase) every [`SPACING`] (from the scan).
    pub samples: Vec<(f64, [f64; 4], Phase)>,
}

/// The model's parameters, read off a `Params` (only values, no production code).
#[derive(Clone, Copy, Debug)]
pub struct Model {
    eta: f64,
    nu: f64,
    f: f64,
    phase: f64,
    k: [[f64; 2]; 2],
    e: [f64; 2],
    mu: f64,
    rho: f64,
}

impl Model {
    /// The oracle's model of `p`.
    pub fn of(p: &Params) -> Model {
        Model {
            eta: p.speed_ratio,
            nu: p.damping_ratio,
            f: p.mass_ratio * p.eccentricity_ratio * p.speed_ratio * p.speed_ratio,
            phase: p.phase,
            k: [[p.k_xx, p.k_xy], [p.k_yx, p.k_yy]],
            e: [p.offset_x, p.offset_y],
            mu: p.friction_coefficient,
            rho: p.radius_ratio,
        }
    }

    /// z and the frame: (z, n, t).
    fn frame(&self, y: &[f64; 4]) -> (f64, [f64; 2], [f64; 2]) {
        let (u, v) = (y[0] - self.e[0], y[1] - self.e[1]);
        let z = (u * u + v * v).sqrt();
        (z, [u / z, v / z], [-v / z, u / z])
    }

    /// K_s g(q), g = (1 − 1/z)(u, v).
    fn elastic(&self, y: &[f64; 4]) -> [f64; 2] {
        let (u, v) = (y[0] - self.e[0], y[1] - self.e[1]);
        let z = (u * u + v * v).sqrt();
        let s = 1.0 - 1.0 / z;
        let (gx, gy) = (s * u, s * v);
        [
            self.k[0][0] * gx + self.k[0][1] * gy,
            self.k[1][0] * gx + self.k[1][1] * gy,
        ]
    }

    /// Every force but the contact forces: F(cos θ, sin θ) − 2ν q' − q.
    fn free_force(&self, t: f64, y: &[f64; 4]) -> [f64; 2] {
        let th = self.eta * t + self.phase;
        [
            self.f * th.cos() - 2.0 * self.nu * y[2] - y[0],
            self.f * th.sin() - 2.0 * self.nu * y[3] - y[1],
        ]
    }

    /// (N, w, λ) at a contact state.
    pub fn friction(&self, t: f64, y: &[f64; 4]) -> (f64, f64, f64) {
        let (z, n, tg) = self.frame(y);
        let el = self.elastic(y);
        let fr = self.free_force(t, y);
        let g = [fr[0] - el[0], fr[1] - el[1]];
        let normal = n[0] * el[0] + n[1] * el[1];
        let vt = y[2] * tg[0] + y[3] * tg[1];
        let vn = y[2] * n[0] + y[3] * n[1];
        let w = vt + self.rho * self.eta;
        let lambda = tg[0] * g[0] + tg[1] * g[1] - vt * vn / z;
        (normal, w, lambda)
    }

    /// The acceleration of `phase` at (t, y).
    pub fn acceleration(&self, phase: Phase, t: f64, y: &[f64; 4]) -> [f64; 2] {
        let fr = self.free_force(t, y);
        match phase {
            Phase::Free => fr,
            Phase::Slipping(sigma) => {
                let el = self.elastic(y);
                let (_, _, tg) = self.frame(y);
                let (normal, _, _) = self.friction(t, y);
                let f = self.mu * sigma * normal;
                [fr[0] - el[0] - f * tg[0], fr[1] - el[1] - f * tg[1]]
            }
            Phase::Rolling => {
                let el = self.elastic(y);
                let (_, _, tg) = self.frame(y);
                let (_, _, lambda) = self.friction(t, y);
                [
                    fr[0] - el[0] - lambda * tg[0],
                    fr[1] - el[1] - lambda * tg[1],
                ]
            }
        }
    }

    /// The switch functions of `phase` (positive inside): [z = 1, friction's].
    fn switches(&self, phase: Phase, t: f64, y: &[f64; 4]) -> [f64; 2] {
        let h = (y[0] - self.e[0]).powi(2) + (y[1] - self.e[1]).powi(2) - 1.0;
        match phase {
            Phase::Free => [-h, f64::INFINITY],
            Phase::Slipping(0.0) => [h, f64::INFINITY],
            Phase::Slipping(sigma) => [h, sigma * self.friction(t, y).1],
            Phase::Rolling => {
                let (normal, _, lambda) = self.friction(t, y);
                [h, self.mu * normal - lambda.abs()]
            }
        }
    }

    /// The phase of a start at (t, y).
    fn start_phase(&self, t: f64, y: &[f64; 4]) -> Phase {
        let h = (y[0] - self.e[0]).powi(2) + (y[1] - self.e[1]).powi(2) - 1.0;
        if h <= 0.0 {
            Phase::Free
        } else {
            self.contact_phase(t, y, None)
        }
    }

    /// The phase of contact starting at (t, y): σ = sign w, or sign λ after `reverse`/`slip`
    /// (`by_lambda`), or rolling when w = 0 and |λ| ≤ μN; μ = 0: frictionless.
    fn contact_phase(&self, t: f64, y: &[f64; 4], by_lambda: Option<()>) -> Phase {
        if self.mu == 0.0 {
            return Phase::Slipping(0.0);
        }
        let (normal, w, lambda) = self.friction(t, y);
        let sign_l = if lambda < 0.0 { -1.0 } else { 1.0 };
        if by_lambda.is_some() {
            return Phase::Slipping(sign_l);
        }
        if w > 0.0 {
            Phase::Slipping(1.0)
        } else if w < 0.0 {
            Phase::Slipping(-1.0)
        } else if lambda.abs() <= self.mu * normal {
            Phase::Rolling
        } else {
            Phase::Slipping(sign_l)
        }
    }
}

struct Field<'a> {
    model: &'a Model,
    phase: Phase,
}

impl ODE<f64, [f64; 4]> for Field<'_> {
    fn diff(&self, t: f64, y: &[f64; 4], dydt: &mut [f64; 4]) {
        let a = self.model.acceleration(self.phase, t, y);
        *dydt = [y[2], y[3], a[0], a[1]];
    }
}

/// The state at `t` of `phase`'s field from (t0, y0): one integration ending exactly at `t`
/// (never an interpolated state, so no interpolation error carries on).
fn state_at(model: &Model, phase: Phase, t0: f64, y0: [f64; 4], t: f64) -> [f64; 4] {
    if t <= t0 {
        return y0;
    }
    let field = Field { model, phase };
    let method = ExplicitRungeKutta::dop853()
        .rtol(TOL)
        .atol(TOL)
        .max_steps(100_000_000);
    let solution = IVP::ode(&field, t0, t, y0)
        .method(method)
        .solve()
        .expect("the oracle integrates");
    let end = *solution.y.last().expect("a solution has its end point");
    assert_eq!(
        solution.t.last().copied(),
        Some(t),
        "the integration ends at t"
    );
    end
}

/// Run the oracle from (t0, y0) to `t_end`.
pub fn run(params: &Params, initial: State, t0: f64, t_end: f64) -> OracleRun {
    let model = Model::of(params);
    let mut y = initial.to_array();
    let mut t = t0;
    let mut phase = model.start_phase(t, &y);
    let mut events = Vec::new();
    let mut samples = vec![(t, y, phase)];
    // The friction function's offset of the current segment (≤ 0).
    let mut offset = (model.switches(phase, t, &y)[1]).min(0.0);
    while t < t_end {
        // One window of samples.
        let n = ((WINDOW.min(t_end - t)) / SPACING).ceil().max(1.0) as usize;
        let times: Vec<f64> = (1..=n)
            .map(|k| (t + k as f64 * SPACING).min(t_end))
            .collect();
        let mut states = Vec::with_capacity(n);
        let (mut ta, mut ya) = (t, y);
        for &tb in &times {
            ya = state_at(&model, phase, ta, ya, tb);
            ta = tb;
            states.push(ya);
        }
        let inside = |tt: f64, yy: &[f64; 4], off: f64| {
            let s = model.switches(phase, tt, yy);
            [s[0], s[1] - off]
        };
        let mut prev = (t, y);
        let mut switched = false;
        for (&tk, yk) in times.iter().zip(&states) {
            let g = inside(tk, yk, offset);
            let which = if g[0] < 0.0 {
                Some(0)
            } else if g[1] < 0.0 {
                Some(1)
            } else {
                None
            };
            if let Some(mut i) = which {
                // If both went negative in this interval, the earlier one wins: bisect both.
                let bisect = |i: usize| {
                    let (mut a, mut b) = (prev.0, tk);
                    for _ in 0..200 {
                        let m = 0.5 * (a + b);
                        if m <= a || m >= b {
                            break;
                        }
                        let ym = state_at(&model, phase, prev.0, prev.1, m);
                        if inside(m, &ym, offset)[i] < 0.0 {
                            b = m;
                        } else {
                            a = m;
                        }
                    }
                    b
                };
                let mut te = bisect(i);
                if i == 0 && g[1] < 0.0 {
                    let t1 = bisect(1);
                    if t1 < te {
                        (te, i) = (t1, 1);
                    }
                }
                let ye = state_at(&model, phase, prev.0, prev.1, te);
                let next = match (phase, i) {
                    (Phase::Free, _) => Some(("enter", model.contact_phase(te, &ye, None))),
                    (_, 0) => Some(("exit", Phase::Free)),
                    (Phase::Rolling, _) => Some(("slip", model.contact_phase(te, &ye, Some(())))),
                    (Phase::Slipping(sigma), _) => {
                        let (normal, _, lambda) = model.friction(te, &ye);
                        let sign_l = if lambda < 0.0 { -1.0 } else { 1.0 };
                        if lambda.abs() <= model.mu * normal {
                            Some(("roll", Phase::Rolling))
                        } else if sign_l != sigma {
                            Some(("reverse", Phase::Slipping(sign_l)))
                        } else {
                            None
                        }
                    }
                };
                t = te;
                y = ye;
                if let Some((kind, p)) = next {
                    events.push(OracleEvent {
                        time: te,
                        kind,
                        state: ye,
                    });
                    phase = p;
                }
                offset = (model.switches(phase, t, &y)[1]).min(0.0);
                samples.push((t, y, phase));
                switched = true;
                break;
            }
            samples.push((tk, *yk, phase));
            prev = (tk, *yk);
        }
        if !switched {
            t = prev.0;
            y = prev.1;
        }
    }
    OracleRun { events, samples }
}
