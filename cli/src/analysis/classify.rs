//! Response classification from a Poincaré section and the largest Lyapunov exponent.

use std::fmt;

use rotor_rub::State;

/// Two section points closer than this (max norm over x, y, vx, vy, in clearances and
/// clearances per unit τ) count as the same point.
pub const POINT_TOLERANCE: f64 = 1e-5;
/// The longest period reported as period-n; longer repetitions count as not periodic.
pub const MAX_PERIOD: usize = 32;
/// A largest Lyapunov exponent (per unit τ) above this is chaos; between −this and this the
/// motion is quasi-periodic.
pub const LYAPUNOV_THRESHOLD: f64 = 0.01;

/// What kind of steady response a section shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Response {
    /// The section repeats after n forcing periods.
    Periodic(usize),
    /// The section approaches an n-periodic orbit but has not reached it within the tolerance
    /// (a slowly attracting orbit: exponent slightly below 0).
    Converging(usize),
    /// Many distinct points, largest Lyapunov exponent ≈ 0.
    QuasiPeriodic,
    /// Many distinct points, largest Lyapunov exponent clearly > 0.
    Chaotic,
    /// Many distinct points but a clearly negative exponent: still converging (a longer
    /// transient would show the periodic orbit).
    Unsettled,
    /// Many distinct points and no exponent to decide with.
    NotPeriodic,
}

impl fmt::Display for Response {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Response::Periodic(n) => write!(f, "period-{n}"),
            Response::Converging(n) => write!(f, "period-{n} (converging)"),
            Response::QuasiPeriodic => f.write_str("quasi-periodic"),
            Response::Chaotic => f.write_str("chaotic"),
            Response::Unsettled => f.write_str("not settled"),
            Response::NotPeriodic => f.write_str("not periodic"),
        }
    }
}

fn distance(a: &State, b: &State) -> f64 {
    let (a, b) = (a.to_array(), b.to_array());
    (0..4).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// Number of distinct points up to [`POINT_TOLERANCE`] (greedy clustering).
pub fn distinct_points(points: &[State]) -> usize {
    let mut representatives: Vec<State> = Vec::new();
    for p in points {
        if !representatives
            .iter()
            .any(|r| distance(r, p) <= POINT_TOLERANCE)
        {
            representatives.push(*p);
        }
    }
    representatives.len()
}

/// The smallest n ≤ [`MAX_PERIOD`] with point k + n equal to point k (up to the tolerance) for
/// every k, when the section holds at least two repetitions of it.
pub fn period(points: &[State]) -> Option<usize> {
    (1..=MAX_PERIOD.min(points.len() / 2)).find(|&n| {
        points
            .iter()
            .zip(&points[n..])
            .all(|(a, b)| distance(a, b) <= POINT_TOLERANCE)
    })
}

/// The smallest n ≤ [`MAX_PERIOD`] for which the n-step differences |p(k+n) − p(k)| shrink by
/// more than a factor 4 from the first quarter of the section to the last, ending below 0.01.
pub fn converging_period(points: &[State]) -> Option<usize> {
    (1..=MAX_PERIOD.min(points.len() / 4)).find(|&n| {
        let d: Vec<f64> = points
            .iter()
            .zip(&points[n..])
            .map(|(a, b)| distance(a, b))
            .collect();
        let quarter = (d.len() / 4).max(1);
        let head = d[..quarter].iter().copied().fold(0.0, f64::max);
        let tail = d[d.len() - quarter..].iter().copied().fold(0.0, f64::max);
        tail < 0.25 * head && tail < 1e-2
    })
}

/// Classify a section, using the largest Lyapunov exponent (per unit τ) when the section does
/// not repeat.
pub fn classify(points: &[State], lyapunov: Option<f64>) -> Response {
    if let Some(n) = period(points) {
        return Response::Periodic(n);
    }
    if lyapunov.is_some_and(|l| l > LYAPUNOV_THRESHOLD) {
        return Response::Chaotic;
    }
    if let Some(n) = converging_period(points) {
        return Response::Converging(n);
    }
    match lyapunov {
        Some(l) if l < -LYAPUNOV_THRESHOLD => Response::Unsettled,
        Some(_) => Response::QuasiPeriodic,
        None => Response::NotPeriodic,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn period_two_section() {
        let a = State::new(0.1, 0.2, 0.0, 0.0);
        let b = State::new(-0.3, 0.2, 0.1, 0.0);
        let pts: Vec<State> = (0..10).map(|k| if k % 2 == 0 { a } else { b }).collect();
        assert_eq!(period(&pts), Some(2));
        assert_eq!(distinct_points(&pts), 2);
        assert_eq!(classify(&pts, None), Response::Periodic(2));
    }

    #[test]
    fn ring_is_quasi_periodic_or_chaotic_by_exponent() {
        let pts: Vec<State> = (0..100)
            .map(|k| {
                let a = k as f64 * 2.0;
                State::new(a.cos(), a.sin(), 0.0, 0.0)
            })
            .collect();
        assert_eq!(period(&pts), None);
        assert_eq!(classify(&pts, Some(0.001)), Response::QuasiPeriodic);
        assert_eq!(classify(&pts, Some(0.2)), Response::Chaotic);
        assert_eq!(classify(&pts, Some(-0.2)), Response::Unsettled);
    }

    #[test]
    fn slowly_attracting_two_cycle_is_converging() {
        let pts: Vec<State> = (0..100)
            .map(|k| {
                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                let r = 0.001 * (-0.03 * k as f64).exp();
                let a = k as f64 * 0.7;
                State::new(sign * 0.5 + r * a.cos(), r * a.sin(), 0.0, 0.0)
            })
            .collect();
        assert_eq!(period(&pts), None);
        assert_eq!(classify(&pts, Some(-0.005)), Response::Converging(2));
    }
}
