//! The bounds of the projected fast path (`projected.rs`, whose module docs hold the proof):
//! the coefficients b_{k,j,i} of one state, made from the per-model magnitudes |W| and |J|
//! ([`Magnitudes`]), and the bounds of |d|, |d'|, |d''| over an interval or a half-line.

use super::complex::Complex;
use super::modal::ModalExponential;
use super::projected::{BOUND_MARGIN, ProjectedBound, ProjectedMotion};
use crate::math;

/// |W| and the near-diagonal |J| of a projection, computed once (they are the same for every
/// state; each costs a `hypot`): the same values [`ProjectedMotion::set_state`] would compute.
#[derive(Clone, Debug)]
pub(super) struct Magnitudes<const CAP: usize> {
    /// |W| entrywise, rows x and y.
    w_abs: [[f64; CAP]; 2],
    /// ‖(|W_xp|, |W_yp|)‖₂ per position p (a 1 × 1 block's projection norm).
    w_norm: [f64; CAP],
    /// |J_pp| per position.
    j_diag: [f64; CAP],
    /// |J_{p,p+1}| per position (0 past the last).
    j_next: [f64; CAP],
    /// Per block: its growth rate α (the largest real part of its eigenvalues).
    growth: [f64; CAP],
}

impl<const CAP: usize> Magnitudes<CAP> {
    pub(super) fn of(modal: &ModalExponential<CAP>, w: &[[Complex; CAP]; 2]) -> Self {
        let mut mag = Magnitudes {
            w_abs: [[0.0; CAP]; 2],
            w_norm: [0.0; CAP],
            j_diag: [0.0; CAP],
            j_next: [0.0; CAP],
            growth: [0.0; CAP],
        };
        for (k, g) in mag.growth.iter_mut().enumerate().take(modal.blocks.count) {
            *g = growth_rate(modal, modal.blocks.range(k));
        }
        for (abs, row) in mag.w_abs.iter_mut().zip(w) {
            for (a, z) in abs.iter_mut().zip(row) {
                *a = z.abs();
            }
        }
        let [ax, ay] = &mag.w_abs;
        for (p, n) in mag.w_norm.iter_mut().enumerate().take(modal.dim()) {
            *n = math::hypot(
                ax.get(p).copied().unwrap_or(0.0),
                ay.get(p).copied().unwrap_or(0.0),
            );
        }
        for (p, (d, e)) in mag
            .j_diag
            .iter_mut()
            .zip(mag.j_next.iter_mut())
            .enumerate()
            .take(modal.dim())
        {
            *d = modal.j.get(p, p).abs();
            *e = modal.j.get(p, p + 1).abs();
        }
        mag
    }

    /// |J_ab| (kept for b = a, a + 1; computed otherwise).
    #[inline]
    fn j_at(&self, modal: &ModalExponential<CAP>, a: usize, b: usize) -> f64 {
        let kept = if b == a {
            self.j_diag.get(a)
        } else if b == a + 1 {
            self.j_next.get(a)
        } else {
            None
        };
        kept.copied().unwrap_or_else(|| modal.j.get(a, b).abs())
    }
}

impl<const CAP: usize> ProjectedMotion<CAP> {
    /// The 1 × 1 blocks' amplitudes u and the bound coefficients b_{k,j,i} of the current c
    /// (module docs), from the per-model magnitudes |W|, |J| kept in [`Magnitudes`]: the only
    /// magnitudes computed per state are |c|'s and the final norms.
    pub(super) fn prepare(&mut self, modal: &ModalExponential<CAP>) {
        let [wx, wy] = &self.w;
        let mag = &self.magnitudes;
        for k in 0..modal.blocks.count {
            let range = modal.blocks.range(k);
            let start = range.start;
            let weight = self.weights.weight.get(k).copied().unwrap_or(1.0);
            if weight == 0.0 {
                for p in range {
                    if let Some(b) = self.coefficients.get_mut(p) {
                        *b = [0.0; 3];
                    }
                }
                continue;
            }
            if range.len() == 1 {
                let c = self.c.c.get(start).copied().unwrap_or_default();
                let (x, y) = (
                    wx.get(start).copied().unwrap_or_default(),
                    wy.get(start).copied().unwrap_or_default(),
                );
                if let Some(u) = self.u.get_mut(start) {
                    *u = [(x * c).scale(weight), (y * c).scale(weight)];
                }
                let lambda = mag.j_at(modal, start, start);
                let b0 = weight * mag.w_norm.get(start).copied().unwrap_or(f64::INFINITY) * c.abs();
                if let Some(b) = self.coefficients.get_mut(start) {
                    *b = [b0, b0 * lambda, b0 * lambda * lambda];
                }
                continue;
            }
            // v_j = |J|^j |c| (j = 0, 1, 2), then |U|^i v_j projected by |W|.
            let p = range.len();
            let mut v = [[0.0f64; CAP]; 3];
            for (a, va) in v[0].iter_mut().enumerate().take(p) {
                *va = self.c.c.get(start + a).map_or(0.0, |z| z.abs());
            }
            for jd in 1..3 {
                let (prev, next) = v.split_at_mut(jd);
                let (Some(prev), Some(next)) = (prev.last(), next.first_mut()) else {
                    continue;
                };
                for (a, na) in next.iter_mut().enumerate().take(p) {
                    *na = (a..p)
                        .map(|b| {
                            mag.j_at(modal, start + a, start + b)
                                * prev.get(b).copied().unwrap_or(0.0)
                        })
                        .sum();
                }
            }
            let [ax, ay] = &mag.w_abs;
            for i in 0..p {
                let mut b = [0.0; 3];
                for (jd, vj) in v.iter_mut().enumerate() {
                    let (mut sx, mut sy) = (0.0, 0.0);
                    for (a, &va) in vj.iter().enumerate().take(p) {
                        sx += ax.get(start + a).copied().unwrap_or(f64::INFINITY) * va;
                        sy += ay.get(start + a).copied().unwrap_or(f64::INFINITY) * va;
                    }
                    if let Some(bj) = b.get_mut(jd) {
                        *bj = weight * math::hypot(sx, sy);
                    }
                    if i + 1 == p {
                        continue;
                    }
                    // vj ← |U| vj for the next power (in place: row a reads rows > a only).
                    for a in 0..p {
                        let na = (a + 1..p)
                            .map(|bb| {
                                mag.j_at(modal, start + a, start + bb)
                                    * vj.get(bb).copied().unwrap_or(0.0)
                            })
                            .sum();
                        if let Some(x) = vj.get_mut(a) {
                            *x = na;
                        }
                    }
                }
                if let Some(slot) = self.coefficients.get_mut(start + i) {
                    *slot = b;
                }
            }
        }
    }

    /// The bound coefficients of mode `p` (|d|, |d'|, |d''| per unit of its basis); infinite
    /// for a mode the projection does not have (never for the modal form it was made from).
    fn coefficient(&self, p: usize) -> [f64; 3] {
        self.coefficients
            .get(p)
            .copied()
            .unwrap_or([f64::INFINITY; 3])
    }

    /// Upper bounds of |d|, |d'|, |d''| valid for every s in [lo, hi] (module docs: the proof).
    pub fn bound(&self, modal: &ModalExponential<CAP>, lo: f64, hi: f64) -> ProjectedBound {
        let inf = ProjectedBound::UNBOUNDED;
        if !(0.0 <= lo && lo <= hi && hi < f64::INFINITY) {
            return inf;
        }
        let mut sum = [0.0f64; 3];
        for (range, alpha) in self.seen_blocks(modal) {
            let mut poly = [0.0f64; 3];
            for (i, p) in range.enumerate() {
                let b = self.coefficient(p);
                let weight = peak(alpha, i, lo, hi);
                for (acc, bj) in poly.iter_mut().zip(b) {
                    *acc += bj * weight;
                }
            }
            for (acc, pj) in sum.iter_mut().zip(poly) {
                // NaN (0·∞ from an overflowing weight) becomes ∞.
                *acc += if pj.is_nan() { f64::INFINITY } else { pj };
            }
        }
        with_margin(sum)
    }
}

impl<const CAP: usize> ProjectedMotion<CAP> {
    /// Upper bounds of |d|, |d'|, |d''| valid for every s ≥ `lo` (finite, ≥ 0): the bound of
    /// [`Self::bound`] with hi → ∞, finite when every block the projection sees decays or, for
    /// its leading term only (i = 0), stays (Re λ = 0: an undamped mode rings for ever at its
    /// amplitude). A growing mode, or a secular term (i ≥ 1) of an undamped block, with a
    /// nonzero coefficient gives ∞. The switch search stops searching a free flight whose
    /// reach over all later times is inside the clearance.
    pub fn bound_after(&self, modal: &ModalExponential<CAP>, lo: f64) -> ProjectedBound {
        let inf = ProjectedBound::UNBOUNDED;
        if !(0.0..f64::INFINITY).contains(&lo) {
            return inf;
        }
        let mut sum = [0.0f64; 3];
        for (range, alpha) in self.seen_blocks(modal) {
            for (i, p) in range.enumerate() {
                let b = self.coefficient(p);
                if b.iter().all(|&x| x == 0.0) {
                    continue;
                }
                let weight = if alpha < 0.0 {
                    // e^{αs} s^i/i! falls after s = i/(−α): its maximum on [lo, ∞).
                    peak(alpha, i, lo, lo.max(i as f64 / -alpha))
                } else if alpha == 0.0 && i == 0 {
                    1.0
                } else {
                    f64::INFINITY
                };
                for (acc, bj) in sum.iter_mut().zip(b) {
                    let term = bj * weight;
                    *acc += if term.is_nan() { f64::INFINITY } else { term };
                }
            }
        }
        with_margin(sum)
    }
}

impl<const CAP: usize> ProjectedMotion<CAP> {
    /// The blocks the projection sees (nonzero weight): each one's index range and growth
    /// rate α.
    fn seen_blocks<'m>(
        &'m self,
        modal: &'m ModalExponential<CAP>,
    ) -> impl Iterator<Item = (core::ops::Range<usize>, f64)> + 'm {
        (0..modal.blocks.count)
            .filter(|&k| self.weight(k) != 0.0)
            .map(|k| {
                let range = modal.blocks.range(k);
                let alpha = self.magnitudes.growth.get(k).copied();
                (
                    range.clone(),
                    alpha.unwrap_or_else(|| growth_rate(modal, range)),
                )
            })
    }
}

/// The bounds |d|, |d'|, |d''| of summed terms, each raised by the rounding margin.
fn with_margin(sum: [f64; 3]) -> ProjectedBound {
    let up = |x: f64| x * (1.0 + BOUND_MARGIN);
    ProjectedBound {
        value: up(sum[0]),
        rate: up(sum[1]),
        acceleration: up(sum[2]),
    }
}

/// max over s ∈ [lo, hi] of e^{αs} s^i / i! (0 ≤ lo ≤ hi < ∞): for i = 0 at an end; for i ≥ 1
/// the function rises while s < i/(−α) and falls after, so its maximum is at that point clamped
/// into [lo, hi] (at hi when α ≥ 0). Computed with one `exp` and i nonnegative factors; the
/// rounding of the peak's location changes the value only to second order (relative
/// i·(δs/s)² ≤ i·ε²).
fn peak(alpha: f64, i: usize, lo: f64, hi: f64) -> f64 {
    if i == 0 {
        // e^{αs} is monotone: its maximum is at hi when α > 0, else at lo (one `exp`).
        return math::exp(alpha * if alpha > 0.0 { hi } else { lo });
    }
    let at = if alpha < 0.0 {
        let top = i as f64 / -alpha;
        if top < lo {
            lo
        } else if top > hi {
            hi
        } else {
            top
        }
    } else {
        hi
    };
    let mut v = math::exp(alpha * at);
    for k in 1..=i {
        v *= at / k as f64;
    }
    v
}

/// The largest real part of the eigenvalues of a triangular block (rows `range` of the modal
/// form): the block's exponential growth rate in the bound e^{αs} e^{|U|s}.
fn growth_rate<const CAP: usize>(
    modal: &ModalExponential<CAP>,
    range: core::ops::Range<usize>,
) -> f64 {
    range
        .map(|p| modal.j.get(p, p).re)
        .fold(f64::NEG_INFINITY, f64::max)
}
