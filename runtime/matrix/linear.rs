//! The linear part of the accelerations, (A y)'s lower half = −M⁻¹K q − M⁻¹(C + ηG) q': what
//! every field evaluation, Taylor order and rate of a matrix model multiplies. A's lower rows
//! are stored by column (`by_column[j][i]` = A[n + i][j]), with each row's nonzero columns
//! listed, for two products with the same sums:
//!
//! - a row at a time over its nonzero entries ([`LinearRows::row_times`]): a rotor's matrices
//!   are sparse in practice (the stator ring's M is diagonal, its K and C couple the rotor's
//!   pair and the ring's pair only: 10 of the 32 entries are nonzero);
//! - every row at once, column by column ([`LinearRows::times`]), for a model that fills
//!   its storage (n = CAP/2, the ring in CAP = 8): every length a constant, the rows' sums side
//!   by side in the vector registers.
//!
//! Both sum each row in column order from −0, as the dense row product does: the terms left
//! out or added as 0·y are ±0, which change a sum that has any nonzero term not at all (y
//! finite), and an all-zero sum only in the sign of its 0.

use crate::linalg::RealMatrix;

/// A's lower rows (one per DOF), by column, with each row's nonzero columns.
#[derive(Clone, Debug)]
pub(crate) struct LinearRows<const CAP: usize> {
    /// Per DOF i: the columns of row n + i holding a nonzero entry, ascending (`counts[i]` used).
    columns: [[u16; CAP]; CAP],
    counts: [usize; CAP],
    /// `by_column[j][i]` = A[n + i][j] (i < n, j < 2n; 0 elsewhere).
    by_column: [[f64; CAP]; CAP],
}

impl<const CAP: usize> LinearRows<CAP> {
    /// Rows n … 2n − 1 of `a` (2n × 2n, 2n ≤ CAP ≤ 65 536).
    pub(crate) fn new(a: &RealMatrix<CAP>, dofs: usize) -> Self {
        let mut rows = LinearRows {
            columns: [[0; CAP]; CAP],
            counts: [0; CAP],
            by_column: [[0.0; CAP]; CAP],
        };
        let width = 2 * dofs;
        for (i, (columns, count)) in rows
            .columns
            .iter_mut()
            .zip(rows.counts.iter_mut())
            .enumerate()
            .take(dofs)
        {
            let row = a.row(dofs + i);
            for (j, &x) in row.iter().enumerate().take(width) {
                if x == 0.0 {
                    continue;
                }
                if let (Some(c), Ok(column)) = (columns.get_mut(*count), u16::try_from(j)) {
                    *c = column;
                    *count += 1;
                }
                if let Some(slot) = rows.by_column.get_mut(j).and_then(|c| c.get_mut(i)) {
                    *slot = x;
                }
            }
        }
        rows
    }

    /// Σ_j A[n + i][j]·y[j] for every i < n = `out.len()` into `out`: column by column when
    /// the model fills its storage (n = CAP/2 and `y` holds CAP entries), else row by row.
    #[inline(always)]
    pub(crate) fn times(&self, y: &[f64], out: &mut [f64]) {
        match y.first_chunk::<CAP>() {
            Some(y) if 2 * out.len() == CAP => self.times_full(y, out),
            _ => {
                for (i, o) in out.iter_mut().enumerate() {
                    *o = self.row_times(i, y);
                }
            }
        }
    }

    /// [`Self::times`] of a model that fills its storage: column by column.
    #[inline(always)]
    fn times_full(&self, y: &[f64; CAP], out: &mut [f64]) {
        for o in out.iter_mut() {
            *o = -0.0;
        }
        for (column, &x) in self.by_column.iter().zip(y) {
            for (o, &a) in out.iter_mut().zip(column) {
                *o += a * x;
            }
        }
    }

    /// Σ_j A[n + i][j]·y[j] over the row's nonzero entries (0 for i ≥ n).
    #[inline]
    fn row_times(&self, i: usize, y: &[f64]) -> f64 {
        let (Some(columns), Some(&count)) = (self.columns.get(i), self.counts.get(i)) else {
            return 0.0;
        };
        let mut sum = -0.0;
        for &c in columns.iter().take(count) {
            let c = usize::from(c);
            let a = self
                .by_column
                .get(c)
                .and_then(|column| column.get(i))
                .copied()
                .unwrap_or(0.0);
            sum += a * y.get(c).copied().unwrap_or(0.0);
        }
        sum
    }
}
