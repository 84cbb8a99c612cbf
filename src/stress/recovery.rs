//! Section forces along the arm, the pivot's reaction and the hands' grip loads, by force
//! summation: the internal force at a section balances every load on the part of the machine
//! outboard of it — the d'Alembert and gravity loads of its mass (the arm's, at four Gauss points
//! per element, and the carried bodies'), the pads' and structures' contact forces, the
//! cylinder's rod force at its pin, and a held string's load at its hands.
//!
//! Summation needs the accelerations only, never the curvature, so a few modes give it right
//! where a load is concentrated (a hand, a pad): the curvature of a truncated modal sum
//! converges slowly there. The one place curvature enters is a string's span between two hands,
//! which is statically indeterminate: its end moments are EI v″ of the string at the hands (the
//! string's own coordinates), its end shears follow from the span's balance, and its axial load
//! divides at the span's midpoint (as in the model's geometric stiffness) plus EA times the
//! span's stretch.
//!
//! The inertial and gravity parts are fixed rows over one per-step vector ([`super::forms`]),
//! evaluated with one matrix product per step; point loads (contact, cylinder) are added exactly.

use nalgebra::{DMatrix, DVector};

use super::forms::{Action, Block, Form, Layout, Point};
use crate::arm::ArmModel;
use crate::arm::StationRows;
use crate::beam::GAUSS_4;
use crate::model::HeldString;
use crate::point_load::{Hub, PointLoad};
use crate::sensor::probe::ArmState;

/// Which side of a node a section is cut at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Just toward the pivot: a load at the node is outboard.
    Inboard,
    /// Just toward the tip: a load at the node is inboard.
    Outboard,
}

/// A section of the arm where the stress is recovered.
#[derive(Debug, Clone)]
pub struct Station {
    /// The section's point.
    pub point: Point,
    /// Which side of its node it is cut at.
    pub side: Side,
    /// The arm segment whose section it is.
    pub segment: usize,
}

impl Station {
    /// Station along the arm, m.
    pub fn x_m(&self) -> f64 {
        self.point.x_m
    }

    /// Whether a load at arm station `x_m` is on the outboard part.
    fn has_outboard(&self, x_m: f64, tolerance_m: f64) -> bool {
        match self.side {
            Side::Inboard => x_m > self.x_m() - tolerance_m,
            Side::Outboard => x_m > self.x_m() + tolerance_m,
        }
    }
}

/// A hand holding a flexible string: where, and how its span to the next hand is cut.
#[derive(Debug, Clone)]
struct Hand {
    point: Point,
}

/// A span of a flexible string between two hands, for loads that land on it at a step.
#[derive(Debug, Clone, Copy)]
struct Span {
    /// Its hands (indices into the hands).
    left: usize,
    right: usize,
}

/// Where the held string's contact loads go, by the part of the string they land on.
#[derive(Debug, Clone)]
struct StringRouting {
    hands: Vec<Hand>,
    spans: Vec<Span>,
}

/// The recovery of section forces, pivot and hand loads on one arm model.
#[derive(Debug, Clone)]
pub struct SectionRecovery {
    layout: Layout,
    /// Sections, hub outwards.
    pub stations: Vec<Station>,
    /// The string's loads on its hands (x, y, moment per hand) over z.
    hand_rows: DMatrix<f64>,
    /// Each station's N, then each one's M, then the pivot's force on the arm (x, y, hub
    /// frame), over the entries of z in `z_support`, then the hand loads in `hand_support` (the
    /// arm's sections do not see a string's own coordinates but through its hands).
    rows: DMatrix<f64>,
    z_support: Vec<usize>,
    hand_support: Vec<usize>,
    string: Option<StringRouting>,
    tolerance_m: f64,
    /// A rigid string's hands, and where its contact loads reach the arm.
    rigid: Option<RigidGrip>,
}

/// A rigid string's hands: pins on the arm (a rigid string between two clamps is statically
/// indeterminate; pins are the determinate reading). The outer two share the transverse load by
/// the lever rule and the axial load as the string's length lies either side of their
/// midpoint; a hand between them carries nothing; a single hand carries everything, moment
/// included.
#[derive(Debug, Clone)]
struct RigidGrip {
    centre_m: f64,
    hands: Vec<Point>,
    /// The outer hand's share of a load along the string.
    axial_outer_share: f64,
}

/// Steps read before their linear part is evaluated, as one matrix product: the steps a
/// [`super::StressProbe`] records between two hand-overs.
pub const CHUNK_STEPS: usize = 512;

/// The readings waiting for their linear part: z of each, the step's point loads.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    z: DMatrix<f64>,
    hands: DMatrix<f64>,
    read: DMatrix<f64>,
    pending: usize,
    loads: Vec<PointLoad<Hub>>,
}

impl SectionRecovery {
    /// The recovery on `arm` at the sections `stations` (built by [`stations_of`]); `held` is the
    /// held string, read for its hands' loads where the arm lumps it (no string member).
    pub fn new(arm: &ArmModel, stations: Vec<Station>, held: Option<&HeldString>) -> Self {
        let hand_count = arm.beam.member.as_ref().map_or(0, |m| m.spec.clamps_m.len());
        let layout = Layout { n: arm.elastic_dofs(), extra: 3 * hand_count };
        let tolerance_m = 1e-9 * arm.length_m();
        let masses = arm_mass_points(arm, &layout);
        let (mut hand_actions, string) = match &arm.beam.member {
            Some(member) => {
                let (actions, routing) = string_hand_loads(arm, &layout, member);
                (actions, Some(routing))
            }
            None => (Vec::new(), None),
        };
        let rigid = held.filter(|_| string.is_none()).map(|held| {
            let (actions, grip) = rigid_hand_loads(arm, &layout, held);
            hand_actions = actions;
            grip
        });
        let hands: Vec<&Hand> = string.iter().flat_map(|s| &s.hands).collect();
        let readings: Vec<Action> = (0..hand_count).map(|h| Action::reading(&layout, 3 * h)).collect();
        // The loads outboard of each station, summed once from the tip inward about the pivot's
        // point and moved to each station: M_s = M_0 − r_s × F.
        let origin = Point { x_m: 0.0, rows: StationRows([0, 1, 2].map(|_| DVector::zeros(layout.n))) };
        let mut loads: Vec<(f64, Action)> = masses
            .iter()
            .map(|(x, point, action)| {
                let mut about_origin = Action::zero(&layout);
                about_origin.add_moved(&layout, action, point, &origin);
                (*x, about_origin)
            })
            .collect();
        for ((hand, action), reading) in hands.iter().zip(&hand_actions).zip(&readings) {
            let mut about_origin = Action::zero(&layout);
            about_origin.add_moved_reading(&layout, reading, action, &hand.point, &origin);
            loads.push((hand.point.x_m, about_origin));
        }
        loads.sort_by(|a, b| b.0.total_cmp(&a.0));
        let mut outboard = Action::zero(&layout);
        let mut next = 0;
        let count = stations.len();
        let mut forms: Vec<Form> = vec![layout.zero(); 2 * count];
        for (i, station) in stations.iter().enumerate().rev() {
            while next < loads.len() && station.has_outboard(loads[next].0, tolerance_m) {
                outboard.add(&loads[next].1);
                next += 1;
            }
            forms[i] = outboard.axial_through(&layout, &station.point);
            forms[count + i] = -outboard.moment_about(&layout, &station.point);
        }
        // The pivot holds everything: its force on the arm balances the loads on the whole.
        let mut whole = Action::zero(&layout);
        for action in masses.iter().map(|(_, _, a)| a).chain(&readings) {
            whole.fx += &action.fx;
            whole.fy += &action.fy;
        }
        forms.push(-whole.fx);
        forms.push(-whole.fy);
        let support: Vec<usize> = (0..layout.form_len()).filter(|&c| forms.iter().any(|f| f[c] != 0.0)).collect();
        let rows = DMatrix::from_fn(forms.len(), support.len(), |r, c| forms[r][support[c]]);
        let (z_support, hand_support): (Vec<usize>, Vec<usize>) =
            support.into_iter().partition(|&c| c < layout.z_len());
        let hand_support = hand_support.into_iter().map(|c| c - layout.z_len()).collect();
        let hand_forms: Vec<&Form> = hand_actions.iter().flat_map(|a| [&a.fx, &a.fy, &a.m]).collect();
        let hand_rows = DMatrix::from_fn(hand_forms.len(), layout.z_len(), |r, c| hand_forms[r][c]);
        SectionRecovery { layout, stations, hand_rows, rows, z_support, hand_support, string, tolerance_m, rigid }
    }

    /// Hands of the held string, in the order of their loads in a reading.
    pub fn hand_count(&self) -> usize {
        match (&self.string, &self.rigid) {
            (Some(s), _) => s.hands.len(),
            (None, Some(r)) => r.hands.len(),
            (None, None) => 0,
        }
    }

    /// Values in one step's reading: each station's axial force (N), then each one's bending
    /// moment (N·m; two blocks, so that a step's stations are read as vectors), the pivot's
    /// force on the arm (x, y hub frame, N), per hand of the held string the string's
    /// load on it (x, y hub frame, N; moment about it, N·m).
    pub fn width(&self) -> usize {
        self.rows.nrows() + self.hand_rows.nrows()
    }

    /// Where the pivot's force starts in a reading.
    pub fn pivot_index(&self) -> usize {
        2 * self.stations.len()
    }

    /// Where hand `h`'s load starts in a reading.
    pub fn hand_index(&self, h: usize) -> usize {
        2 * self.stations.len() + 2 + 3 * h
    }

    /// Reads the state `state` (its hub angle's sine and cosine `sin_cos`) under gravity `g`,
    /// with point loads on the arm `on_arm` and on
    /// the held string `on_string`, into `out` ([`Self::width`] zeros): the point loads' share
    /// now, the rest at the next [`Self::flush`] of the readings in `scratch`, which must come
    /// within [`CHUNK_STEPS`] readings.
    #[allow(clippy::too_many_arguments)]
    pub fn stage(
        &self,
        state: &ArmState,
        sin_cos: (f64, f64),
        g: f64,
        on_arm: &[PointLoad<Hub>],
        on_string: &[PointLoad<Hub>],
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        if scratch.z.nrows() != self.layout.z_len() {
            scratch.z = DMatrix::zeros(self.layout.z_len(), CHUNK_STEPS);
            scratch.hands = DMatrix::zeros(self.hand_rows.nrows(), CHUNK_STEPS);
            scratch.read = DMatrix::zeros(self.rows.ncols(), CHUNK_STEPS);
            scratch.pending = 0;
        }
        let z_len = self.layout.z_len();
        let column = &mut scratch.z.as_mut_slice()[scratch.pending * z_len..(scratch.pending + 1) * z_len];
        self.layout.fill(column, &state.hub, sin_cos, g, state.q.as_slice(), state.qd.as_slice(), state.qdd.as_slice());
        scratch.pending += 1;
        scratch.loads.clear();
        scratch.loads.extend_from_slice(on_arm);
        for load in on_string {
            self.route_string_load(state, load, &mut scratch.loads, out);
        }
        for load in &scratch.loads {
            self.add_point_load(state, load, out);
        }
    }

    /// Adds the linear part of the staged readings to the last of `values`, `stride` values a
    /// step (each step's reading first in its stride).
    pub fn flush(&self, scratch: &mut Scratch, values: &mut [f64], stride: usize) {
        let p = scratch.pending;
        if p == 0 {
            return;
        }
        scratch.pending = 0;
        let z_len = self.layout.z_len();
        scratch.hands.columns_mut(0, p).gemm(1.0, &self.hand_rows, &scratch.z.columns(0, p), 0.0);
        let (z, hands, read) = (scratch.z.as_slice(), scratch.hands.as_slice(), scratch.read.as_mut_slice());
        let height = self.hand_rows.nrows();
        let columns = z.chunks_exact(z_len).zip(hands.chunks_exact(height.max(1)).chain(std::iter::repeat(&[][..])));
        for ((z, hands), read) in columns.zip(read.chunks_exact_mut(self.rows.ncols().max(1))).take(p) {
            let (from_z, from_hands) = read.split_at_mut(self.z_support.len());
            from_z.iter_mut().zip(&self.z_support).for_each(|(r, &c)| *r = z[c]);
            from_hands.iter_mut().zip(&self.hand_support).for_each(|(r, &c)| *r = hands[c]);
        }
        let start = values.len() - p * stride;
        let rows = self.rows.nrows();
        let mut sections =
            nalgebra::DMatrixViewMut::from_slice_with_strides_mut(&mut values[start..], rows, p, 1, stride);
        sections.gemm(1.0, &self.rows, &scratch.read.columns(0, p), 1.0);
        let (hands, height) = (scratch.hands.as_slice(), self.hand_rows.nrows());
        for (k, step) in values[start..].chunks_mut(stride).enumerate() {
            let loads = &mut step[rows..rows + height];
            loads.iter_mut().zip(&hands[k * height..(k + 1) * height]).for_each(|(v, h)| *v += h);
        }
    }

    /// A contact load on the held string, as the loads it puts on the arm: a rigid string's at
    /// its centre station; a flexible one's through the hand of its overhang, or shared by the
    /// two hands of its span (shear by the lever about each, axial by the span's half).
    fn route_string_load(
        &self,
        state: &ArmState,
        load: &PointLoad<Hub>,
        arm: &mut Vec<PointLoad<Hub>>,
        out: &mut [f64],
    ) {
        let Some(routing) = &self.string else {
            if let Some(rigid) = &self.rigid {
                self.share_on_rigid_hands(state, rigid, load, out);
            }
            let station_m = self.rigid.as_ref().map_or(load.station_m, |r| r.centre_m);
            arm.push(load.at_station(station_m));
            return;
        };
        let x = load.station_m;
        let position = |h: usize| routing.hands[h].point.deformed_m(state.q);
        let mut to_hand = |h: usize, point_m: [f64; 2], force_n: [f64; 2]| {
            let r = position(h);
            let k = self.hand_index(h);
            out[k] += force_n[0];
            out[k + 1] += force_n[1];
            out[k + 2] += cross(sub(point_m, r), force_n);
            arm.push(PointLoad::new(routing.hands[h].point.x_m, point_m, force_n));
        };
        let span =
            routing.spans.iter().find(|s| x > routing.hands[s.left].point.x_m && x < routing.hands[s.right].point.x_m);
        match span {
            None => {
                let last = routing.hands.len() - 1;
                let h = if x <= routing.hands[0].point.x_m { 0 } else { last };
                to_hand(h, load.point_m, load.force_n);
            }
            Some(span) => {
                let (left, right) = (position(span.left), position(span.right));
                let length = right[0] - left[0];
                let mid = 0.5 * (routing.hands[span.left].point.x_m + routing.hands[span.right].point.x_m);
                // The right hand takes the shear that balances the load's moment about the left,
                // and the axial part of a load beyond the midpoint.
                let shear = cross(sub(load.point_m, left), load.force_n) / length;
                let axial = if x > mid { load.force_n[0] } else { 0.0 };
                let on_right = [axial, shear];
                let on_left = [load.force_n[0] - axial, load.force_n[1] - shear];
                to_hand(span.right, right, on_right);
                to_hand(span.left, left, on_left);
            }
        }
    }

    /// A contact load on a rigid string, shared by its hands as [`RigidGrip`] says.
    fn share_on_rigid_hands(&self, state: &ArmState, rigid: &RigidGrip, load: &PointLoad<Hub>, out: &mut [f64]) {
        let (first, last) = (0, rigid.hands.len() - 1);
        let first_at = rigid.hands[first].deformed_m(state.q);
        let mut to_hand = |h: usize, force_n: [f64; 2], moment_n_m: f64| {
            let k = self.hand_index(h);
            out[k] += force_n[0];
            out[k + 1] += force_n[1];
            out[k + 2] += moment_n_m;
        };
        let about_first = cross(sub(load.point_m, first_at), load.force_n);
        if first == last {
            to_hand(first, load.force_n, about_first);
            return;
        }
        let length = rigid.hands[last].deformed_m(state.q)[0] - first_at[0];
        let outer = [rigid.axial_outer_share * load.force_n[0], about_first / length];
        to_hand(last, outer, 0.0);
        to_hand(first, sub(load.force_n, outer), 0.0);
    }

    /// Adds a point load on the arm to every section it is outboard of, and to the pivot.
    fn add_point_load(&self, state: &ArmState, load: &PointLoad<Hub>, out: &mut [f64]) {
        let pivot = self.pivot_index();
        out[pivot] -= load.force_n[0];
        out[pivot + 1] -= load.force_n[1];
        let (axial, moment) = out.split_at_mut(self.stations.len());
        for ((station, axial), moment) in self.stations.iter().zip(axial).zip(moment) {
            if !station.has_outboard(load.station_m, self.tolerance_m) {
                continue;
            }
            let [u, v, phi] = station.point.rows.displacement(state.q);
            let lever = sub(load.point_m, [station.x_m() + u, v]);
            let (s, c) = phi.sin_cos();
            *axial += c * load.force_n[0] + s * load.force_n[1];
            *moment -= cross(lever, load.force_n) + load.couple_n_m;
        }
    }
}

/// The arm's mass as loaded points: four Gauss points per element and the carried bodies, each
/// with its station, point and load.
fn arm_mass_points(arm: &ArmModel, layout: &Layout) -> Vec<(f64, Point, Action)> {
    let point = |x_m: f64| arm_point(arm, x_m);
    let mut out = Vec::new();
    for element in &arm.beam.elements {
        for (xi, weight) in GAUSS_4 {
            let p = point(element.x0_m + xi * element.length_m);
            let action = Action::of_mass(layout, &p, weight * element.length_m * element.mass_per_length_kg_m, 0.0);
            out.push((p.x_m, p, action));
        }
    }
    for mass in &arm.beam.spec.masses {
        let p = point(mass.position_m);
        let action = Action::of_mass(layout, &p, mass.mass_kg, mass.rotary_inertia_kg_m2);
        out.push((p.x_m, p, action));
    }
    out
}

/// A flexible string's load on each hand (as an action at the hand's point) and the routing of
/// its contact loads. Overhangs hang on their hand; a span between two hands passes its load to
/// them through its end moments M = −EI v″ (upper face in tension positive), its balance of
/// moments for the shear, and for the axial force the share of each half plus EA Δu / L.
fn string_hand_loads(
    arm: &ArmModel,
    layout: &Layout,
    member: &crate::beam::MemberModel,
) -> (Vec<Action>, StringRouting) {
    let string_point = |x_m: f64| {
        let x = x_m.clamp(member.spec.start_m, member.spec.end_m());
        let e = member.elements.iter().position(|el| x <= el.x0_m + el.length_m).unwrap_or(member.elements.len() - 1);
        let el = &member.elements[e];
        let shape = crate::beam::shape_rows((x - el.x0_m) / el.length_m, el.length_m);
        Point { x_m, rows: project(arm, &member.element_dofs[e], [&shape.u, &shape.v, &shape.dv]) }
    };
    let clamps = &member.spec.clamps_m;
    let hands: Vec<Hand> = clamps.iter().map(|&x| Hand { point: string_point(x) }).collect();
    let mut actions: Vec<Action> = hands.iter().map(|_| Action::zero(layout)).collect();
    let points: Vec<(Point, Action)> = member
        .elements
        .iter()
        .flat_map(|e| GAUSS_4.map(|(xi, w)| (e.x0_m + xi * e.length_m, w * e.length_m * e.mass_per_length_kg_m)))
        .map(|(x, mass)| {
            let p = string_point(x);
            let action = Action::of_mass(layout, &p, mass, 0.0);
            (p, action)
        })
        .collect();
    let last = clamps.len() - 1;
    let spans: Vec<Span> = (0..last).map(|h| Span { left: h, right: h + 1 }).collect();
    for (p, action) in &points {
        if p.x_m <= clamps[0] {
            actions[0].add_moved(layout, action, p, &hands[0].point);
        } else if p.x_m >= clamps[last] {
            actions[last].add_moved(layout, action, p, &hands[last].point);
        }
    }
    let n = arm.beam.dofs();
    let s = &member.spec.segment;
    for span in &spans {
        let (left, right) = (&hands[span.left].point, &hands[span.right].point);
        let length = right.x_m - left.x_m;
        let mid = 0.5 * (left.x_m + right.x_m);
        // The span's loads, about its left hand, and their axial part beyond the midpoint.
        let mut load = Action::zero(layout);
        let mut axial_beyond_mid = layout.zero();
        for (p, action) in points.iter().filter(|(p, _)| p.x_m > left.x_m && p.x_m < right.x_m) {
            load.add_moved(layout, action, p, left);
            if p.x_m > mid {
                axial_beyond_mid += &action.fx;
            }
        }
        // Bending moments at the span's ends from the string's curvature, and its stretch.
        let tolerance = 1e-9 * length;
        let curvature = |x: f64, span_side: Side| {
            let (e, xi) = match span_side {
                Side::Outboard => (member.elements.iter().position(|el| (el.x0_m - x).abs() < tolerance), 0.0),
                Side::Inboard => {
                    (member.elements.iter().position(|el| (el.x0_m + el.length_m - x).abs() < tolerance), 1.0)
                }
            };
            arm.basis.tr_mul(&member.element_rows(e.expect("hands are string nodes"), xi, n)[3])
        };
        let moment_form = |row: DVector<f64>| {
            let mut f = layout.zero();
            layout.add_row(&mut f, Block::Displacement, -s.bending_rigidity_n_m2, &row);
            f
        };
        let m_left = moment_form(curvature(left.x_m, Side::Outboard));
        let m_right = moment_form(curvature(right.x_m, Side::Inboard));
        let mut tension = layout.zero();
        let stretch = right.rows.0[0].clone() - &left.rows.0[0];
        layout.add_row(&mut tension, Block::Displacement, s.axial_rigidity_n / length, &stretch);
        // The right hand's action on the span, P2: L P2y = −(M_w + M_left − M_right);
        // P2x = −(axial load beyond the midpoint) + tension. The left hand's: P1 = −W − P2.
        let p2y = (-(&load.m + &m_left - &m_right)) / length;
        let p2x = -&axial_beyond_mid + &tension;
        // The span's load on each hand is minus the hand's action on the span, with the end
        // moments: −M_left on the left hand, +M_right on the right.
        let right_action = Action { fx: -p2x.clone(), fy: -p2y.clone(), m: m_right };
        let left_action = Action { fx: &load.fx + &p2x, fy: &load.fy + &p2y, m: -m_left };
        actions[span.right].fx += &right_action.fx;
        actions[span.right].fy += &right_action.fy;
        actions[span.right].m += &right_action.m;
        actions[span.left].fx += &left_action.fx;
        actions[span.left].fy += &left_action.fy;
        actions[span.left].m += &left_action.m;
    }
    (actions, StringRouting { hands, spans })
}

/// A rigid string's load on each hand as [`RigidGrip`] shares it, and the grip.
fn rigid_hand_loads(arm: &ArmModel, layout: &Layout, held: &HeldString) -> (Vec<Action>, RigidGrip) {
    let hands: Vec<Point> = held.grips.iter().map(|g| arm_point(arm, g.station_m)).collect();
    let (first, last) = (0, hands.len() - 1);
    let mass = held.lumped_mass();
    let centre = arm_point(arm, mass.position_m);
    let load = Action::of_mass(layout, &centre, mass.mass_kg, mass.rotary_inertia_kg_m2);
    let mut about_first = Action::zero(layout);
    about_first.add_moved(layout, &load, &centre, &hands[first]);
    let mut actions: Vec<Action> = hands.iter().map(|_| Action::zero(layout)).collect();
    let (start, end) = (held.start_m(), held.start_m() + held.pipe.length_m);
    let mid = 0.5 * (hands[first].x_m + hands[last].x_m);
    let axial_outer_share = if first == last { 1.0 } else { ((end - mid) / (end - start)).clamp(0.0, 1.0) };
    if first == last {
        actions[first] = about_first;
    } else {
        let length = hands[last].x_m - hands[first].x_m;
        let outer = Action { fx: &about_first.fx * axial_outer_share, fy: &about_first.m / length, m: layout.zero() };
        actions[first] = Action { fx: &about_first.fx - &outer.fx, fy: &about_first.fy - &outer.fy, m: layout.zero() };
        actions[last] = outer;
    }
    (actions, RigidGrip { centre_m: held.centre_m(), hands, axial_outer_share })
}

/// The sections of the arm where stress is recovered: the root, every node's inboard side, and
/// the outboard side too where a section changes or a carried body, a hand or the cylinder's
/// pin sits (where the axial force jumps); `segment_ends_m` are the segments' outer ends.
pub fn stations_of(arm: &ArmModel, segment_ends_m: &[f64], extra_breaks_m: &[f64]) -> Vec<Station> {
    let beam = &arm.beam;
    let tolerance = 1e-9 * arm.length_m();
    let segment_of = |x: f64, side: Side| {
        segment_ends_m
            .iter()
            .position(|&end| match side {
                Side::Inboard => x <= end + tolerance,
                Side::Outboard => x < end - tolerance,
            })
            .unwrap_or(segment_ends_m.len() - 1)
    };
    let mut breaks: Vec<f64> = segment_ends_m.to_vec();
    breaks.extend(beam.spec.masses.iter().map(|m| m.position_m));
    breaks.extend(beam.member.iter().flat_map(|m| m.spec.clamps_m.iter().copied()));
    breaks.extend_from_slice(extra_breaks_m);
    let station = |x: f64, side: Side| Station { point: arm_point(arm, x), side, segment: segment_of(x, side) };
    let mut out = vec![station(0.0, Side::Outboard)];
    let last = beam.nodes_x_m.len() - 1;
    for (j, &x) in beam.nodes_x_m.iter().enumerate().skip(1) {
        out.push(station(x, Side::Inboard));
        if j < last && breaks.iter().any(|&b| (b - x).abs() <= tolerance) {
            out.push(station(x, Side::Outboard));
        }
    }
    out
}

/// The arm's point at station `x_m`: its rows over q, formed from the few DOFs of its element
/// (the same as [`ArmModel::station_rows`], without a product over every DOF).
fn arm_point(arm: &ArmModel, x_m: f64) -> Point {
    let (dofs, shape) = arm.beam.point_shape(x_m);
    Point { x_m, rows: project(arm, &dofs, [&shape.u, &shape.v, &shape.dv]) }
}

/// Rows over q of shape rows on an element's `dofs`: Σ N_i Φ(g_i, ·).
fn project(arm: &ArmModel, dofs: &[Option<usize>; crate::beam::ELEMENT_DOFS], rows: [&[f64; 6]; 3]) -> StationRows {
    StationRows(rows.map(|r| {
        let mut out = DVector::zeros(arm.elastic_dofs());
        for (g, n) in dofs.iter().zip(r) {
            if let Some(g) = *g
                && *n != 0.0
            {
                for (j, o) in out.iter_mut().enumerate() {
                    *o += n * arm.basis[(g, j)];
                }
            }
        }
        out
    }))
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// z of a × b.
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}
