//! Rainflow counting of a stress history, ASTM E1049-85 (reapproved 2017), §5.4.4.
//!
//! The history is reduced to its reversals (peaks and valleys, the first and last points kept),
//! then counted by the standard's three-point method:
//!
//! 1. read the next reversal; with fewer than three points on the stack, read again;
//! 2. X = the range of the two newest points, Y = the range of the two before it;
//! 3. X < Y: read again;
//! 4. Y holds the starting point S (the oldest point): count Y as a half cycle, drop S (the
//!    next point becomes S), go to 2;
//! 5. otherwise count Y as one cycle, drop both its points, go to 2.
//!
//! At the end every range left on the stack (the residue) is a half cycle. The count is exact:
//! no binning, each cycle keeps its range and mean.

/// One counted cycle or half cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    /// Range, max − min, in the history's unit.
    pub range: f64,
    /// Mean, (max + min) / 2.
    pub mean: f64,
    /// 1 for a full cycle, 0.5 for a half.
    pub count: f64,
}

impl Cycle {
    fn between(a: f64, b: f64, count: f64) -> Self {
        Cycle { range: (a - b).abs(), mean: 0.5 * (a + b), count }
    }
}

/// The reversals of `history`: its first point, every strict peak and valley (a plateau counts
/// once), and its last point. Non-finite points are the caller's to keep out.
pub fn reversals(history: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for &x in history {
        match out.len() {
            0 => out.push(x),
            1 => {
                if x != out[0] {
                    out.push(x);
                }
            }
            n => {
                let (a, b) = (out[n - 2], out[n - 1]);
                if x == b {
                    continue;
                }
                // b is a reversal when the history turns there; otherwise x extends the ramp.
                if (b - a) * (x - b) > 0.0 {
                    out[n - 1] = x;
                } else {
                    out.push(x);
                }
            }
        }
    }
    out
}

/// Rainflow cycles of `history` by ASTM E1049-85's three-point method, the residue counted as
/// half cycles, in the order they are counted.
pub fn count(history: &[f64]) -> Vec<Cycle> {
    let mut cycles = Vec::new();
    let mut stack: Vec<f64> = Vec::new();
    for point in reversals(history) {
        stack.push(point);
        while stack.len() >= 3 {
            let n = stack.len();
            let x = (stack[n - 1] - stack[n - 2]).abs();
            let y = (stack[n - 2] - stack[n - 3]).abs();
            if x < y {
                break;
            }
            if n == 3 {
                cycles.push(Cycle::between(stack[0], stack[1], 0.5));
                stack.remove(0);
            } else {
                cycles.push(Cycle::between(stack[n - 3], stack[n - 2], 1.0));
                stack.drain(n - 3..n - 1);
            }
        }
    }
    cycles.extend(stack.windows(2).map(|w| Cycle::between(w[0], w[1], 0.5)));
    cycles
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts by range, summed: (range, count), ascending range.
    fn by_range(cycles: &[Cycle]) -> Vec<(f64, f64)> {
        let mut out: Vec<(f64, f64)> = Vec::new();
        let mut sorted = cycles.to_vec();
        sorted.sort_by(|a, b| a.range.total_cmp(&b.range));
        for c in sorted {
            match out.last_mut() {
                Some(last) if (last.0 - c.range).abs() < 1e-12 => last.1 += c.count,
                _ => out.push((c.range, c.count)),
            }
        }
        out
    }

    #[test]
    fn astm_e1049_worked_example_is_counted_as_the_standard_tables_it() {
        // ASTM E1049-85 §5.4.4, Fig. 6: A..I = -2, 1, -3, 5, -1, 3, -4, 4, -2. The standard's
        // table: range 3: 0.5 (A-B); 4: 1.5 (B-C half, E-F full); 6: 0.5 (H-I); 8: 1.0 (C-D and
        // G-H, halves); 9: 0.5 (D-G); no other range.
        let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
        let cycles = count(&history);
        assert_eq!(by_range(&cycles), vec![(3.0, 0.5), (4.0, 1.5), (6.0, 0.5), (8.0, 1.0), (9.0, 0.5)]);
        // The events, as the standard's figure draws them, in the order it counts them.
        let events: Vec<(f64, f64)> = cycles.iter().map(|c| (c.range, c.count)).collect();
        assert_eq!(events, vec![(3.0, 0.5), (4.0, 0.5), (4.0, 1.0), (8.0, 0.5), (9.0, 0.5), (8.0, 0.5), (6.0, 0.5)]);
        // E-F is the one full cycle, about a mean of 1.
        let full: Vec<&Cycle> = cycles.iter().filter(|c| c.count == 1.0).collect();
        assert_eq!(full.len(), 1);
        assert_eq!(full[0].mean, 1.0);
    }

    #[test]
    fn a_cosine_of_whole_periods_is_its_periods_at_its_range() {
        // Starting and ending on a peak, k periods are exactly k cycles of the full range,
        // whatever the sampling (here 37 points a period, none on a valley exactly).
        let (k, mean, range) = (25, 40e6, 120e6);
        let n = 37 * k;
        let history: Vec<f64> =
            (0..=n).map(|i| mean + 0.5 * range * (2.0 * std::f64::consts::PI * i as f64 / 37.0).cos()).collect();
        let cycles = count(&history);
        let at_range: f64 = cycles.iter().filter(|c| (c.range / range - 1.0).abs() < 1e-2).map(|c| c.count).sum();
        assert_eq!(at_range, k as f64);
        assert!(cycles.iter().all(|c| (c.range / range - 1.0).abs() < 1e-2), "{cycles:?}");
        assert!(cycles.iter().all(|c| (c.mean - mean).abs() < 1e-3 * range));
    }

    #[test]
    fn a_sine_from_its_mean_adds_two_half_cycles_of_half_its_range() {
        // 0, +1, -1, ..., +1, -1, 0 (k peaks and valleys): every range between reversals is Y
        // of a three-point test holding S, so 2k - 1 half cycles of 2, and the first and last
        // quarter periods as half cycles of 1.
        let k = 10;
        let mut history = vec![0.0];
        for _ in 0..k {
            history.extend([1.0, -1.0]);
        }
        history.push(0.0);
        let table = by_range(&count(&history));
        assert_eq!(table, vec![(1.0, 1.0), (2.0, k as f64 - 0.5)]);
    }

    #[test]
    fn reversals_drop_ramps_and_plateaus() {
        assert_eq!(reversals(&[]), Vec::<f64>::new());
        assert_eq!(reversals(&[3.0]), vec![3.0]);
        assert_eq!(reversals(&[3.0, 3.0, 3.0]), vec![3.0]);
        assert_eq!(reversals(&[0.0, 1.0, 2.0, 3.0]), vec![0.0, 3.0]);
        assert_eq!(reversals(&[0.0, 2.0, 2.0, 2.0, 1.0, 1.0, 4.0, 5.0]), vec![0.0, 2.0, 1.0, 5.0]);
        assert_eq!(reversals(&[1.0, 1.0, 0.0, -1.0, 0.0]), vec![1.0, -1.0, 0.0]);
        assert!(count(&[]).is_empty());
        assert!(count(&[2.0, 2.0]).is_empty());
        assert_eq!(count(&[0.0, 5.0]), vec![Cycle { range: 5.0, mean: 2.5, count: 0.5 }]);
    }

    /// A deterministic pseudo-random history (a linear congruential generator).
    fn noise(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 200.0
            })
            .collect()
    }

    #[test]
    fn every_range_is_counted_once_and_the_largest_is_the_history_span() {
        for seed in 1..40 {
            let history = noise(500 + 13 * seed as usize, seed);
            let points = reversals(&history).len();
            let cycles = count(&history);
            // Each full cycle takes two reversals off the stack, each half cycle one, and the
            // residue of r points is r - 1 halves: 2 x (cycles counted) = reversals - 1.
            let total: f64 = cycles.iter().map(|c| c.count).sum();
            assert_eq!(2.0 * total, (points - 1) as f64);
            let span =
                history.iter().copied().fold(f64::MIN, f64::max) - history.iter().copied().fold(f64::MAX, f64::min);
            let largest = cycles.iter().map(|c| c.range).fold(0.0, f64::max);
            assert_eq!(largest, span);
        }
    }

    /// The four-point method (a cycle closes when an inner range is within both its
    /// neighbours), an independent formulation: on a history that starts and ends at its
    /// absolute maximum it must close the same full cycles as the three-point method, and
    /// leave no residue but that one range.
    fn four_point_closed(history: &[f64]) -> Vec<(f64, f64)> {
        let mut closed = Vec::new();
        let mut stack: Vec<f64> = Vec::new();
        for p in reversals(history) {
            stack.push(p);
            while stack.len() >= 4 {
                let n = stack.len();
                let inner = (stack[n - 2] - stack[n - 3]).abs();
                if inner <= (stack[n - 1] - stack[n - 2]).abs() && inner <= (stack[n - 3] - stack[n - 4]).abs() {
                    closed.push((inner, 1.0));
                    stack.drain(n - 3..n - 1);
                } else {
                    break;
                }
            }
        }
        closed
    }

    #[test]
    fn on_a_history_from_its_maximum_both_methods_close_the_same_cycles() {
        for seed in 100..130 {
            let mut history = noise(300, seed);
            let (imax, _) =
                history.iter().enumerate().fold((0, f64::MIN), |b, (i, &x)| if x > b.1 { (i, x) } else { b });
            history.rotate_left(imax);
            history.push(history[0]);
            let mut three: Vec<(f64, f64)> =
                count(&history).iter().filter(|c| c.count == 1.0).map(|c| (c.range, 1.0)).collect();
            let mut four = four_point_closed(&history);
            three.sort_by(|a, b| a.0.total_cmp(&b.0));
            four.sort_by(|a, b| a.0.total_cmp(&b.0));
            assert_eq!(three, four, "seed {seed}");
            let halves: Vec<Cycle> = count(&history).into_iter().filter(|c| c.count == 0.5).collect();
            // From the maximum down to the minimum and back: the span's two halves, nothing else.
            assert_eq!(halves.len(), 2, "seed {seed}: {halves:?}");
            assert_eq!(halves[0].range, halves[1].range);
        }
    }
}
