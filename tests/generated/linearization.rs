//! `taylor_terms` and `linearized_stiffness` (`docs/MODEL.md` §2–3).

use nalgebra::{Matrix2, Vector2};
use proptest::prelude::*;
use rotor_rub::coefficients as coef;

use crate::support::*;

/// Central-difference step for the Jacobian of g: truncation h²|g'''|/6 with |g'''| ≲ 6/z0³ ≤ 48
/// (z0 ≥ 0.5) gives ≤ 8e-10; rounding u|g|/h ≈ 3e-11. Hence the relative tolerance 1e-6 of the
/// brief leaves a margin of ~1000.
const H: f64 = 1e-5;

proptest! {
    #![proptest_config(config(256))]

    /// A1, B1, B2, A2 are the Jacobian of g(x, y) = (1 − 1/z)(x − εx, y − εy) at (x0, y0) and
    /// D = g(r0) − J r0, both against central differences (rel. 1e-6); the generated values
    /// also equal `docs/MODEL.md` §2's closed forms (α^1.5 form and the n nᵀ form, rel. 1e-12: same
    /// quantity, a few roundings apart).
    #[test]
    fn taylor_terms_match_finite_difference_jacobian(case in any_case()) {
        let (ex, ey) = case.offset;
        let t = case.taylor();
        let ours = Matrix2::new(t.a1, t.b1, t.b2, t.a2);
        let fd = jacobian(|x, y| g(x, y, ex, ey), case.x0, case.y0, H);
        let scale = 1.0 + fd.abs().max();
        prop_assert!((ours - fd).abs().max() <= 1e-6 * scale, "J {ours} vs finite differences {fd}");
        let r0 = Vector2::new(case.x0, case.y0);
        let d_fd = g(case.x0, case.y0, ex, ey) - fd * r0;
        let d_scale = scale * (1.0 + r0.norm());
        prop_assert!((t.d1 - d_fd.x).abs() <= 1e-6 * d_scale, "D1 {} vs {}", t.d1, d_fd.x);
        prop_assert!((t.d2 - d_fd.y).abs() <= 1e-6 * d_scale, "D2 {} vs {}", t.d2, d_fd.y);

        // docs/MODEL.md §2 closed forms.
        let (u0, v0) = (case.x0 - ex, case.y0 - ey);
        let alpha = u0 * u0 + v0 * v0;
        let a15 = alpha.powf(1.5);
        let z0 = alpha.sqrt();
        let (nx, ny) = (u0 / z0, v0 / z0);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs() + b.abs()) * (1.0 + r0.norm());
        prop_assert!(close(t.a1, (a15 - alpha + u0 * u0) / a15) && close(t.a1, 1.0 - 1.0 / z0 + nx * nx / z0));
        prop_assert!(close(t.a2, (a15 - alpha + v0 * v0) / a15) && close(t.a2, 1.0 - 1.0 / z0 + ny * ny / z0));
        prop_assert!(close(t.b1, u0 * v0 / a15) && close(t.b2, nx * ny / z0));
        let x0y0 = case.x0 * u0 + case.y0 * v0;
        prop_assert!(close(t.d1, (-alpha * ex * (z0 - 1.0) - u0 * x0y0) / a15), "D1 {}", t.d1);
        prop_assert!(close(t.d2, (-alpha * ey * (z0 - 1.0) - v0 * x0y0) / a15), "D2 {}", t.d2);
    }

    /// Kl = I + K_s J and Fd = K_s D with nalgebra matrices, in the corrected layout
    /// [[Fa1, Fb1], [Fb2, Fa2]]. Both sides do the same few products in a different order:
    /// rel. 1e-12 of ‖K_s‖‖J‖.
    #[test]
    fn linearized_stiffness_matches_matrix_products(case in any_case()) {
        let t = case.taylor();
        let j = Matrix2::new(t.a1, t.b1, t.b2, t.a2);
        let d = Vector2::new(t.d1, t.d2);
        let ks = case.ks();
        let kl = Matrix2::identity() + ks * j;
        let fd = ks * d;
        let l = case.linearized();
        let scale = 1.0 + ks.abs().max() * (j.abs().max() + d.abs().max());
        prop_assert!((kl_matrix(&l) - kl).abs().max() <= 1e-12 * scale, "{l:?} vs {kl}");
        prop_assert!((l.fd1 - fd.x).abs() <= 1e-12 * scale && (l.fd2 - fd.y).abs() <= 1e-12 * scale);
    }
}

/// At the contact boundary z0 = 1, n = (cos ϑ, sin ϑ): A1 = cos²ϑ, B1 = B2 = sinϑ cosϑ,
/// A2 = sin²ϑ, D1 = −cosϑ (x0 cosϑ + y0 sinϑ), D2 = −sinϑ (x0 cosϑ + y0 sinϑ), and the
/// linearized force K_s n nᵀ (r − r_c) vanishes at the contact point r_c (`docs/MODEL.md` §2).
#[test]
fn taylor_terms_at_the_contact_boundary() {
    for k in 0..24 {
        let th = 0.3 + f64::from(k) * std::f64::consts::TAU / 24.0;
        let (ex, ey) = (0.3, -0.2);
        let (c, s) = (th.cos(), th.sin());
        let (x0, y0) = (ex + c, ey + s);
        let model = coef::ModelParams {
            offset_x: ex,
            offset_y: ey,
            ..coef::ModelParams::default()
        };
        let t = coef::taylor_terms(&model, &coef::Position { x: x0, y: y0 });
        let proj = x0 * c + y0 * s;
        for (got, want) in [
            (t.a1, c * c),
            (t.b1, s * c),
            (t.b2, s * c),
            (t.a2, s * s),
            (t.d1, -c * proj),
            (t.d2, -s * proj),
        ] {
            assert!((got - want).abs() <= 1e-14, "ϑ = {th}: {got} vs {want}");
        }
        // g is zero on the boundary, so J r_c + D = 0.
        assert!((t.a1 * x0 + t.b1 * y0 + t.d1).abs() <= 1e-14);
        assert!((t.b2 * x0 + t.a2 * y0 + t.d2).abs() <= 1e-14);
    }
}
