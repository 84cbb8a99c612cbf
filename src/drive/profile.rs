//! The kinds of [`MotionProfile`] and their constructors: each validates its inputs, solves its
//! timing and stores the profile as constant-jerk segments — a symmetric profile's first half
//! (see the module doc of [`crate::drive`] for the point symmetry that gives the second half), a
//! table's whole span.

use std::f64::consts::PI;

use super::s_curve::{SCurveLimit, s_curve_shape};
use super::shaper::{Shaper, ShaperMode};
use super::state::{DriveState, Piece, Segment, chain};
use super::table;
use super::trapezoid::{TrapezoidLimit, trapezoid_shape};
use super::validate::{DriveError, Move, invalid, require_finite, require_positive};

/// Which kind of profile a [`MotionProfile`] is.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Kind {
    Uniform,
    /// With the limit it was built to (so that it can be built again over another duration).
    Trapezoidal {
        limit: TrapezoidLimit,
    },
    SCurve {
        limit: SCurveLimit,
    },
    Hold,
    SpinUp {
        final_rate_rad_s: f64,
    },
    Table {
        end_rate_rad_s: f64,
    },
    /// A base profile convolved with an input shaper's impulses ([`super::shaped`]).
    Shaped(Box<Shaping>),
}

/// What a shaped profile is made of: its base (a uniform, trapezoidal or s-curve move) and the
/// impulses it is convolved with.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Shaping {
    pub(super) base: MotionProfile,
    pub(super) shaper: Shaper,
    /// The modes it is tuned to, one or more.
    pub(super) modes: Vec<ShaperMode>,
    /// `(t_i s, A_i)`, first at 0, amplitudes summing to 1.
    pub(super) impulses: Vec<(f64, f64)>,
}

/// Peak magnitudes of a profile (rad/s, rad/s², rad/s³).
#[derive(Debug, Clone, Copy)]
struct Peaks {
    rate: f64,
    accel: f64,
    jerk: f64,
}

/// Profile of prescribed hub angle versus time.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionProfile {
    pub(super) kind: Kind,
    pub(super) start_rad: f64,
    pub(super) end_rad: f64,
    pub(super) duration_s: f64,
    pub(super) peak_rate_rad_s: f64,
    pub(super) peak_accel_rad_s2: f64,
    pub(super) peak_jerk_rad_s3: f64,
    /// Constant-jerk segments: `[0, T/2]` of a symmetric profile, `[0, T]` of a table or a shaped
    /// profile (empty for hold and spin-up).
    pub(super) segments: Vec<Segment>,
}

impl MotionProfile {
    /// Constant rate `(B − A)/T` (rad/s) for `0 < t < T`, from `start_rad`
    /// (rad) to `end_rad` (rad) in `duration_s` (s). The rate jumps at `t = 0`
    /// and `t = T` (angle continuous only; see [`Self::rate_jumps`]).
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for non-finite angles, `start == end`
    /// or a non-positive / non-finite duration.
    pub fn uniform(start_rad: f64, end_rad: f64, duration_s: f64) -> Result<Self, DriveError> {
        let mv = Move::new(start_rad, end_rad, duration_s)?;
        let rate = mv.delta() / mv.duration_s;
        let initial = DriveState { angle_rad: mv.start_rad, rate_rad_s: rate, accel_rad_s2: 0.0, jerk_rad_s3: 0.0 };
        let segments = chain(initial, &[Piece::new(0.0, 0.0, 0.0)]);
        let peaks = Peaks { rate: rate.abs(), accel: 0.0, jerk: 0.0 };
        Self::assemble(Kind::Uniform, &mv, peaks, segments)
    }

    /// Acceleration-limited symmetric move from `start_rad` (rad) to `end_rad`
    /// (rad) in `duration_s` (s): constant acceleration, constant rate,
    /// constant deceleration. Rate is continuous, acceleration jumps.
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for invalid move parameters, a
    /// non-positive acceleration, an acceleration below `4|B − A|/T²` (the
    /// minimum is given in `allowed`) or a ramp fraction outside `(0, 0.5]`.
    pub fn trapezoidal(
        start_rad: f64,
        end_rad: f64,
        duration_s: f64,
        limit: TrapezoidLimit,
    ) -> Result<Self, DriveError> {
        let mv = Move::new(start_rad, end_rad, duration_s)?;
        let (t_a, accel) = trapezoid_shape(&mv, limit)?;
        let pieces = [Piece::new(0.0, mv.sign() * accel, 0.0), Piece::new(t_a, 0.0, 0.0)];
        let segments = chain(DriveState::at_rest(mv.start_rad), &pieces);
        let peaks = Peaks { rate: mv.distance() / (mv.duration_s - t_a), accel, jerk: f64::INFINITY };
        Self::assemble(Kind::Trapezoidal { limit }, &mv, peaks, segments)
    }

    /// Jerk-limited symmetric 7-segment S-curve from `start_rad` (rad) to
    /// `end_rad` (rad) in `duration_s` (s): jerk `+J`, 0, `−J` (accel phase),
    /// cruise, then the mirror image. Acceleration is continuous, jerk is
    /// piecewise constant.
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for invalid move parameters,
    /// non-positive limits, fractions outside `(0, 0.5]`, or accel/jerk limits
    /// with which the profile cannot reach `end_rad` in `duration_s` while
    /// using exactly those peaks (the bound is given in `allowed`).
    pub fn s_curve(start_rad: f64, end_rad: f64, duration_s: f64, limit: SCurveLimit) -> Result<Self, DriveError> {
        let mv = Move::new(start_rad, end_rad, duration_s)?;
        let (t_a, t_j, accel, jerk) = s_curve_shape(&mv, limit)?;
        let (signed_accel, signed_jerk) = (mv.sign() * accel, mv.sign() * jerk);
        let pieces = [
            Piece::new(0.0, 0.0, signed_jerk),
            Piece::new(t_j, signed_accel, 0.0),
            Piece::new(t_a - t_j, signed_accel, -signed_jerk),
            Piece::new(t_a, 0.0, 0.0),
        ];
        let segments = chain(DriveState::at_rest(mv.start_rad), &pieces);
        let peaks = Peaks { rate: mv.distance() / (mv.duration_s - t_a), accel, jerk };
        Self::assemble(Kind::SCurve { limit }, &mv, peaks, segments)
    }

    /// Hold at `angle_rad` (rad) forever, at rest.
    pub fn hold(angle_rad: f64) -> Self {
        Self {
            kind: Kind::Hold,
            start_rad: angle_rad,
            end_rad: angle_rad,
            duration_s: 0.0,
            peak_rate_rad_s: 0.0,
            peak_accel_rad_s2: 0.0,
            peak_jerk_rad_s3: 0.0,
            segments: Vec::new(),
        }
    }

    /// Kane–Ryan–Banerjee spin-up to `final_rate_rad_s` (rad/s, `w`) over
    /// `ramp_time_s` (s, `Ts`), offset by `start_rad` (rad):
    /// `θ(t) = A + (w/Ts)[t²/2 + (Ts/2π)²(cos(2πt/Ts) − 1)]` for `0 ≤ t ≤ Ts`,
    /// `θ(t) = A + w(t − Ts/2)` after (constant rate `w` forever).
    /// Angle, rate, acceleration and jerk are all continuous.
    ///
    /// # Errors
    /// [`DriveError::InvalidParameter`] for a non-finite start angle or final
    /// rate, or a non-positive / non-finite ramp time.
    pub fn spin_up(start_rad: f64, final_rate_rad_s: f64, ramp_time_s: f64) -> Result<Self, DriveError> {
        let start_rad = require_finite("start_rad", start_rad)?;
        let rate = require_finite("final_rate_rad_s", final_rate_rad_s)?;
        let ramp = require_positive("ramp_time_s", ramp_time_s)?;
        let end_rad = start_rad + 0.5 * rate * ramp;
        let peak_accel = 2.0 * rate.abs() / ramp;
        let peak_jerk = 2.0 * PI * rate.abs() / (ramp * ramp);
        if !(end_rad.is_finite() && peak_accel.is_finite() && peak_jerk.is_finite()) {
            return Err(invalid("ramp_time_s", ramp, "such that the end angle, peak accel and peak jerk are finite"));
        }
        Ok(Self {
            kind: Kind::SpinUp { final_rate_rad_s: rate },
            start_rad,
            end_rad,
            duration_s: ramp,
            peak_rate_rad_s: rate.abs(),
            peak_accel_rad_s2: peak_accel,
            peak_jerk_rad_s3: peak_jerk,
            segments: Vec::new(),
        })
    }

    /// The clamped cubic spline through the samples `(times_s[i], angles_rad[i])` (s, rad): rate
    /// 0 at the first sample (the hub rests before it), `end_rate_rad_s` (rad/s) at the last and
    /// after it (0: the hub stops there). Angle, rate and acceleration are continuous on
    /// `[0, T]`, the jerk is constant between samples; the acceleration steps from and to 0 at
    /// the ends (see [`crate::drive`]'s `table` module for the choice of spline).
    ///
    /// # Errors
    /// [`DriveError::InvalidSample`] naming the index of a time that is not finite, not
    /// increasing or (the first) not 0, or of an angle that is not finite;
    /// [`DriveError::InvalidParameter`] for fewer than 4 samples, unequal lengths, a non-finite
    /// end rate, or samples so close and steep that the spline's peaks overflow.
    pub fn table(times_s: &[f64], angles_rad: &[f64], end_rate_rad_s: f64) -> Result<Self, DriveError> {
        table::check_samples(times_s, angles_rad)?;
        let end_rate = table::end_rate(end_rate_rad_s)?;
        let segments = table::clamped_spline(times_s, angles_rad, end_rate);
        let duration_s = times_s[times_s.len() - 1];
        let (rate, accel, jerk) = table::peaks(&segments, duration_s, end_rate);
        if !(rate.is_finite() && accel.is_finite() && jerk.is_finite()) {
            return Err(invalid("times_s", duration_s, "samples whose spline has a finite peak rate, accel and jerk"));
        }
        Ok(Self {
            kind: Kind::Table { end_rate_rad_s: end_rate },
            start_rad: angles_rad[0],
            end_rad: angles_rad[angles_rad.len() - 1],
            duration_s,
            peak_rate_rad_s: rate,
            peak_accel_rad_s2: accel,
            peak_jerk_rad_s3: jerk,
            segments,
        })
    }

    /// Smallest and largest angle over `[0, t_end_s]`, rad: a table may overshoot its samples
    /// between them; every other profile is monotone.
    pub fn angle_range_rad(&self, t_end_s: f64) -> (f64, f64) {
        let last = self.sample(t_end_s.max(0.0)).angle_rad;
        let (lo, hi) = match self.kind {
            Kind::Table { .. } => table::angle_range(&self.segments, self.duration_s.min(t_end_s.max(0.0))),
            _ => (self.start_rad, self.start_rad),
        };
        (lo.min(self.start_rad).min(last), hi.max(self.start_rad).max(last))
    }

    /// Angle at `t = 0`, rad.
    pub fn start_rad(&self) -> f64 {
        self.start_rad
    }

    /// Angle at `t = duration_s()`, rad (for spin-up `A + w Ts/2`; for hold the
    /// held angle; for a table its last sample).
    pub fn end_rad(&self) -> f64 {
        self.end_rad
    }

    /// Duration of the motion, s (ramp time for spin-up, 0 for hold, the last sample's time for
    /// a table).
    pub fn duration_s(&self) -> f64 {
        self.duration_s
    }

    /// Peak rate magnitude, rad/s (0 for hold, `|w|` for spin-up; for a table exact over its
    /// cubics and its end rate).
    pub fn peak_rate_rad_s(&self) -> f64 {
        self.peak_rate_rad_s
    }

    /// Peak acceleration magnitude, rad/s² (0 for uniform, whose rate jumps
    /// are impulses, and for hold).
    pub fn peak_accel_rad_s2(&self) -> f64 {
        self.peak_accel_rad_s2
    }

    /// Peak jerk magnitude, rad/s³: finite for s-curve and spin-up,
    /// `f64::INFINITY` for trapezoidal (acceleration steps), 0 for uniform
    /// and hold; for a table the largest of its cubics' constant jerks (the
    /// acceleration steps at its ends are not counted).
    pub fn peak_jerk_rad_s3(&self) -> f64 {
        self.peak_jerk_rad_s3
    }

    /// The motion law: a shaped profile's is its base's (its shaper is [`Self::shaper`]).
    pub fn law(&self) -> MotionLaw {
        match &self.kind {
            Kind::Shaped(shaping) => shaping.base.law(),
            Kind::Uniform => MotionLaw::Uniform,
            Kind::Trapezoidal { .. } => MotionLaw::Trapezoidal,
            Kind::SCurve { .. } => MotionLaw::SCurve,
            Kind::Hold => MotionLaw::Hold,
            Kind::SpinUp { .. } => MotionLaw::SpinUp,
            Kind::Table { .. } => MotionLaw::Table,
        }
    }

    /// The motion law's name as the scenario and the summary spell it ([`MotionLaw::name`]).
    pub fn name(&self) -> &'static str {
        self.law().name()
    }

    /// Builds a symmetric profile and checks that its first half really
    /// reaches the midpoint angle (guards against degenerate extreme inputs).
    fn assemble(kind: Kind, mv: &Move, peaks: Peaks, segments: Vec<Segment>) -> Result<Self, DriveError> {
        let jerk_ok = peaks.jerk.is_finite() || matches!(kind, Kind::Trapezoidal { .. });
        if !(peaks.rate.is_finite() && peaks.accel.is_finite() && jerk_ok) {
            return Err(invalid(
                "duration_s",
                mv.duration_s,
                "long enough that the peak rate, accel and jerk are finite",
            ));
        }
        let profile = Self {
            kind,
            start_rad: mv.start_rad,
            end_rad: mv.end_rad,
            duration_s: mv.duration_s,
            peak_rate_rad_s: peaks.rate,
            peak_accel_rad_s2: peaks.accel,
            peak_jerk_rad_s3: peaks.jerk,
            segments,
        };
        profile.check_midpoint()?;
        Ok(profile)
    }

    /// Verifies that the first half ends at `(A + B)/2` at `T/2`.
    fn check_midpoint(&self) -> Result<(), DriveError> {
        let mid = self.start_rad.midpoint(self.end_rad);
        let reached = self.segment_state(0.5 * self.duration_s, false).angle_rad;
        let tol = 1e-9 * (self.end_rad - self.start_rad).abs()
            + 8.0 * f64::EPSILON * (self.start_rad.abs() + self.end_rad.abs());
        if (reached - mid).abs() <= tol {
            Ok(())
        } else {
            Err(invalid(
                "duration_s",
                self.duration_s,
                "a value for which the requested limits give a numerically representable profile",
            ))
        }
    }
}

/// The law a hub profile follows, whatever its parameters: what callers branch on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionLaw {
    Uniform,
    Trapezoidal,
    SCurve,
    Hold,
    SpinUp,
    Table,
}

impl MotionLaw {
    /// `"uniform"`, `"trapezoidal"`, `"s-curve"`, `"hold"`, `"spin-up"` or `"table"`.
    pub fn name(self) -> &'static str {
        match self {
            MotionLaw::Uniform => "uniform",
            MotionLaw::Trapezoidal => "trapezoidal",
            MotionLaw::SCurve => "s-curve",
            MotionLaw::Hold => "hold",
            MotionLaw::SpinUp => "spin-up",
            MotionLaw::Table => "table",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::MotionProfile;
    use crate::drive::test_support::{DUR, END, START};
    use crate::drive::{DriveError, SCurveLimit, TrapezoidLimit};

    fn err_name(result: Result<MotionProfile, DriveError>) -> &'static str {
        match result {
            Err(DriveError::InvalidParameter { name, .. }) => name,
            other => panic!("expected an invalid parameter, got {other:?}"),
        }
    }

    #[test]
    fn invalid_inputs_are_rejected_by_name() {
        let nan = f64::NAN;
        let accel_jerk = |accel_rad_s2, jerk_rad_s3| SCurveLimit::AccelJerk { accel_rad_s2, jerk_rad_s3 };
        let fractions = |ramp_fraction, jerk_fraction| SCurveLimit::Fractions { ramp_fraction, jerk_fraction };
        let trap = |limit| MotionProfile::trapezoidal(START, END, DUR, limit);
        let scurve = |limit| MotionProfile::s_curve(START, END, DUR, limit);
        let cases = [
            (MotionProfile::uniform(START, END, 0.0), "duration_s"),
            (MotionProfile::uniform(START, END, -1.0), "duration_s"),
            (MotionProfile::uniform(START, END, nan), "duration_s"),
            (MotionProfile::uniform(START, START, DUR), "end_rad"),
            (MotionProfile::uniform(nan, END, DUR), "start_rad"),
            (MotionProfile::uniform(START, f64::INFINITY, DUR), "end_rad"),
            (trap(TrapezoidLimit::AccelRadS2(-1.0)), "accel_rad_s2"),
            (trap(TrapezoidLimit::AccelRadS2(nan)), "accel_rad_s2"),
            (trap(TrapezoidLimit::AccelRadS2(1.0)), "accel_rad_s2"),
            (trap(TrapezoidLimit::RampFraction(0.0)), "ramp_fraction"),
            (trap(TrapezoidLimit::RampFraction(0.6)), "ramp_fraction"),
            (trap(TrapezoidLimit::RampFraction(nan)), "ramp_fraction"),
            (MotionProfile::trapezoidal(START, END, 0.0, TrapezoidLimit::RampFraction(0.2)), "duration_s"),
            (scurve(fractions(0.6, 0.25)), "ramp_fraction"),
            (scurve(fractions(0.4, 0.0)), "jerk_fraction"),
            (scurve(fractions(0.4, 0.51)), "jerk_fraction"),
            (scurve(fractions(0.4, nan)), "jerk_fraction"),
            (scurve(accel_jerk(-2.5, 20.0)), "accel_rad_s2"),
            (scurve(accel_jerk(2.5, nan)), "jerk_rad_s3"),
            (scurve(accel_jerk(2.5, 0.0)), "jerk_rad_s3"),
            (scurve(accel_jerk(2.5, 5.0)), "jerk_rad_s3"),
            (scurve(accel_jerk(1.4, 100.0)), "accel_rad_s2"),
            (scurve(accel_jerk(100.0, 200.0)), "jerk_rad_s3"),
            (MotionProfile::spin_up(0.0, nan, 1.0), "final_rate_rad_s"),
            (MotionProfile::spin_up(0.0, 1.0, 0.0), "ramp_time_s"),
            (MotionProfile::spin_up(0.0, 1.0, f64::INFINITY), "ramp_time_s"),
            (MotionProfile::spin_up(nan, 1.0, 1.0), "start_rad"),
        ];
        for (i, (result, expected)) in cases.into_iter().enumerate() {
            assert_eq!(err_name(result), expected, "case {i}");
        }
    }

    #[test]
    fn error_message_names_parameter() {
        let err = MotionProfile::uniform(START, END, 0.0).expect_err("zero duration");
        let text = err.to_string();
        assert!(text.contains("`duration_s`"), "{text}");
        assert!(text.contains("> 0"), "{text}");
    }
}
