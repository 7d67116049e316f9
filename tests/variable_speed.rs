//! Variable speed (issue 17, `docs/MODEL.md` §14): run-ups, coast-downs and speed profiles.
//! A profile that holds its speed reproduces the constant-speed run bit for bit; a slow ramp
//! follows the constant-speed response; the held steps of the analytic method and the stepper
//! converge to the full equations (DOP853 at tol 1e-13) at second order; the run-up and
//! coast-down jumps of the paper's rotor are found at the same speeds by every method; the
//! generated speed-change force is the unbalance's reaction, checked by finite differences.

mod variable_speed {
    pub mod accuracy;
    pub mod forcing;
    pub mod identity;
    pub mod jumps;
    pub mod profile;
    pub mod support;
}
