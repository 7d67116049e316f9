//! An independent reference for the stator ring with mass (issue 28 item 5, the design note
//! §11), built for the tests only: the 8-state field of each regime written out here by hand
//! from the model's statement (nothing of `rotor_rub::matrix`, the generated code or the
//! production integrators is used; the parameters are read off a `Params` as numbers),
//! integrated by the `differential-equations` crate's DOP853 at rtol = atol = 1e-13.
//!
//! The model (rotor q = (x, y), ring p = (x_s, y_s), d = q − p − ε̂, z = |d|, n = d/z,
//! t = (−n_y, n_x)):
//!
//! ```text
//! rotor:  q'' = F (cos θ, sin θ) + u − 2ν q' − q − N n − f t
//! ring:   m̂ p'' = −ĉ p' − K_s p + N n + f t
//! N = k̂_c (z − 1) in contact, w = (q' − p')·t + ρ_R η,
//! f = μσN slipping, λ rolling, 0 frictionless or free;
//! λ (1 + 1/m̂) = (G_r − G_s/m̂)·t − (d'·t)(d'·n)/z,
//! G_r = F e_θ + u − 2ν q' − q − N n,  G_s = −ĉ p' − K_s p + N n.
//! ```
//!
//! How a run proceeds (as the friction oracle, `tests/friction/oracle.rs`): the current
//! regime's field is integrated sample to sample, every [`SPACING`] (each an integration ending
//! exactly there); the samples are scanned for the first sign change of the regime's switch
//! functions (z = 1; σw while slipping; μN − |λ| while rolling, each measured from its value at
//! the segment start when that is negative by rounding); the crossing is bisected to the
//! resolution of the time, every trial state integrated afresh from the last sample before it.
//! At a zero of w the friction law decides (|λ| ≤ μN: roll; sign λ ≠ σ: reverse; else a touch,
//! and the search goes on). Limits, stated: a crossing and return of a switch function within
//! one sample spacing is not seen.

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use rotor_rub::Params;

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
    /// State there: (x, y, x_s, y_s, x', y', x_s', y_s').
    pub state: [f64; 8],
}

/// A run of the oracle.
#[derive(Clone, Debug)]
pub struct OracleRun {
    /// The events, in order.
    pub events: Vec<OracleEvent>,
    /// Samples (time, state, phase) every [`SPACING`] (from the scan).
    pub samples: Vec<(f64, [f64; 8], Phase)>,
}

/// The ring model's numbers, read off a `Params`.
#[derive(Clone, Copy, Debug)]
pub struct Ring {
    eta: f64,
    nu: f64,
    f: f64,
    phase: f64,
    ks: [[f64; 2]; 2],
    e: [f64; 2],
    u: [f64; 2],
    mu: f64,
    rho: f64,
    mass: f64,
    kc: f64,
    cs: f64,
}

/// The contact geometry of a state.
struct Frame {
    z: f64,
    n: [f64; 2],
    t: [f64; 2],
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

impl Ring {
    /// The oracle's model of `p` (with m̂ > 0).
    pub fn of(p: &Params) -> Ring {
        Ring {
            eta: p.speed_ratio,
            nu: p.damping_ratio,
            f: p.mass_ratio * p.eccentricity_ratio * p.speed_ratio * p.speed_ratio,
            phase: p.phase,
            ks: [[p.k_xx, p.k_xy], [p.k_yx, p.k_yy]],
            e: [p.offset_x, p.offset_y],
            u: [p.force_x, p.force_y],
            mu: p.friction_coefficient,
            rho: p.radius_ratio,
            mass: p.stator_mass_ratio,
            kc: p.contact_stiffness,
            cs: p.stator_damping,
        }
    }

    fn offset(&self, y: &[f64; 8]) -> [f64; 2] {
        [y[0] - y[2] - self.e[0], y[1] - y[3] - self.e[1]]
    }

    fn frame(&self, y: &[f64; 8]) -> Frame {
        let d = self.offset(y);
        let z = (d[0] * d[0] + d[1] * d[1]).sqrt();
        let n = [d[0] / z, d[1] / z];
        Frame {
            z,
            n,
            t: [-n[1], n[0]],
        }
    }

    /// h = z² − 1.
    pub fn h(&self, y: &[f64; 8]) -> f64 {
        let d = self.offset(y);
        d[0] * d[0] + d[1] * d[1] - 1.0
    }

    /// Every force on the rotor but the contact's: F e_θ + u − 2ν q' − q.
    fn rotor_free(&self, t: f64, y: &[f64; 8]) -> [f64; 2] {
        let th = self.eta * t + self.phase;
        [
            self.f * th.cos() + self.u[0] - 2.0 * self.nu * y[4] - y[0],
            self.f * th.sin() + self.u[1] - 2.0 * self.nu * y[5] - y[1],
        ]
    }

    /// Every force on the ring but the contact's: −ĉ p' − K_s p.
    fn ring_free(&self, y: &[f64; 8]) -> [f64; 2] {
        let k = &self.ks;
        [
            -self.cs * y[6] - k[0][0] * y[2] - k[0][1] * y[3],
            -self.cs * y[7] - k[1][0] * y[2] - k[1][1] * y[3],
        ]
    }

    /// (N, w, λ) at a contact state.
    pub fn friction(&self, t: f64, y: &[f64; 8]) -> (f64, f64, f64) {
        let fr = self.frame(y);
        let normal = self.kc * (fr.z - 1.0);
        let dv = [y[4] - y[6], y[5] - y[7]];
        let vt = dot(dv, fr.t);
        let vn = dot(dv, fr.n);
        let w = vt + self.rho * self.eta;
        let r = self.rotor_free(t, y);
        let s = self.ring_free(y);
        let gr = [r[0] - normal * fr.n[0], r[1] - normal * fr.n[1]];
        let gs = [s[0] + normal * fr.n[0], s[1] + normal * fr.n[1]];
        let drive = [gr[0] - gs[0] / self.mass, gr[1] - gs[1] / self.mass];
        let lambda = (dot(drive, fr.t) - vt * vn / fr.z) / (1.0 + 1.0 / self.mass);
        (normal, w, lambda)
    }

    /// y' of `phase` at (t, y).
    pub fn derivative(&self, phase: Phase, t: f64, y: &[f64; 8]) -> [f64; 8] {
        let r = self.rotor_free(t, y);
        let s = self.ring_free(y);
        let (normal, tangential, fr) = match phase {
            Phase::Free => (0.0, 0.0, None),
            _ => {
                let fr = self.frame(y);
                let (normal, _, lambda) = self.friction(t, y);
                let f = match phase {
                    Phase::Slipping(sigma) => self.mu * sigma * normal,
                    Phase::Rolling => lambda,
                    Phase::Free => 0.0,
                };
                (normal, f, Some(fr))
            }
        };
        let (n, tg) = fr.map_or(([0.0; 2], [0.0; 2]), |f| (f.n, f.t));
        let contact = [
            normal * n[0] + tangential * tg[0],
            normal * n[1] + tangential * tg[1],
        ];
        [
            y[4],
            y[5],
            y[6],
            y[7],
            r[0] - contact[0],
            r[1] - contact[1],
            (s[0] + contact[0]) / self.mass,
            (s[1] + contact[1]) / self.mass,
        ]
    }

    /// The switch functions of `phase` (positive inside): [z = 1, friction's].
    fn switches(&self, phase: Phase, t: f64, y: &[f64; 8]) -> [f64; 2] {
        let h = self.h(y);
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

    /// The phase of contact starting at (t, y): σ = sign w, or sign λ after `reverse`/`slip`
    /// (`by_lambda`), or rolling when w = 0 and |λ| ≤ μN; μ = 0: frictionless.
    fn contact_phase(&self, t: f64, y: &[f64; 8], by_lambda: bool) -> Phase {
        if self.mu == 0.0 {
            return Phase::Slipping(0.0);
        }
        let (normal, w, lambda) = self.friction(t, y);
        let sign_l = if lambda < 0.0 { -1.0 } else { 1.0 };
        if by_lambda {
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
    ring: &'a Ring,
    phase: Phase,
}

impl ODE<f64, [f64; 8]> for Field<'_> {
    fn diff(&self, t: f64, y: &[f64; 8], dydt: &mut [f64; 8]) {
        *dydt = self.ring.derivative(self.phase, t, y);
    }
}

/// The state at `t` of `phase`'s field from (t0, y0): one integration ending exactly at `t`.
fn state_at(ring: &Ring, phase: Phase, t0: f64, y0: [f64; 8], t: f64) -> [f64; 8] {
    if t <= t0 {
        return y0;
    }
    let field = Field { ring, phase };
    let method = ExplicitRungeKutta::dop853()
        .rtol(TOL)
        .atol(TOL)
        .max_steps(100_000_000);
    let solution = IVP::ode(&field, t0, t, y0)
        .method(method)
        .solve()
        .expect("the oracle integrates");
    assert_eq!(
        solution.t.last().copied(),
        Some(t),
        "the integration ends at t"
    );
    *solution.y.last().expect("a solution has its end point")
}

/// Run the oracle from (t0, y0) to `t_end` (a start strictly off z = 1).
pub fn run(params: &Params, y0: [f64; 8], t0: f64, t_end: f64) -> OracleRun {
    let ring = Ring::of(params);
    let mut y = y0;
    let mut t = t0;
    let mut phase = if ring.h(&y) <= 0.0 {
        Phase::Free
    } else {
        ring.contact_phase(t, &y, false)
    };
    let mut events = Vec::new();
    let mut samples = vec![(t, y, phase)];
    let mut offset = (ring.switches(phase, t, &y)[1]).min(0.0);
    while t < t_end {
        let n = ((WINDOW.min(t_end - t)) / SPACING).ceil().max(1.0) as usize;
        let times: Vec<f64> = (1..=n)
            .map(|k| (t + k as f64 * SPACING).min(t_end))
            .collect();
        let mut states = Vec::with_capacity(n);
        let (mut ta, mut ya) = (t, y);
        for &tb in &times {
            ya = state_at(&ring, phase, ta, ya, tb);
            ta = tb;
            states.push(ya);
        }
        let inside = |tt: f64, yy: &[f64; 8], off: f64| {
            let s = ring.switches(phase, tt, yy);
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
                let bisect = |i: usize| {
                    let (mut a, mut b) = (prev.0, tk);
                    for _ in 0..200 {
                        let m = 0.5 * (a + b);
                        if m <= a || m >= b {
                            break;
                        }
                        let ym = state_at(&ring, phase, prev.0, prev.1, m);
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
                let ye = state_at(&ring, phase, prev.0, prev.1, te);
                let next = match (phase, i) {
                    (Phase::Free, _) => Some(("enter", ring.contact_phase(te, &ye, false))),
                    (_, 0) => Some(("exit", Phase::Free)),
                    (Phase::Rolling, _) => Some(("slip", ring.contact_phase(te, &ye, true))),
                    (Phase::Slipping(sigma), _) => {
                        let (normal, _, lambda) = ring.friction(te, &ye);
                        let sign_l = if lambda < 0.0 { -1.0 } else { 1.0 };
                        if lambda.abs() <= ring.mu * normal {
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
                offset = (ring.switches(phase, t, &y)[1]).min(0.0);
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
