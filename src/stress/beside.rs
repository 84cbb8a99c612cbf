//! The staged readings' linear part — the two matrix products of a chunk of steps, the extremes
//! and the single-precision copy — evaluated on a thread of its own beside the step loop, which
//! then only stages each step's vector and point loads.
//!
//! Chunks go to the worker in order and are evaluated in order, with the same arithmetic as on
//! the step's thread, so the series is the same to the bit. A run inside rayon's pool (a sweep,
//! an envelope, a design) has its cores busy with other runs already: there the chunks are
//! evaluated on the step's thread, as they are where no thread can be started.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread::JoinHandle;

use super::RunningExtremes;
use super::recovery::{Scratch, SectionRecovery};

/// A chunk of staged readings: the products' inputs, and each step's values so far (the point
/// loads' share), `stride` a step.
#[derive(Debug, Clone, Default)]
pub(super) struct Staged {
    pub scratch: Scratch,
    pub values: Vec<f64>,
}

/// What the evaluated chunks have made: the series' values and extremes.
#[derive(Debug, Default)]
pub(super) struct Evaluated {
    pub values: Vec<f32>,
    pub extremes: RunningExtremes,
}

impl Evaluated {
    /// Completes `staged` (`stride` values a step) and takes it in, leaving it empty.
    pub fn take(&mut self, recovery: &SectionRecovery, stride: usize, staged: &mut Staged) {
        recovery.flush(&mut staged.scratch, &mut staged.values, stride);
        let count = recovery.stations.len();
        for step in staged.values.chunks_exact(stride) {
            let (axial, rest) = step.split_at(count);
            self.extremes.take(axial, &rest[..count]);
        }
        self.values.extend(staged.values.iter().map(|v| *v as f32));
        staged.values.clear();
    }
}

/// The worker evaluating a run's chunks, with the emptied chunks it hands back for reuse.
#[derive(Debug)]
pub(super) struct Worker {
    to_worker: Sender<Staged>,
    emptied: Receiver<Staged>,
    thread: JoinHandle<Evaluated>,
}

impl Worker {
    /// A worker taking `evaluated` on, or `evaluated` back where it should not run (inside
    /// rayon's pool) or cannot (no thread to be had).
    pub fn start(recovery: Arc<SectionRecovery>, stride: usize, evaluated: Evaluated) -> Result<Self, Box<Evaluated>> {
        if rayon::current_thread_index().is_some() {
            return Err(Box::new(evaluated));
        }
        let (to_worker, staged) = channel::<Staged>();
        let (give_back, emptied) = channel();
        let (hand_in, handed_in) = channel::<Evaluated>();
        let spawned = std::thread::Builder::new().name("pipearm-stress".into()).spawn(move || {
            let Ok(mut evaluated) = handed_in.recv() else { return Evaluated::default() };
            for mut chunk in staged {
                evaluated.take(&recovery, stride, &mut chunk);
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

    /// Hands `staged` over and returns an emptied chunk to stage the next in.
    pub fn hand_over(&self, staged: Staged) -> Staged {
        // A send fails only if the worker has panicked; `finish` reports that.
        self.to_worker.send(staged).ok();
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
