//! Interpolation between keys in time, for keyed camera paths and keyed motion.
//!
//! The smooth form is a Catmull–Rom spline whose knots are the keys' times: cubic Hermite
//! segments through every key, where the tangent at key i is the slope of the parabola
//! through keys i-1, i and i+1,
//!
//! m_i = ((p_i - p_{i-1}) / (t_i - t_{i-1}) · (t_{i+1} - t_i) + (p_{i+1} - p_i) / (t_{i+1} - t_i)
//! · (t_i - t_{i-1})) / (t_{i+1} - t_{i-1}),
//!
//! (the Barry–Goldman pyramid with the times as knots evaluates to exactly this). Position and
//! velocity are continuous in time (C1), so a fly-through has no kinks and no jumps in speed
//! at the keys. An open sequence takes one-sided slopes at its two ends and holds its first
//! and last values outside them; a cyclic one wraps time into one period and takes its
//! neighbours across the wrap, so it is C1 there too.
//!
//! The linear form joins the keys by straight segments, for values that must not overshoot.

use glam::DVec3;

/// How a key sequence continues outside its keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Ends {
    /// Holds the first value before the first key and the last after the last.
    Open,
    /// Repeats with this period: the keys are one lap, each key's value comes back a period
    /// later, and the segment after the last key runs to the first key's next lap.
    Cyclic(f64),
}

/// How values are joined between keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Curve {
    /// The C1 Catmull–Rom spline of the module documentation.
    Smooth,
    /// Straight segments.
    Linear,
}

/// The value at time `t` of the keys `(t_i, value_i)` (times strictly increasing; for
/// [`Ends::Cyclic`] all within one period of the first). No keys gives zero.
pub(crate) fn interpolate(keys: &[(f64, DVec3)], ends: Ends, curve: Curve, t: f64) -> DVec3 {
    let Some(&(first, first_value)) = keys.first() else {
        return DVec3::ZERO;
    };
    let n = keys.len();
    // Key i of the sequence extended past both ends (cyclic: by the neighbouring laps).
    let key = |i: isize| -> (f64, DVec3) {
        match ends {
            Ends::Cyclic(period) => {
                let lap = i.div_euclid(n as isize);
                let (ti, vi) = keys[i.rem_euclid(n as isize) as usize];
                (ti + lap as f64 * period, vi)
            }
            Ends::Open => keys[i.clamp(0, n as isize - 1) as usize],
        }
    };
    let t = match ends {
        Ends::Cyclic(period) if period > 0.0 => first + (t - first).rem_euclid(period),
        Ends::Cyclic(_) => first,
        Ends::Open => {
            let last = keys[n - 1].0;
            if t <= first || n == 1 {
                return first_value;
            }
            if t >= last {
                return keys[n - 1].1;
            }
            t
        }
    };
    if n == 1 {
        return first_value;
    }
    // The segment [key i, key i + 1] holding t.
    let i = keys.partition_point(|&(ti, _)| ti <= t).max(1) as isize - 1;
    let (t0, p0) = key(i);
    let (t1, p1) = key(i + 1);
    let h = t1 - t0;
    let s = ((t - t0) / h).clamp(0.0, 1.0);
    match curve {
        Curve::Linear => p0 + (p1 - p0) * s,
        Curve::Smooth => {
            let tangent = |j: isize| -> DVec3 {
                let (ta, pa) = key(j - 1);
                let (tb, pb) = key(j);
                let (tc, pc) = key(j + 1);
                let open_end = ends == Ends::Open;
                if open_end && j == 0 {
                    (pc - pb) / (tc - tb)
                } else if open_end && j == n as isize - 1 {
                    (pb - pa) / (tb - ta)
                } else {
                    ((pb - pa) / (tb - ta) * (tc - tb) + (pc - pb) / (tc - tb) * (tb - ta))
                        / (tc - ta)
                }
            };
            let (m0, m1) = (tangent(i), tangent(i + 1));
            let (s2, s3) = (s * s, s * s * s);
            p0 * (2.0 * s3 - 3.0 * s2 + 1.0)
                + m0 * (h * (s3 - 2.0 * s2 + s))
                + p1 * (3.0 * s2 - 2.0 * s3)
                + m1 * (h * (s3 - s2))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn k(t: f64, x: f64, y: f64) -> (f64, DVec3) {
        (t, DVec3::new(x, y, 0.0))
    }

    fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
        (a - b).length() <= tol
    }

    #[test]
    fn passes_through_keys_and_holds_outside() {
        let keys = [k(0.0, 0.0, 0.0), k(1.0, 2.0, 1.0), k(3.0, 2.0, 5.0)];
        for curve in [Curve::Smooth, Curve::Linear] {
            for &(t, v) in &keys {
                assert!(close(interpolate(&keys, Ends::Open, curve, t), v, 1e-12));
            }
            assert_eq!(interpolate(&keys, Ends::Open, curve, -1.0), keys[0].1);
            assert_eq!(interpolate(&keys, Ends::Open, curve, 9.0), keys[2].1);
        }
        assert!(close(
            interpolate(&keys, Ends::Open, Curve::Linear, 2.0),
            DVec3::new(2.0, 3.0, 0.0),
            1e-12
        ));
    }

    #[test]
    fn smooth_curve_is_c1_at_keys() {
        // Uneven key spacing: velocity must still be continuous in time.
        let keys = [
            k(0.0, 0.0, 0.0),
            k(0.5, 1.0, 2.0),
            k(2.0, 3.0, -1.0),
            k(2.3, 4.0, 0.0),
            k(4.0, 0.0, 1.0),
        ];
        for ends in [Ends::Open, Ends::Cyclic(5.0)] {
            let at = |t| interpolate(&keys, ends, Curve::Smooth, t);
            for &(t, _) in &keys[1..4] {
                let h = 1e-6;
                let before = (at(t) - at(t - h)) / h;
                let after = (at(t + h) - at(t)) / h;
                assert!(
                    close(before, after, 1e-3),
                    "{ends:?} t={t}: {before} vs {after}"
                );
            }
        }
    }

    #[test]
    fn cyclic_wraps_and_closes_smoothly() {
        let keys = [k(0.0, 0.0, 0.0), k(1.0, 1.0, 0.0), k(2.0, 1.0, 1.0)];
        let ends = Ends::Cyclic(3.0);
        let at = |t| interpolate(&keys, ends, Curve::Smooth, t);
        assert!(
            close(at(3.0), keys[0].1, 1e-12),
            "a period later: the first key"
        );
        assert!(close(at(4.0), keys[1].1, 1e-12));
        assert!(close(at(-2.0), keys[1].1, 1e-12));
        let h = 1e-6;
        let before = (at(3.0) - at(3.0 - h)) / h;
        let after = (at(3.0 + h) - at(3.0)) / h;
        assert!(close(before, after, 1e-3), "{before} vs {after}");
        // The closing segment runs from the last key back to the first.
        let mid = at(2.5);
        assert!(mid.x > 0.0 && mid.x < 1.2 && mid.y > 0.0, "{mid}");
    }

    #[test]
    fn one_key_is_constant() {
        let keys = [k(2.0, 7.0, 1.0)];
        for ends in [Ends::Open, Ends::Cyclic(4.0)] {
            assert_eq!(
                interpolate(&keys, ends, Curve::Smooth, 0.3),
                DVec3::new(7.0, 1.0, 0.0)
            );
        }
        assert_eq!(
            interpolate(&[], Ends::Open, Curve::Smooth, 0.3),
            DVec3::ZERO
        );
    }
}
