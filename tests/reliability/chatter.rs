//! Item 1 of issue 32: zero-length switch pairs in the numerical methods with a stiff stator
//! under friction. After `slip` the slipping segment starts on a double zero of σw (w = 0 and
//! w' = λ − μσN = 0 together, `docs/MODEL.md` §10 trap 1); at K̂ ≥ 3e4 the cone margin at the
//! switch is only known to ±5e-12 (its rate times an ulp of τ), so σw sits at 0 to rounding for
//! a few ulps of time with either sign. The dense-output search took that noise for a crossing:
//! `roll` 2.5e-14 after the `slip`, `slip` again 7e-15 later (dop853, hybrid and rk45 recorded
//! 391–399 rolling starts where taylor and analytic record 390). Sibling: an exit whose free
//! flight starts with h = 0 to rounding and returns into contact later in the same step, where
//! the refinement was drawn to the exact zero the dense output gave one ulp after the start
//! (`exit`, `enter`, `exit` within 2e-14, dop853 at tol 1e-8). The rule now (`docs/MODEL.md`
//! §12): a switch function's dip within its rounding band is not a crossing, on the dense output
//! as on the closed forms and the Taylor polynomials, and the crossing is the function's root
//! just before it falls through the band.

use rotor_rub::reference::{Interpolant, first_crossing_beyond, first_crossing_subdivided};
use rotor_rub::{Method, rounding};

use super::common::{counts, dry_whip, shortest_gap, switches};

/// Every method on the stiff dry whip (10 forcing periods, the case and K̂ = 3e4, where
/// it was first seen) at loose, default and tight tolerances: no two switches closer than
/// 1e-9 (the shortest real interval in these runs is 3.6e-7: a rolling episode between `roll`
/// and `slip`), and every kind counted as the taylor method at tol 1e-14 counts it.
#[test]
fn stiff_dry_whip_has_no_zero_length_switch_pairs() {
    for k in [3e4, 1e5] {
        let problem = dry_whip(k);
        let end = 10.0 * problem.params.forcing_period();
        let reference = counts(&switches(&problem, Method::Taylor, 1e-14, end));
        assert!(reference[3] >= 200, "K {k}: {reference:?} rolling starts");
        for method in [
            Method::Dop853,
            Method::Hybrid,
            Method::Rk45,
            Method::Analytic,
        ] {
            for tol in [1e-8, 1e-10, 1e-12] {
                let events = switches(&problem, method, tol, end);
                let (gap, at) = shortest_gap(&events);
                assert!(
                    gap > 1e-9,
                    "K {k} {} tol {tol:e}: {:?} then {:?} {gap:e} later",
                    method.name(),
                    events[at].kind,
                    events[at + 1].kind
                );
                assert_eq!(
                    counts(&events),
                    reference,
                    "K {k} {} tol {tol:e}: switches by kind (enter, exit, reverse, roll, slip)",
                    method.name()
                );
            }
        }
    }
}

/// A "dense output" that is the identity on [0, 1]: the switching function is then a function
/// of time alone.
#[derive(Clone, Copy)]
struct Line;

impl Interpolant<1> for Line {
    fn start(&self) -> f64 {
        0.0
    }
    fn end(&self) -> f64 {
        1.0
    }
    fn eval(&self, t: f64) -> [f64; 1] {
        [t]
    }
}

/// A segment starting on a double zero: g = c·t² − δ·t rises quadratically from 0, its slope
/// at the start −δ a rounding error (after `slip`: σw' = λ − μσN, the cone margin at the switch
/// known to ±5e-12), so it dips by δ²/(4c) ≈ 1e-28 just after the start. The search without a
/// band finds a "crossing" there (the chatter); with the rounding band it finds none.
#[test]
fn a_double_zero_at_the_start_is_not_a_crossing() {
    let g = |_: f64, y: &[f64; 1]| {
        let t = y[0];
        (1e-3 * t * t - 1e-15 * t, 2e-3 * t - 1e-15)
    };
    let band = rounding::SOLUTION;
    assert_eq!(
        first_crossing_beyond(8, &Line, &[0.0], &[1.0], band, g),
        None
    );
    let unbanded = first_crossing_subdivided(8, &Line, &[0.0], &[1.0], g);
    assert!(
        unbanded.is_some_and(|t| t < 1e-11),
        "the dip is a crossing without the band: {unbanded:?}"
    );
}

/// A segment whose function starts at 0 to rounding, rises and falls back through 0 at t = 0.75
/// within the first sub-interval examined: the crossing is at 0.75, not at the exact zero the
/// function takes one ulp after the start (a free flight after `exit` that returns into contact
/// within its first step).
#[test]
fn a_rounding_zero_next_to_the_start_is_not_the_crossing() {
    let g = |_: f64, y: &[f64; 1]| {
        let t = y[0];
        let value = if t < 1e-15 { 0.0 } else { t * (0.75 - t) };
        (value, 0.75 - 2.0 * t)
    };
    let t = first_crossing_beyond(1, &Line, &[0.0], &[1.0], rounding::SOLUTION, g).unwrap();
    assert!((t - 0.75).abs() < 1e-15, "{t}");
}

/// A real crossing is found where it is, whatever the band: a transversal one, one just after
/// a sample point (its value there within the band below 0), and a dip deeper than the band
/// between samples.
#[test]
fn real_crossings_are_located_to_rounding() {
    let band = rounding::SOLUTION;
    for root in [0.3, 0.5 + 1e-15, 0.625 + 3e-16] {
        let g = |_: f64, y: &[f64; 1]| (root - y[0], -1.0);
        let t = first_crossing_beyond(8, &Line, &[0.0], &[1.0], band, g).unwrap();
        assert!((t - root).abs() <= 2.0 * f64::EPSILON, "{t} vs {root}");
    }
    let (centre, depth) = (0.53, 1e-10);
    let g = |_: f64, y: &[f64; 1]| ((y[0] - centre).powi(2) - depth, 2.0 * (y[0] - centre));
    let t = first_crossing_beyond(8, &Line, &[0.0], &[1.0], band, g).unwrap();
    let want = centre - depth.sqrt();
    assert!((t - want).abs() < 1e-15, "{t} vs {want}");
    // A dip shallower than the band is rounding.
    let g = |_: f64, y: &[f64; 1]| ((y[0] - centre).powi(2) - 1e-15, 2.0 * (y[0] - centre));
    assert_eq!(
        first_crossing_beyond(8, &Line, &[0.0], &[1.0], band, g),
        None
    );
}
