//! Bounds of the linearized contact segment: the norms and gains a linearization carries, the
//! fastest contact stiffness over z ≥ 1 (the analytic method's step cap), the harmonic system's
//! condition (near-resonance test, `docs/MODEL.md` §11) and the segment's radius, speed and
//! acceleration bounds the switch search rests on (`docs/MODEL.md` §12).

use super::{LinearSegment, Response};
use crate::analytic::free::harmonic_amplitude;
use crate::analytic::segment::{Bounds, Point, Segment};
use crate::coefficients::{self as coef, LinearizedContact, ModelParams, Position};
use crate::geometry;
use crate::math;
use crate::params::Params;

/// The Frobenius norm of a 2×2 matrix (rows), diagonal first.
pub(super) fn frobenius(m: [[f64; 2]; 2]) -> f64 {
    let [[a, b], [c, d]] = m;
    math::sqrt(a * a + d * d + b * b + c * c)
}

/// Gains of the homogeneous linearized contact acceleration: |q''| ≤ g_v |q'| + g_q |q| with g_v
/// the largest singular value of its Jacobian in q' (this function) and g_q the Frobenius norm
/// (≥ the largest singular value, one root instead of three on this per-sub-step path) of its
/// Jacobian in q ([`position_gain`]); the Jacobians are the generated `linear_field_jacobians`.
pub(super) fn velocity_gain(model: &ModelParams, kl: &LinearizedContact) -> f64 {
    let j = coef::linear_field_jacobians(model, kl);
    harmonic_amplitude(j.v11, j.v12, j.v21, j.v22)
}

/// The position gain g_q of [`velocity_gain`].
pub(super) fn position_gain(model: &ModelParams, kl: &LinearizedContact) -> f64 {
    let j = coef::linear_field_jacobians(model, kl);
    frobenius([[j.q11, j.q12], [j.q21, j.q22]])
}

/// An upper bound of ‖Kl‖₂ over every linearization point with z ≥ 1: the square of the fastest
/// contact frequency (the analytic propagator caps its contact step by its inverse root).
///
/// Argument, from the generated formulas only: Kl (`linearized_stiffness`) is affine in K_s,
/// Kl = Kl₀ + K_s J with Kl₀ its value at K_s = 0 (the restoring spring), so
/// ‖Kl‖₂ ≤ ‖Kl₀‖₂ + ‖K_s‖_F ‖J‖₂. The contact function g is rotation-equivariant about the stator
/// centre (g(Rq) = R g(q)), so J(Rq) = R J(q) Rᵀ and ‖J‖₂ depends on z only: J is evaluated at
/// the offset (z, 0) from the stator centre (`taylor_terms`). J is affine in w = 1/z (checked in
/// `tests/generated/field.rs`) and the norm is convex, so its supremum over w ∈ (0, 1] is at an
/// end: J(1) at z = 1 and J(0) = 2 J(½) − J(1) from z = 2. (For the elastic law
/// J = (1 − w) I + w n nᵀ: the bound is 1 + ‖K_s‖_F up to the singular-value margin.)
/// Slipping under friction adds at most the generated `stator_bounds`' friction gradient
/// 4μ‖K_s‖_F (its proof is with that formula; 0 at μ = 0).
pub fn max_contact_stiffness(params: &Params) -> f64 {
    let mut model = ModelParams::of(params);
    let stator = coef::stator_bounds(&model);
    let jacobian = |z: f64| {
        let (x, y) = geometry::at_offset(&model, (z, 0.0));
        let t = coef::taylor_terms(&model, &Position { x, y });
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
    spectral([[k0.fa1, k0.fb1], [k0.fb2, k0.fa2]])
        + stator.stator_norm * j_norm
        + stator.friction_gradient
}

/// The condition of the harmonic system (Kl − η² I + iη C) Z = F (1, −i)ᵀ (generated
/// `harmonic_system`) that gives the harmonic particular constants: the size of its
/// determinant's terms over the determinant's modulus. Rounding in the generated Cramer formulas
/// is amplified by it; near resonance it can leave finite but wrong constants whose amplitude
/// looks harmless (at z0 = 1 with η = 1 the tangential eigenvalue of Kl is 1 exactly and the
/// computed determinant is rounding noise), so the amplitude alone cannot detect resonance.
pub(super) fn harmonic_condition(model: &ModelParams, kl: &LinearizedContact) -> f64 {
    let h = coef::harmonic_system(model, kl);
    // A lower bound of the modulus (no hypot on this per-sub-step path): the condition is
    // overestimated by at most √2, which only widens the near-resonant band slightly.
    let modulus = math::abs(h.det_re).max(math::abs(h.det_im));
    // |det(A + iB)|'s terms: the moduli of the two complex products it is the difference of.
    let modulus_of = |re: f64, im: f64| math::abs(re) + math::abs(im);
    let product = |(a, b): (f64, f64), (c, d): (f64, f64)| modulus_of(a, b) * modulus_of(c, d);
    let terms =
        product((h.re11, h.im11), (h.re22, h.im22)) + product((h.re12, h.im12), (h.re21, h.im21));
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
        geometry::point(&self.lin.model, state)
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
