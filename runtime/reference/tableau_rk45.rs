//! Coefficients of the Dormand–Prince 5(4) pair (Dormand & Prince, "A family of embedded
//! Runge–Kutta formulae", J. Comput. Appl. Math. 6, 1980; Hairer–Nørsett–Wanner, *Solving ODEs I*,
//! Table II.5.2) and Shampine's 4th-order continuous extension (Hairer–Nørsett–Wanner §II.6,
//! the dense output of `DOPRI5`).
//!
//! Stage 7 is evaluated at (t + h, y1) with the weights of the 5th-order solution, so it is the
//! first stage of the next step (FSAL).

// The published digits are kept as printed (30 significant digits); the compiler rounds
// them to the nearest f64.
#![allow(clippy::excessive_precision)]

/// Nodes c2..c6 (c1 = 0, c7 = 1).
pub const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];

/// Row 2 of A.
pub const A2: [f64; 1] = [1.0 / 5.0];
/// Row 3 of A.
pub const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
/// Row 4 of A.
pub const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
/// Row 5 of A.
pub const A5: [f64; 4] = [
    19372.0 / 6561.0,
    -25360.0 / 2187.0,
    64448.0 / 6561.0,
    -212.0 / 729.0,
];
/// Row 6 of A.
pub const A6: [f64; 5] = [
    9017.0 / 3168.0,
    -355.0 / 33.0,
    46732.0 / 5247.0,
    49.0 / 176.0,
    -5103.0 / 18656.0,
];
/// Weights of the 5th-order solution (= row 7 of A; b2 = b7 = 0).
pub const B: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];
/// Error weights E = b − b̂ (5th minus embedded 4th order), stages 1..7 (E2 = 0).
pub const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense-output coefficients d1..d7 of Shampine's continuous extension (d2 = 0).
pub const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];
