//! Post-conditions on the exact distance fields: no pair of objects and no object/architecture
//! pair penetrates more than the tolerance, every resting object touches its support, and every
//! object is inside the room.

use std::collections::BTreeMap;

use nalgebra::Point3;
use scenethesis_scene_graph::{Aabb, Pose};
use serde::{Deserialize, Serialize};

use crate::objective::RoomBounds;
use crate::obstacles::{box_distance, posed_points, Obstacles};
use crate::prepare::PreparedAsset;
use crate::report::Issue;
use crate::support::Support;
use scenethesis_correspondence::params::world_point;

/// Tolerances of the post-conditions, in metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Tolerances {
    /// Largest allowed penetration depth between two objects or an object and the
    /// architecture (the collision metric counts more than 1 mm).
    pub penetration: f64,
    /// Largest allowed gap between a resting object's bottom and its support.
    pub support_gap: f64,
    /// Largest allowed overhang out of the floor rectangle.
    pub room: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            penetration: 0.001,
            support_gap: 0.002,
            room: 0.001,
        }
    }
}

/// One placed object to check.
pub(crate) struct Placed<'a> {
    pub id: &'a str,
    pub asset: &'a PreparedAsset,
    pub pose: Pose,
    pub support: &'a Support,
    /// The rectangle it must stay inside.
    pub room: RoomBounds,
}

/// The verdict for one object.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Verdict {
    pub penetration: f64,
    pub support_gap: Option<f64>,
    pub issues: Vec<Issue>,
}

/// Checks every post-condition of `placed` (whose exact fields are in `exact`, under their
/// ids, together with the architecture).
pub(crate) fn verify(placed: &[Placed<'_>], exact: &Obstacles, tol: &Tolerances) -> Vec<Verdict> {
    let mut verdicts: Vec<Verdict> = placed.iter().map(|_| Verdict::default()).collect();
    // Deepest penetration per unordered pair (object index, obstacle id).
    let mut pairs: BTreeMap<(String, String), f64> = BTreeMap::new();
    let index_of: BTreeMap<&str, usize> =
        placed.iter().enumerate().map(|(i, p)| (p.id, i)).collect();
    for (a, obj) in placed.iter().enumerate() {
        let points = posed_points(&obj.pose, obj.asset.check_points());
        let own_box = obj.asset.bounds().transformed(&obj.pose);
        for field in exact.near_box(&own_box, tol.penetration) {
            let other = exact.id(field);
            if other == obj.id {
                continue;
            }
            let depth = deepest(exact, field, &points, tol.penetration);
            if depth <= 0.0 {
                continue;
            }
            let key = if exact.is_architecture(field) || obj.id < other {
                (obj.id.to_owned(), other.to_owned())
            } else {
                (other.to_owned(), obj.id.to_owned())
            };
            let entry = pairs.entry(key).or_insert(0.0);
            *entry = entry.max(depth);
        }
        let v = &mut verdicts[a];
        match obj.support {
            Support::Free => {}
            Support::Surface(plane) => {
                let lowest = points.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
                let gap = lowest - plane.height;
                v.support_gap = Some(gap);
                if gap > tol.support_gap {
                    v.issues.push(Issue::Floating {
                        support: plane.owner.clone(),
                        gap,
                    });
                }
                let c = world_point(&obj.pose, &obj.asset.centroid());
                let off = plane.horizontal_distance(c.x, c.z);
                if off > tol.room {
                    v.issues.push(Issue::OffSupport {
                        support: plane.owner.clone(),
                        distance: off,
                    });
                }
            }
            Support::ParentGeometry { parent } => {
                if let Some(field) = exact.index_of(parent) {
                    let gap = obj
                        .asset
                        .bottom_points()
                        .iter()
                        .map(|p| exact.distance_to(field, &world_point(&obj.pose, p)))
                        .fold(f64::INFINITY, f64::min);
                    v.support_gap = Some(gap);
                    if gap > tol.support_gap {
                        v.issues.push(Issue::Floating {
                            support: parent.clone(),
                            gap,
                        });
                    }
                }
            }
        }
        let bounds = Aabb::from_points(points.iter()).unwrap_or(own_box);
        let overhang = obj.room.overhang(&bounds);
        if overhang > tol.room {
            v.issues.push(Issue::OutsideRoom { overhang });
        }
    }
    for ((a, b), depth) in pairs {
        for (me, other) in [(&a, &b), (&b, &a)] {
            if let Some(&i) = index_of.get(me.as_str()) {
                let v = &mut verdicts[i];
                v.penetration = v.penetration.max(depth);
                if depth > tol.penetration {
                    v.issues.push(Issue::Collision {
                        with: other.clone(),
                        depth,
                    });
                }
            }
        }
    }
    verdicts
}

/// The deepest penetration of `points` into field `field` (0 when none is inside), looking
/// only at points within `slack` of the field's box.
fn deepest(exact: &Obstacles, field: usize, points: &[Point3<f64>], slack: f64) -> f64 {
    let b = exact.bounds(field);
    points
        .iter()
        .filter(|p| box_distance(b, p) <= slack)
        .map(|p| -exact.distance_to(field, p))
        .fold(0.0, f64::max)
}
