//! The event comparison utilities.

use rotor_rub::compare::{Disagreement, FirstDisagreement, compare_events, state_difference};
use rotor_rub::{Event, EventKind, State};

fn ev(time: f64, kind: EventKind, x: f64) -> Event {
    Event {
        time,
        kind,
        state: State::new(x, 0.5, -1.0, 2.0),
    }
}

fn run() -> Vec<Event> {
    vec![
        ev(1.0, EventKind::Enter, 1.0),
        ev(1.5, EventKind::Exit, 0.9),
        ev(3.0, EventKind::Enter, 0.8),
        ev(3.2, EventKind::Exit, 0.7),
    ]
}

#[test]
fn identical_runs_agree() {
    let a = run();
    let c = compare_events(&a, &a, 0.0);
    assert!(c.agrees());
    assert_eq!((c.compared, c.matched, c.unmatched), (4, 4, 0));
    assert_eq!((c.max_time_difference, c.max_state_difference), (0.0, 0.0));
    assert_eq!(c.max_time_index, Some(0));
    let empty = compare_events(&[], &[], 1.0);
    assert!(empty.agrees());
    assert_eq!((empty.compared, empty.max_time_index), (0, None));
}

#[test]
fn matched_runs_report_largest_differences() {
    let a = run();
    let mut b = run();
    b[1].time += 2e-9;
    b[2].time -= 5e-9;
    b[3].state.vy += 3e-9;
    let c = compare_events(&a, &b, 1e-8);
    assert!(c.agrees());
    assert_eq!(c.unmatched, 0);
    assert!((c.max_time_difference - 5e-9).abs() < 1e-15);
    assert_eq!(c.max_time_index, Some(2));
    assert!((c.max_state_difference - 3e-9).abs() < 1e-15);
    assert_eq!(c.max_state_index, Some(3));
    // Beyond a tighter tolerance the first disagreement is the first pair over it.
    let c = compare_events(&a, &b, 3e-9);
    assert_eq!(
        c.first_disagreement,
        Some(FirstDisagreement {
            index: 2,
            time: 3.0,
            reason: Disagreement::Time
        })
    );
    let c = compare_events(&a, &b, 2.5e-9);
    assert_eq!(c.first_disagreement.map(|d| d.index), Some(2));
    let mut d = run();
    d[0].state.x += 1.0;
    let c = compare_events(&a, &d, 1e-3);
    assert_eq!(
        c.first_disagreement,
        Some(FirstDisagreement {
            index: 0,
            time: 1.0,
            reason: Disagreement::State
        })
    );
}

#[test]
fn unmatched_switches_are_counted() {
    let a = run();
    // One run misses the last contact (two switches).
    let c = compare_events(&a, &a[..2], 1e-12);
    assert_eq!((c.compared, c.length_difference, c.unmatched), (2, 2, 2));
    assert_eq!(
        c.first_disagreement,
        Some(FirstDisagreement {
            index: 2,
            time: 3.0,
            reason: Disagreement::Missing
        })
    );
    let c = compare_events(&a[..1], &a, 1e-12);
    assert_eq!(
        c.first_disagreement.map(|d| (d.index, d.reason)),
        Some((1, Disagreement::Missing))
    );
    // Kind mismatches: one run misses the first contact, so every pair is out of step.
    let c = compare_events(&a[2..], &a[..2], 10.0);
    assert_eq!((c.kind_mismatches, c.matched, c.unmatched), (0, 2, 0));
    let shifted = [a[1], a[2], a[3]];
    let c = compare_events(&a, &shifted, 10.0);
    assert_eq!(
        (c.kind_mismatches, c.length_difference, c.unmatched),
        (3, 1, 4)
    );
    assert_eq!(c.matched, 0);
    assert_eq!(c.max_time_index, None);
    assert_eq!(
        c.first_disagreement,
        Some(FirstDisagreement {
            index: 0,
            time: 1.0,
            reason: Disagreement::Kind
        })
    );
}

#[test]
fn nan_is_a_disagreement() {
    let a = run();
    let mut b = run();
    b[1].time = f64::NAN;
    let c = compare_events(&a, &b, 1.0);
    assert_eq!(c.first_disagreement.map(|d| d.index), Some(1));
    assert_eq!(c.max_time_difference, f64::INFINITY);
    let s = State::new(f64::NAN, 0.0, 0.0, 0.0);
    assert_eq!(state_difference(&s, &State::default()), f64::INFINITY);
}
