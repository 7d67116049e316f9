//! A contact sub-step's continuous extension as its Taylor polynomial, for the exit search.
//!
//! An exprb43 (or exprb2) sub-step's continuous extension is the exact solution of its linearized
//! equations q'' = F(cos θ, sin θ) + u + a(s) − 2ν q' − Kl q − Fd (`docs/MODEL.md` §3, §8) from
//! the sub-step's start, with the scheme's cubic forcing a(s). Its closed form costs an `exp`, a
//! matrix function and a `sin_cos` per evaluation; a search for the exit evaluates it three to
//! eight times (bracket, refinement) and bounds it. Over a sub-step of the stepper the segment is
//! an entire function with a small rate ρ·h (ρ = max(μ, η), μ the growth rate of the linear
//! recurrence, `analytic::series::rate`; ρh ≈ 0.01 at dt = 1e-3 on the paper preset), so its
//! Taylor polynomial of six to eight terms is the same function to below rounding: its
//! coefficients have the envelope |c_m| ≤ B ρ^m/m! (the bound behind `series::len_for_rate`), so
//! the terms from the n-th on add about (ρh)^n/n! of the piece's scale B, and the polynomial
//! stops where that is ≤ [`TRUNCATION`] = 1e-18. Evaluating it
//! is a Horner sum (about 50 flops) instead of the closed form's transcendental functions, and its
//! bounds on [lo, hi] are its coefficients' sums.
//!
//! The coefficients come from the generated linearized field (`linearized_contact_field`) by the
//! recurrence of `docs/MODEL.md` §3 (as `analytic::series` does for the zero-state response):
//! the coefficient of s^m of q'', q', q is (m + 2)(m + 1) c_{m+2}, (m + 1) c_{m+1}, c_m, and the
//! field is affine in (q, q', a, the forcing phasor), so c_{m+2} is the field at
//! (c_m, (m + 1) c_{m+1}, a_m, the phasor's m-th Taylor coefficient) with its constant part (u
//! and Fd) only at m = 0, over (m + 2)(m + 1). The phasor's coefficients are
//! η^m/m! (cos, sin)(θ0 + mπ/2). No formula is typed here.
//!
//! Free flight is taken the same way (the generated `free_field`) for the search of a contact
//! entry in a free piece. Only the stepper uses it (the analytic method keeps its closed-form searches bit for bit).

use crate::analytic::linear::LinearSegment;
use crate::analytic::segment::{Bounds, Point, Segment};
use crate::analytic::series::eval_terms;
use crate::analytic::series::rate;
use crate::coefficients::{
    self as coef, Acceleration, Force, LinearizedContact, ModelParams, Phasor, Position, Velocity,
};
use crate::geometry;
use crate::math;
use crate::params::State;

/// Most Taylor coefficients of a sub-step polynomial (degree `TERMS − 1`).
pub const TERMS: usize = 16;
/// Largest ρ·h (see the module docs) for which a piece is taken as its polynomial: at most
/// [`TERMS`] terms reach [`TRUNCATION`] there. Longer pieces (dt ≳ 0.05 on stiff stators) are
/// searched on the closed form.
pub const MAX_RATE_STEP: f64 = 0.5;
/// The neglected terms' envelope (ρh)^n/n!, relative to the piece's scale, at which the
/// polynomial stops (below the rounding of a state of that scale, 1.1e-16).
pub const TRUNCATION: f64 = 1e-18;
/// Fewest terms: c0 … c5 hold the scheme's cubic forcing (a_m enters c_{m+2}).
const MIN_TERMS: usize = 6;

/// The Taylor polynomial Σ c_m s^m of a contact sub-step or a free piece on [0, horizon] (see
/// the module docs).
#[derive(Clone, Copy, Debug)]
pub struct SubstepPolynomial<'a> {
    model: &'a ModelParams,
    /// c_0 … c_{len − 1}, (x, y).
    c: [[f64; 2]; TERMS],
    len: usize,
    /// A bound of what the neglected terms add to |r − ε|, |r'| and |r''| on [0, horizon].
    tail: f64,
    /// |c0 − ε|, the start's distance from the stator centre.
    offset: f64,
}

impl<'a> SubstepPolynomial<'a> {
    /// The polynomial of the contact sub-step `segment` from `start`, on [0, `horizon`], or
    /// `None` when ρ·horizon > [`MAX_RATE_STEP`] (then the closed form is the better
    /// evaluation).
    #[inline(always)]
    pub fn contact(segment: &'a LinearSegment, start: &Point, horizon: f64) -> Option<Self> {
        let lin = segment.linearization();
        let model = lin.model();
        let kl = &lin.kl;
        // The field's linear part: the same field without its constants (u, Fd), which enter
        // the coefficient of s⁰ only.
        let linear_model = without_input(model);
        let linear_model = linear_model.as_ref().unwrap_or(model);
        let linear_kl = LinearizedContact {
            fd1: 0.0,
            fd2: 0.0,
            ..*kl
        };
        let stiffness = frobenius(kl.fa1, kl.fb1, kl.fb2, kl.fa2);
        let forcing = segment.forcing();
        build(
            model,
            start,
            horizon,
            stiffness,
            lin.phase0(),
            |m, at, rate, phasor| {
                let (fx, fy) = (
                    forcing.get(2 * m).copied().unwrap_or(0.0),
                    forcing.get(2 * m + 1).copied().unwrap_or(0.0),
                );
                let (mp, kp) = if m == 0 {
                    (model, kl)
                } else {
                    (linear_model, &linear_kl)
                };
                coef::linearized_contact_field(mp, at, rate, &Force { fx, fy }, phasor, kp)
            },
        )
    }

    /// The polynomial of free flight from `start` with the forcing phasor `phasor` = (cos θ,
    /// sin θ) there, on [0, `horizon`] (the generated `free_field`), or `None` as for
    /// [`Self::contact`]. The free stiffness's norm is read from the field itself (its response
    /// to unit displacements).
    #[inline(always)]
    pub fn free(
        model: &'a ModelParams,
        start: &Point,
        phasor: (f64, f64),
        horizon: f64,
    ) -> Option<Self> {
        let linear_model = without_input(model);
        let linear_model = linear_model.as_ref().unwrap_or(model);
        let field = |m: usize, at: &Position, rate: &Velocity, phasor: &Phasor| {
            coef::free_field(if m == 0 { model } else { linear_model }, at, rate, phasor)
        };
        let rest = Velocity { vx: 0.0, vy: 0.0 };
        let none = Phasor { ct: 0.0, st: 0.0 };
        let ex = field(1, &Position { x: 1.0, y: 0.0 }, &rest, &none);
        let ey = field(1, &Position { x: 0.0, y: 1.0 }, &rest, &none);
        let stiffness = frobenius(ex.ax, ey.ax, ex.ay, ey.ay);
        build(model, start, horizon, stiffness, phasor, field)
    }

    /// The state at local time `s` (Horner).
    #[inline]
    pub fn state(&self, s: f64) -> State {
        let [x, y, vx, vy] = eval_terms(self.c.get(..self.len).unwrap_or(&[]), s);
        State::new(x, y, vx, vy)
    }

    /// The number of Taylor coefficients in use.
    pub fn terms(&self) -> usize {
        self.len
    }
}

impl Segment for SubstepPolynomial<'_> {
    #[inline]
    fn point(&self, s: f64) -> Point {
        geometry::point(self.model, self.state(s))
    }

    fn bounds(&self, _lo: f64, hi: f64) -> Bounds {
        // Term by term at s = hi (0 ≤ s ≤ hi on a sub-step), 1-norms bounding the Euclidean
        // ones: |r − ε| ≤ |c0 − ε| + Σ_{m≥1} |c_m| h^m, |r'| ≤ Σ m|c_m| h^(m−1),
        // |r''| ≤ Σ m(m − 1)|c_m| h^(m−2), plus the neglected terms' tail.
        let h = math::abs(hi);
        let terms = self.c.get(1..self.len).unwrap_or(&[]);
        let (mut r, mut v, mut a) = (0.0, 0.0, 0.0);
        // m as a float, counted down from len − 1 to 1.
        let mut m = terms.len() as f64;
        for cm in terms.iter().rev() {
            let n = norm1(cm);
            if m >= 2.0 {
                a = a * h + m * (m - 1.0) * n;
            }
            v = v * h + m * n;
            r = r * h + n;
            m -= 1.0;
        }
        Bounds {
            radius: self.offset + r * h + self.tail,
            speed: v + self.tail,
            accel: a + self.tail,
        }
    }
}

/// `model` without its constant input force u (the field's linear part for m ≥ 1), `None`
/// when it has none (no copy of the parameters then).
fn without_input(model: &ModelParams) -> Option<ModelParams> {
    if model.force_x == 0.0 && model.force_y == 0.0 {
        return None;
    }
    Some(ModelParams {
        force_x: 0.0,
        force_y: 0.0,
        ..*model
    })
}

/// |c_x| + |c_y| (≥ the Euclidean norm) of a coefficient.
fn norm1(c: &[f64; 2]) -> f64 {
    math::abs(c[0]) + math::abs(c[1])
}

/// The Frobenius norm of the 2×2 matrix [[a, b], [c, d]].
fn frobenius(a: f64, b: f64, c: f64, d: f64) -> f64 {
    math::sqrt(a * a + b * b + c * c + d * d)
}

/// The recurrence of the module docs from `start` for `field(m, c_m, (m + 1) c_{m+1}, the
/// phasor's m-th coefficient)` (its calls with m ≥ 1 leave out the field's constants), the
/// phasor (cos θ0, sin θ0) at s = 0; `stiffness` is the norm of the field's position gain (for
/// the rate ρ).
#[inline(always)]
fn build<'a>(
    model: &'a ModelParams,
    start: &Point,
    horizon: f64,
    stiffness: f64,
    (c0, s0): (f64, f64),
    field: impl Fn(usize, &Position, &Velocity, &Phasor) -> Acceleration,
) -> Option<SubstepPolynomial<'a>> {
    let eta = model.speed_ratio;
    let rho = rate(stiffness, model.damping_ratio).max(math::abs(eta));
    let rho_h = rho * horizon;
    // (NaN fails the comparison: no polynomial.)
    if rho_h.is_nan() || rho_h > MAX_RATE_STEP {
        return None;
    }
    let len = terms_for(rho_h);
    let mut c = [[0.0; 2]; TERMS];
    let w = &start.state;
    let (mut cm, mut cn) = ([w.x, w.y], [w.vx, w.vy]);
    let [first, second, ..] = &mut c;
    (*first, *second) = (cm, cn);
    // η^m/m!, and m + 1 as a float.
    let (mut scale, mut k) = (1.0, 0.0);
    for (m, slot) in c.iter_mut().skip(2).take(len - 2).enumerate() {
        // The phasor's m-th coefficient: (cos, sin)(θ0 + mπ/2)·η^m/m!.
        let (ct, st) = match m % 4 {
            0 => (c0, s0),
            1 => (-s0, c0),
            2 => (-c0, -s0),
            _ => (s0, -c0),
        };
        k += 1.0;
        let acc = field(
            m,
            &Position { x: cm[0], y: cm[1] },
            &Velocity {
                vx: k * cn[0],
                vy: k * cn[1],
            },
            &Phasor {
                ct: scale * ct,
                st: scale * st,
            },
        );
        let divisor = 1.0 / ((k + 1.0) * k);
        let next = [acc.ax * divisor, acc.ay * divisor];
        *slot = next;
        (cm, cn) = (cn, next);
        scale *= eta / k;
    }
    // The neglected terms from m = len on. The recurrence's coefficients have the envelope
    // |c_m| ≤ B ρ^m/m! (`series::len_for_rate`; the harmonic forcing's terms add a factor
    // growing like m), with B ≤ |c_{len−1}|·(len − 1)!/ρ^(len−1) and the like from
    // |c_{len−2}|. Then Σ_{m≥len} m(m − 1)|c_m| h^(m−2) ≤ B ρ² (ρh)^(len−2)/(len − 2)!·e^(ρh),
    // which is (|c_{len−1}|(len − 1)ρ + |c_{len−2}|ρ²)·h^(len−2)·e^(ρh); the speed's and the
    // radius's tails are smaller (h ≤ 1, ρh ≤ 1). Taken with a factor 3·len for e^(ρh) and
    // the harmonic terms' growth. (Below rounding: about TRUNCATION of the piece's scale.)
    let h = horizon.min(1.0);
    let power = (2..len).fold(1.0, |p, _| p * h);
    let last = c.get(len - 1).map_or(0.0, norm1);
    let before = c.get(len - 2).map_or(0.0, norm1);
    let n = len as f64;
    let tail = 3.0 * n * (last * (n - 1.0) * rho + before * rho * rho) * power;
    Some(SubstepPolynomial {
        model,
        c,
        len,
        tail,
        // z = √(h + 1) = |c0 − ε|, with room for the rounding of h + 1 and of the root.
        offset: math::sqrt((start.h + 1.0).max(0.0)) * (1.0 + 4.0 * f64::EPSILON),
    })
}

/// The number of Taylor coefficients for a piece of rate·length `rho_h` (≤ [`MAX_RATE_STEP`]):
/// the smallest n ≥ [`MIN_TERMS`] with (ρh)^n/n! ≤ [`TRUNCATION`] (the envelope of the first
/// neglected term relative to the piece's scale).
fn terms_for(rho_h: f64) -> usize {
    let mut term = 1.0;
    let mut n = 0;
    while n < TERMS && (n < MIN_TERMS || term > TRUNCATION) {
        n += 1;
        term *= rho_h / n as f64;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::free::{FreeConstants, FreeSegment};
    use crate::analytic::linear::ContactConstants;
    use crate::analytic::schemes::{SubStep, exprb43_with};
    use crate::field;
    use crate::params::Problem;
    use crate::propagate::Regime;
    use crate::{Preset, Stepper, StepperConfig};

    /// Every 7th step start of `problem` over 30 time units: `visit(time, state, regime)`.
    fn for_starts(problem: &Problem, dt: f64, mut visit: impl FnMut(f64, State, Regime)) {
        let mut s = Stepper::new(problem, StepperConfig::with_dt(dt)).unwrap();
        for k in 0..(30.0 / dt) as usize {
            if k % 7 == 0 {
                visit(s.time(), s.state(), s.regime());
            }
            s.step(dt).unwrap();
        }
    }

    fn problems() -> [Problem; 2] {
        let mut forced = Preset::Paper.problem();
        (forced.params.force_x, forced.params.force_y) = (0.2, -0.1);
        [Preset::Paper.problem(), forced]
    }

    fn assert_close(a: State, b: State, what: &str) {
        for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
            assert!(
                (x - y).abs() <= 4e-15 * (1.0 + y.abs()),
                "{what}: {x:e} against {y:e}"
            );
        }
    }

    /// The largest |r''| seen at 64 points of [0, h] (r'' from the state's neighbours: a
    /// central difference of the velocity, to 1e-9 relative here).
    fn sampled_accel(state: impl Fn(f64) -> State, h: f64) -> f64 {
        let d = h * 1e-4;
        (1..64)
            .map(|i| {
                let s = h * f64::from(i) / 64.0;
                let (a, b) = (state(s - d), state(s + d));
                ((b.vx - a.vx).hypot(b.vy - a.vy)) / (2.0 * d)
            })
            .fold(0.0, f64::max)
    }

    /// `poly` equals the closed form `exact` to rounding at 9 points of [0, dt], and its |r''|
    /// bound holds on sampled differences; its bounds.
    fn matches_within_bounds(
        poly: &SubstepPolynomial,
        dt: f64,
        exact: impl Fn(f64) -> State,
        what: &str,
    ) -> Bounds {
        for i in 0..=8 {
            let s = dt * f64::from(i) / 8.0;
            assert_close(poly.state(s), exact(s), what);
        }
        let b = poly.bounds(0.0, dt);
        let accel = sampled_accel(|s| poly.state(s), dt);
        assert!(
            accel <= b.accel,
            "|r''| {accel:e} above its bound {:e}",
            b.accel
        );
        b
    }

    /// The polynomial of a contact sub-step is its closed form to rounding over the sub-step,
    /// and its bounds hold.
    #[test]
    fn a_contact_sub_step_s_polynomial_is_its_closed_form() {
        let mut checked = 0;
        for problem in problems() {
            let params = problem.params;
            let model = ModelParams::of(&params);
            for dt in [1e-3, 1e-2] {
                for_starts(&problem, dt, |t, w, regime| {
                    if regime != Regime::Contact {
                        return;
                    }
                    let mut sub = SubStep::zeroed();
                    exprb43_with(
                        &ContactConstants::new(&params),
                        0.0,
                        t,
                        w,
                        dt,
                        1.0,
                        &mut sub,
                    )
                    .unwrap();
                    let start = geometry::point(&model, w);
                    let poly = SubstepPolynomial::contact(&sub.segment, &start, dt).unwrap();
                    assert!(poly.terms() <= TERMS);
                    matches_within_bounds(&poly, dt, |s| sub.segment.point(s).state, "contact");
                    checked += 1;
                });
            }
        }
        assert!(checked > 100, "{checked} contact sub-steps");
    }

    /// The polynomial of a free piece is the free closed form to rounding, and its bounds hold.
    #[test]
    fn a_free_piece_s_polynomial_is_the_free_closed_form() {
        let mut checked = 0;
        for problem in problems() {
            let params = problem.params;
            let model = ModelParams::of(&params);
            let constants = FreeConstants::new(&params);
            for dt in [1e-3, 1e-2] {
                for_starts(&problem, dt, |t, w, regime| {
                    if regime != Regime::Free {
                        return;
                    }
                    let seg = FreeSegment::new(&params, &constants, t, w);
                    let p = field::phasor(&model, t);
                    let start = geometry::point(&model, w);
                    let poly = SubstepPolynomial::free(&model, &start, (p.ct, p.st), dt).unwrap();
                    let b = matches_within_bounds(&poly, dt, |s| seg.point(s).state, "free");
                    assert!(b.radius >= (start.h.max(-1.0) + 1.0).sqrt() * (1.0 - 1e-15));
                    checked += 1;
                });
            }
        }
        assert!(checked > 100, "{checked} free pieces");
    }

    /// Too long a piece for the polynomial is left to the closed form.
    #[test]
    fn a_long_piece_has_no_polynomial() {
        let params = Preset::Paper.problem().params;
        let model = ModelParams::of(&params);
        let w = Preset::Paper.problem().initial;
        let start = geometry::point(&model, w);
        assert!(SubstepPolynomial::free(&model, &start, (1.0, 0.0), 0.9).is_none());
        assert!(SubstepPolynomial::free(&model, &start, (1.0, 0.0), f64::NAN).is_none());
        assert!(SubstepPolynomial::free(&model, &start, (1.0, 0.0), 1e-3).is_some());
    }
}
