//! What a run-up's rows say: the run-up and coast-down curves, their jumps, where they differ
//! (the hysteresis loop) and where the rotor rubs.

use rotor_rub::variable_speed::{Jump, JumpSearch, Revolution, SpeedDirection, find_jumps};

/// One direction of a run: its rows in run order and its jumps.
pub struct Branch {
    /// Run-up or coast-down.
    pub direction: SpeedDirection,
    /// Its revolutions, in run order.
    pub rows: Vec<Revolution>,
    /// Where its largest radius jumps.
    pub jumps: Vec<Jump>,
}

impl Branch {
    /// The rows of `rows` going `direction`, with their jumps.
    pub fn of(rows: &[Revolution], direction: SpeedDirection) -> Self {
        let rows: Vec<Revolution> = rows
            .iter()
            .copied()
            .filter(|r| r.direction() == direction)
            .collect();
        let jumps = find_jumps(&rows, &JumpSearch::default())
            .as_slice()
            .to_vec();
        Branch {
            direction,
            rows,
            jumps,
        }
    }

    /// `run-up` or `coast-down`.
    pub fn label(&self) -> &'static str {
        match self.direction {
            SpeedDirection::Up => "run-up",
            SpeedDirection::Down => "coast-down",
            SpeedDirection::Hold => "held speed",
        }
    }

    /// The speed intervals over which the rotor touched the stator: consecutive rubbing
    /// revolutions merged, each revolution covering the speeds it ran through.
    pub fn contact_intervals(&self) -> Vec<(f64, f64)> {
        let mut out: Vec<(f64, f64)> = Vec::new();
        let mut open = false;
        for r in &self.rows {
            let half = 0.5 * r.speed_change.abs();
            let (lo, hi) = (r.speed_ratio - half, r.speed_ratio + half);
            if r.contact_fraction > 0.0 {
                match out.last_mut() {
                    Some(last) if open => *last = (last.0.min(lo), last.1.max(hi)),
                    _ => out.push((lo, hi)),
                }
                open = true;
            } else {
                open = false;
            }
        }
        out
    }

    /// The fraction of the branch's revolutions that touch the stator.
    pub fn rubbing_fraction(&self) -> f64 {
        if self.rows.is_empty() {
            return 0.0;
        }
        let rubbing = self
            .rows
            .iter()
            .filter(|r| r.contact_fraction > 0.0)
            .count();
        rubbing as f64 / self.rows.len() as f64
    }
}

/// The largest difference between the two branches' largest radius at one speed: (speed,
/// run-up's radius, coast-down's radius), comparing each run-up revolution with the coast-down
/// revolution nearest in speed.
pub fn largest_difference(up: &Branch, down: &Branch) -> Option<(f64, f64, f64)> {
    let mut by_speed: Vec<&Revolution> = down.rows.iter().collect();
    by_speed.sort_by(|a, b| a.speed_ratio.total_cmp(&b.speed_ratio));
    let nearest = |speed: f64| -> Option<&Revolution> {
        let k = by_speed.partition_point(|r| r.speed_ratio < speed);
        [k.checked_sub(1), Some(k)]
            .into_iter()
            .flatten()
            .filter_map(|i| by_speed.get(i).copied())
            .min_by(|a, b| {
                (a.speed_ratio - speed)
                    .abs()
                    .total_cmp(&(b.speed_ratio - speed).abs())
            })
    };
    up.rows
        .iter()
        .filter_map(|u| {
            let d = nearest(u.speed_ratio)?;
            // Only where the two runs cover the same speed (a revolution's speed step apart).
            let reach = u.speed_change.abs().max(d.speed_change.abs());
            ((d.speed_ratio - u.speed_ratio).abs() <= reach).then_some((
                u.speed_ratio,
                u.max_radius,
                d.max_radius,
            ))
        })
        .max_by(|a, b| (a.1 - a.2).abs().total_cmp(&(b.1 - b.2).abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(speed: f64, change: f64, radius: f64, contact: f64) -> Revolution {
        Revolution {
            index: 0,
            start: 0.0,
            end: 1.0,
            speed_ratio: speed,
            speed_change: change,
            max_radius: radius,
            min_radius: radius,
            contact_fraction: contact,
            whirl: 1.0,
            enters: 0,
            exits: 0,
        }
    }

    #[test]
    fn contact_intervals_merge_consecutive_rubbing_revolutions() {
        let rows: Vec<Revolution> = (0..10)
            .map(|k| {
                let contact = if (2..5).contains(&k) || k == 8 {
                    0.5
                } else {
                    0.0
                };
                row(1.0 + 0.1 * f64::from(k), 0.1, 1.0, contact)
            })
            .collect();
        let b = Branch::of(&rows, SpeedDirection::Up);
        let iv = b.contact_intervals();
        assert_eq!(iv.len(), 2);
        assert!((iv[0].0 - 1.15).abs() < 1e-12 && (iv[0].1 - 1.45).abs() < 1e-12);
        assert!((iv[1].0 - 1.75).abs() < 1e-12 && (iv[1].1 - 1.85).abs() < 1e-12);
        assert!((b.rubbing_fraction() - 0.4).abs() < 1e-12);
    }

    #[test]
    fn the_largest_difference_compares_equal_speeds() {
        let up: Vec<Revolution> = (0..20)
            .map(|k| {
                row(
                    1.0 + 0.05 * f64::from(k),
                    0.05,
                    if k < 15 { 3.0 } else { 1.0 },
                    1.0,
                )
            })
            .collect();
        let down: Vec<Revolution> = (0..20)
            .map(|k| row(1.95 - 0.05 * f64::from(k), -0.05, 1.0, 1.0))
            .collect();
        let (up, down) = (
            Branch::of(&up, SpeedDirection::Up),
            Branch::of(&down, SpeedDirection::Down),
        );
        let (speed, a, b) = largest_difference(&up, &down).unwrap();
        assert!((a - 3.0).abs() < 1e-12 && (b - 1.0).abs() < 1e-12);
        assert!(speed < 1.75);
    }
}
