//! Ctrl-C (SIGINT) and SIGTERM end a run in any phase. While a loop that polls for the
//! request is running (a [`Graceful`] scope: the frame loops, the reference tracer, the
//! stress matrix), the first signal only sets a flag that the loop checks before each frame
//! (the tracer before each row), so the run unwinds with [`Error::Interrupted`]: the device is
//! waited for and dropped in order, and no report is written (reports are written whole at
//! the end, atomically). In any other phase (loading, pipeline creation, writing files,
//! blocked on a read) nothing would look at the flag, so the signal exits at once, as a second
//! signal always does. Either way the exit status is [`EXIT_CODE`].

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;

/// A stop was asked for.
static REQUESTED: AtomicBool = AtomicBool::new(false);
/// Some code saw the request ([`check`] returned `Err(Interrupted)`), so it is unwinding.
static OBSERVED: AtomicBool = AtomicBool::new(false);
/// Graceful scopes alive.
static SCOPES: AtomicUsize = AtomicUsize::new(0);
/// One thread calls `exit` (calling it from two at once is undefined in C).
static EXITING: AtomicBool = AtomicBool::new(false);
/// Files being written that an exit at once removes (temporary files before their rename).
static TEMPORARY: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Exit status of an interrupted run (128 + SIGINT, as shells report it).
pub const EXIT_CODE: u8 = 130;

/// Install the handler (once per process; later calls do nothing).
pub fn install() {
    static INSTALLED: std::sync::Once = std::sync::Once::new();
    INSTALLED.call_once(|| {
        if let Err(e) = ctrlc::set_handler(on_signal) {
            eprintln!("warning: Ctrl-C handler not installed ({e}); Ctrl-C ends the run at once");
        }
    });
}

/// The handler (on ctrlc's thread). The request is stored before the scopes are counted, and
/// a scope is uncounted before it looks at the request, so a scope ending as the signal comes
/// cannot leave it unseen: one of the two sees the other.
fn on_signal() {
    if REQUESTED.swap(true, Ordering::SeqCst) {
        exit_now("interrupted twice: exiting now");
    }
    if SCOPES.load(Ordering::SeqCst) == 0 {
        exit_now("interrupted: exiting now");
    }
    eprintln!("\ninterrupted: stopping after the frame in flight (again to exit now)");
}

/// Exit with [`EXIT_CODE`] after `message`; a second caller waits for the first's exit.
fn exit_now(message: &str) -> ! {
    if EXITING.swap(true, Ordering::SeqCst) {
        loop {
            std::thread::park();
        }
    }
    eprintln!("\n{message}");
    // Never wait here: the thread writing a file may hold the lock.
    if let Ok(files) = TEMPORARY.try_lock() {
        for f in files.iter() {
            std::fs::remove_file(f).ok();
        }
    }
    std::process::exit(EXIT_CODE as i32)
}

/// While alive, an exit at once removes `path` (a file that is not whole yet).
pub struct Temporary(PathBuf);

/// Have an exit at once remove `path` while the guard lives.
pub fn temporary(path: &Path) -> Temporary {
    if let Ok(mut files) = TEMPORARY.lock() {
        files.push(path.to_path_buf());
    }
    Temporary(path.to_path_buf())
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if let Ok(mut files) = TEMPORARY.lock() {
            if let Some(i) = files.iter().position(|f| *f == self.0) {
                files.swap_remove(i);
            }
        }
    }
}

/// While alive, a signal only sets the flag: the code holding it polls [`check`] or
/// [`requested`] often enough (once per frame, per row of the tracer) to stop promptly.
/// Ending a scope with a request nobody saw exits at once: what follows would not look.
#[must_use = "a scope lasts as long as the guard"]
pub struct Graceful(());

/// Begin a graceful scope (nested scopes count).
pub fn graceful() -> Graceful {
    SCOPES.fetch_add(1, Ordering::SeqCst);
    Graceful(())
}

impl Drop for Graceful {
    fn drop(&mut self) {
        let last = SCOPES.fetch_sub(1, Ordering::SeqCst) == 1;
        if last && REQUESTED.load(Ordering::SeqCst) && !OBSERVED.load(Ordering::SeqCst) {
            exit_now("interrupted: exiting now");
        }
    }
}

/// Whether a stop was requested (a poll that stops by itself: the caller then calls
/// [`check`], which reports it).
pub fn requested() -> bool {
    REQUESTED.load(Ordering::SeqCst)
}

/// `Err(Interrupted)` once a stop was requested.
pub fn check() -> Result<()> {
    if requested() {
        OBSERVED.store(true, Ordering::SeqCst);
        Err(Error::Interrupted)
    } else {
        Ok(())
    }
}
