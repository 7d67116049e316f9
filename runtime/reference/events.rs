//! Event location on a step's dense output: the first time in a step at which a switching
//! function leaves the current regime, including a crossing and return inside one step (a
//! grazing contact, `docs/MODEL.md` §6 case 13).
//!
//! The switching function is given as `g(y) = (s, s')` (or `g(t, y)`): the value, positive
//! inside the current regime, and its time derivative (for the rotor, ±(h, h') with h = z² − 1
//! from [`crate::field::switching_function`]; friction's σw and μN − |λ|, `docs/MODEL.md` §10). The start of every step counts as inside, so a regime
//! that starts exactly on the switching surface is never switched again at its first instant
//! (`docs/MODEL.md` §6 case 15).

use super::scheme::Interpolant;
use crate::math;
use crate::refine::{Knot, Refinement, refine};

/// Interior sample points per step at which the switching function and its derivative are
/// checked (the step is split into this many equal sub-intervals).
pub const SUBDIVISIONS: usize = 8;

/// Most evaluations of one refinement on the dense output (in practice a handful: Newton on the
/// switch function, a secant for the root of its rate).
const MAX_REFINE_STEPS: u32 = 400;

/// Where `f` (value and rate, positive inside) becomes negative between `inside` (where f ≥ 0,
/// or treated so) and `outside` (where f < 0), to the resolution of `f64`: the one refinement
/// ([`crate::refine`]) on −f; a point with f ≤ 0, at most a few ulps past the crossing. `rate`
/// says whether `f`'s second component is its rate (then Newton steps; else secant steps).
fn refine_crossing<F: Fn(f64) -> (f64, f64)>(
    f: F,
    (inside, at_inside): (f64, (f64, f64)),
    (outside, at_outside): (f64, (f64, f64)),
    rate: bool,
) -> f64 {
    let knot = |t: f64, (v, d): (f64, f64)| Knot {
        s: t,
        g: -v,
        dg: if rate { -d } else { f64::NAN },
        point: (),
    };
    let below = Knot {
        g: knot(inside, at_inside).g.min(0.0),
        ..knot(inside, at_inside)
    };
    let settings = Refinement {
        max_steps: MAX_REFINE_STEPS,
        residual: 0.0,
        scale: 1.0,
        first_guess: None,
        close: true,
    };
    refine(
        |t| knot(t, f(t)),
        below,
        knot(outside, at_outside),
        &settings,
    )
    .at_or_past()
    .s
}

/// Where `f` falls below −`band` (> 0) between `inside` and `outside` (f(outside) < −band): the
/// root of `f` itself just before that point, as the taylor method's switch polynomials locate
/// it (`taylor::roots`). The point where f passes −band is refined first (rounding noise of f
/// near 0 cannot draw that refinement), then a point with f ≥ 0 is searched back from it in
/// widening steps (the root lies about band/|f'| earlier) and the root refined between the two;
/// when f stays below 0 back to `inside`, the root is refined from `inside` (f leaves at once).
fn crossing_through_band<F: Fn(f64) -> (f64, f64)>(
    f: F,
    (inside, at_inside): (f64, (f64, f64)),
    (outside, at_outside): (f64, (f64, f64)),
    band: f64,
) -> f64 {
    let lowered = |(v, d): (f64, f64)| (v + band, d);
    let through = refine_crossing(
        |t| lowered(f(t)),
        (inside, lowered(at_inside)),
        (outside, lowered(at_outside)),
        true,
    );
    let at_through = f(through);
    let mut width = if at_through.1 < 0.0 {
        2.0 * band / -at_through.1
    } else {
        f64::EPSILON * (1.0 + math::abs(through))
    };
    loop {
        let before = through - width;
        if before <= inside || before.is_nan() {
            return refine_crossing(&f, (inside, at_inside), (through, at_through), true);
        }
        let at_before = f(before);
        if at_before.0 >= 0.0 {
            return refine_crossing(&f, (before, at_before), (through, at_through), true);
        }
        width *= 4.0;
    }
}

/// The crossing of `f` in the bracket `inside` → `outside` (f(outside) < −`band`): the one
/// refinement ([`refine_crossing`]), kept where f falls there; where it does not (f rises at
/// the point found: the refinement was drawn to a zero of rounding noise, as near a segment's
/// start on its own switch surface, f = 0 to rounding with f' > 0), the band rule
/// ([`crossing_through_band`]). With `band` = 0 the refinement alone.
fn crossing<F: Fn(f64) -> (f64, f64)>(
    f: F,
    inside: (f64, (f64, f64)),
    outside: (f64, (f64, f64)),
    band: f64,
) -> f64 {
    let t = refine_crossing(&f, inside, outside, true);
    if band > 0.0 && f(t).1 > 0.0 {
        crossing_through_band(f, inside, outside, band)
    } else {
        t
    }
}

/// The first time in `(t0, t1]` of the step described by `dense` (with exact end states `y0` at
/// `t0` and `y1` at `t1`) at which `g(t, y).0` becomes negative, or `None` (a switching function
/// of time and state: friction's functions depend on the forcing phase).
///
/// The step is split into `subdivisions` (≥ 1; the reference methods use [`SUBDIVISIONS`])
/// sub-intervals. In each, a negative end value gives a bracket; otherwise, if the derivative goes from negative to positive, the minimum is located
/// by root finding on the derivative and a negative value there gives a bracket (a crossing and
/// return within the sub-interval). The bracket is then refined on the dense output to the
/// resolution of `f64` (the one refinement, [`crate::refine`]).
///
/// With one sub-interval, only the exact end states are examined unless they show a crossing or
/// a minimum, so a lazy interpolant is evaluated only then.
#[inline(always)]
pub fn first_crossing_subdivided<const N: usize, D, G>(
    subdivisions: usize,
    dense: &D,
    y0: &[f64; N],
    y1: &[f64; N],
    g: G,
) -> Option<f64>
where
    D: Interpolant<N>,
    G: Fn(f64, &[f64; N]) -> (f64, f64),
{
    first_crossing_beyond(subdivisions, dense, y0, y1, 0.0, g)
}

/// As [`first_crossing_subdivided`] with a rounding band: a crossing is where `g` falls below
/// −`band` (≥ 0); a dip that stays within the band is rounding, not a switch (`docs/MODEL.md`
/// §12: a touch within rounding is not a crossing, for every method). The crossing found is the
/// root of `g` itself between the last point examined with g ≥ 0 (or the step start, inside by
/// definition) and the first below the band. With `band` = 0 this is
/// [`first_crossing_subdivided`], bit for bit.
///
/// Why a band: a segment that starts on its own switch surface with a vanishing rate as well
/// (after `slip`, σw = 0 and σw' = λ − μσN = 0 together: trap 1 of `docs/MODEL.md` §10) has g
/// equal to 0 to rounding for a few ulps of time, with either sign; without a band the search
/// takes that noise for a crossing and the run chatters (`slip`, `roll`, `slip` within 1e-14).
#[inline(always)]
pub fn first_crossing_beyond<const N: usize, D, G>(
    subdivisions: usize,
    dense: &D,
    y0: &[f64; N],
    y1: &[f64; N],
    band: f64,
    g: G,
) -> Option<f64>
where
    D: Interpolant<N>,
    G: Fn(f64, &[f64; N]) -> (f64, f64),
{
    let subdivisions = subdivisions.max(1);
    let t0 = dense.start();
    let t1 = dense.end();
    let at = |t: f64| g(t, &dense.eval(t));
    let (s0, mut ra) = g(t0, y0);
    // The start is inside by definition.
    let mut sa = s0.max(0.0);
    let mut ta = t0;
    // The last point examined inside (g ≥ 0, or the start): a bracket's inside end. Points with
    // g within the band below 0 are neither inside nor a crossing.
    let mut inside = (ta, (sa, ra));
    let n = subdivisions as f64;
    for k in 1..=subdivisions {
        let (tb, yb) = if k == subdivisions {
            (t1, *y1)
        } else {
            let tb = t0 + (t1 - t0) * (k as f64 / n);
            (tb, dense.eval(tb))
        };
        let (sb, rb) = g(tb, &yb);
        if sb < -band {
            return Some(crossing(at, inside, (tb, (sb, rb)), band));
        }
        if ra < 0.0 && rb > 0.0 {
            // A minimum of s inside (ta, tb): find it from the derivative (secant steps: its
            // rate, s'', is not at hand).
            let rate = |t: f64| {
                let (_, r) = at(t);
                (-r, 0.0)
            };
            let tm = refine_crossing(rate, (ta, (-ra, 0.0)), (tb, (-rb, 0.0)), false);
            let (sm, rm) = at(tm);
            if sm < -band {
                // The crossing lies after the last inside point and before the minimum.
                let from = if sa >= 0.0 { (ta, (sa, ra)) } else { inside };
                return Some(crossing(at, from, (tm, (sm, rm)), band));
            }
        }
        ta = tb;
        sa = sb;
        ra = rb;
        if sb >= 0.0 {
            inside = (tb, (sb, rb));
        }
    }
    None
}

/// Newton iterations of [`polish_switch`].
const POLISH_ITERATIONS: u32 = 3;

/// Largest Newton shift of [`polish_switch`], relative to the step, taken along the
/// derivative instead of by a new explicit step: the linear extrapolation errs by
/// ½·shift²·|y''| (≤ 1e-12·h²·|y''|), far below the error of the step itself.
const LINEAR_SHIFT: f64 = 1e-6;

/// Polish a switch located on the dense output against the step solution itself: starting from
/// `(t, y)` with `y = redo(t)` (the state by one explicit step from the step start), apply Newton
/// steps `t ← t − s/s'` on the switching function, keeping a step only when it stays in
/// `(t_start, t_end]`, moves `t` by at most `max_shift`, and reduces |s|. Returns the best
/// `(t, y)`; its |s| is then at the rounding level of the step, not at the dense output's error.
///
/// A shift no longer than `LINEAR_SHIFT`·(t_end − t_start) moves the state along the field,
/// `y ← y − shift·f(t, y)` (one evaluation of `rhs`), instead of recomputing the step (`redo`, a
/// whole explicit step): the shifts the dense output's error calls for are of that size, and the
/// linear move errs only to second order in the shift.
pub fn polish_switch<const N: usize, R, F, G>(
    t_start: f64,
    t_end: f64,
    max_shift: f64,
    (t, y): (f64, [f64; N]),
    mut redo: R,
    mut rhs: F,
    g: G,
) -> (f64, [f64; N])
where
    R: FnMut(f64) -> [f64; N],
    F: FnMut(f64, &[f64; N]) -> [f64; N],
    G: Fn(f64, &[f64; N]) -> (f64, f64),
{
    let linear_limit = LINEAR_SHIFT * (t_end - t_start);
    let (mut best_t, mut best_y) = (t, y);
    let (mut s, mut ds) = g(t, &y);
    for _ in 0..POLISH_ITERATIONS {
        if s == 0.0 || ds == 0.0 || !s.is_finite() || !ds.is_finite() {
            break;
        }
        let shift = s / ds;
        let t_new = best_t - shift;
        let ok = math::abs(shift) <= max_shift && t_new > t_start && t_new <= t_end;
        if !ok || t_new == best_t {
            break;
        }
        let y_new = if math::abs(shift) <= linear_limit {
            let f = rhs(best_t, &best_y);
            let mut y_new = best_y;
            for (a, d) in y_new.iter_mut().zip(f.iter()) {
                *a -= shift * d;
            }
            y_new
        } else {
            redo(t_new)
        };
        let (s_new, ds_new) = g(t_new, &y_new);
        if s_new.is_nan() || math::abs(s_new) >= math::abs(s) {
            break;
        }
        (best_t, best_y, s, ds) = (t_new, y_new, s_new, ds_new);
    }
    (best_t, best_y)
}
