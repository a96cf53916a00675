//! Ctrl-C (SIGINT) and SIGTERM for long commands: the first signal sets a flag the command
//! polls (so it can stop starting work and still write its summary); a second one ends the
//! process at once, as usual.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// Sets `flag` on the first SIGINT or SIGTERM; the second one ends the process.
pub fn on_interrupt(flag: Arc<AtomicBool>) {
    if FLAG.set(flag).is_err() {
        return;
    }
    #[cfg(unix)]
    {
        extern "C" fn handler(signal: libc::c_int) {
            if let Some(flag) = FLAG.get() {
                flag.store(true, Ordering::SeqCst);
            }
            // SAFETY: restoring the default disposition is async-signal-safe.
            unsafe {
                libc::signal(signal, libc::SIG_DFL);
            }
        }
        // SAFETY: the handler only performs an atomic store and `signal`, both
        // async-signal-safe.
        unsafe {
            libc::signal(libc::SIGINT, handler as *const () as libc::sighandler_t);
            libc::signal(libc::SIGTERM, handler as *const () as libc::sighandler_t);
        }
    }
}
