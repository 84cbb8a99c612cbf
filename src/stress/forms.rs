//! Section forces as linear forms of one per-step vector, built once, read with one product.
//!
//! The d'Alembert and gravity load on a mass point of the arm (station x, elastic rows u, v, φ
//! over q) in the hub frame is −m (a − g_b), with (`docs/model.md`, `sensor::probe`)
//!
//! ```text
//! a_x − g_bx = ü − 2θ̇ v̇ − θ̈ v − θ̇² (x + u) + g sin θ
//! a_y − g_by = v̈ + 2θ̇ u̇ + θ̈ (x + u) − θ̇² v + g cos θ
//! ```
//!
//! Every term is a hub scalar (1, θ̇, θ̈, θ̇², g cos θ, g sin θ) times q, q̇ or q̈, or a hub scalar
//! alone. The moment of such a load about a section point, (r_p − r_s) × F, adds the deflections'
//! lever on the load's zeroth-order part (x θ̈ + g cos θ across, g sin θ − x θ̇² along). Products
//! of two elastic quantities are left out (their relative size is the deflection over the
//! length, 2·10⁻³ on the shipped arm), so each section force is a fixed row over
//!
//! ```text
//! z = [ q̈ | θ̇ q̇ | q | θ̈ q | θ̇² q | g cos θ q | g sin θ q | θ̈, θ̇², g cos θ, g sin θ ]
//! ```
//!
//! The `q` block carries the elastic forces a curvature gives (a string's span moments). A form
//! may also read `extra` values after z: the loads a flexible string puts on its hands, which
//! are themselves forms over z, read first (the arm's sections then need only the arm's
//! coordinates, a fraction of a string's).

use nalgebra::DVector;

use crate::arm::StationRows;
use crate::drive::DriveState;

/// A hub scalar that multiplies loads: θ̈, θ̇², g cos θ, g sin θ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    /// θ̈, rad/s².
    Accel = 0,
    /// θ̇², rad²/s².
    RateSquared = 1,
    /// g cos θ, m/s².
    GravityCos = 2,
    /// g sin θ, m/s².
    GravitySin = 3,
}

const SCALARS: [Scalar; 4] = [Scalar::Accel, Scalar::RateSquared, Scalar::GravityCos, Scalar::GravitySin];

/// A block of z over the elastic coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Block {
    /// q̈.
    Accel,
    /// θ̇ q̇.
    RateTimesVelocity,
    /// q.
    Displacement,
    /// A hub scalar times q.
    Scaled(Scalar),
}

/// The layout of z for `n` elastic coordinates, and `extra` values read after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Elastic coordinates.
    pub n: usize,
    /// Values after z.
    pub extra: usize,
}

/// A row over z.
pub type Form = DVector<f64>;

impl Layout {
    /// Length of z.
    pub fn z_len(&self) -> usize {
        7 * self.n + SCALARS.len()
    }

    /// Length of a form: z and the extra values.
    pub fn form_len(&self) -> usize {
        self.z_len() + self.extra
    }

    /// A form reading extra value `i` alone.
    pub fn extra_value(&self, i: usize) -> Form {
        let mut f = self.zero();
        f[self.z_len() + i] = 1.0;
        f
    }

    /// A zero form.
    pub fn zero(&self) -> Form {
        Form::zeros(self.form_len())
    }

    fn block_start(&self, block: Block) -> usize {
        self.n
            * match block {
                Block::Accel => 0,
                Block::RateTimesVelocity => 1,
                Block::Displacement => 2,
                Block::Scaled(s) => 3 + s as usize,
            }
    }

    fn scalar_index(&self, scalar: Scalar) -> usize {
        7 * self.n + scalar as usize
    }

    /// z at a state: the hub (rate, acceleration; its angle's sine and cosine `sin_cos`, which
    /// the caller has at hand), gravity `g` and q, q̇, q̈.
    #[allow(clippy::too_many_arguments)]
    pub fn fill(
        &self,
        z: &mut [f64],
        hub: &DriveState,
        (s, c): (f64, f64),
        g: f64,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) {
        let (w, alpha) = (hub.rate_rad_s, hub.accel_rad_s2);
        let scalars = [alpha, w * w, g * c, g * s];
        let n = self.n;
        let (blocks, tail) = z.split_at_mut(7 * n);
        let mut chunks = blocks.chunks_exact_mut(n.max(1));
        if n > 0 {
            chunks.next().expect("q̈").copy_from_slice(qdd);
            chunks.next().expect("θ̇ q̇").iter_mut().zip(qd).for_each(|(z, v)| *z = w * v);
            chunks.next().expect("q").copy_from_slice(q);
            for (chunk, scale) in chunks.zip(scalars) {
                chunk.iter_mut().zip(q).for_each(|(z, v)| *z = scale * v);
            }
        }
        tail.copy_from_slice(&scalars);
    }

    /// Adds `coefficient` × `row` (over q) into `block` of `form`.
    pub fn add_row(&self, form: &mut Form, block: Block, coefficient: f64, row: &DVector<f64>) {
        let start = self.block_start(block);
        form.rows_mut(start, self.n).axpy(coefficient, row, 1.0);
    }

    /// Adds `coefficient` to the entry of a hub scalar.
    pub fn add_scalar(&self, form: &mut Form, scalar: Scalar, coefficient: f64) {
        form[self.scalar_index(scalar)] += coefficient;
    }

    /// A form's zeroth-order part: its coefficients of the hub scalars alone.
    pub fn zeroth(&self, form: &Form) -> [f64; 4] {
        SCALARS.map(|s| form[self.scalar_index(s)])
    }

    /// Adds `row` (an elastic quantity over q) times a zeroth-order part `scalars`, scaled by
    /// `sign`: the first-order product of a small lever and an O(1) load.
    pub fn add_lever(&self, form: &mut Form, row: &DVector<f64>, scalars: [f64; 4], sign: f64) {
        for (scalar, coefficient) in SCALARS.iter().zip(scalars) {
            if coefficient != 0.0 {
                self.add_row(form, Block::Scaled(*scalar), sign * coefficient, row);
            }
        }
    }
}

/// A point of the arm (or of a string) a load acts at: station and elastic rows (u, v, φ).
#[derive(Debug, Clone)]
pub struct Point {
    /// Hub-frame x of the undeformed point, m.
    pub x_m: f64,
    /// Its rows over q.
    pub rows: StationRows,
}

impl Point {
    /// Where the point is at elastic coordinates `q`: hub frame (x + u, v), m.
    pub fn deformed_m(&self, q: &DVector<f64>) -> [f64; 2] {
        let [u, v, _] = self.rows.displacement(q);
        [self.x_m + u, v]
    }

    fn u(&self) -> &DVector<f64> {
        &self.rows.0[0]
    }

    fn v(&self) -> &DVector<f64> {
        &self.rows.0[1]
    }

    /// The slope row.
    pub fn phi(&self) -> &DVector<f64> {
        &self.rows.0[2]
    }
}

/// A force (hub-frame x, y) and a moment about its point, each a form over z.
#[derive(Debug, Clone)]
pub struct Action {
    /// Force along the hub frame's x, N.
    pub fx: Form,
    /// Force along the hub frame's y, N.
    pub fy: Form,
    /// Moment about the point it acts at, N·m.
    pub m: Form,
}

impl Action {
    /// No force.
    pub fn zero(layout: &Layout) -> Self {
        Action { fx: layout.zero(), fy: layout.zero(), m: layout.zero() }
    }

    /// The d'Alembert and gravity load on a mass `mass_kg` with rotary inertia
    /// `rotary_inertia_kg_m2` at `point`.
    pub fn of_mass(layout: &Layout, point: &Point, mass_kg: f64, rotary_inertia_kg_m2: f64) -> Self {
        let (x, m) = (point.x_m, mass_kg);
        let mut a = Action::zero(layout);
        // F = −m (a − g_b), term by term.
        layout.add_row(&mut a.fx, Block::Accel, -m, point.u());
        layout.add_row(&mut a.fx, Block::RateTimesVelocity, 2.0 * m, point.v());
        layout.add_row(&mut a.fx, Block::Scaled(Scalar::Accel), m, point.v());
        layout.add_row(&mut a.fx, Block::Scaled(Scalar::RateSquared), m, point.u());
        layout.add_scalar(&mut a.fx, Scalar::RateSquared, m * x);
        layout.add_scalar(&mut a.fx, Scalar::GravitySin, -m);
        layout.add_row(&mut a.fy, Block::Accel, -m, point.v());
        layout.add_row(&mut a.fy, Block::RateTimesVelocity, -2.0 * m, point.u());
        layout.add_row(&mut a.fy, Block::Scaled(Scalar::Accel), -m, point.u());
        layout.add_row(&mut a.fy, Block::Scaled(Scalar::RateSquared), m, point.v());
        layout.add_scalar(&mut a.fy, Scalar::Accel, -m * x);
        layout.add_scalar(&mut a.fy, Scalar::GravityCos, -m);
        // The couple of its rotary inertia, −J (θ̈ + φ̈).
        if rotary_inertia_kg_m2 != 0.0 {
            layout.add_scalar(&mut a.m, Scalar::Accel, -rotary_inertia_kg_m2);
            layout.add_row(&mut a.m, Block::Accel, -rotary_inertia_kg_m2, point.phi());
        }
        a
    }

    /// Adds `other` acting at `from`, moved to act at `to`: the same force, and its moment about
    /// `to` (the lever (x_from − x_to + Δu, Δv) to first order).
    pub fn add_moved(&mut self, layout: &Layout, other: &Action, from: &Point, to: &Point) {
        self.add_moved_reading(layout, other, other, from, to);
    }

    /// [`Self::add_moved`] for an action read as `reading` (the extra values that hold it) whose
    /// zeroth-order part is `other`'s: the levers need the load's O(1) part as a form over z.
    pub fn add_moved_reading(&mut self, layout: &Layout, reading: &Action, other: &Action, from: &Point, to: &Point) {
        self.fx += &reading.fx;
        self.fy += &reading.fy;
        self.m += &reading.m;
        self.m.axpy(from.x_m - to.x_m, &reading.fy, 1.0);
        let du = from.u() - to.u();
        let dv = from.v() - to.v();
        layout.add_lever(&mut self.m, &du, layout.zeroth(&other.fy), 1.0);
        layout.add_lever(&mut self.m, &dv, layout.zeroth(&other.fx), -1.0);
    }

    /// Adds `other`, acting at the same point.
    pub fn add(&mut self, other: &Action) {
        self.fx += &other.fx;
        self.fy += &other.fy;
        self.m += &other.m;
    }

    /// The moment about `to` of this action, which acts about the pivot's point (x = 0, no
    /// displacement): M − r_to × F to first order.
    pub fn moment_about(&self, layout: &Layout, to: &Point) -> Form {
        let mut m = self.m.clone();
        m.axpy(-to.x_m, &self.fy, 1.0);
        layout.add_lever(&mut m, to.u(), layout.zeroth(&self.fy), -1.0);
        layout.add_lever(&mut m, to.v(), layout.zeroth(&self.fx), 1.0);
        m
    }

    /// The axial force (tension positive) this action, applied to the part outboard of a section
    /// at `at`, puts through it: F · t with t = (1, φ) to first order.
    pub fn axial_through(&self, layout: &Layout, at: &Point) -> Form {
        let mut n = self.fx.clone();
        layout.add_lever(&mut n, at.phi(), layout.zeroth(&self.fy), 1.0);
        n
    }

    /// The action read from extra values `first`, `first + 1`, `first + 2` (x, y, moment).
    pub fn reading(layout: &Layout, first: usize) -> Self {
        Action { fx: layout.extra_value(first), fy: layout.extra_value(first + 1), m: layout.extra_value(first + 2) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(x_m: f64, u: f64, v: f64, phi: f64) -> Point {
        let r = |a: f64| DVector::from_vec(vec![a, 0.3 * a]);
        Point { x_m, rows: StationRows([r(u), r(v), r(phi)]) }
    }

    /// Evaluates a form at a state.
    fn at(layout: &Layout, form: &Form, hub: &DriveState, g: f64, q: &[f64], qd: &[f64], qdd: &[f64]) -> f64 {
        let mut z = vec![0.0; layout.z_len()];
        layout.fill(&mut z, hub, hub.angle_rad.sin_cos(), g, q, qd, qdd);
        form.dot(&DVector::from_vec(z))
    }

    #[test]
    fn a_mass_loads_its_section_as_the_exact_kinematics_do_to_first_order() {
        // The exact d'Alembert + gravity load of a mass point and its moment about a section
        // point, evaluated from the full kinematics, against the forms at a small deflection.
        let layout = Layout { n: 2, extra: 0 };
        let (p, s) = (point(6.0, 0.2, 1.0, 0.15), point(2.0, 0.05, 0.2, 0.08));
        let hub = DriveState { angle_rad: 0.7, rate_rad_s: 0.3, accel_rad_s2: -0.4, jerk_rad_s3: 0.0 };
        let g = 9.81;
        let (m, j) = (150.0, 12.0);
        let action = Action::of_mass(&layout, &p, m, j);
        let mut about = Action::zero(&layout);
        about.add_moved(&layout, &action, &p, &s);
        for scale in [1e-3, 1e-4] {
            let (q, qd, qdd) = ([0.4 * scale, -0.3 * scale], [2.0 * scale, 0.5 * scale], [30.0 * scale, -9.0 * scale]);
            let disp = |pt: &Point, x: &[f64]| pt.rows.displacement(&DVector::from_column_slice(x));
            let ([u, v, _], [ud, vd, _], [udd, vdd, phidd]) = (disp(&p, &q), disp(&p, &qd), disp(&p, &qdd));
            let (w, a) = (hub.rate_rad_s, hub.accel_rad_s2);
            let (sn, cs) = hub.angle_rad.sin_cos();
            let (rx, ry) = (p.x_m + u, v);
            let fx = -m * (udd - 2.0 * w * vd - a * ry - w * w * rx + g * sn);
            let fy = -m * (vdd + 2.0 * w * ud + a * rx - w * w * ry + g * cs);
            let [us, vs, _] = disp(&s, &q);
            let moment = (rx - s.x_m - us) * fy - (ry - vs) * fx - j * (a + phidd);
            let eval = |f: &Form| at(&layout, f, &hub, g, &q, &qd, &qdd);
            // Second-order terms: (elastic)² relative to the loads, so the error falls as scale².
            let load_scale = m * (g + w * w * p.x_m + a.abs() * p.x_m);
            assert!((eval(&action.fx) - fx).abs() < 50.0 * scale * scale * load_scale, "{scale}");
            assert!((eval(&action.fy) - fy).abs() < 50.0 * scale * scale * load_scale, "{scale}");
            assert!((eval(&about.m) - moment).abs() < 500.0 * scale * scale * load_scale, "{scale}");
        }
    }
}
