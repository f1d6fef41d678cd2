//! SIGINT and SIGTERM during `covga run`: the first raises the run's interrupt, so that the run
//! ends at its next iteration and removes what it wrote (its partial history, the folder lock,
//! the folder it made); a second signal ends the process at once, as it would have without
//! this. Without it a signal killed the run mid-write and left files that made the same
//! command refuse its own folder.

use crate::planner::executor::Interrupt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Set by the signal handler (the one thing a handler may safely do) and read by the watcher.
static SIGNALLED: AtomicBool = AtomicBool::new(false);

/// How often the watcher looks at the flag: a run stops within this of a signal plus one of
/// its iterations.
const POLL: Duration = Duration::from_millis(20);

#[cfg(unix)]
extern "C" fn on_signal(signal: libc::c_int) {
    SIGNALLED.store(true, Ordering::SeqCst);
    // SAFETY: `signal` is async-signal-safe; the default action makes a second signal end the
    // process as usual.
    unsafe {
        libc::signal(signal, libc::SIG_DFL);
    }
}

/// Raises an [`Interrupt`] on SIGINT or SIGTERM while it lives; dropping it stops watching
/// (the handlers stay installed, with nothing left to raise).
pub struct SignalWatch {
    done: std::sync::Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl SignalWatch {
    /// Installs the handlers and raises `interrupt` once a signal arrives.
    pub fn start(interrupt: Interrupt) -> Self {
        #[cfg(unix)]
        // SAFETY: the handler only stores to an atomic and resets its own disposition.
        unsafe {
            let handler = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
            libc::signal(libc::SIGINT, handler);
            libc::signal(libc::SIGTERM, handler);
        }
        let done = std::sync::Arc::new(AtomicBool::new(false));
        let watching = done.clone();
        let thread = std::thread::spawn(move || {
            while !watching.load(Ordering::SeqCst) {
                if SIGNALLED.load(Ordering::SeqCst) {
                    interrupt.raise();
                    return;
                }
                std::thread::sleep(POLL);
            }
        });
        Self { done, thread: Some(thread) }
    }
}

impl Drop for SignalWatch {
    fn drop(&mut self) {
        self.done.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}
