//! Pseudo-arclength continuation of a branch of period-k orbits (`docs/MODEL.md` §18): from a
//! point u = (s, p) with unit tangent t, the predictor u + h t is corrected on the hyperplane
//! t·(u − u_pred) = 0 (so the branch is followed through folds, where p turns back), the step h
//! grows after quick corrections and shrinks after slow or failed ones and where the tangent
//! turns sharply; between consecutive points the test functions are watched
//! ([`super::locate`]), and each bifurcation found is located and inserted into the branch.
//! A branch ends where p leaves the range (the last point lands on its edge), at the point
//! budget, where it closes on itself, or where no step succeeds.

use rotor_rub::State;

use super::correct::{Corrected, Solution, correct};
use super::evaluate::{Evaluator, Vector5, dot5, norm5};
use super::locate::{Located, between};
use super::{Branch, BranchPoint, Continuation, ContinuationSettings, Kind};
use crate::error::{CliError, Result, num};

/// Most Newton iterations of one corrector.
pub const CORRECTOR_ITERATIONS: u32 = 8;
/// A step whose tangent turns by more than this (cosine below) is retried shorter.
const MIN_COSINE: f64 = 0.97;

/// The monodromy and ∂R/∂p of a point: the chord corrector's Jacobian near it.
pub fn jacobian_of(s: &Solution) -> (&rotor_rub::orbit::Mat4, &[f64; 4]) {
    (
        &s.eval.point.monodromy,
        s.eval.dp.as_ref().unwrap_or(&[0.0; 4]),
    )
}

/// Where a branch starts: a guess of its orbit's state on the section at a parameter value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start {
    /// The guess.
    pub guess: State,
    /// The parameter value.
    pub value: f64,
}

/// The first point: the period-k orbit at p = `start.value` from its guess (Newton with p
/// held), its tangent pointing along `sign` in p.
///
/// # Errors
/// No orbit there ([`CliError::failure`] naming the value), or an interrupt.
pub fn first_point(
    ev: &mut Evaluator<'_>,
    start: &Start,
    sign: f64,
    settings: &ContinuationSettings,
) -> Result<Solution> {
    let (guess, p) = (start.guess, start.value);
    let u = [guess.x, guess.y, guess.vx, guess.vy, p];
    let direction = [0.0, 0.0, 0.0, 0.0, sign];
    let fixed = ([0.0, 0.0, 0.0, 0.0, 1.0], p);
    match correct(ev, u, fixed, &direction, settings.tolerance, 40, None)? {
        Corrected::Point(s) => Ok(*s),
        Corrected::Failed(why) => Err(CliError::failure(format!(
            "no period-{} orbit found at {} = {} from the start state: {why}",
            ev.periods,
            settings.parameter.info().name,
            num(p)
        ))),
    }
}

/// The point of the branch where p reaches `edge`, between `a` (inside) and `b` (outside).
fn land_on_edge(
    ev: &mut Evaluator<'_>,
    a: &Solution,
    b: &Solution,
    edge: f64,
    tolerance: f64,
) -> Result<Option<Solution>> {
    let (pa, pb) = (a.value(), b.value());
    let w = (edge - pa) / (pb - pa);
    let (ua, ub) = (a.u(), b.u());
    let guess: Vector5 = std::array::from_fn(|i| ua[i] + w * (ub[i] - ua[i]));
    let fixed = ([0.0, 0.0, 0.0, 0.0, 1.0], edge);
    match correct(
        ev,
        guess,
        fixed,
        &a.tangent,
        tolerance,
        CORRECTOR_ITERATIONS,
        Some(jacobian_of(a)),
    )? {
        Corrected::Point(s) => Ok(Some(*s)),
        Corrected::Failed(_) => Ok(None),
    }
}

/// Follow one branch from `start` (its tangent the direction of travel), appending its points
/// to `out` (branch number `branch`); the period-doubling points found are returned for
/// branch switching.
pub fn follow(
    ev: &mut Evaluator<'_>,
    start: Solution,
    branch: usize,
    parent_period: Option<u32>,
    settings: &ContinuationSettings,
    out: &mut Continuation,
) -> Result<String> {
    let (lo, hi) = (
        settings.from.min(settings.to),
        settings.from.max(settings.to),
    );
    let first = out.points.len();
    let mut current = start;
    let mut previous: Option<(Vector5, Vector5)> = None;
    let mut h = settings.step;
    out.points
        .push(BranchPoint::new(branch, current.clone(), None));
    let mut count = 1usize;
    loop {
        if count >= settings.max_points {
            return Ok(format!(
                "its point budget ({}) is used up",
                settings.max_points
            ));
        }
        let u = current.u();
        let t = current.tangent;
        // The tangent predictor with the branch's curvature from the last step (the change of
        // the tangent over its length): an error of O(h³) instead of O(h²), fewer corrections.
        let bend: Vector5 = match previous {
            Some((p, pt)) => {
                let d: Vector5 = std::array::from_fn(|i| u[i] - p[i]);
                let length = norm5(&d);
                if length > 0.0 {
                    std::array::from_fn(|i| (t[i] - pt[i]) / length)
                } else {
                    [0.0; 5]
                }
            }
            None => [0.0; 5],
        };
        let predicted: Vector5 = std::array::from_fn(|i| u[i] + h * t[i] + 0.5 * h * h * bend[i]);
        let plane = (t, dot5(&t, &predicted));
        let outcome = correct(
            ev,
            predicted,
            plane,
            &t,
            settings.tolerance,
            CORRECTOR_ITERATIONS,
            Some(jacobian_of(&current)),
        )?;
        let next = match outcome {
            Corrected::Point(s) if dot5(&s.tangent, &t) >= MIN_COSINE || h <= settings.min_step => {
                *s
            }
            other => {
                if h > settings.min_step {
                    h = (0.5 * h).max(settings.min_step);
                    continue;
                }
                let why = match other {
                    Corrected::Failed(why) => why,
                    Corrected::Point(_) => "the branch turns too sharply".to_owned(),
                };
                return Ok(format!(
                    "no step succeeded at {} = {}: {why}",
                    settings.parameter.info().name,
                    num(current.value())
                ));
            }
        };
        // Leaving the range: the last point lands on its edge.
        let p = next.value();
        if p < lo || p > hi {
            let edge = if p < lo { lo } else { hi };
            let last = land_on_edge(ev, &current, &next, edge, settings.tolerance)?;
            let last = match last {
                Some(s) => s,
                None => next,
            };
            let found = between(ev, &current, &last, settings)?;
            push_located(out, branch, found);
            out.points.push(BranchPoint::new(branch, last, None));
            return Ok(format!(
                "it left the range at {} = {}",
                settings.parameter.info().name,
                num(edge)
            ));
        }
        // A branch switched to at a period doubling ends where it rejoins its parent branch:
        // there P^k(s) − s (k the parent's period) passes through 0 and turns over.
        if let Some(k) = parent_period {
            let (a, b) = (half_difference(&current, k), half_difference(&next, k));
            if a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>() < 0.0 {
                return Ok(format!(
                    "it rejoins the period-{k} branch near {} = {}",
                    settings.parameter.info().name,
                    num(0.5 * (current.value() + next.value()))
                ));
            }
        }
        let found = between(ev, &current, &next, settings)?;
        push_located(out, branch, found);
        out.points
            .push(BranchPoint::new(branch, next.clone(), None));
        count += 1;
        h = match next.iterations {
            0..=5 => (1.5 * h).min(settings.max_step),
            6 => h,
            _ => (0.6 * h).max(settings.min_step),
        };
        // A closed branch: back at one of its earlier points, going the same way.
        let u1 = next.u();
        let recent = out.points.len().saturating_sub(8).max(first);
        let back = out.points[first..recent]
            .iter()
            .filter(|q| q.kind.is_none())
            .any(|q| {
                let d: Vector5 = std::array::from_fn(|i| u1[i] - q.solution.u()[i]);
                norm5(&d) < 0.25 * h && dot5(&q.solution.tangent, &next.tangent) > 0.9
            });
        if count > 10 && back {
            return Ok("it closed on itself".into());
        }
        previous = Some((current.u(), current.tangent));
        current = next;
    }
}

/// P^k(s) − s at a point of a period-2k branch: zero where it meets the period-k branch.
fn half_difference(s: &Solution, k: u32) -> [f64; 4] {
    let x = s.u();
    match s.eval.point.sections().get(k as usize - 1) {
        Some(h) => {
            let h = h.to_array();
            [h[0] - x[0], h[1] - x[1], h[2] - x[2], h[3] - x[3]]
        }
        None => [0.0; 4],
    }
}

/// Insert the bifurcations located between two points (in branch order).
fn push_located(out: &mut Continuation, branch: usize, found: Vec<Located>) {
    for l in found {
        out.bifurcations.push(out.points.len());
        out.points
            .push(BranchPoint::new(branch, l.solution, Some(l.kind)));
    }
}

/// Whether `s` lies on a branch already followed (same period): within a small distance of the
/// chord between two of its consecutive points.
fn on_known_branch(out: &Continuation, s: &Solution) -> Option<usize> {
    let u = s.u();
    let periods = s.eval.point.periods;
    out.points.windows(2).find_map(|w| {
        let (a, b) = (&w[0], &w[1]);
        if a.branch != b.branch || a.periods() != periods {
            return None;
        }
        let (ua, ub) = (a.solution.u(), b.solution.u());
        let ab: Vector5 = std::array::from_fn(|i| ub[i] - ua[i]);
        let au: Vector5 = std::array::from_fn(|i| u[i] - ua[i]);
        let len2 = dot5(&ab, &ab);
        let w = if len2 > 0.0 {
            (dot5(&au, &ab) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d: Vector5 = std::array::from_fn(|i| au[i] - w * ab[i]);
        (norm5(&d) <= 1e-3 * (1.0 + norm5(&u)) * len2.sqrt().max(1e-6)).then_some(a.branch)
    })
}

/// The whole continuation: a branch from each start (toward `settings.to`, or toward
/// `settings.from` from a start at `settings.to`; a start on a branch already followed is left
/// out), then a period-2k branch from each period doubling found (while 2k ≤
/// `settings.max_period`), except at one where a period-2k branch already followed ended (a
/// period-2k branch joins two period doublings: it is followed once).
///
/// # Errors
/// No orbit at a start, or an interrupt.
pub fn continuation(
    ev: &mut Evaluator<'_>,
    starts: &[Start],
    settings: &ContinuationSettings,
) -> Result<Continuation> {
    let mut out = Continuation {
        parameter: settings.parameter,
        points: Vec::new(),
        bifurcations: Vec::new(),
        branches: Vec::new(),
        evaluations: 0,
        skipped: Vec::new(),
    };
    for (n, start) in starts.iter().enumerate() {
        let sign = if start.value == settings.to {
            (settings.from - settings.to).signum()
        } else {
            (settings.to - start.value).signum()
        };
        ev.periods = settings.periods;
        let first = first_point(ev, start, sign, settings)?;
        if let Some(b) = on_known_branch(&out, &first) {
            out.skipped.push((n, b));
            continue;
        }
        run_branch(ev, first, None, settings, &mut out)?;
    }
    // Period doublings not yet switched at, in the order found (branches appended as we go).
    let mut done = std::collections::HashSet::new();
    let mut next = 0;
    while next < out.bifurcations.len() {
        let i = out.bifurcations[next];
        next += 1;
        let point = &out.points[i];
        let periods = point.periods();
        if point.kind != Some(Kind::PeriodDoubling)
            || 2 * periods > settings.max_period
            || done.contains(&i)
        {
            continue;
        }
        done.insert(i);
        let solution = point.solution.clone();
        ev.periods = periods;
        let Some(first) = super::locate::switch_branch(ev, &solution, settings)? else {
            continue;
        };
        ev.periods = 2 * periods;
        let end = run_branch(ev, first, Some(i), settings, &mut out)?;
        // The period doubling where it rejoined is not switched at again.
        if let Some(joined) = end {
            done.insert(joined);
        }
    }
    out.evaluations = ev.evaluations;
    Ok(out)
}

/// Follow one branch (switched to at the period doubling `parent`, if any) and record it; for a
/// switched branch that rejoins its parent branch, the period doubling of the parent branch
/// where it does (the one nearest the junction).
fn run_branch(
    ev: &mut Evaluator<'_>,
    first: Solution,
    parent: Option<usize>,
    settings: &ContinuationSettings,
    out: &mut Continuation,
) -> Result<Option<usize>> {
    let id = out.branches.len();
    let periods = ev.periods;
    let parent_period = parent.map(|_| periods / 2);
    let begin = out.points.len();
    let end = follow(ev, first, id, parent_period, settings, out)?;
    let joined = match (parent, out.points.last()) {
        (Some(p), Some(last)) if end.starts_with("it rejoins") && out.points.len() > begin => {
            let parent_branch = out.points[p].branch;
            let u = last.solution.u();
            out.bifurcations
                .iter()
                .copied()
                .filter(|&i| {
                    i != p
                        && out.points[i].branch == parent_branch
                        && out.points[i].kind == Some(Kind::PeriodDoubling)
                })
                .min_by(|&a, &b| {
                    let d = |i: usize| {
                        let v = out.points[i].solution.u();
                        norm5(&std::array::from_fn(|k| v[k] - u[k]))
                    };
                    d(a).total_cmp(&d(b))
                })
        }
        _ => None,
    };
    out.branches.push(Branch {
        id,
        periods,
        parent,
        end,
    });
    Ok(joined)
}
