//! Facts every phase of the procedural guide shares: the door and wall-mount dimensions, a
//! floor object once placed and the target a relative placement is made against (yaws are
//! wrapped by `scenethesis_scene_graph::wrap_yaw`).

use scenethesis_scene_graph::{AssetInfo, RelationKind};

use super::geometry::Footprint;
use crate::plan::{PlannedObject, Zone};

/// Door opening width in metres.
pub(super) const DOOR_WIDTH: f64 = 0.9;
/// Centre height of wall-mounted objects.
pub(super) const WALL_MOUNT_HEIGHT: f64 = 1.6;

/// A floor (or wall-mounted) object once placed: its plan entry, footprint and height.
#[derive(Debug, Clone)]
pub(super) struct Placed {
    pub(super) plan_index: usize,
    pub(super) fp: Footprint,
    pub(super) height: f64,
    /// Checked from the front (objects backed onto a wall) rather than from any side.
    pub(super) front_access: bool,
    pub(super) wall: Option<String>,
    pub(super) mounted: bool,
    /// The height of a mounted object's bottom when it hangs somewhere other than the usual
    /// wall-mount height (above a run of counters).
    pub(super) bottom: Option<f64>,
    /// The floor in front of it that its doors and drawers sweep while opening
    /// ([`Footprint::opening`]): kept free of other objects' bodies.
    pub(super) opening: Option<Footprint>,
}

impl Placed {
    /// A free-standing floor object of asset `info`: reached from any side, backed onto no
    /// wall, not mounted.
    pub(super) fn standing(plan_index: usize, fp: Footprint, info: &AssetInfo) -> Self {
        Self {
            plan_index,
            fp,
            height: info.size[1] as f64,
            opening: fp.opening(info),
            front_access: false,
            wall: None,
            mounted: false,
            bottom: None,
        }
    }

    /// The height of a mounted object's bottom: where it was hung, or centred at
    /// [`WALL_MOUNT_HEIGHT`].
    pub(super) fn mounted_bottom(&self) -> f64 {
        self.bottom.unwrap_or(WALL_MOUNT_HEIGHT - self.height / 2.0)
    }

    /// The same object backed onto `wall`, so reached from its front.
    pub(super) fn against_wall(self, wall: String) -> Self {
        Self {
            front_access: true,
            wall: Some(wall),
            ..self
        }
    }
}

/// The object a relative placement positions against (the first positional relation).
pub(super) fn positional_target(o: &PlannedObject) -> Option<&str> {
    if o.zone != Zone::Relative {
        return None;
    }
    o.relations
        .iter()
        .find(|r| {
            !matches!(
                r.kind,
                RelationKind::AgainstWall | RelationKind::LeftOf | RelationKind::RightOf
            )
        })
        .map(|r| r.target.as_str())
}
