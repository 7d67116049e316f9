//! Matching the switches of two runs of the same problem (analytic vs numerical).

use rotor_rub::Event;

/// Two switches further apart than this (in τ) are not taken as the same switch.
pub const MATCH_GAP: f64 = 0.1;

/// One row of the side-by-side table: a switch of either run, or of both when matched.
#[derive(Clone, Copy, Debug)]
pub struct Pair {
    /// The first run's switch.
    pub a: Option<Event>,
    /// The second run's switch.
    pub b: Option<Event>,
}

impl Pair {
    /// Switch-time difference b − a of a matched pair.
    pub fn dt(&self) -> Option<f64> {
        Some(self.b?.time - self.a?.time)
    }

    /// Largest state difference (max norm over x, y, vx, vy) of a matched pair.
    pub fn dstate(&self) -> Option<f64> {
        let (a, b) = (self.a?.state.to_array(), self.b?.state.to_array());
        Some((0..4).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max))
    }
}

/// The matching of two switch sequences over a window.
pub struct Matching {
    /// Every switch of both runs up to the window end, matched pairs on one row.
    pub pairs: Vec<Pair>,
}

impl Matching {
    /// Pair the switches of `a` and `b` up to time `window` in one merge pass: two switches
    /// match when they are of the same kind and less than [`MATCH_GAP`] apart; otherwise the
    /// earlier one stays unmatched.
    pub fn new(a: &[Event], b: &[Event], window: f64) -> Self {
        let a: Vec<Event> = a.iter().copied().filter(|e| e.time <= window).collect();
        let b: Vec<Event> = b.iter().copied().filter(|e| e.time <= window).collect();
        let (mut i, mut j) = (0, 0);
        let mut pairs = Vec::with_capacity(a.len().max(b.len()));
        while i < a.len() || j < b.len() {
            match (a.get(i), b.get(j)) {
                (Some(&x), Some(&y)) if x.kind == y.kind && (x.time - y.time).abs() < MATCH_GAP => {
                    pairs.push(Pair {
                        a: Some(x),
                        b: Some(y),
                    });
                    i += 1;
                    j += 1;
                }
                (Some(&x), Some(&y)) if x.time <= y.time => {
                    pairs.push(Pair {
                        a: Some(x),
                        b: None,
                    });
                    i += 1;
                }
                (_, Some(&y)) => {
                    pairs.push(Pair {
                        a: None,
                        b: Some(y),
                    });
                    j += 1;
                }
                (Some(&x), None) => {
                    pairs.push(Pair {
                        a: Some(x),
                        b: None,
                    });
                    i += 1;
                }
                (None, None) => unreachable!("loop condition"),
            }
        }
        Self { pairs }
    }

    /// Number of matched pairs.
    pub fn matched(&self) -> usize {
        self.pairs.iter().filter(|p| p.dt().is_some()).count()
    }

    /// Number of switches left unmatched (both runs together).
    pub fn unmatched(&self) -> usize {
        self.pairs.len() - self.matched()
    }

    /// Largest |Δτ| over matched pairs.
    pub fn max_dt(&self) -> Option<f64> {
        self.pairs
            .iter()
            .filter_map(Pair::dt)
            .map(f64::abs)
            .reduce(f64::max)
    }

    /// Largest state difference at matched switches.
    pub fn max_dstate(&self) -> Option<f64> {
        self.pairs.iter().filter_map(Pair::dstate).reduce(f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rotor_rub::{EventKind, State};

    fn ev(time: f64, kind: EventKind) -> Event {
        Event {
            time,
            kind,
            state: State::default(),
        }
    }

    #[test]
    fn matches_close_switches_and_keeps_extra_ones() {
        let a = [
            ev(1.0, EventKind::Enter),
            ev(2.0, EventKind::Exit),
            ev(5.0, EventKind::Enter),
        ];
        let b = [
            ev(1.001, EventKind::Enter),
            ev(1.5, EventKind::Exit),
            ev(1.6, EventKind::Enter),
            ev(2.002, EventKind::Exit),
        ];
        let m = Matching::new(&a, &b, 4.0);
        assert_eq!(m.matched(), 2);
        assert_eq!(m.unmatched(), 2);
        assert!((m.max_dt().unwrap() - 0.002).abs() < 1e-12);
    }
}
