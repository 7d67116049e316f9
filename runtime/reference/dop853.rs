//! Dormand–Prince 8(5,3) as in Hairer's `DOP853`: 12 stages for the 8th-order solution, the
//! combined 5th/3rd-order error estimator `err = |h|·E5² / √(N·(E5² + 0.01·E3²))` (E5, E3 the
//! scaled sums of squares), and the 7th-order dense output from 3 extra stages (Hairer's
//! `CONTD8`). The stage f(t + h, y1) computed at acceptance is the next step's first stage.

use super::ode::{OdeSystem, lin};
use core::marker::PhantomData;

use super::scheme::{
    Attempt, Controller, Dense, DenseForm, Scheme, StepStart, stage_input, weighted,
};
use super::tableau_dop853 as tab;

/// The Dormand–Prince 8(5,3) method (marker type; see [`Scheme`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dop853;

/// Dense output of one DOP853 step: a degree-7 polynomial in s = (t − t0)/h,
/// `r0 + s(r1 + s'(r2 + s(r3 + s'(r4 + s(r5 + s'(r6 + s r7))))))` with s' = 1 − s.
pub type Dop853Dense<const N: usize> = Dense<N, 8, Dop853>;

impl<const N: usize> DenseForm<N, 8> for Dop853 {
    fn at(r: &[[f64; N]; 8], s: f64) -> [f64; N] {
        let [r0, r1, r2, r3, r4, r5, r6, r7] = r;
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

    #[inline]
    fn attempt<S: OdeSystem<N> + ?Sized>(
        sys: &S,
        from: StepStart<'_, N>,
    ) -> Attempt<N, Self::Stages> {
        let StepStart { t, y, f0, h, tol } = from;
        let mut k = [[0.0; N]; 12];
        k[0] = *f0;
        // One line per stage so that every row is a constant of known length (see
        // `stage_input`).
        macro_rules! stage {
            ($i:literal, $row:expr) => {
                let yi = stage_input(y, h, &$row, &k);
                k[$i] = sys.rhs(t + tab::C[$i] * h, &yi);
            };
        }
        stage!(1, tab::A2);
        stage!(2, tab::A3);
        stage!(3, tab::A4);
        stage!(4, tab::A5);
        stage!(5, tab::A6);
        stage!(6, tab::A7);
        stage!(7, tab::A8);
        stage!(8, tab::A9);
        stage!(9, tab::A10);
        stage!(10, tab::A11);
        // c12 = 1: evaluate at exactly t + h, as DOP853 does.
        let yi = stage_input(y, h, &tab::A12, &k);
        k[11] = sys.rhs(t + h, &yi);
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
        let err = crate::math::abs(h)
            * s5
            * crate::math::sqrt(1.0 / (sys.dimension().max(1) as f64 * deno));
        Attempt { y1, err, stages: k }
    }

    fn accept<S: OdeSystem<N> + ?Sized>(
        sys: &S,
        from: StepStart<'_, N>,
        attempt: &Attempt<N, Self::Stages>,
    ) -> ([f64; N], Self::Dense) {
        let StepStart { t, y, h, .. } = from;
        let y1 = &attempt.y1;
        let mut k = [[0.0; N]; 13];
        for (slot, stage) in k.iter_mut().zip(attempt.stages.iter()) {
            *slot = *stage;
        }
        k[12] = sys.rhs(t + h, y1);
        (k[12], dense_output(sys, t, y, h, y1, &k))
    }
}

/// Hairer's `CONTD8`: the dense output of an accepted step from its stages k1..k13
/// (k13 = f(t + h, y1)), with three more evaluations for stages 14–16.
fn dense_output<S: OdeSystem<N> + ?Sized, const N: usize>(
    sys: &S,
    t: f64,
    y: &[f64; N],
    h: f64,
    y1: &[f64; N],
    stages: &[[f64; N]; 13],
) -> Dop853Dense<N> {
    let mut k = [[0.0; N]; 16];
    k[..13].copy_from_slice(stages);
    let yi = stage_input(y, h, &tab::A14, &k);
    k[13] = sys.rhs(t + tab::C[13] * h, &yi);
    let yi = stage_input(y, h, &tab::A15, &k);
    k[14] = sys.rhs(t + tab::C[14] * h, &yi);
    let yi = stage_input(y, h, &tab::A16, &k);
    k[15] = sys.rhs(t + tab::C[15] * h, &yi);
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
    Dense {
        t0: t,
        h,
        r,
        form: PhantomData,
    }
}

/// An accepted DOP853 step whose dense output is built only on demand
/// ([`crate::reference::Integrator::step_deferred`]): its ends and its stages k1..k13
/// (k1 = f(t0, y0), k13 = f(t1, y1)).
#[derive(Clone, Copy, Debug)]
pub struct Dop853Step<const N: usize> {
    /// Start time.
    pub t0: f64,
    /// State at `t0`.
    pub y0: [f64; N],
    /// End time.
    pub t1: f64,
    /// State at `t1`.
    pub y1: [f64; N],
    h: f64,
    k: [[f64; N]; 13],
}

impl<const N: usize> Default for Dop853Step<N> {
    fn default() -> Self {
        Dop853Step {
            t0: 0.0,
            y0: [0.0; N],
            t1: 0.0,
            y1: [0.0; N],
            h: 0.0,
            k: [[0.0; N]; 13],
        }
    }
}

impl<const N: usize> Dop853Step<N> {
    /// Fill from an accepted attempt of size `h` from `(t0, y0)` ending at `t1`: evaluates
    /// f(t0 + h, y1), the next step's first stage.
    #[inline(always)]
    pub(crate) fn set<S: OdeSystem<N> + ?Sized>(
        &mut self,
        sys: &S,
        t0: f64,
        y0: &[f64; N],
        h: f64,
        t1: f64,
        attempt: &Attempt<N, [[f64; N]; 12]>,
    ) {
        self.t0 = t0;
        self.y0 = *y0;
        self.t1 = t1;
        self.y1 = attempt.y1;
        self.h = h;
        self.k[..12].copy_from_slice(&attempt.stages);
        self.k[12] = sys.rhs(t0 + h, &attempt.y1);
    }

    /// The step size (`t1 − t0` up to rounding; the dense output runs over `[t0, t0 + h]`).
    pub fn h(&self) -> f64 {
        self.h
    }

    /// f(t0, y0).
    pub fn f0(&self) -> [f64; N] {
        self.k[0]
    }

    /// f(t1, y1).
    pub fn f1(&self) -> [f64; N] {
        self.k[12]
    }

    /// The dense output on `[t0, t1]` (three evaluations of `sys`, which must be the field the
    /// step was taken on); the same polynomial as [`Scheme::accept`] builds.
    pub fn dense<S: OdeSystem<N> + ?Sized>(&self, sys: &S) -> Dop853Dense<N> {
        dense_output(sys, self.t0, &self.y0, self.h, &self.y1, &self.k)
    }
}
