//! The recovery's work — each step's vector and point loads staged, the two matrix products of
//! a chunk of steps, the extremes and the single-precision copy — done on a thread of its own
//! beside the step loop, which only records what the recovery reads of each step: the hub's
//! state, q, q̇, q̈, the point loads and the cylinder pin's force.
//!
//! Chunks go to the worker in order and are completed in order, with the same arithmetic as on
//! the step's thread, so the series is the same to the bit. A run inside rayon's pool (a sweep,
//! an envelope, a design) has its cores busy with other runs already: there the chunks are
//! completed on the step's thread, as they are with one core to run on (`taskset -c 0`) and
//! where no thread can be started.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread::JoinHandle;

use nalgebra::DVector;

use super::RunningExtremes;
use super::recovery::{Scratch, SectionRecovery};
use crate::drive::DriveState;
use crate::point_load::{Hub, PointLoad};
use crate::sensor::probe::ArmState;

/// A chunk of steps as the step's thread records them.
#[derive(Debug, Clone, Default)]
pub(super) struct Recorded {
    /// Per step: the hub's state and its angle's sine and cosine.
    hubs: Vec<(DriveState, (f64, f64))>,
    /// Per step: q, q̇, q̈.
    elastic: Vec<f64>,
    /// Per step: each cylinder pin's force on the arm, world X, Y, N, one step after another.
    pins: Vec<f64>,
    /// The steps' point loads: the step in the chunk, whether on the held string, the load.
    loads: Vec<(usize, bool, PointLoad<Hub>)>,
}

impl Recorded {
    /// Steps recorded.
    pub fn steps(&self) -> usize {
        self.hubs.len()
    }

    /// Records a step: `state`, its hub angle's `sin_cos`, the point loads on the arm `on_arm`
    /// and on the string `on_string`, each cylinder pin's force `pins_world_n`.
    pub fn push(
        &mut self,
        state: &ArmState,
        sin_cos: (f64, f64),
        (on_arm, on_string): (&[PointLoad<Hub>], &[PointLoad<Hub>]),
        pins_world_n: &[[f64; 2]],
    ) {
        let k = self.steps();
        self.hubs.push((state.hub, sin_cos));
        for v in [state.q, state.qd, state.qdd] {
            self.elastic.extend_from_slice(v.as_slice());
        }
        self.pins.extend(pins_world_n.iter().flatten());
        self.loads.extend(on_arm.iter().map(|l| (k, false, *l)).chain(on_string.iter().map(|l| (k, true, *l))));
    }

    /// Empties it, keeping its room.
    pub fn clear(&mut self) {
        self.hubs.clear();
        self.elastic.clear();
        self.pins.clear();
        self.loads.clear();
    }
}

/// What the completed chunks have made: the series' values and extremes.
#[derive(Debug, Default)]
pub(super) struct Evaluated {
    pub values: Vec<f32>,
    pub extremes: RunningExtremes,
}

/// Completes recorded chunks: the recovery under gravity `g`, with its scratch.
#[derive(Debug)]
pub(super) struct Completer {
    recovery: Arc<SectionRecovery>,
    g: f64,
    /// Values a step: the recovery's, then the cylinder pins'.
    stride: usize,
    scratch: Scratch,
    values: Vec<f64>,
    elastic: [DVector<f64>; 3],
    on_arm: Vec<PointLoad<Hub>>,
    on_string: Vec<PointLoad<Hub>>,
}

impl Completer {
    pub fn new(recovery: Arc<SectionRecovery>, g: f64, stride: usize) -> Self {
        let empty = || DVector::zeros(0);
        Completer {
            recovery,
            g,
            stride,
            scratch: Scratch::default(),
            values: Vec::new(),
            elastic: [empty(), empty(), empty()],
            on_arm: Vec::new(),
            on_string: Vec::new(),
        }
    }

    /// Completes `recorded` (at most [`super::recovery::CHUNK_STEPS`] steps) into `into`.
    pub fn complete(&mut self, recorded: &Recorded, into: &mut Evaluated) {
        let Completer { recovery, g, stride, scratch, values, elastic, on_arm, on_string } = self;
        let n = recorded.elastic.len() / (3 * recorded.steps().max(1));
        let mut loads = recorded.loads.iter().peekable();
        for (k, (hub, sin_cos)) in recorded.hubs.iter().enumerate() {
            let step = &recorded.elastic[3 * n * k..3 * n * (k + 1)];
            for (v, part) in elastic.iter_mut().zip(step.chunks_exact(n.max(1))) {
                if v.len() != n {
                    *v = DVector::zeros(n);
                }
                v.as_mut_slice().copy_from_slice(part);
            }
            on_arm.clear();
            on_string.clear();
            while let Some((_, on, load)) = loads.next_if(|(j, _, _)| *j == k) {
                if *on { on_string.push(*load) } else { on_arm.push(*load) }
            }
            let start = values.len();
            values.resize(start + recovery.width(), 0.0);
            let [q, qd, qdd] = &*elastic;
            let state = ArmState { hub: *hub, q, qd, qdd };
            recovery.stage(&state, *sin_cos, *g, on_arm, on_string, scratch, &mut values[start..]);
            let pins = *stride - recovery.width();
            values.extend_from_slice(&recorded.pins[pins * k..pins * (k + 1)]);
        }
        recovery.flush(scratch, values, *stride);
        let count = recovery.stations.len();
        for step in values.chunks_exact(*stride) {
            let (axial, rest) = step.split_at(count);
            into.extremes.take(axial, &rest[..count]);
        }
        into.values.extend(values.iter().map(|v| *v as f32));
        values.clear();
    }
}

/// The worker completing a run's chunks, with the emptied chunks it hands back for reuse.
#[derive(Debug)]
pub(super) struct Worker {
    to_worker: Sender<Recorded>,
    emptied: Receiver<Recorded>,
    thread: JoinHandle<Evaluated>,
}

impl Worker {
    /// A worker with `completer` taking `evaluated` on, or `evaluated` back where it should not
    /// run (inside rayon's pool, or with one core to run on) or cannot (no thread to be had).
    pub fn start(mut completer: Completer, evaluated: Evaluated) -> Result<Self, Box<Evaluated>> {
        if !crate::cores::spare() {
            return Err(Box::new(evaluated));
        }
        let (to_worker, recorded) = channel::<Recorded>();
        let (give_back, emptied) = channel();
        let (hand_in, handed_in) = channel::<Evaluated>();
        let spawned = std::thread::Builder::new().name("pipearm-stress".into()).spawn(move || {
            let Ok(mut evaluated) = handed_in.recv() else { return Evaluated::default() };
            for mut chunk in recorded {
                completer.complete(&chunk, &mut evaluated);
                chunk.clear();
                // The step loop may have finished: then nobody reuses it.
                give_back.send(chunk).ok();
            }
            evaluated
        });
        match spawned {
            Ok(thread) => {
                hand_in.send(evaluated).ok();
                Ok(Worker { to_worker, emptied, thread })
            }
            Err(_) => Err(Box::new(evaluated)),
        }
    }

    /// Hands `recorded` over and returns an emptied chunk to record the next in.
    pub fn hand_over(&self, recorded: Recorded) -> Recorded {
        // A send fails only if the worker has panicked; `finish` reports that.
        self.to_worker.send(recorded).ok();
        self.emptied.try_recv().unwrap_or_default()
    }

    /// Waits for every chunk handed over and returns what they made.
    pub fn finish(self) -> Evaluated {
        drop(self.to_worker);
        match self.thread.join() {
            Ok(evaluated) => evaluated,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    }
}
