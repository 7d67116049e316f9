//! The first crossing of a switch polynomial inside a step (`docs/MODEL.md` §16): Descartes' rule
//! of signs on the Möbius-transformed polynomial isolates the real roots in (0, 1) by bisection
//! (Vincent–Collins–Akritas), left to right, so the earliest sign change is found however close
//! the roots lie; a safeguarded Newton iteration polishes it.
//!
//! The polynomial is a switch function in the step's scaled local time t = s/h, positive inside
//! the regime, computed with rounding of about 64 ulps of its scale (the band). A crossing is
//! where the function falls through −band — a dip that stays within the band is rounding, not a
//! switch — located at the root of the function itself just before that point. So a segment
//! starting on its own switch surface (after `enter`, `slip`, `reverse`, `roll`, or a touch),
//! where the value is 0 to rounding, finds the next real crossing however soon (a start exactly on
//! z = 1 loses no exit), leaves at once where the function falls away from the start, and does
//! not chatter where the function starts on a double zero (after `slip`: w = 0 and
//! w' = λ − μσN = 0 together).

use super::kernels::{self, CAPACITY};
use crate::math;
use crate::refine::{Knot, Refinement, refine};
use crate::rounding;

/// Rounding band of a switch function's start value, relative to its scale
/// ([`rounding::SOLUTION`]: a Taylor polynomial of the step carries ~64 ulps).
const START_BAND: f64 = rounding::SOLUTION;

/// Narrowest isolating interval examined (relative to the step): below it two roots are a
/// touch (no sign change) or one crossing ([`rounding::BRACKET`]).
const MIN_WIDTH: f64 = rounding::BRACKET;

/// Deepest bisection (2⁻⁵² of the step; the stack holds one pending interval per level).
const MAX_DEPTH: usize = 56;

/// A polynomial of degree < [`CAPACITY`] in t.
#[derive(Clone, Copy)]
struct Poly {
    c: [f64; CAPACITY],
    degree: usize,
}

impl Poly {
    fn eval(&self, t: f64) -> f64 {
        kernels::evaluate(&self.c, self.degree, t)
    }

    fn eval_with_derivative(&self, t: f64) -> (f64, f64) {
        kernels::evaluate_with_derivative(&self.c, self.degree, t)
    }

    /// Sign variations of (1 + x)^d P(a + (b − a)/(1 + x)): Descartes' bound on the number of
    /// roots in (a, b) (exact when 0 or 1).
    fn variations(&self, a: f64, b: f64) -> usize {
        let d = self.degree.min(CAPACITY - 1);
        // P(a + w t): Taylor shift by a, then scale by w.
        let mut q = self.c;
        shift(&mut q, d, a);
        let w = b - a;
        let mut scale = 1.0;
        for ck in q.get_mut(..=d).unwrap_or(&mut []) {
            *ck *= scale;
            scale *= w;
        }
        // Reverse, then shift by 1.
        let mut r = [0.0; CAPACITY];
        if let (Some(to), Some(from)) = (r.get_mut(..=d), q.get(..=d)) {
            for (rk, &qk) in to.iter_mut().zip(from.iter().rev()) {
                *rk = qk;
            }
        }
        shift(&mut r, d, 1.0);
        let mut count = 0;
        let mut last = 0.0;
        for &rk in r.get(..=d).unwrap_or(&[]) {
            if rk != 0.0 {
                if last != 0.0 && (rk < 0.0) != (last < 0.0) {
                    count += 1;
                }
                last = rk;
            }
        }
        count
    }
}

/// Taylor shift in place: the coefficients of p(t + a) (degree `d`), by d passes of synthetic
/// division (each pass carries the coefficient above, already updated, down the array).
fn shift(c: &mut [f64; CAPACITY], d: usize, a: f64) {
    if a == 0.0 {
        return;
    }
    let d = d.min(CAPACITY - 1);
    let top = c.get(d).copied().unwrap_or(0.0);
    for i in 0..d {
        let mut above = top;
        for ck in c.get_mut(i..d).unwrap_or(&mut []).iter_mut().rev() {
            *ck += a * above;
            above = *ck;
        }
    }
}

/// A crossing of a switch polynomial: where the function reaches 0 and where it has fallen
/// through the rounding band below it (local times, `at` ≤ `past`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The root: the last point before `past` where the function is ≥ 0.
    pub at: f64,
    /// Where the function falls through −band: the side the motion takes is resolved there.
    pub past: f64,
}

/// The first local time s ∈ [0, h] where the polynomial `sign`·Σ c_k s^k (degree `degree`)
/// leaves the regime, or `None` when it stays above −band over the step.
///
/// `scale` is the size of the terms the function's value is computed from (1 for z² − 1); the
/// band is 64 ulps of it (or of the polynomial's variation over the step, if larger). At a
/// segment's start (`segment_start`) a start value below the band counts as inside (the
/// segment starts on its switch surface, as the other methods' offsets make it); later it is a
/// crossing missed to rounding at the end of the previous step, reported at once.
///
/// Most steps end at the exclusion test, one pass over the coefficients without a copy; only a
/// step it cannot clear builds the polynomial in t = s/h and isolates its first crossing. The
/// root is polished to the last bits when `precise`; else it is a point where the function is
/// still ≥ 0 within a few rounding bands of it (for a caller that refines it on other
/// polynomials anyway: the exit through z = 1 on the step's state).
pub fn first_exit(
    c: &[f64; CAPACITY],
    sign: f64,
    degree: usize,
    h: f64,
    scale: f64,
    segment_start: bool,
    precise: bool,
) -> Option<Crossing> {
    let degree = degree.min(CAPACITY - 1);
    // The coefficients in t: their size and the sum of the negative ones above order 0 (only
    // those can pull the polynomial down for t ∈ [0, 1]).
    let coefficients = c.get(..=degree).unwrap_or(c);
    let start = coefficients.first().map_or(0.0, |&c0| c0 * sign);
    // Σ|v| and Σv over the coefficients above order 0: the negative ones sum to half their
    // difference (no branch and no comparison per coefficient).
    let (mut magnitude, mut signed) = (0.0, 0.0);
    let mut power = sign;
    for &ck in coefficients.get(1..).unwrap_or(&[]) {
        power *= h;
        let v = ck * power;
        magnitude += math::abs(v);
        signed += v;
    }
    let size = math::abs(start) + magnitude;
    let falls = 0.5 * (magnitude - signed);
    let mut start = start;
    if size == 0.0 || !size.is_finite() {
        return None;
    }
    let band = START_BAND * size.max(scale);
    if start < -band {
        if !segment_start {
            return Some(Crossing { at: 0.0, past: 0.0 });
        }
        // The segment's start is inside by definition: measure from it.
        start = 0.0;
    }
    // Exclusion: p + band stays positive on [0, 1] when its value at 0 exceeds what the
    // negative coefficients can take away.
    if start + band > falls {
        return None;
    }
    let mut p = Poly {
        c: [0.0; CAPACITY],
        degree,
    };
    let mut power = sign;
    for (pk, &ck) in p.c.iter_mut().zip(c.iter()).take(degree + 1) {
        *pk = ck * power;
        power *= h;
    }
    if let Some(c0) = p.c.first_mut() {
        *c0 = start;
    }
    // Where the function falls through −band: the first root of p + band.
    let mut lowered = p;
    if let Some(c0) = lowered.c.first_mut() {
        *c0 += band;
    }
    let (a, b) = isolate(&lowered)?;
    // Past the fall to within half a band: all that is asked of it is p < 0 there.
    let below = polish(&lowered, a, b, 0.5 * band);
    Some(Crossing {
        at: h * crossing_before(&p, below, band, precise),
        past: h * below,
    })
}

/// The root of `p` just before `below`, where p = −band: the last point where p ≥ 0, searched
/// back from `below` in widening brackets (the function falls through the band there, so its
/// root lies about band/|p'| earlier), then polished; 0 when p is negative back to the start.
fn crossing_before(p: &Poly, below: f64, band: f64, precise: bool) -> f64 {
    let (_, slope) = p.eval_with_derivative(below);
    let mut width = if slope < 0.0 {
        2.0 * band / -slope
    } else {
        f64::EPSILON
    };
    loop {
        let a = below - width;
        if a <= 0.0 {
            return if p.eval(0.0) >= 0.0 && precise {
                polish(p, 0.0, below, 0.0)
            } else {
                0.0
            };
        }
        if p.eval(a) >= 0.0 {
            return if precise { polish(p, a, below, 0.0) } else { a };
        }
        width *= 4.0;
    }
}

/// The leftmost interval [a, b] ⊂ [0, 1] over which the polynomial changes sign from > 0 to ≤ 0.
fn isolate(p: &Poly) -> Option<(f64, f64)> {
    let mut stack = [(0.0, 0.0); MAX_DEPTH + 1];
    let mut len = 0;
    if let Some(slot) = stack.get_mut(0) {
        *slot = (0.0, 1.0);
        len = 1;
    }
    while len > 0 {
        len -= 1;
        let (a, b) = stack.get(len).copied().unwrap_or((0.0, 0.0));
        let ((fa, dfa), fb) = (p.eval_with_derivative(a), p.eval(b));
        // Everything left of a was root-free and positive: the crossing is at a when the
        // polynomial is negative there (a root missed to rounding) or falls through 0 there (a
        // simple root on the split point; a touch there has no slope and is not a crossing).
        if a > 0.0 && (fa < 0.0 || (fa == 0.0 && dfa < 0.0)) {
            return Some((a, a));
        }
        let v = p.variations(a, b);
        if v == 0 {
            continue;
        }
        if v == 1 || b - a <= MIN_WIDTH {
            if fb <= 0.0 {
                return Some((a, b));
            }
            // No sign change: a touch (two roots), or one root at b to rounding (the next
            // interval starts there and sees it).
            continue;
        }
        let mid = 0.5 * (a + b);
        // Push the right half, then the left (examined first).
        if len + 2 > stack.len() {
            // Deeper than the stack: a cluster narrower than 2⁻⁵⁶ of the step; decide by sign.
            if fb <= 0.0 {
                return Some((a, b));
            }
            continue;
        }
        if let Some(slot) = stack.get_mut(len) {
            *slot = (mid, b);
        }
        if let Some(slot) = stack.get_mut(len + 1) {
            *slot = (a, mid);
        }
        len += 2;
    }
    None
}

/// The root in [a, b] (p(a) > 0 ≥ p(b)): the one refinement ([`crate::refine`]) on −p with
/// Newton steps on the polynomial. With `residual` 0, to full precision: the first point at or
/// past the crossing; else the first point seen where |p| ≤ `residual`.
fn polish(p: &Poly, a: f64, b: f64, residual: f64) -> f64 {
    if a == b {
        return a;
    }
    let knot = |t: f64| {
        let (f, df) = p.eval_with_derivative(t);
        Knot {
            s: t,
            g: -f,
            dg: -df,
            point: (),
        }
    };
    let (below, above) = (knot(a), knot(b));
    if above.g <= 0.0 {
        // p(b) = 0: b is the root.
        return b;
    }
    let settings = Refinement {
        max_steps: 100,
        residual,
        scale: 0.0,
        first_guess: (residual == 0.0).then_some(0.5 * (a + b)),
        close: residual == 0.0,
    };
    let found = refine(knot, below, above, &settings);
    if residual == 0.0 {
        found.at_or_past().s
    } else {
        found.best.s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(roots: &[f64], lead: f64) -> [f64; CAPACITY] {
        let mut c = [0.0; CAPACITY];
        c[0] = lead;
        for (d, &r) in roots.iter().enumerate() {
            for k in (0..=d + 1).rev() {
                let lower = if k > 0 { c[k - 1] } else { 0.0 };
                c[k] = lower - r * c[k];
            }
        }
        c
    }

    #[test]
    fn finds_the_first_of_close_roots() {
        // (t − 0.3)(t − 0.3 − 1e-5)(t − 0.8), negative leading sign so that p(0) > 0: the first
        // root to the conditioning of a root pair 1e-5 apart (rounding / |p'| ≈ 1e-11).
        let c = poly(&[0.3, 0.3 + 1e-5, 0.8], -1.0);
        let t = first_exit(&c, 1.0, 3, 1.0, 1.0, false, true).map(|c| c.at);
        assert!(t.is_some_and(|t| (t - 0.3).abs() < 1e-10), "{t:?}");
        // 1e-7 apart: the dip between them (−1e-15) is below the band (64 ulps): a touch at
        // rounding level, not a switch; the next crossing is 0.8.
        let c = poly(&[0.3, 0.3 + 1e-7, 0.8], -1.0);
        let t = first_exit(&c, 1.0, 3, 1.0, 1.0, false, true).map(|c| c.at);
        assert!(t.is_some_and(|t| (t - 0.8).abs() < 1e-12), "{t:?}");
        // 1e-6 apart: a dip of −1.3e-13, a real excursion, found at its first root.
        let c = poly(&[0.3, 0.3 + 1e-6, 0.8], -1.0);
        let t = first_exit(&c, 1.0, 3, 1.0, 1.0, false, true).map(|c| c.at);
        assert!(t.is_some_and(|t| (t - 0.3).abs() < 1e-9), "{t:?}");
    }

    #[test]
    fn a_start_on_the_surface_finds_the_next_crossing() {
        // t (t − 1e-10)·(−1): zero at the start, positive until 1e-10, then negative.
        let c = poly(&[0.0, 1e-10], -1.0);
        let t = first_exit(&c, 1.0, 2, 1.0, 1.0, false, true).unwrap().at;
        assert!((t - 1e-10).abs() < 1e-24, "{t}");
        // Leaving at once: −t (t + 1), found within rounding of the start.
        let c = poly(&[0.0, -1.0], -1.0);
        let t = first_exit(&c, 1.0, 2, 1.0, 1.0, false, true).map(|c| c.at);
        assert!(t.is_some_and(|t| t < 1e-13), "{t:?}");
        // A double zero at the start that only dips by rounding: t² − 1e-18 t (after `slip`).
        let mut c = [0.0; CAPACITY];
        c[1] = -1e-18;
        c[2] = 1.0;
        assert_eq!(first_exit(&c, 1.0, 2, 1.0, 1.0, true, true), None);
    }

    #[test]
    fn a_touch_is_not_a_crossing() {
        // (t − 0.5)² ≥ 0.
        let c = poly(&[0.5, 0.5], 1.0);
        assert_eq!(first_exit(&c, 1.0, 2, 1.0, 1.0, false, true), None);
        // Positive throughout: −(t − 1.5)(t + 0.5).
        let c = poly(&[1.5, -0.5], -1.0);
        assert_eq!(first_exit(&c, 1.0, 2, 1.0, 1.0, false, true), None);
    }

    #[test]
    fn scales_to_the_step() {
        // 1 − s/0.25 on a step of 0.5: exit at s = 0.25.
        let mut c = [0.0; CAPACITY];
        c[0] = 1.0;
        c[1] = -4.0;
        let s = first_exit(&c, 1.0, 1, 0.5, 1.0, false, true).unwrap().at;
        assert!((s - 0.25).abs() < 1e-16);
    }
}
