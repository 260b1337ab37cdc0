//! The boundary between Python and the library: the GIL released, panics caught, and long runs
//! interruptible by Ctrl-C.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use pyo3::prelude::*;

use crate::InternalError;

/// How often a long run looks at Python's signal handlers.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// The message of a caught panic.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

fn internal(message: String) -> PyErr {
    InternalError::new_err(format!(
        "internal error in dyncontact (please report it): {message}"
    ))
}

/// Runs `work` with the GIL released and a panic turned into `InternalError`. For short calls
/// (no thread is started).
pub fn released<T: Send>(py: Python<'_>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    py.detach(|| catch_unwind(AssertUnwindSafe(work)))
        .map_err(|p| internal(panic_message(p.as_ref())))
}

/// Runs `work` on a worker thread with the GIL released, while this thread checks Python's
/// signal handlers every 50 ms; on a signal (Ctrl-C) `stop` is set, `work` is expected to
/// return soon (the library's progress callbacks read it), and the signal's exception
/// (`KeyboardInterrupt`) is raised. A panic in `work` becomes `InternalError`.
pub fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&AtomicBool) -> T + Send,
) -> PyResult<T> {
    let stop = AtomicBool::new(false);
    let (outcome, signal) = py.detach(|| {
        std::thread::scope(|scope| {
            let (tx, rx) = mpsc::channel();
            let stop = &stop;
            scope.spawn(move || {
                let result = catch_unwind(AssertUnwindSafe(|| work(stop)));
                // The receiver waits for this message; it is dropped only after it came.
                let _ = tx.send(result);
            });
            let mut signal = None;
            loop {
                match rx.recv_timeout(SIGNAL_POLL) {
                    Ok(result) => return (result, signal),
                    Err(mpsc::RecvTimeoutError::Timeout) => {
                        if signal.is_none()
                            && let Err(e) = Python::attach(|py| py.check_signals())
                        {
                            stop.store(true, Ordering::Relaxed);
                            signal = Some(e);
                        }
                    }
                    Err(mpsc::RecvTimeoutError::Disconnected) => {
                        let lost: Box<dyn std::any::Any + Send> =
                            Box::new("the worker thread ended without a result");
                        return (Err(lost), signal);
                    }
                }
            }
        })
    });
    if let Some(e) = signal {
        return Err(e);
    }
    outcome.map_err(|p| internal(panic_message(p.as_ref())))
}

/// `_panic_for_tests(interruptible)`: panics inside the boundary (for the test that a Rust
/// panic reaches Python as `InternalError`, python/tests/test_errors.py). Not public API.
#[pyfunction]
#[pyo3(name = "_panic_for_tests")]
pub fn panic_for_tests(py: Python<'_>, interruptible_run: bool) -> PyResult<()> {
    if interruptible_run {
        interruptible::<()>(py, |_| panic!("a deliberate panic (test)"))
    } else {
        released::<()>(py, || panic!("a deliberate panic (test)"))
    }
}
