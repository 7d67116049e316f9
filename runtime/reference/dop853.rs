//! Dormand–Prince 8(5,3) as in Hairer's `DOP853`: 12 stages for the 8th-order solution, the
//! combined 5th/3rd-order error estimator `err = |h|·E5² / √(N·(E5² + 0.01·E3²))` (E5, E3 the
//! scaled sums of squares), and the 7th-order dense output from 3 extra stages (Hairer's
//! `CONTD8`). The stage f(t + h, y1) computed at acceptance is the next step's first stage.

use super::ode::{OdeSystem, lin};
use super::scheme::{Attempt, Controller, Interpolant, Scheme, Tolerance, stage_input, weighted};
use super::tableau_dop853 as tab;

/// The Dormand–Prince 8(5,3) method (marker type; see [`Scheme`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dop853;

/// Dense output of one DOP853 step: a degree-7 polynomial in s = (t − t0)/h,
/// `r0 + s(r1 + s'(r2 + s(r3 + s'(r4 + s(r5 + s'(r6 + s r7))))))` with s' = 1 − s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dop853Dense<const N: usize> {
    t0: f64,
    h: f64,
    r: [[f64; N]; 8],
}

impl<const N: usize> Interpolant<N> for Dop853Dense<N> {
    fn start(&self) -> f64 {
        self.t0
    }

    fn end(&self) -> f64 {
        self.t0 + self.h
    }

    fn eval(&self, t: f64) -> [f64; N] {
        let [r0, r1, r2, r3, r4, r5, r6, r7] = &self.r;
        if self.h == 0.0 {
            return *r0;
        }
        let s = (t - self.t0) / self.h;
        let s1 = 1.0 - s;
        let mut out = [0.0; N];
        let low = out.iter_mut().zip(r0).zip(r1).zip(r2).zip(r3);
        let high = r4.iter().zip(r5).zip(r6).zip(r7);
        for (((((o, a0), a1), a2), a3), (((a4, a5), a6), a7)) in low.zip(high) {
            let par = a4 + s * (a5 + s1 * (a6 + s * a7));
            *o = a0 + s * (a1 + s1 * (a2 + s * (a3 + s1 * par)));
        }
        out
    }
}

impl<const N: usize> Scheme<N> for Dop853 {
    /// k1..k12.
    type Stages = [[f64; N]; 12];
    type Dense = Dop853Dense<N>;
    const ORDER: i32 = 8;
    const STAGE_EVALUATIONS: u64 = 11;
    const ACCEPT_EVALUATIONS: u64 = 4;
    const CONTROLLER: Controller = Controller {
        safety: 0.9,
        fac_min: 0.333,
        fac_max: 6.0,
        alpha: 1.0 / 8.0,
        beta: 0.0,
    };

    fn attempt<S: OdeSystem<N> + ?Sized>(
        sys: &S,
        t: f64,
        y: &[f64; N],
        f0: &[f64; N],
        h: f64,
        tol: &Tolerance,
    ) -> Attempt<N, Self::Stages> {
        let mut k = [[0.0; N]; 12];
        k[0] = *f0;
        let rows: [&[f64]; 11] = [
            &tab::A2,
            &tab::A3,
            &tab::A4,
            &tab::A5,
            &tab::A6,
            &tab::A7,
            &tab::A8,
            &tab::A9,
            &tab::A10,
            &tab::A11,
            &tab::A12,
        ];
        for (i, (row, c)) in rows.iter().zip(tab::C.iter().skip(1)).enumerate() {
            let yi = stage_input(y, h, row, &k);
            // c12 = 1: evaluate at exactly t + h, as DOP853 does.
            let ti = if i == 10 { t + h } else { t + c * h };
            if let Some(slot) = k.get_mut(i + 1) {
                *slot = sys.rhs(ti, &yi);
            }
        }
        let incr = weighted(&tab::B, &k);
        let y1 = lin(&[(1.0, y), (h, &incr)]);
        let e5 = weighted(&tab::ER, &k);
        let e3 = lin(&[(1.0, &incr), (-1.0, &weighted(&tab::BHH, &k))]);
        let (mut s5, mut s3) = (0.0, 0.0);
        for (((a, b), x5), x3) in y.iter().zip(y1.iter()).zip(e5.iter()).zip(e3.iter()) {
            let sk = tol.scale(*a, *b);
            s5 += (x5 / sk) * (x5 / sk);
            s3 += (x3 / sk) * (x3 / sk);
        }
        let deno = s5 + 0.01 * s3;
        let deno = if deno > 0.0 { deno } else { 1.0 };
        let err = crate::math::abs(h) * s5 * crate::math::sqrt(1.0 / (N.max(1) as f64 * deno));
        Attempt { y1, err, stages: k }
    }

    fn accept<S: OdeSystem<N> + ?Sized>(
        sys: &S,
        t: f64,
        y: &[f64; N],
        _f0: &[f64; N],
        h: f64,
        attempt: &Attempt<N, Self::Stages>,
    ) -> ([f64; N], Self::Dense) {
        let y1 = &attempt.y1;
        let mut k = [[0.0; N]; 16];
        for (slot, stage) in k.iter_mut().zip(attempt.stages.iter()) {
            *slot = *stage;
        }
        k[12] = sys.rhs(t + h, y1);
        let extra: [&[f64]; 3] = [&tab::A14, &tab::A15, &tab::A16];
        for (i, (row, c)) in extra.iter().zip(tab::C.iter().skip(13)).enumerate() {
            let yi = stage_input(y, h, row, &k);
            if let Some(slot) = k.get_mut(13 + i) {
                *slot = sys.rhs(t + c * h, &yi);
            }
        }
        let [k1, .., k13, _, _, _] = &k;
        let ydiff = lin(&[(1.0, y1), (-1.0, y)]);
        let bspl = lin(&[(h, k1), (-1.0, &ydiff)]);
        let r3 = lin(&[(1.0, &ydiff), (-h, k13), (-1.0, &bspl)]);
        let [d4, d5, d6, d7] = &tab::D;
        let r = [
            *y,
            ydiff,
            bspl,
            r3,
            lin(&[(h, &weighted(d4, &k))]),
            lin(&[(h, &weighted(d5, &k))]),
            lin(&[(h, &weighted(d6, &k))]),
            lin(&[(h, &weighted(d7, &k))]),
        ];
        (*k13, Dop853Dense { t0: t, h, r })
    }
}
