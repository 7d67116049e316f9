//! The building blocks, per call, on states taken from the contact-heavy case (`paper` preset,
//! η = 2.5):
//!
//! * `coefficients/*`: the generated coefficient sets — free flight (per parameter set and per
//!   segment) and contact (linearization, modes, particular constants, all of a
//!   [`Linearization`]);
//! * `evaluate/*`: a closed-form segment at one time (state and h = z² − 1 with h');
//! * `switch/*`: one switch located (bracket and refinement) — entry on a free segment, exit on
//!   an exprb43 sub-step, exit on a DOP853 step's dense output (and with the polish onto the step
//!   solution, as the reference propagator does).

mod common;

use std::hint::black_box;

use common::Case;
use rotor_rub::analytic::free::{FreeConstants, FreeSegment};
use rotor_rub::analytic::linear::Linearization;
use rotor_rub::analytic::schemes::exprb43;
use rotor_rub::analytic::segment::Segment;
use rotor_rub::analytic::switch::{Direction, first_crossing};
use rotor_rub::coefficients as coef;
use rotor_rub::coefficients::ModelParams;
use rotor_rub::geometry;
use rotor_rub::reference::{
    Dop853, Integrator, RotorSystem, SUBDIVISIONS, Switches, Tolerance, first_crossing_subdivided,
    inside_measure, switch_in_step,
};
use rotor_rub::{Event, EventKind, Regime, State, events};

fn switches(case: Case) -> Vec<Event> {
    let problem = case.problem();
    let mut p = rotor_rub::Propagator::new(
        &problem,
        &common::Setting::tol(rotor_rub::Method::Hybrid, 1e-12).options(),
    )
    .expect("valid");
    let end = 10.0 * problem.params.forcing_period();
    events(&mut p, end)
        .collect::<Result<_, _>>()
        .expect("propagates")
}

fn main() {
    let mut c = common::criterion();
    let case = Case::Heavy;
    let problem = case.problem();
    let params = problem.params;
    let evs = switches(case);
    let exit = *evs
        .iter()
        .find(|e| e.kind == EventKind::Exit)
        .expect("an exit");
    let next_entry = *evs
        .iter()
        .find(|e| e.kind == EventKind::Enter && e.time > exit.time)
        .expect("an entry after the exit");
    let entry = next_entry;
    let constants = FreeConstants::new(&params);

    {
        // Every input passes through `black_box` each iteration, so nothing is hoisted.
        let mut g = c.benchmark_group("coefficients");
        g.bench_function("free: per parameter set (FreeConstants::new)", |b| {
            b.iter(|| FreeConstants::new(&black_box(params)))
        });
        let s = exit.state;
        let p = constants.particular;
        g.bench_function("free: per segment (free_homogeneous)", |b| {
            b.iter(|| {
                let (s, p, model) = black_box((s, p, coef::ModelParams::of(&params)));
                let phasor = coef::Phasor { ct: 0.6, st: 0.8 };
                coef::free_homogeneous(&model, &s.into(), &phasor, &p)
            })
        });
        g.bench_function(
            "free: FreeSegment::new (phase, constants, bounds data)",
            |b| {
                b.iter(|| {
                    let (p, c, t, s) = black_box((params, constants, exit.time, s));
                    FreeSegment::new(&p, &c, t, s)
                })
            },
        );
        let q = entry.state;
        g.bench_function(
            "contact: linearization (taylor_terms + linearized_stiffness)",
            |b| {
                b.iter(|| {
                    let (q, p) = black_box((q, params));
                    let model = coef::ModelParams::of(&p);
                    let t = coef::taylor_terms(&model, &coef::Position { x: q.x, y: q.y });
                    coef::linearized_stiffness(&model, &t)
                })
            },
        );
        let model = coef::ModelParams::of(&params);
        let t = coef::taylor_terms(&model, &coef::Position { x: q.x, y: q.y });
        let kl = coef::linearized_stiffness(&model, &t);
        g.bench_function("contact: modes (contact_modes)", |b| {
            b.iter(|| {
                let (kl, model) = black_box((kl, model));
                coef::contact_modes(&model, &kl)
            })
        });
        g.bench_function("contact: particular constants (contact_particular)", |b| {
            b.iter(|| {
                let (kl, model) = black_box((kl, model));
                coef::contact_particular(&model, &kl)
            })
        });
        g.bench_function("contact: all (Linearization::new)", |b| {
            b.iter(|| {
                let (p, t, q) = black_box((params, entry.time, q));
                Linearization::new(&p, t, q.x, q.y)
            })
        });
        g.finish();
    }

    // One exprb43 sub-step from the contact entry: its linearization and continuous extension.
    let h = 0.02;
    let lin = Linearization::new(&params, entry.time, entry.state.x, entry.state.y)
        .expect("regular contact");
    let sub = exprb43(&params, entry.time, entry.state, h, 1e-10).expect("regular contact");
    let free_seg = FreeSegment::new(&params, &constants, exit.time, exit.state);
    {
        let mut g = c.benchmark_group("evaluate");
        g.bench_function("free segment: state, h, h' at one time", |b| {
            b.iter(|| free_seg.point(black_box(0.37)))
        });
        g.bench_function("free segment: bounds on an interval", |b| {
            b.iter(|| free_seg.bounds(black_box(0.3), 0.5))
        });
        let plain = lin.segment(entry.state, [0.0; 8], h);
        g.bench_function("contact segment (no extra forcing): state, h, h'", |b| {
            b.iter(|| plain.point(black_box(0.013)))
        });
        g.bench_function(
            "contact segment (exprb43 cubic forcing): state, h, h'",
            |b| b.iter(|| sub.segment.point(black_box(0.013))),
        );
        g.bench_function("exprb43 sub-step (linearize, 4 segments, error)", |b| {
            b.iter(|| exprb43(&params, black_box(entry.time), entry.state, h, 1e-10))
        });
        g.finish();
    }

    {
        let mut g = c.benchmark_group("switch");
        let start = geometry::point(&ModelParams::of(&params), exit.state);
        let horizon = 1.5 * (next_entry.time - exit.time);
        let chunk = 0.5 / params.speed_ratio.max(1.0 + params.damping_ratio);
        let found = first_crossing(&free_seg, 0.0, start, horizon, Direction::Up, chunk)
            .expect("the next entry");
        assert!((exit.time + found.0 - next_entry.time).abs() < 1e-8);
        g.bench_function("entry on a free segment (exit to next entry)", |b| {
            b.iter(|| {
                first_crossing(
                    &free_seg,
                    0.0,
                    start,
                    black_box(horizon),
                    Direction::Up,
                    chunk,
                )
            })
        });

        // exprb43 sub-steps from the entry until one holds the exit.
        let (mut t, mut s) = (entry.time, entry.state);
        let exit_step = loop {
            let step = exprb43(&params, t, s, h, 1e-10).expect("regular contact");
            let start = geometry::point(&ModelParams::of(&params), s);
            if first_crossing(
                &step.segment,
                0.0,
                start,
                step.length,
                Direction::Down,
                step.length,
            )
            .is_some()
            {
                break (s, step);
            }
            (t, s) = (t + h, step.end);
        };
        let (s0, step) = exit_step;
        let start = geometry::point(&ModelParams::of(&params), s0);
        g.bench_function("exit on an exprb43 sub-step", |b| {
            b.iter(|| {
                first_crossing(
                    &step.segment,
                    0.0,
                    start,
                    black_box(step.length),
                    Direction::Down,
                    step.length,
                )
            })
        });

        // DOP853 steps on the contact field from the entry until one holds the exit.
        let sys = RotorSystem {
            params,
            regime: Regime::Contact,
            slip: 0.0,
        };
        let mut integ = Integrator::<Dop853, 4>::new(
            &sys,
            entry.time,
            entry.state.to_array(),
            Tolerance::uniform(1e-10),
            0.25 * params.forcing_period(),
        );
        let g_in = |y: &[f64; 4]| inside_measure(&ModelParams::of(&params), Regime::Contact, y);
        let dstep = loop {
            let st = integ.step(&sys, f64::INFINITY).expect("steps");
            if first_crossing_subdivided(SUBDIVISIONS, &st.dense, &st.y0, &st.y1, |_, y| g_in(y))
                .is_some()
            {
                break st;
            }
        };
        g.bench_function(
            "exit on a DOP853 step (dense output, 8 sub-intervals)",
            |b| {
                b.iter(|| {
                    first_crossing_subdivided(
                        SUBDIVISIONS,
                        &dstep.dense,
                        &dstep.y0,
                        &dstep.y1,
                        |_, y| g_in(y),
                    )
                })
            },
        );
        let switches = Switches::new(
            &params,
            Regime::Contact,
            0.0,
            entry.time,
            &entry.state.to_array(),
        );
        g.bench_function(
            "exit on a DOP853 step, polished onto the step solution",
            |b| b.iter(|| switch_in_step(&mut integ, &sys, black_box(&dstep), &switches)),
        );
        g.finish();
        let _: State = exit.state;
    }
    c.final_summary();
}
