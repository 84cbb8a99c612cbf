//! Putting a measured and a simulated signal on one time base: linear interpolation, and the
//! time shift that best aligns them by cross-correlation.

/// `values` (at increasing `times`) linearly interpolated at `t`; `None` outside their span.
pub fn interpolate(times: &[f64], values: &[f64], t: f64) -> Option<f64> {
    let (first, last) = (*times.first()?, *times.last()?);
    if !(first..=last).contains(&t) {
        return None;
    }
    let i = times.partition_point(|&x| x <= t).clamp(1, times.len() - 1);
    let (t0, t1) = (times[i - 1], times[i]);
    let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
    Some(values[i - 1] + w * (values[i] - values[i - 1]))
}

/// `values` at `times` resampled at `start + k·step` over their span.
fn resample(times: &[f64], values: &[f64], start: f64, step: f64) -> Vec<f64> {
    let count = ((times[times.len() - 1] - start) / step).floor() as usize + 1;
    (0..count).filter_map(|k| interpolate(times, values, start + k as f64 * step)).collect()
}

/// Median spacing of increasing `times`, s.
pub fn median_step(times: &[f64]) -> f64 {
    let mut steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    steps.sort_by(f64::total_cmp);
    steps.get(steps.len() / 2).copied().unwrap_or(f64::NAN)
}

/// A signal pair for [`estimate_shift`]: measured (times, values), simulated (times, values).
pub type Pair<'a> = ((&'a [f64], &'a [f64]), (&'a [f64], &'a [f64]));

/// The shift τ (s) for which measured(t) ≈ simulated(t − τ): the peak of the sum over `pairs` of
/// each pair's normalised cross-correlation (Pearson's r over the overlap), both resampled at the
/// measured file's median step, refined between steps by a parabola through the peak and its
/// neighbours. One shift for all signals: a logger's clock is off by the same time on every
/// channel. Shifts are searched up to half the shorter record, and only where the records
/// overlap over at least half of it (a correlation on a sliver is noise).
pub fn estimate_shift(pairs: &[Pair]) -> Option<f64> {
    let ((measured_t, _), (simulated_t, _)) = *pairs.first()?;
    let step = median_step(measured_t);
    let (m0, s0) = (measured_t[0], simulated_t[0]);
    let grids: Vec<(Vec<f64>, Vec<f64>)> =
        pairs.iter().map(|((mt, mv), (st, sv))| (resample(mt, mv, m0, step), resample(st, sv, s0, step))).collect();
    let (m_len, s_len) = (grids[0].0.len(), grids[0].1.len());
    let shorter = m_len.min(s_len);
    let max_shift = 0.5 * shorter as f64 * step;
    // τ = m0 − s0 + ℓ·step pairs measured sample j with simulated sample j − ℓ.
    let lag_of = |tau: f64| (tau - (m0 - s0)) / step;
    let (lo, hi) = (lag_of(-max_shift).ceil() as i64, lag_of(max_shift).floor() as i64);
    let score = |lag: i64| -> Option<f64> {
        let total: Option<f64> = grids.iter().map(|(m, s)| pearson(m, s, lag, shorter / 2)).sum();
        total
    };
    let scores: Vec<(i64, f64)> = (lo..=hi).filter_map(|lag| score(lag).map(|c| (lag, c))).collect();
    let at = (0..scores.len()).max_by(|&a, &b| scores[a].1.total_cmp(&scores[b].1))?;
    let (lag, best) = scores[at];
    let refine = match (at.checked_sub(1).map(|i| scores[i]), scores.get(at + 1)) {
        (Some((_, before)), Some(&(_, after))) => {
            let curvature = before - 2.0 * best + after;
            if curvature < 0.0 { 0.5 * (before - after) / curvature } else { 0.0 }
        }
        _ => 0.0,
    };
    Some(m0 - s0 + (lag as f64 + refine) * step)
}

/// Pearson's r between `m[j]` and `s[j − lag]` over their overlap, if it holds `min_overlap`
/// samples and neither is constant there.
fn pearson(m: &[f64], s: &[f64], lag: i64, min_overlap: usize) -> Option<f64> {
    let start = lag.max(0) as usize;
    let end = (s.len() as i64 + lag).min(m.len() as i64);
    if end - (start as i64) < min_overlap.max(2) as i64 {
        return None;
    }
    let end = end as usize;
    let n = (end - start) as f64;
    let pairs = || (start..end).map(|j| (m[j], s[(j as i64 - lag) as usize]));
    let (mean_m, mean_s) = pairs().fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (x, y) in pairs() {
        let (dx, dy) = (x - mean_m, y - mean_s);
        sxy += dx * dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_is_linear_and_stays_inside() {
        let (t, v) = ([0.0, 1.0, 3.0], [0.0, 2.0, 0.0]);
        assert_eq!(interpolate(&t, &v, 0.5), Some(1.0));
        assert_eq!(interpolate(&t, &v, 2.0), Some(1.0));
        assert_eq!(interpolate(&t, &v, 3.0), Some(0.0));
        assert_eq!(interpolate(&t, &v, 3.1), None);
    }

    /// A decaying chirp delayed by a known time, sampled on a different clock.
    #[test]
    fn recovers_a_known_shift_between_steps() {
        let signal = |t: f64| (-0.2 * t).exp() * (2.0 * std::f64::consts::PI * (1.0 + 0.3 * t) * t).sin();
        let simulated_t: Vec<f64> = (0..=5000).map(|k| k as f64 * 0.002).collect();
        let simulated: Vec<f64> = simulated_t.iter().map(|&t| signal(t)).collect();
        let tau = 0.2371;
        let measured_t: Vec<f64> = (0..=1800).map(|k| 0.5 + k as f64 * 0.005).collect();
        let measured: Vec<f64> = measured_t.iter().map(|&t| signal(t - tau)).collect();
        let found = estimate_shift(&[((&measured_t, &measured), (&simulated_t, &simulated))]).unwrap();
        assert!((found - tau).abs() < 0.1 * 0.005, "found {found}, expected {tau}");
    }
}
