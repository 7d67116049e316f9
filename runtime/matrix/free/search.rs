//! The contact search on a free flight: h(s) = z² − 1 of the station's relative position
//! P = B q(s) − ε̂ (both bodies moving) as an event function of the one switch kernel
//! (`analytic::switch`, its certificate `certificate.rs`: one proof for every model), walked
//! on a grid of chunks fixed by the segment alone.
//!
//! # Why no contact is missed
//! The kernel discards an interval [a, b] only when g ≤ min of two parabolas through the ends'
//! exact g, g' with curvature M ≥ |g''| stays ≤ TOUCH (`docs/MODEL.md` §12). Here g = h and
//! h'' = 2(|P'|² + (P − ε̂)·P''), so M = 2(V² + R·A) with R ≥ |P − ε̂|, V ≥ |P'|, A ≥ |P''|
//! on [a, b] (`analytic::switch::local_curvature`, which also tightens R and V around the
//! known point at a). R, V and A are the sums of
//! - the homogeneous part's bounds, Σ_k Σ_i b_{k,j,i} max e^{α_k s} s^i/i! over [a, b]
//!   (`linalg::ProjectedMotion::bound`, proved in `linalg/projected.rs`: entrywise
//!   |e^{Ts}| ≤ e^{αs} e^{|U|s} for each triangular block T = Λ + U of the modal form),
//! - the harmonic part's: |Re(P̂ e^{iθ})| ≤ σ1, the largest singular value of the real 2 × 2
//!   map (cos θ, sin θ) ↦ Re(P̂ e^{iθ}), and ησ1, η²σ1 for its derivatives,
//! - the constant part's |P_u − ε̂|,
//!
//! each computed from nonnegative operands with a relative margin for rounding, so M is never
//! low. The bounds are of the function the point evaluations compute (the stored modal form
//! and amplitudes), so the proof holds for the computed h to its rounding (a touch within
//! TOUCH is not a contact). Grazing contacts are found because nothing is discarded without
//! that proof; a segment's start counts as inside free flight (the kernel clamps g(0) ≤ 0).
//!
//! # The grid
//! Chunks start at the segment's start; each chunk's length is the previous one's, doubled
//! after a chunk the first bound test proved free, halved after one that needed more than
//! [`SPLIT_TESTS`] tests, within [L_max/[`CHUNK_RANGE`], L_max], L_max a quarter of the
//! forcing period. It depends on the segment alone, never on the targets served, so sampling
//! never moves a switch. Every [`SETTLE_CHECK_CHUNKS`] chunks the station's reach over all
//! later times is bounded (`ProjectedMotion::bound_after`): inside the clearance, the flight
//! is settled and never searched again.
//!
//! # Budget
//! One chunk is searched with the analytic method's budget (`Budget::EXPLORE`). A chunk the
//! budget leaves unresolved is searched again in [`RETRY_PARTS`] parts with a fresh budget
//! each; a part still unresolved holds h within rounding of 0 along a stretch (sliding on the
//! clearance circle without crossing it): it is a touch, counted in `FreeWork::unresolved`.
//! A switch whose refinement hit its cap is reported and counted in `FreeWork::uncertain`.

use core::cell::Cell;

use super::super::model::MatrixModel;
use super::flight::{Decomposition, Flight, StationPoint};
use crate::analytic::switch::{Budget, EventFunction, Search, local_curvature, locate};
use crate::math;

/// Chunks between two checks of whether the flight has settled.
pub(super) const SETTLE_CHECK_CHUNKS: u64 = 8;
/// Bound tests above which a chunk counts as hard (the next one is halved).
pub(super) const SPLIT_TESTS: u64 = 4;
/// The shortest chunk is L_max over this.
pub(super) const CHUNK_RANGE: f64 = 1024.0;
/// Parts an unresolved chunk is searched again in.
pub(super) const RETRY_PARTS: usize = 8;

/// h = z² − 1 along a flight as the kernel's event function, counting its work.
pub(super) struct StationSwitch<'a, const CAP: usize> {
    pub(super) model: &'a MatrixModel<CAP>,
    pub(super) decomposition: &'a Decomposition<CAP>,
    pub(super) flight: &'a Flight<CAP>,
    pub(super) evaluations: Cell<u64>,
    pub(super) tests: Cell<u64>,
}

impl<const CAP: usize> EventFunction for StationSwitch<'_, CAP> {
    type Point = StationPoint;

    #[inline]
    fn point(&self, s: f64) -> StationPoint {
        self.evaluations.set(self.evaluations.get() + 1);
        self.flight.point(self.model, self.decomposition, s)
    }

    #[inline]
    fn value(&self, p: &StationPoint) -> (f64, f64) {
        (p.h, p.dh)
    }

    fn curvature(&self, lo: f64, at_lo: &StationPoint, hi: f64) -> f64 {
        self.tests.set(self.tests.get() + 1);
        let r = self.flight.reach(self.decomposition, lo, hi);
        let r0 = math::sqrt((at_lo.h + 1.0).max(0.0));
        local_curvature(
            r0,
            at_lo.speed(),
            r.radius,
            r.speed,
            r.acceleration,
            hi - lo,
        )
    }
}

/// What searching one chunk found.
pub(super) enum ChunkResult {
    /// Proved free (or a touch) up to the chunk's end.
    Free {
        /// Whether a part stayed unresolved after the retries (a touch within rounding).
        unresolved: bool,
    },
    /// The first contact at local time `s`, with the station there (the refinement's last
    /// evaluation: not evaluated again).
    Contact {
        s: f64,
        at: StationPoint,
        /// Whether it is proved first and refined to rounding.
        certain: bool,
    },
}

/// Search (a, b] (points `pa`, `pb` known) for the first contact: the kernel with the
/// analytic budget, then an unresolved chunk again in parts with fresh budgets.
pub(super) fn search_chunk<const CAP: usize>(
    f: &StationSwitch<'_, CAP>,
    a: f64,
    pa: StationPoint,
    b: f64,
    pb: StationPoint,
) -> ChunkResult {
    match locate(f, a, pa, b, Some(pb), f64::INFINITY, &Budget::EXPLORE, None) {
        Search::None => ChunkResult::Free { unresolved: false },
        Search::Found { s, point, certain } => ChunkResult::Contact {
            s,
            at: point,
            certain,
        },
        Search::Unresolved => {
            let mut unresolved = false;
            let (mut lo, mut plo) = (a, pa);
            let width = (b - a) / RETRY_PARTS as f64;
            for k in 1..=RETRY_PARTS {
                let hi = if k == RETRY_PARTS {
                    b
                } else {
                    a + width * k as f64
                };
                let phi = if k == RETRY_PARTS { pb } else { f.point(hi) };
                match locate(
                    f,
                    lo,
                    plo,
                    hi,
                    Some(phi),
                    f64::INFINITY,
                    &Budget::EXPLORE,
                    None,
                ) {
                    Search::None => {}
                    Search::Found { s, point, certain } => {
                        return ChunkResult::Contact {
                            s,
                            at: point,
                            certain,
                        };
                    }
                    Search::Unresolved => unresolved = true,
                }
                (lo, plo) = (hi, phi);
            }
            ChunkResult::Free { unresolved }
        }
    }
}
