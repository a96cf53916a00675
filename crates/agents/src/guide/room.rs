//! The room a plan asks for: its size checked, its walls (or, outdoors, the edges of the
//! ground) as sides objects back onto, and every planned object's asset metadata.

use scenethesis_scene_graph::AssetInfo;
use scenethesis_scene_graph::{Architecture, Environment, ParentRef};

use super::geometry::Footprint;
use super::shared::DOOR_WIDTH;
use super::{AssetLookup, GuideError};
use crate::plan::Plan;

/// The empty room of a plan.
pub(super) struct Room {
    /// Floor, walls and door (indoors) or open ground (outdoors).
    pub architecture: Architecture,
    /// Whether the plan is indoor (walls and a door).
    pub indoor: bool,
    /// Half the width (x) and depth (z) of the floor.
    pub half: [f64; 2],
    /// The four sides objects back onto, in the order of the walls.
    pub sides: Vec<Side>,
}

impl Room {
    /// The room of `plan`; rooms smaller than 1.5 m either way are refused.
    pub(super) fn of(plan: &Plan) -> Result<Self, GuideError> {
        let [width, depth] = plan.room_size;
        if !(width.is_finite() && depth.is_finite() && width >= 1.5 && depth >= 1.5) {
            return Err(GuideError::InvalidPlan(format!(
                "room_size {width} × {depth} m: expected at least 1.5 m each way"
            )));
        }
        let indoor = plan.environment == Environment::Indoor;
        let architecture = if indoor {
            Architecture::rectangular_room(width, depth, plan.wall_height.max(2.2), DOOR_WIDTH)
        } else {
            Architecture::open_ground(width, depth)
        };
        let (hw, hd) = (width / 2.0, depth / 2.0);
        let sides: Vec<Side> = {
            let (x, z) = (hw, hd);
            let id = |i: usize| indoor.then(|| format!("wall_{i}"));
            vec![
                Side {
                    id: id(0),
                    face: [0.0, -z],
                    normal: [0.0, 1.0],
                    along: [1.0, 0.0],
                    half_len: x,
                },
                Side {
                    id: id(1),
                    face: [-x, 0.0],
                    normal: [1.0, 0.0],
                    along: [0.0, 1.0],
                    half_len: z,
                },
                Side {
                    id: id(2),
                    face: [0.0, z],
                    normal: [0.0, -1.0],
                    along: [1.0, 0.0],
                    half_len: x,
                },
                Side {
                    id: id(3),
                    face: [x, 0.0],
                    normal: [-1.0, 0.0],
                    along: [0.0, 1.0],
                    half_len: z,
                },
            ]
        };

        Ok(Self {
            architecture,
            indoor,
            half: [hw, hd],
            sides,
        })
    }
}

/// The empty room a plan asks for (floor, walls and door indoors, open ground outdoors), as every
/// guide lays it out: the procedural guide places objects in it, the vision guide renders it
/// and lifts objects into it. Rooms smaller than 1.5 m either way are refused.
pub fn room_architecture(plan: &Plan) -> Result<Architecture, GuideError> {
    Room::of(plan).map(|room| room.architecture)
}

/// The asset metadata of every planned object, in plan order, after checking that every
/// parent is planned.
pub(super) fn asset_infos(
    plan: &Plan,
    assets: &dyn AssetLookup,
) -> Result<Vec<AssetInfo>, GuideError> {
    let mut infos: Vec<AssetInfo> = Vec::with_capacity(plan.objects.len());
    for o in &plan.objects {
        let info = assets
            .asset_info(o)
            .ok_or_else(|| GuideError::MissingAsset {
                id: o.id.clone(),
                category: o.category.clone(),
            })?;
        infos.push(info);
    }
    for o in &plan.objects {
        if let ParentRef::Object(p) = &o.parent {
            if plan.object(p).is_none() {
                return Err(GuideError::InvalidPlan(format!(
                    "object `{}`: parent `{p}` is not planned",
                    o.id
                )));
            }
        }
    }
    Ok(infos)
}

/// A wall (or, outdoors, an edge of the ground) that objects can back onto.
#[derive(Debug, Clone)]
pub(super) struct Side {
    pub(super) id: Option<String>,
    /// Point on the inner face at the middle of the wall.
    pub(super) face: [f64; 2],
    /// Unit normal into the room.
    pub(super) normal: [f64; 2],
    /// Unit direction along the wall.
    pub(super) along: [f64; 2],
    pub(super) half_len: f64,
}

impl Side {
    /// The yaw of an object backed onto this side, facing into the room.
    pub(super) fn yaw(&self) -> f64 {
        self.normal[0].atan2(self.normal[1])
    }

    /// The footprint of half-extents `hx` × `hz` backed onto this side at `s` along it.
    pub(super) fn footprint_at(&self, s: f64, hx: f64, hz: f64) -> Footprint {
        let gap = 0.01;
        Footprint {
            cx: self.face[0] + self.along[0] * s + self.normal[0] * (hz + gap),
            cz: self.face[1] + self.along[1] * s + self.normal[1] * (hz + gap),
            yaw: self.yaw(),
            hx,
            hz,
        }
    }

    /// How far along this side (either way from its middle) a footprint of half-width `hx`
    /// may sit.
    pub(super) fn limit(&self, hx: f64) -> f64 {
        self.half_len - hx - 0.01
    }
}
