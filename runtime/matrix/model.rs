//! The statement of a rotor from matrices ([`MatrixModel`]): its second-order matrices, its
//! running speed and unbalances, its input force and its rub station, checked once and turned
//! into what every solver reads (the first-order matrix A, M⁻¹ applied to each force, the
//! station's compliance W = B M⁻¹ Bᵀ).
//!
//! The station's scalars live in the parameter table's names: the model holds a generated
//! `ModelParams` built from a [`Params`] whose `speed_ratio`, `phase`, `offset_x`, `offset_y`,
//! `friction_coefficient` and `radius_ratio` are the model's (the other entries are unused), so
//! that the forcing phase, the station's geometry and its contact law are the generated
//! formulas the planar model runs.

use super::checks::{check_dof, check_finite, check_scalar, check_station, input_forces};
use super::error::MatrixError;
use super::linear::LinearRows;
use crate::coefficients::{self as coef, ContactLaw, ModelParams, StationCompliance};
use crate::linalg::{Complex, Lu, RealMatrix, SecondOrder};
use crate::params::{Parameter, Params, Range};

/// One unbalance: `amount` = m·e (mass times eccentricity, in the model's mass unit times
/// clearances) at the degree-of-freedom pair (`x`, `y`) and angle `phase` ahead of the forcing
/// phase θ = ητ + φ0: it forces η² m e (cos(θ + φ), sin(θ + φ)) on (x, y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unbalance {
    /// The DOF of the unbalance's x force.
    pub x: usize,
    /// The DOF of its y force.
    pub y: usize,
    /// m·e.
    pub amount: f64,
    /// φ, rad.
    pub phase: f64,
}

/// The rub station: where the rotor meets the stator, and the contact law there. The contact
/// acts on d = (q[rotor.0] − q[stator.0], q[rotor.1] − q[stator.1]) − ε̂ (a fixed stator: no
/// stator DOFs), with the force f_c on the rotor's pair and −f_c on the stator's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Station {
    /// The rotor point's x and y DOFs.
    pub rotor: (usize, usize),
    /// The stator point's x and y DOFs (`None`: a fixed stator).
    pub stator: Option<(usize, usize)>,
    /// ε̂: the stator centre's offset from the rotor point's rest position, clearances.
    pub offset: (f64, f64),
    /// K_c, the contact stiffness (force per clearance of penetration; rows: x, y force).
    pub contact_stiffness: [[f64; 2]; 2],
    /// μ, the Coulomb friction coefficient (0: frictionless).
    pub friction_coefficient: f64,
    /// ρ_R = R/δ, the rotor's radius at the station over the clearance.
    pub radius_ratio: f64,
}

/// The running condition: speed and the forcing phase at τ = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Running {
    /// η, the running speed (rad per unit of the model's time).
    pub speed_ratio: f64,
    /// φ0, rad.
    pub phase: f64,
}

/// Valid running speeds (rad per unit time: dimensionless speed ratios and rad/s alike).
pub const SPEED_RANGE: Range = Range::above(0.0, 1e6);

/// A linear rotor with a rub station: M q'' + (C + ηG) q' + K q = unbalance + u + Bᵀ f_c
/// (`docs/MODEL.md` §17), in storage of first-order capacity CAP (n ≤ CAP/2).
#[derive(Clone, Debug)]
pub struct MatrixModel<const CAP: usize> {
    dofs: usize,
    mass: RealMatrix<CAP>,
    damping: RealMatrix<CAP>,
    gyroscopic: RealMatrix<CAP>,
    stiffness: RealMatrix<CAP>,
    first_order: RealMatrix<CAP>,
    /// A's lower rows by their nonzero entries (what the fields multiply).
    linear: LinearRows<CAP>,
    mass_lu: Lu<f64, CAP>,
    running: ModelParams,
    law: ContactLaw,
    station: Station,
    unbalance: [Complex; CAP],
    input: [f64; CAP],
    unbalance_acceleration: [Complex; CAP],
    input_acceleration: [f64; CAP],
    contact_acceleration: [[f64; CAP]; 2],
    compliance: StationCompliance,
}

impl<const CAP: usize> MatrixModel<CAP> {
    /// Check and state a model: `rotor`'s matrices, the running condition, the unbalances, the
    /// constant input force `input` (n entries, or empty for none) and the rub station.
    ///
    /// # Errors
    /// A [`MatrixError`] naming the first value that is wrong and what is valid.
    pub fn new(
        rotor: &SecondOrder<'_, CAP>,
        running: Running,
        unbalances: &[Unbalance],
        input: &[f64],
        station: Station,
    ) -> Result<Self, MatrixError> {
        let n = rotor.check()?;
        if 2 * n > CAP {
            return Err(MatrixError::TooLarge {
                dofs: n,
                capacity: CAP / 2,
            });
        }
        check_scalar("speed", running.speed_ratio, SPEED_RANGE)?;
        check_scalar("phase", running.phase, Parameter::Phase.range())?;
        check_station(&station, n)?;
        let mut unbalance = [Complex::ZERO; CAP];
        for u in unbalances {
            for (what, dof) in [("unbalance x", u.x), ("unbalance y", u.y)] {
                check_dof(what, dof, n)?;
            }
            check_finite("unbalance amount", 0, u.amount)?;
            check_finite("unbalance phase", 0, u.phase)?;
            // η² m e (cos(θ + φ), sin(θ + φ)) = η² Re(m e e^{iφ} (1, −i) e^{iθ}).
            let (s, c) = crate::math::sin_cos(u.phase);
            let a = Complex::new(u.amount * c, u.amount * s);
            if let Some(x) = unbalance.get_mut(u.x) {
                *x += a;
            }
            if let Some(y) = unbalance.get_mut(u.y) {
                *y += Complex::new(a.im, -a.re);
            }
        }
        let forces = input_forces::<CAP>(input, n)?;
        let params = Params {
            speed_ratio: running.speed_ratio,
            phase: running.phase,
            offset_x: station.offset.0,
            offset_y: station.offset.1,
            friction_coefficient: station.friction_coefficient,
            radius_ratio: station.radius_ratio,
            // η_m ρ̂ = 1: the generated unbalance force is η² per unit of m·e.
            mass_ratio: 1.0,
            eccentricity_ratio: 1.0,
            ..Params::DEFAULT
        };
        let k = station.contact_stiffness;
        let first_order = rotor.first_order(running.speed_ratio)?;
        let mut model = MatrixModel {
            dofs: n,
            mass: rotor.mass.clone(),
            damping: rotor.damping.clone(),
            gyroscopic: rotor.gyroscopic.clone(),
            stiffness: rotor.stiffness.clone(),
            linear: LinearRows::new(&first_order, n),
            first_order,
            mass_lu: Lu::factor(rotor.mass, "mass matrix")?,
            running: coef::model_params(&params),
            law: ContactLaw {
                kc_xx: k[0][0],
                kc_xy: k[0][1],
                kc_yx: k[1][0],
                kc_yy: k[1][1],
            },
            station,
            unbalance,
            input: forces,
            unbalance_acceleration: [Complex::ZERO; CAP],
            input_acceleration: [0.0; CAP],
            contact_acceleration: [[0.0; CAP]; 2],
            compliance: StationCompliance {
                w_xx: 0.0,
                w_xy: 0.0,
                w_yx: 0.0,
                w_yy: 0.0,
            },
        };
        model.derive();
        Ok(model)
    }

    /// M⁻¹ applied to each force, and W = B M⁻¹ Bᵀ.
    fn derive(&mut self) {
        let mut re = [0.0; CAP];
        let mut im = [0.0; CAP];
        for ((r, i), u) in re.iter_mut().zip(im.iter_mut()).zip(&self.unbalance) {
            (*r, *i) = (u.re, u.im);
        }
        self.mass_lu.solve(&mut re);
        self.mass_lu.solve(&mut im);
        for ((a, &r), &i) in self.unbalance_acceleration.iter_mut().zip(&re).zip(&im) {
            *a = Complex::new(r, i);
        }
        self.input_acceleration = self.input;
        self.mass_lu.solve(&mut self.input_acceleration);
        let (rotor, stator) = (self.station.rotor, self.station.stator);
        for (k, column) in self.contact_acceleration.iter_mut().enumerate() {
            *column = [0.0; CAP];
            let (r, s) = if k == 0 {
                (rotor.0, stator.map(|s| s.0))
            } else {
                (rotor.1, stator.map(|s| s.1))
            };
            if let Some(x) = column.get_mut(r) {
                *x = 1.0;
            }
            if let Some(x) = s.and_then(|s| column.get_mut(s)) {
                *x = -1.0;
            }
            self.mass_lu.solve(column);
        }
        let [cx, cy] = &self.contact_acceleration;
        let w = |c: &[f64; CAP], k: usize| self.station_component(c, k);
        self.compliance = StationCompliance {
            w_xx: w(cx, 0),
            w_xy: w(cy, 0),
            w_yx: w(cx, 1),
            w_yy: w(cy, 1),
        };
    }

    /// Component `k` (0: x, 1: y) of B v: the rotor point's entry minus the stator point's.
    #[inline]
    pub(crate) fn station_component(&self, v: &[f64], k: usize) -> f64 {
        let (r, s) = if k == 0 {
            (self.station.rotor.0, self.station.stator.map(|s| s.0))
        } else {
            (self.station.rotor.1, self.station.stator.map(|s| s.1))
        };
        let at = |i: usize| v.get(i).copied().unwrap_or(0.0);
        match s {
            Some(s) => at(r) - at(s),
            None => at(r),
        }
    }

    /// A new input force (n entries; empty: none) between steps, without re-deriving the rest.
    ///
    /// # Errors
    /// [`MatrixError::Shape`] or [`MatrixError::NonFinite`].
    pub fn set_input(&mut self, input: &[f64]) -> Result<(), MatrixError> {
        let n = self.dofs;
        let forces = input_forces::<CAP>(input, n)?;
        self.input = forces;
        self.input_acceleration = forces;
        self.mass_lu.solve(&mut self.input_acceleration);
        Ok(())
    }

    /// n, the number of degrees of freedom.
    pub const fn dofs(&self) -> usize {
        self.dofs
    }

    /// The second-order matrices M, C, G, K.
    pub fn second_order(&self) -> SecondOrder<'_, CAP> {
        SecondOrder {
            mass: &self.mass,
            damping: &self.damping,
            gyroscopic: &self.gyroscopic,
            stiffness: &self.stiffness,
        }
    }

    /// The first-order matrix A at the running speed (y' = A y + forces).
    pub fn first_order(&self) -> &RealMatrix<CAP> {
        &self.first_order
    }

    /// The station's scalars in the table's names (generated `ModelParams`): speed, phase,
    /// offset, friction, radius; its `unbalance_force` is η² (per unit of m·e).
    pub fn running(&self) -> &ModelParams {
        &self.running
    }

    /// M⁻¹f̂, M⁻¹u and M⁻¹Bᵀ over the whole storage (0 beyond n): what the field reads.
    #[inline]
    #[allow(clippy::type_complexity, reason = "three named storage arrays")]
    pub(crate) fn force_accelerations(&self) -> (&[Complex; CAP], &[f64; CAP], &[[f64; CAP]; 2]) {
        (
            &self.unbalance_acceleration,
            &self.input_acceleration,
            &self.contact_acceleration,
        )
    }

    /// A's lower rows by their nonzero entries.
    #[inline]
    pub(crate) fn linear(&self) -> &LinearRows<CAP> {
        &self.linear
    }

    /// The running speed η.
    pub fn speed_ratio(&self) -> f64 {
        self.running.speed_ratio
    }

    /// The rub station.
    pub fn station(&self) -> &Station {
        &self.station
    }

    /// The contact stiffness as the generated formulas take it.
    pub fn law(&self) -> &ContactLaw {
        &self.law
    }

    /// W = B M⁻¹ Bᵀ: the station offset's acceleration per unit contact force.
    pub fn compliance(&self) -> &StationCompliance {
        &self.compliance
    }

    /// f̂ (n entries): the unbalance forces are η² Re(f̂ e^{iθ}).
    pub fn unbalance(&self) -> &[Complex] {
        self.unbalance.get(..self.dofs).unwrap_or(&[])
    }

    /// The constant input force u (n entries).
    pub fn input(&self) -> &[f64] {
        self.input.get(..self.dofs).unwrap_or(&[])
    }

    /// M⁻¹ f̂ (n entries).
    pub fn unbalance_acceleration(&self) -> &[Complex] {
        self.unbalance_acceleration.get(..self.dofs).unwrap_or(&[])
    }

    /// M⁻¹ u (n entries).
    pub fn input_acceleration(&self) -> &[f64] {
        self.input_acceleration.get(..self.dofs).unwrap_or(&[])
    }

    /// M⁻¹ Bᵀ: the accelerations of a unit contact force along x (`[0]`) and y (`[1]`) on the
    /// rotor point (and its reaction on the stator point), n entries each.
    pub fn contact_acceleration(&self, k: usize) -> &[f64] {
        self.contact_acceleration
            .get(k)
            .and_then(|c| c.get(..self.dofs))
            .unwrap_or(&[])
    }

    /// Whether the station has friction (μ > 0).
    pub fn has_friction(&self) -> bool {
        self.station.friction_coefficient > 0.0
    }
}
