//! Free flight over one fixed step as a precomputed affine map, and the bound that proves a free
//! step contact-free.
//!
//! The free equations (`docs/MODEL.md` §4) are linear with a harmonic forcing, so over a step of
//! length `dt` the end state is w(dt) = Φ(dt)·w(0) + G(dt)·(cos θ0, sin θ0): Φ is the 4×4
//! transition matrix of the homogeneous system and G the zero-state response to the forcing over
//! the step. The map is linear in (w, cos θ0, sin θ0), so its columns are the free closed form
//! at the unit vectors: the generator substitutes them and emits Φ and G as formulas of the
//! basis at `dt` (`analytic::free::transition_matrix`, `forcing_matrix`; near resonance G's
//! columns are the resonance-stable form, §11, evaluated on the unit phasors). No closed form is
//! typed here, and the switch bound is the free segment's own (`analytic::free`).
//!
//! Under a constant input force u (`docs/MODEL.md` §15) free flight is free flight about the
//! static deflection d: w(dt) − d = Φ·(w(0) − d) + G·phasor, so the map gains the constant
//! b = d − Φ·d, recomputed (16 multiplications) when u changes; Φ and G do not depend on u.

use super::resolution::ContactResolution;
use super::search::local_curvature;
use crate::analytic::free::{
    BasisBound, FreeConstants, FreeInstant, FreeSegment, forcing_matrix, plain_norm,
    transition_matrix,
};
use crate::coefficients::FreeBasis;
use crate::params::{Params, State};

/// The exact free-flight map over one step of fixed length, with the constants of the switch
/// bound on that step. Computing it costs the basis at `dt` (one `exp`, one `sin_cos`), the
/// rotation (one `sin_cos`, plus an `expm1` and a `sin_cos` in the resonance-stable form), the
/// generated Φ and G (90 flops; two closed-form evaluations for G near resonance) and the
/// basis bounds, paid once per step length and parameter set; a parameter change that keeps
/// the damping reuses Φ, the basis and its bounds ([`Self::set_params`]).
#[derive(Clone, Copy, Debug)]
// In the order a free step reads it, the parameter-change-only `basis_at_dt` last (left to
// itself, rustc puts the fields with niches first; `benches/stepper.rs` measures steps from
// cold copies, where the cache lines touched count).
#[repr(C)]
pub struct FreeTransition {
    dt: f64,
    /// Φ(dt), row-major: `phi[i][j]` is component i of the end state for a unit component j
    /// at the start (order x, y, x', y').
    phi: [[f64; 4]; 4],
    /// G(dt): the end state for a zero start state and the forcing phasor (1, 0), (0, 1).
    g: [[f64; 2]; 4],
    /// b = d − Φ·d for the input force's static deflection d; `None` without input force.
    input: Option<[f64; 4]>,
    /// (cos η·dt, sin η·dt): the forcing phasor's rotation over one step.
    rotation: (f64, f64),
    /// (ε̂x, ε̂y).
    offset: (f64, f64),
    /// |ε − d| for the switch bound (`FreeSegment::offset_distance`), kept with `constants`.
    offset_distance: f64,
    /// Bounds of the basis functions on [0, dt].
    basis: BasisBound,
    constants: FreeConstants,
    /// The basis (EC, ES) at dt, kept with Φ by [`Self::set_params`].
    basis_at_dt: FreeBasis,
    /// The contact sub-steps one step of `dt` needs (`ContactResolution`).
    contact: ContactResolution,
}

impl FreeTransition {
    /// The map over `dt` (> 0) for `params`, with their free constants.
    pub fn new(params: &Params, constants: &FreeConstants, dt: f64) -> Self {
        let mut transition = FreeTransition {
            dt,
            phi: [[0.0; 4]; 4],
            g: [[0.0; 2]; 4],
            rotation: (1.0, 0.0),
            constants: *constants,
            basis: BasisBound::on(constants, 0.0, dt),
            basis_at_dt: FreeBasis::default(),
            offset: (params.offset_x, params.offset_y),
            offset_distance: FreeSegment::offset_distance(
                constants,
                (params.offset_x, params.offset_y),
            ),
            input: None,
            contact: ContactResolution::new(params, dt),
        };
        transition.compute();
        transition.take_input((params.offset_x, params.offset_y), constants.deflection());
        transition
    }

    /// Take changed parameters, the step kept: the map [`Self::new`] gives for them, with
    /// Φ(dt), the basis at dt and its bounds kept when the damping is unchanged
    /// (`FreeConstants::damping_key`) — a change of speed, forcing, stator or input force
    /// recomputes G(dt) and the rotation only. In place either way, the free constants too
    /// (the map is 650 bytes; built on the stack and copied, the copy's wide loads of the
    /// constants' just-written fields cost more than computing them).
    pub fn set_params(&mut self, params: &Params) {
        let damping = self.constants.damping_key();
        let deflection = self.constants.deflection();
        self.constants = FreeConstants::new(params);
        let offset = (params.offset_x, params.offset_y);
        if self.constants.damping_key() != damping {
            self.basis = BasisBound::on(&self.constants, 0.0, self.dt);
            self.compute();
        } else {
            let (g, rotation) = self.constants.unforced(|unforced| {
                let at_dt = FreeInstant::with_basis(unforced, self.dt, self.basis_at_dt);
                (forcing_matrix(unforced, &at_dt), at_dt.rotation())
            });
            self.g = g;
            self.rotation = rotation;
            self.basis = self.basis.with_forcing(&self.constants, self.dt);
        }
        if self.contact.changed_by(params) {
            self.contact = ContactResolution::new(params, self.dt);
        }
        self.take_input(offset, deflection);
    }

    /// Φ, G, the rotation and the basis at dt for the constants in force (the basis bounds
    /// are the caller's); the input force's part is the caller's ([`Self::take_input`]).
    fn compute(&mut self) {
        // The unforced free step; the basis and the rotation at dt once for Φ and G.
        let dt = self.dt;
        let (phi, g, at_dt) = self.constants.unforced(|unforced| {
            let at_dt = FreeInstant::at(unforced, dt);
            (
                transition_matrix(unforced, &at_dt),
                forcing_matrix(unforced, &at_dt),
                at_dt,
            )
        });
        self.phi = phi;
        self.g = g;
        self.rotation = at_dt.rotation();
        self.basis_at_dt = at_dt.basis();
    }

    /// Take the input force of `constants` (the same parameters otherwise): b = d − Φ·d for
    /// its static deflection d, and the constants of the switch bound. Φ and G are kept.
    pub fn set_input(&mut self, constants: &FreeConstants) {
        let deflection = self.constants.deflection();
        self.constants = *constants;
        self.take_input(self.offset, deflection);
    }

    /// The stator offset `offset` and the input force's part for the constants in force,
    /// whose static deflection was `previous` before: b = d − Φ·d, and |ε − d| (a `hypot`)
    /// again only when ε or d changed.
    fn take_input(&mut self, offset: (f64, f64), previous: (f64, f64)) {
        let (dx, dy) = self.constants.deflection();
        if offset != self.offset || (dx, dy) != previous {
            self.offset_distance = FreeSegment::offset_distance(&self.constants, offset);
        }
        self.offset = offset;
        self.input = if (dx, dy) == (0.0, 0.0) {
            None
        } else {
            let mut b = [dx, dy, 0.0, 0.0];
            for (bi, row) in b.iter_mut().zip(&self.phi) {
                *bi -= row[0] * dx + row[1] * dy;
            }
            Some(b)
        };
    }

    /// The step length this map is for.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The contact mode's rate bound ρ_c (see `ContactResolution`).
    pub fn contact_rate(&self) -> f64 {
        self.contact.rate()
    }

    /// The contact sub-steps a step of [`Self::dt`] needs so that each is at most
    /// [`MAX_RATE_STEP`]/ρ_c long (at least 1, at most [`MAX_SUBSTEPS`]).
    pub fn resolving_substeps(&self) -> u32 {
        self.contact.substeps()
    }

    /// The stator offset (ε̂x, ε̂y).
    #[inline]
    pub fn offset(&self) -> (f64, f64) {
        self.offset
    }

    /// |ε − d| of the parameters in force (`FreeSegment::offset_distance`).
    #[inline]
    pub fn offset_distance(&self) -> f64 {
        self.offset_distance
    }

    /// The free constants of the parameters in force, input force included (the stepper's
    /// only copy of them).
    pub fn constants(&self) -> &FreeConstants {
        &self.constants
    }

    /// The forcing phasor after one step from `phasor` = (cos θ0, sin θ0).
    #[inline]
    pub fn rotate(&self, phasor: (f64, f64)) -> (f64, f64) {
        let (c, s) = phasor;
        let (cd, sd) = self.rotation;
        (c * cd - s * sd, s * cd + c * sd)
    }

    /// The free state one step after `w`, with forcing phasor `phasor` at the start:
    /// Φ·w + G·phasor (24 multiplications, 20 additions), plus b under an input force.
    #[inline]
    pub fn apply(&self, w: &State, phasor: (f64, f64)) -> State {
        let end = self.apply_unforced(w, phasor);
        match self.input {
            None => end,
            Some(b) => State::new(end.x + b[0], end.y + b[1], end.vx + b[2], end.vy + b[3]),
        }
    }

    #[inline]
    fn apply_unforced(&self, w: &State, phasor: (f64, f64)) -> State {
        let a = w.to_array();
        let mut out = [0.0; 4];
        for (o, (row, g)) in out.iter_mut().zip(self.phi.iter().zip(&self.g)) {
            *o = row[0] * a[0]
                + row[1] * a[1]
                + row[2] * a[2]
                + row[3] * a[3]
                + g[0] * phasor.0
                + g[1] * phasor.1;
        }
        State::from_array(out)
    }

    /// A rigorous upper bound of |h''| (h = z² − 1) over the free step from `w` with forcing
    /// phasor `phasor` at the start, where |r − ε| = `r0`: the free-flight bound
    /// ([`crate::analytic::free`]) on [0, dt], with radius and speed tightened around the start as
    /// in [`super::search::curvature`].
    #[inline]
    pub fn curvature_bound(&self, w: &State, phasor: (f64, f64), r0: f64) -> f64 {
        let reach = FreeSegment::reach_with_phasor(
            &self.constants,
            self.offset,
            self.offset_distance,
            phasor,
            *w,
        );
        let b = reach.bounds(&self.basis);
        let v0 = plain_norm(w.vx, w.vy);
        local_curvature(r0, v0, b.radius, b.speed, b.accel, self.dt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Preset;

    /// Equal as numbers, and bit for bit unless zero (a zero forcing term may carry either
    /// sign).
    fn same(a: f64, b: f64) -> bool {
        a == b && (a == 0.0 || a.to_bits() == b.to_bits())
    }

    fn assert_same_map(kept: &FreeTransition, fresh: &FreeTransition, what: &str) {
        let pairs = kept
            .phi
            .iter()
            .flatten()
            .zip(fresh.phi.iter().flatten())
            .chain(kept.g.iter().flatten().zip(fresh.g.iter().flatten()))
            .chain([
                (&kept.rotation.0, &fresh.rotation.0),
                (&kept.rotation.1, &fresh.rotation.1),
                (&kept.basis_at_dt.ec, &fresh.basis_at_dt.ec),
                (&kept.basis_at_dt.es, &fresh.basis_at_dt.es),
            ]);
        assert_eq!(kept.contact, fresh.contact, "{what}: contact resolution");
        for (a, b) in pairs {
            assert!(
                same(*a, *b),
                "{what}: {a:e} kept against {b:e} computed anew"
            );
        }
        // The bound constants, through their one use.
        for (w, phasor, r0) in [
            (State::new(0.1, 0.2, -0.3, 0.4), (1.0, 0.0), 0.5),
            (State::new(-0.4, 0.1, 0.7, -0.2), (0.6, 0.8), 0.9),
        ] {
            let (a, b) = (
                kept.curvature_bound(&w, phasor, r0),
                fresh.curvature_bound(&w, phasor, r0),
            );
            assert!(same(a, b), "{what}: curvature bound {a:e} against {b:e}");
            let (a, b) = (kept.apply(&w, phasor), fresh.apply(&w, phasor));
            for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
                assert!(same(x, y), "{what}: step {x:e} against {y:e}");
            }
        }
    }

    type Change = fn(&mut Params);

    /// A parameter change that keeps the damping gives the map `new` computes for the changed
    /// parameters (Φ and the basis kept, the rest recomputed); one that changes it, or near
    /// resonance, recomputes everything.
    #[test]
    fn a_kept_map_is_the_map_computed_anew() {
        let mut kept_phi = 0;
        for preset in Preset::PLANAR {
            let base = preset.problem().params;
            for dt in [1e-3, 0.01, 0.3] {
                let before = FreeTransition::new(&base, &FreeConstants::new(&base), dt);
                let changes: [(&str, Change); 7] = [
                    ("speed", |p| p.speed_ratio = 1.6),
                    ("slow speed", |p| p.speed_ratio = 0.3),
                    ("resonance", |p| p.speed_ratio = 1.0),
                    ("unbalance and phase", |p| {
                        p.eccentricity_ratio *= 2.0;
                        p.phase = 1.0;
                    }),
                    ("offset and stiffness", |p| {
                        p.offset_x = -0.2;
                        p.k_xx *= 3.0;
                    }),
                    ("input force", |p| p.force_x = 0.3),
                    ("damping", |p| p.damping_ratio *= 1.5),
                ];
                for (what, change) in changes {
                    let mut params = base;
                    change(&mut params);
                    assert!(params.validate().is_ok(), "{what}");
                    let constants = FreeConstants::new(&params);
                    kept_phi +=
                        usize::from(before.constants.damping_key() == constants.damping_key());
                    let mut kept = before;
                    kept.set_params(&params);
                    let fresh = FreeTransition::new(&params, &constants, dt);
                    assert_same_map(&kept, &fresh, what);
                }
            }
        }
        // Speed, unbalance, stator and input changes away from resonance keep Φ.
        assert!(
            kept_phi >= 4 * 3 * Preset::PLANAR.len(),
            "Φ kept {kept_phi} times"
        );
    }
}
