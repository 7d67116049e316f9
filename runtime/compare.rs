//! Comparing the switches of two runs (for example two methods, or one method at two
//! tolerances): pure functions on event slices, no allocation.
//!
//! The events are matched one to one in order: the i-th switch of one run with the i-th of the
//! other. This is the right pairing as long as both runs see the same sequence of contacts; the
//! first place where they stop doing so is reported as the first disagreement, and everything
//! after it should be read with care (a missed contact shifts every later pair).
//!
//! A contact only one run has may lie below what the runs resolve ([`contact_depth`],
//! [`contact_resolution`]): the numerical methods miss contacts shallower than about 10·tol, and
//! on an orbit that grazes z = 1 their own truncation error makes contacts that shallow
//! (`docs/MODEL.md` §12); a comparison sets those aside instead of calling them unmatched.

use crate::coefficients::ModelParams;
use crate::geometry;
use crate::params::{Params, State};
use crate::propagate::{Event, EventKind};

/// Why two runs first disagree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Disagreement {
    /// The matched switches have different kinds (one enters where the other exits).
    Kind,
    /// The switch times differ by more than the tolerance.
    Time,
    /// The states at the switches differ by more than the tolerance (largest component).
    State,
    /// One run has no switch left to match this one.
    Missing,
}

/// Where two runs first disagree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstDisagreement {
    /// Index of the switch (in both runs; for [`Disagreement::Missing`], in the longer run).
    pub index: usize,
    /// Its time in the first run, or in the longer run for [`Disagreement::Missing`].
    pub time: f64,
    /// What differs.
    pub reason: Disagreement,
}

/// The outcome of [`compare_events`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// Number of index pairs compared: the length of the shorter run.
    pub compared: usize,
    /// Pairs of the same kind (the ones the time and state differences are taken over).
    pub matched: usize,
    /// Pairs whose kinds differ.
    pub kind_mismatches: usize,
    /// Difference of the run lengths, `|a.len() − b.len()|`.
    pub length_difference: usize,
    /// Switches without a same-kind partner: `kind_mismatches + length_difference`.
    pub unmatched: usize,
    /// Largest |t_a − t_b| over matched pairs (0 when none).
    pub max_time_difference: f64,
    /// Index of the pair with [`Comparison::max_time_difference`] (`None` when no pair matched).
    pub max_time_index: Option<usize>,
    /// Largest component difference max_k |s_a,k − s_b,k| of the states over matched pairs
    /// (0 when none).
    pub max_state_difference: f64,
    /// Index of the pair with [`Comparison::max_state_difference`].
    pub max_state_index: Option<usize>,
    /// The first pair (in order) that differs in kind, or by more than the tolerance in time or
    /// state, or the first switch that has no partner; `None` when the runs agree.
    pub first_disagreement: Option<FirstDisagreement>,
}

impl Comparison {
    /// Whether the runs agree to the tolerance: same number and kinds of switches, times and
    /// states within it.
    pub fn agrees(&self) -> bool {
        self.first_disagreement.is_none()
    }
}

/// The largest component difference of two states (NaN in either gives +∞).
pub fn state_difference(a: &State, b: &State) -> f64 {
    let d = [a.x - b.x, a.y - b.y, a.vx - b.vx, a.vy - b.vy];
    d.iter().fold(0.0, |m: f64, v| {
        let v = crate::math::abs(*v);
        if v.is_nan() { f64::INFINITY } else { m.max(v) }
    })
}

/// `d ≤ tolerance`, false when either is NaN.
fn within(d: f64, tolerance: f64) -> bool {
    d <= tolerance
}

/// Match the switches of runs `a` and `b` one to one in order and measure their differences;
/// `tolerance` applies to both the time difference and the state difference when looking for the
/// first disagreement (a difference equal to it is still agreement; NaN is a disagreement).
pub fn compare_events(a: &[Event], b: &[Event], tolerance: f64) -> Comparison {
    let compared = a.len().min(b.len());
    let length_difference = a.len().max(b.len()) - compared;
    let mut c = Comparison {
        compared,
        matched: 0,
        kind_mismatches: 0,
        length_difference,
        unmatched: length_difference,
        max_time_difference: 0.0,
        max_time_index: None,
        max_state_difference: 0.0,
        max_state_index: None,
        first_disagreement: None,
    };
    let note = |c: &mut Comparison, index: usize, time: f64, reason: Disagreement| {
        if c.first_disagreement.is_none() {
            c.first_disagreement = Some(FirstDisagreement {
                index,
                time,
                reason,
            });
        }
    };
    for (index, (ea, eb)) in a.iter().zip(b.iter()).enumerate() {
        if ea.kind != eb.kind {
            c.kind_mismatches += 1;
            c.unmatched += 1;
            note(&mut c, index, ea.time, Disagreement::Kind);
            continue;
        }
        c.matched += 1;
        let dt = crate::math::abs(ea.time - eb.time);
        let dt = if dt.is_nan() { f64::INFINITY } else { dt };
        let ds = state_difference(&ea.state, &eb.state);
        if c.max_time_index.is_none() || dt > c.max_time_difference {
            c.max_time_difference = dt;
            c.max_time_index = Some(index);
        }
        if c.max_state_index.is_none() || ds > c.max_state_difference {
            c.max_state_difference = ds;
            c.max_state_index = Some(index);
        }
        if !within(dt, tolerance) {
            note(&mut c, index, ea.time, Disagreement::Time);
        } else if !within(ds, tolerance) {
            note(&mut c, index, ea.time, Disagreement::State);
        }
    }
    let longer = if a.len() > b.len() { a } else { b };
    if let Some(extra) = longer.get(compared) {
        note(&mut c, compared, extra.time, Disagreement::Missing);
    }
    c
}

/// How deep a contact must reach (z − 1) for two runs at tolerances `tol_a` and `tol_b` to be
/// held to both seeing it: 10·max(tol_a, tol_b), the numerical methods' resolution. Shallower
/// contacts may be missed by a numerical method (its dense output errs by about its tolerance)
/// or made by it where the true orbit only grazes z = 1 (the exactly grazing orbit z ≡ 1, which
/// the closed forms follow to rounding and dop853 at tol 1e-10 leaves by up to 8e-11 in z,
/// issue 32): `docs/MODEL.md` §12.
pub fn contact_resolution(tol_a: f64, tol_b: f64) -> f64 {
    10.0 * tol_a.max(tol_b)
}

/// Samples of the cubic in [`penetration`].
const DEPTH_SAMPLES: u32 = 64;

/// The penetration depth z − 1 of the contact from `enter` to the `exit` that ends it (switches
/// of one run): [`penetration`] between them. NaN unless `enter` is an `enter` and `exit` an
/// `exit` after it.
pub fn contact_depth(params: &Params, enter: &Event, exit: &Event) -> f64 {
    let ordered = exit.time >= enter.time;
    if enter.kind != EventKind::Enter || exit.kind != EventKind::Exit || !ordered {
        return f64::NAN;
    }
    penetration(params, (enter.time, &enter.state), (exit.time, &exit.state))
}

/// How far past z = 1 (z − 1) a run reaches between two of its states, estimated from
/// h = z² − 1 and its rate h′ at both (a contact's `enter` and `exit`, where h = 0, or its
/// `enter` and a run's last state inside it): the largest value of the cubic through them,
/// halved (z − 1 ≈ h/2 near z = 1). Exact for a parabola; 0 when the cubic stays below 0.
pub fn penetration(params: &Params, from: (f64, &State), to: (f64, &State)) -> f64 {
    let length = to.0 - from.0;
    let model = ModelParams::of(params);
    let (a, b) = (
        geometry::point(&model, *from.1),
        geometry::point(&model, *to.1),
    );
    // Hermite on σ ∈ [0, 1]: H = h0 (1 − 3σ² + 2σ³) + h1 (3σ² − 2σ³)
    //   + m0 (σ³ − 2σ² + σ) + m1 (σ³ − σ²), m = h′·length.
    let (m0, m1) = (a.dh * length, b.dh * length);
    let mut deepest: f64 = a.h.max(b.h).max(0.0);
    for k in 1..DEPTH_SAMPLES {
        let s = f64::from(k) / f64::from(DEPTH_SAMPLES);
        let (s2, s3) = (s * s, s * s * s);
        let h = a.h * (1.0 - 3.0 * s2 + 2.0 * s3)
            + b.h * (3.0 * s2 - 2.0 * s3)
            + m0 * (s3 - 2.0 * s2 + s)
            + m1 * (s3 - s2);
        deepest = deepest.max(h);
    }
    0.5 * deepest
}
