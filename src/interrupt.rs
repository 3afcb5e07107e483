//! Ctrl-C (SIGINT) and SIGTERM stop a long run cleanly: the first signal sets a flag that the
//! renderer checks before each frame (and the reference tracer before each tile), so the run
//! unwinds with [`Error::Interrupted`]: the device is waited for and dropped in order, and no
//! report is written (reports are written whole at the end, atomically). A second signal
//! exits at once.

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Exit status of an interrupted run (128 + SIGINT, as shells report it).
pub const EXIT_CODE: u8 = 130;

/// Install the handler (once per process; later calls do nothing).
pub fn install() {
    static INSTALLED: std::sync::Once = std::sync::Once::new();
    INSTALLED.call_once(|| {
        let handler = || {
            if REQUESTED.swap(true, Ordering::SeqCst) {
                eprintln!("\ninterrupted twice: exiting now");
                std::process::exit(EXIT_CODE as i32);
            }
            eprintln!("\ninterrupted: stopping after the frame in flight (again to exit now)");
        };
        if let Err(e) = ctrlc::set_handler(handler) {
            eprintln!("warning: Ctrl-C handler not installed ({e}); Ctrl-C ends the run at once");
        }
    });
}

/// Whether a stop was requested.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::SeqCst)
}

/// `Err(Interrupted)` once a stop was requested.
pub fn check() -> Result<()> {
    if requested() {
        Err(Error::Interrupted)
    } else {
        Ok(())
    }
}
