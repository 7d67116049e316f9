//! Matching the switches of two runs of the same problem (analytic vs numerical).

use rotor_rub::{Event, EventKind, Params, State};

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
    /// Switches of contacts only one run has that are shallower than both runs resolve
    /// ([`Matching::set_aside_shallow`]): not counted as unmatched.
    pub shallow: usize,
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
        Self { pairs, shallow: 0 }
    }

    /// Set aside the contacts only one run has (its `enter` and the `exit` right after it, both
    /// unmatched; or its last `enter`, unmatched, with the run ending inside that contact in
    /// `ends`' state for its run, a then b) that reach less than `resolution` past z = 1
    /// (depth estimated from the switches, `rotor_rub::compare::penetration`): below what the
    /// runs resolve, such a contact is no disagreement (`rotor_rub::compare::contact_resolution`,
    /// issue 32: dop853 reported thousands on an orbit that grazes z = 1 exactly, which the
    /// analytic method follows without contact).
    pub fn set_aside_shallow(
        mut self,
        params: &Params,
        resolution: f64,
        ends: [Option<(f64, State)>; 2],
    ) -> Self {
        use rotor_rub::compare::penetration;
        // The run a pair's switch belongs to when only one run has it.
        let one_run = |p: &Pair| match (p.a, p.b) {
            (Some(e), None) => Some((0, e)),
            (None, Some(e)) => Some((1, e)),
            _ => None,
        };
        let shallow = |from: &Event, to: (f64, &State)| {
            penetration(params, (from.time, &from.state), to) < resolution
        };
        let mut i = 0;
        while let Some(p) = self.pairs.get(i) {
            let set_aside = match (one_run(p), self.pairs.get(i + 1).map(one_run)) {
                (Some((r, e)), Some(Some((s, x)))) if r == s => {
                    e.kind == EventKind::Enter
                        && x.kind == EventKind::Exit
                        && shallow(&e, (x.time, &x.state))
                        && (x.time >= e.time)
                }
                (Some((r, e)), None) => {
                    e.kind == EventKind::Enter
                        && ends[r].is_some_and(|(t, s)| t >= e.time && shallow(&e, (t, &s)))
                }
                _ => false,
            };
            let taken = match (set_aside, self.pairs.get(i + 1)) {
                (false, _) => 0,
                (true, Some(_)) => 2,
                (true, None) => 1,
            };
            self.shallow += taken;
            i += taken.max(1);
        }
        self
    }

    /// Number of matched pairs.
    pub fn matched(&self) -> usize {
        self.pairs.iter().filter(|p| p.dt().is_some()).count()
    }

    /// Number of switches left unmatched (both runs together), the shallow contacts set aside
    /// not counted.
    pub fn unmatched(&self) -> usize {
        self.pairs.len() - self.matched() - self.shallow
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

    /// A contact only one run has is set aside when it is shallower than the resolution (the
    /// grazing orbit of issue 32), counted unmatched when it is deeper.
    #[test]
    fn shallow_one_run_contacts_are_set_aside() {
        let params = rotor_rub::Params {
            offset_x: 0.0,
            offset_y: 0.0,
            ..rotor_rub::Params::DEFAULT
        };
        // On the unit circle at angle φ moving with radial rate h′/2 and speed 1.
        let at = |time: f64, kind, phi: f64, dh: f64| Event {
            time,
            kind,
            state: State::new(
                phi.cos(),
                phi.sin(),
                -phi.sin() + 0.5 * dh * phi.cos(),
                phi.cos() + 0.5 * dh * phi.sin(),
            ),
        };
        let a = [
            at(1.0, EventKind::Enter, 0.0, 1.0),
            at(1.5, EventKind::Exit, 0.5, -1.0),
        ];
        // b: the same contact, one only b has of depth z − 1 = 2e-10 (h′ = ±4e-9 over 0.4:
        // h = 4e-10 at its top), and a deep one (h′ = ±0.4: z − 1 = 2e-2).
        let b = [
            at(1.0, EventKind::Enter, 0.0, 1.0),
            at(1.5, EventKind::Exit, 0.5, -1.0),
            at(2.0, EventKind::Enter, 1.0, 4e-9),
            at(2.4, EventKind::Exit, 1.4, -4e-9),
            at(3.0, EventKind::Enter, 2.0, 0.4),
            at(3.4, EventKind::Exit, 2.4, -0.4),
        ];
        let m = Matching::new(&a, &b, 4.0).set_aside_shallow(&params, 1e-9, [None, None]);
        assert_eq!((m.matched(), m.shallow, m.unmatched()), (2, 2, 2));
        // A run ending inside a shallow contact only it has: set aside with its last state.
        let c = &b[..3];
        let inside = at(2.2, EventKind::Exit, 1.2, 0.0).state;
        let m = Matching::new(&a, c, 4.0).set_aside_shallow(&params, 1e-9, [None, None]);
        assert_eq!(m.unmatched(), 1);
        let m =
            Matching::new(&a, c, 4.0).set_aside_shallow(&params, 1e-9, [None, Some((2.2, inside))]);
        assert_eq!((m.shallow, m.unmatched()), (1, 0));
        let depth = rotor_rub::compare::contact_depth(&params, &b[2], &b[3]);
        assert!((depth - 2e-10).abs() < 1e-12, "{depth:e}");
    }
}
