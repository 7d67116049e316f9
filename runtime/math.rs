//! The one math shim: every transcendental function the runtime and the generated code call goes
//! through here, backed by `libm`, so host and embedded targets compute the same bits.
//!
//! `core` on stable has no `sqrt`, `sin`, `exp` or `mul_add`; routing them through one module
//! also keeps the choice of implementation in one place.

/// Square root (correctly rounded in `libm`).
#[inline]
pub fn sqrt(x: f64) -> f64 {
    libm::sqrt(x)
}

/// Exponential.
#[inline]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// `exp(x) − 1` without cancellation near 0.
#[inline]
pub fn expm1(x: f64) -> f64 {
    libm::expm1(x)
}

/// Sine.
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// Cosine.
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// Sine and cosine of one argument, `(sin x, cos x)`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// The largest |x| [`sin_cos_small`] takes its polynomials for.
pub const SMALL_ANGLE: f64 = 0.3;

/// `(sin x, cos x)` for a small angle: for |x| ≤ [`SMALL_ANGLE`] their Taylor polynomials to
/// x¹³ and x¹² (the first terms left out, x¹⁵/15! and x¹⁴/14!, are below 4e-20 and 6e-19 of
/// the result there), within 1 ulp of [`sin_cos`] (unit test); beyond it [`sin_cos`]. What a
/// step's stages take to turn the forcing direction by η·s: no argument reduction and no
/// dispatch, about half of `sin_cos`'s instructions.
#[inline]
pub fn sin_cos_small(x: f64) -> (f64, f64) {
    // (A NaN takes the polynomials, which give NaN as `sin_cos` does.)
    if abs(x) > SMALL_ANGLE {
        return sin_cos(x);
    }
    const S: [f64; 6] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
    ];
    const C: [f64; 6] = [
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
    ];
    let x2 = x * x;
    let horner = |c: &[f64; 6]| c.iter().rev().fold(0.0, |acc, &k| acc * x2 + k);
    (x + x * x2 * horner(&S), 1.0 + x2 * horner(&C))
}

/// Hyperbolic sine.
#[inline]
pub fn sinh(x: f64) -> f64 {
    libm::sinh(x)
}

/// Hyperbolic cosine.
#[inline]
pub fn cosh(x: f64) -> f64 {
    libm::cosh(x)
}

/// `√(x² + y²)` without undue overflow or underflow.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// The angle of the point (x, y), `atan2(y, x)` in (−π, π].
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// Fused multiply-add `a·b + c` with one rounding.
#[inline]
pub fn mul_add(a: f64, b: f64, c: f64) -> f64 {
    libm::fma(a, b, c)
}

/// `x` reduced to `[0, 2π)`.
#[inline]
pub fn wrap_angle(x: f64) -> f64 {
    let two_pi = core::f64::consts::TAU;
    let r = libm::fmod(x, two_pi);
    if r < 0.0 { r + two_pi } else { r }
}

/// Absolute value.
#[inline]
pub fn abs(x: f64) -> f64 {
    libm::fabs(x)
}

/// Power with a real exponent.
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// Natural logarithm.
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place (same sign, finite).
    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64).abs_diff(b.to_bits() as i64)
    }

    /// The small-angle polynomials are within 2 ulps of libm's sine and cosine over the whole
    /// range they serve, and are libm's beyond it.
    #[test]
    fn small_angle_sine_and_cosine_match_libm() {
        let mut worst = (0, 0);
        let n = 600_000;
        for k in 0..=n {
            let x = SMALL_ANGLE * (2.0 * k as f64 / n as f64 - 1.0);
            let (s, c) = sin_cos_small(x);
            let (s0, c0) = sin_cos(x);
            if x != 0.0 {
                worst.0 = worst.0.max(ulps(s, s0));
            }
            worst.1 = worst.1.max(ulps(c, c0));
        }
        assert!(
            worst.0 <= 1 && worst.1 <= 1,
            "worst ulps (sin, cos) = {worst:?}"
        );
        for x in [0.0, 1e-300, -1e-300, 1e-9] {
            assert_eq!(sin_cos_small(x), sin_cos(x), "{x}");
        }
        for x in [0.31, -0.5, 3.0, 1e6] {
            assert_eq!(sin_cos_small(x), sin_cos(x), "{x}");
        }
        for x in [f64::INFINITY, f64::NAN] {
            let (s, c) = sin_cos_small(x);
            assert!(s.is_nan() && c.is_nan(), "{x}");
        }
    }
}
