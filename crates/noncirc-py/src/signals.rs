//! Ctrl-C while Rust works: Python handles signals in its main thread only, so long work
//! runs on a thread of its own while the interpreter's thread checks for a signal every
//! [`SIGNAL_CHECK_MS`] with the GIL released in between. A signal sets the work's stop
//! flag at once; the work then ends within one design's evaluation per thread.

use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// How often the interpreter's thread checks for Ctrl-C while work runs (ms).
pub(crate) const SIGNAL_CHECK_MS: u64 = 20;

/// Runs `work` on a thread of its own and returns what it returns, with the signal's
/// error (`KeyboardInterrupt`) if one came: `stop` was set then, and `work` is expected to
/// watch it. A panic in `work` is passed on.
pub(crate) fn watched<T: Send>(
    py: Python<'_>,
    stop: &AtomicBool,
    work: impl FnOnce() -> T + Send,
) -> (T, Option<PyErr>) {
    let mut interrupt = None;
    let outcome = std::thread::scope(|scope| {
        let interpreter = std::thread::current();
        let worker = scope.spawn(move || {
            let outcome = work();
            interpreter.unpark();
            outcome
        });
        let wait = std::time::Duration::from_millis(SIGNAL_CHECK_MS);
        while !worker.is_finished() {
            py.allow_threads(|| std::thread::park_timeout(wait));
            if let Err(e) = py.check_signals() {
                stop.store(true, Ordering::SeqCst);
                interrupt.get_or_insert(e);
            }
        }
        worker
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    });
    (outcome, interrupt)
}
