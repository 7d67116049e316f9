//! A speed profile: the speed ratio η(τ) as a piecewise-linear function of time, given by its
//! points (`docs/MODEL.md` §14), validated once against the parameter table's speed range and
//! the limits of a changing speed.

use core::fmt;

use super::piece::SpeedPiece;
use crate::params::{Number, Parameter, Range};

/// One point of a speed profile: the speed ratio at a time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpeedPoint {
    /// τ.
    pub time: f64,
    /// η at `time`.
    pub speed_ratio: f64,
}

impl SpeedPoint {
    /// The point (τ, η).
    pub const fn new(time: f64, speed_ratio: f64) -> Self {
        SpeedPoint { time, speed_ratio }
    }
}

/// The largest |dη/dτ| of a profile or ramp. A machine's run-up is far slower (a turbine
/// reaching 3000 rpm in a minute, ω_n = 157 rad/s: 2e-4; a small motor to 10 000 rpm in 2 s:
/// 5e-3); at 1 the speed changes by its own size within one natural period, and the
/// speed-change force η_m ρ̂ η' reaches the supercritical unbalance force η_m ρ̂.
pub const MAX_SPEED_RATE: f64 = 1.0;

/// The valid rates of a ramp, (0, [`MAX_SPEED_RATE`]] (a profile's pieces may also hold the
/// speed, rate 0).
pub const RAMP_RATE_RANGE: Range = Range::above(0.0, MAX_SPEED_RATE);

/// The valid times of a profile: the parameter table's range of the start time (the forcing
/// phase keeps an absolute error ≤ 1e-8 there).
pub fn time_range() -> Range {
    Parameter::StartTime.info().range
}

/// The valid speed ratios of a profile: the parameter table's.
pub fn speed_range() -> Range {
    Parameter::SpeedRatio.info().range
}

/// What a profile value is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// A time τ.
    Time,
    /// A speed ratio η.
    SpeedRatio,
}

impl Quantity {
    /// `time` or `speed_ratio`.
    pub const fn name(self) -> &'static str {
        match self {
            Quantity::Time => "time",
            Quantity::SpeedRatio => "speed_ratio",
        }
    }
}

/// Why a speed profile was refused. Point indices count from 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpeedProfileError {
    /// Fewer than two points: a profile spans from its first to its last point.
    TooFewPoints {
        /// The number of points given.
        count: usize,
    },
    /// A value is NaN or infinite.
    NonFinite {
        /// The point.
        index: usize,
        /// Which value.
        quantity: Quantity,
        /// The value.
        value: f64,
    },
    /// A value lies outside its valid range.
    OutOfRange {
        /// The point.
        index: usize,
        /// Which value.
        quantity: Quantity,
        /// The value.
        value: f64,
        /// Its valid range.
        range: Range,
    },
    /// A point's time is not after the previous point's.
    NotIncreasing {
        /// The point.
        index: usize,
        /// Its time.
        time: f64,
        /// The previous point's time.
        previous: f64,
    },
    /// The speed changes faster than [`MAX_SPEED_RATE`] between a point and the next.
    RateTooHigh {
        /// The point the piece starts at.
        index: usize,
        /// dη/dτ on the piece.
        rate: f64,
    },
}

impl SpeedProfileError {
    /// The point the error is about, if it is about one.
    pub const fn index(&self) -> Option<usize> {
        match *self {
            SpeedProfileError::TooFewPoints { .. } => None,
            SpeedProfileError::NonFinite { index, .. }
            | SpeedProfileError::OutOfRange { index, .. }
            | SpeedProfileError::NotIncreasing { index, .. }
            | SpeedProfileError::RateTooHigh { index, .. } => Some(index),
        }
    }
}

impl fmt::Display for SpeedProfileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            SpeedProfileError::TooFewPoints { count } => write!(
                f,
                "a speed profile needs at least 2 points (time, speed_ratio), it has {count}"
            ),
            SpeedProfileError::NonFinite {
                quantity, value, ..
            } => write!(f, "{} = {value} is not a finite number", quantity.name()),
            SpeedProfileError::OutOfRange {
                quantity,
                value,
                range,
                ..
            } => write!(
                f,
                "{} = {} is out of range: it must be in {range}",
                quantity.name(),
                Number(value)
            ),
            SpeedProfileError::NotIncreasing { time, previous, .. } => write!(
                f,
                "time = {} is not after the previous point's time {}: times must increase",
                Number(time),
                Number(previous)
            ),
            SpeedProfileError::RateTooHigh { rate, .. } => write!(
                f,
                "the speed changes at dη/dτ = {} up to the next point: |dη/dτ| must be at most {}",
                Number(rate),
                Number(MAX_SPEED_RATE)
            ),
        }
    }
}

impl core::error::Error for SpeedProfileError {}

/// A validated speed profile over borrowed points (no heap): η(τ) linear between consecutive
/// points, from the first point's time to the last's, held at the last speed after it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpeedProfile<'a> {
    points: &'a [SpeedPoint],
}

impl<'a> SpeedProfile<'a> {
    /// Check `points` (at least two; times finite, in [`time_range`] and increasing; speeds
    /// finite and in [`speed_range`]; |dη/dτ| ≤ [`MAX_SPEED_RATE`] between points). The first
    /// error in point order is reported.
    pub fn new(points: &'a [SpeedPoint]) -> Result<Self, SpeedProfileError> {
        if points.len() < 2 {
            return Err(SpeedProfileError::TooFewPoints {
                count: points.len(),
            });
        }
        let mut previous: Option<&SpeedPoint> = None;
        for (index, p) in points.iter().enumerate() {
            check(index, Quantity::Time, p.time, time_range())?;
            check(index, Quantity::SpeedRatio, p.speed_ratio, speed_range())?;
            if let Some(prev) = previous {
                if p.time <= prev.time {
                    return Err(SpeedProfileError::NotIncreasing {
                        index,
                        time: p.time,
                        previous: prev.time,
                    });
                }
                let rate = rate_between(prev, p);
                // A rounding's worth of slack: a ramp at exactly MAX_SPEED_RATE passes.
                if crate::math::abs(rate) > MAX_SPEED_RATE * (1.0 + 1e-12) {
                    return Err(SpeedProfileError::RateTooHigh {
                        index: index - 1,
                        rate,
                    });
                }
            }
            previous = Some(p);
        }
        Ok(SpeedProfile { points })
    }

    /// The points.
    pub fn points(&self) -> &'a [SpeedPoint] {
        self.points
    }

    /// The first point's time: where a run on the profile starts.
    pub fn start(&self) -> f64 {
        self.points.first().map_or(0.0, |p| p.time)
    }

    /// The last point's time: where the profile's program ends.
    pub fn end(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.time)
    }

    /// Whether the speed never changes (every point at the first point's speed).
    pub fn is_constant(&self) -> bool {
        let first = self.points.first().map_or(0.0, |p| p.speed_ratio);
        self.points.iter().all(|p| p.speed_ratio == first)
    }

    /// The piece starting at point `index` with phase constant `phase_constant`. Consecutive
    /// points at one speed make one piece (the speed is held across them, and after the last
    /// point).
    fn piece_at(&self, index: usize, phase_constant: f64) -> Option<SpeedPiece> {
        let p = self.points.get(index)?;
        let held = self
            .points
            .get(index + 1..)?
            .iter()
            .take_while(|q| q.speed_ratio == p.speed_ratio)
            .count();
        let end_index = index + held.max(1);
        // A speed held up to the last point is held after it too: one piece to the end.
        let last = held > 0 && end_index + 1 == self.points.len();
        Some(match self.points.get(end_index).filter(|_| !last) {
            Some(end) if held > 0 => SpeedPiece {
                index,
                end_index,
                start: p.time,
                end: end.time,
                speed_ratio: p.speed_ratio,
                rate: 0.0,
                phase_constant,
            },
            Some(next) => SpeedPiece {
                index,
                end_index,
                start: p.time,
                end: next.time,
                speed_ratio: p.speed_ratio,
                rate: rate_between(p, next),
                phase_constant,
            },
            None => SpeedPiece {
                index,
                end_index: self.points.len(),
                start: p.time,
                end: f64::INFINITY,
                speed_ratio: p.speed_ratio,
                rate: 0.0,
                phase_constant,
            },
        })
    }

    /// The first piece, with the forcing phase θ = η_0 τ + φ0 at its start (the constant-speed
    /// phase of a rotor with `phase` φ0).
    pub fn first_piece(&self, phase: f64) -> SpeedPiece {
        self.piece_at(0, phase).unwrap_or(SpeedPiece {
            index: 0,
            end_index: 1,
            start: 0.0,
            end: f64::INFINITY,
            speed_ratio: 1.0,
            rate: 0.0,
            phase_constant: phase,
        })
    }

    /// The piece after `piece` (θ continuous across the point between them); `None` after the
    /// last.
    pub fn next_piece(&self, piece: &SpeedPiece) -> Option<SpeedPiece> {
        let next = self.piece_at(piece.end_index, 0.0)?;
        Some(piece.continued_by(next))
    }

    /// The piece holding time `t` (the first piece for times before the start, the last after
    /// the end), walking on from `from` (pass the first piece to search from the start).
    pub fn piece_holding(&self, from: SpeedPiece, t: f64) -> SpeedPiece {
        let mut piece = from;
        while t >= piece.end {
            match self.next_piece(&piece) {
                Some(next) => piece = next,
                None => break,
            }
        }
        piece
    }
}

fn rate_between(a: &SpeedPoint, b: &SpeedPoint) -> f64 {
    (b.speed_ratio - a.speed_ratio) / (b.time - a.time)
}

fn check(
    index: usize,
    quantity: Quantity,
    value: f64,
    range: Range,
) -> Result<(), SpeedProfileError> {
    if !value.is_finite() {
        Err(SpeedProfileError::NonFinite {
            index,
            quantity,
            value,
        })
    } else if !range.contains(value) {
        Err(SpeedProfileError::OutOfRange {
            index,
            quantity,
            value,
            range,
        })
    } else {
        Ok(())
    }
}
