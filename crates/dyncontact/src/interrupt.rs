//! Ctrl-C (SIGINT) and SIGTERM: the first one asks the running simulation to stop after its
//! current step (it then writes what is complete, marked `"completed": false`, and exits with
//! code 1); a second one, or the first one while nothing can stop at a step, exits at once
//! with code 1.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);
static STOPPABLE: AtomicBool = AtomicBool::new(false);

/// Install the handler (once, at start-up).
pub fn install() {
    let r = ctrlc::set_handler(|| {
        if REQUESTED.swap(true, Ordering::SeqCst) || !STOPPABLE.load(Ordering::SeqCst) {
            eprintln!("\ninterrupted");
            std::process::exit(crate::errors::EXIT_RUN_FAILED);
        }
        eprintln!(
            "\ninterrupt: stopping after the current step and writing what is complete (press Ctrl-C again to exit at once)"
        );
    });
    if let Err(e) = r {
        eprintln!("warning: cannot install the Ctrl-C handler: {e}");
    }
}

/// From now on an interrupt stops the run at its next step instead of exiting at once; the
/// caller must poll [`requested`] in its stepping loop.
pub fn stop_at_next_step() {
    STOPPABLE.store(true, Ordering::SeqCst);
}

/// Whether a stop was requested.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// The error a run returns after it has written its partial results.
#[derive(Debug)]
pub struct Interrupted {
    /// Simulated time reached \[s\].
    pub time_reached: f64,
}

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "interrupted at t = {} s; the outputs written are partial (summary.json has \"completed\": false)",
            self.time_reached
        )
    }
}

impl std::error::Error for Interrupted {}
