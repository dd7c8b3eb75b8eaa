//! Ctrl-C: the command line's handler sets a flag; long work (a run's loop, a build waiting
//! for its compiler, a suite's workers) checks it and stops cleanly, its outputs complete up
//! to there and its temporary files removed.

use std::sync::atomic::{AtomicBool, Ordering};

static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Catch Ctrl-C (SIGINT) from now on: it sets the flag instead of ending the process.
pub fn catch() {
    let _ = ctrlc::set_handler(|| INTERRUPTED.store(true, Ordering::Relaxed));
}

/// Whether Ctrl-C was pressed.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}
