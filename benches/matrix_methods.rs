//! Every method on the stator ring with mass (`rotor_rub::matrix::MatrixPropagator`, n = 4)
//! against the same method on the planar (massless-stator) model, heavy rub: the paper's rotor
//! and offset, 10 forcing periods, each method at its default tolerance.
//!
//! * `matrix_methods/ring/<method>`: the ring, m̂ = 1, k̂_c = 100, ĉ = 0.5 (107 switches);
//! * `matrix_methods/planar/<method>`: the paper preset on the planar `Propagator` (the
//!   massless limit's cost; 47 switches).
//!
//! * `matrix_methods/sparse/<method>`: the ring's contact-sparse rub (ε̂ = 0, the same ring, 6
//!   switches in 10 periods) at tol 1e-13, where every method is within 1.5e-12 of the oracle's
//!   switch times (`tests/matrix_ring.rs`): exact free flight against DOP853 on the whole system;
//! * `matrix_methods/sparse100/<method>`: the same over 100 periods (as the planar model's
//!   contact-sparse target): the same 6 switches, all in the first 10 periods, then free flight
//!   that the exact methods prove contact-free for good (settled) and DOP853 integrates.
//!
//! The targets: hybrid and taylor on the ring within 2× their planar cost; exact free
//! flight ≥ 50× faster than dop853 on contact-sparse rub at equal switch accuracy.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rotor_rub::matrix::{MatrixPropagator, ring_model, ring_start};
use rotor_rub::method::{Method, Options};
use rotor_rub::{Parameter, Preset, Propagator, events};

const PERIODS: f64 = 10.0;

fn methods(c: &mut Criterion) {
    let planar = Preset::Paper.problem();
    let mut ring = Preset::Paper.problem();
    for (p, v) in [
        (Parameter::StatorMassRatio, 1.0),
        (Parameter::ContactStiffness, 100.0),
        (Parameter::StatorDamping, 0.5),
    ] {
        p.set(&mut ring, v);
    }
    let model = Box::new(ring_model(&ring.params).unwrap());
    let end = PERIODS * planar.params.forcing_period();
    for method in [
        Method::Hybrid,
        Method::Taylor,
        Method::Analytic,
        Method::Dop853,
        Method::Rk45,
    ] {
        let options = Options::with_method(method);
        let name = method.name();
        c.bench_function(&format!("matrix_methods/ring/{name}"), |b| {
            b.iter(|| {
                let mut p =
                    MatrixPropagator::new(&*model, 0.0, ring_start(&ring), &options).unwrap();
                black_box(events(&mut p, end).count())
            })
        });
        c.bench_function(&format!("matrix_methods/planar/{name}"), |b| {
            b.iter(|| {
                let mut p = Propagator::new(&planar, &options).unwrap();
                black_box(events(&mut p, end).count())
            })
        });
    }
}

fn sparse(c: &mut Criterion) {
    let mut ring = Preset::Paper.problem();
    for (p, v) in [
        (Parameter::OffsetX, 0.0),
        (Parameter::OffsetY, 0.0),
        (Parameter::StatorMassRatio, 1.0),
        (Parameter::ContactStiffness, 100.0),
        (Parameter::StatorDamping, 0.5),
    ] {
        p.set(&mut ring, v);
    }
    let model = Box::new(ring_model(&ring.params).unwrap());
    for (group, periods) in [("sparse", PERIODS), ("sparse100", 10.0 * PERIODS)] {
        let end = periods * ring.params.forcing_period();
        for method in [Method::Hybrid, Method::Taylor, Method::Dop853] {
            let options = Options {
                tol: Some(1e-13),
                ..Options::with_method(method)
            };
            c.bench_function(&format!("matrix_methods/{group}/{}", method.name()), |b| {
                b.iter(|| {
                    let mut p =
                        MatrixPropagator::new(&*model, 0.0, ring_start(&ring), &options).unwrap();
                    black_box(events(&mut p, end).count())
                })
            });
        }
    }
}

criterion_group!(benches, methods, sparse);
criterion_main!(benches);
