//! What an embedded Runge–Kutta pair provides to the adaptive driver
//! ([`super::Integrator`]): one trial step with its error norm, and, once the step is accepted, the
//! derivative at its end and its dense output.

use core::marker::PhantomData;

use super::ode::OdeSystem;

/// Error-control tolerances: a component is within tolerance when its local error estimate is at
/// most `atol + rtol·max(|y0_i|, |y1_i|)` (Hairer's mixed absolute/relative scale, evaluated at
/// the step's start and end values). The error norm is the root mean square of the scaled
/// components and a step is accepted when the norm is ≤ 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
}

impl Tolerance {
    /// `rtol = atol = tol`, as the reference propagators use it.
    pub const fn uniform(tol: f64) -> Self {
        Tolerance {
            rtol: tol,
            atol: tol,
        }
    }

    /// The scale `atol + rtol·max(|a|, |b|)` of one component.
    #[inline]
    pub fn scale(&self, a: f64, b: f64) -> f64 {
        self.atol + self.rtol * crate::math::abs(a).max(crate::math::abs(b))
    }
}

/// Parameters of Hairer's step-size controller (with Gustafsson/Lund PI stabilisation):
/// `fac = err^alpha / err_old^beta`, `h_new = h / clamp(fac / safety, 1/fac_max, 1/fac_min)`;
/// after a rejection the step is not allowed to grow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controller {
    /// Safety factor (0.9 in DOPRI5 and DOP853).
    pub safety: f64,
    /// Smallest ratio h_new / h (0.2 in DOPRI5, 0.333 in DOP853).
    pub fac_min: f64,
    /// Largest ratio h_new / h (10 in DOPRI5, 6 in DOP853).
    pub fac_max: f64,
    /// Exponent of the current error (1/(q+1) − 0.75·beta in DOPRI5, 1/8 − 0.2·beta in DOP853).
    pub alpha: f64,
    /// Exponent of the previous accepted error (0.04 in DOPRI5, 0 in DOP853: PI stabilisation
    /// off).
    pub beta: f64,
}

/// A continuous extension of one step: the state at any time of `[start, end]`.
pub trait Interpolant<const N: usize> {
    /// The step's start time.
    fn start(&self) -> f64;
    /// The step's end time.
    fn end(&self) -> f64;
    /// The interpolated state at `t` (meant for `t` in `[start, end]`; extrapolates outside).
    fn eval(&self, t: f64) -> [f64; N];
}

/// A scheme's continuous extension as a polynomial in s = (t − t0)/h with `R` vector
/// coefficients (the scheme's own form, e.g. Hairer's `CONTD8`).
pub trait DenseForm<const N: usize, const R: usize> {
    /// The polynomial's value at `s`.
    fn at(r: &[[f64; N]; R], s: f64) -> [f64; N];
}

/// Dense output of one step of scheme `F`: its polynomial's coefficients on `[t0, t0 + h]`.
#[derive(Debug, PartialEq)]
pub struct Dense<const N: usize, const R: usize, F> {
    pub(super) t0: f64,
    pub(super) h: f64,
    pub(super) r: [[f64; N]; R],
    pub(super) form: PhantomData<F>,
}

// Derived Clone/Copy would ask F (a marker) to be Copy as well.
impl<const N: usize, const R: usize, F> Clone for Dense<N, R, F> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<const N: usize, const R: usize, F> Copy for Dense<N, R, F> {}

impl<const N: usize, const R: usize, F: DenseForm<N, R>> Interpolant<N> for Dense<N, R, F> {
    fn start(&self) -> f64 {
        self.t0
    }

    fn end(&self) -> f64 {
        self.t0 + self.h
    }

    fn eval(&self, t: f64) -> [f64; N] {
        if self.h == 0.0 {
            return self.r[0];
        }
        F::at(&self.r, (t - self.t0) / self.h)
    }
}

/// The dense output of a step from a later start (the search after a touch).
pub(crate) struct After<'a, D> {
    pub(crate) dense: &'a D,
    pub(crate) start: f64,
}

impl<const N: usize, D: Interpolant<N>> Interpolant<N> for After<'_, D> {
    fn start(&self) -> f64 {
        self.start
    }
    fn end(&self) -> f64 {
        self.dense.end()
    }
    fn eval(&self, t: f64) -> [f64; N] {
        self.dense.eval(t)
    }
}

/// Where a trial step starts: `(t, y)` with `f0 = f(t, y)`, its size `h` and the tolerances its
/// error is measured in.
#[derive(Clone, Copy, Debug)]
pub struct StepStart<'a, const N: usize> {
    /// The start time.
    pub t: f64,
    /// The state there.
    pub y: &'a [f64; N],
    /// f(t, y).
    pub f0: &'a [f64; N],
    /// The step size.
    pub h: f64,
    /// The error control.
    pub tol: &'a Tolerance,
}

/// One trial step: the new state, the scaled error norm (accept when ≤ 1; may be `inf` or NaN
/// when the stages overflowed) and the stage derivatives the dense output needs.
#[derive(Clone, Copy, Debug)]
pub struct Attempt<const N: usize, K> {
    /// The propagated solution at t + h.
    pub y1: [f64; N],
    /// The scaled error norm.
    pub err: f64,
    /// Stage derivatives, kept for [`Scheme::accept`].
    pub stages: K,
}

/// An embedded explicit Runge–Kutta pair with a continuous extension.
pub trait Scheme<const N: usize> {
    /// Stage derivatives kept from an attempt.
    type Stages: Copy + core::fmt::Debug;
    /// The dense output of an accepted step.
    type Dense: Interpolant<N> + Copy + core::fmt::Debug;
    /// Order of the propagated solution (used by the initial step-size guess).
    const ORDER: i32;
    /// The default step-size controller.
    const CONTROLLER: Controller;
    /// Right-hand-side evaluations of one [`Scheme::attempt`].
    const STAGE_EVALUATIONS: u64;
    /// Right-hand-side evaluations of one [`Scheme::accept`].
    const ACCEPT_EVALUATIONS: u64;

    /// One step of size `from.h` from `(from.t, from.y)` with `from.f0 = f(t, y)`. Never panics;
    /// `h = 0` returns `y`.
    fn attempt<S: OdeSystem<N> + ?Sized>(
        sys: &S,
        from: StepStart<'_, N>,
    ) -> Attempt<N, Self::Stages>;

    /// Complete an accepted attempt: `f(t + h, y1)` (the next step's first stage) and the dense
    /// output on `[t, t + h]`.
    fn accept<S: OdeSystem<N> + ?Sized>(
        sys: &S,
        from: StepStart<'_, N>,
        attempt: &Attempt<N, Self::Stages>,
    ) -> ([f64; N], Self::Dense);
}

/// `y + h·Σ_j row_j·k_j` (the input of a stage), pairing `row` with the first stages of `k`.
///
/// The row is a fixed-size array so that, inlined with a constant tableau row, the loop unrolls
/// and the zero coefficients drop out at compile time (same sums, same order, same bits).
#[inline(always)]
pub(crate) fn stage_input<const N: usize, const M: usize>(
    y: &[f64; N],
    h: f64,
    row: &[f64; M],
    k: &[[f64; N]],
) -> [f64; N] {
    combine(y, h, row, k)
}

/// `Σ_j row_j·k_j`.
#[inline(always)]
pub(crate) fn weighted<const N: usize, const M: usize>(row: &[f64; M], k: &[[f64; N]]) -> [f64; N] {
    combine(&[0.0; N], 1.0, row, k)
}

/// [`stage_input`] for a row of run-time length (DOPRI5's loop over its stages measured
/// slightly faster this way than unrolled).
#[inline]
pub(crate) fn stage_input_slice<const N: usize>(
    y: &[f64; N],
    h: f64,
    row: &[f64],
    k: &[[f64; N]],
) -> [f64; N] {
    combine(y, h, row, k)
}

/// [`weighted`] for a row of run-time length.
#[inline]
pub(crate) fn weighted_slice<const N: usize>(row: &[f64], k: &[[f64; N]]) -> [f64; N] {
    combine(&[0.0; N], 1.0, row, k)
}

/// `y + h·Σ_j row_j·k_j`, the sums in stage order (zero coefficients skipped); inlined into its
/// callers, so a constant row's length and zeros are known where it is one.
#[inline(always)]
fn combine<const N: usize>(y: &[f64; N], h: f64, row: &[f64], k: &[[f64; N]]) -> [f64; N] {
    let mut acc = [0.0; N];
    for (c, kj) in row.iter().zip(k.iter()) {
        if *c != 0.0 {
            for (a, v) in acc.iter_mut().zip(kj.iter()) {
                *a += c * v;
            }
        }
    }
    let mut out = *y;
    for (o, a) in out.iter_mut().zip(acc.iter()) {
        *o += h * a;
    }
    out
}
