//! The phases of one [`Pipeline::generate`](crate::Pipeline::generate) run, one file each, in
//! the order they run: [`clock`] times and announces every stage, [`retrieve`] picks one asset
//! per planned object, [`layout`] asks the guide for the initial layout, [`correspond`] aligns
//! the poses to the guide's image when it gave one, [`optimize`] refines
//! the poses, [`looks`] records what the scene wears, [`judge`] scores the attempt (while [`beside`] draws its previews), [`rework`] applies the re-plan policy when the
//! judge rejects it, [`previews`] renders the chosen attempt and [`summary`] writes its report.

pub(crate) mod beside;
pub(crate) mod clock;
pub(crate) mod correspond;
pub(crate) mod judge;
pub(crate) mod layout;
pub(crate) mod looks;
pub(crate) mod optimize;
pub(crate) mod previews;
pub(crate) mod retrieve;
pub(crate) mod rework;
pub(crate) mod summary;

/// Gives the calling thread the lowest scheduling priority (nice 19), so that it runs on a core
/// the process's other threads leave idle and never slows them (Linux schedules each thread
/// with its own niceness; elsewhere the thread keeps its priority).
pub(crate) fn run_at_lowest_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: gettid has no preconditions; setpriority on the calling thread's own id only
    // changes that thread's niceness, and a failure (reported by its return value) leaves the
    // priority as it was, which is harmless.
    unsafe {
        let thread = libc::gettid();
        libc::setpriority(libc::PRIO_PROCESS, thread as libc::id_t, 19);
    }
}
