//! Bounds of the linearized contact segment: the norms and gains a linearization carries, the
//! fastest contact stiffness over z ≥ 1 (the analytic method's step cap), the harmonic system's
//! condition (near-resonance test, `docs/MODEL.md` §11) and the segment's radius, speed and
//! acceleration bounds the switch search rests on (`docs/MODEL.md` §12).

use super::{LinearSegment, Response};
use crate::analytic::free::harmonic_amplitude;
use crate::analytic::segment::{Bounds, Point, Segment, point_of};
use crate::coefficients::{
    self as coef, Force, LinearizedContact, ModelParams, Position, Velocity,
};
use crate::math;
use crate::params::Params;

/// The Frobenius norm of a 2×2 matrix (rows), diagonal first.
pub(super) fn frobenius(m: [[f64; 2]; 2]) -> f64 {
    let [[a, b], [c, d]] = m;
    math::sqrt(a * a + d * d + b * b + c * c)
}

/// The homogeneous linearized contact acceleration q'' = −2ν q' − Kl q (the generated
/// `linear_acceleration` with no extra force) at position `q` and velocity `v`.
#[inline]
fn homogeneous_acceleration(
    model: &ModelParams,
    kl: &LinearizedContact,
    q: [f64; 2],
    v: [f64; 2],
) -> [f64; 2] {
    let a = coef::linear_acceleration(
        model,
        &Position { x: q[0], y: q[1] },
        &Velocity { vx: v[0], vy: v[1] },
        &Force::default(),
        kl,
    );
    [a.ax, a.ay]
}

/// Gains of the homogeneous linearized contact acceleration: |q''| ≤ g_v |q'| + g_q |q| with g_v
/// the largest singular value of its Jacobian in q' (this function) and g_q the Frobenius norm
/// (≥ the largest singular value, one root instead of three on this per-sub-step path) of its
/// Jacobian in q ([`position_gain`]), read off as its values at unit vectors (the map is
/// linear).
pub(super) fn velocity_gain(model: &ModelParams, kl: &LinearizedContact) -> f64 {
    let acc = |v: [f64; 2]| homogeneous_acceleration(model, kl, [0.0; 2], v);
    let (c1, c2) = (acc([1.0, 0.0]), acc([0.0, 1.0]));
    harmonic_amplitude(c1[0], c2[0], c1[1], c2[1])
}

/// The position gain g_q of [`velocity_gain`].
pub(super) fn position_gain(model: &ModelParams, kl: &LinearizedContact) -> f64 {
    let acc = |q: [f64; 2]| homogeneous_acceleration(model, kl, q, [0.0; 2]);
    frobenius([acc([1.0, 0.0]), acc([0.0, 1.0])])
}

/// An upper bound of ‖Kl‖₂ over every linearization point with z ≥ 1: the square of the fastest
/// contact frequency (the analytic propagator caps its contact step by its inverse root).
///
/// Argument, from the generated formulas only: Kl (`linearized_stiffness`) is affine in K_s,
/// Kl = Kl₀ + K_s J with Kl₀ its value at K_s = 0 (the restoring spring), so
/// ‖Kl‖₂ ≤ ‖Kl₀‖₂ + ‖K_s‖_F ‖J‖₂. The contact function g is rotation-equivariant about the stator
/// centre (g(Rq) = R g(q)), so J(Rq) = R J(q) Rᵀ and ‖J‖₂ depends on z only: J is evaluated along
/// (1, 0) (`taylor_terms`). J is affine in w = 1/z (checked in `tests/generated/field.rs`) and the
/// norm is convex, so its supremum over w ∈ (0, 1] is at an end: J(1) at z = 1 and
/// J(0) = 2 J(½) − J(1) from z = 2. (For the elastic law J = (1 − w) I + w n nᵀ: the bound is
/// 1 + ‖K_s‖_F up to the singular-value margin.)
///
/// Slipping under friction adds μσ ∂(N t)/∂q to Kl (`docs/MODEL.md` §10). With N = (z − 1) nᵀK_s n,
/// ∇N = (nᵀK_s n) n + ((z − 1)/z)(I − n nᵀ)(K_s + K_sᵀ) n, so |∇N| ≤ 3‖K_s‖₂, and
/// ∂t/∂q = R(I − n nᵀ)/z has norm ≤ 1/z ≤ 1: ‖∂(N t)/∂q‖ ≤ |∇N| + |N|/z ≤ 4‖K_s‖₂ on z ≥ 1,
/// added as 4μ‖K_s‖_F (0 at μ = 0).
pub fn max_contact_stiffness(params: &Params) -> f64 {
    let mut model = ModelParams::of(params);
    let ks = frobenius([[model.k_xx, model.k_xy], [model.k_yx, model.k_yy]]);
    let jacobian = |z: f64| {
        let at = Position {
            x: model.offset_x + z,
            y: model.offset_y,
        };
        let t = coef::taylor_terms(&model, &at);
        [[t.a1, t.b1], [t.b2, t.a2]]
    };
    let (j1, j2) = (jacobian(1.0), jacobian(2.0));
    let j0 = [[0, 1], [2, 3]].map(|row| {
        row.map(|k| {
            let (a, b) = (j2.as_flattened(), j1.as_flattened());
            2.0 * a.get(k).copied().unwrap_or(0.0) - b.get(k).copied().unwrap_or(0.0)
        })
    });
    let spectral = |m: [[f64; 2]; 2]| harmonic_amplitude(m[0][0], m[0][1], m[1][0], m[1][1]);
    let j_norm = spectral(j1).max(spectral(j0));
    (model.k_xx, model.k_xy, model.k_yx, model.k_yy) = (0.0, 0.0, 0.0, 0.0);
    let t = coef::taylor_terms(&model, &Position { x: 1.0, y: 0.0 });
    let k0 = coef::linearized_stiffness(&model, &t);
    let friction = 4.0 * params.friction_coefficient * ks;
    spectral([[k0.fa1, k0.fb1], [k0.fb2, k0.fa2]]) + ks * j_norm + friction
}

/// The condition of the harmonic system (Kl − η² I + 2iνη I) Z = F (1, −i)ᵀ that gives the
/// harmonic particular constants: the size of its determinant's terms over the determinant's
/// modulus. Rounding in the generated Cramer formulas is amplified by it; near resonance it can
/// leave finite but wrong constants whose amplitude looks harmless (at z0 = 1 with η = 1 the
/// tangential eigenvalue of Kl is 1 exactly and the computed determinant is rounding noise), so
/// the amplitude alone cannot detect resonance. The determinant comes from the generated
/// `contact_modes` of the shifted stiffness Kl − η² I: det(M + iP I) = det M − P² + iP tr M.
pub(super) fn harmonic_condition(model: &ModelParams, kl: &LinearizedContact) -> f64 {
    let eta_sq = model.speed_ratio * model.speed_ratio;
    let shifted = LinearizedContact {
        fa1: kl.fa1 - eta_sq,
        fa2: kl.fa2 - eta_sq,
        ..*kl
    };
    let det = coef::contact_modes(model, &shifted).det;
    let p = 2.0 * model.damping_ratio * model.speed_ratio;
    let trace = shifted.fa1 + shifted.fa2;
    // A lower bound of the modulus (no hypot on this per-sub-step path): the condition is
    // overestimated by at most √2, which only widens the near-resonant band slightly.
    let modulus = math::abs(det - p * p).max(math::abs(p * trace));
    let terms = math::abs(shifted.fa1 * shifted.fa2)
        + math::abs(shifted.fb1 * shifted.fb2)
        + p * p
        + p * (math::abs(shifted.fa1) + math::abs(shifted.fa2));
    // (0/0 at a zero system is not resonant: there is no harmonic forcing to amplify.)
    if terms == 0.0 { 0.0 } else { terms / modulus }
}

/// Σ‖c_m‖ s^m and the same bound for the first two derivatives at s = `hi`, from the norms
/// ‖c_m‖ in order of m.
#[inline]
fn polynomial_bounds(norms: impl Iterator<Item = f64>, hi: f64) -> (f64, f64, f64) {
    let (mut pr, mut pv, mut pa) = (0.0, 0.0, 0.0);
    // p2 = hi^(m−2), p1 = hi^(m−1), p0 = hi^m.
    let (mut p2, mut p1, mut p0) = (0.0, 0.0, 1.0);
    for (m, norm) in norms.enumerate() {
        let mf = m as f64;
        pr += norm * p0;
        pv += mf * norm * p1;
        pa += mf * (mf - 1.0) * norm * p2;
        (p2, p1, p0) = (if m == 0 { 1.0 } else { p1 }, p0, p0 * hi);
    }
    (pr, pv, pa)
}

impl Segment for LinearSegment {
    fn point(&self, s: f64) -> Point {
        let state = self.state_with(s, &self.lin.scalars(s));
        point_of(state, self.lin.offset.0, self.lin.offset.1)
    }

    fn bounds(&self, lo: f64, hi: f64) -> Bounds {
        let l = &self.lin;
        // ‖cos(√A s)‖ ≤ cosh(√‖A‖ s), ‖sin(√A s)/√A‖ ≤ s·cosh(√‖A‖ s) (power series).
        let ch = math::cosh(math::sqrt(l.norm_a) * hi);
        let decay = math::exp(-l.nu * lo);
        // |q0|, |w0| (no overflow: states are bounded by the divergence radius).
        let h = &self.part.start;
        let q0 = math::sqrt(h.q0x * h.q0x + h.q0y * h.q0y);
        let w0 = math::sqrt(h.w0x * h.w0x + h.w0y * h.w0y);
        let rh = decay * ch * (q0 + hi * w0);
        let vh = l.nu * rh + decay * ch * (l.norm_a * hi * q0 + w0);
        let ah = l.gains.0 * vh + l.gains.1 * rh;
        let (amp, shift) = (l.harmonic_amplitude, l.harmonic_shift);
        // |Σ c_m s^m| and its derivatives, bounded term by term at s = hi (1-norms bound the
        // Euclidean ones).
        let norm = |c: &[f64]| c.iter().take(2).map(|v| math::abs(*v)).sum::<f64>();
        let (pr, pv, pa) = match &self.part.response {
            Response::None => (0.0, 0.0, 0.0),
            Response::Polynomial(b) => {
                let c = [b.b0x, b.b0y, b.b1x, b.b1y, b.b2x, b.b2y, b.b3x, b.b3y];
                polynomial_bounds(c.chunks_exact(2).map(norm), hi)
            }
            Response::Series(c) => polynomial_bounds(c.terms().iter().map(|c| norm(c)), hi),
        };
        Bounds {
            radius: rh + amp + shift + pr,
            speed: vh + l.eta * amp + pv,
            accel: ah + l.eta * l.eta * amp + pa,
        }
    }
}
