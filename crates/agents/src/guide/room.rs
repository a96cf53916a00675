//! The room a plan asks for: its size checked, its walls (or, outdoors, the edges of the
//! ground) as sides objects back onto, and every planned object's asset metadata.

use scenethesis_assets::AssetInfo;
use scenethesis_scene_graph::{Architecture, Environment, ParentRef};

use super::candidates::Side;
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
