//! The exponential e^{As} of a real m × m matrix in a stable modal form: A = S J S⁻¹ with J
//! block diagonal, each block J_k upper triangular holding one cluster of eigenvalues, and S
//! well conditioned, so that y(s) = e^{As} y0 = S e^{Js} S⁻¹ y0 is exact to rounding for every
//! s ≥ 0 and every A — distinct, repeated, defective and near-defective eigenvalues alike.
//!
//! The route (Golub & Van Loan, *Matrix Computations*, 4th ed.): balancing and Hessenberg
//! reduction (`hessenberg.rs`, §7.4), the complex Schur form by shifted QR (`schur.rs`, §7.5),
//! clusters made contiguous by swaps and decoupled by Sylvester equations (`cluster.rs`,
//! §7.6.3), then each block's exponential applied to a vector (`block.rs`). With D the
//! balancing, Q the Schur vectors and Y the decoupling: S = D Q Y, S⁻¹ = Y⁻¹ Q^H D⁻¹.
//!
//! **Accuracy** (`docs/MODEL.md`, "Linear algebra for matrix models"). Every step is backward
//! stable except the decoupling, whose transformation has entries ≤ 10 by the clustering rule;
//! the error of y(s) is ~ c·m·ε·cond(S) relative to ‖e^{As}‖·‖y0‖ plus the conditioning of
//! the problem itself (a perturbation δA of A moves e^{As} by ~ s‖δA‖ relative: over long
//! spans the eigenvalues' rounding, ~ε‖A‖, becomes s‖A‖ε — any method in f64 has it).
//! Measured against nalgebra's `exp` (`tests/linalg.rs`).
//!
//! **Long spans.** A block's decay e^{Re σ s} is applied last as a scalar (`block.rs`), so decay
//! underflows cleanly to 0; only a growing mode can overflow, where the true value does.

use super::block::{BlockShift, apply_block_exp};
use super::cluster::{Blocks, Clusters, MERGE_DISTANCE, decouple, make_contiguous};
use super::complex::Complex;
use super::dense::{ComplexMatrix, RealMatrix, dot};
use super::error::LinalgError;
use super::schur::Schur;

/// Modal coordinates c = S⁻¹ y of a state (the first m entries are used).
#[derive(Clone, Debug, PartialEq)]
pub struct ModalVector<const CAP: usize> {
    pub(crate) c: [Complex; CAP],
    pub(crate) m: usize,
}

impl<const CAP: usize> ModalVector<CAP> {
    /// The coordinates.
    pub fn as_slice(&self) -> &[Complex] {
        self.c.get(..self.m).unwrap_or(&[])
    }
}

/// e^{As} for a real A in the modal form A = S J S⁻¹ (module docs). Plain data; build once per
/// matrix ([`ModalExponential::new`] or, in place, [`ModalExponential::rebuild`]), then
/// evaluate at any s.
///
/// Storage: five complex CAP × CAP matrices (80·CAP² bytes: 5 KiB at CAP = 8, 1.3 MiB at
/// CAP = 128 — box it; building uses about 32·CAP² bytes of stack for work matrices,
/// 512 KiB at CAP = 128).
#[derive(Clone, Debug)]
pub struct ModalExponential<const CAP: usize> {
    m: usize,
    /// The Schur form kept for the retries of the clustering.
    pub(crate) schur: Schur<CAP>,
    /// J, block diagonal (entries outside the blocks are 0).
    pub(crate) j: ComplexMatrix<CAP>,
    /// S = D Q Y.
    pub(crate) s: ComplexMatrix<CAP>,
    /// S⁻¹ = Y⁻¹ Q^H D⁻¹.
    pub(crate) s_inv: ComplexMatrix<CAP>,
    pub(crate) blocks: Blocks<CAP>,
    /// Per block: shift and spread.
    pub(crate) shifts: [BlockShift; CAP],
    /// Per block: index of the block each position belongs to.
    pub(crate) block_of: [usize; CAP],
    condition: f64,
}

impl<const CAP: usize> ModalExponential<CAP> {
    /// The decomposition of `a` (square, finite, m ≤ CAP).
    ///
    /// ```
    /// use rotor_rub::linalg::{ModalExponential, RealMatrix};
    /// // Critical damping, a defective eigenvalue −1: e^{As} = e^{−s} [[1 + s, s], [−s, 1 − s]].
    /// let a = RealMatrix::<2>::from_rows(&[&[0.0, 1.0], &[-1.0, -2.0]]).unwrap();
    /// let e = ModalExponential::new(&a).unwrap();
    /// let c = e.modal_coordinates(&[1.0, 0.0]).unwrap();
    /// let mut y = [0.0; 2];
    /// e.state(&c, 3.0, &mut y);
    /// let x = (-3.0f64).exp();
    /// assert!((y[0] - 4.0 * x).abs() < 1e-15 && (y[1] + 3.0 * x).abs() < 1e-15);
    /// ```
    pub fn new(a: &RealMatrix<CAP>) -> Result<Self, LinalgError> {
        let m = a.check_square("matrix")?;
        let mut e = ModalExponential {
            m,
            schur: Schur::zeros(m)?,
            j: ComplexMatrix::zeros(m, m)?,
            s: ComplexMatrix::zeros(m, m)?,
            s_inv: ComplexMatrix::zeros(m, m)?,
            blocks: Blocks {
                starts: [0; CAP],
                count: 0,
                m,
            },
            shifts: [BlockShift::default(); CAP],
            block_of: [0; CAP],
            condition: 1.0,
        };
        e.rebuild(a)?;
        Ok(e)
    }

    /// Decompose `a` into this storage (a boxed instance is rebuilt without moving it). On an
    /// error the instance is left empty (m = 0).
    pub fn rebuild(&mut self, a: &RealMatrix<CAP>) -> Result<(), LinalgError> {
        self.m = 0;
        let m = a.check_square("matrix")?;
        let mut work = RealMatrix::<CAP>::zeros(m, m)?;
        let mut work_q = RealMatrix::<CAP>::zeros(m, m)?;
        self.schur.decompose(a, &mut work, &mut work_q)?;
        let t_scale = self.schur.t.max_magnitude();
        let mut clusters = Clusters::<CAP>::singletons();
        for i in 0..m {
            for k in 0..i {
                let d = (self.schur.t.get(i, i) - self.schur.t.get(k, k)).abs();
                if d <= MERGE_DISTANCE * t_scale {
                    clusters.union(i, k);
                }
            }
        }
        let mut origin = [0usize; CAP];
        // Each retry merges two clusters: at most m − 1 retries.
        for _ in 0..m.max(1) {
            self.j.copy_from(&self.schur.t);
            self.s.copy_from(&self.schur.q);
            make_contiguous(&mut self.j, &mut self.s, &clusters, &mut origin);
            self.blocks = Blocks::of(&clusters, &origin, m);
            // R = Q^H (of the reordered Q).
            self.s_inv.resize(m, m)?;
            for i in 0..m {
                for k in 0..m {
                    self.s_inv.set(i, k, self.s.get(k, i).conj());
                }
            }
            match decouple(&mut self.j, &mut self.s, &mut self.s_inv, &self.blocks) {
                None => {
                    self.finish(m);
                    return Ok(());
                }
                Some((p, q)) => {
                    let (a, b) = (
                        origin.get(p).copied().unwrap_or(p),
                        origin.get(q).copied().unwrap_or(q),
                    );
                    clusters.union(a, b);
                }
            }
        }
        // Unreachable: with one cluster there is nothing to decouple.
        Err(LinalgError::NoConvergence {
            converged: 0,
            size: m,
        })
    }

    /// Undo the balancing (S ← D S, S⁻¹ ← S⁻¹ D⁻¹) and record the blocks' shifts and the
    /// condition number.
    fn finish(&mut self, m: usize) {
        for i in 0..m {
            let d = self.schur.scale.get(i).copied().unwrap_or(1.0);
            self.s.row_mut(i).iter_mut().for_each(|x| *x = x.scale(d));
            for r in 0..m {
                let v = self.s_inv.get(r, i).scale(1.0 / d);
                self.s_inv.set(r, i, v);
            }
        }
        for k in 0..self.blocks.count {
            let range = self.blocks.range(k);
            if let Some(sh) = self.shifts.get_mut(k) {
                *sh = BlockShift::of(&self.j, range.clone());
            }
            for p in range {
                if let Some(b) = self.block_of.get_mut(p) {
                    *b = k;
                }
            }
        }
        self.condition = self.s.norm1() * self.s_inv.norm1();
        self.m = m;
    }

    /// The dimension m.
    pub fn dim(&self) -> usize {
        self.m
    }

    /// The eigenvalues in J's diagonal order (clusters contiguous).
    pub fn eigenvalues(&self) -> impl Iterator<Item = Complex> + '_ {
        (0..self.m).map(|i| self.j.get(i, i))
    }

    /// The clusters: ranges of J's diagonal positions, one per block.
    pub fn clusters(&self) -> impl Iterator<Item = core::ops::Range<usize>> + '_ {
        (0..self.blocks.count).map(|k| self.blocks.range(k))
    }

    /// cond₁(S) = ‖S‖₁‖S⁻¹‖₁ (exact for the computed S and S⁻¹; |·| = |re| + |im| entries):
    /// the rounding amplification of the modal form.
    pub fn condition(&self) -> f64 {
        self.condition
    }

    /// The modal coordinates c = S⁻¹ y of a real state y (m entries, finite).
    pub fn modal_coordinates(&self, y: &[f64]) -> Result<ModalVector<CAP>, LinalgError> {
        let m = self.m;
        if y.len() != m {
            return Err(LinalgError::Shape {
                what: "state",
                got: y.len(),
                expected: m,
            });
        }
        if let Some(i) = y.iter().position(|v| !v.is_finite()) {
            return Err(LinalgError::NonFinite {
                what: "state",
                row: i,
                col: 0,
            });
        }
        let mut c = [Complex::ZERO; CAP];
        for (i, ci) in c.iter_mut().enumerate().take(m) {
            *ci = self
                .s_inv
                .row(i)
                .iter()
                .zip(y)
                .fold(Complex::ZERO, |acc, (&s, &v)| acc + s.scale(v));
        }
        Ok(ModalVector { c, m })
    }

    /// x = e^{Js} c (modal coordinates at s).
    pub(crate) fn propagate_modal(&self, c: &ModalVector<CAP>, s: f64, x: &mut [Complex; CAP]) {
        let mut work = [Complex::ZERO; CAP];
        x.iter_mut().zip(c.c.iter()).for_each(|(a, &b)| *a = b);
        for k in 0..self.blocks.count {
            let range = self.blocks.range(k);
            let shift = self.shifts.get(k).copied().unwrap_or_default();
            if let Some(xs) = x.get_mut(range.clone()) {
                apply_block_exp(&self.j, range, shift, s, xs, &mut work);
            }
        }
    }

    /// v ← J v (block diagonal product, per block).
    pub(crate) fn apply_j(&self, v: &[Complex; CAP], out: &mut [Complex; CAP]) {
        for k in 0..self.blocks.count {
            let range = self.blocks.range(k);
            for a in range.clone() {
                let row = self.j.row(a);
                let acc = row
                    .iter()
                    .zip(v.iter())
                    .take(range.end)
                    .skip(a)
                    .fold(Complex::ZERO, |acc, (&j, &x)| acc + j * x);
                if let Some(o) = out.get_mut(a) {
                    *o = acc;
                }
            }
        }
    }

    /// y(s) = e^{As} y0 from its modal coordinates c (`out`: m entries). `s` ≥ 0 (a negative s
    /// is treated as 0: e^{As} for s < 0 would grow every decaying mode).
    pub fn state(&self, c: &ModalVector<CAP>, s: f64, out: &mut [f64]) {
        let mut x = [Complex::ZERO; CAP];
        self.propagate_modal(c, span(s), &mut x);
        self.real_image(&x, out);
    }

    /// y(s) and y'(s) = A y(s) (each m entries).
    pub fn state_and_rate(&self, c: &ModalVector<CAP>, s: f64, y: &mut [f64], dy: &mut [f64]) {
        let mut x = [Complex::ZERO; CAP];
        self.propagate_modal(c, span(s), &mut x);
        self.real_image(&x, y);
        let mut jx = [Complex::ZERO; CAP];
        self.apply_j(&x, &mut jx);
        self.real_image(&jx, dy);
    }

    /// out = Re(S x).
    fn real_image(&self, x: &[Complex; CAP], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate().take(self.m) {
            *o = dot(self.s.row(i), x).re;
        }
    }
}

/// s clamped to [0, ∞) (NaN → 0).
#[inline]
pub(crate) fn span(s: f64) -> f64 {
    if s > 0.0 { s } else { 0.0 }
}
