//! Jumps of the response during a run-up or coast-down: where the orbit's largest radius steps
//! from one level to another within a few revolutions (`docs/MODEL.md` §14). A rub makes the
//! response curve fold over, so the run-up leaves the upper branch at one speed and the
//! coast-down regains it at another: the two jump speeds bound the hysteresis loop.
//!
//! A jump is a discontinuity of the largest radius as a function of the revolution: at each
//! boundary between revolutions i − 1 and i, a straight line is fitted (least squares) to the
//! `window` revolutions before it and another to the `window` revolutions after it, and both
//! are extrapolated to the boundary. Where the response changes smoothly the two lines meet
//! there (to within its curvature over a window); at a jump they are apart by the jump's size.
//! The boundary where they are furthest apart, by at least `min_step` of the larger of the two
//! levels (and `min_absolute`), is a jump; its speed is the speed between revolutions i − 1 and
//! i, and it is reported from the extreme of the window before to the opposite extreme of the
//! window after (a jump down: from the highest radius before to the lowest after), the levels
//! a plot shows. Further jumps are searched for away from the windows of those already found. Fitting over
//! windows keeps the revolution-to-revolution variation of chaotic, quasi-periodic or
//! period-n rubbing from counting as jumps, and the lines follow the steep but continuous
//! flanks of the resonance curve.

use super::period::Revolution;

/// A jump of the largest radius.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jump {
    /// The speed ratio where it happens (mean of the speeds of the revolutions either side).
    pub speed_ratio: f64,
    /// The index, in the revolutions searched, of the first revolution after the step.
    pub position: usize,
    /// The level it jumps from: the largest radius over the window before (the smallest, for
    /// a jump up).
    pub before: f64,
    /// The level it jumps to: the smallest radius over the window after (the largest, for a
    /// jump up).
    pub after: f64,
}

/// How jumps are told from the response's smooth change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JumpSearch {
    /// Revolutions averaged either side of a step (≥ 1).
    pub window: usize,
    /// The smallest step, relative to the larger of the two levels.
    pub min_step: f64,
    /// The smallest step in clearances.
    pub min_absolute: f64,
}

impl Default for JumpSearch {
    /// 10 revolutions either side, a step of at least 30 % of the larger level and 0.05
    /// clearances.
    fn default() -> Self {
        JumpSearch {
            window: 10,
            min_step: 0.3,
            min_absolute: 0.05,
        }
    }
}

/// Most jumps reported from one search.
pub const MAX_JUMPS: usize = 8;

/// The jumps found, in the order of the revolutions.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jumps {
    list: [Jump; MAX_JUMPS],
    len: usize,
}

impl Jumps {
    /// The jumps, in revolution order.
    pub fn as_slice(&self) -> &[Jump] {
        self.list.get(..self.len).unwrap_or(&[])
    }

    /// The largest jump (by |after − before|), if any.
    pub fn largest(&self) -> Option<Jump> {
        self.as_slice().iter().copied().max_by(|a, b| {
            crate::math::abs(a.after - a.before).total_cmp(&crate::math::abs(b.after - b.before))
        })
    }
}

/// The least-squares line through `values` at abscissae 0, 1, …, evaluated at `x`.
fn line_at(values: &[Revolution], x: f64) -> f64 {
    let n = values.len() as f64;
    let mean_x = 0.5 * (n - 1.0);
    let mean_y = values.iter().map(|r| r.max_radius).sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (k, r) in values.iter().enumerate() {
        let dx = k as f64 - mean_x;
        sxy += dx * (r.max_radius - mean_y);
        sxx += dx * dx;
    }
    let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    mean_y + slope * (x - mean_x)
}

/// The two levels at the boundary before revolution `i`: the lines fitted to the `w`
/// revolutions either side, extrapolated to it.
fn levels(radii: &[Revolution], i: usize, w: usize) -> Option<(f64, f64)> {
    let before = radii.get(i.checked_sub(w)?..i)?;
    let after = radii.get(i..i.checked_add(w)?)?;
    Some((line_at(before, w as f64 - 0.5), line_at(after, -0.5)))
}

/// The jumps of the largest radius in `revolutions` (one direction of a run, in order).
pub fn find_jumps(revolutions: &[Revolution], search: &JumpSearch) -> Jumps {
    let w = search.window.max(1);
    let mut found = Jumps::default();
    let qualifies = |(before, after): (f64, f64)| {
        let step = crate::math::abs(after - before);
        step >= search.min_absolute && step >= search.min_step * before.max(after)
    };
    while found.len < MAX_JUMPS {
        let taken = found.as_slice();
        let best = (w..=revolutions.len().saturating_sub(w))
            .filter(|&i| taken.iter().all(|j| i.abs_diff(j.position) > w))
            .filter_map(|i| levels(revolutions, i, w).map(|l| (i, l)))
            .filter(|&(_, l)| qualifies(l))
            .max_by(|(_, a), (_, b)| {
                crate::math::abs(a.1 - a.0).total_cmp(&crate::math::abs(b.1 - b.0))
            });
        let Some((position, (before, after))) = best else {
            break;
        };
        let speed = |k: usize| revolutions.get(k).map_or(f64::NAN, |r| r.speed_ratio);
        let window = |range: core::ops::Range<usize>| {
            revolutions
                .get(range)
                .unwrap_or(&[])
                .iter()
                .map(|r| r.max_radius)
        };
        let (from, to) = (
            window(position.saturating_sub(w)..position),
            window(position..position + w),
        );
        let (before, after) = if after < before {
            (from.fold(before, f64::max), to.fold(after, f64::min))
        } else {
            (from.fold(before, f64::min), to.fold(after, f64::max))
        };
        if let Some(slot) = found.list.get_mut(found.len) {
            *slot = Jump {
                speed_ratio: 0.5 * (speed(position.saturating_sub(1)) + speed(position)),
                position,
                before,
                after,
            };
            found.len += 1;
        }
    }
    let len = found.len;
    if let Some(list) = found.list.get_mut(..len) {
        list.sort_unstable_by_key(|j| j.position);
    }
    found
}
