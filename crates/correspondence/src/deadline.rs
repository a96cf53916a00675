//! Wall-clock deadlines of the time budgets of the alignment ([`crate::GuidedSettings`]) and of
//! the physics optimizer of `scenethesis-physics-opt`, which imports them from here. The clock
//! is only compared with a deadline (to stop work early), never used in a computation, so a
//! budget that is not reached leaves every result unchanged.

use std::time::{Duration, Instant};

/// `now + seconds`, `None` for an infinite or unrepresentable budget (a non-positive or NaN
/// budget is spent at once).
pub fn deadline_after(seconds: f64) -> Option<Instant> {
    let seconds = if seconds.is_nan() {
        0.0
    } else {
        seconds.max(0.0)
    };
    Duration::try_from_secs_f64(seconds)
        .ok()
        .and_then(|d| Instant::now().checked_add(d))
}

/// Whether `deadline` has passed.
pub fn past(deadline: Option<Instant>) -> bool {
    deadline.is_some_and(|d| Instant::now() >= d)
}
