//! One diagonal block's exponential applied to a vector: e^{J_k s} c for the upper triangular
//! block J_k of a cluster of eigenvalues (`cluster.rs`), exact to rounding for every s ≥ 0.
//!
//! J_k = σ I + N with the shift σ = (max Re λ_i) + i·(mean Im λ_i) over the block: every
//! eigenvalue of N has Re ≤ 0 and |N_ii| ≤ ρ (the block's spread). Then
//! e^{J_k s} c = e^{σ s} (e^{N h})^n c with n = max(1, ⌈ρ s / θ⌉), h = s/n, θ = 1/2, each
//! e^{N h} applied by its Taylor series truncated after p + 16 terms (p the block's size).
//!
//! **Accuracy.** Write N = D + U (diagonal, strictly upper). Entrywise
//! |N h|^j ≤ (θ I + |U| h)^j = Σ_{i<p} C(j, i) θ^{j−i} (|U| h)^i (|U| is nilpotent), so the tail
//! after the terms j ≤ p + 15 is ≤ θ^17/17!·e^θ ≈ 3.5e-20 times the majorant
//! Σ_{i<p} (|U|h)^i/i!: below rounding. The sum of the kept terms rounds to a few ulps of that
//! majorant per term, so each factor e^{N h} is exact to ~(p + 16)·p·ε relative to
//! ‖e^{|U|h}‖, and the n factors to n times that. With σ the rightmost real part the factors
//! never grow exponentially (only polynomially, through U), so nothing overflows however long
//! s is; the decay e^{Re σ s} comes last, as one scalar, and underflows to 0 cleanly.
//!
//! **Cost.** n·(p + 16)·p² complex multiply-adds: for a repeated or defective eigenvalue
//! (ρ at rounding level) n = 1 for any practical s; for a cluster of distinct close eigenvalues
//! n grows like ρ s (the spread is ≤ ~1e-2·‖A‖ by the clustering rule in practice).
//! A 1 × 1 block is one complex exponential; a 2 × 2 block (the repeated eigenvalue of an
//! isotropic rotor's x and y, a defective pair) is in closed form at one or two ([`exp_pair`]),
//! not by the series: this block is the one every evaluation of an isotropic model's free flight
//! pays for.

use super::complex::Complex;
use super::dense::ComplexMatrix;

/// |w| (|re| + |im|) below which a 2 × 2 block's series stops at w²: w⁴/120 < 1e-34.
const TINY_SPLIT: f64 = 1e-8;
/// Substep size limit: ρ h ≤ θ.
const THETA: f64 = 0.5;
/// Taylor terms beyond the block size.
const EXTRA_TERMS: usize = 16;

/// A block's shift σ and spread ρ = max |J_ii − σ|.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct BlockShift {
    pub(crate) sigma: Complex,
    pub(crate) spread: f64,
}

impl BlockShift {
    /// σ and ρ of the diagonal block `range` of `j`.
    pub(crate) fn of<const CAP: usize>(
        j: &ComplexMatrix<CAP>,
        range: core::ops::Range<usize>,
    ) -> Self {
        let p = range.len().max(1) as f64;
        let re = range
            .clone()
            .map(|i| j.get(i, i).re)
            .fold(f64::NEG_INFINITY, f64::max);
        let im = range.clone().map(|i| j.get(i, i).im).sum::<f64>() / p;
        let sigma = Complex::new(if re.is_finite() { re } else { 0.0 }, im);
        let spread = range
            .map(|i| (j.get(i, i) - sigma).abs())
            .fold(0.0, f64::max);
        BlockShift { sigma, spread }
    }

    /// The number of substeps n for a span s.
    pub(crate) fn substeps(&self, s: f64) -> usize {
        let x = self.spread * s / THETA;
        if x >= 1.0 {
            // ⌈x⌉, saturating for absurd spans (the loop count stays finite); NaN gives 1.
            let n = x.min(usize::MAX as f64) as usize;
            if (n as f64) < x {
                n.saturating_add(1)
            } else {
                n
            }
        } else {
            1
        }
    }
}

/// x ← e^{J s} x over the block `range` of `j` (x holds that block's entries of c, first
/// `range.len()` entries of `x`); `work` is scratch of the same length.
pub(crate) fn apply_block_exp<const CAP: usize>(
    j: &ComplexMatrix<CAP>,
    range: core::ops::Range<usize>,
    shift: BlockShift,
    s: f64,
    x: &mut [Complex],
    work: &mut [Complex; CAP],
) {
    let p = range.len();
    if p == 1 {
        if let Some(x0) = x.first_mut() {
            *x0 = scale_by_exp(*x0, j.get(range.start, range.start).scale(s));
        }
        return;
    }
    if p == 2 {
        let (i, k) = (range.start, range.start + 1);
        if let [x0, x1, ..] = x {
            (*x0, *x1) = exp_pair(j.get(i, i), j.get(i, k), j.get(k, k), s, (*x0, *x1));
        }
        return;
    }
    let n = shift.substeps(s);
    let h = s / n as f64;
    let mut term = [Complex::ZERO; CAP];
    for _ in 0..n {
        // term ← x; sum (in x) accumulates; term_{k} = (N h) term_{k−1} / k.
        for (t, &v) in term.iter_mut().zip(x.iter()).take(p) {
            *t = v;
        }
        for k in 1..p + EXTRA_TERMS {
            let f = h / k as f64;
            // work = (N h / k) term, N = J − σ I upper triangular on the block.
            for (a, wa) in work.iter_mut().enumerate().take(p) {
                let row = j.row(range.start + a);
                let mut acc = Complex::ZERO;
                for (b, &tb) in term.iter().enumerate().take(p).skip(a) {
                    let mut n_ab = row.get(range.start + b).copied().unwrap_or(Complex::ZERO);
                    if a == b {
                        n_ab -= shift.sigma;
                    }
                    acc += n_ab * tb;
                }
                *wa = acc.scale(f);
            }
            let mut zero = true;
            for ((t, &w), xa) in term.iter_mut().zip(work.iter()).zip(x.iter_mut()).take(p) {
                *t = w;
                *xa += w;
                zero &= w == Complex::ZERO;
            }
            if zero {
                break;
            }
        }
    }
    let e = shift.sigma.scale(s);
    for xa in x.iter_mut().take(p) {
        *xa = scale_by_exp(*xa, e);
    }
}

/// e^{T s} (x0, x1) for the 2 × 2 upper triangular block T = [[a, u], [0, b]] in closed form:
/// e^{Ts} = [[e^{as}, u·(e^{as} − e^{bs})/(a − b)], [0, e^{bs}]]. With μ = (a + b)/2 and
/// w = (a − b)s/2 that is e^{μs}·[[e^{w}, u·s·sinh(w)/w], [0, e^{−w}]]; for |w| < 1/4 (a repeated
/// eigenvalue, w at rounding level, or a near-defective pair) e^{±w} = cosh w ± sinh w and
/// sinh(w)/w by their Taylor series to w¹² (the next terms are below 5e-20 relative; to w²
/// below |w| = 1e-8, the repeated eigenvalue of an isotropic rotor, where w⁴/120 < 1e-34), so the
/// divided difference never cancels and the block costs one complex exponential; for larger |w|
/// the divided difference is (e^{as} − e^{bs})/(a − b), whose rounding is ε·max|e^{as}|, |e^{bs}|
/// over |a − b| ≤ 2ε·s·max(…)/(2|w|) ≤ 4ε·s·max(…): within rounding of the majorant s·max(…).
#[inline]
pub(crate) fn exp_pair(
    a: Complex,
    u: Complex,
    b: Complex,
    s: f64,
    (x0, x1): (Complex, Complex),
) -> (Complex, Complex) {
    let w = (a - b).scale(0.5 * s);
    if w.abs1() < TINY_SPLIT {
        // A repeated eigenvalue (w at rounding level): the series to w² (the next terms are
        // below 1e-32 relative), the same values to rounding as the full series below.
        let w2 = w * w;
        let sinhc = Complex::ONE + w2.scale(1.0 / 6.0);
        let cosh = Complex::ONE + w2.scale(0.5);
        let sinh = w * sinhc;
        let mu = (a + b).scale(0.5 * s);
        let y0 = (cosh + sinh) * x0 + (u * sinhc).scale(s) * x1;
        let y1 = (cosh - sinh) * x1;
        return if mu.re > 700.0 {
            (scale_by_exp(y0, mu), scale_by_exp(y1, mu))
        } else {
            let e = mu.exp();
            (y0 * e, y1 * e)
        };
    }
    if w.abs1() < 0.25 {
        let w2 = w * w;
        let series = |c: &[f64]| {
            c.iter()
                .rev()
                .fold(Complex::ZERO, |acc, &k| acc * w2 + Complex::real(k))
        };
        // sinh(w)/w = Σ w^{2k}/(2k + 1)!, cosh w = Σ w^{2k}/(2k)!, k ≤ 6.
        let sinhc = series(&[
            1.0,
            1.0 / 6.0,
            1.0 / 120.0,
            1.0 / 5040.0,
            1.0 / 362_880.0,
            1.0 / 39_916_800.0,
            1.0 / 6_227_020_800.0,
        ]);
        let cosh = series(&[
            1.0,
            0.5,
            1.0 / 24.0,
            1.0 / 720.0,
            1.0 / 40_320.0,
            1.0 / 3_628_800.0,
            1.0 / 479_001_600.0,
        ]);
        let sinh = w * sinhc;
        let mu = (a + b).scale(0.5 * s);
        let y0 = (cosh + sinh) * x0 + (u * sinhc).scale(s) * x1;
        let y1 = (cosh - sinh) * x1;
        if mu.re > 700.0 {
            (scale_by_exp(y0, mu), scale_by_exp(y1, mu))
        } else {
            // One complex exponential for both entries (what `scale_by_exp` multiplies by).
            let e = mu.exp();
            (y0 * e, y1 * e)
        }
    } else {
        let ea = scale_by_exp(Complex::ONE, a.scale(s));
        let eb = scale_by_exp(Complex::ONE, b.scale(s));
        let divided = (ea - eb) / (a - b);
        (ea * x0 + u * divided * x1, eb * x1)
    }
}

/// v·e^z without inf·0 = NaN: for Re z > 700 the factor is applied in two halves, so the
/// result overflows only where the true product does.
#[inline]
pub(crate) fn scale_by_exp(v: Complex, z: Complex) -> Complex {
    if z.re > 700.0 {
        let half = z.scale(0.5).exp();
        (v * half) * half
    } else {
        v * z.exp()
    }
}
