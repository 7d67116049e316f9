//! Scalar basis functions of the closed forms, robust in every damping regime.
//!
//! * Free flight (`docs/MODEL.md` §4): EC(s) = e^{−νs} cos βs and ES(s) = e^{−νs} sin(βs)/β for any
//!   sign of β² = 1 − ν² (cosh/sinh when over-damped, written with e^{(b−ν)s} so nothing
//!   overflows on long segments; a series when |β²s²| is small, so ν = 1 needs no special case).
//! * Contact (`docs/MODEL.md` §5, the form without eigenvectors): the even and odd parts of
//!   f(μ) = cos(√μ s) and f(μ) = sin(√μ s)/√μ over the eigenvalue pair μ = γ̄² ± √Δ of
//!   A = Kl − ν²I, which give C = cos(√A s) = cc·I + cd·B and S = sin(√A s)/√A = sc·I + sd·B with
//!   B = A − γ̄²I (trace-free, B² = Δ·I). Δ > 0: real pair; Δ < 0: complex pair (case 2);
//!   |Δ| tiny: repeated or near-defective pair (cases 7–8), first-order Taylor in √Δ.

use crate::math;

/// |x| below which the power series of cos(√x) and sin(√x)/√x are used (truncation < 1e-18).
const SERIES_LIMIT: f64 = 1e-2;

/// cos(√x) and sin(√x)/√x·(1/s) scaled: returns (c, sn/s) for x = μ s², by series.
fn series(x: f64) -> (f64, f64) {
    // c = Σ (−x)^k/(2k)!, sn/s = Σ (−x)^k/(2k+1)!, five terms.
    let c = 1.0 - x / 2.0 * (1.0 - x / 12.0 * (1.0 - x / 30.0 * (1.0 - x / 56.0)));
    let sn = 1.0 - x / 6.0 * (1.0 - x / 20.0 * (1.0 - x / 42.0 * (1.0 - x / 72.0)));
    (c, sn)
}

/// (cos(√μ s), sin(√μ s)/√μ) for real μ of either sign.
pub fn cos_sinc(mu: f64, s: f64) -> (f64, f64) {
    let x = mu * s * s;
    if math::abs(x) < SERIES_LIMIT {
        let (c, sn) = series(x);
        return (c, sn * s);
    }
    if mu > 0.0 {
        let r = math::sqrt(mu);
        let (sin, cos) = math::sin_cos(r * s);
        (cos, sin / r)
    } else {
        let r = math::sqrt(-mu);
        (math::cosh(r * s), math::sinh(r * s) / r)
    }
}

/// d/dμ of (cos(√μ s), sin(√μ s)/√μ): (−(s/2)·sn, (s·c − sn)/(2μ)), by series near μ s² = 0.
fn cos_sinc_derivative(mu: f64, s: f64) -> (f64, f64) {
    let (c, sn) = cos_sinc(mu, s);
    let x = mu * s * s;
    let dsn = if math::abs(x) < SERIES_LIMIT {
        // s³ Σ_{k≥1} (−1)^k k x^{k−1}/(2k+1)!
        s * s * s * (-1.0 / 6.0 + x / 60.0 - x * x / 1680.0 + x * x * x / 90720.0)
    } else {
        (s * c - sn) / (2.0 * mu)
    };
    (-0.5 * s * sn, dsn)
}

/// ν and β² with what the free basis and its bounds derive from them alone: √|β²|, the slowest
/// decay rate κ and the two caps of |ES|. Computed once per parameter set ([`FreeRates::new`])
/// instead of at every evaluation — the same operations on the same numbers, so the same bits —
/// which takes a square root (and a division for the bound) off every evaluation's critical
/// path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeRates {
    /// ν.
    pub nu: f64,
    /// β² = 1 − ν².
    pub beta_sq: f64,
    /// √|β²|.
    root: f64,
    /// κ: ν, or ν − √(−β²) when over-damped.
    decay: f64,
    /// |ES| ≤ e^{−κ lo}·min(hi, `es_cap`): 1/β, 1/(2b), or ∞ at β² = 0.
    es_cap: f64,
    /// 2/(κe) (used when κ > 0): |ES| ≤ `es_alt`·e^{−κ lo/2}.
    es_alt: f64,
}

impl FreeRates {
    /// The rates of damping ratio `nu` with β² = `beta_sq`.
    pub fn new(nu: f64, beta_sq: f64) -> Self {
        let root = math::sqrt(math::abs(beta_sq));
        let (decay, es_cap) = if beta_sq > 0.0 {
            (nu, 1.0 / root)
        } else if beta_sq < 0.0 {
            (nu - root, 0.5 / root)
        } else {
            (nu, f64::INFINITY)
        };
        FreeRates {
            nu,
            beta_sq,
            root,
            decay,
            es_cap,
            es_alt: 2.0 / (decay * core::f64::consts::E),
        }
    }

    /// The free-flight basis (EC, ES) at local time `s` ≥ 0 (`docs/MODEL.md` §4, §6 cases 5,
    /// 11, 12).
    #[inline]
    pub fn basis(&self, s: f64) -> (f64, f64) {
        let (nu, beta_sq) = (self.nu, self.beta_sq);
        let x = beta_sq * s * s;
        if math::abs(x) < SERIES_LIMIT {
            let d = math::exp(-nu * s);
            let (c, sn) = series(x);
            return (d * c, d * sn * s);
        }
        let b = self.root;
        if beta_sq > 0.0 {
            let d = math::exp(-nu * s);
            let (sin, cos) = math::sin_cos(b * s);
            (d * cos, d * sin / b)
        } else {
            // e^{−νs} cosh(bs) = (e^{(b−ν)s} + e^{−(b+ν)s})/2 with b < ν: no overflow.
            let slow = math::exp((b - nu) * s);
            let fast = math::exp(-(b + nu) * s);
            (0.5 * (slow + fast), 0.5 * (slow - fast) / b)
        }
    }

    /// Upper bounds of |EC| and |ES| on s ∈ [lo, hi] (`hi` may be infinite).
    ///
    /// |EC| ≤ e^{−κ lo} with κ the slowest decay rate (ν, or ν − √(−β²) when over-damped), and
    /// |ES| ≤ e^{−κ lo}·min(hi, 1/β or 1/(2b)) as well as |ES| ≤ s e^{−κs} ≤ (2/(κe)) e^{−κ lo/2}.
    #[inline]
    pub fn bound(&self, lo: f64, hi: f64) -> (f64, f64) {
        let rate = self.decay;
        // One exponential: e^{−κ lo} = (e^{−κ lo/2})², rounded up by a few ulps so that the
        // bound stays a bound.
        let half = math::exp(-0.5 * rate * lo);
        let d = half * half * (1.0 + 4.0 * f64::EPSILON);
        let mut es = d * hi.min(self.es_cap);
        if rate > 0.0 {
            es = es.min(self.es_alt * half);
        }
        (d, es)
    }
}

/// The free-flight basis (EC, ES) at local time `s` ≥ 0: [`FreeRates::basis`].
pub fn free_basis(nu: f64, beta_sq: f64, s: f64) -> (f64, f64) {
    FreeRates::new(nu, beta_sq).basis(s)
}

/// A minimal complex number for the complex eigenvalue pair (`docs/MODEL.md` §6 case 2).
#[derive(Clone, Copy, Debug)]
struct Complex {
    re: f64,
    im: f64,
}

impl Complex {
    fn mul(self, o: Complex) -> Complex {
        Complex {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }

    fn div(self, o: Complex) -> Complex {
        let d = o.re * o.re + o.im * o.im;
        Complex {
            re: (self.re * o.re + self.im * o.im) / d,
            im: (self.im * o.re - self.re * o.im) / d,
        }
    }

    /// Principal square root, without cancellation: the larger part from √((|z| + |Re z|)/2),
    /// the other as Im z / (2·larger).
    fn sqrt(self) -> Complex {
        let r = math::hypot(self.re, self.im);
        if r == 0.0 {
            return Complex { re: 0.0, im: 0.0 };
        }
        let big = math::sqrt(0.5 * (r + math::abs(self.re)));
        let small = self.im / (2.0 * big);
        if self.re >= 0.0 {
            Complex { re: big, im: small }
        } else {
            Complex {
                re: math::abs(small),
                im: if self.im < 0.0 { -big } else { big },
            }
        }
    }

    /// (cos z, sin z).
    fn cos_sin(self) -> (Complex, Complex) {
        let (s, c) = math::sin_cos(self.re);
        let (ch, sh) = (math::cosh(self.im), math::sinh(self.im));
        (
            Complex {
                re: c * ch,
                im: -s * sh,
            },
            Complex {
                re: s * ch,
                im: c * sh,
            },
        )
    }
}

/// (cos(√μ s), sin(√μ s)/√μ) for complex μ.
fn cos_sinc_complex(mu: Complex, s: f64) -> (Complex, Complex) {
    let x = Complex {
        re: mu.re * s * s,
        im: mu.im * s * s,
    };
    if math::hypot(x.re, x.im) < SERIES_LIMIT {
        // Horner in complex arithmetic, as `series`.
        let one = Complex { re: 1.0, im: 0.0 };
        let step = |acc: Complex, k: f64| {
            let t = x.mul(acc);
            Complex {
                re: 1.0 - t.re / k,
                im: -t.im / k,
            }
        };
        let c = step(step(step(step(one, 56.0), 30.0), 12.0), 2.0);
        let sn = step(step(step(step(one, 72.0), 42.0), 20.0), 6.0);
        return (
            c,
            Complex {
                re: sn.re * s,
                im: sn.im * s,
            },
        );
    }
    let r = mu.sqrt();
    let (c, sn) = Complex {
        re: r.re * s,
        im: r.im * s,
    }
    .cos_sin();
    (c, sn.div(r))
}

/// Coefficients of C = cc·I + cd·B and S = sc·I + sd·B (B = A − γ̄²I) at local time `s`, for the
/// eigenvalues γ̄² ± √Δ of A = Kl − ν²I. The decay e^{−νs} is not included.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatrixFunction {
    /// Even part of cos(√μ s) over the pair.
    pub cc: f64,
    /// Odd part (divided difference) of cos(√μ s).
    pub cd: f64,
    /// Even part of sin(√μ s)/√μ.
    pub sc: f64,
    /// Odd part of sin(√μ s)/√μ.
    pub sd: f64,
}

/// Relative size of √|Δ| below which the pair is treated as repeated (first-order Taylor).
const CONFLUENT_LIMIT: f64 = 1e-5;

/// C and S coefficients for the pair γ̄² ± √Δ at local time `s` (see [`MatrixFunction`]).
pub fn matrix_function(gamma_sq_mean: f64, disc: f64, s: f64) -> MatrixFunction {
    let e = math::sqrt(math::abs(disc));
    if e <= CONFLUENT_LIMIT * (1.0 + math::abs(gamma_sq_mean)) {
        // f(A) ≈ f(γ̄²) I + f'(γ̄²) B: error O(Δ·f'') (cases 7–8).
        let (c, sn) = cos_sinc(gamma_sq_mean, s);
        let (dc, dsn) = cos_sinc_derivative(gamma_sq_mean, s);
        return MatrixFunction {
            cc: c,
            cd: dc,
            sc: sn,
            sd: dsn,
        };
    }
    if disc > 0.0 {
        let (c1, s1) = cos_sinc(gamma_sq_mean + e, s);
        let (c2, s2) = cos_sinc(gamma_sq_mean - e, s);
        MatrixFunction {
            cc: 0.5 * (c1 + c2),
            cd: (c1 - c2) / (2.0 * e),
            sc: 0.5 * (s1 + s2),
            sd: (s1 - s2) / (2.0 * e),
        }
    } else {
        // f(γ̄² + ie) and its conjugate: even part Re f, odd part Im f / e.
        let (c, sn) = cos_sinc_complex(
            Complex {
                re: gamma_sq_mean,
                im: e,
            },
            s,
        );
        MatrixFunction {
            cc: c.re,
            cd: c.im / e,
            sc: sn.re,
            sd: sn.im / e,
        }
    }
}
