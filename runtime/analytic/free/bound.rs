//! The one free-flight bound (module docs of [`super`]): bounds of the basis functions on an
//! interval ([`BasisBound`]) and a segment's amplitudes ([`FreeReach`]), combined into bounds of
//! |r − ε|, |r'| and |r''|; the singular value σ(M) of the harmonic part
//! ([`harmonic_amplitude`]).

use super::super::segment::Bounds;
use super::FreeConstants;
use crate::math;

/// The largest |(c11 cos θ + c22 sin θ, c33 cos θ + c44 sin θ)| over θ: the largest singular
/// value σ1 of [[c11, c22], [c33, c44]], with a relative margin for rounding, never above the
/// Frobenius norm √S (S the sum of squares).
///
/// σ1 ± σ2 = √(S ± 2|det|) (σ1² + σ2² = S, σ1σ2 = |det|), and S ± 2det are the sums of squares
/// (c11 ± c44)² + (c22 ∓ c33)², so σ1 is the mean of their two roots, in either order. Sums of
/// squares round to a few ulps relative, so the 1e-12 margin holds; the form σ1² = (S + √(S² −
/// 4det²))/2 loses up to √ε relative near a circular response (S² ≈ 4det²), where the margin
/// did not cover it. The two roots are independent: one square-root latency on the
/// parameter-change path.
pub(crate) fn harmonic_amplitude(c11: f64, c22: f64, c33: f64, c44: f64) -> f64 {
    let sum = c11 * c11 + c22 * c22 + c33 * c33 + c44 * c44;
    let (p, q) = (c11 + c44, c22 - c33);
    let (r, t) = (c11 - c44, c22 + c33);
    let sigma = 0.5 * (math::sqrt(p * p + q * q) + math::sqrt(r * r + t * t));
    (sigma * (1.0 + 1e-12)).min(math::sqrt(sum))
}

/// √(x² + y²) with one rounded root, where libm's `hypot` (four times the instructions) guards
/// against overflow and keeps extra precision. For the stepper's per-step free-flight bound,
/// which only decides whether a step is provably free: its rounding (a few ulps of the bound)
/// moves that decision only when the two-parabola test's margin is at rounding level, and an
/// overflowing square gives an infinite bound, which sends the step to the exact path.
#[inline]
pub(crate) fn plain_norm(x: f64, y: f64) -> f64 {
    math::sqrt(x * x + y * y)
}

/// Bounds of the scalar basis functions and their derivatives on one interval.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BasisBound {
    /// max |EC|, |ES|, |EC'|, |ES'|, |EC''|, |ES''|.
    e: [f64; 6],
    /// κ ≥ max(|FC + iFS|, |FC' + iFS'|) (forced form only).
    kappa: f64,
    eta: f64,
}

impl BasisBound {
    /// The bounds on s ∈ [lo, hi] (`hi` may be infinite).
    pub(crate) fn on(constants: &FreeConstants, lo: f64, hi: f64) -> Self {
        let (nu, b2) = (
            constants.model.damping_ratio,
            math::abs(constants.beta_sq()),
        );
        let (ec, es) = constants.rates.bound(lo, hi);
        // EC' = −νEC − β²ES, ES' = EC − νES, applied twice, bounded term by term.
        let (dec, des) = (nu * ec + b2 * es, ec + nu * es);
        let (ddec, ddes) = (nu * dec + b2 * des, dec + nu * des);
        BasisBound {
            e: [ec, es, dec, des, ddec, ddes],
            kappa: 0.0,
            eta: 0.0,
        }
        .with_forcing(constants, hi)
    }

    /// These bounds (on [lo, `hi`]) for `constants` with the same ν and β²: the basis bounds
    /// depend on those only, the forcing's parts (η, the forced basis) are taken anew — what
    /// [`Self::on`] gives for `constants`.
    pub(crate) fn with_forcing(self, constants: &FreeConstants, hi: f64) -> Self {
        BasisBound {
            kappa: constants.resonance.map_or(0.0, |r| r.bound(hi)),
            eta: constants.model.speed_ratio,
            ..self
        }
    }
}

/// |X|, |P| and σ(M) of one form (module docs).
#[derive(Clone, Copy, Debug)]
pub(super) struct Amplitudes {
    pub(super) pos: f64,
    pub(super) vel: f64,
    pub(super) drive: f64,
}

impl Amplitudes {
    /// Radius, speed and acceleration bounds for drive-function bounds `b` (value, first and
    /// second derivative).
    fn bounds(&self, e: &[f64; 6], b: [f64; 3], off: f64) -> Bounds {
        let [ec, es, dec, des, ddec, ddes] = *e;
        Bounds {
            radius: self.pos * ec + self.vel * es + self.drive * b[0] + off,
            speed: self.pos * dec + self.vel * des + self.drive * b[1],
            accel: self.pos * ddec + self.vel * ddes + self.drive * b[2],
        }
    }
}

/// The amplitudes of one free segment that [`FreeReach::bounds`] combines with interval bounds of
/// the basis: the one free-flight bound (module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FreeReach {
    pub(super) steady: Option<Amplitudes>,
    pub(super) forced: Option<Amplitudes>,
    pub(super) off: f64,
}

impl FreeReach {
    /// Bounds on the interval `basis` was computed for.
    #[inline]
    pub(crate) fn bounds(&self, basis: &BasisBound) -> Bounds {
        let eta = basis.eta;
        let steady = self
            .steady
            .map(|a| a.bounds(&basis.e, [1.0, eta, eta * eta], self.off));
        let forced = self.forced.map(|a| {
            let k = basis.kappa;
            a.bounds(&basis.e, [k, k, k + 1.0], self.off)
        });
        match (steady, forced) {
            (Some(s), Some(f)) => Bounds {
                radius: s.radius.min(f.radius),
                speed: s.speed.min(f.speed),
                accel: s.accel.min(f.accel),
            },
            (Some(b), None) | (None, Some(b)) => b,
            (None, None) => Bounds {
                radius: f64::INFINITY,
                speed: f64::INFINITY,
                accel: f64::INFINITY,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::harmonic_amplitude;
    use nalgebra::Matrix2;
    use proptest::prelude::*;

    /// σ1 by nalgebra's singular value decomposition (an independent computation).
    fn reference(c: [f64; 4]) -> f64 {
        Matrix2::new(c[0], c[1], c[2], c[3]).singular_values().max()
    }

    fn check(c: [f64; 4]) -> Result<(), TestCaseError> {
        let (sigma, exact) = (harmonic_amplitude(c[0], c[1], c[2], c[3]), reference(c));
        // An upper bound by the margin, never loose by more than it (and the rounding).
        prop_assert!(sigma >= exact, "{c:?}: {sigma:e} below σ1 = {exact:e}");
        prop_assert!(
            sigma <= exact * (1.0 + 2e-12),
            "{c:?}: {sigma:e} against σ1 = {exact:e}"
        );
        Ok(())
    }

    proptest! {
        #[test]
        fn the_amplitude_bounds_the_largest_singular_value(
            c in prop::array::uniform4(-10.0f64..10.0),
        ) {
            check(c)?;
        }

        /// Near a circular response (c44 ≈ c11, c33 ≈ −c22: σ1 ≈ σ2), where a root of
        /// S² − 4det² loses √ε relative.
        #[test]
        fn the_amplitude_holds_near_a_circular_response(
            a in -10.0f64..10.0,
            b in -10.0f64..10.0,
            e in prop::array::uniform4(-1e-7f64..1e-7),
        ) {
            check([a + e[0], b + e[1], -b + e[2], a + e[3]])?;
        }
    }
}
