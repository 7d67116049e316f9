//! The small ODE interface the integrators are generic over, and the fixed-size vector helpers
//! they share.
//!
//! A system is anything that evaluates y' = f(t, y) on a fixed-size state `[f64; N]`: the
//! reference propagators use the 4-state rotor field ([`super::RotorSystem`]); the hybrid method
//! can run the same integrators on a 6-state system (rotor state plus the rotating forcing phasor,
//! [`super::PhasorRotorSystem`]) or on any closure `Fn(f64, &[f64; N]) -> [f64; N]`.

/// An explicit first-order system y' = f(t, y) with `N` states.
///
/// Implementations must not panic on finite input; non-finite output is allowed (the step is then
/// rejected and, if that persists, reported as a step-size underflow).
pub trait OdeSystem<const N: usize> {
    /// The right-hand side f(t, y).
    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N];

    /// The number of states the system uses (≤ N): the error norm is the root mean square over
    /// this many components. A system whose size is a runtime property (a matrix model of 2n
    /// states in storage of N ≥ 2n, `crate::matrix`) keeps its unused entries at 0 and says how
    /// many it uses, so that its tolerance means what it means for 2n states.
    #[inline(always)]
    fn dimension(&self) -> usize {
        N
    }
}

impl<const N: usize, F> OdeSystem<N> for F
where
    F: Fn(f64, &[f64; N]) -> [f64; N],
{
    #[inline]
    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N] {
        self(t, y)
    }
}

/// `Σ_j c_j·v_j` over the given (coefficient, vector) pairs.
#[inline]
pub(crate) fn lin<const N: usize>(terms: &[(f64, &[f64; N])]) -> [f64; N] {
    let mut acc = [0.0; N];
    for (c, v) in terms {
        for (a, x) in acc.iter_mut().zip(v.iter()) {
            *a += c * x;
        }
    }
    acc
}

/// Whether every component is finite.
#[inline]
pub(crate) fn all_finite<const N: usize>(y: &[f64; N]) -> bool {
    y.iter().all(|v| v.is_finite())
}
