//! The projected fast path: d(s) = B e^{As} y0 for a fixed 2 × m matrix B (the rub station's
//! relative displacement), with d'(s), d''(s), and rigorous bounds of |d|, |d'|, |d''| over an
//! interval — what a switch search needs, at O(m) per evaluation.
//!
//! With W = B S (2 × m, once per B) and c = S⁻¹ y0 (once per state),
//! d(s) = Re Σ_k W_k e^{J_k s} c_k. A 1 × 1 block contributes Re(u_k e^{λ_k s}) with the
//! 2-vector u_k = W_k c_k precomputed, so an evaluation costs one complex exponential per
//! block and O(m) products; a larger block (a cluster) applies its exponential to c_k
//! (`block.rs`) and projects it. The derivatives multiply by J (λ_k for a 1 × 1 block).
//!
//! # Why the bounds hold (the proof the switch search rests on)
//! Let T = Λ + U be one upper triangular block (Λ its diagonal, U the strictly upper part),
//! α = max_i Re λ_i. **Claim:** entrywise |e^{Ts}| ≤ e^{αs} e^{|U|s} for s ≥ 0.
//! *Proof:* e^{Ts} = lim_{n→∞} (I + Ts/n)^n. Entrywise |I + Ts/n| ≤ |I + Λs/n| + |U|s/n and
//! |1 + λ_i s/n| ≤ 1 + αs/n + |λ_i|²s²/n² for n large, so |I + Ts/n| ≤ (1 + αs/n + c/n²) I +
//! |U| s/n with every entry ≥ 0. Products of nonnegative matrices are monotone in their
//! factors, so |(I + Ts/n)^n| ≤ ((1 + αs/n + c/n²) I + |U|s/n)^n = (1 + αs/n + c/n²)^n
//! (I + |U|s/(n + αs + c/n))^n (the identity commutes), whose limit is e^{αs} e^{|U|s}. ∎
//! Since |U| is nilpotent (strictly upper, size p), e^{|U|s} = Σ_{i<p} |U|^i s^i/i!.
//!
//! **Conjugate pairs.** d is real, so the parts of two conjugate blocks are conjugate
//! (`conjugate.rs`): the first block of each pair is evaluated with weight 2 (u_k and the bound
//! coefficients doubled, exactly) and its partner not at all; the bounds below are of that
//! weighted sum, the function the evaluations compute (|2 Re z| ≤ 2|z|).
//!
//! The j-th derivative of block k's part is W_k e^{J_k s} J_k^j c_k, so componentwise
//! |d^{(j)}_k(s)| ≤ |W_k| e^{α_k s} e^{|U_k| s} |J_k|^j |c_k| (|Re z| ≤ |z|, |Pv| ≤ |P||v|),
//! and by the triangle inequality for the Euclidean norm of nonnegative 2-vectors
//!
//! ```text
//! |d^{(j)}(s)| ≤ Σ_k e^{α_k s} Σ_{i<p_k} b_{k,j,i} s^i/i!,   b_{k,j,i} = ‖ |W_k| |U_k|^i |J_k|^j |c_k| ‖₂.
//! ```
//!
//! Over s ∈ [lo, hi] (0 ≤ lo ≤ hi < ∞) the bound is Σ_k Σ_i b_{k,j,i} max_s e^{α_k s} s^i/i!,
//! each maximum in closed form (at an end, or at s = i/(−α_k) when α_k < 0 and that lies
//! inside: [`peak`]). For a 1 × 1 block it is |u_k||λ_k|^j max(e^{Re λ_k lo}, e^{Re λ_k hi}):
//! the mode's exact amplitude.
//!
//! **Rounding.** Every quantity in the bound is computed from the stored W, J, c with
//! nonnegative operands only (absolute values, products, sums, libm's `exp` within 1 ulp), so
//! its computed value is within a relative γ_K = Kε/(1 − Kε) of the exact one, K ≤ 4m + 40
//! operations along any path; the result is multiplied by 1 + [`BOUND_MARGIN`] = 1 + 1e-12,
//! which covers K up to 9000 (m ≤ 2000). The bound is of the function the evaluations compute
//! (the stored modal form, exact to rounding as `modal.rs` states), so a search that
//! evaluates d and bounds it on the same data never misses a sign change for want of rigor.
//! Invalid intervals (lo > hi, NaN, hi infinite) give an infinite bound, never NaN.

use super::block::{exp_pair, scale_by_exp};
use super::complex::Complex;
use super::conjugate::BlockWeights;
use super::error::LinalgError;
use super::modal::{ModalExponential, ModalVector, span};
use super::projected_bound::Magnitudes;

/// Relative margin the bounds carry for rounding (module docs).
pub const BOUND_MARGIN: f64 = 1e-12;

/// d(s), d'(s), d''(s) at one s.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ProjectedPoint {
    /// d = B y(s).
    pub value: [f64; 2],
    /// d' = B y'(s).
    pub rate: [f64; 2],
    /// d'' = B y''(s).
    pub acceleration: [f64; 2],
}

/// Upper bounds of |d|, |d'|, |d''| (Euclidean norms) valid at every s of an interval.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ProjectedBound {
    /// ≥ |d(s)|.
    pub value: f64,
    /// ≥ |d'(s)|.
    pub rate: f64,
    /// ≥ |d''(s)|.
    pub acceleration: f64,
}

impl ProjectedBound {
    /// No bound (every entry infinite): what an interval the bounds do not cover gets.
    pub const UNBOUNDED: ProjectedBound = ProjectedBound {
        value: f64::INFINITY,
        rate: f64::INFINITY,
        acceleration: f64::INFINITY,
    };
}

/// The projection W = B S of a fixed 2 × m matrix B, and one state's modal data: evaluates
/// d(s) = B e^{As} y0 and its bounds with the [`ModalExponential`] it was made from (passed to
/// each call, so this stays small plain data: 2·16·CAP + 16·CAP + 32·CAP + 24·CAP + 40·CAP
/// bytes).
#[derive(Clone, Debug)]
pub struct ProjectedMotion<const CAP: usize> {
    pub(super) m: usize,
    /// W = B S, rows x and y.
    pub(super) w: [[Complex; CAP]; 2],
    /// c = S⁻¹ y0.
    pub(super) c: ModalVector<CAP>,
    /// Per position p of a 1 × 1 block: u = W_p c_p; unused in larger blocks.
    pub(super) u: [[Complex; 2]; CAP],
    /// Per position: the bound coefficients b_{k,j,i} for j = 0..3, stored at position
    /// start_k + i of block k (times the block's weight).
    pub(super) coefficients: [[f64; 3]; CAP],
    /// Per block: 2 for the first of a conjugate pair, 0 for its partner (never evaluated nor
    /// bounded), 1 otherwise (`conjugate.rs`): d is real, so a pair's parts are conjugate.
    pub(super) weights: BlockWeights<CAP>,
    /// The magnitudes of W and J the bound coefficients are made of: per model, not per state.
    pub(super) magnitudes: Magnitudes<CAP>,
}

impl<const CAP: usize> ProjectedMotion<CAP> {
    /// The projection of B = [`bx`; `by`] (each m entries, finite) for `modal`, at the zero
    /// state (set one with [`Self::set_state`]).
    pub fn new(modal: &ModalExponential<CAP>, bx: &[f64], by: &[f64]) -> Result<Self, LinalgError> {
        let m = modal.dim();
        let mut w = [[Complex::ZERO; CAP]; 2];
        for (row, b) in w.iter_mut().zip([bx, by]) {
            if b.len() != m {
                return Err(LinalgError::Shape {
                    what: "projection row",
                    got: b.len(),
                    expected: m,
                });
            }
            if let Some(i) = b.iter().position(|v| !v.is_finite()) {
                return Err(LinalgError::NonFinite {
                    what: "projection row",
                    row: i,
                    col: 0,
                });
            }
            for (p, wp) in row.iter_mut().enumerate().take(m) {
                *wp = b.iter().enumerate().fold(Complex::ZERO, |acc, (i, &bi)| {
                    acc + modal.s.get(i, p).scale(bi)
                });
            }
        }
        Ok(ProjectedMotion {
            m,
            c: ModalVector {
                c: [Complex::ZERO; CAP],
                m,
            },
            u: [[Complex::ZERO; 2]; CAP],
            coefficients: [[0.0; 3]; CAP],
            weights: BlockWeights::of(modal),
            magnitudes: Magnitudes::of(modal, &w),
            w,
        })
    }

    /// Start from the state y0 (m entries, finite): c = S⁻¹ y0, the 1 × 1 blocks' amplitudes
    /// and the bound coefficients. O(m²) (O(p³) more per cluster of size p).
    pub fn set_state(
        &mut self,
        modal: &ModalExponential<CAP>,
        y0: &[f64],
    ) -> Result<(), LinalgError> {
        if modal.dim() != self.m {
            return Err(LinalgError::Shape {
                what: "modal exponential",
                got: modal.dim(),
                expected: self.m,
            });
        }
        self.c = modal.modal_coordinates(y0)?;
        self.prepare(modal);
        Ok(())
    }

    /// The modal coordinates of the current state.
    pub fn modal_coordinates(&self) -> &ModalVector<CAP> {
        &self.c
    }

    /// d, d', d'' at s ≥ 0 (a negative or NaN s counts as 0; s must be finite for a finite
    /// answer).
    pub fn at(&self, modal: &ModalExponential<CAP>, s: f64) -> ProjectedPoint {
        let [value, rate, acceleration] = self.derivatives::<3, false>(modal, s);
        ProjectedPoint {
            value,
            rate,
            acceleration,
        }
    }

    /// d and d' at s ≥ 0: [`Self::at`] without d'' (what a switch function's value and rate
    /// need), the same values to the bit.
    pub fn value_and_rate(&self, modal: &ModalExponential<CAP>, s: f64) -> ([f64; 2], [f64; 2]) {
        let [value, rate] = self.derivatives::<2, false>(modal, s);
        (value, rate)
    }

    /// d and d' at s = 0: [`Self::value_and_rate`] there without exponentials (e^{J·0} c = c
    /// exactly, as the closed forms give it, to the sign of a zero).
    pub fn value_and_rate_at_start(&self, modal: &ModalExponential<CAP>) -> ([f64; 2], [f64; 2]) {
        let [value, rate] = self.derivatives::<2, true>(modal, 0.0);
        (value, rate)
    }

    /// d^{(j)}(s) for j < N (N ≤ 3); at s = 0 (`START`) without exponentials.
    #[inline(always)]
    fn derivatives<const N: usize, const START: bool>(
        &self,
        modal: &ModalExponential<CAP>,
        s: f64,
    ) -> [[f64; 2]; N] {
        let s = if START { 0.0 } else { span(s) };
        let at_start = START;
        let mut out = [[Complex::ZERO; 2]; N];
        let [wx, wy] = &self.w;
        for k in 0..modal.blocks.count {
            let range = modal.blocks.range(k);
            let weight = self.weight(k);
            if weight == 0.0 {
                continue;
            }
            if range.len() == 1 {
                let p = range.start;
                let lambda = modal.j.get(p, p);
                let e = if at_start {
                    Complex::ONE
                } else {
                    scale_by_exp(Complex::ONE, lambda.scale(s))
                };
                let [ux, uy] = self.u.get(p).copied().unwrap_or_default();
                // u e^{λs}, then each derivative times λ.
                let (mut x, mut y) = (ux * e, uy * e);
                for (j, o) in out.iter_mut().enumerate() {
                    o[0] += x;
                    o[1] += y;
                    if j + 1 < N {
                        (x, y) = (x * lambda, y * lambda);
                    }
                }
                continue;
            }
            if range.len() == 2 {
                // The 2 × 2 block (an isotropic rotor's repeated pair) in closed form, with the
                // general path's operations on two entries and no CAP-sized work arrays.
                let (i, k) = (range.start, range.start + 1);
                let (a, u, b) = (modal.j.get(i, i), modal.j.get(i, k), modal.j.get(k, k));
                let c = |p: usize| self.c.c.get(p).copied().unwrap_or_default();
                let w = |row: &[Complex; CAP], p: usize| row.get(p).copied().unwrap_or_default();
                let (mut x0, mut x1) = if at_start {
                    (c(i), c(k))
                } else {
                    exp_pair(a, u, b, s, (c(i), c(k)))
                };
                for (j, o) in out.iter_mut().enumerate() {
                    let mut px = Complex::ZERO;
                    let mut py = Complex::ZERO;
                    px += w(wx, i) * x0;
                    py += w(wy, i) * x0;
                    px += w(wx, k) * x1;
                    py += w(wy, k) * x1;
                    o[0] += px.scale(weight);
                    o[1] += py.scale(weight);
                    if j + 1 < N {
                        (x0, x1) = (Complex::ZERO + a * x0 + u * x1, Complex::ZERO + b * x1);
                    }
                }
                continue;
            }
            let mut x = [Complex::ZERO; CAP];
            let mut work = [Complex::ZERO; CAP];
            for (xa, &ca) in x
                .iter_mut()
                .zip(self.c.c.iter().skip(range.start))
                .take(range.len())
            {
                *xa = ca;
            }
            if !at_start {
                let shift = modal.shifts.get(k).copied().unwrap_or_default();
                super::block::apply_block_exp(&modal.j, range.clone(), shift, s, &mut x, &mut work);
            }
            // x, Jx, J²x on the block, each projected.
            let mut cur = x;
            for (j, o) in out.iter_mut().enumerate() {
                let mut px = Complex::ZERO;
                let mut py = Complex::ZERO;
                for (a, &ca) in cur.iter().enumerate().take(range.len()) {
                    px += wx.get(range.start + a).copied().unwrap_or_default() * ca;
                    py += wy.get(range.start + a).copied().unwrap_or_default() * ca;
                }
                o[0] += px.scale(weight);
                o[1] += py.scale(weight);
                if j + 1 == N {
                    break;
                }
                let mut next = [Complex::ZERO; CAP];
                for (a, na) in next.iter_mut().enumerate().take(range.len()) {
                    *na = (a..range.len()).fold(Complex::ZERO, |acc, b| {
                        acc + modal.j.get(range.start + a, range.start + b)
                            * cur.get(b).copied().unwrap_or_default()
                    });
                }
                cur = next;
            }
        }
        out.map(|z| [z[0].re, z[1].re])
    }

    /// The full state y(s) = e^{As} y0 (`out`: m entries; s ≥ 0, a negative s counts as 0) of
    /// the state set last: Σ_k w_k Re(S_k e^{J_k s} c_k) with the blocks' conjugate-pair
    /// weights, so a pair's partner is neither propagated nor projected (`conjugate.rs`: its
    /// part is the conjugate of the first's), and only real parts are formed. Equal to
    /// [`ModalExponential::state`] to rounding.
    pub fn state(&self, modal: &ModalExponential<CAP>, s: f64, out: &mut [f64]) {
        let s = span(s);
        let mut x = [Complex::ZERO; CAP];
        let mut work = [Complex::ZERO; CAP];
        for (xa, &ca) in x.iter_mut().zip(self.c.c.iter()) {
            *xa = ca;
        }
        for k in 0..modal.blocks.count {
            let range = modal.blocks.range(k);
            let weight = self.weight(k);
            if let Some(xs) = x.get_mut(range.clone()) {
                if weight == 0.0 {
                    xs.iter_mut().for_each(|v| *v = Complex::ZERO);
                    continue;
                }
                let shift = modal.shifts.get(k).copied().unwrap_or_default();
                super::block::apply_block_exp(&modal.j, range, shift, s, xs, &mut work);
                if weight != 1.0 {
                    xs.iter_mut().for_each(|v| *v = v.scale(weight));
                }
            }
        }
        for (i, o) in out.iter_mut().enumerate().take(self.m) {
            // Re(Σ_p S_ip x_p), the partners' x_p being 0.
            *o = modal
                .s
                .row(i)
                .iter()
                .zip(x.iter())
                .fold(0.0, |acc, (sp, xp)| acc + (sp.re * xp.re - sp.im * xp.im));
        }
    }

    /// Block k's weight (2: a pair's first, 0: its partner, 1: alone).
    #[inline]
    pub(super) fn weight(&self, k: usize) -> f64 {
        self.weights.weight.get(k).copied().unwrap_or(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::RealMatrix;

    /// The weighted state (a pair's partner not evaluated) equals the full modal state to
    /// rounding (‖y0‖ ≈ 1.4): an anisotropic 2-DOF rotor with cross-coupling (complex pairs),
    /// an isotropic one (repeated pairs: 2 × 2 blocks), and real eigenvalues (overdamped).
    #[test]
    fn the_weighted_state_is_the_full_state() {
        let rotor = |k: (f64, f64), kxy: f64, c: f64| {
            RealMatrix::<8>::from_rows(&[
                &[0.0, 0.0, 1.0, 0.0],
                &[0.0, 0.0, 0.0, 1.0],
                &[-k.0, -kxy, -c, 0.0],
                &[kxy, -k.1, 0.0, -c],
            ])
            .unwrap()
        };
        for a in [
            rotor((1.0, 1.7), 0.3, 0.1),
            rotor((1.0, 1.0), 0.0, 0.25),
            rotor((1.0, 2.0), 0.0, 5.0),
        ] {
            let e = ModalExponential::new(&a).unwrap();
            let mut motion =
                ProjectedMotion::new(&e, &[1.0, 0.0, 0.0, 0.0], &[0.0, 1.0, 0.0, 0.0]).unwrap();
            let y0 = [0.3, -0.7, 1.1, 0.4];
            motion.set_state(&e, &y0).unwrap();
            for s in [0.0, 0.01, 0.7, 3.0, 40.0] {
                let (mut full, mut weighted) = ([0.0; 4], [0.0; 4]);
                e.state(motion.modal_coordinates(), s, &mut full);
                motion.state(&e, s, &mut weighted);
                // Both are exact to rounding relative to ‖y0‖, plus the eigenvalues' rounding
                // turned into phase over the span (≈ s‖A‖ε; `modal.rs`).
                let size = (1.0 + 2.0 * s) * 1.1;
                for (f, w) in full.iter().zip(&weighted) {
                    assert!((f - w).abs() <= 1e-14 * size, "s = {s}: {f} vs {w}");
                }
            }
        }
    }
}
