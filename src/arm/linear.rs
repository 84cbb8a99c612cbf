//! The arm with its drive linearised about a state: the poles of the closed loop, and how the
//! drive's reference moves it.
//!
//! An actuated hub's controller is taken as sampling continuously (its law unsaturated, its
//! integral a state): the loop a linear analysis of the plant sees. The poles say whether the
//! loop is stable where the lift starts, and how fast its fastest motion is — what limits an
//! explicit integrator's step, which the clamped modes alone understate once the hub is free.
//! The input matrix (the rates' derivatives with respect to the reference's angle, rate and
//! acceleration) says how much of each mode a move excites ([`crate::tuning`]).

use nalgebra::{Complex, DMatrix, DVector};

use super::{ArmError, ArmSimulation, ArmSystem, HubCache, HubDrive};
use crate::drive::{MotionProfile, TrapezoidLimit};
use crate::integrate::{Dynamics, solve_acceleration};

/// The system linearised about a state at rest: `ẏ = A y + B r`, `y` the state's departure from
/// it, `r` the reference's departure (angle rad, rate rad/s, acceleration rad/s²).
#[derive(Debug, Clone)]
pub struct LinearSystem {
    /// `A`, n × n.
    pub a: DMatrix<f64>,
    /// `B`, n × 3: columns for the reference's angle, rate and acceleration.
    pub b: DMatrix<f64>,
    /// Where the linear state holds the hub's angle and rate, under a free or actuated hub.
    pub hub: Option<(usize, usize)>,
    /// Where the elastic coordinates q start in the linear state (they are the arm's
    /// [`super::ArmModel::elastic_dofs`] in a row).
    pub elastic_offset: usize,
}

impl ArmSimulation {
    /// Poles of the system linearised about its current state, rad/s: λ with Re λ < 0 decays.
    /// Coordinates held at zero (first-order states' positions) and a prescribed hub's angle
    /// are left out.
    pub fn linear_poles(&self) -> Result<Vec<Complex<f64>>, ArmError> {
        Ok(self.jacobian()?.complex_eigenvalues().iter().copied().collect())
    }

    /// The system linearised about its current state, which must be at rest at t = 0 with its
    /// drive's reference at rest (a simulation just built on a held drive,
    /// [`crate::model::Model::hub_drive_held_at`]): `A` as [`Self::linear_poles`] takes it, and
    /// `B` by central differences of the rates over the reference's angle, rate and acceleration.
    ///
    /// # Errors
    /// A state not at t = 0 or a reference not at rest (`linearisation`); the dynamics' own.
    pub fn linearised(&self) -> Result<LinearSystem, ArmError> {
        let reference = match &self.drive {
            HubDrive::Prescribed(p) => Some(p.sample(0.0)),
            HubDrive::Actuated(plant) => Some(plant.reference.sample(0.0)),
            HubDrive::Free { .. } => None,
        };
        let at_rest = reference.is_none_or(|r| r.rate_rad_s == 0.0 && r.accel_rad_s2 == 0.0);
        if self.time_s() != 0.0 || !at_rest {
            return Err(ArmError::InvalidParameter {
                name: "linearisation".into(),
                value: self.time_s(),
                allowed: "a simulation at t = 0 on a reference at rest".into(),
            });
        }
        let a = self.jacobian()?;
        let mut b = DMatrix::zeros(a.nrows(), 3);
        if let Some(r) = reference {
            for (k, column) in reference_probes(r.angle_rad)?.into_iter().enumerate() {
                let (plus, minus, step) = column;
                let rates = |probe: MotionProfile| -> Result<DVector<f64>, ArmError> {
                    let mut out = DVector::zeros(a.nrows());
                    self.linear_rates_with(&self.with_reference(probe), &self.linear_state(), &mut out)?;
                    Ok(out)
                };
                b.set_column(k, &((rates(plus)? - rates(minus)?) / (2.0 * step)));
            }
        }
        let hub = self.drive.hub_is_free().then(|| (0, self.linear_layout().0));
        Ok(LinearSystem { a, b, hub, elastic_offset: usize::from(self.drive.hub_is_free()) })
    }

    /// ∂ẏ/∂y at the current state, by central differences.
    fn jacobian(&self) -> Result<DMatrix<f64>, ArmError> {
        let y0 = self.linear_state();
        let n = y0.len();
        let mut jacobian = DMatrix::zeros(n, n);
        let (mut yp, mut plus, mut minus) = (y0.clone(), DVector::zeros(n), DVector::zeros(n));
        for j in 0..n {
            // A state's 1e-7, and 1e-7 of its unit where it is smaller: the arm's rates reach
            // ω² y over its stiffest DOFs (10¹⁰ s⁻² on an fe arm), and a smaller step lets their
            // rounding into the slow poles (a growing one of 5372 rad/s on the fe arm under the
            // servo at 1e-11), while the deflections at rest stay far above 1e-7 m.
            let h = 1e-7 * y0[j].abs().max(1.0);
            yp[j] = y0[j] + h;
            self.linear_rates(&yp, &mut plus)?;
            yp[j] = y0[j] - h;
            self.linear_rates(&yp, &mut minus)?;
            yp[j] = y0[j];
            jacobian.set_column(j, &((&plus - &minus) / (2.0 * h)));
        }
        Ok(jacobian)
    }

    /// The drive with its reference (a prescribed hub's motion, an actuator's reference)
    /// replaced by `reference`; a free hub unchanged.
    fn with_reference(&self, reference: MotionProfile) -> HubDrive {
        match &self.drive {
            HubDrive::Prescribed(_) => HubDrive::Prescribed(reference),
            HubDrive::Actuated(plant) => {
                let mut plant = plant.clone();
                plant.reference = reference;
                HubDrive::Actuated(plant)
            }
            free @ HubDrive::Free { .. } => free.clone(),
        }
    }

    /// Counts of (positions, rates, controller integral) in the linear state.
    fn linear_layout(&self) -> (usize, usize, usize) {
        let s = self.state();
        let first_order = self.drive.plant().map_or(0, |p| p.first_order_dofs());
        let integral = self.drive.plant().map_or(0, |p| usize::from(p.controller.gains.ki > 0.0));
        (s.x.len() - first_order, s.v.len(), integral)
    }

    /// [second-order positions, all rates, the controller's integral].
    fn linear_state(&self) -> DVector<f64> {
        let (positions, rates, integral) = self.linear_layout();
        let s = self.state();
        let integral_value = self.drive.plant().map(|p| p.controller.integral);
        let values = s.x.iter().take(positions).chain(s.v.iter().take(rates)).copied();
        DVector::from_iterator(positions + rates + integral, values.chain(integral_value.into_iter().take(integral)))
    }

    /// d/dt of the linear state at `y`, with the controller's output its law at `y`.
    fn linear_rates(&self, y: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), ArmError> {
        self.linear_rates_with(&self.drive, y, out)
    }

    /// [`Self::linear_rates`] under `drive` instead of the simulation's.
    fn linear_rates_with(&self, drive: &HubDrive, y: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), ArmError> {
        let (positions, rates, integral) = self.linear_layout();
        let t = self.time_s();
        let mut x = DVector::zeros(rates);
        x.rows_mut(0, positions).copy_from(&y.rows(0, positions));
        let v = y.rows(positions, rates).into_owned();
        let mut drive = drive.clone();
        let mut error = 0.0;
        if let HubDrive::Actuated(plant) = &mut drive {
            let own = 1 + self.arm.elastic_dofs() + self.arm.head_dofs();
            if integral == 1 {
                plant.controller.integral = y[positions + rates];
            }
            let (hub, x_own, v_own) = ((x[0], v[0]), &x.as_slice()[own..], &v.as_slice()[own..]);
            plant.controller.output = plant.continuous_output(t, hub, x_own, v_own);
            let measured = if plant.second_order_dofs() > 0 { x_own[0] } else { x[0] };
            error = plant.reference.sample(t).angle_rad - measured;
        }
        let hub = HubCache::default();
        let system = ArmSystem::new(&self.arm, &drive, &self.load, &self.contacts, &hub);
        let mut a = DVector::zeros(system.dofs());
        solve_acceleration(&system, t, &x, &v, &mut a)?;
        out.rows_mut(0, positions).copy_from(&v.rows(0, positions));
        out.rows_mut(positions, rates).copy_from(&a);
        if integral == 1 {
            out[positions + rates] = error;
        }
        Ok(())
    }
}

/// References through `angle_rad` at t = 0 that depart from rest there in one of angle, rate or
/// acceleration: for each, the probes `+h` and `−h` and `h` (rad, rad/s, rad/s²). A hold for the
/// angle; a uniform move's (right-limit) rate at its start; a trapezoid's acceleration at its
/// start, its angle and rate still those of rest.
fn reference_probes(angle_rad: f64) -> Result<[(MotionProfile, MotionProfile, f64); 3], ArmError> {
    const ANGLE_RAD: f64 = 1e-6;
    const RATE_RAD_S: f64 = 1e-6;
    const ACCEL_RAD_S2: f64 = 1e-4;
    let hold = |sign: f64| MotionProfile::hold(angle_rad + sign * ANGLE_RAD);
    // 1 s moves: a uniform one of RATE over it, a trapezoid of ACCEL covering ACCEL/8 (feasible:
    // below the triangle's ACCEL/4).
    let uniform = |sign: f64| MotionProfile::uniform(angle_rad, angle_rad + sign * RATE_RAD_S, 1.0);
    let limit = TrapezoidLimit::AccelRadS2(ACCEL_RAD_S2);
    let trapezoid =
        |sign: f64| MotionProfile::trapezoidal(angle_rad, angle_rad + sign * ACCEL_RAD_S2 / 8.0, 1.0, limit);
    Ok([
        (hold(1.0), hold(-1.0), ANGLE_RAD),
        (uniform(1.0)?, uniform(-1.0)?, RATE_RAD_S),
        (trapezoid(1.0)?, trapezoid(-1.0)?, ACCEL_RAD_S2),
    ])
}

#[cfg(test)]
mod tests {
    use super::reference_probes;

    /// Each probe departs from rest at t = 0 in its own component only, by ±h.
    #[test]
    fn probes_depart_in_one_component() {
        let angle = 0.7;
        for (k, (plus, minus, h)) in reference_probes(angle).unwrap().into_iter().enumerate() {
            for (probe, sign) in [(plus, 1.0), (minus, -1.0)] {
                let s = probe.sample(0.0);
                let got = [s.angle_rad - angle, s.rate_rad_s, s.accel_rad_s2];
                for (j, value) in got.into_iter().enumerate() {
                    let want = if j == k { sign * h } else { 0.0 };
                    assert!((value - want).abs() <= 1e-8 * h, "probe {k} component {j}: {value} vs {want}");
                }
            }
        }
    }
}
