//! What an orbit does between its switches, measured on each segment's own solution (the free
//! closed form, the contact segment's dense output): the local extrema of the distance z from
//! the stator centre (where a contact appears, vanishes or splits as a parameter moves: grazing,
//! `docs/MODEL.md` §18) and of the radius |q| from the rotor's rest position (the orbit's size, as
//! the run-up measures it, `docs/MODEL.md` §14), with the time spent in contact and the switches.
//!
//! A segment is sampled on a grid; where the rate of z² (h' = 2 d·q') or of |q|² (2 q·q') changes
//! sign between two samples, the extremum is refined by [`crate::refine`] (Newton with the
//! second rate, h'' from the generated `switching_curvature`).

use crate::coefficients::ModelParams;
use crate::geometry;
use crate::math;
use crate::params::State;
use crate::propagate::{EventKind, Regime};
use crate::refine::{Knot, Refinement, refine};

/// A local extremum of the distance z = |q − ε̂| along an orbit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extremum {
    /// When (absolute time τ of the map's run).
    pub time: f64,
    /// The state there.
    pub state: State,
    /// z there.
    pub distance: f64,
    /// A maximum of z (else a minimum).
    pub maximum: bool,
    /// The regime of the segment it lies in.
    pub regime: Regime,
}

/// What a stretch of orbit did: its size, its contact and its switches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// The largest |q| (clearances from the rotor's rest position).
    pub max_radius: f64,
    /// The smallest |q|.
    pub min_radius: f64,
    /// The largest distance z from the stator centre.
    pub max_distance: f64,
    /// The smallest z.
    pub min_distance: f64,
    /// Time in contact (contact or rolling).
    pub contact_time: f64,
    /// The stretch's length.
    pub duration: f64,
    /// Switches by kind, in the order of [`EventKind::ALL`].
    pub switches: [u32; 5],
    /// A hash (FNV-1a) of the switch kinds in their order: two stretches with the same switch
    /// sequence have the same value (a change of it along a branch is a grazing or a change of
    /// friction's switches).
    pub sequence: u64,
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0100_0000_01b3;

impl Default for Summary {
    fn default() -> Self {
        Summary {
            max_radius: 0.0,
            min_radius: f64::INFINITY,
            max_distance: 0.0,
            min_distance: f64::INFINITY,
            contact_time: 0.0,
            duration: 0.0,
            switches: [0; 5],
            sequence: FNV_OFFSET,
        }
    }
}

impl Summary {
    /// The fraction of the stretch spent in contact.
    pub fn contact_fraction(&self) -> f64 {
        if self.duration > 0.0 {
            self.contact_time / self.duration
        } else {
            0.0
        }
    }

    /// The number of switches of `kind`.
    pub fn count(&self, kind: EventKind) -> u32 {
        EventKind::ALL
            .iter()
            .zip(self.switches)
            .find_map(|(k, n)| (*k == kind).then_some(n))
            .unwrap_or(0)
    }

    /// The total number of switches.
    pub fn total_switches(&self) -> u32 {
        self.switches.iter().sum()
    }

    /// Count a switch.
    pub(super) fn switch(&mut self, kind: EventKind) {
        for (k, n) in EventKind::ALL.iter().zip(self.switches.iter_mut()) {
            if *k == kind {
                *n = n.saturating_add(1);
            }
        }
        let code = EventKind::ALL.iter().position(|k| *k == kind).unwrap_or(0) as u64;
        self.sequence = (self.sequence ^ (code + 1)).wrapping_mul(FNV_PRIME);
    }

    /// Take a point of the orbit into the extremes.
    pub(super) fn point(&mut self, model: &ModelParams, s: &State) {
        let r = math::hypot(s.x, s.y);
        self.max_radius = self.max_radius.max(r);
        self.min_radius = self.min_radius.min(r);
        let z = geometry::distance(model, s.x, s.y);
        self.max_distance = self.max_distance.max(z);
        self.min_distance = self.min_distance.min(z);
    }
}

/// A sample of a segment: time, state and acceleration, with the rates of z² and |q|².
#[derive(Clone, Copy, Debug)]
pub(super) struct Probe {
    t: f64,
    state: State,
    /// h' = d(z²)/dτ and h''.
    dz: (f64, f64),
    /// d|q|²/dτ and its rate.
    dr: (f64, f64),
}

impl Probe {
    /// The probe at time `t` of a segment whose state there is `state` and acceleration `a`.
    pub(super) fn new(model: &ModelParams, t: f64, state: State, a: (f64, f64)) -> Self {
        let p = geometry::point(model, state);
        let d2h = geometry::curvature(model, &state, a);
        let s = &state;
        let dr = 2.0 * (s.x * s.vx + s.y * s.vy);
        let d2r = 2.0 * (s.vx * s.vx + s.vy * s.vy + s.x * a.0 + s.y * a.1);
        Probe {
            t,
            state,
            dz: (p.dh, d2h),
            dr: (dr, d2r),
        }
    }
}

/// Which extremum a rate's sign change between `a` and `b` brackets: `Some(true)` a maximum
/// (+ to − or 0), `Some(false)` a minimum; none where the sign stays or `a`'s rate is 0 (a
/// root on a boundary belongs to the stretch that ends there).
fn bracketed(a: f64, b: f64) -> Option<bool> {
    if a > 0.0 && b <= 0.0 {
        Some(true)
    } else if a < 0.0 && b >= 0.0 {
        Some(false)
    } else {
        None
    }
}

/// The root of a rate (`rate` picks it from a probe) between `a` and `b`, where it changes sign
/// ([`bracketed`]: `maximum`), by the one refinement; `eval` gives the probe at a time.
fn root_between(
    a: &Probe,
    b: &Probe,
    maximum: bool,
    rate: impl Fn(&Probe) -> (f64, f64),
    mut eval: impl FnMut(f64) -> Probe,
) -> Probe {
    let sign = if maximum { -1.0 } else { 1.0 };
    let knot = |p: &Probe| {
        let (g, dg) = rate(p);
        Knot {
            s: p.t,
            g: sign * g,
            dg: sign * dg,
            point: *p,
        }
    };
    let (below, above) = (knot(a), knot(b));
    if above.g <= 0.0 {
        return *b;
    }
    let settings = Refinement {
        max_steps: 80,
        residual: 0.0,
        scale: 1.0,
        first_guess: None,
        close: false,
    };
    refine(|t| knot(&eval(t)), below, above, &settings)
        .best
        .point
}

/// Scan the probes of one stretch of a segment (in time order) for extrema of z and |q|:
/// each extremum of z goes to `found`, every extremum and sample into `summary`.
pub(super) fn scan(
    model: &ModelParams,
    regime: Regime,
    probes: &[Probe],
    mut eval: impl FnMut(f64) -> Probe,
    summary: &mut Summary,
    mut found: impl FnMut(&Extremum),
) {
    for p in probes {
        summary.point(model, &p.state);
    }
    for pair in probes.windows(2) {
        let [a, b] = pair else { continue };
        if let Some(maximum) = bracketed(a.dz.0, b.dz.0) {
            let p = root_between(a, b, maximum, |p| p.dz, &mut eval);
            summary.point(model, &p.state);
            found(&Extremum {
                time: p.t,
                state: p.state,
                distance: geometry::distance(model, p.state.x, p.state.y),
                maximum,
                regime,
            });
        }
        if let Some(maximum) = bracketed(a.dr.0, b.dr.0) {
            let p = root_between(a, b, maximum, |p| p.dr, &mut eval);
            summary.point(model, &p.state);
        }
    }
}
