//! The series response of a linearized contact segment to an extra forcing (`docs/MODEL.md` §3,
//! §8, §11): the zero-state solution of q'' + 2νq' + Kl q = Σ a_m s^m as a Taylor polynomial
//! Σ c_m s^m. Used for a cubic forcing over short horizons, where the polynomial particular
//! solution cancels badly (its coefficients grow like (‖Kl‖h²)⁻ᵏ while the response is O(h²)),
//! and for the harmonic forcing itself near resonance, where the harmonic particular solution
//! and the homogeneous part cancel (the forcing's Taylor coefficients then run to every order).
//!
//! The recurrence is the model's linear contact acceleration (`coefficients::linear_acceleration`,
//! generated) evaluated at the Taylor coefficients: with c0 = c1 = 0,
//! (m + 2)(m + 1) c_{m+2} = a_m − 2ν (m + 1) c_{m+1} − Kl c_m, since the coefficient of s^m in
//! q'', q' and q is (m + 2)(m + 1) c_{m+2}, (m + 1) c_{m+1} and c_m.

use crate::coefficients::{
    self as coef, Force, LinearizedContact, ModelParams, Position, Velocity,
};
use crate::math;

/// Number of Taylor coefficients of the series response (degree `SERIES_TERMS − 1`); with
/// μh ≤ 2 (see [`series_len`]) the first neglected term is below 1e-19 of the degree-5 term.
pub const SERIES_TERMS: usize = 28;

/// Largest μh (see [`series_len`]) the fixed number of terms serves to rounding.
pub const MAX_RATE_HORIZON: f64 = 2.0;

/// Taylor coefficients (x, y) of the series response, c_0 … c_{SERIES_TERMS − 1}.
pub type Coefficients = [[f64; 2]; SERIES_TERMS];

/// 1/((m + 2)(m + 1)) for m = 0 … SERIES_TERMS − 3 (the recurrence's divisors).
#[allow(
    clippy::indexing_slicing,
    reason = "a const initializer: an out-of-range index fails the build, never a run"
)]
const DIVISORS: [f64; SERIES_TERMS - 2] = {
    let mut r = [0.0; SERIES_TERMS - 2];
    let mut m = 0;
    while m < SERIES_TERMS - 2 {
        r[m] = 1.0 / (((m + 2) * (m + 1)) as f64);
        m += 1;
    }
    r
};

/// How many Taylor coefficients the series response needs on s ∈ [0, horizon].
///
/// Beyond the forcing (m ≥ 4) the recurrence gives ‖c_m‖ ≤ B μ^m / m! with μ = ν + √(ν² + ‖Kl‖)
/// (μ² = 2νμ + ‖Kl‖ turns the bound into an equality), so the terms from n on add at most
/// (μh)^(n−5)·5!/n!·e^(μh) relative to the degree-5 term. The count is the smallest n ≥ 6 with
/// (μh)^(n−5)·5!/n! ≤ 1e-19, at most [`SERIES_TERMS`] (reached only beyond
/// [`MAX_RATE_HORIZON`], the fixed length's design).
pub fn series_len(norm_kl: f64, nu: f64, horizon: f64) -> usize {
    len_for_rate(rate(norm_kl, nu) * horizon).min(CUBIC_TERMS)
}

/// The most terms a cubic forcing's response uses: with ‖Kl‖h² ≤ 1 (where the series replaces
/// the polynomial particular solution) the first neglected term is below 1e-16 of the response.
const CUBIC_TERMS: usize = 20;

/// μ = ν + √(ν² + ‖Kl‖), the growth rate of the recurrence's coefficients.
#[inline]
pub fn rate(norm_kl: f64, nu: f64) -> f64 {
    nu + math::sqrt(nu * nu + norm_kl)
}

/// The number of terms for a given μh (see [`series_len`]). A forcing that goes on to every
/// order with |a_m| ≤ A η^m/m! (the harmonic forcing) keeps the bound with μ replaced by
/// max(μ, η), up to a factor growing linearly in m that the 1e-19 margin absorbs.
pub fn len_for_rate(mu_h: f64) -> usize {
    // term = (μh)^(n−5)·5!/n!, from n = 6.
    let mut term = mu_h / 6.0;
    let mut n = 6;
    // (NaN runs to the full length.)
    while n < SERIES_TERMS && (term > 1e-19 || term.is_nan()) {
        n += 1;
        term *= mu_h / n as f64;
    }
    n
}

/// The equation the series solves: the linearized contact acceleration and the forcing.
#[derive(Clone, Copy)]
pub struct Recurrence<'a> {
    /// ν (the other parameters are unused by the linear acceleration).
    pub model: &'a ModelParams,
    /// Kl.
    pub kl: &'a LinearizedContact,
    /// The forcing's Taylor coefficients `[a0x, a0y, a1x, a1y, …]` (a cubic has 8; missing
    /// coefficients are zero).
    pub forcing: &'a [f64],
}

impl Recurrence<'_> {
    /// Runs the recurrence for the first `len` (6 … [`SERIES_TERMS`]) coefficients and hands
    /// each c_{m+2} (m = 0 … len − 3) to `visit` with the next of `slots` (the run stops early
    /// when they run out): c_{m+2} is the generated linear acceleration at position c_m,
    /// velocity (m + 1) c_{m+1} and force a_m, divided by (m + 2)(m + 1). The forcing's
    /// coefficients are walked by pairs and zero after them (no per-term lookup). `visit` also
    /// gets m + 1 as a float (counted in floats: small integers are exact, and no integer
    /// conversion per term).
    #[inline(always)]
    fn run<S>(
        &self,
        len: usize,
        slots: impl Iterator<Item = S>,
        mut visit: impl FnMut(S, f64, [f64; 2]),
    ) {
        let len = len.clamp(6, SERIES_TERMS);
        let mut forcing = self.forcing.chunks_exact(2);
        let (mut cm, mut cn) = ([0.0; 2], [0.0; 2]);
        // (m + 1) as f64.
        let mut k = 0.0;
        for (&divisor, slot) in DIVISORS.iter().take(len - 2).zip(slots) {
            let (fx, fy) = match forcing.next() {
                Some(&[fx, fy]) => (fx, fy),
                _ => (0.0, 0.0),
            };
            k += 1.0;
            let acc = coef::linear_acceleration(
                self.model,
                &Position { x: cm[0], y: cm[1] },
                &Velocity {
                    vx: k * cn[0],
                    vy: k * cn[1],
                },
                &Force { fx, fy },
                self.kl,
            );
            let next = [acc.ax * divisor, acc.ay * divisor];
            visit(slot, k, next);
            (cm, cn) = (cn, next);
        }
    }

    /// The first `len` (6 … [`SERIES_TERMS`]) coefficients into `out`, the others zero.
    pub fn coefficients_into(&self, len: usize, out: &mut Series) {
        // Any term of `out` may be non-zero: clear every one after `len`.
        out.used = SERIES_TERMS;
        self.refill(len, out);
    }

    /// [`Self::coefficients_into`] for a slot whose terms from its `used` on are zero (what
    /// every series this module writes holds, and [`Series::ZERO`]): of the terms after `len`
    /// only those up to the old `used` are cleared. The same coefficients and count.
    pub(crate) fn refill(&self, len: usize, out: &mut Series) {
        let len = len.clamp(6, SERIES_TERMS);
        let stale = out.used;
        // c0 = c1 = 0.
        let [c0, c1, rest @ ..] = &mut out.coefficients;
        (*c0, *c1) = ([0.0; 2], [0.0; 2]);
        self.run(len, rest.iter_mut(), |slot, _, next| *slot = next);
        // The terms after `len` are zero from here on: those after `stale` were already.
        if let Some(tail) = out.coefficients.get_mut(len..stale) {
            tail.fill([0.0; 2]);
        }
        // [`used`]: the terms after `len` are zero, so the search starts there (it usually
        // stops at once: the last computed term is rarely zero).
        out.used = out
            .coefficients
            .get(..len)
            .and_then(|c| c.iter().rposition(|t| t[0] != 0.0 || t[1] != 0.0))
            .map_or(0, |i| i + 1);
    }

    /// Position and velocity at `s` of the first `len` terms in one pass, without storing the
    /// coefficients (the same value as [`eval`] of [`Self::coefficients_into`] up to rounding).
    /// Kept out of line: inlined into its callers (as an unrelated change once let the compiler
    /// decide) the analytic method and the stepper ran 0.5 % more instructions.
    #[inline(never)]
    pub fn value(&self, len: usize, s: f64) -> [f64; 4] {
        // c0 = c1 = 0: the terms m = 0, 1 contribute nothing.
        let (mut x, mut y, mut vx, mut vy) = (0.0, 0.0, 0.0, 0.0);
        // s^(m+1) for the term c_{m+2} s^(m+2).
        let mut pow1 = s;
        self.run(len, core::iter::repeat(()), |(), k, next| {
            let pow2 = pow1 * s;
            // (m + 2) as f64, exactly.
            let d = (k + 1.0) * pow1;
            x += next[0] * pow2;
            y += next[1] * pow2;
            vx += next[0] * d;
            vy += next[1] * d;
            pow1 = pow2;
        });
        [x, y, vx, vy]
    }
}

/// A series response's Taylor coefficients with the count up to the last non-zero one (kept so
/// that evaluations and bounds do not search for it each time).
#[derive(Clone, Copy, Debug)]
pub struct Series {
    /// c_0 … c_{SERIES_TERMS − 1}.
    pub coefficients: Coefficients,
    /// [`used`] of `coefficients`.
    pub used: usize,
}

impl Series {
    /// No terms.
    pub const ZERO: Series = Series {
        coefficients: [[0.0; 2]; SERIES_TERMS],
        used: 0,
    };

    /// The coefficients up to the last non-zero one.
    #[inline]
    pub fn terms(&self) -> &[[f64; 2]] {
        self.coefficients.get(..self.used).unwrap_or(&[])
    }

    /// Position and velocity at s (Horner): [`eval`].
    #[inline]
    pub fn eval(&self, s: f64) -> [f64; 4] {
        eval_terms(self.terms(), s)
    }
}

/// The number of coefficients up to the last non-zero one.
#[inline]
pub fn used(c: &Coefficients) -> usize {
    c.iter()
        .rposition(|t| t[0] != 0.0 || t[1] != 0.0)
        .map_or(0, |i| i + 1)
}

/// Position and velocity of a Taylor polynomial at s (Horner).
pub fn eval(c: &Coefficients, s: f64) -> [f64; 4] {
    eval_terms(c.get(..used(c)).unwrap_or(&[]), s)
}

/// [`eval`] of the coefficients `c` (the velocity's Horner sum stops before the constant term):
/// (x, y, x', y') of the polynomial Σ c_m s^m at `s`.
#[inline]
pub(crate) fn eval_terms(c: &[[f64; 2]], s: f64) -> [f64; 4] {
    let (mut x, mut y, mut vx, mut vy) = (0.0, 0.0, 0.0, 0.0);
    let Some((c0, rest)) = c.split_first() else {
        return [x, y, vx, vy];
    };
    // The index of `cm` in `c` as a float (exact for these small counts), counted down.
    let mut m = rest.len() as f64;
    for cm in rest.iter().rev() {
        x = x * s + cm[0];
        y = y * s + cm[1];
        vx = vx * s + m * cm[0];
        vy = vy * s + m * cm[1];
        m -= 1.0;
    }
    x = x * s + c0[0];
    y = y * s + c0[1];
    [x, y, vx, vy]
}
