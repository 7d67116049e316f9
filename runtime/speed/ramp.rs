//! Speed ramps: η from one speed to another at a constant rate, or over a number of forcing
//! periods of the mean speed, optionally held at the start (to let the start transient die
//! out), held at the turning speed and run back (a run-up followed by a coast-down), written as
//! the points of a [`SpeedProfile`] (no heap: at most [`MAX_RAMP_POINTS`]).

use core::f64::consts::TAU;
use core::fmt;

use super::profile::{
    RAMP_RATE_RANGE, SpeedPoint, SpeedProfile, SpeedProfileError, speed_range, time_range,
};
use crate::params::{Number, Range};

/// Most points a ramp needs: start, end of the settling hold, turning speed, end of the dwell
/// there, back at the start speed.
pub const MAX_RAMP_POINTS: usize = 5;

/// How fast a ramp runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RampPace {
    /// |dη/dτ|, in [`RAMP_RATE_RANGE`].
    Rate(f64),
    /// The ramp's length in forcing periods of its mean speed (a linear ramp from a to b lasts
    /// N·2π/((a + b)/2): exactly N turns of the unbalance), > 0.
    Periods(f64),
}

/// A ramp program: from `from` to `to` (and back, unless `one_way`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ramp {
    /// When the program starts (τ).
    pub start_time: f64,
    /// The speed ratio at the start.
    pub from: f64,
    /// The turning speed ratio.
    pub to: f64,
    /// How fast the speed changes.
    pub pace: RampPace,
    /// Forcing periods held at `from` before the ramp starts (≥ 0).
    pub settle_periods: f64,
    /// Forcing periods held at `to` before running back (≥ 0; not used when `one_way`).
    pub dwell_periods: f64,
    /// Stop at `to` instead of running back to `from`.
    pub one_way: bool,
}

/// Why a ramp was refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RampError {
    /// A speed ratio outside the parameter table's range (or not finite).
    Speed {
        /// `from` or `to`.
        which: &'static str,
        /// The value.
        value: f64,
        /// The valid range.
        range: Range,
    },
    /// `from` and `to` are the same speed: nothing to ramp.
    SameSpeeds {
        /// The speed.
        speed: f64,
    },
    /// A rate outside [`RAMP_RATE_RANGE`] (given, or implied by a number of periods).
    Rate {
        /// The rate.
        value: f64,
        /// The number of periods it comes from, if it was given as periods.
        periods: Option<f64>,
        /// The valid range.
        range: Range,
    },
    /// A number of periods that is not a finite number > 0 (ramp) or ≥ 0 (settle, dwell).
    Periods {
        /// `periods`, `settle` or `dwell`.
        which: &'static str,
        /// The value.
        value: f64,
        /// The valid range.
        range: Range,
    },
    /// The program ends after the latest valid time.
    TooLong {
        /// When it would end.
        end: f64,
        /// The valid times.
        range: Range,
    },
    /// The start time is outside the valid times.
    StartTime {
        /// The value.
        value: f64,
        /// The valid times.
        range: Range,
    },
}

impl fmt::Display for RampError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            RampError::Speed {
                which,
                value,
                range,
            } => write!(
                f,
                "ramp speed ratio {which} = {} is out of range: it must be in {range}",
                Number(value)
            ),
            RampError::SameSpeeds { speed } => write!(
                f,
                "the ramp starts and turns at the same speed ratio {}: nothing to ramp",
                Number(speed)
            ),
            RampError::Rate {
                value,
                periods: None,
                range,
            } => write!(
                f,
                "ramp rate dη/dτ = {} is out of range: it must be in {range}",
                Number(value)
            ),
            RampError::Rate {
                value,
                periods: Some(n),
                range,
            } => write!(
                f,
                "a ramp over {} periods changes the speed at dη/dτ = {}, out of range: it must be in {range} (use more periods)",
                Number(n),
                Number(value)
            ),
            RampError::Periods {
                which,
                value,
                range,
            } => write!(
                f,
                "ramp {which} = {} forcing periods is out of range: it must be in {range}",
                Number(value)
            ),
            RampError::TooLong { end, range } => write!(
                f,
                "the speed program would end at τ = {}, past the valid times {range}: use a faster rate or fewer periods",
                Number(end)
            ),
            RampError::StartTime { value, range } => write!(
                f,
                "the speed program's start time {} is out of range: it must be in {range}",
                Number(value)
            ),
        }
    }
}

impl core::error::Error for RampError {}

/// The valid numbers of periods of a ramp, (0, 1e7].
pub const PERIODS_RANGE: Range = Range::above(0.0, 1e7);
/// The valid numbers of periods held at the start or the turning speed, [0, 1e7].
pub const HOLD_RANGE: Range = Range::closed(0.0, 1e7);

/// A ramp's points, held inline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RampPoints {
    points: [SpeedPoint; MAX_RAMP_POINTS],
    len: usize,
}

impl RampPoints {
    /// The points in use.
    pub fn as_slice(&self) -> &[SpeedPoint] {
        self.points.get(..self.len).unwrap_or(&[])
    }

    /// The points as a validated profile.
    pub fn profile(&self) -> Result<SpeedProfile<'_>, SpeedProfileError> {
        SpeedProfile::new(self.as_slice())
    }

    fn push(&mut self, time: f64, speed_ratio: f64) {
        if let Some(slot) = self.points.get_mut(self.len) {
            *slot = SpeedPoint::new(time, speed_ratio);
            self.len += 1;
        }
    }
}

impl Ramp {
    /// |dη/dτ| of the ramp.
    pub fn rate(&self) -> f64 {
        match self.pace {
            RampPace::Rate(r) => r,
            RampPace::Periods(n) => {
                let mean = 0.5 * (self.from + self.to);
                crate::math::abs(self.to - self.from) * mean / (n * TAU)
            }
        }
    }

    /// Validate the ramp and write its points: settle at `from`, ramp to `to`, then (unless
    /// `one_way`) dwell at `to` and ramp back to `from`. Holds of zero length add no point.
    pub fn points(&self) -> Result<RampPoints, RampError> {
        let speeds = speed_range();
        for (which, value) in [("from", self.from), ("to", self.to)] {
            if !(value.is_finite() && speeds.contains(value)) {
                return Err(RampError::Speed {
                    which,
                    value,
                    range: speeds,
                });
            }
        }
        if self.from == self.to {
            return Err(RampError::SameSpeeds { speed: self.from });
        }
        let times = time_range();
        if !(self.start_time.is_finite() && times.contains(self.start_time)) {
            return Err(RampError::StartTime {
                value: self.start_time,
                range: times,
            });
        }
        if let RampPace::Periods(n) = self.pace
            && !(n.is_finite() && PERIODS_RANGE.contains(n))
        {
            return Err(RampError::Periods {
                which: "periods",
                value: n,
                range: PERIODS_RANGE,
            });
        }
        for (which, value) in [
            ("settle", self.settle_periods),
            ("dwell", self.dwell_periods),
        ] {
            if !(value.is_finite() && HOLD_RANGE.contains(value)) {
                return Err(RampError::Periods {
                    which,
                    value,
                    range: HOLD_RANGE,
                });
            }
        }
        let rate = self.rate();
        if !(rate.is_finite() && RAMP_RATE_RANGE.contains(rate)) {
            return Err(RampError::Rate {
                value: rate,
                periods: match self.pace {
                    RampPace::Periods(n) => Some(n),
                    RampPace::Rate(_) => None,
                },
                range: RAMP_RATE_RANGE,
            });
        }
        let ramp = crate::math::abs(self.to - self.from) / rate;
        let settle = self.settle_periods * TAU / self.from;
        let dwell = self.dwell_periods * TAU / self.to;
        let end = if self.one_way {
            self.start_time + settle + ramp
        } else {
            self.start_time + settle + ramp + dwell + ramp
        };
        if !(end.is_finite() && times.contains(end)) {
            return Err(RampError::TooLong { end, range: times });
        }
        let mut out = RampPoints {
            points: [SpeedPoint::default(); MAX_RAMP_POINTS],
            len: 0,
        };
        let mut t = self.start_time;
        out.push(t, self.from);
        if settle > 0.0 {
            t += settle;
            out.push(t, self.from);
        }
        t += ramp;
        out.push(t, self.to);
        if !self.one_way {
            if dwell > 0.0 {
                t += dwell;
                out.push(t, self.to);
            }
            out.push(t + ramp, self.from);
        }
        Ok(out)
    }
}
