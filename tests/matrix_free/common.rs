//! Shared by the matrix free-flight tests: the reference files of `scripts/matrix_expm.py`
//! (`tests/data/matrix_free/*.txt`), the models they state, and running [`ExactFree`] to a
//! target.

use rotor_rub::driver::SegmentStart;
use std::collections::BTreeMap;
use std::path::PathBuf;

use rotor_rub::driver::{Located, SegmentSolver};
use rotor_rub::linalg::{RealMatrix, SecondOrder};
use rotor_rub::matrix::{ExactFree, MatrixModel, MatrixState, Running, Station, Unbalance};
use rotor_rub::propagate::{Event, PropagationError, Regime};

/// Storage for every case (n ≤ 20).
pub const CAP: usize = 40;

pub type Model = MatrixModel<CAP>;
pub type State = MatrixState<CAP>;
pub type Free<'a> = ExactFree<&'a Model, CAP>;

/// One reference file.
#[derive(Clone, Debug)]
pub struct Case {
    pub name: String,
    pub n: usize,
    pub speed: f64,
    pub phase: f64,
    pub mass: Vec<f64>,
    pub damping: Vec<f64>,
    pub gyroscopic: Vec<f64>,
    pub stiffness: Vec<f64>,
    pub unbalances: Vec<Unbalance>,
    pub input: Vec<f64>,
    pub rotor: (usize, usize),
    pub stator: Option<(usize, usize)>,
    pub offset: (f64, f64),
    pub t0: f64,
    pub y0: Vec<f64>,
    /// scipy's expm against the 30-digit mpmath one (largest relative difference).
    pub expm_check: Option<f64>,
    /// (t, y(t)) from a 30-digit mpmath expm of the augmented system.
    pub states: Vec<(f64, Vec<f64>)>,
    /// (t, y(t)) from scipy's expm of the augmented system (double precision).
    pub scipy: Vec<(f64, Vec<f64>)>,
    /// The first contact time (30-digit reference, parsed to the nearest double).
    pub contact: Option<f64>,
    /// No contact up to this time.
    pub no_contact_to: Option<f64>,
}

fn numbers(words: &[&str]) -> Vec<f64> {
    words.iter().map(|w| w.parse().unwrap()).collect()
}

pub fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/matrix_free")
}

impl Case {
    pub fn load(name: &str) -> Case {
        let path = data_dir().join(format!("{name}.txt"));
        let text = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("{}: {e} (run scripts/matrix_expm.py)", path.display()));
        let mut fields: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
        let mut case = Case {
            name: String::new(),
            n: 0,
            speed: 0.0,
            phase: 0.0,
            mass: vec![],
            damping: vec![],
            gyroscopic: vec![],
            stiffness: vec![],
            unbalances: vec![],
            input: vec![],
            rotor: (0, 1),
            stator: None,
            offset: (0.0, 0.0),
            t0: 0.0,
            y0: vec![],
            expm_check: None,
            states: vec![],
            scipy: vec![],
            contact: None,
            no_contact_to: None,
        };
        for line in text
            .lines()
            .filter(|l| !l.starts_with('#') && !l.is_empty())
        {
            let words: Vec<&str> = line.split_whitespace().collect();
            let (key, rest) = (words[0], &words[1..]);
            match key {
                "unbalance" => case.unbalances.push(Unbalance {
                    x: rest[0].parse().unwrap(),
                    y: rest[1].parse().unwrap(),
                    amount: rest[2].parse().unwrap(),
                    phase: rest[3].parse().unwrap(),
                }),
                "state" => {
                    let v = numbers(rest);
                    case.states.push((v[0], v[1..].to_vec()));
                }
                "scipy" => {
                    let v = numbers(rest);
                    case.scipy.push((v[0], v[1..].to_vec()));
                }
                "station" => {
                    case.rotor = (rest[0].parse().unwrap(), rest[1].parse().unwrap());
                    if rest[2] != "-" {
                        case.stator = Some((rest[2].parse().unwrap(), rest[3].parse().unwrap()));
                    }
                    case.offset = (rest[4].parse().unwrap(), rest[5].parse().unwrap());
                }
                _ => {
                    fields.insert(key, rest.to_vec());
                }
            }
        }
        case.name = fields["name"][0].to_string();
        case.n = fields["n"][0].parse().unwrap();
        case.speed = fields["speed"][0].parse().unwrap();
        case.phase = fields["phase"][0].parse().unwrap();
        case.mass = numbers(&fields["mass"]);
        case.damping = numbers(&fields["damping"]);
        case.gyroscopic = numbers(&fields["gyroscopic"]);
        case.stiffness = numbers(&fields["stiffness"]);
        case.input = numbers(&fields["input"]);
        let start = numbers(&fields["start"]);
        case.t0 = start[0];
        case.y0 = start[1..].to_vec();
        case.expm_check = fields.get("expm_check").map(|v| v[0].parse().unwrap());
        case.contact = fields.get("contact").map(|v| v[0].parse().unwrap());
        case.no_contact_to = fields.get("nocontact").map(|v| v[0].parse().unwrap());
        case
    }

    pub fn matrix(&self, data: &[f64]) -> RealMatrix<CAP> {
        RealMatrix::from_fn(self.n, self.n, |i, j| data[i * self.n + j]).unwrap()
    }

    pub fn station(&self) -> Station {
        Station {
            rotor: self.rotor,
            stator: self.stator,
            offset: self.offset,
            contact_stiffness: [[1.0, 0.0], [0.0, 1.0]],
            friction_coefficient: 0.0,
            radius_ratio: 100.0,
        }
    }

    pub fn model(&self) -> Model {
        self.try_model().unwrap()
    }

    pub fn try_model(&self) -> Result<Model, rotor_rub::matrix::MatrixError> {
        let (m, c, g, k) = (
            self.matrix(&self.mass),
            self.matrix(&self.damping),
            self.matrix(&self.gyroscopic),
            self.matrix(&self.stiffness),
        );
        let rotor = SecondOrder {
            mass: &m,
            damping: &c,
            gyroscopic: &g,
            stiffness: &k,
        };
        MatrixModel::new(
            &rotor,
            Running {
                speed_ratio: self.speed,
                phase: self.phase,
            },
            &self.unbalances,
            &self.input,
            self.station(),
        )
    }

    pub fn start(&self) -> State {
        let n = self.n;
        MatrixState::new(&self.y0[..n], &self.y0[n..]).unwrap()
    }
}

/// A solver started at `(t0, y0)`.
pub fn started(model: &Model, t0: f64, y0: State) -> Free<'_> {
    let mut free = ExactFree::new(model).unwrap();
    free.start(SegmentStart {
        regime: Regime::Free,
        slip: 0.0,
        time: t0,
        state: y0,
    })
    .unwrap();
    free
}

/// What the solver reports for `target`, stepping as the driver does.
pub fn run_to<S: SegmentSolver<State>>(solver: &mut S, target: f64) -> Located<State> {
    for _ in 0..1_000_000 {
        match solver.locate(target) {
            Located::NeedStep => solver.step().unwrap(),
            other => return other,
        }
    }
    panic!("no answer for {target}");
}

/// The state at `target` (no contact expected before it).
pub fn reached<S: SegmentSolver<State>>(solver: &mut S, target: f64) -> Vec<f64> {
    match run_to(solver, target) {
        Located::Reached(y) => y.as_slice().to_vec(),
        other => panic!("expected free flight to {target}, got {other:?}"),
    }
}

/// The first contact before `target`, if any.
pub fn contact<S: SegmentSolver<State>>(solver: &mut S, target: f64) -> Option<Event<State>> {
    match run_to(solver, target) {
        Located::Reached(_) => None,
        Located::Switch(e) => Some(e),
        Located::NeedStep => unreachable!(),
    }
}

pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// ‖a − b‖₂ / ‖b‖₂.
pub fn relative(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(&d) / norm(b)
}

/// Keep the error type in scope for callers matching on it.
pub type Error = PropagationError;

/// e^{Â(t − t0)} z0 of the augmented system z = (y, cos θ, sin θ, 1) by nalgebra's `exp`: an
/// independent free flight (no particular solution, no modal form), from the case's raw
/// matrices.
pub fn augmented_state(case: &Case, t0: f64, y0: &[f64], t: f64) -> Vec<f64> {
    use nalgebra::{DMatrix, DVector};
    let n = case.n;
    let m = 2 * n;
    let mat = |d: &[f64]| DMatrix::from_row_slice(n, n, d);
    let minv = mat(&case.mass).try_inverse().unwrap();
    let eta = case.speed;
    let mut a = DMatrix::zeros(m + 3, m + 3);
    let mk = -&minv * mat(&case.stiffness);
    let mc = -&minv * (mat(&case.damping) + mat(&case.gyroscopic) * eta);
    // f̂ = fc + i fs: an unbalance m e at φ on (x, y) forces m e (cos(θ + φ), sin(θ + φ)).
    let (mut fc, mut fs) = (DVector::zeros(n), DVector::zeros(n));
    for u in &case.unbalances {
        let (s, c) = u.phase.sin_cos();
        fc[u.x] += u.amount * c;
        fs[u.x] += u.amount * s;
        fc[u.y] += u.amount * s;
        fs[u.y] -= u.amount * c;
    }
    let vc = &minv * fc * (eta * eta);
    let vs = &minv * fs * (-eta * eta);
    let input = if case.input.is_empty() {
        DVector::zeros(n)
    } else {
        DVector::from_column_slice(&case.input)
    };
    let vu = &minv * input;
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = mk[(i, j)];
            a[(n + i, n + j)] = mc[(i, j)];
        }
        a[(n + i, m)] = vc[i];
        a[(n + i, m + 1)] = vs[i];
        a[(n + i, m + 2)] = vu[i];
    }
    a[(m, m + 1)] = -eta;
    a[(m + 1, m)] = eta;
    let theta = eta * t0 + case.phase;
    let mut z0 = DVector::zeros(m + 3);
    for (i, &v) in y0.iter().enumerate() {
        z0[i] = v;
    }
    z0[m] = theta.cos();
    z0[m + 1] = theta.sin();
    z0[m + 2] = 1.0;
    let z = (a * (t - t0)).exp() * z0;
    z.iter().take(m).copied().collect()
}

/// h = |P − ε̂|² − 1 of a state, from the case's station (independent of the model's code).
pub fn station_h(case: &Case, y: &[f64]) -> f64 {
    let (mut px, mut py) = (y[case.rotor.0], y[case.rotor.1]);
    if let Some((sx, sy)) = case.stator {
        px -= y[sx];
        py -= y[sy];
    }
    let (u, v) = (px - case.offset.0, py - case.offset.1);
    u * u + v * v - 1.0
}
