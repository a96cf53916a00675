//! The scene graph shared by every scenethesis stage.
//!
//! A [`Scene`] holds the room's [`Architecture`] (floor, walls, door openings), the movable
//! [`SceneObject`]s with their 5-DoF [`Pose`]s (uniform scale, yaw about +Y, translation), the
//! anchor object, parent links rooted at the ground (an object hung on a wall names the wall as
//! its parent, with support `mounted`: [`SceneObject::fixed_to_world`]), and spatial
//! [`Relation`]s. It reads and
//! writes `scene.json` ([`Scene::from_json_str`], [`Scene::write_json_atomic`]), checks itself
//! ([`Scene::validate`]) and walks its hierarchy breadth-first from the ground
//! ([`Scene::bfs_order`]). The triangle [`Mesh`] with per-part [`Material`]s lives here too, so
//! that assets, rendering, signed distance fields, correspondence and export share one geometry,
//! and so do the yaw rules every stage uses ([`wrap_yaw`], [`yaw_distance`]). The pinhole camera
//! and the images live in `scenethesis-imagery`.
//!
//! Conventions: metres, right-handed, +Y up, ground plane at y = 0. An object's canonical front
//! is +Z in its own frame, and the origin of an asset's frame is the centre of its footprint at
//! its lowest point, so a pose's translation is where the object stands.
//!
//! A room with a table and a mug on it, checked, walked from the ground and round-tripped
//! through `scene.json`:
//!
//! ```
//! use scenethesis_scene_graph::nalgebra::{Point3, Vector3};
//! use scenethesis_scene_graph::{
//!     Aabb, Architecture, AssetRef, ParentRef, Pose, RelationKind, Scene, SceneObject,
//! };
//!
//! let mut scene = Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.6, 0.9));
//! let table = SceneObject {
//!     id: "table_0".into(),
//!     category: "dining_table".into(),
//!     asset: AssetRef::Procedural { generator: "dining_table".into(), seed: 1, look: None },
//!     pose: Pose::new(1.0, 0.0, Vector3::new(0.0, 0.0, -0.5)),
//!     parent: ParentRef::Ground,
//!     support: RelationKind::OnFloor,
//!     relations: Vec::new(),
//!     local_bounds: Aabb::new(Point3::new(-0.6, 0.0, -0.4), Point3::new(0.6, 0.75, 0.4)),
//!     joints: Vec::new(),
//!     parent_link: None,
//!     room: None,
//! };
//! let mug = SceneObject {
//!     id: "mug_0".into(),
//!     category: "mug".into(),
//!     asset: AssetRef::Procedural { generator: "mug".into(), seed: 2, look: None },
//!     pose: Pose::new(1.0, 0.0, Vector3::new(0.1, 0.75, -0.5)),
//!     parent: ParentRef::Object("table_0".into()),
//!     support: RelationKind::On,
//!     relations: Vec::new(),
//!     local_bounds: Aabb::new(Point3::new(-0.05, 0.0, -0.05), Point3::new(0.05, 0.1, 0.05)),
//!     joints: Vec::new(),
//!     parent_link: None,
//!     room: None,
//! };
//! scene.anchor = Some("table_0".into());
//! scene.objects = vec![mug, table]; // stored order is free; the hierarchy orders the walk
//! assert!(scene.validate().is_ok());
//!
//! let order: Vec<&str> = scene.bfs_order()?.iter().map(|o| o.id.as_str()).collect();
//! assert_eq!(order, ["table_0", "mug_0"]);
//! assert!((scene.object("mug_0").unwrap().world_aabb().min.y - 0.75).abs() < 1e-12);
//!
//! let back = Scene::from_json_str(&scene.to_json_string()).expect("scene.json parses");
//! assert_eq!(back, scene);
//! # Ok::<(), scenethesis_scene_graph::ValidationError>(())
//! ```

#![warn(missing_docs)]

mod aabb;
mod architecture;
mod asset;
mod carry;
mod door;
mod floor_raster;
mod hash;
mod hull;
mod io;
mod joint;
pub mod limits;
mod look;
mod mesh;
mod object;
mod openings;
mod pose;
mod recovery;
mod relations;
mod scene;
mod texture;
mod traversal;
mod validate;
mod walkway;

pub use aabb::{is_square_footprint, Aabb, SQUARE_FOOTPRINT};
pub use architecture::{
    hangs_on_wall, Architecture, DoorOpening, Environment, Floor, RoomArea, Wall, WindowOpening,
    EXTERIOR, MOUNT_MIN_BOTTOM, MOUNT_WALL_REACH,
};
pub use asset::{
    holds_under, is_low_shelf, Asset, AssetInfo, Placement, SupportSurface, SurfaceKind,
    LOW_SHELF_SHARE,
};
pub use door::{
    leaf_material, DoorLeaf, LeafGeometry, LEAF_FLOOR_GAP, LEAF_GAP, LEAF_JOINT, LEAF_OPEN_LIMIT,
    LEAF_THICKNESS, SECOND_LEAF_JOINT,
};
pub use floor_raster::{Components, FloorRaster, BLOCKED_CELL};
pub use hash::{fnv1a64, fnv1a64_from, mix64, FNV_OFFSET_BASIS, GOLDEN_GAMMA};
pub use hull::convex_hull;
pub use io::{read_bounded, write_file_atomic, SceneIoError};
pub use joint::{
    carried_by, opening_sweep, Joint, JointError, JointKind, JointState, OpenState, OpensTo,
    OPEN_SHARE,
};
pub use look::{AssetLook, LookAttribute, LookScope, SceneLook, Srgb, WornMaterial};
pub use mesh::{Material, Mesh, MeshPart};
pub use object::{AssetRef, ParentRef, Relation, RelationKind, SceneObject, GROUND_ID};
pub use openings::{WallBox, PANE_THICKNESS, WINDOW_CLEARANCE, WINDOW_COVER_SHARE};
pub use pose::{wrap_yaw, yaw_distance, yaw_distance_modulo, Pose};
pub use recovery::recovery_errors;
pub use relations::{
    aabb_floor_gap, floor_centre, floor_gap, front_dir, relation_holds, right_dir, FACING_TOLERANCE,
};
pub use scene::{Scene, FORMAT_VERSION};
pub use texture::{TextureError, TextureImage};
pub use validate::{is_printable_id, printable, OutOfBounds, ValidationError};
pub use walkway::ROBOT_RADIUS;

/// Re-export of the linear-algebra crate used in this crate's public types.
pub use nalgebra;

#[cfg(test)]
pub(crate) mod test_support {
    use crate::*;
    use nalgebra::{Point3, Vector3};

    /// A unit-box object with the given parent link.
    pub fn object(id: &str, parent: ParentRef, support: RelationKind) -> SceneObject {
        SceneObject {
            id: id.into(),
            category: "box".into(),
            asset: AssetRef::Procedural {
                generator: "box".into(),
                seed: 1,
                look: None,
            },
            pose: Pose::new(1.0, 0.0, Vector3::zeros()),
            parent,
            support,
            relations: Vec::new(),
            local_bounds: Aabb::new(Point3::new(-0.5, 0.0, -0.5), Point3::new(0.5, 1.0, 0.5)),
            joints: Vec::new(),
            parent_link: None,
            room: None,
        }
    }

    /// A window 1.2 m wide and high, its sill 0.9 m up, centred `offset` m along `wall`.
    pub fn window(id: &str, wall: &str, offset: f64) -> WindowOpening {
        WindowOpening {
            id: id.into(),
            wall: wall.into(),
            offset,
            width: 1.2,
            height: 1.2,
            sill: 0.9,
            room: None,
        }
    }

    /// A 6 × 4 m room holding `objects`.
    pub fn scene_with(objects: Vec<SceneObject>) -> Scene {
        let mut scene = Scene::new(Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9));
        scene.objects = objects;
        scene
    }
}
