//! From the Schur form to the block-diagonal modal form: clusters of eigenvalues made
//! contiguous by swaps of adjacent diagonal entries, then decoupled by triangular Sylvester
//! equations (Golub & Van Loan, 4th ed., §7.6.3, Algorithm 7.6.3 "block diagonalization";
//! Bavely & Stewart 1979 grow a block until its decoupling is well conditioned).
//!
//! **The clustering rule.** Two eigenvalues start in one cluster when they are within
//! [`MERGE_DISTANCE`]·‖T‖_max of each other (closure over chains: repeated and defective
//! eigenvalues, which rounding separates by up to ~ε^{1/k}‖T‖ for a Jordan block of size k ≤ 3).
//! Then the decoupling is tried; when a Sylvester solution Z (T_ii Z − Z T_jj = −T_ij) has an
//! entry larger than [`MAX_COUPLING`] (or is not finite) the two clusters it couples are merged
//! and the decoupling is redone from the Schur form. The transformation Y (unit block upper
//! triangular, its off-diagonal blocks the Z's) then has entries ≤ [`MAX_COUPLING`], which
//! bounds the rounding its use adds: e^{As}y loses at most ~‖Z‖·ε relative, so ≤ 10·ε.
//! At most m − 1 merges happen (one block at worst), each costing one O(m³) decoupling.

use super::complex::Complex;
use super::dense::ComplexMatrix;
use super::schur::swap_diagonal;

/// Eigenvalues closer than this times ‖T‖_max start in one cluster.
pub const MERGE_DISTANCE: f64 = 1e-6;
/// The largest entry a Sylvester solution may have before its two clusters are merged.
pub const MAX_COUPLING: f64 = 10.0;

/// A partition of 0..m into sets (union–find over the Schur form's diagonal positions).
#[derive(Clone, Debug)]
pub(crate) struct Clusters<const CAP: usize> {
    parent: [usize; CAP],
}

impl<const CAP: usize> Clusters<CAP> {
    /// Every position alone.
    pub(crate) fn singletons() -> Self {
        let mut parent = [0; CAP];
        parent.iter_mut().enumerate().for_each(|(i, p)| *p = i);
        Clusters { parent }
    }

    /// The set's representative.
    pub(crate) fn find(&self, mut i: usize) -> usize {
        // Paths are short (m ≤ CAP steps at worst); no compression needed for correctness.
        for _ in 0..CAP {
            match self.parent.get(i) {
                Some(&p) if p != i => i = p,
                _ => break,
            }
        }
        i
    }

    /// Merge the sets of a and b.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb
            && let Some(p) = self.parent.get_mut(ra.max(rb))
        {
            *p = ra.min(rb);
        }
    }
}

/// Reorder the Schur form (t, q) so that each cluster is contiguous, clusters in the order of
/// their first member, members in diagonal order. `origin[p]` is the original diagonal position
/// of the eigenvalue now at p (written here).
pub(crate) fn make_contiguous<const CAP: usize>(
    t: &mut ComplexMatrix<CAP>,
    q: &mut ComplexMatrix<CAP>,
    clusters: &Clusters<CAP>,
    origin: &mut [usize; CAP],
) {
    let m = t.rows();
    origin.iter_mut().enumerate().for_each(|(i, o)| *o = i);
    let mut placed = 0;
    for first in 0..m {
        // Clusters in order of their smallest member: `first` is a representative's position
        // when find(first) == first (the union keeps the smaller index as root).
        if clusters.find(first) != first {
            continue;
        }
        for member in first..m {
            if clusters.find(member) != first {
                continue;
            }
            // Move `member` from its current position down to `placed`.
            let Some(at) = (placed..m).find(|&p| origin.get(p) == Some(&member)) else {
                continue;
            };
            for r in (placed..at).rev() {
                swap_diagonal(t, q, r);
                origin.swap(r, r + 1);
            }
            placed += 1;
        }
    }
}

/// The contiguous blocks after [`make_contiguous`]: `starts[k]` for k < count, ending at the
/// next start or m.
#[derive(Clone, Debug)]
pub(crate) struct Blocks<const CAP: usize> {
    pub(crate) starts: [usize; CAP],
    pub(crate) count: usize,
    pub(crate) m: usize,
}

impl<const CAP: usize> Blocks<CAP> {
    /// The blocks of the reordered form.
    pub(crate) fn of(clusters: &Clusters<CAP>, origin: &[usize; CAP], m: usize) -> Self {
        let mut starts = [0; CAP];
        let mut count = 0;
        let mut last = usize::MAX;
        for p in 0..m {
            let root = clusters.find(origin.get(p).copied().unwrap_or(p));
            if root != last {
                if let Some(s) = starts.get_mut(count) {
                    *s = p;
                }
                count += 1;
                last = root;
            }
        }
        Blocks { starts, count, m }
    }

    /// Block k's range.
    pub(crate) fn range(&self, k: usize) -> core::ops::Range<usize> {
        let start = self.starts.get(k).copied().unwrap_or(self.m);
        let end = if k + 1 < self.count {
            self.starts.get(k + 1).copied().unwrap_or(self.m)
        } else {
            self.m
        };
        start..end
    }
}

/// Decouple the blocks of the triangular `t` (block diagonalization, Golub & Van Loan
/// Algorithm 7.6.3), updating S ← S Y (`s`, holding Q on entry) and R ← Y⁻¹ R (`r`, holding
/// Q^H on entry), so that afterwards t = Y⁻¹ T Y is block diagonal, S = QY and R = S⁻¹.
/// Stops at the first Sylvester solution with an entry above [`MAX_COUPLING`] (or not finite)
/// and returns the pair of positions, one in each of its two blocks, of the closest
/// eigenvalues: those clusters are to be merged.
pub(crate) fn decouple<const CAP: usize>(
    t: &mut ComplexMatrix<CAP>,
    s: &mut ComplexMatrix<CAP>,
    r: &mut ComplexMatrix<CAP>,
    blocks: &Blocks<CAP>,
) -> Option<(usize, usize)> {
    let m = t.rows();
    for jb in 1..blocks.count {
        let jr = blocks.range(jb);
        for ib in 0..jb {
            let ir = blocks.range(ib);
            if !solve_sylvester(t, ir.clone(), jr.clone()) {
                return Some(closest(t, ir, jr));
            }
            // T_ik −= Z T_jk for the blocks k right of j (Z sits in T_ij).
            for i in ir.clone() {
                for c in jr.end..m {
                    let mut acc = t.get(i, c);
                    for l in jr.clone() {
                        acc -= t.get(i, l) * t.get(l, c);
                    }
                    t.set(i, c, acc);
                }
            }
            // S_:,j += S_:,i Z (every row).
            for row in 0..m {
                for l in jr.clone() {
                    let mut acc = s.get(row, l);
                    for i in ir.clone() {
                        acc += s.get(row, i) * t.get(i, l);
                    }
                    s.set(row, l, acc);
                }
            }
            // R_i,: −= Z R_j,: (every column).
            for i in ir.clone() {
                for l in jr.clone() {
                    let z = t.get(i, l);
                    if z == Complex::ZERO {
                        continue;
                    }
                    if let Some((ri, rl)) = r.two_rows_mut(i, l) {
                        super::dense::axpy(-z, rl, ri);
                    }
                }
            }
            for i in ir.clone() {
                for l in jr.clone() {
                    t.set(i, l, Complex::ZERO);
                }
            }
        }
    }
    None
}

/// Solve T_ii Z − Z T_jj = −T_ij in place (Z overwrites T_ij), column by column with back
/// substitution (both blocks upper triangular: LAPACK `ztrsyl`'s order). False when an entry
/// of Z exceeds [`MAX_COUPLING`] or is not finite (the clusters are too close to decouple).
fn solve_sylvester<const CAP: usize>(
    t: &mut ComplexMatrix<CAP>,
    ir: core::ops::Range<usize>,
    jr: core::ops::Range<usize>,
) -> bool {
    for l in jr.clone() {
        let tll = t.get(l, l);
        // rhs = −T_i,l + Σ_{r<l in j} Z_i,r T_r,l.
        for i in ir.clone() {
            let mut acc = -t.get(i, l);
            for rr in jr.start..l {
                acc += t.get(i, rr) * t.get(rr, l);
            }
            t.set(i, l, acc);
        }
        // (T_ii − t_ll I) z = rhs, back substitution.
        for i in ir.clone().rev() {
            let mut acc = t.get(i, l);
            for c in i + 1..ir.end {
                acc -= t.get(i, c) * t.get(c, l);
            }
            let d = t.get(i, i) - tll;
            let z = acc / d;
            if !(z.is_finite() && z.abs1() <= MAX_COUPLING) {
                return false;
            }
            t.set(i, l, z);
        }
    }
    true
}

/// The positions (one in each range) of the two closest diagonal entries.
fn closest<const CAP: usize>(
    t: &ComplexMatrix<CAP>,
    ir: core::ops::Range<usize>,
    jr: core::ops::Range<usize>,
) -> (usize, usize) {
    let mut best = (ir.start, jr.start, f64::INFINITY);
    for i in ir {
        for j in jr.clone() {
            let d = (t.get(i, i) - t.get(j, j)).abs();
            if d < best.2 {
                best = (i, j, d);
            }
        }
    }
    (best.0, best.1)
}
