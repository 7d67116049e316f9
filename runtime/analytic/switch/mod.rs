//! The switch search, one kernel for every closed-form method: the first time an event function
//! g crosses 0 upward on a closed-form piece, found so that no crossing is skipped, and refined
//! to rounding. The analytic propagator and the fixed-step stepper both call [`locate`]; they
//! differ only in their [`Budget`]. The event function is a parameter ([`EventFunction`]): z = 1
//! in either direction today ([`Boundary`], in `boundary.rs`), further switches (friction's w = 0,
//! |λ| = μN) later, each an event function in a file beside it.
//!
//! # Why no crossing is skipped (`docs/MODEL.md` §12)
//! On an interval [a, b] of length L the search knows g and g' at both ends (exactly, from the
//! closed form) and a rigorous bound M ≥ |g''| on [a, b] ([`EventFunction::curvature`]). Then
//! g(t) ≤ min(Ua(t), Ub(t)) with the parabolas Ua(t) = g(a) + g'(a)t + Mt²/2 and
//! Ub(t) = g(b) − g'(b)(L − t) + M(L − t)²/2. Both are convex and Ua − Ub is linear, so the
//! maximum of their minimum over [a, b] is at an end or where they meet ([`no_crossing`]).
//! If that maximum is ≤ [`TOUCH`] the interval is discarded: it is *proven* to hold no contact
//! deeper than the rounding of g (h = z² − 1 is known to ~4ε near z = 1). Otherwise it is
//! halved and both halves examined, left first, so the first crossing is the one found. An
//! interval with g(b) > 0 whose slope stays positive (g'(a) > M·L) holds exactly one crossing,
//! refined by safeguarded Newton. The left end of a search is the start of the current regime:
//! its g is clamped to ≤ 0, so a start on z = 1 is never reported again (`docs/MODEL.md` §6
//! case 15), and one that leaves at once is discarded by the first test.
//!
//! Two shortcuts keep the common case cheap: a span whose end is known is first tested whole,
//! and a chunk whose end is past a switch has that sign change refined first, then one bound
//! test over the part before it proves it the first (if that fails, the interval search runs on
//! that part only: it proves it free, or finds the earlier crossing there).
//!
//! # Work
//! Intervals are dropped without proof only when shorter than [`Budget::min_interval`]
//! (relative to 1 + |s|: a contact inside is shallower than M·L²/8), deeper than [`MAX_DEPTH`]
//! or once [`Budget::tests`] bound tests are spent; the last two make the search report
//! [`Search::Unresolved`] or an uncertain [`Search::Found`], never a silent miss. One call costs
//! at most `tests` bound tests and as many point evaluations in the interval search, one point
//! per chunk end, and `refine` Newton steps for each of at most two refined brackets (the chunk
//! that returns refines its end's sign change first, then, if that is not proved the first, the
//! bracket the interval search ends on). The sliding case that made a recursive search's work
//! grow like 2^depth (g within rounding of 0 along a whole interval) is cut by the touch slack
//! and, failing that, by the budget.

mod boundary;
mod certificate;
mod hermite;
mod slip;

pub use boundary::{
    Boundary, Direction, curvature, first_crossing, first_crossing_to, local_curvature,
};
pub use certificate::{no_crossing, no_crossing_likely};
pub use slip::{MAX_TOUCHES, SlipPoint, SlipVelocity, first_slip_switch};

use crate::math;
use crate::refine::{Knot, Refinement, refine};

/// An event function along a closed-form piece, in local time s: g ≤ 0 in the current regime,
/// the switch is where g crosses 0 upward.
pub trait EventFunction {
    /// One evaluation of the piece (its state, with whatever g is computed from).
    type Point: Copy;
    /// The piece at local time `s`.
    fn point(&self, s: f64) -> Self::Point;
    /// g and g' = dg/ds at a point.
    fn value(&self, point: &Self::Point) -> (f64, f64);
    /// A rigorous upper bound M ≥ |g''| on [lo, hi], given the point at `lo`. May be loose,
    /// must never be low: the proof rests on it.
    fn curvature(&self, lo: f64, at_lo: &Self::Point, hi: f64) -> f64;
}

/// g must exceed this to count as a crossing when an interval is discarded
/// ([`crate::rounding::TOUCH`]: a penetration z − 1 below 1e-15 is not a switch).
pub use crate::rounding::TOUCH;
/// Deepest interval split (the search's recursion). Below [`Budget::min_interval`] = 1e-13 relative
/// a chunk of length ≤ 1 is never split deeper than 44 levels.
pub const MAX_DEPTH: usize = 48;
/// |g| at which refinement stops (converged to rounding).
const CONVERGED: f64 = 1e-15;

/// The work one search may do. Exhausting it is reported, never silent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Most bound tests (each followed by at most one evaluation) in one call.
    pub tests: u32,
    /// Intervals shorter than this times 1 + |s| are not split: they are dropped when g ≤ 0 at
    /// both ends (a contact inside is shallower than M·L²/8) and refined when g changes sign.
    pub min_interval: f64,
    /// Most Newton/bisection steps refining one bracket.
    pub refine: u32,
    /// Start each refinement at the root of the bracket's cubic Hermite interpolant
    /// (`hermite.rs`): fewer closed-form evaluations, the same switch to rounding but not to
    /// the bit. Off in both standard budgets.
    pub hermite_start: bool,
}

impl Budget {
    /// The analytic propagator's: explore down to 1e-13 relative; the test cap (≈ 512 splits)
    /// only bounds pathological input (measured: at most 255 tests in one search over 2000
    /// random degenerate-corner problems and the Fig. 2 runs).
    pub const EXPLORE: Budget = Budget {
        tests: 1024,
        min_interval: 1e-13,
        refine: 80,
        hermite_start: false,
    };
    /// The fixed-step stepper's: hard caps for a bounded step time.
    pub const CAPPED: Budget = Budget {
        tests: 32,
        min_interval: crate::rounding::BRACKET,
        refine: 40,
        hermite_start: false,
    };
    /// [`Budget::CAPPED`] with refinements started at the Hermite root (the stepper's
    /// `SwitchStart::Hermite`).
    pub const CAPPED_HERMITE: Budget = Budget {
        hermite_start: true,
        ..Budget::CAPPED
    };
}

/// What a search found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Search<P> {
    /// No switch in the interval (proved, up to touches below [`TOUCH`]).
    None,
    /// The first switch, at local time `s`. `certain` is false when a cap was hit: the
    /// refinement stopped at [`Budget::refine`] (the time is known to its last bracket, not to
    /// rounding), or the budget ran out before the part of the interval left of the sign change
    /// was proved free (an earlier, shallower contact may exist).
    Found {
        /// Local time of the switch.
        s: f64,
        /// The point there (g within 1e-15 of 0 when converged).
        point: P,
        /// Whether the switch is proved first and refined to rounding.
        certain: bool,
    },
    /// The budget ran out with no sign change of g left to refine: a shallow crossing pair
    /// inside the unresolved part may be missed.
    Unresolved,
}

impl<P> Search<P> {
    /// The switch as (s, point), however certain; `None` for no switch or an unresolved search.
    pub fn found(self) -> Option<(f64, P)> {
        match self {
            Search::Found { s, point, .. } => Some((s, point)),
            Search::None | Search::Unresolved => None,
        }
    }
}

/// The knot of `f` at local time `s` with the point `p` there.
#[inline]
fn knot<F: EventFunction>(f: &F, s: f64, p: F::Point) -> Knot<F::Point> {
    let (g, dg) = f.value(&p);
    Knot { s, g, dg, point: p }
}

/// The switch in the bracket [a, b] (g(a) ≤ 0 < g(b)) refined to rounding by the one refinement
/// ([`crate::refine`]) on the closed form, within the budget's steps (from the bracket's Hermite
/// root with `hermite_start`): the point with the smallest |g| and whether it converged.
fn refine_switch<F: EventFunction>(
    f: &F,
    a: Knot<F::Point>,
    b: Knot<F::Point>,
    budget: &Budget,
) -> (Knot<F::Point>, bool) {
    let first_guess = if budget.hermite_start {
        let w = b.s - a.s;
        hermite::root(a.g, a.dg * w, b.g, b.dg * w).map(|tau| a.s + tau * w)
    } else {
        None
    };
    let settings = Refinement {
        max_steps: budget.refine,
        residual: CONVERGED,
        scale: 1.0,
        first_guess,
        close: false,
    };
    let r = refine(|t| knot(f, t, f.point(t)), a, b, &settings);
    (r.best, r.converged)
}

/// The first crossing on (lo, hi], given the point at `lo` (inside the current regime whatever
/// rounding says) and, if known, at `hi`; searched in chunks of at most `chunk` (the bounds are
/// tight on chunks of a fraction of the fastest period). `known` = (lo, hi, M): a bound the
/// caller already computed on [lo, hi] from `start` (a failed quick test before the search), not
/// computed again; `None` otherwise. See the module docs.
#[allow(clippy::too_many_arguments)]
pub fn locate<F: EventFunction>(
    f: &F,
    lo: f64,
    start: F::Point,
    hi: f64,
    end: Option<F::Point>,
    chunk: f64,
    budget: &Budget,
    known: Option<(f64, f64, f64)>,
) -> Search<F::Point> {
    if lo >= hi || lo.is_nan() || hi.is_nan() {
        return Search::None;
    }
    let mut a = knot(f, lo, start);
    a.g = a.g.min(0.0);
    let mut work = Work {
        tests: budget.tests,
        capped: false,
        bound: known,
    };
    if let Some(end) = end.filter(|_| hi - lo > chunk) {
        // The whole span at once: one bound test, no evaluation.
        let b = knot(f, hi, end);
        if b.g <= TOUCH && work.proves_free(f, &a, &b) {
            return Search::None;
        }
    }
    while a.s < hi {
        // (A chunk below the spacing of floats at a.s, or NaN, takes the rest at once.)
        let s = if hi - a.s > chunk && a.s + chunk > a.s {
            a.s + chunk
        } else {
            hi
        };
        let p = match end {
            Some(end) if s == hi => end,
            _ => f.point(s),
        };
        let b = knot(f, s, p);
        match search_chunk(f, a, b, budget, &mut work) {
            Search::None => {
                a = Knot {
                    g: b.g.min(0.0),
                    ..b
                }
            }
            found => return found,
        }
    }
    if work.capped {
        Search::Unresolved
    } else {
        Search::None
    }
}

/// The budget left in one call, whether anything was dropped unproved, and the last bound.
struct Work {
    tests: u32,
    capped: bool,
    /// The last curvature bound computed, as (lo, hi, M): a chunk's quick test and its search's
    /// first interval are the same interval (and a caller's failed test before the search, see
    /// `known` of [`locate`]), so their bound is computed once. Within one search the point at a
    /// time is always the same, so (lo, hi) identifies the bound.
    bound: Option<(f64, f64, f64)>,
}

impl Work {
    /// [`EventFunction::curvature`] on [x, hi], or the same bound computed last.
    fn curvature<F: EventFunction>(&mut self, f: &F, x: &Knot<F::Point>, hi: f64) -> f64 {
        if let Some((lo, known_hi, m2)) = self.bound
            && lo == x.s
            && known_hi == hi
        {
            return m2;
        }
        let m2 = f.curvature(x.s, &x.point, hi);
        self.bound = Some((x.s, hi, m2));
        m2
    }

    /// Whether the bound proves g ≤ [`TOUCH`] on [a, b] (one curvature bound, no evaluation).
    fn proves_free<F: EventFunction>(
        &mut self,
        f: &F,
        a: &Knot<F::Point>,
        b: &Knot<F::Point>,
    ) -> bool {
        let m2 = self.curvature(f, a, b.s);
        no_crossing(a.g, a.dg, b.g, b.dg, m2, b.s - a.s, TOUCH)
    }
}

/// The first crossing in one chunk [a, b] (both ends known, g(a) ≤ 0).
fn search_chunk<F: EventFunction>(
    f: &F,
    a: Knot<F::Point>,
    b: Knot<F::Point>,
    budget: &Budget,
    work: &mut Work,
) -> Search<F::Point> {
    if b.g > TOUCH && a.g < -TOUCH {
        // A sign change: refine it first, then one bound test proves that no earlier crossing
        // precedes it (the common case: one transversal switch in the chunk). Not from a start
        // within rounding of g = 0 (just after a switch): the secant would be drawn to the
        // rounding noise there; the interval search proves the start's neighbourhood first.
        let (x, converged) = refine_switch(f, a, b, budget);
        if x.s > a.s {
            if work.proves_free(f, &a, &x) {
                return found(x, converged && !work.capped);
            }
            // The bound over the whole of [a, x] is too loose for one test (a long chunk): the
            // interval search proves [a, x] free or finds the earlier crossing there, without
            // refining the same switch again.
            let mut start = a;
            return match interval_search(f, &mut start, x, 0, budget, work) {
                None => found(x, converged && !work.capped),
                Some(end) => end,
            };
        }
    }
    // The common case, the whole chunk proved free by one bound test, is the search's first
    // step.
    let mut x = a;
    interval_search(f, &mut x, b, 0, budget, work).unwrap_or(Search::None)
}

/// The left-first depth-first interval search on [x, y] at split depth `depth`: `None` when
/// the interval is proved free (or dropped), with `x` moved to its right end, else what ends
/// the search. A split examines its left half first (recursively, so the search's stack holds
/// only the levels in use), then the rest [x, y] again from the moved `x`.
fn interval_search<F: EventFunction>(
    f: &F,
    x: &mut Knot<F::Point>,
    y: Knot<F::Point>,
    depth: usize,
    budget: &Budget,
    work: &mut Work,
) -> Option<Search<F::Point>> {
    loop {
        if y.g.is_nan() {
            work.capped = true;
            return Some(Search::Unresolved);
        }
        let len = y.s - x.s;
        let short = len <= budget.min_interval * (1.0 + math::abs(y.s));
        let spent = work.tests == 0 || depth >= MAX_DEPTH;
        let m2 = if short || spent {
            f64::NAN
        } else {
            work.tests -= 1;
            work.curvature(f, x, y.s)
        };
        if y.g > TOUCH && (short || spent || x.dg > m2 * len) {
            // g(x) ≤ 0 < g(y): one crossing (g increases throughout), or no more splitting.
            let (r, converged) = refine_switch(f, *x, y, budget);
            return Some(found(r, converged && !spent && !work.capped));
        }
        if y.g <= TOUCH && (short || spent || no_crossing(x.g, x.dg, y.g, y.dg, m2, len, TOUCH)) {
            // Proved free, a touch, or (spent) dropped unproved.
            work.capped |= spent && !short;
            // g ≤ TOUCH is within rounding of the boundary: inside, as the start.
            *x = Knot {
                g: y.g.min(0.0),
                ..y
            };
            return None;
        }
        let mid = x.s + 0.5 * len;
        let m = knot(f, mid, f.point(mid));
        if let Some(end) = interval_search(f, x, m, depth + 1, budget, work) {
            return Some(end);
        }
    }
}

fn found<P>(k: Knot<P>, certain: bool) -> Search<P> {
    Search::Found {
        s: k.s,
        point: k.point,
        certain,
    }
}
