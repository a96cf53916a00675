//! The phases of one [`Pipeline::generate`](crate::Pipeline::generate) run, one file each, in
//! the order they run: [`clock`] times and announces every stage, [`retrieve`] picks one asset
//! per planned object, [`layout`] asks the guide for the initial layout, [`correspond`] aligns
//! the poses to the guide's image when it gave one, [`optimize`] refines
//! the poses, [`looks`] records what the scene wears, [`judge`] scores the attempt, [`rework`] applies the re-plan policy when the
//! judge rejects it, [`previews`] renders the chosen attempt and [`summary`] writes its report.

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
