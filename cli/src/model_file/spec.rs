//! A rotor from matrices as the user states it, in SI units ([`ModelSpec`]), checked value by
//! value with errors naming the key ([`ModelError`]), and turned into the runtime's
//! dimensionless statement ([`ModelSpec::build`]): every length divided by the clearance δ.
//!
//! Why only lengths: the model is linear, so q̃ = q/δ turns M q'' + (C + ΩG) q' + K q = f into
//! M q̃'' + (C + ΩG) q̃' + K q̃ = f/δ with the same matrices, the same time (s) and speed
//! (rad/s). Forces become f/δ: the unbalance m·e (kg·m) becomes m·e/δ, a constant force u (N)
//! u/δ; the contact force K_c (|d| − δ) n becomes K_c (z − 1) n with z = |d|/δ, so K_c (N/m)
//! stays as given. Rotational DOFs (rad) scale by δ too and come back out as rad.

use std::fmt;

use rotor_rub::linalg::{Complex, RealMatrix, SecondOrder, eigenvalues};
use rotor_rub::matrix::{
    MatrixError, MatrixModel, MatrixState, Running, SPEED_RANGE, Station, Unbalance,
};
use rotor_rub::params::{Number, Parameter, Range};

/// First-order capacity of the CLI's and Python's matrix models: n ≤ 64 DOFs, boxed.
pub const CAPACITY: usize = 128;
/// The largest number of degrees of freedom a model file may have (CAPACITY/2).
pub const MAX_DOFS: usize = CAPACITY / 2;

/// A matrix model at the CLI's capacity.
pub type Model = MatrixModel<CAPACITY>;
/// Its state.
pub type ModelState = MatrixState<CAPACITY>;

/// A dense matrix, row-major, as read (SI units).
#[derive(Clone, Debug, PartialEq)]
pub struct Dense {
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// rows × cols entries, row after row.
    pub data: Vec<f64>,
}

impl Dense {
    /// The rows × cols zero matrix.
    pub fn zeros(rows: usize, cols: usize) -> Self {
        Dense {
            rows,
            cols,
            data: vec![0.0; rows * cols],
        }
    }

    /// Entry (i, j) (0 outside).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if i < self.rows && j < self.cols {
            self.data.get(i * self.cols + j).copied().unwrap_or(0.0)
        } else {
            0.0
        }
    }

    /// The first entry that is not finite: (row, column, value).
    fn first_non_finite(&self) -> Option<(usize, usize, f64)> {
        let cols = self.cols.max(1);
        self.data.iter().position(|x| !x.is_finite()).map(|k| {
            (
                k / cols,
                k % cols,
                self.data.get(k).copied().unwrap_or(f64::NAN),
            )
        })
    }

    /// (1 − w) a + w b (same shape).
    fn blend(a: &Dense, b: &Dense, w: f64) -> Dense {
        Dense {
            rows: a.rows,
            cols: a.cols,
            data: a
                .data
                .iter()
                .zip(&b.data)
                .map(|(&x, &y)| if w == 0.0 { x } else { x + w * (y - x) })
                .collect(),
        }
    }

    fn to_real(&self) -> Result<RealMatrix<CAPACITY>, MatrixError> {
        Ok(RealMatrix::from_fn(self.rows, self.cols, |i, j| {
            self.get(i, j)
        })?)
    }
}

/// Which value of a model an error is about. Each front end names it in its own words
/// ([`Key::file_name`]: the model file's keys; the Python binding maps it to its keywords).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// The file as a whole (its format, a missing section).
    File,
    /// `dofs`, the DOF names.
    Dofs,
    /// M.
    Mass,
    /// C.
    Damping,
    /// G.
    Gyroscopic,
    /// K.
    Stiffness,
    /// Ω.
    Speed,
    /// φ0.
    Phase,
    /// One field of unbalance `i` (`dof_x`, `dof_y`, `m_e`, `phase`).
    Unbalance(usize, &'static str),
    /// The constant force u.
    Force,
    /// One field of the rub station (`dof_x`, `dof_y`, `stator`, `clearance`,
    /// `contact_stiffness`, `friction_coefficient`, `radius`, `offset`).
    Rub(&'static str),
    /// The initial positions.
    InitialPositions,
    /// The initial velocities.
    InitialVelocities,
    /// One field of speed point `i` (`speed`, `damping`, `stiffness`).
    SpeedDependent(usize, &'static str),
}

impl Key {
    /// The key as a model file spells it (`rub.clearance`, `unbalance[1].m_e`, …).
    pub fn file_name(self) -> String {
        match self {
            Key::File => "model".into(),
            Key::Dofs => "dofs".into(),
            Key::Mass => "matrices.mass".into(),
            Key::Damping => "matrices.damping".into(),
            Key::Gyroscopic => "matrices.gyroscopic".into(),
            Key::Stiffness => "matrices.stiffness".into(),
            Key::Speed => "speed".into(),
            Key::Phase => "phase".into(),
            Key::Unbalance(i, f) => format!("unbalance[{i}].{f}"),
            Key::Force => "force".into(),
            Key::Rub(f) => format!("rub.{f}"),
            Key::InitialPositions => "initial.positions".into(),
            Key::InitialVelocities => "initial.velocities".into(),
            Key::SpeedDependent(i, f) => format!("speed_dependent[{i}].{f}"),
        }
    }
}

/// A model that cannot be read or stated: which value ([`Key`]) and what is wrong with it (the
/// text after the key's name: ` = -1 is out of range: it must be > 0 (m)`).
#[derive(Clone, Debug, PartialEq)]
pub struct ModelError {
    /// The value.
    pub key: Key,
    /// What is wrong, to follow the key's name.
    pub detail: String,
}

impl ModelError {
    /// An error about `key`.
    pub fn new(key: Key, detail: impl Into<String>) -> Self {
        ModelError {
            key,
            detail: detail.into(),
        }
    }

    /// The message with the key named by `name`.
    pub fn message_with(&self, name: &str) -> String {
        format!("{name}{}", self.detail)
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message_with(&self.key.file_name()))
    }
}

impl std::error::Error for ModelError {}

/// One unbalance, SI: m·e in kg·m at the DOF pair (x, y), `phase` rad ahead of the forcing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnbalanceSpec {
    /// The DOF of its x force.
    pub dof_x: usize,
    /// The DOF of its y force.
    pub dof_y: usize,
    /// m·e, kg·m.
    pub m_e: f64,
    /// φ, rad.
    pub phase: f64,
}

/// The rub station, SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RubSpec {
    /// The rotor point's x DOF.
    pub dof_x: usize,
    /// The rotor point's y DOF.
    pub dof_y: usize,
    /// The stator point's (x, y) DOFs; `None`: a fixed stator.
    pub stator: Option<(usize, usize)>,
    /// δ, the radial clearance, m.
    pub clearance: f64,
    /// K_c, N/m (a number k is k·I).
    pub contact_stiffness: [[f64; 2]; 2],
    /// μ.
    pub friction_coefficient: f64,
    /// R, the rotor's radius at the station, m (needed with friction: the surface speed ΩR).
    pub radius: Option<f64>,
    /// The stator centre from the rotor point's rest position, m.
    pub offset: (f64, f64),
}

/// C and K at one speed (each `None`: the base matrix).
#[derive(Clone, Debug, PartialEq)]
pub struct SpeedPoint {
    /// Ω, rad/s.
    pub speed: f64,
    /// C at Ω, N·s/m.
    pub damping: Option<Dense>,
    /// K at Ω, N/m.
    pub stiffness: Option<Dense>,
}

/// A rotor from matrices with a rub station, in SI units, as a file or Python states it.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelSpec {
    /// A name for reports (may be empty).
    pub name: String,
    /// The DOFs' names (n entries; `q0`, `q1`, … when the file gives none).
    pub dofs: Vec<String>,
    /// M, kg (kg·m² on rotations).
    pub mass: Dense,
    /// C, N·s/m.
    pub damping: Dense,
    /// G, multiplied by Ω (C + ΩG).
    pub gyroscopic: Dense,
    /// K, N/m.
    pub stiffness: Dense,
    /// Ω, rad/s.
    pub speed: f64,
    /// φ0, rad: the forcing phase θ = Ωt + φ0.
    pub phase: f64,
    /// The unbalances.
    pub unbalances: Vec<UnbalanceSpec>,
    /// A constant force per DOF, N (empty: none).
    pub force: Vec<f64>,
    /// The rub station.
    pub rub: RubSpec,
    /// The initial positions and velocities (m, m/s; `None`: rest).
    pub initial: Option<(Vec<f64>, Vec<f64>)>,
    /// C and K at listed speeds, increasing (empty: independent of the speed).
    pub speed_dependent: Vec<SpeedPoint>,
}

/// The default DOF names q0 … q{n−1}.
pub fn default_dof_names(n: usize) -> Vec<String> {
    (0..n).map(|i| format!("q{i}")).collect()
}

fn out_of_range(key: Key, value: f64, valid: &str) -> ModelError {
    ModelError::new(
        key,
        format!(" = {} is out of range: it must be {valid}", Number(value)),
    )
}

fn finite(key: Key, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ModelError::new(
            key,
            format!(" = {value} is not a finite number"),
        ))
    }
}

fn positive(key: Key, value: f64, unit: &str) -> Result<f64, ModelError> {
    finite(key, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(out_of_range(key, value, &format!("a number > 0 ({unit})")))
    }
}

fn in_range(key: Key, value: f64, valid: Range, unit: &str) -> Result<f64, ModelError> {
    finite(key, value)?;
    if valid.contains(value) {
        Ok(value)
    } else {
        Err(out_of_range(key, value, &format!("in {valid} ({unit})")))
    }
}

fn dof(key: Key, index: usize, n: usize) -> Result<usize, ModelError> {
    if index < n {
        Ok(index)
    } else {
        Err(ModelError::new(
            key,
            format!(
                " = {index} is not a degree of freedom of the model: it must be in [0, {}]",
                n.saturating_sub(1)
            ),
        ))
    }
}

fn square(key: Key, a: &Dense, n: usize) -> Result<(), ModelError> {
    if a.rows != n || a.cols != n {
        return Err(ModelError::new(
            key,
            format!(
                " is {} × {}; it must be n × n = {n} × {n} (n from the mass matrix)",
                a.rows, a.cols
            ),
        ));
    }
    if a.data.len() != n * n {
        return Err(ModelError::new(
            key,
            format!(" has {} entries; it must have {}", a.data.len(), n * n),
        ));
    }
    if let Some((i, j, v)) = a.first_non_finite() {
        return Err(ModelError::new(
            key,
            format!("[{i}][{j}] = {v} is not a finite number"),
        ));
    }
    Ok(())
}

fn vector(key: Key, v: &[f64], n: usize) -> Result<(), ModelError> {
    if v.len() != n {
        return Err(ModelError::new(
            key,
            format!(" has {} entries; it must have n = {n}", v.len()),
        ));
    }
    if let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(ModelError::new(
            key,
            format!("[{i}] = {x} is not a finite number"),
        ));
    }
    Ok(())
}

/// The largest |offset| in clearances, as the runtime's `offset_x`/`offset_y` range allows.
fn offset_limit() -> f64 {
    Parameter::OffsetX.range().max
}

impl ModelSpec {
    /// n, the number of degrees of freedom (the mass matrix's size).
    pub fn dofs(&self) -> usize {
        self.mass.rows
    }

    /// Check every value, naming the first that is wrong. [`ModelSpec::build`] checks the rest
    /// (M symmetric positive definite, the contact stiffness's definiteness) through the
    /// runtime.
    ///
    /// # Errors
    /// The first [`ModelError`].
    pub fn check(&self) -> Result<(), ModelError> {
        let n = self.dofs();
        if n == 0 {
            return Err(ModelError::new(
                Key::Mass,
                " is empty: a model needs at least the rub station's two degrees of freedom",
            ));
        }
        if n > MAX_DOFS {
            return Err(ModelError::new(
                Key::Mass,
                format!(
                    " is {n} × {n}: this build holds at most {MAX_DOFS} degrees of freedom (reduce the model, e.g. to its lowest modes)"
                ),
            ));
        }
        if self.dofs.len() != n {
            return Err(ModelError::new(
                Key::Dofs,
                format!(
                    " has {} names; the model has n = {n} degrees of freedom",
                    self.dofs.len()
                ),
            ));
        }
        if let Some((i, name)) = self
            .dofs
            .iter()
            .enumerate()
            .find(|(i, d)| self.dofs.iter().take(*i).any(|e| e == *d))
        {
            return Err(ModelError::new(
                Key::Dofs,
                format!(
                    "[{i}] = \"{}\" names a degree of freedom twice",
                    name.escape_debug()
                ),
            ));
        }
        for (key, a) in [
            (Key::Mass, &self.mass),
            (Key::Damping, &self.damping),
            (Key::Gyroscopic, &self.gyroscopic),
            (Key::Stiffness, &self.stiffness),
        ] {
            square(key, a, n)?;
        }
        in_range(Key::Speed, self.speed, SPEED_RANGE, "rad/s")?;
        in_range(Key::Phase, self.phase, Parameter::Phase.range(), "rad")?;
        for (i, u) in self.unbalances.iter().enumerate() {
            dof(Key::Unbalance(i, "dof_x"), u.dof_x, n)?;
            dof(Key::Unbalance(i, "dof_y"), u.dof_y, n)?;
            if u.dof_x == u.dof_y {
                return Err(ModelError::new(
                    Key::Unbalance(i, "dof_y"),
                    format!(
                        " = {} is also its dof_x: an unbalance acts on two different degrees of freedom",
                        u.dof_y
                    ),
                ));
            }
            finite(Key::Unbalance(i, "m_e"), u.m_e)?;
            if u.m_e < 0.0 {
                return Err(out_of_range(
                    Key::Unbalance(i, "m_e"),
                    u.m_e,
                    "≥ 0 (kg·m; turn it by its phase instead)",
                ));
            }
            finite(Key::Unbalance(i, "phase"), u.phase)?;
        }
        if !self.force.is_empty() {
            vector(Key::Force, &self.force, n)?;
        }
        self.check_rub(n)?;
        if let Some((q, v)) = &self.initial {
            vector(Key::InitialPositions, q, n)?;
            vector(Key::InitialVelocities, v, n)?;
        }
        self.check_speeds(n)
    }

    fn check_rub(&self, n: usize) -> Result<(), ModelError> {
        let r = &self.rub;
        let mut used = vec![(r.dof_x, Key::Rub("dof_x")), (r.dof_y, Key::Rub("dof_y"))];
        if let Some((x, y)) = r.stator {
            used.push((x, Key::Rub("stator")));
            used.push((y, Key::Rub("stator")));
        }
        for (i, &(d, key)) in used.iter().enumerate() {
            dof(key, d, n)?;
            if used.iter().take(i).any(|&(e, _)| e == d) {
                return Err(ModelError::new(
                    key,
                    format!(
                        " uses degree of freedom {d} ({}) again: the rotor point's x and y and the stator point's x and y must be four different degrees of freedom",
                        self.dofs.get(d).map_or("", String::as_str)
                    ),
                ));
            }
        }
        let delta = positive(Key::Rub("clearance"), r.clearance, "m")?;
        let k = r.contact_stiffness;
        for (i, &x) in k.iter().flatten().enumerate() {
            if !x.is_finite() {
                return Err(ModelError::new(
                    Key::Rub("contact_stiffness"),
                    format!("[{}][{}] = {x} is not a finite number", i / 2, i % 2),
                ));
            }
        }
        let cross = 0.5 * (k[0][1] + k[1][0]);
        let det = k[0][0] * k[1][1] - cross * cross;
        if !(k[0][0] > 0.0 && k[1][1] > 0.0 && det > 0.0) {
            return Err(ModelError::new(
                Key::Rub("contact_stiffness"),
                format!(
                    " = [[{}, {}], [{}, {}]] is not positive definite (its symmetric part): a contact pushes the rotor back out (N/m; a number k means k·I, k > 0)",
                    Number(k[0][0]),
                    Number(k[0][1]),
                    Number(k[1][0]),
                    Number(k[1][1])
                ),
            ));
        }
        in_range(
            Key::Rub("friction_coefficient"),
            r.friction_coefficient,
            Parameter::FrictionCoefficient.range(),
            "dimensionless",
        )?;
        match r.radius {
            Some(radius) => {
                positive(Key::Rub("radius"), radius, "m")?;
                let ratio = radius / delta;
                let valid = Parameter::RadiusRatio.range();
                if !valid.contains(ratio) {
                    return Err(ModelError::new(
                        Key::Rub("radius"),
                        format!(
                            " = {} m is {} clearances: radius/clearance must be in {valid}",
                            Number(radius),
                            Number(ratio)
                        ),
                    ));
                }
            }
            None if r.friction_coefficient > 0.0 => {
                return Err(ModelError::new(
                    Key::Rub("radius"),
                    format!(
                        " is missing: with friction_coefficient = {} the slip velocity needs the rotor's radius at the station (m)",
                        Number(r.friction_coefficient)
                    ),
                ));
            }
            None => {}
        }
        for (component, o) in [r.offset.0, r.offset.1].into_iter().enumerate() {
            finite(Key::Rub("offset"), o).map_err(|e| ModelError {
                detail: format!("[{component}]{}", e.detail),
                ..e
            })?;
        }
        let limit = offset_limit();
        for o in [r.offset.0, r.offset.1] {
            if (o / delta).abs() > limit {
                return Err(ModelError::new(
                    Key::Rub("offset"),
                    format!(
                        " = ({}, {}) m is more than {} clearances ({} m) from the rotor point's rest position in x or y",
                        Number(r.offset.0),
                        Number(r.offset.1),
                        Number(limit),
                        Number(limit * delta)
                    ),
                ));
            }
        }
        Ok(())
    }

    fn check_speeds(&self, n: usize) -> Result<(), ModelError> {
        let mut last = f64::NEG_INFINITY;
        for (i, p) in self.speed_dependent.iter().enumerate() {
            let speed = in_range(
                Key::SpeedDependent(i, "speed"),
                p.speed,
                SPEED_RANGE,
                "rad/s",
            )?;
            if speed <= last {
                return Err(ModelError::new(
                    Key::SpeedDependent(i, "speed"),
                    format!(
                        " = {} does not increase: the speeds must be listed in increasing order (the one before is {})",
                        Number(speed),
                        Number(last)
                    ),
                ));
            }
            last = speed;
            if p.damping.is_none() && p.stiffness.is_none() {
                return Err(ModelError::new(
                    Key::SpeedDependent(i, "speed"),
                    format!(
                        " = {}: the point gives neither damping nor stiffness",
                        Number(speed)
                    ),
                ));
            }
            if let Some(c) = &p.damping {
                square(Key::SpeedDependent(i, "damping"), c, n)?;
            }
            if let Some(k) = &p.stiffness {
                square(Key::SpeedDependent(i, "stiffness"), k, n)?;
            }
        }
        if !self.speed_dependent.is_empty() {
            self.speed_range_holds(Key::Speed, self.speed)?;
        }
        Ok(())
    }

    /// The listed speeds' range, when the matrices depend on the speed.
    pub fn speed_range(&self) -> Option<(f64, f64)> {
        let first = self.speed_dependent.first()?;
        let last = self.speed_dependent.last()?;
        Some((first.speed, last.speed))
    }

    fn speed_range_holds(&self, key: Key, speed: f64) -> Result<(), ModelError> {
        match self.speed_range() {
            Some((lo, hi)) if !(lo..=hi).contains(&speed) => Err(out_of_range(
                key,
                speed,
                &format!(
                    "within the speeds the matrices are given at, [{}, {}] rad/s (speed_dependent)",
                    Number(lo),
                    Number(hi)
                ),
            )),
            _ => Ok(()),
        }
    }

    /// C and K at `speed`: the base matrices, or interpolated linearly in the speed between the
    /// two listed speeds around it (a point without one of them uses the base matrix there).
    ///
    /// # Errors
    /// A speed outside the listed speeds (named by `key`).
    pub fn matrices_at(&self, key: Key, speed: f64) -> Result<(Dense, Dense), ModelError> {
        if self.speed_dependent.is_empty() {
            return Ok((self.damping.clone(), self.stiffness.clone()));
        }
        self.speed_range_holds(key, speed)?;
        let points = &self.speed_dependent;
        let upper = points
            .iter()
            .position(|p| p.speed >= speed)
            .unwrap_or(points.len() - 1);
        let lower = upper.saturating_sub(1);
        let (a, b) = (&points[lower], &points[upper]);
        let w = if b.speed > a.speed {
            (speed - a.speed) / (b.speed - a.speed)
        } else {
            0.0
        };
        let pick = |m: &Option<Dense>, base: &Dense| m.clone().unwrap_or_else(|| base.clone());
        let c = Dense::blend(
            &pick(&a.damping, &self.damping),
            &pick(&b.damping, &self.damping),
            w,
        );
        let k = Dense::blend(
            &pick(&a.stiffness, &self.stiffness),
            &pick(&b.stiffness, &self.stiffness),
            w,
        );
        Ok((c, k))
    }

    /// The runtime's statement at the running speed (lengths in clearances), boxed.
    ///
    /// # Errors
    /// The first value that is wrong ([`ModelSpec::check`]), or what the runtime refuses
    /// (M not symmetric positive definite, …) named by its key.
    pub fn build(&self) -> Result<Box<Model>, ModelError> {
        self.build_at(self.speed)
    }

    /// The statement at another running speed Ω (a sweep or a run-up point): the matrices
    /// re-evaluated there when they depend on the speed.
    ///
    /// # Errors
    /// As [`ModelSpec::build`]; a speed out of range or outside the listed speeds.
    pub fn build_at(&self, speed: f64) -> Result<Box<Model>, ModelError> {
        self.check()?;
        in_range(Key::Speed, speed, SPEED_RANGE, "rad/s")?;
        let (damping, stiffness) = self.matrices_at(Key::Speed, speed)?;
        let delta = self.rub.clearance;
        let unbalances: Vec<Unbalance> = self
            .unbalances
            .iter()
            .map(|u| Unbalance {
                x: u.dof_x,
                y: u.dof_y,
                amount: u.m_e / delta,
                phase: u.phase,
            })
            .collect();
        let force: Vec<f64> = self.force.iter().map(|f| f / delta).collect();
        let r = &self.rub;
        let station = Station {
            rotor: (r.dof_x, r.dof_y),
            stator: r.stator,
            offset: (r.offset.0 / delta, r.offset.1 / delta),
            contact_stiffness: r.contact_stiffness,
            friction_coefficient: r.friction_coefficient,
            // Without friction the radius only enters the slip velocity, which is not tracked.
            radius_ratio: r.radius.map_or(1.0, |radius| radius / delta),
        };
        let running = Running {
            speed_ratio: speed,
            phase: self.phase,
        };
        let (mass, gyroscopic) = (&self.mass, &self.gyroscopic);
        on_large_stack(move || {
            let real = |key: Key, a: &Dense| a.to_real().map_err(|e| runtime_error(key, e));
            let m = Box::new(real(Key::Mass, mass)?);
            let c = Box::new(real(Key::Damping, &damping)?);
            let g = Box::new(real(Key::Gyroscopic, gyroscopic)?);
            let k = Box::new(real(Key::Stiffness, &stiffness)?);
            let rotor = SecondOrder {
                mass: &m,
                damping: &c,
                gyroscopic: &g,
                stiffness: &k,
            };
            Model::new(&rotor, running, &unbalances, &force, station)
                .map(Box::new)
                .map_err(|e| runtime_error(Key::File, e))
        })
    }

    /// The start state in clearances (rest when the spec gives none).
    ///
    /// # Errors
    /// The initial state's shape or values.
    pub fn start(&self) -> Result<ModelState, ModelError> {
        let n = self.dofs();
        let delta = self.rub.clearance;
        match &self.initial {
            None => ModelState::rest(n).map_err(|e| runtime_error(Key::Mass, e)),
            Some((q, v)) => {
                vector(Key::InitialPositions, q, n)?;
                vector(Key::InitialVelocities, v, n)?;
                let q: Vec<f64> = q.iter().map(|x| x / delta).collect();
                let v: Vec<f64> = v.iter().map(|x| x / delta).collect();
                ModelState::new(&q, &v).map_err(|e| runtime_error(Key::InitialPositions, e))
            }
        }
    }

    /// The eigenvalues of the first-order matrix A at the running speed (rad/s), sorted by
    /// modulus, smallest first.
    ///
    /// # Errors
    /// As [`ModelSpec::build`], or a failed eigenvalue iteration.
    pub fn eigenvalues(&self) -> Result<Vec<Complex>, ModelError> {
        let model = self.build()?;
        on_large_stack(move || {
            let mut out = vec![Complex::ZERO; 2 * model.dofs()];
            let n = eigenvalues(model.first_order(), &mut out)
                .map_err(|e| runtime_error(Key::File, MatrixError::Linalg(e)))?;
            out.truncate(n);
            out.reverse();
            Ok(out)
        })
    }
}

/// A runtime refusal as a model error: the matrices' faults named by their key.
fn runtime_error(fallback: Key, e: MatrixError) -> ModelError {
    use rotor_rub::linalg::LinalgError;
    let key = match e {
        MatrixError::Linalg(
            LinalgError::MassNotSymmetric { .. } | LinalgError::MassNotPositiveDefinite { .. },
        ) => Key::Mass,
        MatrixError::Linalg(LinalgError::Singular { what, .. }) if what.contains("mass") => {
            Key::Mass
        }
        _ => fallback,
    };
    let text = e.to_string();
    let text = text
        .strip_prefix("mass matrix is ")
        .or_else(|| text.strip_prefix("mass matrix "))
        .filter(|_| key == Key::Mass)
        .map_or_else(|| format!(": {text}"), |rest| format!(" is {rest}"));
    ModelError::new(key, text)
}

/// Run `f` on a thread with a 64 MiB stack: a model of capacity 128 is ~1 MiB of matrices and
/// the eigenvalue iteration works on ~0.5 MiB of stack, more than a worker thread's 2 MiB holds
/// in a debug build. Called on such a thread already (a run-up's steps), `f` runs there.
pub fn on_large_stack<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    if LARGE_STACK.with(std::cell::Cell::get) {
        return not_inlined(f);
    }
    std::thread::scope(|scope| {
        match std::thread::Builder::new()
            .name("rotor-rub model".into())
            .stack_size(64 << 20)
            .spawn_scoped(scope, || {
                LARGE_STACK.with(|flag| flag.set(true));
                not_inlined(f)
            }) {
            Ok(handle) => match handle.join() {
                Ok(value) => value,
                Err(panic) => std::panic::resume_unwind(panic),
            },
            // No thread to be had: run here (a main thread's stack holds it).
            Err(_) => unreachable_spawn(),
        }
    })
}

/// `f()` in a frame of its own: inlined into [`on_large_stack`], `f`'s locals (a model of
/// capacity 128) would be part of the caller's frame, reserved (and stack-probed) on entry on
/// the small stack too, where the call that runs `f` in place is never taken (a stack overflow
/// in release builds).
#[inline(never)]
fn not_inlined<T>(f: impl FnOnce() -> T) -> T {
    f()
}

thread_local! {
    /// Whether this thread is one [`on_large_stack`] started.
    static LARGE_STACK: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Spawning a thread fails only when the system is out of threads or memory: nothing can run.
fn unreachable_spawn<T>() -> T {
    panic!("cannot start a thread for the model: the system is out of threads or memory")
}
