//! The linear part of the accelerations, (A y)'s lower half = −M⁻¹K q − M⁻¹(C + ηG) q', by the
//! nonzero entries of A's lower rows: what every field evaluation, Taylor order and rate of a
//! matrix model multiplies. A rotor's matrices are sparse in practice (the stator ring's M is
//! diagonal, its K and C couple the rotor's pair and the ring's pair only: 10 of the 32 entries
//! are nonzero), so the product runs over the nonzero entries of each row, in column order.
//!
//! The result is the dense row product's: the terms left out are products with a zero entry,
//! ±0, which change a sum that has any nonzero term not at all, and an all-zero sum only in the
//! sign of its 0.

use crate::linalg::RealMatrix;

/// A's lower rows (one per DOF) by their nonzero entries.
#[derive(Clone, Debug)]
pub(crate) struct LinearRows<const CAP: usize> {
    /// Per DOF i: the columns of row n + i holding a nonzero entry, ascending (`counts[i]` used).
    columns: [[u16; CAP]; CAP],
    /// Their entries, in the same order.
    values: [[f64; CAP]; CAP],
    counts: [usize; CAP],
}

impl<const CAP: usize> LinearRows<CAP> {
    /// The nonzero entries of rows n … 2n − 1 of `a` (2n × 2n, 2n ≤ CAP ≤ 65 536).
    pub(crate) fn new(a: &RealMatrix<CAP>, dofs: usize) -> Self {
        let mut rows = LinearRows {
            columns: [[0; CAP]; CAP],
            values: [[0.0; CAP]; CAP],
            counts: [0; CAP],
        };
        let width = 2 * dofs;
        for (i, ((columns, values), count)) in rows
            .columns
            .iter_mut()
            .zip(rows.values.iter_mut())
            .zip(rows.counts.iter_mut())
            .enumerate()
            .take(dofs)
        {
            let row = a.row(dofs + i);
            for (j, &x) in row.iter().enumerate().take(width) {
                if x != 0.0
                    && let (Some(c), Some(v), Ok(j)) = (
                        columns.get_mut(*count),
                        values.get_mut(*count),
                        u16::try_from(j),
                    )
                {
                    (*c, *v) = (j, x);
                    *count += 1;
                }
            }
        }
        rows
    }

    /// Σ_j A[n + i][j]·y[j] over the row's nonzero entries (0 for i ≥ n).
    #[inline]
    pub(crate) fn row_times(&self, i: usize, y: &[f64]) -> f64 {
        let (Some(columns), Some(values), Some(&count)) =
            (self.columns.get(i), self.values.get(i), self.counts.get(i))
        else {
            return 0.0;
        };
        let mut sum = -0.0;
        for (&c, &v) in columns.iter().zip(values).take(count) {
            sum += v * y.get(usize::from(c)).copied().unwrap_or(0.0);
        }
        sum
    }
}
