//! The step an expansion allows (Jorba–Zou, `docs/MODEL.md` §16), with the logarithms and the
//! power it takes computed to about 2e-5 instead of to the last bit.
//!
//! The step rule is an estimate of the radius of convergence from two coefficients, scaled by a
//! safety factor e^{−2}: a relative error δ in the step changes the step's truncation error by
//! about p·δ, so 2e-5 (0.03 % of the truncation error at p = 16) is far below anything the rule
//! itself can tell apart, and libm's correctly rounded `ln` and `exp` buy nothing here. They
//! cost: the step is on the chain from one expansion to the next (the next one starts from the
//! state at its end), and libm's three logarithms, two divisions and an exponential were a
//! seventh of a step's time. Both approximations below are short polynomials on the double's
//! bits, without a division: the same on every target, like the rest of the runtime.

use super::kernels::{self, Series};
use crate::math;

/// ln 2.
const LN_2: f64 = core::f64::consts::LN_2;

/// The Jorba–Zou step for expansions of one order p: ρ = min over n ∈ {p − 1, p} of
/// (max(1, ‖x₀‖∞)/‖xₙ‖∞)^{1/n} over the six states estimates the radius of convergence, and
/// h = ρ e^{−2 − 0.7/(p−1)} (heyoka's safety factors).
#[derive(Clone, Copy, Debug)]
pub struct StepRule {
    order: usize,
    /// 1/(p − 1) and 1/p.
    inverse: (f64, f64),
    /// (2 + 0.7/(p − 1))/ln 2: log₂ of the safety factor.
    shrink: f64,
}

impl StepRule {
    /// The rule for expansions of order `order` (≥ 2).
    pub fn new(order: usize) -> Self {
        let p = order.max(2) as f64;
        StepRule {
            order: order.max(2),
            inverse: (1.0 / (p - 1.0), 1.0 / p),
            shrink: (2.0 + 0.7 / (p - 1.0)) * core::f64::consts::LOG2_E,
        }
    }

    /// The step for the series `s` (states first).
    pub fn step(&self, s: &Series) -> f64 {
        let p = self.order;
        // ‖x₀‖∞, ‖x_{p−1}‖∞, ‖x_p‖∞ over the six states in one pass.
        let (mut reference, mut before_last, mut last) = (1.0, 0.0, 0.0);
        for c in s.iter().take(6) {
            let at = |n: usize| math::abs(kernels::at(c, n));
            let (v0, v1, v2) = (at(0), at(p - 1), at(p));
            if v0 > reference {
                reference = v0;
            }
            if v1 > before_last {
                before_last = v1;
            }
            if v2 > last {
                last = v2;
            }
        }
        let log_reference = log2(reference);
        // log₂ ρₙ = (log₂ ref − log₂ ‖xₙ‖)/n (+∞ for a vanishing order).
        let log_radius = |v: f64, inverse: f64| {
            if v > 0.0 {
                (log_reference - log2(v)) * inverse
            } else {
                f64::INFINITY
            }
        };
        let log_rho = log_radius(before_last, self.inverse.0).min(log_radius(last, self.inverse.1));
        exp2(log_rho - self.shrink)
    }
}

/// log₂ x for a positive normal x, to 2e-5: the exponent, plus log₂ m of the mantissa
/// m ∈ [1, 2) by a quintic in m − 1 (least squares on 200 Chebyshev nodes of [0, 1], largest
/// error 1.7e-5). Anything else goes to [`math::ln`].
#[inline]
fn log2(x: f64) -> f64 {
    if !x.is_normal() || x < 0.0 {
        return math::ln(x) * core::f64::consts::LOG2_E;
    }
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let t = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000) - 1.0;
    let t2 = t * t;
    let mantissa = t
        * ((1.441_879_895_806_464 - 0.708_865_217_733_881_2 * t)
            + t2 * ((0.415_245_560_389_367_4 - 0.193_516_524_605_571_03 * t)
                + t2 * 0.045_268_292_603_906_42));
    exponent as f64 + mantissa
}

/// 2^x to 4e-6 relative for |x| ≤ 1000: 2^⌊x⌋ in the exponent bits times 2^f of the fraction
/// f ∈ [0, 1) by a quartic (least squares on 200 Chebyshev nodes of [0, 1], largest error
/// 3.8e-6). Beyond ±1000 (and for NaN) [`math::exp`].
#[inline]
fn exp2(x: f64) -> f64 {
    if math::abs(x) > 1000.0 || x.is_nan() {
        return math::exp(x * LN_2);
    }
    // ⌊x⌋: x + 1.5·2⁵² rounds to the nearest integer; one less where that is above x.
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let mut k = (x + ROUND) - ROUND;
    if k > x {
        k -= 1.0;
    }
    let f = x - k;
    let f2 = f * f;
    let fraction = (1.000_003_597_144_562_9 + 0.692_969_550_931_913_4 * f)
        + f2 * ((0.241_621_322_662_929_27 + 0.051_717_735_460_198_214 * f)
            + f2 * 0.013_683_982_893_834_564);
    fraction * f64::from_bits(((k as i64 + 1023) as u64) << 52)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn logarithm_and_exponential_to_the_accuracy_stated() {
        let mut x = 1e-300;
        while x < 1e300 {
            for y in [x, x * 1.37, x * 1.9999] {
                let (got, want) = (log2(y), libm::log2(y));
                assert!((got - want).abs() <= 2e-5, "log2 {y}: {got} vs {want}");
            }
            x *= 7.3;
        }
        let mut x = -1000.0;
        while x <= 1000.0 {
            let (got, want) = (exp2(x), libm::exp2(x));
            assert!(
                (got - want).abs() <= 4e-6 * want,
                "exp2 {x}: {got} vs {want}"
            );
            x += 0.0173;
        }
        assert!(exp2(1100.0).is_infinite() && exp2(-1100.0) == 0.0);
        assert_eq!(log2(0.0), f64::NEG_INFINITY);
    }
}
