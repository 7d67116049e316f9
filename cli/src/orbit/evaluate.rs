//! The continuation's equations: for u = (s, p), a state on the section and a parameter value,
//! R(u) = P^k(s; p) − s = 0 with its Jacobian [M − I | ∂R/∂p]: M the monodromy from the segments
//! (`rotor_rub::orbit`), ∂R/∂p by a central difference of the map in p (the map's parameter
//! dependence has no closed form: η moves the period itself). The corrector is Newton's method
//! on R(u) = 0 with one more equation (the pseudo-arclength constraint, or a fixed parameter).

use rotor_rub::linalg::{Lu, RealMatrix};
use rotor_rub::orbit::{
    Extremum, MapObserver, MapPoint, MapSettings, Mat4, OrbitError, stroboscopic_map,
};
use rotor_rub::{Event, Parameter, Params, Problem, State};

use crate::error::{CliError, Result, num};

/// The unknowns (x, y, x', y', p).
pub type Vector5 = [f64; 5];

/// The map's evaluation at one u: its value, monodromy and what the orbit did.
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// (s, p).
    pub u: Vector5,
    /// P^k(s; p).
    pub point: MapPoint,
    /// R = P^k(s; p) − s.
    pub residual: [f64; 4],
    /// ∂R/∂p (when asked for).
    pub dp: Option<[f64; 4]>,
    /// The local extrema of z along the orbit (when asked for).
    pub extrema: Vec<Extremum>,
    /// The switches along the orbit (when extrema are asked for).
    pub events: Vec<Event>,
}

/// The map of one continuation problem: the parameters, the continued parameter, the period.
pub struct Evaluator<'a> {
    /// The parameters apart from the continued one.
    pub base: Params,
    /// The continued parameter.
    pub parameter: Parameter,
    /// k.
    pub periods: u32,
    /// How the map is computed.
    pub map: MapSettings,
    /// Called at every map evaluation with the parameter value: a progress report or a stop.
    pub poll: &'a mut dyn FnMut(f64) -> Result<()>,
    /// Map evaluations made.
    pub evaluations: u64,
}

/// An orbit error as the command line's error (a propagation failure is exit 1, an invalid
/// input exit 2).
pub fn orbit_error(context: &str, e: OrbitError) -> CliError {
    match e {
        OrbitError::Propagation(p) => CliError::propagation(context, p),
        OrbitError::InvalidPeriod { .. } | OrbitError::InvalidSetting { .. } => {
            CliError::input(format!("{context}{e}"))
        }
        _ => CliError::failure(format!("{context}{e}")),
    }
}

impl Evaluator<'_> {
    /// The parameters at value `p` of the continued parameter (validated).
    pub fn params_at(&self, p: f64) -> Result<Params> {
        let mut problem = Problem {
            params: self.base,
            ..Problem::DEFAULT
        };
        self.parameter.set(&mut problem, p);
        problem.params.validate().map_err(|e| {
            CliError::input(format!("{} = {}: {e}", self.parameter.info().name, num(p)))
        })?;
        Ok(problem.params)
    }

    fn run(
        &mut self,
        params: &Params,
        s: State,
        settings: &MapSettings,
        watch: &mut impl MapObserver,
    ) -> Result<MapPoint> {
        (self.poll)(self.parameter.get(&Problem {
            params: *params,
            ..Problem::DEFAULT
        }))?;
        self.evaluations += 1;
        let context = format!(
            "{} = {}: ",
            self.parameter.info().name,
            num(self.parameter.get(&Problem {
                params: *params,
                ..Problem::DEFAULT
            }))
        );
        stroboscopic_map(params, s, self.periods, settings, watch)
            .map_err(|e| orbit_error(&context, e))
    }

    /// The map at `u`: with the monodromy when `jacobian`, ∂R/∂p when `dp`, the extrema and
    /// switches when `extrema`.
    pub fn evaluate(
        &mut self,
        u: Vector5,
        jacobian: bool,
        dp: bool,
        extrema: bool,
    ) -> Result<Evaluation> {
        let s = State::new(u[0], u[1], u[2], u[3]);
        let params = self.params_at(u[4])?;
        let settings = MapSettings {
            jacobian,
            extrema,
            ..self.map
        };
        let mut collect = super::command::Collect::default();
        let point = self.run(&params, s, &settings, &mut collect)?;
        let end = point.state.to_array();
        let residual = [end[0] - u[0], end[1] - u[1], end[2] - u[2], end[3] - u[3]];
        let dp = if dp {
            Some(self.parameter_derivative(s, u[4])?)
        } else {
            None
        };
        Ok(Evaluation {
            u,
            point,
            residual,
            dp,
            extrema: collect.extrema,
            events: collect.events,
        })
    }

    /// ∂P^k/∂p at (s, p) by a central difference (one-sided at the table's range's edge), step
    /// 1e-6·max(1, |p|): the truncation error ~1e-12 relative, the trajectory's ~1e-6.
    fn parameter_derivative(&mut self, s: State, p: f64) -> Result<[f64; 4]> {
        let h = 1e-6 * p.abs().max(1.0);
        let range = self.parameter.range();
        let (lo, hi) = (
            if range.contains(p - h) { p - h } else { p },
            if range.contains(p + h) { p + h } else { p },
        );
        let settings = MapSettings {
            jacobian: false,
            extrema: false,
            ..self.map
        };
        let at = |me: &mut Self, v: f64| -> Result<[f64; 4]> {
            let params = me.params_at(v)?;
            Ok(me.run(&params, s, &settings, &mut ())?.state.to_array())
        };
        let (a, b) = (at(self, lo)?, at(self, hi)?);
        let d = hi - lo;
        Ok([
            (b[0] - a[0]) / d,
            (b[1] - a[1]) / d,
            (b[2] - a[2]) / d,
            (b[3] - a[3]) / d,
        ])
    }
}

/// |v|∞ of the state part.
pub fn state_norm(u: &Vector5) -> f64 {
    u[..4].iter().fold(0.0, |a: f64, v| a.max(v.abs()))
}

/// The 5 × 5 system `[[M − I, r_p], [cᵀ]]` of a corrector step, row-major.
pub fn bordered(monodromy: &Mat4, dp: &[f64; 4], constraint: &Vector5) -> [[f64; 5]; 5] {
    let mut a = [[0.0; 5]; 5];
    for i in 0..4 {
        for j in 0..4 {
            a[i][j] = monodromy[i][j] - if i == j { 1.0 } else { 0.0 };
        }
        a[i][4] = dp[i];
    }
    a[4] = *constraint;
    a
}

/// x solving a·x = b for a 5 × 5 matrix (LU with partial pivoting); `None` when singular.
pub fn solve5(a: &[[f64; 5]; 5], b: Vector5) -> Option<Vector5> {
    let rows: Vec<&[f64]> = a.iter().map(|r| r.as_slice()).collect();
    let m = RealMatrix::<5>::from_rows(&rows).ok()?;
    let lu = Lu::factor(&m, "continuation matrix").ok()?;
    let mut x = b;
    lu.solve(&mut x);
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The unit tangent of the branch at a point with monodromy `monodromy` and ∂R/∂p `dp`: the null
/// vector of [M − I | r_p], oriented along `previous` (its sign: the direction of travel).
pub fn tangent(monodromy: &Mat4, dp: &[f64; 4], previous: &Vector5) -> Option<Vector5> {
    let a = bordered(monodromy, dp, previous);
    let t = solve5(&a, [0.0, 0.0, 0.0, 0.0, 1.0])?;
    let n = norm5(&t);
    (n > 0.0 && n.is_finite()).then(|| t.map(|v| v / n))
}

/// The Euclidean norm.
pub fn norm5(v: &Vector5) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// a·b.
pub fn dot5(a: &Vector5, b: &Vector5) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
