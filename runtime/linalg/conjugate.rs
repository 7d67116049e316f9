//! The conjugate pairs among a real matrix's modal blocks: what lets the projected fast path
//! (`projected.rs`) evaluate one block of each pair.
//!
//! For a real A the spectrum is closed under conjugation, and the invariant subspace of a
//! cluster's conjugate is the conjugate of the cluster's. For a real state y0 and a real
//! projection B, the part of B e^{As} y0 that a block contributes, W_k e^{J_k s} c_k, does not
//! depend on the basis the modal form chose for its subspace (it is B times the spectral
//! projector's part), so the conjugate block's is its complex conjugate, and the pair's real
//! part is 2 Re(W_k e^{J_k s} c_k): one block evaluated instead of two, exact to rounding (the
//! two computed parts agree to the rounding of S, S⁻¹ and c).
//!
//! A block is paired with another block of the same size whose every eigenvalue is, to
//! [`PAIR_DISTANCE`] relative to ‖J‖, the conjugate of one of its own, and the match is
//! unique; a block whose eigenvalues are real (or that holds a conjugate pair inside it) and a
//! block without a unique match are evaluated as they are (weight 1).

use super::complex::Complex;
use super::modal::ModalExponential;

/// The relative distance below which two eigenvalues count as conjugate (the modal form's
/// eigenvalues are exact to ~ε‖A‖·cond; its clusters are 1e-6‖T‖ apart or merged).
pub(crate) const PAIR_DISTANCE: f64 = 1e-9;

/// How each block enters the real part of a projected sum: weight 2 for the first block of a
/// conjugate pair, 0 for its partner (not evaluated), 1 otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BlockWeights<const CAP: usize> {
    pub(crate) weight: [f64; CAP],
}

impl<const CAP: usize> BlockWeights<CAP> {
    /// Every block as it is (weight 1).
    pub(crate) const ONE: BlockWeights<CAP> = BlockWeights { weight: [1.0; CAP] };

    /// The weights of `modal`'s blocks (module docs).
    pub(crate) fn of(modal: &ModalExponential<CAP>) -> Self {
        let mut w = Self::ONE;
        let count = modal.blocks.count;
        let scale = (0..modal.dim())
            .map(|i| modal.j.get(i, i).abs())
            .fold(0.0, f64::max);
        let tol = PAIR_DISTANCE * scale.max(f64::MIN_POSITIVE);
        for k in 0..count {
            if w.weight.get(k).copied() != Some(1.0) || conjugate_of(modal, k, k, tol) {
                continue;
            }
            let mut partner = None;
            let mut matches = 0;
            for other in (k + 1)..count {
                if w.weight.get(other).copied() == Some(1.0) && conjugate_of(modal, k, other, tol) {
                    partner = Some(other);
                    matches += 1;
                }
            }
            if let (Some(p), 1) = (partner, matches) {
                if let Some(x) = w.weight.get_mut(k) {
                    *x = 2.0;
                }
                if let Some(x) = w.weight.get_mut(p) {
                    *x = 0.0;
                }
            }
        }
        w
    }
}

/// Whether block `b`'s eigenvalues are the conjugates of block `a`'s (same size, each of `a`'s
/// conjugates within `tol` of one of `b`'s and each of `b`'s of one of `a`'s conjugates). With
/// `a` = `b`: whether the block is its own conjugate (real eigenvalues, or a pair inside it).
fn conjugate_of<const CAP: usize>(
    modal: &ModalExponential<CAP>,
    a: usize,
    b: usize,
    tol: f64,
) -> bool {
    let (ra, rb) = (modal.blocks.range(a), modal.blocks.range(b));
    if ra.len() != rb.len() || ra.is_empty() {
        return false;
    }
    let eig = |i: usize| modal.j.get(i, i);
    let near = |x: Complex, y: Complex| (x - y.conj()).abs() <= tol;
    ra.clone().all(|i| rb.clone().any(|k| near(eig(i), eig(k))))
        && rb.clone().all(|k| ra.clone().any(|i| near(eig(i), eig(k))))
}
