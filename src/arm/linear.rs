//! The arm with its drive linearised about a state: the poles of the closed loop.
//!
//! An actuated hub's controller is taken as sampling continuously (its law unsaturated, its
//! integral a state): the loop a linear analysis of the plant sees. The poles say whether the
//! loop is stable where the lift starts, and how fast its fastest motion is — what limits an
//! explicit integrator's step, which the clamped modes alone understate once the hub is free.

use nalgebra::{Complex, DMatrix, DVector};

use super::{ArmError, ArmSimulation, ArmSystem, HubCache, HubDrive};
use crate::integrate::{Dynamics, solve_acceleration};

impl ArmSimulation {
    /// Poles of the system linearised about its current state, rad/s: λ with Re λ < 0 decays.
    /// Coordinates held at zero (first-order states' positions) and a prescribed hub's angle
    /// are left out.
    pub fn linear_poles(&self) -> Result<Vec<Complex<f64>>, ArmError> {
        let y0 = self.linear_state();
        let n = y0.len();
        let mut jacobian = DMatrix::zeros(n, n);
        let (mut yp, mut plus, mut minus) = (y0.clone(), DVector::zeros(n), DVector::zeros(n));
        for j in 0..n {
            let h = 1e-7 * y0[j].abs().max(1e-4);
            yp[j] = y0[j] + h;
            self.linear_rates(&yp, &mut plus)?;
            yp[j] = y0[j] - h;
            self.linear_rates(&yp, &mut minus)?;
            yp[j] = y0[j];
            jacobian.set_column(j, &((&plus - &minus) / (2.0 * h)));
        }
        Ok(jacobian.complex_eigenvalues().iter().copied().collect())
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
        let (positions, rates, integral) = self.linear_layout();
        let t = self.time_s();
        let mut x = DVector::zeros(rates);
        x.rows_mut(0, positions).copy_from(&y.rows(0, positions));
        let v = y.rows(positions, rates).into_owned();
        let mut drive = self.drive.clone();
        let mut error = 0.0;
        if let HubDrive::Actuated(plant) = &mut drive {
            let own = 1 + self.arm.elastic_dofs();
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
