//! One forcing period of a run (`revolutions.rs`): its row ([`Revolution`]) and the sums it is
//! made of, node by node: the radius's extremes between nodes from the cubic Hermite polynomial
//! of r² = |q|², the time in contact, the orbit's signed area and its spread about its mean
//! position (the whirl).

use core::f64::consts::{PI, TAU};

use crate::math;
use crate::params::State;
use crate::propagate::Regime;

/// Which way the speed went over a revolution.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SpeedDirection {
    /// The speed rose (run-up).
    Up,
    /// The speed fell (coast-down).
    Down,
    /// The speed was the same at both ends.
    Hold,
}

impl SpeedDirection {
    /// `up`, `down` or `hold`, as written in files.
    pub const fn name(self) -> &'static str {
        match self {
            SpeedDirection::Up => "up",
            SpeedDirection::Down => "down",
            SpeedDirection::Hold => "hold",
        }
    }
}

/// Which way the orbit turned over a revolution.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WhirlDirection {
    /// With the rotor's spin (counter-clockwise).
    Forward,
    /// Against it.
    Backward,
    /// Neither clearly: |whirl| below [`WHIRL_THRESHOLD`] (a flat orbit, or one that reverses).
    Mixed,
}

impl WhirlDirection {
    /// `forward`, `backward` or `mixed`, as written in files.
    pub const fn name(self) -> &'static str {
        match self {
            WhirlDirection::Forward => "forward",
            WhirlDirection::Backward => "backward",
            WhirlDirection::Mixed => "mixed",
        }
    }
}

/// |whirl| below which a revolution's whirl counts as [`WhirlDirection::Mixed`]: an ellipse of
/// axis ratio 1:20 traversed once has whirl 0.1.
pub const WHIRL_THRESHOLD: f64 = 0.1;

/// One revolution of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Revolution {
    /// k, counted from the start of the tracking.
    pub index: u64,
    /// When it starts.
    pub start: f64,
    /// When it ends.
    pub end: f64,
    /// Its mean speed ratio 2π/(end − start).
    pub speed_ratio: f64,
    /// η(end) − η(start).
    pub speed_change: f64,
    /// The largest |q| (clearances from the rotor's rest position).
    pub max_radius: f64,
    /// The smallest |q|.
    pub min_radius: f64,
    /// The fraction of the revolution spent in contact.
    pub contact_fraction: f64,
    /// The orbit's signed area about its own mean position over π times its mean squared
    /// distance from it: +1 for one forward circle, −1 for one backward circle, 2ab/(a² + b²)
    /// for an ellipse of semi-axes a, b traversed forward once, n for n turns.
    pub whirl: f64,
    /// Contacts that started.
    pub enters: u32,
    /// Contacts that ended.
    pub exits: u32,
}

impl Revolution {
    /// Which way the speed went.
    pub fn direction(&self) -> SpeedDirection {
        if self.speed_change > 0.0 {
            SpeedDirection::Up
        } else if self.speed_change < 0.0 {
            SpeedDirection::Down
        } else {
            SpeedDirection::Hold
        }
    }

    /// Which way the orbit turned.
    pub fn whirl_direction(&self) -> WhirlDirection {
        if self.whirl > WHIRL_THRESHOLD {
            WhirlDirection::Forward
        } else if self.whirl < -WHIRL_THRESHOLD {
            WhirlDirection::Backward
        } else {
            WhirlDirection::Mixed
        }
    }
}

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
