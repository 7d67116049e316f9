//! The series kernels the generated recurrences call (`ts::…` in
//! `coefficients::contact_taylor` and its siblings): coefficient n of a product, a square, a
//! reciprocal, an integer power and a square root of truncated Taylor series, from the lower
//! coefficients (`docs/MODEL.md` §16). These are the rules of automatic differentiation of
//! Taylor series, not the model: the model enters only through the generated code.
//!
//! A series is a fixed array of [`CAPACITY`] coefficients; reads beyond it give 0 and writes
//! beyond it are dropped, so no index can panic (the method never asks for more than
//! [`MAX_ORDER`] + 1 coefficients).

use crate::coefficients::{STATION_TAYLOR_SERIES_MAX, TAYLOR_SERIES_MAX};

/// Coefficients stored per series: orders 0 ..= [`MAX_ORDER`] + 1.
pub const CAPACITY: usize = 24;

/// The highest order the method expands to (the events and the step use orders ≤ this; the
/// states get one more).
pub const MAX_ORDER: usize = CAPACITY - 2;

/// The orders of an expansion with N a constant in each (every convolution a loop of known
/// length), at most [`MAX_ORDER`] = 22: `orders!(p, |N| each, last)` runs `each` for
/// N = 1 .. `p` and `last` for N = `p`; `orders!(p, |N| call)` runs `call` for N = 1 ..= `p`.
macro_rules! orders {
    ($p:expr, |$n:ident| $each:expr, $last:expr) => {{
        orders!(@split $p, $n, $each, $last; 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22);
    }};
    ($p:expr, |$n:ident| $call:expr) => {{
        orders!(@all $p, $n, $call; 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22);
    }};
    (@split $p:expr, $n:ident, $each:expr, $last:expr; $($k:literal)+) => {
        $(
            if $k < $p {
                const $n: usize = $k;
                $each;
            } else if $k == $p {
                const $n: usize = $k;
                $last;
            }
        )+
    };
    (@all $p:expr, $n:ident, $call:expr; $($k:literal)+) => {
        $(
            if $k <= $p {
                const $n: usize = $k;
                $call;
            }
        )+
    };
}
pub(crate) use orders;

/// The coefficients of every series of a system, states first.
pub type Series = [[f64; CAPACITY]; TAYLOR_SERIES_MAX];

/// The series of a rub station's Taylor system (rotors from matrices, `crate::matrix`).
pub type StationSeries = [[f64; CAPACITY]; STATION_TAYLOR_SERIES_MAX];

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
//
// Their cost is latency, not arithmetic: coefficient N of one series needs coefficient N of the
// series before it, and the position's coefficient N comes from the acceleration's N − 2 (a
// chain through every operation of the field, once per two orders). So each sum is ordered by
// when its terms can be known: the terms of coefficients below N − 1 first (known before the
// order starts; in [`LANES`] partial sums, so that even they are ready early), then those with a
// coefficient N − 1, then those with coefficient N — of the operand computed earlier in the
// order (the lower series), and last of the later one. Only those last one or two products and
// additions are on the chain.

/// Independent partial sums the terms of old coefficients are split into: the terms j ≡ k (mod
/// [`LANES`]) are summed in accumulator k and the accumulators added pairwise at the end.
const LANES: usize = 4;

/// The pairwise total of the accumulators. They start at −0.0, the identity of addition, so
/// that an accumulator no term reaches drops out exactly.
#[inline(always)]
#[allow(clippy::indexing_slicing, reason = "constant indices below LANES = 4")]
fn total(acc: [f64; LANES]) -> f64 {
    (acc[0] + acc[2]) + (acc[1] + acc[3])
}

/// Σ_{j=FROM}^{N} a_j b_{N−j}: the terms with both coefficients below N − 1 (2 ≤ j ≤ N − 2) in
/// [`LANES`] partial sums, then j = 1 and j = N − 1, then a_N b_0, then a_0 b_N (`b` is the
/// operand computed later in the order).
#[inline(always)]
#[allow(
    clippy::indexing_slicing,
    reason = "j ≤ N < CAPACITY, asserted at compile time; the lane is below LANES"
)]
fn convolution<const N: usize, const FROM: usize>(a: &[f64; CAPACITY], b: &[f64; CAPACITY]) -> f64 {
    const { assert!(N < CAPACITY) };
    let mut acc = [-0.0; LANES];
    let mut j = if FROM > 2 { FROM } else { 2 };
    while j + 2 <= N {
        acc[j % LANES] += a[j] * b[N - j];
        j += 1;
    }
    let mut sum = total(acc);
    // Coefficient N − 1 (j = 1 and j = N − 1, one term when they coincide at N = 2).
    if FROM <= 1 && N >= 2 {
        sum += a[1] * b[N - 1];
    }
    if N >= 3 && N > FROM {
        sum += a[N - 1] * b[1];
    }
    // Coefficient N: of the earlier operand, then of the later one (one term at N = 0).
    if N >= FROM && N >= 1 {
        sum += a[N] * b[0];
    }
    if FROM == 0 {
        sum += a[0] * b[N];
    }
    sum
}

/// Coefficient N of a·b: Σ_{j=0}^{N} a_j b_{N−j}.
#[inline]
pub fn product<const N: usize>(a: &[f64; CAPACITY], b: &[f64; CAPACITY]) -> f64 {
    convolution::<N, 0>(a, b)
}

/// Σ_{j=FROM}^{N−FROM} a_j a_{N−j}: each pair once, doubled, and the middle term once — the
/// pairs and the middle of coefficients below N − 1 first (in [`LANES`] partial sums), then the
/// pair of a_{N−1} (the middle a_1² at N = 2), then the pair of a_N.
#[inline(always)]
#[allow(
    clippy::indexing_slicing,
    reason = "j ≤ N < CAPACITY, asserted at compile time; the lane is below LANES"
)]
fn symmetric<const N: usize, const FROM: usize>(a: &[f64; CAPACITY]) -> f64 {
    const { assert!(N < CAPACITY) };
    let mut acc = [-0.0; LANES];
    let mut j = if FROM > 2 { FROM } else { 2 };
    while 2 * j < N {
        acc[j % LANES] += a[j] * a[N - j];
        j += 1;
    }
    let mut sum = 2.0 * total(acc);
    if N.is_multiple_of(2) && N / 2 >= FROM && N >= 4 {
        sum += a[N / 2] * a[N / 2];
    }
    // Coefficient N − 1: the pair (1, N − 1), or the middle a_1² at N = 2.
    if FROM <= 1 && N == 2 {
        sum += a[1] * a[1];
    }
    if FROM <= 1 && N >= 3 {
        sum += (a[1] + a[1]) * a[N - 1];
    }
    // Coefficient N: the pair (0, N), or the middle a_0² at N = 0.
    if FROM == 0 && N == 0 {
        sum += a[0] * a[0];
    }
    if FROM == 0 && N >= 1 {
        sum += (a[0] + a[0]) * a[N];
    }
    sum
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

/// Coefficient N ≥ 1 of r = a^{k/2} (k = `halves`, a_0 > 0), r's lower coefficients given: from
/// a·r' = (k/2) a'·r, N a_0 r_N = Σ_{j=1}^{N} ((k/2 + 1) j − N) a_j r_{N−j}; the weights are
/// constants of the order (N and k are), the terms ordered as in the convolutions (a_N r_0,
/// the newest, last) and 1/(N a_0) off the chain.
#[inline]
#[allow(
    clippy::indexing_slicing,
    reason = "j ≤ N < CAPACITY, asserted at compile time; the lane is below LANES"
)]
pub fn half_power<const N: usize>(a: &[f64; CAPACITY], r: &[f64; CAPACITY], halves: i32) -> f64 {
    const { assert!(N < CAPACITY) };
    let (p1, nf) = (0.5 * f64::from(halves) + 1.0, N as f64);
    let weight = |j: usize| p1 * j as f64 - nf;
    let mut acc = [-0.0; LANES];
    let mut j = 2;
    while j + 2 <= N {
        acc[j % LANES] += weight(j) * a[j] * r[N - j];
        j += 1;
    }
    let mut sum = total(acc);
    if N >= 2 {
        sum += weight(1) * a[1] * r[N - 1];
    }
    if N >= 3 {
        sum += weight(N - 1) * a[N - 1] * r[1];
    }
    if N >= 1 {
        sum += weight(N) * r[0] * a[N];
    }
    sum * (1.0 / (nf * a[0]))
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
    // 0.5/r_0 depends on r_0 only: computed off the chain of the sum, not at its end.
    (a[N] - symmetric::<N, 1>(r)) * (0.5 / r[0])
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
    coefficients(c, degree)
        .iter()
        .rev()
        .fold(0.0, |acc, &ck| acc * s + ck)
}

/// The polynomials `c[m]` (each Σ_{k ≤ degree} c_k s^k) at `s`, by Horner in one pass: M
/// independent chains side by side.
#[inline]
pub fn evaluate_many<const M: usize>(c: [&[f64; CAPACITY]; M], degree: usize, s: f64) -> [f64; M] {
    let mut acc = [0.0; M];
    for k in (0..=degree.min(CAPACITY - 1)).rev() {
        for (a, series) in acc.iter_mut().zip(c) {
            *a = *a * s + series.get(k).copied().unwrap_or(0.0);
        }
    }
    acc
}

/// Coefficients 0 ..= `degree` of `c` (all of them beyond the capacity).
#[inline(always)]
fn coefficients(c: &[f64; CAPACITY], degree: usize) -> &[f64] {
    c.get(..=degree).unwrap_or(c)
}

/// The polynomial's value and derivative at `s`.
#[inline]
pub fn evaluate_with_derivative(c: &[f64; CAPACITY], degree: usize, s: f64) -> (f64, f64) {
    let mut p = 0.0;
    let mut d = 0.0;
    for &ck in coefficients(c, degree).iter().rev() {
        d = d * s + p;
        p = p * s + ck;
    }
    (p, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coefficients that make every term of a sum distinct (no two products equal).
    fn series(seed: f64) -> [f64; CAPACITY] {
        core::array::from_fn(|k| 1.0 + seed * (k as f64 + 1.0).sqrt() + 0.01 * (k * k) as f64)
    }

    fn naive(a: &[f64; CAPACITY], b: &[f64; CAPACITY], n: usize, from: usize) -> f64 {
        (from..=n).map(|j| a[j] * b[n - j]).sum()
    }

    fn close(got: f64, want: f64, n: usize, what: &str) {
        assert!(
            (got - want).abs() <= 1e-13 * want.abs().max(1.0),
            "{what} at order {n}: {got} vs {want}"
        );
    }

    macro_rules! every_order {
        ($($n:literal)+) => {$({
            const N: usize = $n;
            let (a, b) = (series(0.37), series(-0.21));
            close(product::<N>(&a, &b), naive(&a, &b, N, 0), N, "product");
            close(square::<N>(&a), naive(&a, &a, N, 0), N, "square");
            // 1/a and √a from their defining identities, the coefficients below N given.
            let mut r = [0.0; CAPACITY];
            r[0] = 1.0 / a[0];
            close(reciprocal::<N>(&a, &r) * a[0], -naive(&a, &r, N, 1), N, "reciprocal");
            let mut q = series(0.11);
            q[0] = a[0].sqrt();
            let sum: f64 = (1..N).map(|j| q[j] * q[N - j]).sum();
            close(sqrt::<N>(&a, &q) * 2.0 * q[0], a[N] - sum, N, "sqrt");
            // 1/√a: N a_0 r_N = Σ (j/2 − N) a_j r_{N−j}.
            let mut h = series(0.05);
            h[0] = 1.0 / a[0].sqrt();
            let want: f64 = (1..=N).map(|j| (0.5 * j as f64 - N as f64) * a[j] * h[N - j]).sum();
            close(half_power::<N>(&a, &h, -1) * N as f64 * a[0], want, N, "half power");
        })+};
    }

    /// Every term of every sum once, at every order the method uses (the terms are reordered
    /// by when their coefficients are known: none may be lost or doubled).
    #[test]
    fn the_kernels_sum_every_term_once() {
        every_order!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22);
    }
}
