//! A point-to-point move convolved with an input shaper ([`super::shaper`]):
//! `θ(t) = Σ A_i θ_base(t − t_i)`, and its rate, acceleration and jerk likewise.
//!
//! Since the amplitudes sum to 1 and the base holds at its start before 0 and at its end after
//! its duration `T_b`, the sum starts at the base's start, ends at its end at `T = T_b + t_N`
//! and holds outside `[0, T]`. Between the shifted breakpoints `t_i + b` every term is one cubic,
//! so the shaped profile is itself constant-jerk pieces: it is stored as segments over `[0, T]`
//! like a table, and sampled as cheaply (one search and one cubic). It is not point-symmetric
//! unless its impulses are.

use super::profile::{Kind, MotionProfile, Shaping};
use super::shaper::{Shaper, ShaperMode};
use super::state::{DriveState, Segment};
use super::table;
use super::validate::{DriveError, invalid, require_positive};

/// Breakpoints closer than this fraction of the duration are one (rounding of `t_i + b`).
const MERGE_FRACTION: f64 = 1e-9;

impl MotionProfile {
    /// `base` (a uniform, trapezoidal or s-curve move) convolved with `shaper` tuned to a mode of
    /// natural frequency `frequency_hz` (Hz) and damping ratio `damping_ratio`: same start and
    /// end angles, duration the base's plus the shaper's length
    /// ([`Shaper::length_s`]). Continuity is the base's: a shaped trapezoid's rate is
    /// continuous, its acceleration steps at each `t_i + b` (b a breakpoint of the base).
    ///
    /// # Errors
    /// As [`Self::shaped_for`].
    pub fn shaped(
        base: MotionProfile,
        shaper: Shaper,
        frequency_hz: f64,
        damping_ratio: f64,
    ) -> Result<Self, DriveError> {
        Self::shaped_for(base, shaper, &[ShaperMode { frequency_hz, damping_ratio }])
    }

    /// `base` convolved with `shaper` tuned to every one of `modes` (the convolution of one
    /// shaper per mode, [`Shaper::impulses_for`]): same start and end angles, duration the
    /// base's plus the shapers' lengths ([`Shaper::length_for_s`]).
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for a base that is not uniform, trapezoidal or s-curve
    /// (`base`), no mode (`modes`), a frequency that is not finite and > 0 (`frequency_hz`), or a
    /// damping ratio outside `0 ≤ ζ < 1` (`damping_ratio`).
    pub fn shaped_for(base: MotionProfile, shaper: Shaper, modes: &[ShaperMode]) -> Result<Self, DriveError> {
        base.check_shapeable(modes)?;
        let impulses = shaper.impulses_for(modes);
        let duration_s = base.duration_s + impulses.last().map_or(0.0, |i| i.0);
        let segments = convolved_segments(&base, &impulses, duration_s);
        let (rate, accel, jerk) = table::peaks(&segments, duration_s, 0.0);
        // A trapezoid's acceleration steps: its jerk is impulsive, and so is every shifted copy's.
        let jerk = if base.peak_jerk_rad_s3.is_finite() { jerk } else { f64::INFINITY };
        Ok(Self {
            start_rad: base.start_rad,
            end_rad: base.end_rad,
            duration_s,
            peak_rate_rad_s: rate,
            peak_accel_rad_s2: accel,
            peak_jerk_rad_s3: jerk,
            segments,
            kind: Kind::Shaped(Box::new(Shaping { base, shaper, modes: modes.to_vec(), impulses })),
        })
    }

    /// This move (uniform, trapezoidal or s-curve, unshaped) convolved with `shaper` tuned to
    /// every one of `modes`, its base move shortened by the shaper's length so that the whole
    /// move still takes this one's duration.
    ///
    /// # Errors
    /// As [`Self::shaped_for`]; `duration_s` not longer than the shaper's length; the move's
    /// limits not reachable over the shortened duration.
    pub fn shaped_within(&self, shaper: Shaper, modes: &[ShaperMode]) -> Result<Self, DriveError> {
        self.check_shapeable(modes)?;
        let length_s = shaper.length_for_s(modes);
        if self.duration_s <= length_s {
            let listed: Vec<String> = modes.iter().map(|m| format!("{:.4}", m.frequency_hz)).collect();
            return Err(DriveError::InvalidParameter {
                name: "duration_s",
                value: self.duration_s,
                allowed: format!(
                    "> the {} shaper's length {length_s:.3} s at [{}] Hz (the base move lasts duration_s minus it)",
                    shaper.name(),
                    listed.join(", ")
                ),
            });
        }
        Self::shaped_for(self.over(self.duration_s - length_s)?, shaper, modes)
    }

    /// The same move (uniform, trapezoidal or s-curve: its angles and limit) over `duration_s`.
    fn over(&self, duration_s: f64) -> Result<Self, DriveError> {
        let (start, end) = (self.start_rad, self.end_rad);
        match &self.kind {
            Kind::Uniform => Self::uniform(start, end, duration_s),
            Kind::Trapezoidal { limit } => Self::trapezoidal(start, end, duration_s, *limit),
            Kind::SCurve { limit } => Self::s_curve(start, end, duration_s, *limit),
            _ => Err(not_a_base()),
        }
    }

    /// This move may be shaped to `modes`: it is an unshaped uniform, trapezoidal or s-curve
    /// move, and they are one or more, each with a frequency > 0 and a damping ratio in [0, 1).
    fn check_shapeable(&self, modes: &[ShaperMode]) -> Result<(), DriveError> {
        if !matches!(self.kind, Kind::Uniform | Kind::Trapezoidal { .. } | Kind::SCurve { .. }) {
            return Err(not_a_base());
        }
        if modes.is_empty() {
            return Err(invalid("modes", 0.0, "at least one mode to tune to"));
        }
        for mode in modes {
            require_positive("frequency_hz", mode.frequency_hz)?;
            if !(0.0..1.0).contains(&mode.damping_ratio) {
                return Err(invalid("damping_ratio", mode.damping_ratio, "0 <= damping_ratio < 1"));
            }
        }
        Ok(())
    }

    /// The shaper of a shaped profile, `None` for every other.
    pub fn shaper(&self) -> Option<Shaper> {
        self.shaping().map(|s| s.shaper)
    }

    /// The modes a shaped profile's shaper is tuned to; empty for every other profile.
    pub fn shaper_modes(&self) -> &[ShaperMode] {
        self.shaping().map_or(&[], |s| &s.modes)
    }

    /// A shaped profile's impulses `(t_i s, A_i)`; empty for every other profile.
    pub fn impulses(&self) -> &[(f64, f64)] {
        self.shaping().map_or(&[], |s| &s.impulses)
    }

    /// The unshaped move a shaped profile convolves.
    pub fn base(&self) -> Option<&MotionProfile> {
        self.shaping().map(|s| &s.base)
    }

    fn shaping(&self) -> Option<&Shaping> {
        match &self.kind {
            Kind::Shaped(shaping) => Some(shaping),
            _ => None,
        }
    }

    /// A shaped uniform move's rate jumps: each of the base's, shifted by `t_i` and scaled by
    /// `A_i`, those at one instant summed.
    pub(super) fn shaped_rate_jumps(shaping: &Shaping, duration_s: f64) -> Vec<(f64, f64)> {
        let mut jumps: Vec<(f64, f64)> = shaping
            .impulses
            .iter()
            .flat_map(|&(t_i, a)| shaping.base.rate_jumps().into_iter().map(move |(t, jump)| (t + t_i, a * jump)))
            .collect();
        jumps.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut merged: Vec<(f64, f64)> = Vec::with_capacity(jumps.len());
        for (t, jump) in jumps {
            match merged.last_mut() {
                Some(last) if t - last.0 <= MERGE_FRACTION * duration_s => last.1 += jump,
                _ => merged.push((t, jump)),
            }
        }
        let scale = shaping.base.peak_rate_rad_s;
        merged.retain(|j| j.1.abs() > 1e-12 * scale);
        merged
    }
}

/// A shaper's base that is not an unshaped point-to-point move.
fn not_a_base() -> DriveError {
    invalid("base", f64::NAN, "an unshaped uniform, trapezoidal or s-curve move")
}

/// The shaped profile's constant-jerk segments over `[0, duration_s)`: one per interval between
/// the shifted breakpoints. Each segment's cubic is taken at the interval's midpoint, where every
/// shifted base is inside one of its own pieces (no rounding can put a term on the wrong side of
/// its breakpoint), and carried back to the interval's start: a cubic is its own Taylor series.
fn convolved_segments(base: &MotionProfile, impulses: &[(f64, f64)], duration_s: f64) -> Vec<Segment> {
    let mut starts: Vec<f64> = impulses
        .iter()
        .flat_map(|&(t_i, _)| std::iter::once(0.0).chain(base.breakpoints_s()).map(move |b| t_i + b))
        .filter(|&t| t < duration_s)
        .collect();
    starts.sort_by(f64::total_cmp);
    starts.dedup_by(|later, earlier| *later - *earlier <= MERGE_FRACTION * duration_s);
    let ends: Vec<f64> = starts.iter().skip(1).copied().chain(std::iter::once(duration_s)).collect();
    let mut segments: Vec<Segment> = starts
        .iter()
        .zip(ends)
        .map(|(&t0_s, t1_s)| {
            let mid = 0.5 * (t0_s + t1_s);
            let at_mid = impulses.iter().fold(DriveState::default(), |sum, &(t_i, a)| {
                let s = base.sample(mid - t_i);
                DriveState {
                    angle_rad: sum.angle_rad + a * s.angle_rad,
                    rate_rad_s: sum.rate_rad_s + a * s.rate_rad_s,
                    accel_rad_s2: sum.accel_rad_s2 + a * s.accel_rad_s2,
                    jerk_rad_s3: sum.jerk_rad_s3 + a * s.jerk_rad_s3,
                }
            });
            Segment { t0_s, state: at_mid.advanced(t0_s - mid) }
        })
        .collect();
    // At 0 every shifted copy but the first still rests at the start, and the first starts there.
    if let Some(first) = segments.first_mut() {
        first.state.angle_rad = base.start_rad;
    }
    segments
}

#[cfg(test)]
mod tests {
    use crate::drive::test_support::{assert_close, check_derivatives, max_abs};
    use crate::drive::{MotionLaw, MotionProfile, SCurveLimit, Shaper, TrapezoidLimit};

    const F: f64 = 0.7;
    const ZETA: f64 = 0.02;

    fn bases() -> Vec<MotionProfile> {
        vec![
            MotionProfile::uniform(0.0, 1.5, 10.0).unwrap(),
            MotionProfile::trapezoidal(0.0, 1.5, 10.0, TrapezoidLimit::RampFraction(0.2)).unwrap(),
            MotionProfile::s_curve(1.5, 0.2, 10.0, SCurveLimit::Fractions { ramp_fraction: 0.3, jerk_fraction: 0.25 })
                .unwrap(),
        ]
    }

    /// The stored segments against the convolution evaluated term by term, at every time.
    #[test]
    fn shaped_profile_is_the_convolution() {
        for base in bases() {
            for shaper in Shaper::ALL {
                let p = MotionProfile::shaped(base.clone(), shaper, F, ZETA).unwrap();
                let impulses = shaper.impulses(F, ZETA);
                assert_close(p.duration_s(), base.duration_s() + impulses.last().unwrap().0, 1e-12, "duration");
                for k in 0..=20_000 {
                    let t = -0.5 + (p.duration_s() + 1.0) * f64::from(k) / 20_000.0;
                    let got = p.sample(t);
                    let sum = |pick: fn(&crate::drive::DriveState) -> f64| {
                        impulses.iter().map(|&(ti, a)| a * pick(&base.sample(t - ti))).sum::<f64>()
                    };
                    assert_close(got.angle_rad, sum(|s| s.angle_rad), 1e-11, "angle");
                    // Rate and below may differ at a breakpoint itself (right limits); skip those.
                    let on_break = p.breakpoints_s().iter().chain([0.0].iter()).any(|b| (t - b).abs() < 1e-9);
                    if !on_break {
                        assert_close(got.rate_rad_s, sum(|s| s.rate_rad_s), 1e-11, "rate");
                        assert_close(got.accel_rad_s2, sum(|s| s.accel_rad_s2), 1e-10, "accel");
                        assert_close(got.jerk_rad_s3, sum(|s| s.jerk_rad_s3), 1e-9, "jerk");
                    }
                }
                assert_eq!(p.name(), base.name());
                assert_eq!(p.shaper(), Some(shaper));
                assert_eq!(p.shaper_modes(), [crate::drive::ShaperMode { frequency_hz: F, damping_ratio: ZETA }]);
            }
        }
    }

    /// Ends exact, holds outside, rate continuous where the base's is, derivatives consistent,
    /// peaks equal to a dense sampling's.
    #[test]
    fn shaped_ends_continuity_and_peaks() {
        for base in bases() {
            let p = MotionProfile::shaped(base.clone(), Shaper::Zvd, F, ZETA).unwrap();
            let t_end = p.duration_s();
            assert_eq!(p.sample(0.0).angle_rad, base.start_rad());
            assert_eq!(p.sample(-1.0), crate::drive::DriveState::at_rest(base.start_rad()));
            assert_eq!(p.sample(t_end), crate::drive::DriveState::at_rest(base.end_rad()));
            assert_close(p.sample(t_end * (1.0 - 1e-12)).angle_rad, base.end_rad(), 1e-10, "angle before T");
            let points = p.breakpoints_s();
            assert_eq!(*points.last().unwrap(), t_end);
            if base.name() != "uniform" {
                assert!(p.rate_jumps().is_empty());
                for &b in &points {
                    let (lo, hi) = (p.sample(b - 1e-9), p.sample(b + 1e-9));
                    assert_close(lo.rate_rad_s, hi.rate_rad_s, 1e-7, "rate continuous at a breakpoint");
                }
            }
            let scales = [p.peak_rate_rad_s(), p.peak_accel_rad_s2().max(1e-3), 10.0];
            let mut bounds = points.clone();
            bounds.push(0.0);
            check_derivatives(&p, t_end, &bounds, scales);
            let dense_rate = max_abs(&p, t_end, |s| s.rate_rad_s);
            assert_close(p.peak_rate_rad_s(), dense_rate, 1e-6 * dense_rate, "peak rate");
            assert!(p.peak_rate_rad_s() < base.peak_rate_rad_s() * (1.0 + 1e-12), "shaping never raises the peak rate");
            let dense_accel = max_abs(&p, t_end, |s| s.accel_rad_s2);
            assert_close(p.peak_accel_rad_s2(), dense_accel, 1e-6 * dense_accel.max(1e-9), "peak accel");
            if base.law() == MotionLaw::SCurve {
                let dense_jerk = max_abs(&p, t_end, |s| s.jerk_rad_s3);
                assert_close(p.peak_jerk_rad_s3(), dense_jerk, 1e-9 * dense_jerk, "peak jerk");
            } else if base.law() == MotionLaw::Trapezoidal {
                assert_eq!(p.peak_jerk_rad_s3(), f64::INFINITY);
            }
        }
    }

    /// A shaped uniform move's rate steps by A_i (B − A)/T_b at each t_i and back at T_b + t_i.
    #[test]
    fn shaped_uniform_rate_jumps() {
        let base = MotionProfile::uniform(0.0, 1.5, 10.0).unwrap();
        let rate = 0.15;
        let p = MotionProfile::shaped(base, Shaper::Zv, 1.0, 0.0).unwrap();
        let expected = [(0.0, 0.5 * rate), (0.5, 0.5 * rate), (10.0, -0.5 * rate), (10.5, -0.5 * rate)];
        let jumps = p.rate_jumps();
        assert_eq!(jumps.len(), 4);
        for ((t, j), (te, je)) in jumps.iter().zip(expected) {
            assert_close(*t, te, 1e-12, "jump time");
            assert_close(*j, je, 1e-15, "jump");
        }
        assert_close(p.peak_rate_rad_s(), rate, 1e-15, "peak rate");
        // The rate just after each jump is the sum of the jumps so far.
        assert_close(p.sample(0.25).rate_rad_s, 0.5 * rate, 1e-15, "rate after the first jump");
        assert_close(p.sample(0.5).rate_rad_s, rate, 1e-15, "rate after the second jump");
    }

    #[test]
    fn shaped_refuses_bad_inputs() {
        let base = MotionProfile::trapezoidal(0.0, 1.5, 10.0, TrapezoidLimit::RampFraction(0.2)).unwrap();
        let name = |r: Result<MotionProfile, crate::drive::DriveError>| match r {
            Err(crate::drive::DriveError::InvalidParameter { name, .. }) => name,
            other => panic!("expected an error, got {other:?}"),
        };
        assert_eq!(name(MotionProfile::shaped(base.clone(), Shaper::Zv, 0.0, 0.0)), "frequency_hz");
        assert_eq!(name(MotionProfile::shaped(base.clone(), Shaper::Zv, f64::NAN, 0.0)), "frequency_hz");
        assert_eq!(name(MotionProfile::shaped(base.clone(), Shaper::Zv, 1.0, 1.0)), "damping_ratio");
        assert_eq!(name(MotionProfile::shaped(MotionProfile::hold(0.3), Shaper::Zv, 1.0, 0.0)), "base");
        assert_eq!(name(MotionProfile::shaped_for(base.clone(), Shaper::Zv, &[])), "modes");
        let shaped = MotionProfile::shaped(base, Shaper::Zv, 1.0, 0.0).unwrap();
        assert_eq!(name(MotionProfile::shaped(shaped, Shaper::Zv, 1.0, 0.0)), "base");
    }
}
