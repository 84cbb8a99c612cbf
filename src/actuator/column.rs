//! The cylinders' oil columns running: each cylinder's rod force from its chamber pressures, and
//! the pressures' rates from the valves' flows and the rods' motion (Merritt's equations, module
//! doc of [`super::hydraulic`]), for any number of cylinders fed by one valve or by one each.
//!
//! The first-order states (scaled by the supply pressure) are one (p₁, p₂) pair per valve, then
//! the spool opening shared by every valve: [p₁, p₂, (p₁, p₂)…, x].
//!
//! A modal arm leaves a residual flexibility C at the pins ([`super::PinCouplings`]), in series
//! with the rods: cylinder i is s_i + Σⱼ C_ij F_j long (F the pressures' forces) and extends at
//! ṡe_i = ṡ_i + Σⱼ C_ij Ḟ_j, where Ḟ_j follows from the chamber equations and the ṡe of the
//! cylinders sharing j's chambers. That is the linear system (I + C B) ṡe = ṡ + C b₀, with
//! B_ij = β (A₁ᵢ A₁ⱼ / V₁ + A₂ᵢ A₂ⱼ / V₂) for cylinders on the same valve (0 otherwise) and
//! b₀ the valve flows' share: one cylinder gives ṡe = (ṡ + c Ḟ₀) / (1 + c k), the column and the
//! flexibility in series.

use smallvec::SmallVec;

use super::HydraulicDrive;

/// A value per cylinder, kept inline for the usual one or two.
pub type PerCylinder = SmallVec<[f64; 2]>;

/// A cylinder's pin-to-pin length and rate as the arm's coordinates give them (m, m/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stroke {
    /// Pin-to-pin length, m (or, for a servo, the hub angle, rad).
    pub position: f64,
    /// Its rate, m/s (rad/s).
    pub rate: f64,
}

/// The cylinders' strokes as the arm's step hands them over, and the residual flexibility between
/// their rods.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CylinderStrokes {
    /// Each cylinder's stroke.
    pub strokes: SmallVec<[Stroke; 2]>,
    /// Row-major n × n, m/N: cylinder i is longer by entry (i, j) per newton of cylinder j's rod
    /// force (all zero on a rigid or a full FE arm).
    pub flexibility_m_per_n: SmallVec<[f64; 4]>,
}

impl CylinderStrokes {
    fn flexibility(&self, i: usize, j: usize) -> f64 {
        self.flexibility_m_per_n[i * self.strokes.len() + j]
    }
}

/// Index of the spool opening among the first-order states.
pub fn spool_index(h: &HydraulicDrive) -> usize {
    2 * h.cylinders.chambers()
}

/// Valve `g`'s chamber pressures (cap, rod), Pa, from the scaled states `v`.
fn valve_pressures_pa(h: &HydraulicDrive, v: &[f64], g: usize) -> [f64; 2] {
    let ps = h.circuit.supply_pressure_pa;
    [v[2 * g] * ps, v[2 * g + 1] * ps]
}

/// Each valve's chamber pressures (cap, rod), Pa, from the scaled states `v`.
pub fn pressures_per_valve_pa(h: &HydraulicDrive, v: &[f64]) -> SmallVec<[[f64; 2]; 2]> {
    (0..h.cylinders.chambers()).map(|g| valve_pressures_pa(h, v, g)).collect()
}

/// Each cylinder's chamber pressures (cap, rod), Pa, from the scaled states `v`.
pub fn pressures_pa(h: &HydraulicDrive, v: &[f64]) -> SmallVec<[[f64; 2]; 2]> {
    (0..h.cylinders.each.len()).map(|i| valve_pressures_pa(h, v, h.cylinders.chamber_of(i))).collect()
}

/// Each rod's force from its chamber pressures, N.
fn pressure_forces_n(h: &HydraulicDrive, v: &[f64]) -> PerCylinder {
    let ps = h.circuit.supply_pressure_pa;
    let cylinders = &h.cylinders;
    let force = |(i, c): (usize, &super::Cylinder)| {
        let g = 2 * cylinders.chamber_of(i);
        ps * (v[g] * c.cap_area_m2() - v[g + 1] * c.rod_area_m2())
    };
    cylinders.each.iter().enumerate().map(force).collect()
}

/// Each cylinder's pin-to-pin length with its series flexibility under the pressures' forces, m.
fn lengths_m(strokes: &CylinderStrokes, forces_n: &[f64]) -> PerCylinder {
    let n = strokes.strokes.len();
    let stretch = |i: usize| (0..n).map(|j| strokes.flexibility(i, j) * forces_n[j]).sum::<f64>();
    strokes.strokes.iter().enumerate().map(|(i, s)| s.position + stretch(i)).collect()
}

/// Rod forces (N, positive extending) at `strokes` with the scaled states `v`: the pressures'
/// force and, past its stroke, its end cap's.
pub fn rod_forces_n(h: &HydraulicDrive, strokes: &CylinderStrokes, v: &[f64]) -> PerCylinder {
    let mut forces = pressure_forces_n(h, v);
    let lengths = lengths_m(strokes, &forces);
    let outside = |(c, l): (&super::Cylinder, &f64)| !(0.0..=c.stroke_m).contains(&(l - c.closed_length_m));
    if h.cylinders.each.iter().zip(&lengths).any(outside) {
        forces = Columns::at(h, strokes, v).rod_forces_n(h);
    }
    forces
}

/// Each cylinder's pin-to-pin length with its series flexibility, m.
pub fn cylinder_lengths_m(h: &HydraulicDrive, strokes: &CylinderStrokes, v: &[f64]) -> PerCylinder {
    lengths_m(strokes, &pressure_forces_n(h, v))
}

/// Writes the rates of the scaled pressures and of the spool into `f` (module doc), and returns
/// the rod forces ([`rod_forces_n`]): one evaluation of the columns for both.
pub fn rates_and_rod_forces(
    h: &HydraulicDrive,
    strokes: &CylinderStrokes,
    command: f64,
    v: &[f64],
    f: &mut [f64],
) -> PerCylinder {
    let columns = Columns::at(h, strokes, v);
    let circuit = &h.circuit;
    let beta = circuit.bulk_modulus_pa / circuit.supply_pressure_pa;
    let mut displaced: SmallVec<[[f64; 2]; 2]> = SmallVec::from_elem([0.0; 2], h.cylinders.chambers());
    for (i, c) in h.cylinders.each.iter().enumerate() {
        let d = &mut displaced[h.cylinders.chamber_of(i)];
        d[0] += c.cap_area_m2() * columns.rates_m_s[i];
        d[1] += c.rod_area_m2() * columns.rates_m_s[i];
    }
    for (g, ((v1, v2), [q1, q2])) in columns.volumes_m3.iter().zip(&columns.flows_m3_s).enumerate() {
        f[2 * g] = beta / v1 * (q1 - displaced[g][0]);
        f[2 * g + 1] = beta / v2 * (q2 + displaced[g][1]);
    }
    let spool = spool_index(h);
    f[spool] = (command - v[spool]) / circuit.valve.spool_time_constant_s;
    columns.rod_forces_n(h)
}

/// The oil columns at one state.
struct Columns {
    /// Chamber volumes (cap, rod) per valve, m³.
    volumes_m3: SmallVec<[(f64, f64); 2]>,
    /// Flows into the chambers through each valve, relief included (cap, rod), m³/s.
    flows_m3_s: SmallVec<[[f64; 2]; 2]>,
    /// Each rod's force from its chamber pressures, N.
    forces_n: PerCylinder,
    /// Each cylinder's length with its series flexibility, m.
    lengths_m: PerCylinder,
    /// Each cylinder's rate of extension, m/s (module doc).
    rates_m_s: PerCylinder,
}

impl Columns {
    fn at(h: &HydraulicDrive, strokes: &CylinderStrokes, v: &[f64]) -> Self {
        let (cylinders, circuit) = (&h.cylinders, &h.circuit);
        let forces_n = pressure_forces_n(h, v);
        let lengths = lengths_m(strokes, &forces_n);
        let mut volumes: SmallVec<[(f64, f64); 2]> = SmallVec::from_elem((0.0, 0.0), cylinders.chambers());
        for (i, c) in cylinders.each.iter().enumerate() {
            let (v1, v2) = c.volumes_m3(lengths[i]);
            let g = &mut volumes[cylinders.chamber_of(i)];
            (g.0, g.1) = (g.0 + v1, g.1 + v2);
        }
        volumes.iter_mut().for_each(|(v1, v2)| (*v1, *v2) = (v1.max(1e-9), v2.max(1e-9)));
        let spool = v[spool_index(h)].clamp(-1.0, 1.0);
        let flows = (0..cylinders.chambers()).map(|g| circuit.flows_m3_s(spool, valve_pressures_pa(h, v, g)));
        let flows_m3_s: SmallVec<[[f64; 2]; 2]> = flows.collect();
        let rates_m_s = column_rates_m_s(h, strokes, &volumes, &flows_m3_s);
        Columns { volumes_m3: volumes, flows_m3_s, forces_n, lengths_m: lengths, rates_m_s }
    }

    /// The rod forces: the pressures' and, past a stroke, the end cap's (zero within it).
    fn rod_forces_n(self, h: &HydraulicDrive) -> PerCylinder {
        let mut forces = self.forces_n;
        for (i, c) in h.cylinders.each.iter().enumerate() {
            forces[i] += c.end_stop_force_n(self.lengths_m[i], self.rates_m_s[i]);
        }
        forces
    }
}

/// The rods' rates of extension through the series flexibility: (I + C B) ṡe = ṡ + C b₀ (module
/// doc), solved by Gaussian elimination (a few cylinders at most).
fn column_rates_m_s(
    h: &HydraulicDrive,
    strokes: &CylinderStrokes,
    volumes_m3: &[(f64, f64)],
    flows_m3_s: &[[f64; 2]],
) -> PerCylinder {
    let rates: PerCylinder = strokes.strokes.iter().map(|s| s.rate).collect();
    if strokes.flexibility_m_per_n.iter().all(|&c| c == 0.0) {
        return rates;
    }
    let (cylinders, beta) = (&h.cylinders.each, h.circuit.bulk_modulus_pa);
    let n = cylinders.len();
    let areas = |i: usize| (cylinders[i].cap_area_m2(), cylinders[i].rod_area_m2());
    if n == 1 {
        // The system is one equation: ṡe = (ṡ + c Ḟ₀) / (1 + c k), k the oil column's spring.
        let ((a1, a2), (v1, v2), [q1, q2], c) = (areas(0), volumes_m3[0], flows_m3_s[0], strokes.flexibility(0, 0));
        let (force_rate, column) = (beta * (a1 * q1 / v1 - a2 * q2 / v2), beta * (a1 * a1 / v1 + a2 * a2 / v2));
        return PerCylinder::from_elem((rates[0] + c * force_rate) / (1.0 + c * column), 1);
    }
    let group = |i: usize| h.cylinders.chamber_of(i);
    // Ḟ_i = b₀_i − Σ_j B_ij ṡe_j.
    let b0 = |i: usize| {
        let ((a1, a2), (v1, v2), [q1, q2]) = (areas(i), volumes_m3[group(i)], flows_m3_s[group(i)]);
        beta * (a1 * q1 / v1 - a2 * q2 / v2)
    };
    let b = |i: usize, j: usize| {
        if group(i) != group(j) {
            return 0.0;
        }
        let ((a1i, a2i), (a1j, a2j), (v1, v2)) = (areas(i), areas(j), volumes_m3[group(i)]);
        beta * (a1i * a1j / v1 + a2i * a2j / v2)
    };
    let mut matrix: SmallVec<[f64; 4]> = SmallVec::from_elem(0.0, n * n);
    let mut rhs = rates;
    for i in 0..n {
        for j in 0..n {
            let cb: f64 = (0..n).map(|k| strokes.flexibility(i, k) * b(k, j)).sum();
            matrix[i * n + j] = f64::from(u8::from(i == j)) + cb;
        }
        rhs[i] += (0..n).map(|k| strokes.flexibility(i, k) * b0(k)).sum::<f64>();
    }
    solve_in_place(n, &mut matrix, &mut rhs);
    rhs
}

/// Solves the n × n row-major `matrix` · x = `rhs` in place (x in `rhs`), partial pivoting. The
/// matrix is I plus a positive semi-definite product of flexibility and oil stiffness, never
/// singular.
fn solve_in_place(n: usize, matrix: &mut [f64], rhs: &mut [f64]) {
    for col in 0..n {
        let pivot = (col..n).max_by(|&a, &b| matrix[a * n + col].abs().total_cmp(&matrix[b * n + col].abs()));
        let pivot = pivot.unwrap_or(col);
        if pivot != col {
            for k in 0..n {
                matrix.swap(col * n + k, pivot * n + k);
            }
            rhs.swap(col, pivot);
        }
        for row in col + 1..n {
            let factor = matrix[row * n + col] / matrix[col * n + col];
            for k in col..n {
                matrix[row * n + k] -= factor * matrix[col * n + k];
            }
            rhs[row] -= factor * rhs[col];
        }
    }
    for row in (0..n).rev() {
        let known: f64 = (row + 1..n).map(|k| matrix[row * n + k] * rhs[k]).sum();
        rhs[row] = (rhs[row] - known) / matrix[row * n + row];
    }
}

#[cfg(test)]
mod tests {
    use super::solve_in_place;

    #[test]
    fn elimination_solves_a_pivoting_system() {
        // [[0, 2, 1], [1, 1, 0], [3, 0, 1]] x = [7, 3, 6] has x = (1, 2, 3) and needs a row swap.
        let mut m = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let mut b = [7.0, 3.0, 6.0];
        solve_in_place(3, &mut m, &mut b);
        for (x, e) in b.iter().zip([1.0, 2.0, 3.0]) {
            assert!((x - e).abs() < 1e-12, "{b:?}");
        }
    }
}
