//! One house scene from its furnished rooms: every room's objects moved from its frame into
//! the house, their ids prefixed by the room's id (`bedroom_1.bed_0`), `room` set, and the
//! walls they hang on or back onto renamed to the house's walls.

use std::collections::BTreeMap;

use nalgebra::{Point2, Vector2};
use scenethesis_scene_graph::{Architecture, Mesh, ParentRef, Scene, SceneObject};

use super::frame::RoomShell;

/// A furnished room in its own frame.
pub(crate) struct FurnishedRoom<'a> {
    /// The room's shell and frame.
    pub(crate) shell: &'a RoomShell,
    /// The scene laid out in the shell (room frame).
    pub(crate) scene: &'a Scene,
    /// Its objects' meshes by (room-local) id.
    pub(crate) meshes: &'a BTreeMap<String, Mesh>,
}

/// The id of a room's object in the house.
pub(crate) fn house_id(room: &str, object: &str) -> String {
    format!("{room}.{object}")
}

/// The house scene over `architecture` holding every room's objects, and their meshes by
/// house id. The anchor is the first room's.
pub(crate) fn assemble(
    architecture: Architecture,
    rooms: &[FurnishedRoom<'_>],
    prompt: &str,
    seed: u64,
) -> (Scene, BTreeMap<String, Mesh>) {
    let mut house = Scene::new(architecture);
    house.prompt = prompt.to_owned();
    house.seed = seed;
    let mut meshes = BTreeMap::new();
    for room in rooms {
        let id = &room.shell.id;
        if house.anchor.is_none() {
            house.anchor = room.scene.anchor.as_ref().map(|a| house_id(id, a));
        }
        if house.look.style.is_none() {
            house.look.style = room.scene.look.style.clone();
            house.look.surfaces = room.scene.look.surfaces.clone();
        }
        for (object, worn) in &room.scene.look.objects {
            house
                .look
                .objects
                .insert(house_id(id, object), worn.clone());
        }
        for object in &room.scene.objects {
            let moved = moved_object(object, room, &house.architecture);
            if let Some(mesh) = room.meshes.get(&object.id) {
                meshes.insert(moved.id.clone(), mesh.clone());
            }
            house.objects.push(moved);
        }
    }
    (house, meshes)
}

/// `object` of `room` in the house: posed in the house, its id, parent and relation targets
/// renamed, its room named.
fn moved_object(
    object: &SceneObject,
    room: &FurnishedRoom<'_>,
    house: &Architecture,
) -> SceneObject {
    let room_id = &room.shell.id;
    let local = &room.shell.architecture;
    let mut moved = object.clone();
    moved.id = house_id(room_id, &object.id);
    moved.pose = room.shell.frame.pose_to_house(&object.pose);
    moved.room = Some(room_id.clone());
    let centre = moved.world_aabb().center();
    let at = Point2::new(centre.x, centre.z);
    let rename = |target: &str| -> String {
        match local.walls.iter().find(|w| w.id == target) {
            Some(wall) => {
                let along = room.shell.frame.direction_to_house(wall.direction());
                nearest_wall(house, at, along).unwrap_or_else(|| target.to_owned())
            }
            None if target == scenethesis_scene_graph::GROUND_ID => target.to_owned(),
            None => house_id(room_id, target),
        }
    };
    moved.parent = match &object.parent {
        ParentRef::Ground => ParentRef::Ground,
        ParentRef::Object(p) => ParentRef::Object(house_id(room_id, p)),
        ParentRef::Wall(w) => ParentRef::Wall(rename(w)),
    };
    for relation in &mut moved.relations {
        relation.target = rename(&relation.target);
    }
    moved
}

/// The id of the house wall parallel to `along` nearest to the floor point `at`.
fn nearest_wall(house: &Architecture, at: Point2<f64>, along: Vector2<f64>) -> Option<String> {
    house
        .walls
        .iter()
        .filter(|w| w.direction().dot(&along).abs() > 0.99)
        .map(|w| (distance_to_segment(at, w.start, w.end), w))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, w)| w.id.clone())
}

/// The distance from `p` to the segment `a`–`b`.
fn distance_to_segment(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}
