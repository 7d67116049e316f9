//! The certificate that an interval holds no crossing: g ≤ min(Ua, Ub) with the two parabolas
//! of the kernel's module docs (`docs/MODEL.md` §12), its maximum at an end or where they meet.

use crate::math;

/// Whether g provably stays ≤ `slack` on [0, len], from its values and slopes at both ends and
/// a bound `m2` ≥ |g''| on the interval: g ≤ min(Ua, Ub) (module docs), and with t* where
/// Ua = Ub (Ua − Ub = c0 + c1 t, c1 ≥ 0 for a valid bound) the maximum of that minimum is
/// max(ga, gb, Ua(t*)) when t* ∈ [0, len], else that of the lower parabola at the ends. False
/// when the bound does not prove it (NaN included).
#[inline]
pub fn no_crossing(ga: f64, dga: f64, gb: f64, dgb: f64, m2: f64, len: f64, slack: f64) -> bool {
    // (0 ≤ m2 < ∞ rather than `is_finite`: the same test, two comparisons.)
    if !(ga <= slack && gb <= slack && (0.0..f64::INFINITY).contains(&m2)) {
        return false;
    }
    let c1 = dga - dgb + m2 * len;
    let c0 = ga - gb + dgb * len - 0.5 * m2 * len * len;
    let meet = if c1 > 0.0 {
        // `clamp` without its assertion (len ≥ 0 here; NaN passes through as with `clamp`).
        let t = -c0 / c1;
        let t = if t < 0.0 {
            0.0
        } else if t > len {
            len
        } else {
            t
        };
        ga + dga * t + 0.5 * m2 * t * t
    } else if c1 == 0.0 {
        ga.max(gb)
    } else {
        return false;
    };
    meet <= slack
}

/// [`no_crossing`] with a quick accept first, for callers whose test nearly always succeeds
/// (the stepper's free step). Ua is convex, so on [0, len] Ua(t) ≤ max(ga, Ua(len)); with room
/// for the rounding of the general evaluation (≤ 6 ulps of the terms' size; 16 taken) a bound
/// under `slack` means that evaluation answers true as well. The same decision, so the same
/// steps, without the division. Where the outcome is close to a coin toss (the interval
/// search's splits) the extra branch costs more in mispredictions than the division it saves
/// (`BENCHMARKS.md`, the ninth speed fix).
#[inline]
pub fn no_crossing_likely(
    ga: f64,
    dga: f64,
    gb: f64,
    dgb: f64,
    m2: f64,
    len: f64,
    slack: f64,
) -> bool {
    if ga <= slack && gb <= slack && (0.0..f64::INFINITY).contains(&m2) {
        let c1 = dga - dgb + m2 * len;
        if c1 > 0.0 {
            let quad = 0.5 * m2 * len * len;
            let end = ga + dga * len + quad;
            let size = math::abs(ga) + math::abs(dga * len) + quad;
            if ga.max(end) + 16.0 * f64::EPSILON * size <= slack {
                return true;
            }
        }
    }
    no_crossing(ga, dga, gb, dgb, m2, len, slack)
}

#[cfg(test)]
mod tests {
    use super::super::TOUCH;
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The quick accept never decides otherwise than the full evaluation: the same steps
        /// whichever a caller uses. Values on a coarse grid of binary fractions put many cases
        /// on or next to the decision boundary, where the rounding room matters.
        #[test]
        fn the_quick_accept_decides_as_the_full_test(
            ga in -64i32..=1, dga in -64i32..=64, gb in -64i32..=1, dgb in -64i32..=64,
            m2 in 0i32..=64, len in 1i32..=16, slack in prop::sample::select(&[0.0, TOUCH][..]),
            scale in prop::sample::select(&[1.0, 1e-3, 1e-8, 1e-15][..]),
        ) {
            let (ga, dga, gb, dgb) = (
                f64::from(ga) * scale / 64.0,
                f64::from(dga) / 16.0,
                f64::from(gb) * scale / 64.0,
                f64::from(dgb) / 16.0,
            );
            let (m2, len) = (f64::from(m2) / 4.0, f64::from(len) / 16.0);
            prop_assert_eq!(
                no_crossing_likely(ga, dga, gb, dgb, m2, len, slack),
                no_crossing(ga, dga, gb, dgb, m2, len, slack)
            );
        }

        /// Real-valued inputs: the same.
        #[test]
        fn the_quick_accept_agrees_on_random_values(
            ga in -1.0f64..1e-15, dga in -10.0f64..10.0, gb in -1.0f64..1e-15,
            dgb in -10.0f64..10.0, m2 in 0.0f64..100.0, len in 1e-6f64..1.0,
        ) {
            prop_assert_eq!(
                no_crossing_likely(ga, dga, gb, dgb, m2, len, TOUCH),
                no_crossing(ga, dga, gb, dgb, m2, len, TOUCH)
            );
        }
    }

    /// A parabola that stays below 0 is proved free by both; one that rises above is not.
    #[test]
    fn a_plain_case_each_way() {
        // g = −1 + t² on [0, 0.5] (g'' = 2): at most −0.75.
        assert!(no_crossing(-1.0, 0.0, -0.75, 1.0, 2.0, 0.5, 0.0));
        assert!(no_crossing_likely(-1.0, 0.0, -0.75, 1.0, 2.0, 0.5, 0.0));
        // g = −1 + 4t on [0, 0.5] reaches 1: not provable.
        assert!(!no_crossing(-1.0, 4.0, 1.0, 4.0, 0.0, 0.5, 0.0));
        assert!(!no_crossing_likely(-1.0, 4.0, 1.0, 4.0, 0.0, 0.5, 0.0));
    }
}
