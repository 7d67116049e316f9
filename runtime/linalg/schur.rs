//! The complex Schur form A = Q T Q^H of a real matrix (T upper triangular, Q unitary) by the
//! single-shift complex QR iteration on the Hessenberg form (Golub & Van Loan, 4th ed., §7.5;
//! the structure of LAPACK `zlahqr`: Wilkinson shifts, exceptional shifts after 10 and 20
//! iterations without deflation, the Ahues–Tisseur negligibility test), and the swap of two
//! adjacent diagonal entries by one Givens rotation (LAPACK `ztrexc`), which the modal
//! decomposition uses to make clusters of eigenvalues contiguous.
//!
//! Complex arithmetic avoids the real Schur form's 2 × 2 blocks: every eigenvalue, real or
//! one of a complex pair, is one diagonal entry. The iteration is backward stable:
//! Q T Q^H = A + E with ‖E‖ ≲ c·m·ε·‖A‖, so each computed eigenvalue is exact for a nearby
//! matrix (its error is its condition number times that).

use super::complex::Complex;
use super::dense::{ComplexMatrix, RealMatrix};
use super::error::LinalgError;
use super::hessenberg::{balance, hessenberg};

/// Iterations without a deflation after which the QR iteration gives up, per eigenvalue:
/// 30·max(10, m) (LAPACK's `itmax`).
fn max_iterations(n: usize) -> usize {
    30 * n.max(10)
}

/// Exceptional shift every this many iterations without deflation (LAPACK's `kexsh`).
const EXCEPTIONAL: usize = 10;

/// A Givens rotation G = [[c, s], [−s̄, c]] (c real) with G (f, g)ᵀ = (r, 0)ᵀ.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rotation {
    c: f64,
    s: Complex,
}

impl Rotation {
    /// The rotation that zeroes g against f, and r.
    pub(crate) fn zeroing(f: Complex, g: Complex) -> (Rotation, Complex) {
        let (af, ag) = (f.abs(), g.abs());
        if ag == 0.0 {
            return (
                Rotation {
                    c: 1.0,
                    s: Complex::ZERO,
                },
                f,
            );
        }
        if af == 0.0 {
            return (
                Rotation {
                    c: 0.0,
                    s: g.conj().scale(1.0 / ag),
                },
                Complex::real(ag),
            );
        }
        let norm = crate::math::hypot(af, ag);
        let phase = f.scale(1.0 / af);
        let rot = Rotation {
            c: af / norm,
            s: phase * g.conj().scale(1.0 / norm),
        };
        (rot, phase.scale(norm))
    }

    /// (a, b) ← G (a, b): rows from the left.
    #[inline]
    pub(crate) fn left(&self, a: Complex, b: Complex) -> (Complex, Complex) {
        (
            a.scale(self.c) + self.s * b,
            b.scale(self.c) - self.s.conj() * a,
        )
    }

    /// (a, b) ← (a, b) G^H: columns from the right.
    #[inline]
    pub(crate) fn right(&self, a: Complex, b: Complex) -> (Complex, Complex) {
        (
            a.scale(self.c) + b * self.s.conj(),
            b.scale(self.c) - a * self.s,
        )
    }
}

/// Apply G from the left to rows k, k+1 over columns `from..to`.
fn rotate_rows<const CAP: usize>(
    h: &mut ComplexMatrix<CAP>,
    g: Rotation,
    k: usize,
    from: usize,
    to: usize,
) {
    if let Some((rk, rk1)) = h.two_rows_mut(k, k + 1) {
        for (a, b) in rk.iter_mut().zip(rk1.iter_mut()).take(to).skip(from) {
            (*a, *b) = g.left(*a, *b);
        }
    }
}

/// Apply G^H from the right to columns k, k+1 over rows `from..to`.
fn rotate_cols<const CAP: usize>(
    h: &mut ComplexMatrix<CAP>,
    g: Rotation,
    k: usize,
    from: usize,
    to: usize,
) {
    for i in from..to {
        let row = h.row_mut(i);
        if let Some([a, b]) = row
            .get_mut(k..k + 2)
            .and_then(|p| <&mut [Complex; 2]>::try_from(p).ok())
        {
            (*a, *b) = g.right(*a, *b);
        }
    }
}

/// Whether the subdiagonal entry h[k][k−1] is negligible (LAPACK `zlahqr`'s test, with
/// |re| + |im| in place of its real subdiagonal).
fn negligible<const CAP: usize>(h: &ComplexMatrix<CAP>, k: usize, lo: usize, hi: usize) -> bool {
    let ulp = f64::EPSILON;
    let small = f64::MIN_POSITIVE * (h.rows() as f64 / ulp);
    let sub = h.get(k, k - 1).abs1();
    if sub <= small {
        return true;
    }
    let (a, d) = (h.get(k - 1, k - 1), h.get(k, k));
    let mut tst = a.abs1() + d.abs1();
    if tst == 0.0 {
        if k >= lo + 2 {
            tst += h.get(k - 1, k - 2).abs1();
        }
        if k < hi {
            tst += h.get(k + 1, k).abs1();
        }
    }
    if sub > ulp * tst {
        return false;
    }
    let sup = h.get(k - 1, k).abs1();
    let (ab, ba) = (sub.max(sup), sub.min(sup));
    let diff = (a - d).abs1();
    let (aa, bb) = (d.abs1().max(diff), d.abs1().min(diff));
    let s = aa + ab;
    ba * (ab / s) <= small.max(ulp * (bb * (aa / s)))
}

/// The shift for the active block `lo..=hi`: the eigenvalue of the trailing 2 × 2 nearer to
/// its last diagonal entry (Wilkinson), or an exceptional shift.
fn shift<const CAP: usize>(
    h: &ComplexMatrix<CAP>,
    lo: usize,
    hi: usize,
    stalled: usize,
) -> Complex {
    if stalled.is_multiple_of(2 * EXCEPTIONAL) {
        return h.get(hi, hi) + Complex::real(0.75 * crate::math::abs(h.get(hi, hi - 1).re));
    }
    if stalled.is_multiple_of(EXCEPTIONAL) {
        return h.get(lo, lo) + Complex::real(0.75 * crate::math::abs(h.get(lo + 1, lo).re));
    }
    let t = h.get(hi, hi);
    let u = h.get(hi - 1, hi).sqrt() * h.get(hi, hi - 1).sqrt();
    let su = u.abs1();
    if su == 0.0 {
        return t;
    }
    let x = (h.get(hi - 1, hi - 1) - t).scale(0.5);
    let sx = x.abs1();
    let s = su.max(sx);
    let (xs, us) = (x.scale(1.0 / s), u.scale(1.0 / s));
    let mut y = (xs * xs + us * us).sqrt().scale(s);
    if sx > 0.0 {
        let xn = x.scale(1.0 / sx);
        if xn.re * y.re + xn.im * y.im < 0.0 {
            y = -y;
        }
    }
    t - u * (u / (x + y))
}

/// Reduce an upper Hessenberg `h` in place to upper triangular T by the shifted QR iteration.
/// With `q` (holding the Hessenberg reduction's Q on entry) the whole T and Q are updated
/// (Schur form); without, only the active blocks (eigenvalues only, on T's diagonal).
pub(crate) fn triangularize<const CAP: usize>(
    h: &mut ComplexMatrix<CAP>,
    mut q: Option<&mut ComplexMatrix<CAP>>,
) -> Result<(), LinalgError> {
    let n = h.rows();
    if n < 2 {
        return Ok(());
    }
    let full = q.is_some();
    let mut hi = n - 1;
    loop {
        let mut converged = None;
        for its in 0..=max_iterations(n) {
            // The lowest negligible subdiagonal entry splits off the active block lo..=hi.
            let mut lo = hi;
            while lo > 0 && !negligible(h, lo, 0, hi) {
                lo -= 1;
            }
            if lo > 0 {
                h.set(lo, lo - 1, Complex::ZERO);
            }
            if lo == hi {
                converged = Some(lo);
                break;
            }
            let sigma = shift(h, lo, hi, its + 1);
            let (col_end, row_start) = if full { (n, 0) } else { (hi + 1, lo) };
            for k in lo..hi {
                let (f, g) = if k == lo {
                    (h.get(lo, lo) - sigma, h.get(lo + 1, lo))
                } else {
                    (h.get(k, k - 1), h.get(k + 1, k - 1))
                };
                let (rot, r) = Rotation::zeroing(f, g);
                let from = if k > lo {
                    h.set(k, k - 1, r);
                    h.set(k + 1, k - 1, Complex::ZERO);
                    k
                } else {
                    lo
                };
                rotate_rows(h, rot, k, from, col_end);
                rotate_cols(h, rot, k, row_start, (k + 3).min(hi + 1));
                if let Some(q) = q.as_deref_mut() {
                    rotate_cols(q, rot, k, 0, n);
                }
            }
        }
        let Some(lo) = converged else {
            return Err(LinalgError::NoConvergence {
                converged: n - 1 - hi,
                size: n,
            });
        };
        if lo == 0 {
            break;
        }
        hi = lo - 1;
        if hi == 0 {
            break;
        }
    }
    Ok(())
}

/// Swap the adjacent diagonal entries k, k+1 of the upper triangular `t` by one rotation,
/// updating `q` (t ← G t G^H, q ← q G^H): LAPACK `ztrexc`'s step.
pub(crate) fn swap_diagonal<const CAP: usize>(
    t: &mut ComplexMatrix<CAP>,
    q: &mut ComplexMatrix<CAP>,
    k: usize,
) {
    let n = t.rows();
    let (t11, t22) = (t.get(k, k), t.get(k + 1, k + 1));
    if t11 == t22 {
        return;
    }
    let (rot, _) = Rotation::zeroing(t.get(k, k + 1), t22 - t11);
    rotate_rows(t, rot, k, k + 2, n);
    rotate_cols(t, rot, k, 0, k);
    t.set(k, k, t22);
    t.set(k + 1, k + 1, t11);
    rotate_cols(q, rot, k, 0, n);
}

/// The complex Schur form of a balanced real matrix: A = D Q T Q^H D⁻¹.
#[derive(Clone, Debug)]
pub(crate) struct Schur<const CAP: usize> {
    /// T, upper triangular.
    pub(crate) t: ComplexMatrix<CAP>,
    /// Q, unitary.
    pub(crate) q: ComplexMatrix<CAP>,
    /// D's diagonal (powers of 2).
    pub(crate) scale: [f64; CAP],
}

impl<const CAP: usize> Schur<CAP> {
    /// Storage for an m × m decomposition.
    pub(crate) fn zeros(m: usize) -> Result<Self, LinalgError> {
        Ok(Schur {
            t: ComplexMatrix::zeros(m, m)?,
            q: ComplexMatrix::zeros(m, m)?,
            scale: [1.0; CAP],
        })
    }

    /// Decompose `a` (square, finite) into this storage; `work` is scratch of a's size.
    pub(crate) fn decompose(
        &mut self,
        a: &RealMatrix<CAP>,
        work: &mut RealMatrix<CAP>,
        work_q: &mut RealMatrix<CAP>,
    ) -> Result<(), LinalgError> {
        work.copy_from(a);
        balance(work, &mut self.scale);
        hessenberg(work, work_q);
        self.t = work.to_complex();
        self.q = work_q.to_complex();
        triangularize(&mut self.t, Some(&mut self.q))
    }
}
