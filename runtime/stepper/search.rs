//! The stepper's switch search: the one kernel of [`crate::analytic::switch`] with the hard caps
//! of [`Budget::CAPPED`], so that a step's work is bounded; what the caps cost is reported in
//! [`super::StepReport::search_capped`].

use crate::analytic::segment::{Point, Segment};
use crate::analytic::switch::{self, Boundary, Budget, Direction, Search};

pub use crate::analytic::switch::{
    TOUCH, curvature, local_curvature, no_crossing, no_crossing_likely,
};

/// Most bound tests (each with at most one segment evaluation) in one search.
pub const MAX_SEARCH_EVALUATIONS: u32 = Budget::CAPPED.tests;
/// Most Newton/bisection iterations refining one located switch.
pub const MAX_REFINE_ITERATIONS: u32 = Budget::CAPPED.refine;

/// The first crossing of z = 1 in `direction` on (lo, hi] of `seg`, given the points at `lo`
/// (counted inside the current regime) and `hi`, searched in chunks of at most `chunk`.
pub fn locate<S: Segment>(
    seg: &S,
    start: (f64, Point),
    end: (f64, Point),
    direction: Direction,
    chunk: f64,
) -> Search<Point> {
    locate_with(seg, start, end, direction, chunk, &Budget::CAPPED)
}

/// [`locate`] with another capped budget ([`Budget::CAPPED_HERMITE`]: the stepper's
/// `SwitchStart::Hermite`).
pub fn locate_with<S: Segment>(
    seg: &S,
    (lo, start): (f64, Point),
    (hi, end): (f64, Point),
    direction: Direction,
    chunk: f64,
    budget: &Budget,
) -> Search<Point> {
    let f = Boundary::new(seg, direction);
    switch::locate(&f, lo, start, hi, Some(end), chunk, budget, None)
}
