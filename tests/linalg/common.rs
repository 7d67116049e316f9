//! Shared by the linalg tests: conversions to nalgebra (the independent reference), the rotor
//! cases, and the error measures.

use nalgebra::DMatrix;
use rotor_rub::linalg::{ModalExponential, RealMatrix, SecondOrder};

/// A capacity large enough for every case here (n ≤ 8 DOFs in the rotor cases, m ≤ 16).
pub const CAP: usize = 16;

pub fn to_na<const C: usize>(a: &RealMatrix<C>) -> DMatrix<f64> {
    DMatrix::from_fn(a.rows(), a.cols(), |i, j| a.get(i, j))
}

pub fn from_na<const C: usize>(a: &DMatrix<f64>) -> RealMatrix<C> {
    RealMatrix::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)]).unwrap()
}

pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// nalgebra's e^{As} y0.
pub fn reference<const C: usize>(a: &RealMatrix<C>, s: f64, y0: &[f64]) -> Vec<f64> {
    let e = (to_na(a) * s).exp();
    let y = e * nalgebra::DVector::from_column_slice(y0);
    y.iter().copied().collect()
}

/// Ours: e^{As} y0 through the modal form.
pub fn ours<const C: usize>(e: &ModalExponential<C>, s: f64, y0: &[f64]) -> Vec<f64> {
    let c = e.modal_coordinates(y0).unwrap();
    let mut y = vec![0.0; y0.len()];
    e.state(&c, s, &mut y);
    y
}

/// ‖ours − reference‖₂ / ‖reference‖₂ (the norm every accuracy statement uses).
pub fn relative_error(ours: &[f64], reference: &[f64]) -> f64 {
    let diff: Vec<f64> = ours.iter().zip(reference).map(|(a, b)| a - b).collect();
    norm(&diff) / norm(reference)
}

/// A rotor's four matrices (n × n each).
pub struct Rotor {
    pub m: RealMatrix<CAP>,
    pub c: RealMatrix<CAP>,
    pub g: RealMatrix<CAP>,
    pub k: RealMatrix<CAP>,
}

impl Rotor {
    pub fn from_rows(m: &[&[f64]], c: &[&[f64]], g: &[&[f64]], k: &[&[f64]]) -> Self {
        Rotor {
            m: RealMatrix::from_rows(m).unwrap(),
            c: RealMatrix::from_rows(c).unwrap(),
            g: RealMatrix::from_rows(g).unwrap(),
            k: RealMatrix::from_rows(k).unwrap(),
        }
    }

    /// The isotropic Jeffcott rotor M = I, C = 2νI, K = I (n = 2).
    pub fn jeffcott(nu: f64) -> Self {
        let z = 2.0 * nu;
        Rotor::from_rows(
            &[&[1.0, 0.0], &[0.0, 1.0]],
            &[&[z, 0.0], &[0.0, z]],
            &[&[0.0, 0.0], &[0.0, 0.0]],
            &[&[1.0, 0.0], &[0.0, 1.0]],
        )
    }

    pub fn second_order(&self) -> SecondOrder<'_, CAP> {
        SecondOrder {
            mass: &self.m,
            damping: &self.c,
            gyroscopic: &self.g,
            stiffness: &self.k,
        }
    }

    pub fn first_order(&self, eta: f64) -> RealMatrix<CAP> {
        self.second_order().first_order(eta).unwrap()
    }
}

/// A two-disk rotor on anisotropic, cross-coupled bearings with gyroscopic disks (n = 8:
/// x, y of two disks and two bearing journals), non-symmetric K and C.
pub fn two_disk_rotor() -> Rotor {
    let n = 8;
    let mut m = DMatrix::<f64>::zeros(n, n);
    let mut c = DMatrix::<f64>::zeros(n, n);
    let mut g = DMatrix::<f64>::zeros(n, n);
    let mut k = DMatrix::<f64>::zeros(n, n);
    // DOFs: (x, y) of node 0 (bearing), 1 (disk), 2 (disk), 3 (bearing).
    let masses = [0.3, 1.0, 1.4, 0.3];
    let polar = [0.0, 0.15, 0.25, 0.0];
    for (node, (&mass, &ip)) in masses.iter().zip(&polar).enumerate() {
        let (x, y) = (2 * node, 2 * node + 1);
        m[(x, x)] = mass;
        m[(y, y)] = mass;
        g[(x, y)] = ip;
        g[(y, x)] = -ip;
    }
    // Shaft: springs between consecutive nodes, the same in x and y.
    let shaft = [3.0, 2.5, 3.5];
    for (e, &ks) in shaft.iter().enumerate() {
        for d in 0..2 {
            let (a, b) = (2 * e + d, 2 * (e + 1) + d);
            k[(a, a)] += ks;
            k[(b, b)] += ks;
            k[(a, b)] -= ks;
            k[(b, a)] -= ks;
        }
    }
    // Bearings at nodes 0 and 3: anisotropic, cross-coupled (non-symmetric) K and C.
    for (node, (kxx, kyy, kxy, kyx)) in [(0, (2.0, 1.2, 0.4, -0.3)), (3, (1.5, 2.2, 0.25, -0.35))] {
        let (x, y) = (2 * node, 2 * node + 1);
        k[(x, x)] += kxx;
        k[(y, y)] += kyy;
        k[(x, y)] += kxy;
        k[(y, x)] += kyx;
        c[(x, x)] += 0.05;
        c[(y, y)] += 0.07;
        c[(x, y)] += 0.01;
        c[(y, x)] -= 0.015;
    }
    Rotor {
        m: from_na(&m),
        c: from_na(&c),
        g: from_na(&g),
        k: from_na(&k),
    }
}

/// A small deterministic generator (xorshift) for random matrices and states.
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    pub fn matrix(&mut self, m: usize) -> RealMatrix<CAP> {
        RealMatrix::from_fn(m, m, |_, _| self.uniform()).unwrap()
    }

    pub fn vector(&mut self, m: usize) -> Vec<f64> {
        (0..m).map(|_| self.uniform()).collect()
    }
}

/// ‖e^{As}‖₂ (nalgebra).
pub fn exp_norm<const C: usize>(a: &RealMatrix<C>, s: f64) -> f64 {
    (to_na(a) * s).exp().singular_values().max()
}

/// The relative condition number of e^{As} (Van Loan 1977's bound, which the Fréchet
/// derivative attains within a small factor): κ = ‖A‖ s · mean_t ‖e^{A(s−t)}‖‖e^{At}‖ / ‖e^{As}‖,
/// the mean over t ∈ [0, s] by the trapezoid rule on 33 points. For a normal A it is ‖A‖s; for
/// a Jordan block of size k it grows like s^k: a perturbation of A by ε‖A‖ (which any f64
/// method's rounding is) moves e^{As} by κε relative.
pub fn exp_condition<const C: usize>(a: &RealMatrix<C>, s: f64) -> f64 {
    let an = to_na(a);
    let norm_a = an.clone().singular_values().max();
    let k = 32;
    let norms: Vec<f64> = (0..=k)
        .map(|i| {
            (&an * (s * i as f64 / k as f64))
                .exp()
                .singular_values()
                .max()
        })
        .collect();
    let mean = (0..=k)
        .map(|i| {
            let w = if i == 0 || i == k { 0.5 } else { 1.0 };
            w * norms[i] * norms[k - i]
        })
        .sum::<f64>()
        / k as f64;
    norm_a * s * mean / norms[k]
}

/// The accuracy every exponential test holds ours to, normwise, ‖Δy‖₂ / (‖e^{As}‖₂‖y0‖₂):
/// 1e-13, or 4ε times the problem's own condition number where that is larger (long spans,
/// defective eigenvalues: no f64 method does better, nalgebra's `exp` included).
pub fn tolerance<const C: usize>(a: &RealMatrix<C>, s: f64) -> f64 {
    1e-13f64.max(4.0 * f64::EPSILON * exp_condition(a, s))
}

/// ‖ours − reference‖₂ / (‖e^{As}‖₂ ‖y0‖₂).
pub fn normwise_error<const C: usize>(
    a: &RealMatrix<C>,
    s: f64,
    y0: &[f64],
    ours: &[f64],
    reference: &[f64],
) -> f64 {
    let diff: Vec<f64> = ours.iter().zip(reference).map(|(a, b)| a - b).collect();
    norm(&diff) / (exp_norm(a, s) * norm(y0))
}
