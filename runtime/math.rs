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
