//! The steady response to harmonic and constant forcing: the particular solution of
//! M q'' + (C + ηG) q' + K q = Re(F e^{iηs}) + u, so that free flight is
//! y(s) = y_p(s) + e^{As} (y0 − y_p(0)).
//!
//! q_p(s) = Re(Z e^{iηs}) + q_u with (K − η²M + iη(C + ηG)) Z = F (a complex LU solve) and
//! K q_u = u (a real one, only when u ≠ 0). A singular matrix is solved when the force is
//! consistent with it (`consistent.rs`: an undamped mode at η that F does not force, a free
//! rigid-body mode u does not push along); otherwise the response does not exist and the error
//! names η ([`LinalgError::Resonance`]) or the rigid-body mode ([`LinalgError::StaticSingular`]). In first-order form y_p = (q_p, q_p'), i.e.
//! y_p(s) = Re(Y e^{iηs}) + (q_u, 0) with Y = (Z, iηZ). Both solves are backward stable; the
//! response is exact to rounding relative to its size times the dynamic stiffness's condition
//! number (large only near resonance, where the particular and homogeneous parts are both
//! large and cancel: `docs/MODEL.md` §11 treats that for n = 2).
//!
//! F carries the forcing's phase at s = 0: the unbalance η² m_e e_k (cos(θ + φ), sin(θ + φ))
//! at a DOF pair (i, j) is F_i = η² m_e e^{i(θ0 + φ)}, F_j = −i η² m_e e^{i(θ0 + φ)}.

use super::complex::Complex;
use super::consistent::solve_consistent;
use super::dense::ComplexMatrix;
use super::error::LinalgError;
use super::first_order::SecondOrder;
use super::lu::Lu;
use super::projected::{ProjectedBound, ProjectedPoint};
use crate::math;

/// y_p(s) = Re(Y e^{iηs}) + y_u of a rotor (module docs).
#[derive(Clone, Debug)]
pub struct HarmonicResponse<const CAP: usize> {
    m: usize,
    speed_ratio: f64,
    amplitude: [Complex; CAP],
    constant: [f64; CAP],
}

impl<const CAP: usize> HarmonicResponse<CAP> {
    /// The steady response of `rotor` at speed ratio η to the harmonic force Re(F e^{iηs})
    /// (`force`: n entries) and the constant force u (`constant_force`: n entries, or empty for
    /// none). Errors: [`LinalgError::Resonance`] naming η when the dynamic stiffness is
    /// singular; [`LinalgError::StaticSingular`] when u ≠ 0 and K is singular.
    ///
    /// ```
    /// use rotor_rub::linalg::{Complex, HarmonicResponse, RealMatrix, SecondOrder};
    /// // x'' + x = cos(2s): x_p = −cos(2s)/3.
    /// let one = RealMatrix::<2>::identity(1).unwrap();
    /// let zero = RealMatrix::<2>::zeros(1, 1).unwrap();
    /// let rotor = SecondOrder { mass: &one, damping: &zero, gyroscopic: &zero, stiffness: &one };
    /// let h = HarmonicResponse::new(&rotor, 2.0, &[Complex::ONE], &[]).unwrap();
    /// let mut y = [0.0; 2];
    /// h.state(0.0, &mut y);
    /// assert!((y[0] + 1.0 / 3.0).abs() < 1e-16 && y[1].abs() < 1e-16);
    /// assert!(HarmonicResponse::new(&rotor, 1.0, &[Complex::ONE], &[]).is_err());
    /// ```
    pub fn new(
        rotor: &SecondOrder<'_, CAP>,
        speed_ratio: f64,
        force: &[Complex],
        constant_force: &[f64],
    ) -> Result<Self, LinalgError> {
        let n = rotor.check()?;
        if 2 * n > CAP {
            return Err(LinalgError::TooLarge {
                what: "first-order state",
                size: 2 * n,
                capacity: CAP,
            });
        }
        if !speed_ratio.is_finite() {
            return Err(LinalgError::NonFinite {
                what: "speed ratio",
                row: 0,
                col: 0,
            });
        }
        check_vector(
            force.len(),
            n,
            "harmonic force",
            force.iter().position(|z| !z.is_finite()),
        )?;
        if !constant_force.is_empty() {
            check_vector(
                constant_force.len(),
                n,
                "constant force",
                constant_force.iter().position(|v| !v.is_finite()),
            )?;
        }
        let eta = speed_ratio;
        let mut amplitude = [Complex::ZERO; CAP];
        if force.iter().any(|z| *z != Complex::ZERO) {
            let dynamic = ComplexMatrix::<CAP>::from_fn(n, n, |i, j| {
                Complex::new(
                    rotor.stiffness.get(i, j) - eta * eta * rotor.mass.get(i, j),
                    eta * (rotor.damping.get(i, j) + eta * rotor.gyroscopic.get(i, j)),
                )
            })?;
            let mut z = [Complex::ZERO; CAP];
            z.iter_mut().zip(force).for_each(|(a, &f)| *a = f);
            match Lu::factor(&dynamic, "dynamic stiffness") {
                Ok(lu) => lu.solve(&mut z),
                // Singular: a particular solution still exists when F does not force the
                // undamped mode at η (`consistent.rs`).
                Err(LinalgError::Singular { .. }) => solve_consistent(&dynamic, &mut z)
                    .map_err(|_| LinalgError::Resonance { speed_ratio })?,
                Err(other) => return Err(other),
            }
            for (i, &zi) in z.iter().enumerate().take(n) {
                if let Some(a) = amplitude.get_mut(i) {
                    *a = zi;
                }
                if let Some(a) = amplitude.get_mut(n + i) {
                    *a = Complex::new(0.0, eta) * zi;
                }
            }
        }
        let mut constant = [0.0; CAP];
        if constant_force.iter().any(|&v| v != 0.0) {
            constant
                .iter_mut()
                .zip(constant_force)
                .for_each(|(a, &f)| *a = f);
            match Lu::factor(rotor.stiffness, "stiffness matrix") {
                Ok(lu) => lu.solve(&mut constant),
                // Singular: a static deflection exists when u does not push along the free
                // rigid-body mode (`consistent.rs`).
                Err(LinalgError::Singular { .. }) => {
                    solve_consistent(rotor.stiffness, &mut constant)
                        .map_err(|column| LinalgError::StaticSingular { column })?
                }
                Err(other) => return Err(other),
            }
        }
        Ok(HarmonicResponse {
            m: 2 * n,
            speed_ratio,
            amplitude,
            constant,
        })
    }

    /// The first-order dimension m = 2n.
    pub fn dim(&self) -> usize {
        self.m
    }

    /// The forcing's speed ratio η.
    pub fn speed_ratio(&self) -> f64 {
        self.speed_ratio
    }

    /// The complex amplitude Y = (Z, iηZ) (m entries).
    pub fn amplitude(&self) -> &[Complex] {
        self.amplitude.get(..self.m).unwrap_or(&[])
    }

    /// The constant response y_u = (K⁻¹u, 0) (m entries).
    pub fn constant(&self) -> &[f64] {
        self.constant.get(..self.m).unwrap_or(&[])
    }

    /// y_p(s) (m entries of `out`).
    pub fn state(&self, s: f64, out: &mut [f64]) {
        let (sin, cos) = math::sin_cos(self.speed_ratio * s);
        self.state_at_phase(Complex::new(cos, sin), out);
    }

    /// y_p where the forcing's phasor e^{iηs} is `phasor` (a caller that keeps the forcing
    /// phase itself: the matrix model's one forcing phase, `crate::field::phasor`).
    pub fn state_at_phase(&self, phasor: Complex, out: &mut [f64]) {
        for ((o, &y), &c) in out
            .iter_mut()
            .zip(&self.amplitude)
            .zip(&self.constant)
            .take(self.m)
        {
            *o = (y * phasor).re + c;
        }
    }

    /// The projection d_p(s) = B y_p(s) for B = [`bx`; `by`] (m entries each).
    pub fn project(&self, bx: &[f64], by: &[f64]) -> Result<ProjectedHarmonic, LinalgError> {
        let mut amplitude = [Complex::ZERO; 2];
        let mut constant = [0.0; 2];
        for ((a, c), b) in amplitude.iter_mut().zip(constant.iter_mut()).zip([bx, by]) {
            check_vector(
                b.len(),
                self.m,
                "projection row",
                b.iter().position(|v| !v.is_finite()),
            )?;
            *a = b
                .iter()
                .zip(&self.amplitude)
                .fold(Complex::ZERO, |acc, (&bi, &y)| acc + y.scale(bi));
            *c = b.iter().zip(&self.constant).map(|(&bi, &y)| bi * y).sum();
        }
        Ok(ProjectedHarmonic {
            speed_ratio: self.speed_ratio,
            amplitude,
            constant,
        })
    }
}

fn check_vector(
    len: usize,
    n: usize,
    what: &'static str,
    non_finite: Option<usize>,
) -> Result<(), LinalgError> {
    if len != n {
        return Err(LinalgError::Shape {
            what,
            got: len,
            expected: n,
        });
    }
    if let Some(row) = non_finite {
        return Err(LinalgError::NonFinite { what, row, col: 0 });
    }
    Ok(())
}

/// d_p(s) = Re(P e^{iηs}) + d_u: two complex numbers and two reals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedHarmonic {
    speed_ratio: f64,
    amplitude: [Complex; 2],
    constant: [f64; 2],
}

impl ProjectedHarmonic {
    /// P (x and y rows): d_p(s) = Re(P e^{iηs}) + d_u.
    pub fn amplitude(&self) -> [Complex; 2] {
        self.amplitude
    }

    /// d_u.
    pub fn constant(&self) -> [f64; 2] {
        self.constant
    }

    /// d_p, d_p', d_p'' at s.
    pub fn at(&self, s: f64) -> ProjectedPoint {
        let (sin, cos) = math::sin_cos(self.speed_ratio * s);
        self.at_phase(Complex::new(cos, sin))
    }

    /// d_p, d_p', d_p'' where the phasor e^{iηs} is `phasor`.
    pub fn at_phase(&self, phasor: Complex) -> ProjectedPoint {
        let eta = self.speed_ratio;
        let [px, py] = self.amplitude.map(|a| a * phasor);
        let i_eta = Complex::new(0.0, eta);
        let rate = [(px * i_eta).re, (py * i_eta).re];
        let acc = -eta * eta;
        ProjectedPoint {
            value: [px.re + self.constant[0], py.re + self.constant[1]],
            rate,
            acceleration: [px.re * acc, py.re * acc],
        }
    }

    /// Bounds of |d_p|, |d_p'|, |d_p''| valid for every s: |P| + |d_u|, η|P|, η²|P| with
    /// |P| = √(|P_x|² + |P_y|²) ≥ |Re(P e^{iθ})| for every θ (Cauchy–Schwarz), times
    /// 1 + 1e-12 for rounding.
    pub fn bound(&self) -> ProjectedBound {
        let p = math::hypot(self.amplitude[0].abs(), self.amplitude[1].abs());
        let c = math::hypot(self.constant[0], self.constant[1]);
        let eta = math::abs(self.speed_ratio);
        let up = 1.0 + super::projected::BOUND_MARGIN;
        ProjectedBound {
            value: (p + c) * up,
            rate: eta * p * up,
            acceleration: eta * eta * p * up,
        }
    }
}
