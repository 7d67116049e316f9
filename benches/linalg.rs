//! The linear algebra for matrix models (`rotor_rub::linalg`), per call:
//!
//! * `decompose/m`: the modal form of a rotor's first-order matrix (balancing, Hessenberg,
//!   complex Schur, clustering, decoupling) for m = 8, 40, 120 (n = 4, 20, 60 DOFs);
//! * `projected/m`: one evaluation of d, d', d'' of the rub station at one s (m = 8, 40);
//! * `bound/m`: one bound of |d|, |d'|, |d''| over an interval (m = 8, 40).
//!
//! The rotor: a chain of n/2 nodes (x, y each), shaft springs between neighbours, gyroscopic
//! disks, anisotropic cross-coupled bearings at both ends (non-symmetric K and C), η = 0.8; the
//! rub station at the middle node.

mod common;

use std::hint::black_box;

use rotor_rub::linalg::{ModalExponential, ProjectedMotion, RealMatrix, SecondOrder};

/// The chain rotor's first-order matrix (m = 2n) in capacity C.
fn chain<const C: usize>(n: usize) -> RealMatrix<C> {
    let mut m = RealMatrix::<C>::zeros(n, n).unwrap();
    let mut c = RealMatrix::<C>::zeros(n, n).unwrap();
    let mut g = RealMatrix::<C>::zeros(n, n).unwrap();
    let mut k = RealMatrix::<C>::zeros(n, n).unwrap();
    let nodes = n / 2;
    let add = |a: &mut RealMatrix<C>, i: usize, j: usize, v: f64| {
        let x = a.get(i, j) + v;
        a.set(i, j, x);
    };
    for node in 0..nodes {
        let (x, y) = (2 * node, 2 * node + 1);
        let mass = 1.0 + 0.3 * ((node * 7) % 5) as f64 / 5.0;
        add(&mut m, x, x, mass);
        add(&mut m, y, y, mass);
        let ip = 0.1 + 0.05 * (node % 3) as f64;
        add(&mut g, x, y, ip);
        add(&mut g, y, x, -ip);
        add(&mut c, x, x, 0.01);
        add(&mut c, y, y, 0.01);
        if node + 1 < nodes {
            let ks = 50.0 + 10.0 * (node % 4) as f64;
            for d in 0..2 {
                let (a, b) = (2 * node + d, 2 * (node + 1) + d);
                add(&mut k, a, a, ks);
                add(&mut k, b, b, ks);
                add(&mut k, a, b, -ks);
                add(&mut k, b, a, -ks);
            }
        }
    }
    for node in [0, nodes - 1] {
        let (x, y) = (2 * node, 2 * node + 1);
        add(&mut k, x, x, 20.0);
        add(&mut k, y, y, 14.0);
        add(&mut k, x, y, 3.0);
        add(&mut k, y, x, -2.0);
        add(&mut c, x, x, 0.5);
        add(&mut c, y, y, 0.7);
        add(&mut c, x, y, 0.1);
        add(&mut c, y, x, -0.15);
    }
    SecondOrder {
        mass: &m,
        damping: &c,
        gyroscopic: &g,
        stiffness: &k,
    }
    .first_order(0.8)
    .unwrap()
}

fn decompose<const C: usize>(c: &mut criterion::Criterion, m: usize) {
    let a = chain::<C>(m / 2);
    let mut modal = Box::new(ModalExponential::<C>::new(&a).unwrap());
    c.bench_function(&format!("linalg/decompose/{m}"), |b| {
        b.iter(|| modal.rebuild(black_box(&a)).unwrap())
    });
}

fn projected<const C: usize>(c: &mut criterion::Criterion, m: usize) {
    let a = chain::<C>(m / 2);
    let modal = Box::new(ModalExponential::<C>::new(&a).unwrap());
    let node = m / 8;
    let (mut bx, mut by) = (vec![0.0; m], vec![0.0; m]);
    bx[2 * node] = 1.0;
    by[2 * node + 1] = 1.0;
    let mut motion = ProjectedMotion::new(&modal, &bx, &by).unwrap();
    let y0: Vec<f64> = (0..m).map(|i| (0.3 * i as f64).sin()).collect();
    motion.set_state(&modal, &y0).unwrap();
    c.bench_function(&format!("linalg/projected/{m}"), |b| {
        b.iter(|| motion.at(&modal, black_box(3.7)))
    });
    c.bench_function(&format!("linalg/bound/{m}"), |b| {
        b.iter(|| motion.bound(&modal, black_box(3.7), black_box(3.9)))
    });
}

fn main() {
    let mut c = common::criterion();
    decompose::<8>(&mut c, 8);
    decompose::<40>(&mut c, 40);
    decompose::<128>(&mut c, 120);
    projected::<8>(&mut c, 8);
    projected::<40>(&mut c, 40);
    c.final_summary();
}
