use std::fmt;

use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::{Aabb, Architecture, ParentRef, SceneLook, SceneObject};

/// The `scene.json` format version this build reads and writes.
pub const FORMAT_VERSION: u32 = 1;

/// A whole scene: architecture, objects, anchor and hierarchy.
///
/// Deserializing a scene reads each object's `parent` string against the architecture: the id
/// of one of its walls becomes [`ParentRef::Wall`] (a mounted object), `ground` the ground, and
/// anything else an object id.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(from = "SceneFile")]
pub struct Scene {
    /// Version of the `scene.json` format; [`FORMAT_VERSION`] for scenes built here.
    pub format_version: u32,
    /// The text prompt the scene was generated from (empty for hand-made scenes).
    #[serde(default)]
    pub prompt: String,
    /// The seed the scene was generated with.
    #[serde(default)]
    pub seed: u64,
    /// Floor, walls and door openings.
    pub architecture: Architecture,
    /// Id of the anchor object, the first object placed after the ground.
    #[serde(default)]
    pub anchor: Option<String>,
    /// The movable objects in a stable order. In `scene.json` this is a JSON object keyed by
    /// object id, in this order; every entry also carries its derived `world_aabb`.
    #[serde(with = "object_map")]
    pub objects: Vec<SceneObject>,
    /// The room's style, its surfaces' materials and every object's worn materials (empty
    /// for scenes made without looks).
    #[serde(default, skip_serializing_if = "SceneLook::is_empty")]
    pub look: SceneLook,
}

impl Scene {
    /// An empty scene over the given architecture.
    pub fn new(architecture: Architecture) -> Self {
        Self {
            format_version: FORMAT_VERSION,
            prompt: String::new(),
            seed: 0,
            architecture,
            anchor: None,
            objects: Vec::new(),
            look: SceneLook::default(),
        }
    }

    /// The object with this id.
    pub fn object(&self, id: &str) -> Option<&SceneObject> {
        self.objects.iter().find(|o| o.id == id)
    }

    /// The object with this id, mutably.
    pub fn object_mut(&mut self, id: &str) -> Option<&mut SceneObject> {
        self.objects.iter_mut().find(|o| o.id == id)
    }

    /// The objects whose parent is `parent`, in stored order.
    pub fn children_of<'a>(
        &'a self,
        parent: &'a ParentRef,
    ) -> impl Iterator<Item = &'a SceneObject> + 'a {
        self.objects.iter().filter(move |o| &o.parent == parent)
    }

    /// The anchor object, if one is set and exists.
    pub fn anchor_object(&self) -> Option<&SceneObject> {
        self.anchor.as_deref().and_then(|id| self.object(id))
    }

    /// The union of all objects' world boxes, or `None` for an empty scene.
    pub fn objects_aabb(&self) -> Option<Aabb> {
        self.objects
            .iter()
            .map(SceneObject::world_aabb)
            .reduce(|a, b| a.union(&b))
    }
}

/// `scene.json` as parsed, before parents are resolved against the walls.
#[derive(Deserialize)]
struct SceneFile {
    format_version: u32,
    #[serde(default)]
    prompt: String,
    #[serde(default)]
    seed: u64,
    architecture: Architecture,
    #[serde(default)]
    anchor: Option<String>,
    #[serde(with = "object_map")]
    objects: Vec<SceneObject>,
    #[serde(default)]
    look: SceneLook,
}

impl From<SceneFile> for Scene {
    fn from(file: SceneFile) -> Self {
        let SceneFile {
            format_version,
            prompt,
            seed,
            architecture,
            anchor,
            mut objects,
            look,
        } = file;
        for object in &mut objects {
            if let ParentRef::Object(id) = &object.parent {
                if architecture.wall(id).is_some() {
                    object.parent = ParentRef::Wall(id.clone());
                }
            }
        }
        Scene {
            format_version,
            prompt,
            seed,
            architecture,
            anchor,
            objects,
            look,
        }
    }
}

/// Serde for the object list as a JSON map keyed by id, keeping order and duplicate keys (so
/// that validation can report duplicates instead of silently dropping one).
mod object_map {
    use super::*;

    #[derive(Serialize)]
    struct Entry<'a> {
        #[serde(flatten)]
        object: &'a SceneObject,
        world_aabb: Aabb,
    }

    pub fn serialize<S: Serializer>(objects: &[SceneObject], s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(objects.len()))?;
        for object in objects {
            let entry = Entry {
                object,
                world_aabb: object.world_aabb(),
            };
            map.serialize_entry(&object.id, &entry)?;
        }
        map.end()
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<SceneObject>, D::Error> {
        struct ObjectsVisitor;
        impl<'de> Visitor<'de> for ObjectsVisitor {
            type Value = Vec<SceneObject>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a map from object id to object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
                let mut out = Vec::new();
                while let Some((id, mut object)) = map.next_entry::<String, SceneObject>()? {
                    object.id = id;
                    out.push(object);
                }
                Ok(out)
            }
        }
        d.deserialize_map(ObjectsVisitor)
    }
}
