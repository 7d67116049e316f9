//! The series kernels the generated recurrences call (`ts::…` in
//! `coefficients::contact_taylor` and its siblings): coefficient n of a product, a square, a
//! reciprocal, an integer power and a square root of truncated Taylor series, from the lower
//! coefficients (`docs/MODEL.md` §16). These are the rules of automatic differentiation of
//! Taylor series, not the model: the model enters only through the generated code.
//!
//! A series is a fixed array of [`CAPACITY`] coefficients; reads beyond it give 0 and writes
//! beyond it are dropped, so no index can panic (the method never asks for more than
//! [`MAX_ORDER`] + 1 coefficients).

use crate::coefficients::TAYLOR_SERIES_MAX;

/// Coefficients stored per series: orders 0 ..= [`MAX_ORDER`] + 1.
pub const CAPACITY: usize = 24;

/// The highest order the method expands to (the events and the step use orders ≤ this; the
/// states get one more).
pub const MAX_ORDER: usize = CAPACITY - 2;

/// The coefficients of every series of a system, states first.
pub type Series = [[f64; CAPACITY]; TAYLOR_SERIES_MAX];

/// Coefficient `n` of `a` (0 beyond the capacity).
#[inline(always)]
pub fn at(a: &[f64; CAPACITY], n: usize) -> f64 {
    a.get(n).copied().unwrap_or(0.0)
}

/// Set coefficient `n` of `a` (dropped beyond the capacity).
#[inline(always)]
pub fn set(a: &mut [f64; CAPACITY], n: usize, v: f64) {
    if let Some(c) = a.get_mut(n) {
        *c = v;
    }
}

// The kernels below index with j ≤ N only; `N < CAPACITY` is asserted at compile time in each
// (a const block: a larger N does not build), so every index is in bounds and no index can
// panic. Plain indexing over constant ranges lets the compiler unroll each convolution fully.

/// Σ_{j=FROM}^{N} a_j b_{N−j}.
#[inline(always)]
#[allow(
    clippy::indexing_slicing,
    reason = "j ≤ N < CAPACITY, asserted at compile time"
)]
fn convolution<const N: usize, const FROM: usize>(a: &[f64; CAPACITY], b: &[f64; CAPACITY]) -> f64 {
    const { assert!(N < CAPACITY) };
    let mut acc = 0.0;
    let mut j = FROM;
    while j <= N {
        acc += a[j] * b[N - j];
        j += 1;
    }
    acc
}

/// Coefficient N of a·b: Σ_{j=0}^{N} a_j b_{N−j}.
#[inline]
pub fn product<const N: usize>(a: &[f64; CAPACITY], b: &[f64; CAPACITY]) -> f64 {
    convolution::<N, 0>(a, b)
}

/// Σ_{j=FROM}^{N−FROM} a_j a_{N−j}: each pair once, doubled, and the middle term once.
#[inline(always)]
#[allow(
    clippy::indexing_slicing,
    reason = "j ≤ N < CAPACITY, asserted at compile time"
)]
fn symmetric<const N: usize, const FROM: usize>(a: &[f64; CAPACITY]) -> f64 {
    const { assert!(N < CAPACITY) };
    let mut acc = 0.0;
    let mut j = FROM;
    while 2 * j < N {
        acc += a[j] * a[N - j];
        j += 1;
    }
    acc *= 2.0;
    if N.is_multiple_of(2) && N / 2 >= FROM {
        acc += a[N / 2] * a[N / 2];
    }
    acc
}

/// Coefficient N of a²: 2 Σ_{j<N−j} a_j a_{N−j} (+ a_{N/2}² for even N).
#[inline]
pub fn square<const N: usize>(a: &[f64; CAPACITY]) -> f64 {
    symmetric::<N, 0>(a)
}

/// Coefficient N ≥ 1 of r = 1/a, r's lower coefficients given: r_N = −(Σ_{j=1}^{N} a_j r_{N−j}) / a_0,
/// with 1/a_0 = r_0 (a multiplication instead of a division per order).
#[inline]
pub fn reciprocal<const N: usize>(a: &[f64; CAPACITY], r: &[f64; CAPACITY]) -> f64 {
    -convolution::<N, 1>(a, r) * r[0]
}

/// 1/(N + 1), a constant of the order (a state's coefficient N + 1 is its rate's N over N + 1).
#[inline(always)]
pub const fn inverse<const N: usize>() -> f64 {
    1.0 / (N as f64 + 1.0)
}

/// Coefficient N ≥ 1 of r = a^p (a_0 ≠ 0), r's lower coefficients given: from a·r' = p a'·r,
/// N a_0 r_N = Σ_{j=1}^{N} ((p + 1) j − N) a_j r_{N−j}.
#[inline]
#[allow(
    clippy::indexing_slicing,
    reason = "j ≤ N < CAPACITY, asserted at compile time"
)]
pub fn power<const N: usize>(a: &[f64; CAPACITY], r: &[f64; CAPACITY], p: i32) -> f64 {
    const { assert!(N < CAPACITY) };
    let (p1, nf) = (f64::from(p) + 1.0, N as f64);
    let mut acc = 0.0;
    let mut j = 1;
    while j <= N {
        acc += (p1 * j as f64 - nf) * a[j] * r[N - j];
        j += 1;
    }
    acc / (nf * a[0])
}

/// Coefficient N ≥ 1 of r = √a (a_0 > 0), r's lower coefficients given:
/// r_N = (a_N − Σ_{j=1}^{N−1} r_j r_{N−j}) / (2 r_0).
#[inline]
#[allow(
    clippy::indexing_slicing,
    reason = "N < CAPACITY, asserted at compile time"
)]
pub fn sqrt<const N: usize>(a: &[f64; CAPACITY], r: &[f64; CAPACITY]) -> f64 {
    const { assert!(N < CAPACITY) };
    (a[N] - symmetric::<N, 1>(r)) / (2.0 * r[0])
}

/// x^p for an integer p (order 0 of a power).
#[inline]
pub fn powi(x: f64, p: i32) -> f64 {
    let mut acc = 1.0;
    for _ in 0..p.unsigned_abs() {
        acc *= x;
    }
    if p < 0 { 1.0 / acc } else { acc }
}

/// The polynomial Σ_{k ≤ degree} c_k s^k at `s` (Horner).
#[inline]
pub fn evaluate(c: &[f64; CAPACITY], degree: usize, s: f64) -> f64 {
    c.iter()
        .take(degree + 1)
        .rev()
        .fold(0.0, |acc, &ck| acc * s + ck)
}

/// The polynomial's value and derivative at `s`.
#[inline]
pub fn evaluate_with_derivative(c: &[f64; CAPACITY], degree: usize, s: f64) -> (f64, f64) {
    let mut p = 0.0;
    let mut d = 0.0;
    for &ck in c.iter().take(degree + 1).rev() {
        d = d * s + p;
        p = p * s + ck;
    }
    (p, d)
}
