//! Dormand–Prince 5(4) (`DOPRI5`, MATLAB's `ode45`): 7 stages with FSAL, local extrapolation
//! (the 5th-order solution is propagated), error from the embedded 4th-order solution, and
//! Shampine's 4th-order dense output.

use core::marker::PhantomData;

use super::ode::{OdeSystem, lin};
use super::scheme::{
    Attempt, Controller, Dense, DenseForm, Scheme, StepStart, stage_input_slice, weighted_slice,
};
use super::tableau_rk45 as tab;

/// The Dormand–Prince 5(4) pair (marker type; see [`Scheme`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rk45;

/// Dense output of one DOPRI5 step: a quartic in θ = (t − t0)/h,
/// `r0 + θ(r1 + (1−θ)(r2 + θ(r3 + (1−θ) r4)))` (Hairer's `CONTD5`).
pub type Rk45Dense<const N: usize> = Dense<N, 5, Rk45>;

impl<const N: usize> DenseForm<N, 5> for Rk45 {
    fn at(r: &[[f64; N]; 5], th: f64) -> [f64; N] {
        let [r0, r1, r2, r3, r4] = r;
        let th1 = 1.0 - th;
        let mut out = [0.0; N];
        let rows = out.iter_mut().zip(r0).zip(r1).zip(r2).zip(r3).zip(r4);
        for (((((o, a0), a1), a2), a3), a4) in rows {
            *o = a0 + th * (a1 + th1 * (a2 + th * (a3 + th1 * a4)));
        }
        out
    }
}

impl<const N: usize> Scheme<N> for Rk45 {
    /// k1..k7 (k7 = f(t + h, y1)).
    type Stages = [[f64; N]; 7];
    type Dense = Rk45Dense<N>;
    const ORDER: i32 = 5;
    const STAGE_EVALUATIONS: u64 = 6;
    const ACCEPT_EVALUATIONS: u64 = 0;
    const CONTROLLER: Controller = Controller {
        safety: 0.9,
        fac_min: 0.2,
        fac_max: 10.0,
        alpha: 0.2 - 0.04 * 0.75,
        beta: 0.04,
    };

    #[inline]
    fn attempt<S: OdeSystem<N> + ?Sized>(
        sys: &S,
        from: StepStart<'_, N>,
    ) -> Attempt<N, Self::Stages> {
        let StepStart { t, y, f0, h, tol } = from;
        let mut k = [[0.0; N]; 7];
        k[0] = *f0;
        let rows: [&[f64]; 5] = [&tab::A2, &tab::A3, &tab::A4, &tab::A5, &tab::A6];
        for (i, (row, c)) in rows.iter().zip(tab::C.iter().skip(1)).enumerate() {
            let yi = stage_input_slice(y, h, row, &k);
            if let Some(slot) = k.get_mut(i + 1) {
                *slot = sys.rhs(t + c * h, &yi);
            }
        }
        let y1 = stage_input_slice(y, h, &tab::B, &k);
        k[6] = sys.rhs(t + h, &y1);
        let e = weighted_slice(&tab::E, &k);
        let mut sum = 0.0;
        for ((ei, a), b) in e.iter().zip(y.iter()).zip(y1.iter()) {
            let r = h * ei / tol.scale(*a, *b);
            sum += r * r;
        }
        let err = crate::math::sqrt(sum / sys.dimension().max(1) as f64);
        Attempt { y1, err, stages: k }
    }

    fn accept<S: OdeSystem<N> + ?Sized>(
        _sys: &S,
        from: StepStart<'_, N>,
        attempt: &Attempt<N, Self::Stages>,
    ) -> ([f64; N], Self::Dense) {
        let StepStart { t, y, h, .. } = from;
        let k = &attempt.stages;
        let [k1, .., k7] = k;
        let ydiff = lin(&[(1.0, &attempt.y1), (-1.0, y)]);
        let bspl = lin(&[(h, k1), (-1.0, &ydiff)]);
        let r3 = lin(&[(1.0, &ydiff), (-h, k7), (-1.0, &bspl)]);
        let r4 = lin(&[(h, &weighted_slice(&tab::D, k))]);
        let r = [*y, ydiff, bspl, r3, r4];
        (
            *k7,
            Dense {
                t0: t,
                h,
                r,
                form: PhantomData,
            },
        )
    }
}
