//! The state of a rotor from matrices: y = (q, q'), n positions then n velocities, in storage of
//! capacity CAP (the largest first-order dimension 2n it holds).

use super::error::MatrixError;

/// y = (q, q') of an n-degree-of-freedom model (2n ≤ CAP), lengths in clearances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatrixState<const CAP: usize> {
    dim: usize,
    y: [f64; CAP],
}

impl<const CAP: usize> MatrixState<CAP> {
    /// Rest (q = q' = 0) of an n-DOF model.
    ///
    /// # Errors
    /// [`MatrixError::TooLarge`] when 2n exceeds CAP.
    pub fn rest(dofs: usize) -> Result<Self, MatrixError> {
        if 2 * dofs > CAP {
            return Err(MatrixError::TooLarge {
                dofs,
                capacity: CAP / 2,
            });
        }
        Ok(MatrixState {
            dim: 2 * dofs,
            y: [0.0; CAP],
        })
    }

    /// The state with positions `q` and velocities `v` (n entries each, finite).
    ///
    /// # Errors
    /// [`MatrixError::TooLarge`], [`MatrixError::Shape`] when `v` and `q` differ in length,
    /// [`MatrixError::NonFinite`] naming the first entry that is not finite.
    pub fn new(q: &[f64], v: &[f64]) -> Result<Self, MatrixError> {
        let n = q.len();
        if v.len() != n {
            return Err(MatrixError::Shape {
                what: "initial velocities",
                got: v.len(),
                expected: n,
            });
        }
        let mut s = Self::rest(n)?;
        for (i, &x) in q.iter().chain(v).enumerate() {
            if !x.is_finite() {
                return Err(MatrixError::NonFinite {
                    what: if i < n {
                        "initial position"
                    } else {
                        "initial velocity"
                    },
                    index: i % n.max(1),
                    value: x,
                });
            }
        }
        for (slot, &x) in s.y.iter_mut().zip(q.iter().chain(v)) {
            *slot = x;
        }
        Ok(s)
    }

    /// The state filling the whole storage: n = CAP/2 (CAP even), y = `y`.
    pub const fn full(y: [f64; CAP]) -> Self {
        MatrixState {
            dim: CAP - CAP % 2,
            y,
        }
    }

    /// The state with y = `y` (2n entries, positions then velocities), unchecked values.
    ///
    /// # Errors
    /// [`MatrixError::TooLarge`] when y has more than CAP entries, [`MatrixError::Shape`] when
    /// its length is odd.
    pub fn from_slice(y: &[f64]) -> Result<Self, MatrixError> {
        if !y.len().is_multiple_of(2) {
            return Err(MatrixError::Shape {
                what: "state",
                got: y.len(),
                expected: y.len() + 1,
            });
        }
        let mut s = Self::rest(y.len() / 2)?;
        for (slot, &x) in s.y.iter_mut().zip(y) {
            *slot = x;
        }
        Ok(s)
    }

    /// The state of `dofs` degrees of freedom whose y is the first 2·`dofs` entries of `y` (the
    /// rest of the storage set to 0; `dofs` capped at CAP/2): what the numerical solvers, which
    /// integrate the whole storage, hand back.
    pub fn from_array(dofs: usize, y: [f64; CAP]) -> Self {
        let dim = (2 * dofs).min(CAP - CAP % 2);
        let mut s = MatrixState { dim, y };
        for x in s.y.iter_mut().skip(dim) {
            *x = 0.0;
        }
        s
    }

    /// The whole storage: y in its first 2n entries, 0 beyond.
    pub const fn array(&self) -> &[f64; CAP] {
        &self.y
    }

    /// The number of degrees of freedom n.
    pub const fn dofs(&self) -> usize {
        self.dim / 2
    }

    /// y = (q, q'): 2n entries.
    pub fn as_slice(&self) -> &[f64] {
        self.y.get(..self.dim).unwrap_or(&[])
    }

    /// y, mutable.
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        self.y.get_mut(..self.dim).unwrap_or(&mut [])
    }

    /// The positions q.
    pub fn positions(&self) -> &[f64] {
        self.y.get(..self.dim / 2).unwrap_or(&[])
    }

    /// The velocities q'.
    pub fn velocities(&self) -> &[f64] {
        self.y.get(self.dim / 2..self.dim).unwrap_or(&[])
    }

    /// Entry `i` of y (0 beyond 2n).
    #[inline]
    pub fn get(&self, i: usize) -> f64 {
        if i < self.dim {
            self.y.get(i).copied().unwrap_or(0.0)
        } else {
            0.0
        }
    }

    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.as_slice().iter().all(|x| x.is_finite())
    }
}
