//! A complex number for the linear algebra of matrix models: the few operations the complex
//! Schur form, the modal exponential and the harmonic solve need, with the transcendental parts
//! through `crate::math` (libm) like the rest of the runtime.
//!
//! Accuracy: `+`, `−`, `·` round each real part once or twice (no fused operations); `/` is
//! Smith's algorithm (no overflow for operands within range, relative error a few ulps);
//! [`Complex::abs`] is `hypot` (no overflow); [`Complex::exp`] and [`Complex::sqrt`] a few ulps
//! relative.

use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

use crate::math;

/// x + iy.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Complex {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Complex {
    /// 0.
    pub const ZERO: Complex = Complex { re: 0.0, im: 0.0 };
    /// 1.
    pub const ONE: Complex = Complex { re: 1.0, im: 0.0 };
    /// i.
    pub const I: Complex = Complex { re: 0.0, im: 1.0 };

    /// re + i·im.
    #[inline]
    pub const fn new(re: f64, im: f64) -> Self {
        Complex { re, im }
    }

    /// A real number.
    #[inline]
    pub const fn real(re: f64) -> Self {
        Complex { re, im: 0.0 }
    }

    /// The complex conjugate.
    #[inline]
    pub const fn conj(self) -> Self {
        Complex {
            re: self.re,
            im: -self.im,
        }
    }

    /// |z| (without undue overflow).
    #[inline]
    pub fn abs(self) -> f64 {
        math::hypot(self.re, self.im)
    }

    /// |re| + |im|: within √2 of |z|, cheap; LAPACK's `cabs1`, used for pivoting and
    /// negligibility tests.
    #[inline]
    pub fn abs1(self) -> f64 {
        math::abs(self.re) + math::abs(self.im)
    }

    /// re² + im².
    #[inline]
    pub fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    /// Both parts finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }

    /// z·x for a real x.
    #[inline]
    pub fn scale(self, x: f64) -> Self {
        Complex {
            re: self.re * x,
            im: self.im * x,
        }
    }

    /// e^z = e^re (cos im + i sin im). Underflows to 0 (not NaN) for re → −∞ with finite im.
    #[inline]
    pub fn exp(self) -> Self {
        let r = math::exp(self.re);
        if r == 0.0 {
            return Complex::ZERO;
        }
        let (s, c) = math::sin_cos(self.im);
        Complex {
            re: r * c,
            im: r * s,
        }
    }

    /// The principal square root (re ≥ 0; on the negative real axis +i√|re|), computed without
    /// cancellation: the larger of the two parts from √((|z| + |re|)/2), the other by division.
    pub fn sqrt(self) -> Self {
        if self.re == 0.0 && self.im == 0.0 {
            return Complex::ZERO;
        }
        let t = math::sqrt(0.5 * (self.abs() + math::abs(self.re)));
        if self.re >= 0.0 {
            Complex {
                re: t,
                im: 0.5 * self.im / t,
            }
        } else {
            Complex {
                re: 0.5 * math::abs(self.im) / t,
                im: if self.im < 0.0 { -t } else { t },
            }
        }
    }
}

impl From<f64> for Complex {
    #[inline]
    fn from(re: f64) -> Self {
        Complex::real(re)
    }
}

impl Add for Complex {
    type Output = Complex;
    #[inline]
    fn add(self, o: Complex) -> Complex {
        Complex {
            re: self.re + o.re,
            im: self.im + o.im,
        }
    }
}

impl Sub for Complex {
    type Output = Complex;
    #[inline]
    fn sub(self, o: Complex) -> Complex {
        Complex {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
}

impl Mul for Complex {
    type Output = Complex;
    #[inline]
    fn mul(self, o: Complex) -> Complex {
        Complex {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }
}

impl Div for Complex {
    type Output = Complex;
    /// Smith's algorithm: scale by the larger part of the divisor (no overflow of |o|²).
    #[inline]
    fn div(self, o: Complex) -> Complex {
        if math::abs(o.re) >= math::abs(o.im) {
            let r = o.im / o.re;
            let d = o.re + o.im * r;
            Complex {
                re: (self.re + self.im * r) / d,
                im: (self.im - self.re * r) / d,
            }
        } else {
            let r = o.re / o.im;
            let d = o.re * r + o.im;
            Complex {
                re: (self.re * r + self.im) / d,
                im: (self.im * r - self.re) / d,
            }
        }
    }
}

impl Mul<f64> for Complex {
    type Output = Complex;
    #[inline]
    fn mul(self, x: f64) -> Complex {
        self.scale(x)
    }
}

impl Neg for Complex {
    type Output = Complex;
    #[inline]
    fn neg(self) -> Complex {
        Complex {
            re: -self.re,
            im: -self.im,
        }
    }
}

impl AddAssign for Complex {
    #[inline]
    fn add_assign(&mut self, o: Complex) {
        *self = *self + o;
    }
}

impl SubAssign for Complex {
    #[inline]
    fn sub_assign(&mut self, o: Complex) {
        *self = *self - o;
    }
}

impl MulAssign for Complex {
    #[inline]
    fn mul_assign(&mut self, o: Complex) {
        *self = *self * o;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn division_undoes_multiplication() {
        let a = Complex::new(3.0, -4.0);
        let b = Complex::new(-1e-3, 2e5);
        let q = (a * b) / b;
        assert!((q - a).abs() < 1e-15 * a.abs());
        let q = (a * b) / Complex::new(2e5, -1e-3);
        assert!(q.is_finite());
    }

    #[test]
    fn square_root_is_principal_and_squares_back() {
        for z in [
            Complex::new(-4.0, 0.0),
            Complex::new(-4.0, -0.0),
            Complex::new(0.0, 2.0),
            Complex::new(-1e-20, 1.0),
            Complex::new(3.0, -4.0),
        ] {
            let r = z.sqrt();
            assert!(r.re >= 0.0);
            assert!((r * r - z).abs() <= 4.0 * f64::EPSILON * z.abs(), "{z:?}");
        }
        assert_eq!(Complex::new(-4.0, 0.0).sqrt(), Complex::new(0.0, 2.0));
    }

    #[test]
    fn exponential_underflows_to_zero() {
        assert_eq!(Complex::new(-1e4, 3.0).exp(), Complex::ZERO);
        let e = Complex::new(0.0, core::f64::consts::PI).exp();
        assert!((e + Complex::ONE).abs() < 1e-15);
    }
}
