//! The free-flight step map (`docs/MODEL.md` §4): Φ(s) and G(s) of w(s) = Φ(s)·w(0) +
//! G(s)·(cos θ0, sin θ0), the free closed form of `free.rs` at unit inputs (the fixed-step
//! stepper's fast path).

use super::free::{free_trajectory, homogeneous_constants};
use super::{Model, Rates};
use crate::derive::derivative;

/// Free flight over a step of length s as an affine map of the start: w(s) = Φ(s)·w(0) +
/// G(s)·(cos θ0, sin θ0) (`docs/MODEL.md` §4). The steady form is linear in the start state and
/// the start phasor, so Φ's columns are its state at s from the unit start states with the
/// phasor zero, and G's from the zero state with the phasors (1, 0), (0, 1): the trajectory with
/// X, P, Y, Q from `homogeneous_constants` and the phasor at s by angle addition from θ0, the
/// unit inputs substituted here so that the generated map multiplies no exact zeros.
pub(super) fn derive(m: &mut Model) {
    let mut rates = Rates::new();
    let q = free_trajectory(m, &mut rates);
    let g = &mut m.graph;
    let state = [
        q[0],
        q[1],
        derivative(g, q[0], &rates),
        derivative(g, q[1], &rates),
    ];
    let [ct, st, ce, se] = ["ct", "st", "ce", "se"].map(|n| m.var(n));
    let g = &mut m.graph;
    let at_s = {
        let (a, b) = (g.mul(ct, ce), g.mul(st, se));
        let c = g.sub(a, b);
        let (a, b) = (g.mul(st, ce), g.mul(ct, se));
        [c, g.add(a, b)]
    };
    let constants = homogeneous_constants(m);
    let from_start = state.map(|e| {
        let e = m.subst(e, &[("ct", at_s[0]), ("st", at_s[1])]);
        let pairs: Vec<(&str, crate::expr::ExprId)> = ["xh", "px", "yh", "py"]
            .into_iter()
            .zip(constants.iter().copied())
            .collect();
        m.subst(e, &pairs)
    });
    let (one, zero) = (m.graph.constant(1.0), m.graph.constant(0.0));
    let inputs = ["x0", "y0", "vx0", "vy0", "ct", "st"];
    // The value of every state component for the inputs set to 1 at `unit`, 0 elsewhere.
    let column = |m: &mut Model, unit: usize| -> [crate::expr::ExprId; 4] {
        let pairs: Vec<(&str, crate::expr::ExprId)> = inputs
            .iter()
            .enumerate()
            .map(|(k, &n)| (n, if k == unit { one } else { zero }))
            .collect();
        from_start.map(|e| m.subst(e, &pairs))
    };
    let phi: [[crate::expr::ExprId; 4]; 4] = core::array::from_fn(|j| column(m, j));
    let forcing = [column(m, 4), column(m, 5)];
    const PHI: [[&str; 4]; 4] = [
        ["p00", "p01", "p02", "p03"],
        ["p10", "p11", "p12", "p13"],
        ["p20", "p21", "p22", "p23"],
        ["p30", "p31", "p32", "p33"],
    ];
    const PHI_DOC: [[&str; 4]; 4] = [
        ["∂x/∂x0", "∂x/∂y0", "∂x/∂x0'", "∂x/∂y0'"],
        ["∂y/∂x0", "∂y/∂y0", "∂y/∂x0'", "∂y/∂y0'"],
        ["∂x'/∂x0", "∂x'/∂y0", "∂x'/∂x0'", "∂x'/∂y0'"],
        ["∂y'/∂x0", "∂y'/∂y0", "∂y'/∂x0'", "∂y'/∂y0'"],
    ];
    let outputs = row_major(&PHI, &PHI_DOC, &phi);
    m.add_formula(
        "free_step_transition",
        "Φ(s), the transition matrix of unforced free flight over a step of length s (state order x, y, x', y'; `pij` is row i, column j), from the basis EC(s), ES(s).",
        "docs/MODEL.md §4",
        "the steady-form trajectory X·EC + P·ES + xp with X, P, Y, Q from the start state, at the unit start states with the forcing phasor zero.",
        "FreeStepTransition",
        outputs,
    );
    const G: [[&str; 2]; 4] = [
        ["g00", "g01"],
        ["g10", "g11"],
        ["g20", "g21"],
        ["g30", "g31"],
    ];
    const G_DOC: [[&str; 2]; 4] = [
        [
            "x from the start phasor (1, 0)",
            "x from the start phasor (0, 1)",
        ],
        [
            "y from the start phasor (1, 0)",
            "y from the start phasor (0, 1)",
        ],
        [
            "x' from the start phasor (1, 0)",
            "x' from the start phasor (0, 1)",
        ],
        [
            "y' from the start phasor (1, 0)",
            "y' from the start phasor (0, 1)",
        ],
    ];
    let outputs = row_major(&G, &G_DOC, &forcing);
    m.add_formula(
        "free_step_forcing",
        "G(s), the forced response of free flight over a step of length s from rest (row i: x, y, x', y'; column 0 for the start phasor (1, 0), column 1 for (0, 1)), from the basis EC(s), ES(s) and the forcing's rotation (cos ηs, sin ηs).",
        "docs/MODEL.md §4",
        "the steady-form trajectory X·EC + P·ES + xp with X, P, Y, Q from the start state and the phasor at s by angle addition, at the zero start state and the unit start phasors.",
        "FreeStepForcing",
        outputs,
    );
}

/// The outputs of a 4-row matrix given by its `columns`, row by row, named and documented by
/// `names` and `docs` (row-major).
fn row_major<const C: usize>(
    names: &[[&'static str; C]; 4],
    docs: &[[&'static str; C]; 4],
    columns: &[[crate::expr::ExprId; 4]; C],
) -> Vec<(&'static str, &'static str, crate::expr::ExprId)> {
    let mut outputs = Vec::with_capacity(4 * C);
    for (i, (names, docs)) in names.iter().zip(docs).enumerate() {
        for ((name, doc), column) in names.iter().zip(docs).zip(columns) {
            outputs.push((*name, *doc, column[i]));
        }
    }
    outputs
}
