//! The sums of one forcing period of a run (`revolutions.rs`), node by node: the radius's
//! extremes between nodes from the cubic Hermite polynomial of r² = |q|², the time in contact,
//! the orbit's signed area and its spread about its mean position (the whirl).

use core::f64::consts::{PI, TAU};

use super::revolutions::Revolution;
use crate::math;
use crate::params::State;
use crate::propagate::Regime;

/// The sums one revolution accumulates, node by node.
pub(super) struct Accumulator {
    start: f64,
    last: (f64, State),
    first_position: (f64, f64),
    max_sq: f64,
    min_sq: f64,
    contact: f64,
    /// ∮ (x dy − y dx), trapezoidal.
    moment: f64,
    /// ∫ x dτ, ∫ y dτ, ∫ |q|² dτ, trapezoidal.
    integrals: [f64; 3],
    pub(super) enters: u32,
    pub(super) exits: u32,
}

impl Accumulator {
    pub(super) fn new(time: f64, state: State) -> Self {
        let r2 = state.x * state.x + state.y * state.y;
        Accumulator {
            start: time,
            last: (time, state),
            first_position: (state.x, state.y),
            max_sq: r2,
            min_sq: r2,
            contact: 0.0,
            moment: 0.0,
            integrals: [0.0; 3],
            enters: 0,
            exits: 0,
        }
    }

    /// The next node: `regime` held since the last one.
    pub(super) fn node(&mut self, time: f64, state: State, regime: Regime) {
        let (t0, a) = self.last;
        let h = time - t0;
        if h > 0.0 {
            let (lo, hi) = hermite_extremes(squared_radius(&a), squared_radius(&state), h);
            self.max_sq = self.max_sq.max(hi);
            self.min_sq = self.min_sq.min(lo);
            if regime.in_contact() {
                self.contact += h;
            }
            self.moment +=
                0.5 * ((a.x + state.x) * (state.y - a.y) - (a.y + state.y) * (state.x - a.x));
            let r2 = |s: &State| s.x * s.x + s.y * s.y;
            for (sum, (u, v)) in self.integrals.iter_mut().zip([
                (a.x, state.x),
                (a.y, state.y),
                (r2(&a), r2(&state)),
            ]) {
                *sum += 0.5 * (u + v) * h;
            }
        }
        self.last = (time, state);
    }

    pub(super) fn finish(&self, index: u64, speed_change: f64) -> Revolution {
        let (end, last) = self.last;
        let length = end - self.start;
        let [ix, iy, ir] = self.integrals.map(|v| v / length);
        let spread = ir - (ix * ix + iy * iy);
        let (dx, dy) = (
            last.x - self.first_position.0,
            last.y - self.first_position.1,
        );
        let area = 0.5 * (self.moment - ix * dy + iy * dx);
        let whirl = if spread > 1e-300 {
            area / (PI * spread)
        } else {
            0.0
        };
        Revolution {
            index,
            start: self.start,
            end,
            speed_ratio: TAU / length,
            speed_change,
            max_radius: math::sqrt(self.max_sq),
            min_radius: math::sqrt(self.min_sq.max(0.0)),
            contact_fraction: self.contact / length,
            whirl,
            enters: self.enters,
            exits: self.exits,
        }
    }
}

/// (r², d(r²)/dτ) of a state.
fn squared_radius(s: &State) -> (f64, f64) {
    (s.x * s.x + s.y * s.y, 2.0 * (s.x * s.vx + s.y * s.vy))
}

/// The smallest and largest value on [0, h] of the cubic Hermite polynomial through
/// (value, slope) pairs `a` at 0 and `b` at h.
fn hermite_extremes(a: (f64, f64), b: (f64, f64), h: f64) -> (f64, f64) {
    let (fa, da) = (a.0, a.1 * h);
    let (fb, db) = (b.0, b.1 * h);
    // p(s) = fa + da s + c2 s² + c3 s³ on s ∈ [0, 1].
    let c2 = 3.0 * (fb - fa) - 2.0 * da - db;
    let c3 = 2.0 * (fa - fb) + da + db;
    let p = |s: f64| fa + s * (da + s * (c2 + s * c3));
    let (mut lo, mut hi) = (fa.min(fb), fa.max(fb));
    // p'(s) = da + 2 c2 s + 3 c3 s² = 0.
    let (qa, qb, qc) = (3.0 * c3, 2.0 * c2, da);
    let mut consider = |s: f64| {
        if s > 0.0 && s < 1.0 {
            let v = p(s);
            lo = lo.min(v);
            hi = hi.max(v);
        }
    };
    if qa == 0.0 {
        if qb != 0.0 {
            consider(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let root = math::sqrt(disc);
            let q = -0.5 * (qb + if qb < 0.0 { -root } else { root });
            if q != 0.0 {
                consider(q / qa);
                consider(qc / q);
            }
        }
    }
    (lo, hi)
}
