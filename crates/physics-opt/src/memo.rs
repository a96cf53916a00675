//! What one object's contact checks learn about distances, kept for its next checks: a
//! solver tries many nearby poses of the same object against the same obstacles, and most of
//! its sample points stay clear of everything. A true signed distance changes by at most the
//! distance a point moves (it is 1-Lipschitz), so two proofs need no distance query:
//!
//! - a point found `d` outside every obstacle and moved by `δ` is still at least `d − δ` away;
//!   while that clears the collision margin, nothing near it is queried at all;
//! - a point found `d` outside and moved by less than `d + r` cannot have crossed into an
//!   obstacle whose surface is not within `r` of it now (the crossing would lie on its path,
//!   at least `d` from the start and `r` from the end). Whether a surface comes within `r` is
//!   a search that stops at the first triangle that near, far cheaper than the nearest one.
//!
//! Both are proofs, not estimates: a check that uses a [`ContactMemo`] finds exactly the
//! contacts one without it finds.

use std::sync::{Mutex, MutexGuard, PoisonError};

use nalgebra::Point3;

/// Bounds must clear the margin by this much more (metres) to skip a query: the fields are
/// queried in `f32`, whose rounding over a room's coordinates stays far below it.
const SLACK: f64 = 1e-5;

/// Distances remembered between the contact checks of one object against one fixed set of
/// obstacles (an [`crate::ObjectProblem`] whose obstacles do not move while it is solved).
/// Give each such problem its own memo; one shared by problems with other obstacles or
/// another asset would prove wrong things.
#[derive(Debug, Default)]
pub struct ContactMemo {
    state: Mutex<MemoState>,
}

impl ContactMemo {
    /// An empty memo: the first check queries everything.
    pub fn new() -> Self {
        Self::default()
    }

    /// The state, for one check at a time (a poisoned lock still holds valid bounds: every
    /// entry is written whole).
    pub(crate) fn lock(&self) -> MutexGuard<'_, MemoState> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// A point where a distance was measured, and a lower bound on that signed distance there
/// (positive: the point was outside).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Clearance {
    at: Point3<f64>,
    distance: f64,
}

impl Clearance {
    /// Nothing known.
    const UNKNOWN: Clearance = Clearance {
        at: Point3::new(0.0, 0.0, 0.0),
        distance: f64::NEG_INFINITY,
    };

    /// What was measured at `at`: the signed distance is at least `distance` there.
    pub fn new(at: Point3<f64>, distance: f64) -> Self {
        Self { at, distance }
    }

    /// Whether the distance at `p` is proven at least `margin` (first proof above).
    pub fn clear_of(&self, p: &Point3<f64>, margin: f64) -> bool {
        self.distance - (p - self.at).norm() >= margin + SLACK
    }

    /// Whether `p` is proven outside every field whose surface does not come within `radius`
    /// of it (second proof above).
    pub fn outside_unless_within(&self, p: &Point3<f64>, radius: f64) -> bool {
        self.distance > 0.0 && (p - self.at).norm() + SLACK < self.distance + radius
    }
}

/// The remembered bounds of one object's checks. Without a memo a check runs on an empty
/// state, which knows nothing and keeps nothing.
#[derive(Debug, Default)]
pub(crate) struct MemoState {
    /// The obstacles near the object when the entries were written (the entries hold for
    /// exactly these).
    near: Vec<usize>,
    /// Per surface sample of the object: its clearance in world coordinates from every near
    /// obstacle whose field is 1-Lipschitz.
    own: Vec<Clearance>,
    /// Per near obstacle (in `near`'s order), per sample of it: its clearance from the
    /// object's own field, in the object's unscaled frame.
    foreign: Vec<Vec<Clearance>>,
}

impl MemoState {
    /// Makes the state hold for `near` obstacles with `foreign` samples each and `own` object
    /// samples, forgetting everything when the near set changed.
    pub fn hold_for(&mut self, near: &[usize], own: usize, foreign: impl Fn(usize) -> usize) {
        if self.near == near && self.own.len() == own {
            return;
        }
        self.near = near.to_vec();
        self.own = vec![Clearance::UNKNOWN; own];
        self.foreign = near
            .iter()
            .map(|&index| vec![Clearance::UNKNOWN; foreign(index)])
            .collect();
    }

    /// What is known of the object's sample `k` (world coordinates) against every near
    /// 1-Lipschitz obstacle.
    pub fn own(&self, k: usize) -> Clearance {
        self.own.get(k).copied().unwrap_or(Clearance::UNKNOWN)
    }

    /// Remembers what was measured of the object's sample `k`.
    pub fn set_own(&mut self, k: usize, clearance: Clearance) {
        if let Some(c) = self.own.get_mut(k) {
            *c = clearance;
        }
    }

    /// What is known of sample `k` of the near obstacle at position `slot` of the near set
    /// against the object's own field (the object's unscaled frame and units).
    pub fn foreign(&self, slot: usize, k: usize) -> Clearance {
        self.foreign
            .get(slot)
            .and_then(|samples| samples.get(k))
            .copied()
            .unwrap_or(Clearance::UNKNOWN)
    }

    /// Remembers what was measured of sample `k` of the near obstacle at `slot`.
    pub fn set_foreign(&mut self, slot: usize, k: usize, clearance: Clearance) {
        if let Some(c) = self.foreign.get_mut(slot).and_then(|s| s.get_mut(k)) {
            *c = clearance;
        }
    }
}

/// How far beyond the margin a cheap "is the surface this near" search reaches: beyond the
/// margin by the rounding slack, so that "nothing within it" proves the distance clears the
/// margin.
pub(crate) fn reach(margin: f64) -> f64 {
    margin + SLACK
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clearance_proves_distance_only_while_the_point_stays_near() {
        let c = Clearance::new(Point3::new(1.0, 0.0, 0.0), 0.05);
        assert!(c.clear_of(&Point3::new(1.04, 0.0, 0.0), 0.001));
        assert!(!c.clear_of(&Point3::new(1.05, 0.0, 0.0), 0.001));
        assert!(!Clearance::UNKNOWN.clear_of(&Point3::origin(), 0.0));
    }

    #[test]
    fn a_clearance_keeps_the_sign_for_moves_shorter_than_it_plus_the_radius() {
        let c = Clearance::new(Point3::origin(), 0.002);
        assert!(c.outside_unless_within(&Point3::new(0.0, 0.0, 0.0029), 0.001));
        assert!(!c.outside_unless_within(&Point3::new(0.0, 0.0, 0.0031), 0.001));
        // A point found inside proves nothing.
        let inside = Clearance::new(Point3::origin(), -0.01);
        assert!(!inside.outside_unless_within(&Point3::origin(), 0.001));
    }

    #[test]
    fn a_changed_near_set_forgets() {
        let mut state = MemoState::default();
        state.hold_for(&[3], 1, |_| 2);
        state.set_own(0, Clearance::new(Point3::origin(), 1.0));
        state.set_foreign(0, 1, Clearance::new(Point3::origin(), 1.0));
        assert!(state.own(0).clear_of(&Point3::origin(), 0.001));
        assert!(state.foreign(0, 1).clear_of(&Point3::origin(), 0.001));
        state.hold_for(&[3, 4], 1, |_| 2);
        assert!(!state.own(0).clear_of(&Point3::origin(), 0.001));
        assert!(!state.foreign(0, 1).clear_of(&Point3::origin(), 0.001));
    }

    #[test]
    fn an_empty_state_knows_nothing_and_keeps_nothing() {
        let mut state = MemoState::default();
        state.set_own(0, Clearance::new(Point3::origin(), 1.0));
        assert!(!state.own(0).clear_of(&Point3::origin(), 0.0));
    }
}
