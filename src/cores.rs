//! Whether work may go to a second core beside the run's thread: the sign-off's stress recovery
//! ([`crate::stress`]) and the recording's blueprint ([`crate::record`]) do, where one is spare.

/// Whether this process may run on more than one core (its affinity and cgroup quota read
/// once: reading them takes file reads).
fn second_core() -> bool {
    static SECOND_CORE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *SECOND_CORE.get_or_init(|| std::thread::available_parallelism().is_ok_and(|n| n.get() > 1))
}

/// Whether a core is spare for work beside this thread: the process has a second one and this
/// thread is not one of a parallel sweep's workers (which keep every core busy).
pub(crate) fn spare() -> bool {
    rayon::current_thread_index().is_none() && second_core()
}
