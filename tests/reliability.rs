//! Issue 32's silent wrong answers in the runtime, each fixed as a class and kept fixed here with
//! more than the example (`docs/MODEL.md` §10, §12, §9, §14):
//!
//! - `chatter`: zero-length switch pairs on the numerical methods' dense output (the double zero
//!   after `slip`, rounding zeros next to a segment's start), item 1.
//! - `stiff`: the analytic method's tolerance on stiff stators (item 2).
//! - `grazing`: touches within the methods' resolution (item 4).
//! - `restarts`: a run continued from a state it reached (a held speed's last sliver, a
//!   perturbed restart outside the start ranges).

mod reliability {
    pub mod chatter;
    pub mod common;
    pub mod grazing;
    pub mod restarts;
    pub mod stiff;
}
