//! The corrector: Newton's method on R(u) = 0 with one linear constraint c·u = b (the
//! pseudo-arclength hyperplane, or a fixed parameter value), and the branch points it gives.

use rotor_rub::linalg::Complex;
use rotor_rub::orbit::{Mat4, eigenvalues_of};

use super::evaluate::{Evaluation, Evaluator, Vector5, bordered, solve5, state_norm, tangent};
use crate::error::{CliError, Result};
use crate::watch::EXIT_INTERRUPTED;

/// A converged point of a branch: its evaluation (monodromy, ∂R/∂p, extrema), multipliers and
/// tangent.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The evaluation at the point.
    pub eval: Evaluation,
    /// The Floquet multipliers, largest modulus first.
    pub multipliers: [Complex; 4],
    /// The unit tangent of the branch, in the direction of travel.
    pub tangent: Vector5,
    /// Newton iterations it took.
    pub iterations: u32,
}

impl Solution {
    /// The point (s, p).
    pub fn u(&self) -> Vector5 {
        self.eval.u
    }

    /// The parameter value.
    pub fn value(&self) -> f64 {
        self.eval.u[4]
    }

    /// Every multiplier inside the unit circle.
    pub fn stable(&self) -> bool {
        self.multipliers.iter().all(|m| m.abs() < 1.0)
    }

    /// ∏(λ − a) over the multipliers (real: they come in conjugate pairs): det(M − aI).
    pub fn characteristic(&self, a: f64) -> f64 {
        self.multipliers
            .iter()
            .fold(Complex::ONE, |acc, m| acc * (*m - Complex::real(a)))
            .re
    }

    /// ∏_{i<j}(λ_i λ_j − 1): zero where two multipliers multiply to 1 (a complex pair on the
    /// unit circle: Neimark–Sacker; or a real pair λ, 1/λ: a neutral saddle, no bifurcation).
    pub fn pair_product(&self) -> f64 {
        let m = &self.multipliers;
        let mut acc = Complex::ONE;
        for i in 0..4 {
            for j in i + 1..4 {
                acc *= m[i] * m[j] - Complex::ONE;
            }
        }
        acc.re
    }
}

/// How a corrector ends.
pub enum Corrected {
    /// Converged.
    Point(Box<Solution>),
    /// Failed: the reason, for the message if the branch ends here.
    Failed(String),
}

/// Whether an error ends the continuation (an interrupt) rather than one corrector.
fn fatal(e: &CliError) -> bool {
    e.code == EXIT_INTERRUPTED || e.code == crate::error::EXIT_PIPE
}

/// The converged point at `u`: its full evaluation (monodromy, ∂R/∂p, extrema), multipliers and
/// tangent (oriented along `direction`); `iterations` is reported with it.
fn finish(
    ev: &mut Evaluator<'_>,
    u: Vector5,
    direction: &Vector5,
    iterations: u32,
    done: Option<Evaluation>,
) -> Result<Corrected> {
    let e = match done {
        Some(e) => e,
        None => match ev.evaluate(u, true, true, true) {
            Ok(e) => e,
            Err(e) if fatal(&e) => return Err(e),
            Err(e) => return Ok(Corrected::Failed(e.message)),
        },
    };
    let dp = e.dp.unwrap_or([0.0; 4]);
    let multipliers = match eigenvalues_of(&e.point.monodromy) {
        Ok(m) => m,
        Err(err) => return Ok(Corrected::Failed(err.to_string())),
    };
    let Some(t) = tangent(&e.point.monodromy, &dp, direction) else {
        return Ok(Corrected::Failed(
            "the branch's tangent is undefined here".into(),
        ));
    };
    Ok(Corrected::Point(Box::new(Solution {
        eval: e,
        multipliers,
        tangent: t,
        iterations,
    })))
}

/// Whether the residual `r` at `u` and the constraint's `g` are within the tolerance.
fn converged(r: &[f64; 4], g: f64, u: &Vector5, tolerance: f64) -> bool {
    let size = r.iter().fold(0.0, |a: f64, v| a.max(v.abs()));
    size <= tolerance * (1.0 + state_norm(u)) && g.abs() <= 1e-12 * (1.0 + u[4].abs())
}

/// The constraint's value c·u − b.
fn constraint_value((c, b): &(Vector5, f64), u: &Vector5) -> f64 {
    c.iter().zip(u).map(|(x, y)| x * y).sum::<f64>() - b
}

/// The corrector from `guess` on R(u) = 0, c·u = b (`constraint` = (c, b)), until
/// |R|∞ ≤ `tolerance`·(1 + |s|∞) and the constraint holds; the tangent oriented along
/// `direction`. With `jacobian` (the monodromy and ∂R/∂p of a nearby point: the previous point
/// of the branch) it first runs the chord method on it (each iteration one map without the
/// variational equations); where that stalls, and without it, Newton's method, each iteration
/// with the monodromy at the iterate. At most `max_iterations` iterations of each.
///
/// # Errors
/// Only an interrupt (the watch's stop) or a closed pipe; every other failure is
/// [`Corrected::Failed`].
pub fn correct(
    ev: &mut Evaluator<'_>,
    guess: Vector5,
    constraint: (Vector5, f64),
    direction: &Vector5,
    tolerance: f64,
    max_iterations: u32,
    jacobian: Option<(&Mat4, &[f64; 4])>,
) -> Result<Corrected> {
    let mut u = guess;
    let mut spent = 0;
    if let Some((m, dp)) = jacobian {
        let a = bordered(m, dp, &constraint.0);
        let mut last = f64::INFINITY;
        for _ in 0..max_iterations {
            spent += 1;
            let e = match ev.evaluate(u, false, false, false) {
                Ok(e) => e,
                Err(e) if fatal(&e) => return Err(e),
                Err(_) => break,
            };
            let g = constraint_value(&constraint, &u);
            if converged(&e.residual, g, &u, tolerance) {
                return finish(ev, u, direction, spent, None);
            }
            let size = e.residual.iter().fold(0.0, |acc: f64, v| acc.max(v.abs()));
            if size > 0.3 * last {
                break;
            }
            last = size;
            let r = e.residual;
            let Some(delta) = solve5(&a, [-r[0], -r[1], -r[2], -r[3], -g]) else {
                break;
            };
            for (ui, di) in u.iter_mut().zip(delta) {
                *ui += di;
            }
        }
        u = guess;
    }
    newton(
        ev,
        u,
        &constraint,
        direction,
        tolerance,
        max_iterations,
        spent,
    )
}

/// Newton's method for [`correct`], `spent` iterations already made.
fn newton(
    ev: &mut Evaluator<'_>,
    guess: Vector5,
    constraint: &(Vector5, f64),
    direction: &Vector5,
    tolerance: f64,
    max_iterations: u32,
    spent: u32,
) -> Result<Corrected> {
    let mut u = guess;
    let mut last = f64::INFINITY;
    for k in 1..=max_iterations {
        let e = match ev.evaluate(u, true, true, true) {
            Ok(e) => e,
            Err(e) if fatal(&e) => return Err(e),
            Err(e) => return Ok(Corrected::Failed(e.message)),
        };
        let r = e.residual;
        let g = constraint_value(constraint, &u);
        if converged(&r, g, &u, tolerance) {
            return finish(ev, u, direction, spent + k, Some(e));
        }
        let size = r.iter().fold(0.0, |a: f64, v| a.max(v.abs()));
        // Diverging: the guess is outside Newton's basin.
        if k > 2 && size > 2.0 * last {
            return Ok(Corrected::Failed(format!(
                "Newton's residual grew to {size:e}"
            )));
        }
        last = size;
        let dp = e.dp.unwrap_or([0.0; 4]);
        let a = bordered(&e.point.monodromy, &dp, &constraint.0);
        let Some(delta) = solve5(&a, [-r[0], -r[1], -r[2], -r[3], -g]) else {
            return Ok(Corrected::Failed(
                "the corrector's matrix is singular".into(),
            ));
        };
        for (ui, di) in u.iter_mut().zip(delta) {
            *ui += di;
        }
    }
    Ok(Corrected::Failed(format!(
        "Newton's method did not converge in {max_iterations} iterations (residual {last:e})"
    )))
}
