//! The forced basis of resonance-stable free flight (`docs/MODEL.md` §11): the zero-state
//! response of the free oscillator to harmonic forcing, written with divided differences of exp so
//! that nothing cancels as the forcing approaches the natural frequency.
//!
//! The free oscillator q'' + 2νq' + q has the roots λ± = −ν ± iβ (β² = 1 − ν² > 0 here) and the
//! impulse response g = (e^{λ+s} − e^{λ−s})/(2iβ), the ES of [`super::basis::free_basis`]. Its
//! zero-state response to e^{iηs} is
//!
//! ```text
//! K(s) = ∫₀ˢ g(s − σ) e^{iησ} dσ = (D+(s) − D−(s))/(2iβ),
//! D±(s) = ∫₀ˢ e^{λ±(s−σ)} e^{iησ} dσ = (e^{iηs} − e^{λ±s})/δ±,   δ± = iη − λ± = ν + i(η ∓ β),
//! ```
//!
//! so FC = Re K and FS = Im K answer cos ηs and sin ηs, with FC(0) = FC'(0) = 0, and
//! K' = (λ+D+ − λ−D−)/(2iβ). Near resonance δ+ → 0 and the quotient defining D+ is 0/0: it is
//! evaluated as D+ = e^{λ+s}·(e^{δ+s} − 1)/δ+ with a complex expm1 (no cancellation at all, and
//! D+ = s·e^{λ+s} at δ+ = 0, the secular growth of exact resonance). |δ−| ≥ η + β stays large.
//!
//! # Bounds
//! Re λ± = −ν, so |D±(s)| ≤ ∫₀ˢ e^{−ν(s−σ)} dσ = (1 − e^{−νs})/ν ≤ min(s, 1/ν), and from the
//! quotient |D±(s)| ≤ (1 + e^{−νs})/|δ±| ≤ 2/|δ±|; all three grow with s, so their least value at
//! `hi` bounds |D±| on [0, hi]. With |λ±| = 1, |K| and |K'| are both at most
//! κ = (max|D+| + max|D−|)/(2β), and K'' = (λ+²D+ − λ−²D−)/(2iβ) + e^{iηs} gives |K''| ≤ κ + 1.

use crate::coefficients::ForcedBasis;
use crate::math;

/// The forced basis is used where |δ+|·|δ−| = |1 − η² + 2iνη| (the distance of the forcing from
/// resonance) is below this: there the steady-state form's particular amplitude F/|δ+δ−| exceeds
/// 2F and its cancellation against the homogeneous part costs more than a bit.
pub const RESONANT_BAND: f64 = 0.5;

/// Relative margin that keeps the rounded bounds upper bounds.
const MARGIN: f64 = 1.0 + 1e-12;

/// A complex number as (re, im).
type C = (f64, f64);

fn mul(a: C, b: C) -> C {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn div(a: C, b: C) -> C {
    let d = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
}

/// e^z − 1 without cancellation: expm1(a)·cos b − 2 sin²(b/2) + i e^a sin b, z = a + ib.
fn expm1c(z: C) -> C {
    let (sh, ch) = math::sin_cos(0.5 * z.1);
    let m = math::expm1(z.0);
    let two_sh2 = 2.0 * sh * sh;
    (m * (1.0 - two_sh2) - two_sh2, (1.0 + m) * 2.0 * sh * ch)
}

/// The per-parameter-set constants of the forced basis: the roots and their distances δ± from
/// the forcing frequency.
#[derive(Clone, Copy, Debug)]
pub struct Resonance {
    nu: f64,
    beta: f64,
    delta_plus: C,
    delta_minus: C,
    /// 2/|δ+| and 2/|δ−| (infinite at exact resonance).
    reach_plus: f64,
    reach_minus: f64,
}

impl Resonance {
    /// The forced basis for damping `nu`, β² = `beta_sq` and forcing frequency `eta`, when the
    /// forcing lies within [`RESONANT_BAND`] of resonance (`None` elsewhere: the steady-state form
    /// is accurate there).
    #[inline]
    pub fn near(nu: f64, beta_sq: f64, eta: f64) -> Option<Self> {
        // β² > 0 (NaN excluded): the band lies well inside the under-damped range.
        if beta_sq.is_nan() || beta_sq <= 0.0 {
            return None;
        }
        // Far from resonance without a root: |δ+||δ−| ≥ |η − β||η + β| = |η² − β²|, and the
        // computed distance (two faithful `hypot`s and a product) is within 3ε of it below; a
        // gap beyond the band by 8ε of the terms' size decides as the distance would.
        let (eta_sq, gap) = (eta * eta, eta * eta - beta_sq);
        if math::abs(gap) >= RESONANT_BAND + 8.0 * f64::EPSILON * (eta_sq + beta_sq) {
            return None;
        }
        Self::within_band(nu, beta_sq, eta)
    }

    /// [`Self::near`] past its quick rejections (out of line: the common case, far from
    /// resonance, stays in the caller's registers).
    #[inline(never)]
    fn within_band(nu: f64, beta_sq: f64, eta: f64) -> Option<Self> {
        let beta = math::sqrt(beta_sq);
        let delta_plus = (nu, eta - beta);
        let delta_minus = (nu, eta + beta);
        let (a, b) = (
            math::hypot(delta_plus.0, delta_plus.1),
            math::hypot(nu, eta + beta),
        );
        let distance = a * b;
        if distance.is_nan() || distance >= RESONANT_BAND {
            return None;
        }
        Some(Resonance {
            nu,
            beta,
            delta_plus,
            delta_minus,
            reach_plus: 2.0 / a,
            reach_minus: 2.0 / b,
        })
    }

    /// FC, FS, FC', FS' at local time `s` ≥ 0, given the free basis (EC, ES) at `s` and
    /// (cos ηs, sin ηs).
    pub fn basis(&self, s: f64, ec: f64, es: f64, forcing: C) -> ForcedBasis {
        let (nu, beta) = (self.nu, self.beta);
        let e_plus = (ec, beta * es);
        let e_minus = (ec, -beta * es);
        let d_plus = if nu * s <= 1.0 {
            // Divided difference e^{λ+s}·(e^{δs} − 1)/δ: exact 0/0 limit s·e^{λ+s}.
            let dd = if self.delta_plus == (0.0, 0.0) {
                (s, 0.0)
            } else {
                let z = (self.delta_plus.0 * s, self.delta_plus.1 * s);
                div(expm1c(z), self.delta_plus)
            };
            mul(e_plus, dd)
        } else {
            // |e^{δs}| ≥ e: the plain quotient has no cancellation.
            div(
                (forcing.0 - e_plus.0, forcing.1 - e_plus.1),
                self.delta_plus,
            )
        };
        let d_minus = div(
            (forcing.0 - e_minus.0, forcing.1 - e_minus.1),
            self.delta_minus,
        );
        // (a + ib)/(2iβ) = (b − ia)/(2β).
        let half = 0.5 / beta;
        let k = (d_plus.0 - d_minus.0, d_plus.1 - d_minus.1);
        let lp = mul((-nu, beta), d_plus);
        let lm = mul((-nu, -beta), d_minus);
        let dk = (lp.0 - lm.0, lp.1 - lm.1);
        ForcedBasis {
            fc: k.1 * half,
            fs: -k.0 * half,
            dfc: dk.1 * half,
            dfs: -dk.0 * half,
        }
    }

    /// κ ≥ max(|K|, |K'|) on s ∈ [0, hi] (`hi` may be infinite); |K''| ≤ κ + 1 (module docs).
    pub fn bound(&self, hi: f64) -> f64 {
        let slow = if self.nu > 0.0 {
            hi.min(1.0 / self.nu)
        } else {
            hi
        };
        let m_plus = slow.min(self.reach_plus);
        let m_minus = slow.min(self.reach_minus);
        (m_plus + m_minus) * (0.5 / self.beta) * MARGIN
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The shortcut far from resonance decides as the distance |δ+||δ−| itself does, near
        /// the band's edges included.
        #[test]
        fn the_band_is_decided_by_the_distance(
            nu in 0.0f64..0.99,
            eta in 1e-3f64..3.0,
            edge in prop::bool::ANY,
        ) {
            let beta_sq = 1.0 - nu * nu;
            let beta = math::sqrt(beta_sq);
            // Half the cases put η where η² − β² is at the band's edge (±0.5).
            let eta = if edge { math::sqrt((beta_sq + RESONANT_BAND).max(0.0)) + (eta - 1.5) * 1e-9 } else { eta };
            let distance = math::hypot(nu, eta - beta) * math::hypot(nu, eta + beta);
            prop_assert_eq!(Resonance::near(nu, beta_sq, eta).is_some(), distance < RESONANT_BAND);
        }
    }
}
