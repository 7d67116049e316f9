//! The FMU built for a model file (`cargo xtask fmu --model FILE`, issue 29 item 5): a rotor
//! from matrices with n ≤ [`MAX_DOFS`] degrees of freedom (the stator ring with mass is its
//! n = 4 instance), stepped by `MatrixStepper<OwnedModel<8>, 8>`.
//!
//! The xtask reads the model file with the CLI's reader (`rotor_rub_cli::model_file::load`, the
//! one reader), states its matrices at the file's running speed and writes them, in SI, as the
//! FMU's resource [`RESOURCE`] in the plain text format of [`FileModel::to_text`]: one
//! `key value…` line per item, every number in Rust's shortest round-trip form, so the FMU
//! reads back the exact `f64`s. The FMU parses it at instantiation (the one place it may
//! allocate) and states the runtime model exactly as the CLI does (`ModelSpec::build`: lengths,
//! m·e and forces divided by the clearance δ; time in s, speed in rad/s unchanged), so the
//! FMU's states are the CLI's `simulate --model` states.
//!
//! `run.rs` is the instance's model (variables, communication step); `description.rs` its
//! `modelDescription.xml` and token; `resource.rs` finds and reads the resource.

pub mod description;
pub mod resource;
pub mod run;

use rotor_rub::linalg::{RealMatrix, SecondOrder};
use rotor_rub::matrix::{MatrixModel, MatrixState, Running, Station, Unbalance};
use rotor_rub::stepper::OwnedModel;

/// First-order capacity of the model-file FMU's stepper.
pub const CAPACITY: usize = 8;
/// The most degrees of freedom a model-file FMU holds.
pub const MAX_DOFS: usize = CAPACITY / 2;
/// The resource file's name (in the FMU's `resources/`).
pub const RESOURCE: &str = "rotor_rub_model.txt";
/// The resource format's first line.
const HEADER: &str = "rotor-rub model-file FMU resource 1";

/// One unbalance in SI: m·e (kg·m) on the DOF pair at angle `phase` (rad).
#[derive(Clone, Debug, PartialEq)]
pub struct FileUnbalance {
    /// The DOF of its x force.
    pub dof_x: usize,
    /// The DOF of its y force.
    pub dof_y: usize,
    /// m·e, kg·m.
    pub m_e: f64,
    /// Its phase, rad.
    pub phase: f64,
}

/// A model file stated at its running speed, in SI: what the FMU's resource holds.
#[derive(Clone, Debug, PartialEq)]
pub struct FileModel {
    /// The model's name.
    pub name: String,
    /// The DOF names (n of them): the FMU's variables are named after them.
    pub dofs: Vec<String>,
    /// M, C (at the running speed), G, K (at the running speed): n × n each, row-major.
    pub mass: Vec<f64>,
    /// C at the running speed.
    pub damping: Vec<f64>,
    /// G (multiplied by Ω).
    pub gyroscopic: Vec<f64>,
    /// K at the running speed.
    pub stiffness: Vec<f64>,
    /// Ω, rad/s.
    pub speed: f64,
    /// The forcing phase at t = 0, rad.
    pub phase: f64,
    /// The unbalances.
    pub unbalances: Vec<FileUnbalance>,
    /// The constant force per DOF, N (the start values of the FMU's force inputs).
    pub force: Vec<f64>,
    /// The rub station's rotor DOF pair.
    pub rub: (usize, usize),
    /// The stator point's DOF pair (`None`: a fixed stator).
    pub stator: Option<(usize, usize)>,
    /// δ, m.
    pub clearance: f64,
    /// K_c, N/m (rows: x, y force).
    pub contact_stiffness: [[f64; 2]; 2],
    /// μ.
    pub friction_coefficient: f64,
    /// R, m (`None`: not given, only allowed without friction).
    pub radius: Option<f64>,
    /// ε, m: the stator centre from the rotor point's rest position.
    pub offset: (f64, f64),
    /// The start positions and velocities (m, m/s; rad, rad/s on tilts), n each.
    pub initial: (Vec<f64>, Vec<f64>),
}

fn numbers(out: &mut String, key: &str, values: &[f64]) {
    out.push_str(key);
    for v in values {
        out.push(' ');
        // `{:?}` is the shortest text that parses back to the same f64 (and keeps -0.0).
        out.push_str(&format!("{v:?}"));
    }
    out.push('\n');
}

impl FileModel {
    /// n, the number of degrees of freedom.
    pub fn n(&self) -> usize {
        self.dofs.len()
    }

    /// The resource text: `key value…` lines, numbers exact (see the module docs).
    pub fn to_text(&self) -> String {
        let mut out = format!("{HEADER}\n");
        out.push_str(&format!("name {}\n", self.name.replace('\n', " ")));
        out.push_str(&format!("dofs {}\n", self.dofs.join(" ")));
        for (key, m) in [
            ("mass", &self.mass),
            ("damping", &self.damping),
            ("gyroscopic", &self.gyroscopic),
            ("stiffness", &self.stiffness),
        ] {
            numbers(&mut out, key, m);
        }
        numbers(&mut out, "speed", &[self.speed]);
        numbers(&mut out, "phase", &[self.phase]);
        for u in &self.unbalances {
            out.push_str(&format!(
                "unbalance {} {} {:?} {:?}\n",
                u.dof_x, u.dof_y, u.m_e, u.phase
            ));
        }
        numbers(&mut out, "force", &self.force);
        out.push_str(&format!("rub {} {}\n", self.rub.0, self.rub.1));
        if let Some((sx, sy)) = self.stator {
            out.push_str(&format!("stator {sx} {sy}\n"));
        }
        numbers(&mut out, "clearance", &[self.clearance]);
        let k = self.contact_stiffness;
        numbers(
            &mut out,
            "contact_stiffness",
            &[k[0][0], k[0][1], k[1][0], k[1][1]],
        );
        numbers(
            &mut out,
            "friction_coefficient",
            &[self.friction_coefficient],
        );
        if let Some(r) = self.radius {
            numbers(&mut out, "radius", &[r]);
        }
        numbers(&mut out, "offset", &[self.offset.0, self.offset.1]);
        numbers(&mut out, "initial_positions", &self.initial.0);
        numbers(&mut out, "initial_velocities", &self.initial.1);
        out
    }

    /// Read a resource text back ([`FileModel::to_text`]); the error names the line at fault.
    ///
    /// # Errors
    /// A message naming the key or line that is missing or malformed, or n out of 1 ..= 4.
    pub fn parse(text: &str) -> Result<FileModel, String> {
        let mut lines = text.lines();
        if lines.next() != Some(HEADER) {
            return Err(format!("the model resource does not start with {HEADER:?}"));
        }
        let mut m = FileModel {
            name: String::new(),
            dofs: Vec::new(),
            mass: Vec::new(),
            damping: Vec::new(),
            gyroscopic: Vec::new(),
            stiffness: Vec::new(),
            speed: f64::NAN,
            phase: 0.0,
            unbalances: Vec::new(),
            force: Vec::new(),
            rub: (usize::MAX, usize::MAX),
            stator: None,
            clearance: f64::NAN,
            contact_stiffness: [[f64::NAN; 2]; 2],
            friction_coefficient: 0.0,
            radius: None,
            offset: (0.0, 0.0),
            initial: (Vec::new(), Vec::new()),
        };
        for (index, line) in lines.enumerate() {
            let at = index + 2;
            let (key, rest) = line.split_once(' ').unwrap_or((line, ""));
            let floats = || -> Result<Vec<f64>, String> {
                rest.split_whitespace()
                    .map(|w| {
                        w.parse::<f64>()
                            .map_err(|_| format!("line {at} ({key}): {w:?} is not a number"))
                    })
                    .collect()
            };
            let indices = || -> Result<Vec<usize>, String> {
                rest.split_whitespace()
                    .map(|w| {
                        w.parse::<usize>()
                            .map_err(|_| format!("line {at} ({key}): {w:?} is not a DOF index"))
                    })
                    .collect()
            };
            let one = || -> Result<f64, String> {
                match floats()?.as_slice() {
                    [x] => Ok(*x),
                    v => Err(format!(
                        "line {at} ({key}): 1 number expected, {} given",
                        v.len()
                    )),
                }
            };
            let pair = |v: Vec<usize>| -> Result<(usize, usize), String> {
                match v.as_slice() {
                    [a, b] => Ok((*a, *b)),
                    _ => Err(format!("line {at} ({key}): 2 DOF indices expected")),
                }
            };
            match key {
                "name" => m.name = rest.to_owned(),
                "dofs" => m.dofs = rest.split_whitespace().map(str::to_owned).collect(),
                "mass" => m.mass = floats()?,
                "damping" => m.damping = floats()?,
                "gyroscopic" => m.gyroscopic = floats()?,
                "stiffness" => m.stiffness = floats()?,
                "speed" => m.speed = one()?,
                "phase" => m.phase = one()?,
                "unbalance" => {
                    let w: Vec<&str> = rest.split_whitespace().collect();
                    let parsed = match w.as_slice() {
                        [x, y, me, ph] => (x.parse(), y.parse(), me.parse(), ph.parse()),
                        _ => return Err(format!("line {at}: unbalance takes 4 values")),
                    };
                    match parsed {
                        (Ok(dof_x), Ok(dof_y), Ok(m_e), Ok(phase)) => {
                            m.unbalances.push(FileUnbalance {
                                dof_x,
                                dof_y,
                                m_e,
                                phase,
                            })
                        }
                        _ => return Err(format!("line {at}: malformed unbalance {rest:?}")),
                    }
                }
                "force" => m.force = floats()?,
                "rub" => m.rub = pair(indices()?)?,
                "stator" => m.stator = Some(pair(indices()?)?),
                "clearance" => m.clearance = one()?,
                "contact_stiffness" => match floats()?.as_slice() {
                    [a, b, c, d] => m.contact_stiffness = [[*a, *b], [*c, *d]],
                    _ => return Err(format!("line {at}: contact_stiffness takes 4 numbers")),
                },
                "friction_coefficient" => m.friction_coefficient = one()?,
                "radius" => m.radius = Some(one()?),
                "offset" => match floats()?.as_slice() {
                    [x, y] => m.offset = (*x, *y),
                    _ => return Err(format!("line {at}: offset takes 2 numbers")),
                },
                "initial_positions" => m.initial.0 = floats()?,
                "initial_velocities" => m.initial.1 = floats()?,
                "" => {}
                other => return Err(format!("line {at}: unknown key {other:?}")),
            }
        }
        let n = m.n();
        if !(1..=MAX_DOFS).contains(&n) {
            return Err(format!(
                "the model has {n} degrees of freedom: a model-file FMU holds 1 to {MAX_DOFS}"
            ));
        }
        for (key, len, want) in [
            ("mass", m.mass.len(), n * n),
            ("damping", m.damping.len(), n * n),
            ("gyroscopic", m.gyroscopic.len(), n * n),
            ("stiffness", m.stiffness.len(), n * n),
            ("force", m.force.len(), n),
            ("initial_positions", m.initial.0.len(), n),
            ("initial_velocities", m.initial.1.len(), n),
        ] {
            if len != want {
                return Err(format!("{key}: {len} numbers, {want} expected (n = {n})"));
            }
        }
        if !(m.clearance.is_finite() && m.clearance > 0.0) {
            return Err(format!(
                "clearance = {} must be a positive length (m)",
                m.clearance
            ));
        }
        Ok(m)
    }

    /// The runtime's statement (lengths in clearances), as `ModelSpec::build` states it.
    ///
    /// # Errors
    /// What the runtime refuses, as text naming the value.
    pub fn state(&self) -> Result<OwnedModel<CAPACITY>, String> {
        let n = self.n();
        let delta = self.clearance;
        let real = |a: &[f64]| {
            RealMatrix::<CAPACITY>::from_fn(n, n, |i, j| {
                a.get(i * n + j).copied().unwrap_or(f64::NAN)
            })
            .map_err(|e| e.to_string())
        };
        let (mass, damping) = (real(&self.mass)?, real(&self.damping)?);
        let (gyroscopic, stiffness) = (real(&self.gyroscopic)?, real(&self.stiffness)?);
        let rotor = SecondOrder {
            mass: &mass,
            damping: &damping,
            gyroscopic: &gyroscopic,
            stiffness: &stiffness,
        };
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
        let station = Station {
            rotor: self.rub,
            stator: self.stator,
            offset: (self.offset.0 / delta, self.offset.1 / delta),
            contact_stiffness: self.contact_stiffness,
            friction_coefficient: self.friction_coefficient,
            radius_ratio: self.radius.map_or(1.0, |r| r / delta),
        };
        let running = Running {
            speed_ratio: self.speed,
            phase: self.phase,
        };
        MatrixModel::new(&rotor, running, &unbalances, &force, station)
            .map(OwnedModel)
            .map_err(|e| e.to_string())
    }

    /// The start state in clearances.
    ///
    /// # Errors
    /// A start value that is not finite.
    pub fn start(&self) -> Result<MatrixState<CAPACITY>, String> {
        let scaled = |v: &[f64]| v.iter().map(|x| x / self.clearance).collect::<Vec<f64>>();
        MatrixState::new(&scaled(&self.initial.0), &scaled(&self.initial.1))
            .map_err(|e| e.to_string())
    }
}
