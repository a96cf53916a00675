use std::fmt;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use nalgebra::Vector3;

use crate::{Aabb, AssetLook, JointState, Pose};

/// The reserved id of the ground, the root of every scene graph.
pub const GROUND_ID: &str = "ground";

/// A movable object of the scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneObject {
    /// Stable id: the key in `scene.json` and the glTF node name. Not serialized inside the
    /// object: `scene.json` stores it as the object's key.
    #[serde(skip)]
    pub id: String,
    /// Semantic category, e.g. `bookshelf`.
    pub category: String,
    /// Which mesh the object uses.
    pub asset: AssetRef,
    /// The object's 5-DoF pose in world coordinates.
    pub pose: Pose,
    /// What holds the object: the ground, another object, or the wall it hangs on.
    pub parent: ParentRef,
    /// How the object rests on its parent (`on-floor`, `against-wall`, `on`, `inside`, `under`,
    /// or `mounted` on a wall).
    pub support: RelationKind,
    /// Further spatial relations the layout should satisfy.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub relations: Vec<Relation>,
    /// Bounding box of the asset in its own frame, before the pose (scale 1).
    pub local_bounds: Aabb,
    /// The asset's joints and the state each is in (empty for a rigid object).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointState>,
    /// The parent's moving link this object rests in or on (a drawer, the shelf behind a
    /// door), so it moves with that part; `None` for the parent's fixed body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parent_link: Option<String>,
    /// The house room it stands in ([`RoomArea::id`](crate::RoomArea::id)); `None` in a
    /// single-room scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub room: Option<String>,
}

impl SceneObject {
    /// An object of category `id` standing unturned on the floor at (`x`, `z`), its mesh the
    /// procedural `box` generator (seed 0) and its local box `bounds`; no relations, no
    /// joints. A building block for tests and examples of every stage.
    ///
    /// ```
    /// use scenethesis_scene_graph::{nalgebra::Point3, Aabb, ParentRef, SceneObject};
    /// let bounds = Aabb::new(Point3::new(-0.4, 0.0, -0.25), Point3::new(0.4, 0.7, 0.25));
    /// let crate_box = SceneObject::standing_box("crate", bounds, 1.0, -2.0);
    /// assert_eq!(crate_box.parent, ParentRef::Ground);
    /// assert!((crate_box.world_aabb().min.z + 2.25).abs() < 1e-12);
    /// ```
    pub fn standing_box(id: &str, bounds: Aabb, x: f64, z: f64) -> SceneObject {
        SceneObject {
            id: id.into(),
            category: id.into(),
            asset: AssetRef::Procedural {
                generator: "box".into(),
                seed: 0,
                look: None,
            },
            pose: Pose::new(1.0, 0.0, Vector3::new(x, 0.0, z)),
            parent: ParentRef::Ground,
            support: RelationKind::OnFloor,
            relations: Vec::new(),
            local_bounds: bounds,
            joints: Vec::new(),
            parent_link: None,
            room: None,
        }
    }

    /// The world-space axis-aligned box of the posed asset.
    pub fn world_aabb(&self) -> Aabb {
        self.local_bounds.transformed(&self.pose)
    }

    /// Whether the object is fixed to the world (welded in a simulation, never moved by
    /// gravity): exactly when its support is [`RelationKind::Mounted`], i.e. it hangs on the
    /// wall its parent names ([`Scene::validate`](crate::Scene::validate) checks that the two
    /// go together). Every other object is a free body: one that floats without a mounted
    /// support is a defect, not something to weld.
    ///
    /// This is the one rule the optimizer, the evaluation, the judge and the exporters share.
    pub fn fixed_to_world(&self) -> bool {
        self.support.fixes_to_world()
    }
}

/// Where an object's mesh comes from.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum AssetRef {
    /// A built-in procedural generator run with a seed.
    Procedural {
        /// Generator name, usually the category.
        generator: String,
        /// Seed that fixes dimensions and materials.
        seed: u64,
        /// The look the asset was generated with (room style, requested colours and
        /// materials); `None` for the generator's own materials.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        look: Option<AssetLook>,
    },
    /// A user-supplied asset imported from a directory.
    Imported {
        /// The asset's id in its library's `assets.json`.
        id: String,
        /// Path of the mesh file as given to the importer.
        path: String,
    },
}

impl fmt::Display for AssetRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AssetRef::Procedural {
                generator,
                seed,
                look: None,
            } => write!(f, "{generator}#{seed}"),
            AssetRef::Procedural {
                generator,
                seed,
                look: Some(look),
            } => write!(f, "{generator}#{seed}~{}", &look.digest()[..8]),
            AssetRef::Imported { id, path } => write!(f, "{id} ({path})"),
        }
    }
}

/// An object's parent: the ground, another object, or a wall of the room. Serialized as a plain
/// string: `"ground"`, the object's id or the wall's id.
///
/// Object ids never equal architecture ids ([`Scene::validate`](crate::Scene::validate) refuses
/// the collision), so the string alone says which it is once the walls are known: a bare
/// `ParentRef` deserializes every id other than `ground` as [`ParentRef::Object`], and
/// deserializing a whole [`Scene`](crate::Scene) turns the ids of its walls into
/// [`ParentRef::Wall`] ([`ParentRef::resolve`]).
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ParentRef {
    /// The ground plane, root of the scene graph.
    Ground,
    /// Another object, by id.
    Object(String),
    /// A wall of the scene's architecture, by id: the object hangs on it (support
    /// [`RelationKind::Mounted`]). Walls stand on the ground, so such an object is a root of
    /// the hierarchy like a ground object.
    Wall(String),
}

impl ParentRef {
    /// The parent's object id, or `None` for the ground or a wall.
    pub fn object_id(&self) -> Option<&str> {
        match self {
            ParentRef::Object(id) => Some(id),
            ParentRef::Ground | ParentRef::Wall(_) => None,
        }
    }

    /// The wall's id when the parent is a wall.
    pub fn wall_id(&self) -> Option<&str> {
        match self {
            ParentRef::Wall(id) => Some(id),
            ParentRef::Ground | ParentRef::Object(_) => None,
        }
    }

    /// The id as written in `scene.json`: `ground`, the object's id or the wall's id.
    pub fn as_str(&self) -> &str {
        match self {
            ParentRef::Ground => GROUND_ID,
            ParentRef::Object(id) | ParentRef::Wall(id) => id,
        }
    }

    /// The parent named by `id` in a scene whose architecture has walls with the ids for which
    /// `is_wall` returns true: `ground`, a wall, or else an object.
    pub fn resolve(id: &str, is_wall: impl Fn(&str) -> bool) -> Self {
        if id == GROUND_ID {
            ParentRef::Ground
        } else if is_wall(id) {
            ParentRef::Wall(id.to_owned())
        } else {
            ParentRef::Object(id.to_owned())
        }
    }
}

impl fmt::Display for ParentRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Serialize for ParentRef {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl<'de> Deserialize<'de> for ParentRef {
    /// `ground` or an object id; wall ids are told apart by the scene ([`ParentRef::resolve`]).
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        Ok(ParentRef::resolve(&s, |_| false))
    }
}

/// The kinds of spatial relation a plan or scene may state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RelationKind {
    /// Resting on top of the target's support surface.
    On,
    /// Resting inside the target (a shelf compartment, a crate, a bowl).
    Inside,
    /// Standing underneath the target (under a table or desk).
    Under,
    /// Standing on the ground.
    OnFloor,
    /// Back against a wall (target: a wall id, or the ground for "any wall").
    AgainstWall,
    /// Hanging on a wall, off the floor (target: the wall id, also the object's parent). The
    /// only support that fixes an object to the world ([`RelationKind::fixes_to_world`]).
    Mounted,
    /// Next to the target, side by side.
    Beside,
    /// In front of the target (along the target's front direction).
    InFrontOf,
    /// Behind the target.
    Behind,
    /// To the target's left (seen from the target's front).
    LeftOf,
    /// To the target's right (seen from the target's front).
    RightOf,
    /// Turned so that its front points at the target.
    Facing,
    /// Arranged around the target (chairs around a table).
    Around,
}

impl RelationKind {
    /// Every relation kind, in declaration order.
    pub const ALL: [RelationKind; 13] = [
        RelationKind::On,
        RelationKind::Inside,
        RelationKind::Under,
        RelationKind::OnFloor,
        RelationKind::AgainstWall,
        RelationKind::Mounted,
        RelationKind::Beside,
        RelationKind::InFrontOf,
        RelationKind::Behind,
        RelationKind::LeftOf,
        RelationKind::RightOf,
        RelationKind::Facing,
        RelationKind::Around,
    ];

    /// The kebab-case name used in `scene.json` (e.g. `in-front-of`).
    pub fn as_str(&self) -> &'static str {
        match self {
            RelationKind::On => "on",
            RelationKind::Inside => "inside",
            RelationKind::Under => "under",
            RelationKind::OnFloor => "on-floor",
            RelationKind::AgainstWall => "against-wall",
            RelationKind::Mounted => "mounted",
            RelationKind::Beside => "beside",
            RelationKind::InFrontOf => "in-front-of",
            RelationKind::Behind => "behind",
            RelationKind::LeftOf => "left-of",
            RelationKind::RightOf => "right-of",
            RelationKind::Facing => "facing",
            RelationKind::Around => "around",
        }
    }

    /// Whether this relation says what physically supports an object (its parent link).
    pub fn is_support(&self) -> bool {
        matches!(
            self,
            RelationKind::On
                | RelationKind::Inside
                | RelationKind::Under
                | RelationKind::OnFloor
                | RelationKind::AgainstWall
                | RelationKind::Mounted
        )
    }

    /// Whether an object with this support is fixed to the world: only [`RelationKind::Mounted`].
    /// Read it through [`SceneObject::fixed_to_world`] when a scene object is at hand.
    pub fn fixes_to_world(&self) -> bool {
        matches!(self, RelationKind::Mounted)
    }
}

impl fmt::Display for RelationKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A spatial relation from the owning object to a target: another object's id, a wall id, or
/// `ground`.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Relation {
    /// What kind of relation.
    pub kind: RelationKind,
    /// Id of the related object, wall or `ground`.
    pub target: String,
}

impl Relation {
    /// A relation of `kind` to `target`.
    pub fn new(kind: RelationKind, target: impl Into<String>) -> Self {
        Self {
            kind,
            target: target.into(),
        }
    }
}
