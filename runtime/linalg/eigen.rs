//! The eigenvalues of any real square matrix, sorted by modulus: the Floquet multipliers of a
//! monodromy matrix (stable when all lie inside the unit circle). Balancing, Hessenberg
//! reduction and the complex QR iteration of `schur.rs` without accumulating the Schur
//! vectors (only the active block is updated: about half the work of the full Schur form).
//! Each computed eigenvalue is exact for a matrix within ~c·m·ε‖A‖ of A.

use super::complex::Complex;
use super::dense::RealMatrix;
use super::error::LinalgError;
use super::hessenberg::{balance, hessenberg};
use super::schur::triangularize;

/// The eigenvalues of a real square matrix (any: a monodromy matrix for its Floquet
/// multipliers), sorted by modulus, largest first (ties by argument), written to `out`
/// (its first n entries); n returned. Uses work matrices on the stack (about 32·CAP² bytes,
/// 512 KiB at CAP = 128).
///
/// ```
/// use rotor_rub::linalg::{RealMatrix, eigenvalues, Complex};
/// let a = RealMatrix::<2>::from_rows(&[&[0.0, 1.0], &[-4.0, 0.0]]).unwrap();
/// let mut ev = [Complex::ZERO; 2];
/// assert_eq!(eigenvalues(&a, &mut ev).unwrap(), 2);
/// assert!((ev[0].abs() - 2.0).abs() < 1e-15 && (ev[0].re).abs() < 1e-15);
/// assert!((ev[0] - ev[1].conj()).abs() < 1e-15);
/// ```
pub fn eigenvalues<const CAP: usize>(
    a: &RealMatrix<CAP>,
    out: &mut [Complex],
) -> Result<usize, LinalgError> {
    let n = a.check_square("matrix")?;
    if out.len() < n {
        return Err(LinalgError::Shape {
            what: "eigenvalue output",
            got: out.len(),
            expected: n,
        });
    }
    let mut work = a.clone();
    let mut scale = [1.0; CAP];
    balance(&mut work, &mut scale);
    let mut q = RealMatrix::<CAP>::zeros(n, n)?;
    hessenberg(&mut work, &mut q);
    let mut h = work.to_complex();
    triangularize(&mut h, None)?;
    for (i, o) in out.iter_mut().enumerate().take(n) {
        *o = h.get(i, i);
    }
    if let Some(values) = out.get_mut(..n) {
        sort_by_modulus(values);
    }
    Ok(n)
}

/// Sort by modulus, largest first, ties by argument (insertion sort: no allocation).
pub(crate) fn sort_by_modulus(v: &mut [Complex]) {
    let key = |z: &Complex| (z.abs(), crate::math::atan2(z.im, z.re));
    for i in 1..v.len() {
        let mut j = i;
        while j > 0 {
            let (Some(a), Some(b)) = (v.get(j - 1), v.get(j)) else {
                break;
            };
            let (ka, kb) = (key(a), key(b));
            if kb.0 > ka.0 || (kb.0 == ka.0 && kb.1 > ka.1) {
                v.swap(j - 1, j);
                j -= 1;
            } else {
                break;
            }
        }
    }
}
