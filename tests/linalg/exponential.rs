//! e^{As} y0 against nalgebra's `exp`: random matrices and every degenerate case.

use super::common::*;
use rotor_rub::linalg::{ModalExponential, RealMatrix};

const SPANS: [f64; 6] = [1e-3, 0.1, 1.0, 10.0, 100.0, 1e3];

fn worst(a: &RealMatrix<CAP>, spans: &[f64]) -> (f64, f64) {
    let e = ModalExponential::new(a).unwrap();
    let m = a.rows();
    let mut worst: f64 = 0.0;
    for k in 0..3 {
        let y0: Vec<f64> = (0..m).map(|i| ((i * 7 + k * 3) % 5) as f64 - 1.7).collect();
        for &s in spans {
            let r = reference(a, s, &y0);
            if !r.iter().all(|x| x.is_finite()) || norm(&r) < 1e-290 || norm(&r) > 1e290 {
                continue;
            }
            let err = relative_error(&ours(&e, s, &y0), &r);
            worst = worst.max(err);
        }
    }
    (worst, e.condition())
}

#[test]
fn measure() {
    let cases: Vec<(&str, RealMatrix<CAP>)> = vec![
        ("critical", RealMatrix::from_rows(&[&[0.0, 1.0], &[-1.0, -2.0]]).unwrap()),
        ("jeffcott nu=0.1", Rotor::jeffcott(0.1).first_order(0.0)),
        ("jeffcott nu=0", Rotor::jeffcott(0.0).first_order(0.0)),
        ("jeffcott nu=1", Rotor::jeffcott(1.0).first_order(0.0)),
        ("jeffcott nu=1-1e-8", Rotor::jeffcott(1.0 - 1e-8).first_order(0.0)),
        ("jeffcott nu=1-1e-4", Rotor::jeffcott(1.0 - 1e-4).first_order(0.0)),
        ("jeffcott nu=2", Rotor::jeffcott(2.0).first_order(0.0)),
        ("jeffcott nu=-0.05", Rotor::jeffcott(-0.05).first_order(0.0)),
        ("two-disk eta=0.7", two_disk_rotor().first_order(0.7)),
        ("free mass", RealMatrix::from_rows(&[&[0.0, 1.0], &[0.0, 0.0]]).unwrap()),
        ("free mass damped", RealMatrix::from_rows(&[&[0.0, 1.0], &[0.0, -0.1]]).unwrap()),
    ];
    for (name, a) in &cases {
        let (w, cond) = worst(a, &SPANS);
        let per: Vec<String> = SPANS.iter().map(|&s| format!("{:.1e}", worst(a, &[s]).0)).collect();
        eprintln!("{name:24} worst {w:.2e} cond {cond:.2e} per span {per:?}");
    }
}

#[test]
fn measure_exact() {
    let rot = RealMatrix::<CAP>::from_rows(&[&[0.0, 1.0], &[-1.0, 0.0]]).unwrap();
    let crit = RealMatrix::<CAP>::from_rows(&[&[0.0, 1.0], &[-1.0, -2.0]]).unwrap();
    let er = ModalExponential::new(&rot).unwrap();
    let ec = ModalExponential::new(&crit).unwrap();
    for s in SPANS {
        let y0 = [0.3, -1.1];
        let (sn, cs) = (s as f64).sin_cos();
        let exact = [cs * y0[0] + sn * y0[1], -sn * y0[0] + cs * y0[1]];
        let e1 = relative_error(&ours(&er, s, &y0), &exact);
        let n1 = relative_error(&reference(&rot, s, &y0), &exact);
        let x = (-s as f64).exp();
        let exact = [x * ((1.0 + s) * y0[0] + s * y0[1]), x * (-s * y0[0] + (1.0 - s) * y0[1])];
        let e2 = relative_error(&ours(&ec, s, &y0), &exact);
        let n2 = relative_error(&reference(&crit, s, &y0), &exact);
        eprintln!("s={s:e}: rotation ours {e1:.1e} nalgebra {n1:.1e}; critical ours {e2:.1e} nalgebra {n2:.1e}");
    }
}

#[test]
fn measure_near_critical() {
    for nu in [1.0 - 1e-4, 1.0 - 1e-8, 0.1] {
        let a1 = RealMatrix::<CAP>::from_rows(&[&[0.0, 1.0], &[-1.0, -2.0 * nu]]).unwrap();
        let e = ModalExponential::new(&a1).unwrap();
        for s in [1.0, 10.0, 100.0, 1e3] {
            let y0 = [0.3, -1.1];
            let beta = ((1.0 - nu) * (1.0 + nu)).sqrt();
            let (sn, cs) = (beta * s).sin_cos();
            let x = (-nu * s).exp();
            let es = x * sn / beta;
            let ec = x * cs;
            // x(s) = EC x0 + ES (v0 + ν x0); v(s) = EC v0 − ES (x0 + ν v0)
            let exact = [ec * y0[0] + es * (y0[1] + nu * y0[0]), ec * y0[1] - es * (y0[0] + nu * y0[1])];
            let e1 = relative_error(&ours(&e, s, &y0), &exact);
            let n1 = relative_error(&reference(&a1, s, &y0), &exact);
            eprintln!("nu={nu} s={s:e}: ours {e1:.1e} nalgebra {n1:.1e}");
        }
    }
}
