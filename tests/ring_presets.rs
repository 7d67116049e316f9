//! The ring presets (issue 28 item 1) do what their documentation says, through the matrix
//! model that runs them (`rotor_rub::matrix::ring_model`), and the planar entry points refuse
//! them with the typed error that names `stator_mass_ratio`.
//!
//! The numbers checked are those quoted in `runtime/params/presets.rs` (hybrid at its default
//! tolerance, states sampled 200 times per forcing period); the bounds leave room for a change of
//! method or tolerance but not for a different response (no rub, a ring at rest, a forward whirl).

use std::f64::consts::{PI, TAU};

use rotor_rub::matrix::{MatrixPropagator, ring_model, ring_start};
use rotor_rub::method::{Method, Options};
use rotor_rub::{EventKind, ParamError, Preset, PropagationError, Propagator, Regime, advance_to};

/// What a stretch of a ring preset's run shows.
#[derive(Debug)]
struct Stretch {
    /// Contact starts in the stretch.
    enters: usize,
    /// Events other than enter and exit (reversals, rolling) in the stretch.
    other_events: usize,
    /// Fraction of the samples rolling without slip.
    rolling: f64,
    /// Fraction of the samples in contact (|relative offset| > 1).
    contact: f64,
    /// Largest |(x, y)| of the rotor.
    rotor: f64,
    /// Largest |(xs, ys)| of the ring's centre.
    ring: f64,
    /// Mean rate of the angle of the rotor's offset from the ring's centre and the stator
    /// offset (d = q − q_s − ε̂), per unit τ: negative is backward whirl.
    whirl: f64,
    /// Mean |d|.
    mean_offset: f64,
}

/// Run `preset` with `method` over forcing periods [from, to] (after a transient from its start)
/// and measure the stretch.
fn stretch(preset: Preset, method: Method, from: f64, to: f64) -> Stretch {
    let problem = preset.problem();
    let p = problem.params;
    let model = ring_model(&p).expect("a ring preset states the ring model");
    let options = Options::with_method(method);
    let mut run = MatrixPropagator::new(&model, problem.start_time, ring_start(&problem), &options)
        .expect("the method starts");
    let period = p.forcing_period();
    let per_period = 200;
    let (mut enters, mut other_events, mut in_contact, mut samples) = (0, 0, 0, 0);
    let mut rolling = 0;
    let (mut rotor, mut ring, mut offset_sum) = (0.0f64, 0.0f64, 0.0);
    let (mut turned, mut previous, mut first_time, mut last_time) = (0.0f64, 0.0f64, 0.0, 0.0);
    let total = (to * f64::from(per_period)) as u32;
    for k in 1..=total {
        let t = problem.start_time + f64::from(k) * period / f64::from(per_period);
        let counting = t > from * period;
        let sample = advance_to(&mut run, t, |event| {
            if counting {
                match event.kind {
                    EventKind::Enter => enters += 1,
                    EventKind::Exit => {}
                    _ => other_events += 1,
                }
            }
        })
        .expect("the run goes on");
        if !counting {
            continue;
        }
        // The ring model's state: x, y, xs, ys, then the velocities.
        let s = sample.state.as_slice();
        let (x, y, xs, ys) = (s[0], s[1], s[2], s[3]);
        let (dx, dy) = (x - xs - p.offset_x, y - ys - p.offset_y);
        let z = dx.hypot(dy);
        samples += 1;
        in_contact += usize::from(z > 1.0);
        rolling += usize::from(sample.regime == Regime::Rolling);
        rotor = rotor.max(x.hypot(y));
        ring = ring.max(xs.hypot(ys));
        offset_sum += z;
        // Unwrap the angle of d from sample to sample (200 samples a period: |Δ| < π).
        let a = dy.atan2(dx);
        if samples == 1 {
            (first_time, previous) = (t, a);
        } else {
            let step = (a - previous + PI).rem_euclid(TAU) - PI;
            (turned, previous) = (turned + step, a);
        }
        last_time = t;
    }
    let whirl = turned / (last_time - first_time);
    Stretch {
        enters,
        other_events,
        rolling: rolling as f64 / samples as f64,
        contact: in_contact as f64 / samples as f64,
        rotor,
        ring,
        whirl,
        mean_offset: offset_sum / samples as f64,
    }
}

/// The rotor–ring system's natural frequencies (per unit τ) with the two bodies joined by a
/// spring `k` (isotropic support `k_s`, ring mass ratio `m`): the roots of
/// det(K − ω² M) = 0 for M = diag(1, m), K = [[1 + k, −k], [−k, k_s + k]].
fn coupled_modes(m: f64, k_s: f64, k: f64) -> (f64, f64) {
    let (a, b, c) = (
        m,
        -((1.0 + k) * m + (k_s + k)),
        (1.0 + k) * (k_s + k) - k * k,
    );
    let root = (b * b - 4.0 * a * c).sqrt();
    (
        ((-b - root) / (2.0 * a)).sqrt(),
        ((-b + root) / (2.0 * a)).sqrt(),
    )
}

#[test]
fn the_presets_split_into_planar_and_ring() {
    for preset in Preset::ALL {
        let ring = preset.problem().params.stator_mass_ratio > 0.0;
        assert_eq!(preset.has_ring_mass(), ring, "{}", preset.name());
        assert_eq!(Preset::RING.contains(&preset), ring, "{}", preset.name());
        assert_eq!(Preset::PLANAR.contains(&preset), !ring, "{}", preset.name());
        assert_eq!(Preset::from_name(preset.name()), Some(preset));
        assert_eq!(preset.problem().validate(), Ok(()), "{}", preset.name());
    }
    assert_eq!(Preset::PLANAR.len() + Preset::RING.len(), Preset::ALL.len());
}

#[test]
fn the_planar_driver_refuses_a_ring_preset_by_name() {
    for preset in Preset::RING {
        let problem = preset.problem();
        let err = Propagator::new(&problem, &Options::default())
            .err()
            .expect("the planar driver refuses a ring with mass");
        assert_eq!(
            err,
            PropagationError::InvalidProblem(ParamError::RingNeedsMatrixModel {
                stator_mass_ratio: problem.params.stator_mass_ratio,
            }),
            "{}",
            preset.name()
        );
        assert!(err.to_string().contains("stator_mass_ratio"), "{err}");
    }
}

/// `stator-mass`: a sustained rub with the ring moving.
#[test]
fn stator_mass_rubs_with_the_ring_moving() {
    let s = stretch(Preset::StatorMass, Method::Hybrid, 50.0, 100.0);
    println!("stator-mass, periods 50–100: {s:?}");
    assert!((250..=400).contains(&s.enters), "{s:?}");
    assert!((0.35..=0.6).contains(&s.contact), "{s:?}");
    assert!((0.45..=0.75).contains(&s.ring), "{s:?}");
    assert!((1.5..=2.0).contains(&s.rotor), "{s:?}");
}

/// `ring-whirl`: the rotor rolls on the ring in full annular backward whirl, the ring whirling
/// with it, at the coupled mode's frequency and the radius where rolling needs no slip; the same
/// with taylor (another contact solver).
#[test]
fn ring_whirl_whips_backward_at_the_coupled_mode() {
    let p = Preset::RingWhirl.problem().params;
    for method in [Method::Hybrid, Method::Taylor] {
        let s = stretch(Preset::RingWhirl, method, 90.0, 100.0);
        println!("ring-whirl {method:?}, periods 90–100: {s:?}");
        assert_eq!((s.enters, s.other_events), (0, 0), "{s:?}");
        assert_eq!((s.contact, s.rolling), (1.0, 1.0), "{s:?}");
        // Rolling: the relative position's surface speed is the rotor's, z̄ |ω| = ρ_R η.
        let surface = p.radius_ratio * p.speed_ratio;
        assert!(
            (s.mean_offset * -s.whirl - surface).abs() < 1e-3 * surface,
            "{s:?}"
        );
        assert!(s.ring > 3.0 && s.rotor > 3.0, "{s:?}");
        // The out-of-phase mode with the contact's secant stiffness at the mean offset.
        let secant = p.contact_stiffness * (1.0 - 1.0 / s.mean_offset);
        let (_, out_of_phase) = coupled_modes(p.stator_mass_ratio, p.k_xx, secant);
        assert!(
            (s.whirl + out_of_phase).abs() < 0.02 * out_of_phase,
            "whirl {} against the coupled mode's {out_of_phase}",
            s.whirl
        );
        // A massless ring on the same springs would whip near its series stiffness' frequency.
        let series = (1.0 + p.k_xx * secant / (p.k_xx + secant)).sqrt();
        assert!(-s.whirl > 2.0 * series, "{} against {series}", s.whirl);
        assert!(-s.whirl > 10.0 * p.speed_ratio, "{s:?}");
    }
}
