//! Bifurcations between two consecutive points of a branch (`docs/MODEL.md` §18): detected by a
//! test function's sign change, located by the Illinois secant along the step (each trial point
//! corrected onto the branch on the hyperplane t·(u − u_a) = σ), to `locate_tolerance` in the
//! parameter.
//!
//! | bifurcation | test function |
//! |---|---|
//! | fold | det(M − I) = ∏(λ − 1), with the tangent's p component changing sign |
//! | period doubling | det(M + I) = ∏(λ + 1) |
//! | Neimark–Sacker | ∏_{i<j}(λ_i λ_j − 1), kept where a complex pair lies on the unit circle |
//! | grazing | z_e − 1 of the extremum of z that crosses 1 (the number of contacts changes) |

use rotor_rub::EventKind;
use rotor_rub::orbit::Extremum;

use super::correct::{Corrected, Solution, correct};
use super::evaluate::{Evaluator, Vector5, dot5, norm5, state_norm};
use super::{ContinuationSettings, Kind};
use crate::error::Result;

/// A bifurcation located on a branch.
pub struct Located {
    /// Which.
    pub kind: Kind,
    /// The point.
    pub solution: Solution,
    /// Its position along the step (for ordering).
    pub sigma: f64,
}

/// Most corrections spent locating one bifurcation.
const LOCATE_ITERATIONS: usize = 60;

/// The number of contacts (entries) over the orbit.
fn contacts(s: &Solution) -> u32 {
    s.eval.point.summary.count(EventKind::Enter)
}

/// The point of the branch at σ along `a`'s tangent from `a`, from the guess interpolated
/// between the bracket's points `lo`, `hi`.
fn at_sigma(
    ev: &mut Evaluator<'_>,
    a: &Solution,
    (lo, hi): (&(f64, Vector5), &(f64, Vector5)),
    sigma: f64,
    tolerance: f64,
) -> Result<Option<Solution>> {
    let w = if hi.0 != lo.0 {
        (sigma - lo.0) / (hi.0 - lo.0)
    } else {
        0.5
    };
    let guess: Vector5 = std::array::from_fn(|i| lo.1[i] + w * (hi.1[i] - lo.1[i]));
    let t = a.tangent;
    let plane = (t, dot5(&t, &a.u()) + sigma);
    match correct(
        ev,
        guess,
        plane,
        &t,
        tolerance,
        10,
        Some(super::continuation::jacobian_of(a)),
    )? {
        Corrected::Point(s) => Ok(Some(*s)),
        Corrected::Failed(_) => Ok(None),
    }
}

/// The root of `test` (None: not defined there) between `a` (σ = 0) and `b`, where it changes
/// sign: Illinois on σ; bisection where the test is not defined.
fn locate(
    ev: &mut Evaluator<'_>,
    a: &Solution,
    b: &Solution,
    settings: &ContinuationSettings,
    test: &mut dyn FnMut(&Solution) -> Option<f64>,
) -> Result<Option<(Solution, f64)>> {
    let sb = dot5(&a.tangent, &std::array::from_fn(|i| b.u()[i] - a.u()[i]));
    let (Some(ga), Some(gb)) = (test(a), test(b)) else {
        return Ok(None);
    };
    // (σ, u), g and the Illinois weight of each end.
    let mut lo = ((0.0, a.u()), ga);
    let mut hi = ((sb, b.u()), gb);
    let mut side = 0i8;
    let mut best: Option<(Solution, f64)> = None;
    let mut previous = f64::NAN;
    for _ in 0..LOCATE_ITERATIONS {
        let (s0, g0) = (lo.0.0, lo.1);
        let (s1, g1) = (hi.0.0, hi.1);
        let mut sigma = s0 - g0 * (s1 - s0) / (g1 - g0);
        if !sigma.is_finite() || (sigma - s0) * (sigma - s1) >= 0.0 {
            sigma = 0.5 * (s0 + s1);
        }
        let Some(s) = at_sigma(ev, a, (&lo.0, &hi.0), sigma, settings.tolerance)? else {
            return Ok(best);
        };
        let value = s.value();
        let Some(g) = test(&s) else {
            return Ok(best);
        };
        let close = (value - previous).abs() <= settings.locate_tolerance * value.abs().max(1.0);
        previous = value;
        let u = s.u();
        if g == 0.0 || close || (s1 - s0).abs() <= 1e-15 * (1.0 + sigma.abs()) {
            return Ok(Some((s, sigma)));
        }
        if (g > 0.0) == (g0 > 0.0) {
            lo = ((sigma, u), g);
            if side == -1 {
                hi.1 *= 0.5;
            }
            side = -1;
        } else {
            hi = ((sigma, u), g);
            if side == 1 {
                lo.1 *= 0.5;
            }
            side = 1;
        }
        best = Some((s, sigma));
    }
    Ok(best)
}

/// A test function of a branch point: its sign changes at a bifurcation.
type TestFunction = fn(&Solution) -> f64;

/// Whether two values have strictly opposite signs.
fn crosses(a: f64, b: f64) -> bool {
    (a < 0.0 && b > 0.0) || (a > 0.0 && b < 0.0)
}

/// The extremum of z in `s` of the same kind as `e` and nearest in time to it (times compared
/// modulo the orbit's length).
fn matching(s: &Solution, e: &Extremum) -> Option<Extremum> {
    let length = s.eval.point.summary.duration;
    let gap = |t: f64| {
        let d = (t - e.time).rem_euclid(length);
        d.min(length - d)
    };
    s.eval
        .extrema
        .iter()
        .filter(|x| x.maximum == e.maximum)
        .min_by(|x, y| gap(x.time).total_cmp(&gap(y.time)))
        .copied()
}

/// The extremum of `a` whose counterpart in `b` lies on the other side of z = 1, nearest to it.
fn crossing_extremum(a: &Solution, b: &Solution) -> Option<Extremum> {
    a.eval
        .extrema
        .iter()
        .filter_map(|e| {
            let m = matching(b, e)?;
            crosses(e.distance - 1.0, m.distance - 1.0)
                .then(|| (e, (e.distance - 1.0).abs() + (m.distance - 1.0).abs()))
        })
        .min_by(|x, y| x.1.total_cmp(&y.1))
        .map(|(e, _)| *e)
}

/// The bifurcations between consecutive points `a` and `b`, located, in branch order.
///
/// # Errors
/// Only an interrupt.
pub fn between(
    ev: &mut Evaluator<'_>,
    a: &Solution,
    b: &Solution,
    settings: &ContinuationSettings,
) -> Result<Vec<Located>> {
    let mut found = Vec::new();
    if !settings.locate {
        return Ok(found);
    }
    let tests: [(Kind, TestFunction); 3] = [
        (Kind::Fold, |s| s.characteristic(1.0)),
        (Kind::PeriodDoubling, |s| s.characteristic(-1.0)),
        (Kind::NeimarkSacker, Solution::pair_product),
    ];
    for (kind, test) in tests {
        // A fold turns the branch back: the tangent's p component changes sign too.
        let turns = a.tangent[4] * b.tangent[4] < 0.0;
        if !crosses(test(a), test(b)) || (kind == Kind::Fold && !turns) {
            continue;
        }
        let Some((s, sigma)) = locate(ev, a, b, settings, &mut |s| Some(test(s)))? else {
            continue;
        };
        // A pair λ, 1/λ of real multipliers zeroes the Neimark–Sacker test too (a neutral
        // saddle, no bifurcation): only a complex pair on the unit circle counts.
        let on_circle = s
            .multipliers
            .iter()
            .any(|m| m.im.abs() > 1e-9 && (m.abs() - 1.0).abs() < 1e-6);
        if kind == Kind::NeimarkSacker && !on_circle {
            continue;
        }
        found.push(Located {
            kind,
            solution: s,
            sigma,
        });
    }
    if contacts(a) != contacts(b)
        && let Some((s, sigma)) = locate_grazing(ev, a, b, settings)?
    {
        found.push(Located {
            kind: Kind::Grazing,
            solution: s,
            sigma,
        });
    }
    found.sort_by(|x, y| x.sigma.total_cmp(&y.sigma));
    Ok(found)
}

/// The grazing point between `a` and `b`: where the extremum of z that crosses 1 reaches it
/// (the secant on z_e − 1); where no extremum can be followed, bisection on the number of
/// contacts.
fn locate_grazing(
    ev: &mut Evaluator<'_>,
    a: &Solution,
    b: &Solution,
    settings: &ContinuationSettings,
) -> Result<Option<(Solution, f64)>> {
    if let Some(mut tracked) = crossing_extremum(a, b) {
        let mut test = |s: &Solution| {
            let e = matching(s, &tracked)?;
            tracked = e;
            Some(e.distance - 1.0)
        };
        if let Some(found) = locate(ev, a, b, settings, &mut test)? {
            return Ok(Some(found));
        }
    }
    let before = contacts(a);
    let mut test = |s: &Solution| Some(if contacts(s) == before { -1.0 } else { 1.0 });
    locate(ev, a, b, settings, &mut test)
}

/// The first point of the period-2k branch born at the period doubling `pd` (period k): the
/// eigenvector v of the multiplier −1, the new branch's direction d = (v, 0) made orthogonal
/// to the old branch's tangent, and Newton on P^{2k}(s) − s = 0 with d·(u − u_pd) = ε, for
/// growing ε until the orbit found is not the period-k one. `None` where none is found.
///
/// # Errors
/// Only an interrupt.
pub fn switch_branch(
    ev: &mut Evaluator<'_>,
    pd: &Solution,
    settings: &ContinuationSettings,
) -> Result<Option<Solution>> {
    let k = ev.periods;
    let Some(v) = flip_vector(&pd.eval.point.monodromy) else {
        return Ok(None);
    };
    let t = pd.tangent;
    let v5 = [v[0], v[1], v[2], v[3], 0.0];
    let along = dot5(&v5, &t);
    let mut d: Vector5 = std::array::from_fn(|i| v5[i] - along * t[i]);
    let n = norm5(&d);
    if n == 0.0 {
        return Ok(None);
    }
    d.iter_mut().for_each(|x| *x /= n);
    let u0 = pd.u();
    let scale = 1.0 + state_norm(&u0);
    ev.periods = 2 * k;
    let mut result = None;
    for epsilon in [1e-3, 4e-3, 1.6e-2, 6.4e-2].map(|e| e * scale) {
        let guess: Vector5 = std::array::from_fn(|i| u0[i] + epsilon * d[i]);
        let plane = (d, dot5(&d, &u0) + epsilon);
        if let Corrected::Point(s) = correct(ev, guess, plane, &d, settings.tolerance, 12, None)? {
            let x = s.eval.u;
            let half = s.eval.point.sections().get(k as usize - 1).copied();
            let apart = half.is_some_and(|h| {
                let h = h.to_array();
                (0..4).any(|i| (h[i] - x[i]).abs() > 1e-6 * scale)
            });
            if apart {
                result = Some(*s);
                break;
            }
        }
    }
    ev.periods = k;
    Ok(result)
}

/// The eigenvector of the monodromy for its multiplier nearest −1 (inverse iteration on
/// M + I, shifted off singular).
fn flip_vector(m: &rotor_rub::orbit::Mat4) -> Option<[f64; 4]> {
    let size = m
        .iter()
        .flatten()
        .fold(0.0, |a: f64, v| a.max(v.abs()))
        .max(1.0);
    let mut a = *m;
    for (i, row) in a.iter_mut().enumerate() {
        row[i] += 1.0 + 1e-9 * size;
    }
    let mut v = [0.5, 0.5, 0.5, 0.5];
    for _ in 0..4 {
        let w = rotor_rub::orbit::solve(&a, v, "M + I").ok()?;
        let n = w.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        v = w.map(|x| x / n);
    }
    Some(v)
}
