use std::borrow::Cow;
use std::collections::HashMap;

use crate::limits::{
    MAX_COORDINATE, MAX_DOORS, MAX_ID_BYTES, MAX_OBJECTS, MAX_OBJECT_SIZE, MAX_RELATIONS,
    MAX_ROOMS, MAX_ROOM_CORNERS, MAX_SCALE, MAX_WALLS, MAX_WALL_HEIGHT, MAX_WALL_THICKNESS,
    MAX_WINDOWS, MAX_YAW, MIN_SCALE,
};
use crate::{
    Aabb, Architecture, AssetRef, DoorLeaf, DoorOpening, Floor, OpensTo, ParentRef, Pose,
    RelationKind, RoomArea, Scene, SceneObject, Wall, WindowOpening, EXTERIOR, FORMAT_VERSION,
    GROUND_ID, LEAF_FLOOR_GAP, LEAF_GAP, LEAF_OPEN_LIMIT,
};

/// `text` safe to print on a terminal or write into a log line: control characters (escape
/// sequences, newlines, carriage returns, bidi overrides are not the only danger, but the control
/// characters are what can drive a terminal) are replaced by Rust-style escapes such as `\u{1b}`.
/// Text without control characters is returned unchanged.
pub fn printable(text: &str) -> Cow<'_, str> {
    if !text.chars().any(needs_escape) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if needs_escape(c) {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// Whether `c` must not reach a terminal raw: C0/C1 controls, DEL and the bidirectional
/// formatting characters that reorder what the reader sees.
fn needs_escape(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// Whether `id` is usable as an id: 1 to [`MAX_ID_BYTES`] bytes of printable characters (no
/// control or bidi formatting characters, no leading or trailing white space).
pub fn is_printable_id(id: &str) -> bool {
    !id.is_empty() && id.len() <= MAX_ID_BYTES && !id.chars().any(needs_escape) && id.trim() == id
}

/// One rule a scene breaks, naming the object (or architecture element) and field at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ValidationError {
    /// The file's `format_version` is not one this build reads.
    #[error("format_version is {found}, but this build reads version {expected}")]
    UnsupportedVersion {
        /// The version in the file.
        found: u32,
        /// The version this build reads.
        expected: u32,
    },
    /// An id is empty.
    #[error("{owner} has an empty id; every object, wall, door and floor needs a non-empty id")]
    EmptyId {
        /// Which element (e.g. `object #3`, `wall #0`).
        owner: String,
    },
    /// An object uses the id reserved for the ground.
    #[error("object `{id}` uses the reserved id `ground`")]
    ReservedId {
        /// The offending id.
        id: String,
    },
    /// An id or name holds characters the tools cannot print or write safely, or is too long.
    #[error("{owner}: field `{field}` is {shown}, expected 1 to {max} bytes of printable characters without leading or trailing spaces", max = MAX_ID_BYTES)]
    UnprintableId {
        /// Which element (e.g. `object #3`).
        owner: String,
        /// The field (`id`, `category`, ...).
        field: &'static str,
        /// The value, escaped and shortened for printing.
        shown: String,
    },
    /// More elements of one kind than the tools handle.
    #[error("the scene has {count} {what}, more than the limit of {limit} (see docs/limits.md)")]
    TooMany {
        /// What is counted (`objects`, `walls`, ...).
        what: &'static str,
        /// How many there are.
        count: usize,
        /// The limit.
        limit: usize,
    },
    /// An object's procedural generator is not one this build knows.
    #[error("object `{id}`: asset.generator `{generator}` is not a built-in generator")]
    UnknownGenerator {
        /// The object id.
        id: String,
        /// The generator named in the file.
        generator: String,
    },
    /// Two elements share one id.
    #[error("id `{id}` is used more than once (by {first} and {second})")]
    DuplicateId {
        /// The repeated id.
        id: String,
        /// What kind of element first uses it.
        first: &'static str,
        /// What kind of element uses it again.
        second: &'static str,
    },
    /// A joint of an object is malformed (zero axis, reversed limits, …).
    #[error("object `{id}`: joints: {error}")]
    BadJoint {
        /// The object id.
        id: String,
        /// What is wrong with the joint.
        error: crate::JointError,
    },
    /// A joint's state lies outside its limits.
    #[error("object `{id}`: joint `{joint}` has state {state}, outside its limits {limits:?}")]
    JointStateOutOfRange {
        /// The object id.
        id: String,
        /// The joint's name.
        joint: String,
        /// The state found.
        state: f32,
        /// The joint's limits.
        limits: [f32; 2],
    },
    /// `parent_link` names no joint of the parent object.
    #[error("object `{id}`: parent_link `{link}` is not a joint of its parent `{parent}`")]
    UnknownParentLink {
        /// The object id.
        id: String,
        /// The link named.
        link: String,
        /// The parent's id.
        parent: String,
    },
    /// A door leaf is hinged on neither side (`opens_to` up, down or out).
    #[error("door `{door}`: field `leaf.opens_to` is {opens_to:?}, expected left or right")]
    BadLeafHinge {
        /// The door id.
        door: String,
        /// The side found.
        opens_to: OpensTo,
    },
    /// A number is NaN or infinite.
    #[error("{owner}: field `{field}` is not a finite number")]
    NonFinite {
        /// The object or element id.
        owner: String,
        /// The field path, e.g. `pose.translation`.
        field: &'static str,
    },
    /// An object's scale is zero or negative.
    #[error("object `{id}`: pose.scale is {scale}, expected a positive number")]
    NonPositiveScale {
        /// The object id.
        id: String,
        /// The scale found.
        scale: f64,
    },
    /// A number is outside its allowed range.
    #[error("{owner}: field `{field}` is {}, expected {expected}", show_number(*value))]
    OutOfRange {
        /// The object or element id.
        owner: String,
        /// The field path.
        field: &'static str,
        /// The value found.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// An object's parent is not an object or wall of the scene.
    #[error(
        "object `{id}`: parent `{parent}` is not an object or wall of this scene (nor `ground`)"
    )]
    UnknownParent {
        /// The object id.
        id: String,
        /// The missing parent id.
        parent: String,
    },
    /// An object's support is `mounted` but its parent is not a wall.
    #[error("object `{id}`: support `mounted` needs a wall of this scene as parent, but the parent is `{parent}`")]
    MountedOffWall {
        /// The object id.
        id: String,
        /// The parent it names instead.
        parent: String,
    },
    /// An object hangs on a wall (its parent is a wall id) with a support other than `mounted`.
    #[error(
        "object `{id}`: parent `{wall}` is a wall, so support must be `mounted`, not `{support}`"
    )]
    WallParentNotMounted {
        /// The object id.
        id: String,
        /// The wall id.
        wall: String,
        /// The support found.
        support: String,
    },
    /// Objects whose parents form a loop, so they never reach the ground.
    #[error("objects {ids:?} form a parent cycle and never reach the ground")]
    ParentCycle {
        /// The ids on the cycle, sorted.
        ids: Vec<String>,
    },
    /// A relation points at something that does not exist.
    #[error("object `{id}`: relation `{kind}` targets `{target}`, which is not an object, wall or `ground` of this scene")]
    MissingRelationTarget {
        /// The object id.
        id: String,
        /// The relation kind.
        kind: String,
        /// The missing target.
        target: String,
    },
    /// The anchor id is not an object of the scene.
    #[error("anchor `{anchor}` is not an object of this scene")]
    UnknownAnchor {
        /// The anchor id.
        anchor: String,
    },
    /// The anchor does not stand on the ground.
    #[error("anchor `{anchor}` has parent `{parent}`, expected `ground`")]
    AnchorNotOnGround {
        /// The anchor id.
        anchor: String,
        /// Its parent.
        parent: String,
    },
    /// A door names a wall that does not exist.
    #[error("door `{door}`: wall `{wall}` is not a wall of this scene")]
    UnknownDoorWall {
        /// The door id.
        door: String,
        /// The missing wall id.
        wall: String,
    },
    /// A window names a wall that does not exist.
    #[error("window `{window}`: wall `{wall}` is not a wall of this scene")]
    UnknownWindowWall {
        /// The window id.
        window: String,
        /// The missing wall id.
        wall: String,
    },
    /// Two openings (a window and a door, or two windows) overlap along their wall.
    #[error(
        "{first} and {second} overlap on wall `{wall}`; openings in one wall must not overlap"
    )]
    OpeningsOverlap {
        /// The first opening (e.g. `door `door_0``).
        first: String,
        /// The second opening (e.g. `window `window_0``).
        second: String,
        /// The wall both are cut into.
        wall: String,
    },
    /// An object, door or window names a room that is not in `architecture.rooms`.
    #[error("{owner}: field `{field}` names room `{room}`, which is not in architecture.rooms{}", if *is_exterior_ok { " (nor `exterior`)" } else { "" })]
    UnknownRoom {
        /// Which element (e.g. `object `sofa``).
        owner: String,
        /// The field (`room`, `joins`).
        field: &'static str,
        /// The room named.
        room: String,
        /// Whether `exterior` would also have been accepted (a door's `joins`).
        is_exterior_ok: bool,
    },
    /// A door joins a room to itself.
    #[error("door `{door}`: field `joins` names `{room}` twice, expected two different rooms")]
    DoorJoinsItself {
        /// The door id.
        door: String,
        /// The room named twice.
        room: String,
    },
    /// A room's floor outline is not a usable polygon.
    #[error("room `{room}`: field `polygon` {problem}")]
    BadRoomOutline {
        /// The room id.
        room: String,
        /// What is wrong.
        problem: String,
    },
}

impl Scene {
    /// Checks every rule of a well-formed scene and returns all problems found, each naming the
    /// object or element and field at fault. Never panics, whatever the contents.
    ///
    /// Besides the structural rules, every number must lie within the ranges of
    /// [`crate::limits`] (documented in `docs/limits.md`), which bound the work of every tool
    /// that reads a scene, and every id must be printable ([`is_printable_id`]). A scene with
    /// more objects, walls or doors than the limits is reported with that one problem only.
    pub fn validate(&self) -> Result<(), Vec<ValidationError>> {
        let mut errors = Vec::new();
        let arch = &self.architecture;
        for (what, count, limit) in [
            ("objects", self.objects.len(), MAX_OBJECTS),
            ("walls", arch.walls.len(), MAX_WALLS),
            ("doors", arch.doors.len(), MAX_DOORS),
            ("windows", arch.windows.len(), MAX_WINDOWS),
            ("rooms", arch.rooms.len(), MAX_ROOMS),
        ] {
            if count > limit {
                errors.push(ValidationError::TooMany { what, count, limit });
            }
        }
        if let Some(o) = self
            .objects
            .iter()
            .find(|o| o.relations.len() > MAX_RELATIONS)
        {
            errors.push(ValidationError::TooMany {
                what: "relations on one object",
                count: o.relations.len(),
                limit: MAX_RELATIONS,
            });
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        if self.format_version != FORMAT_VERSION {
            errors.push(ValidationError::UnsupportedVersion {
                found: self.format_version,
                expected: FORMAT_VERSION,
            });
        }
        self.check_ids(&mut errors);
        self.check_architecture(&mut errors);
        self.check_objects(&mut errors);
        if let Some(anchor) = &self.anchor {
            match self.object(anchor) {
                None => errors.push(ValidationError::UnknownAnchor {
                    anchor: anchor.clone(),
                }),
                Some(o) if o.parent != ParentRef::Ground => {
                    errors.push(ValidationError::AnchorNotOnGround {
                        anchor: anchor.clone(),
                        parent: o.parent.to_string(),
                    })
                }
                Some(_) => {}
            }
        }
        errors.extend(self.parent_link_errors());
        if errors.is_empty() {
            Ok(())
        } else {
            Err(errors)
        }
    }

    /// Problems with procedural generators: every `procedural` asset must name a generator for
    /// which `known` returns true (the asset library passes its catalogue lookup).
    pub fn generator_errors(&self, known: impl Fn(&str) -> bool) -> Vec<ValidationError> {
        self.objects
            .iter()
            .filter_map(|o| match &o.asset {
                AssetRef::Procedural { generator, .. } if !known(generator) => {
                    Some(ValidationError::UnknownGenerator {
                        id: printable(&o.id).into_owned(),
                        generator: shorten(generator),
                    })
                }
                _ => None,
            })
            .collect()
    }

    fn check_ids(&self, errors: &mut Vec<ValidationError>) {
        let arch = &self.architecture;
        let mut seen: HashMap<&str, &'static str> = HashMap::new();
        let elements = std::iter::once(("floor", arch.floor.id.as_str()))
            .chain(arch.walls.iter().map(|w| ("wall", w.id.as_str())))
            .chain(arch.doors.iter().map(|d| ("door", d.id.as_str())))
            .chain(arch.windows.iter().map(|w| ("window", w.id.as_str())))
            .chain(arch.rooms.iter().map(|r| ("room", r.id.as_str())))
            .chain(self.objects.iter().map(|o| ("object", o.id.as_str())));
        let mut counts: HashMap<&'static str, usize> = HashMap::new();
        for (kind, id) in elements {
            let n = counts.entry(kind).or_default();
            if !id.is_empty() && !is_printable_id(id) {
                errors.push(ValidationError::UnprintableId {
                    owner: format!("{kind} #{n}"),
                    field: "id",
                    shown: shorten(id),
                });
            } else if id.is_empty() {
                errors.push(ValidationError::EmptyId {
                    owner: format!("{kind} #{n}"),
                });
            } else if id == GROUND_ID {
                errors.push(ValidationError::ReservedId { id: id.to_owned() });
            } else if let Some(first) = seen.insert(id, kind) {
                let id = &*printable(id);
                errors.push(ValidationError::DuplicateId {
                    id: id.to_owned(),
                    first,
                    second: kind,
                });
            }
            *n += 1;
        }
    }

    fn check_architecture(&self, errors: &mut Vec<ValidationError>) {
        let arch = &self.architecture;
        check_floor(&arch.floor, errors);
        for wall in &arch.walls {
            check_wall(wall, errors);
        }
        for door in &arch.doors {
            check_door(arch, door, errors);
            check_joins(arch, door, errors);
        }
        for window in &arch.windows {
            check_window(arch, window, errors);
        }
        check_overlaps(arch, errors);
        for room in &arch.rooms {
            check_room_outline(room, errors);
        }
    }

    fn check_objects(&self, errors: &mut Vec<ValidationError>) {
        for object in &self.objects {
            let id = &*printable(&object.id);
            check_object_names(object, id, errors);
            check_pose(&object.pose, id, errors);
            check_local_bounds(object, id, errors);
            self.check_parent(object, id, errors);
            self.check_relation_targets(object, id, errors);
            check_joints(object, id, errors);
            self.check_parent_link(object, id, errors);
            if let Some(room) = &object.room {
                check_room_named(
                    &self.architecture,
                    &format!("object `{id}`"),
                    "room",
                    room,
                    errors,
                );
            }
        }
    }

    /// A `parent_link` names a joint of the object's parent.
    fn check_parent_link(&self, object: &SceneObject, id: &str, errors: &mut Vec<ValidationError>) {
        let Some(link) = &object.parent_link else {
            return;
        };
        let parent = match &object.parent {
            ParentRef::Object(p) => self.object(p),
            _ => None,
        };
        let known = parent.is_some_and(|p| p.joints.iter().any(|j| &j.joint.name == link));
        if !known {
            errors.push(ValidationError::UnknownParentLink {
                id: id.to_owned(),
                link: shorten(link),
                parent: shorten(&object.parent.to_string()),
            });
        }
    }

    /// A wall parent is a wall of the architecture and holds the object `mounted`; a mounted
    /// object hangs on a wall.
    fn check_parent(&self, object: &SceneObject, id: &str, errors: &mut Vec<ValidationError>) {
        let arch = &self.architecture;
        match &object.parent {
            ParentRef::Wall(wall) => {
                if arch.wall(wall).is_none() {
                    errors.push(ValidationError::UnknownParent {
                        id: id.to_owned(),
                        parent: shorten(wall),
                    });
                } else if object.support != RelationKind::Mounted {
                    errors.push(ValidationError::WallParentNotMounted {
                        id: id.to_owned(),
                        wall: shorten(wall),
                        support: object.support.to_string(),
                    });
                }
            }
            parent if object.support == RelationKind::Mounted => {
                errors.push(ValidationError::MountedOffWall {
                    id: id.to_owned(),
                    parent: shorten(parent.as_str()),
                });
            }
            _ => {}
        }
    }

    /// Every relation names the ground, an object or a part of the architecture.
    fn check_relation_targets(
        &self,
        object: &SceneObject,
        id: &str,
        errors: &mut Vec<ValidationError>,
    ) {
        for relation in &object.relations {
            let t = relation.target.as_str();
            let exists = t == GROUND_ID
                || self.object(t).is_some()
                || self.architecture.ids().any(|a| a == t);
            if !exists {
                errors.push(ValidationError::MissingRelationTarget {
                    id: id.to_owned(),
                    kind: relation.kind.to_string(),
                    target: shorten(t),
                });
            }
        }
    }
}

/// The floor's numbers are finite, within ±[`MAX_COORDINATE`], and span a positive area.
fn check_floor(floor: &Floor, errors: &mut Vec<ValidationError>) {
    if !(floor
        .min
        .iter()
        .chain(floor.max.iter())
        .all(|v| v.is_finite()))
    {
        errors.push(non_finite(&floor.id, "min/max"));
    } else if let Some(v) = floor
        .min
        .iter()
        .chain(floor.max.iter())
        .find(|v| v.abs() > MAX_COORDINATE)
    {
        errors.push(out_of_range(
            &floor.id,
            "min/max",
            *v,
            "coordinates within ±1000 m (limits::MAX_COORDINATE)",
        ));
    } else {
        let e = floor.extent();
        for (v, field) in [(e.x, "max.x - min.x"), (e.y, "max.z - min.z")] {
            if v <= 0.0 {
                errors.push(out_of_range(&floor.id, field, v, "a positive floor size"));
            }
        }
    }
}

/// A wall's numbers are finite and within the limits, its length, height and thickness positive.
fn check_wall(wall: &Wall, errors: &mut Vec<ValidationError>) {
    let numbers = [
        wall.start.x,
        wall.start.y,
        wall.end.x,
        wall.end.y,
        wall.height,
        wall.thickness,
    ];
    if !numbers.iter().all(|v| v.is_finite()) {
        errors.push(non_finite(&wall.id, "start/end/height/thickness"));
        return;
    }
    if let Some(v) = numbers[..4].iter().find(|v| v.abs() > MAX_COORDINATE) {
        errors.push(out_of_range(
            &wall.id,
            "start/end",
            *v,
            "coordinates within ±1000 m (limits::MAX_COORDINATE)",
        ));
    }
    if wall.height > MAX_WALL_HEIGHT {
        errors.push(out_of_range(
            &wall.id,
            "height",
            wall.height,
            "at most 100 m (limits::MAX_WALL_HEIGHT)",
        ));
    }
    if wall.thickness > MAX_WALL_THICKNESS {
        errors.push(out_of_range(
            &wall.id,
            "thickness",
            wall.thickness,
            "at most 10 m (limits::MAX_WALL_THICKNESS)",
        ));
    }
    if wall.length() <= 0.0 {
        errors.push(out_of_range(
            &wall.id,
            "end",
            wall.length(),
            "an end point different from start",
        ));
    }
    if wall.height <= 0.0 {
        errors.push(out_of_range(
            &wall.id,
            "height",
            wall.height,
            "a positive height",
        ));
    }
    if wall.thickness <= 0.0 {
        errors.push(out_of_range(
            &wall.id,
            "thickness",
            wall.thickness,
            "a positive thickness",
        ));
    }
}

/// A door's numbers are finite and within the limits, and it opens within a wall of `arch`.
fn check_door(arch: &Architecture, door: &DoorOpening, errors: &mut Vec<ValidationError>) {
    if ![door.offset, door.width, door.height]
        .iter()
        .all(|v| v.is_finite())
    {
        errors.push(non_finite(&door.id, "offset/width/height"));
        return;
    }
    if door.height > MAX_WALL_HEIGHT {
        errors.push(out_of_range(
            &door.id,
            "height",
            door.height,
            "at most 100 m (limits::MAX_WALL_HEIGHT)",
        ));
    }
    if door.width <= 0.0 {
        errors.push(out_of_range(
            &door.id,
            "width",
            door.width,
            "a positive width",
        ));
    }
    if door.height <= 0.0 {
        errors.push(out_of_range(
            &door.id,
            "height",
            door.height,
            "a positive height",
        ));
    }
    match arch.wall(&door.wall) {
        None => errors.push(ValidationError::UnknownDoorWall {
            door: door.id.clone(),
            wall: door.wall.clone(),
        }),
        Some(wall) => {
            let half = door.width / 2.0;
            if door.offset - half < 0.0 || door.offset + half > wall.length() {
                errors.push(out_of_range(
                    &door.id,
                    "offset",
                    door.offset,
                    "an opening that lies within its wall's length",
                ));
            }
            if let Some(leaf) = &door.leaf {
                check_leaf(door, leaf, wall.thickness, errors);
            }
        }
    }
}

/// The rooms a door joins are rooms of the house (or [`EXTERIOR`]) and two different ones.
fn check_joins(arch: &Architecture, door: &DoorOpening, errors: &mut Vec<ValidationError>) {
    let Some(joins) = &door.joins else {
        return;
    };
    let owner = format!("door `{}`", printable(&door.id));
    for room in joins.iter().filter(|r| r.as_str() != EXTERIOR) {
        if arch.room(room).is_none() {
            errors.push(ValidationError::UnknownRoom {
                owner: owner.clone(),
                field: "joins",
                room: shorten(room),
                is_exterior_ok: true,
            });
        }
    }
    if joins[0] == joins[1] {
        errors.push(ValidationError::DoorJoinsItself {
            door: printable(&door.id).into_owned(),
            room: shorten(&joins[0]),
        });
    }
}

/// `room`, named by `owner`'s `field`, is a room of the house.
fn check_room_named(
    arch: &Architecture,
    owner: &str,
    field: &'static str,
    room: &str,
    errors: &mut Vec<ValidationError>,
) {
    if arch.room(room).is_none() {
        errors.push(ValidationError::UnknownRoom {
            owner: owner.to_owned(),
            field,
            room: shorten(room),
            is_exterior_ok: false,
        });
    }
}

/// A window's numbers are finite and positive, it opens within its wall's length and height,
/// and the room it lights is a room of the house.
fn check_window(arch: &Architecture, window: &WindowOpening, errors: &mut Vec<ValidationError>) {
    let id = &window.id;
    let numbers = [window.offset, window.width, window.height, window.sill];
    if !numbers.iter().all(|v| v.is_finite()) {
        errors.push(non_finite(id, "offset/width/height/sill"));
        return;
    }
    for (field, value) in [("width", window.width), ("height", window.height)] {
        if value <= 0.0 {
            errors.push(out_of_range(id, field, value, "a positive size"));
        }
    }
    if window.sill < 0.0 {
        errors.push(out_of_range(
            id,
            "sill",
            window.sill,
            "a sill at or above the floor (>= 0)",
        ));
    }
    if let Some(room) = &window.room {
        check_room_named(
            arch,
            &format!("window `{}`", printable(id)),
            "room",
            room,
            errors,
        );
    }
    let Some(wall) = arch.wall(&window.wall) else {
        errors.push(ValidationError::UnknownWindowWall {
            window: printable(id).into_owned(),
            wall: shorten(&window.wall),
        });
        return;
    };
    let half = window.width / 2.0;
    if window.offset - half < 0.0 || window.offset + half > wall.length() {
        errors.push(out_of_range(
            id,
            "offset",
            window.offset,
            "an opening that lies within its wall's length",
        ));
    }
    if window.sill + window.height > wall.height {
        errors.push(out_of_range(
            id,
            "sill + height",
            window.sill + window.height,
            "at most its wall's height",
        ));
    }
}

/// No window overlaps a door or another window on the same wall.
fn check_overlaps(arch: &Architecture, errors: &mut Vec<ValidationError>) {
    let doors = arch
        .doors
        .iter()
        .map(|d| ("door", &d.id, &d.wall, d.offset, d.width));
    let windows = arch
        .windows
        .iter()
        .map(|w| ("window", &w.id, &w.wall, w.offset, w.width));
    let openings: Vec<_> = doors.chain(windows).collect();
    let first_window = arch.doors.len();
    for (j, b) in openings.iter().enumerate().skip(first_window) {
        for a in &openings[..j] {
            let apart = (a.3 - b.3).abs() >= (a.4 + b.4) / 2.0 - 1e-9;
            if a.2 == b.2 && !apart {
                errors.push(ValidationError::OpeningsOverlap {
                    first: format!("{} `{}`", a.0, printable(a.1)),
                    second: format!("{} `{}`", b.0, printable(b.1)),
                    wall: shorten(b.2),
                });
            }
        }
    }
}

/// A room's outline has 3 to [`MAX_ROOM_CORNERS`] corners, finite and within
/// ±[`MAX_COORDINATE`], and encloses a positive area.
fn check_room_outline(room: &RoomArea, errors: &mut Vec<ValidationError>) {
    let n = room.polygon.len();
    let problem = if !(3..=MAX_ROOM_CORNERS).contains(&n) {
        Some(format!("has {n} corners, expected 3 to {MAX_ROOM_CORNERS}"))
    } else if !room
        .polygon
        .iter()
        .all(|p| p.iter().all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE))
    {
        Some("has a corner that is not finite or lies beyond ±1000 m".to_owned())
    } else if room.area() <= 0.0 {
        Some("encloses no area".to_owned())
    } else {
        None
    };
    if let Some(problem) = problem {
        errors.push(ValidationError::BadRoomOutline {
            room: printable(&room.id).into_owned(),
            problem,
        });
    }
}

/// A door's leaf: hinged left or right, thicker than nothing and no thicker than its wall,
/// wider and taller than its gaps, its state within its limits.
fn check_leaf(
    door: &DoorOpening,
    leaf: &DoorLeaf,
    wall_thickness: f64,
    errors: &mut Vec<ValidationError>,
) {
    if !matches!(leaf.opens_to, OpensTo::Left | OpensTo::Right) {
        errors.push(ValidationError::BadLeafHinge {
            door: printable(&door.id).into_owned(),
            opens_to: leaf.opens_to,
        });
    }
    if !(leaf.thickness > 0.0 && leaf.thickness <= wall_thickness) {
        errors.push(out_of_range(
            &door.id,
            "leaf.thickness",
            leaf.thickness,
            "more than 0 and at most its wall's thickness",
        ));
    }
    if door.width <= 2.0 * LEAF_GAP || door.height <= LEAF_GAP + LEAF_FLOOR_GAP {
        errors.push(out_of_range(
            &door.id,
            "width",
            door.width.min(door.height),
            "an opening wider than 1 cm and taller than 1.5 cm, to hang its leaf in",
        ));
    }
    if !(0.0..=LEAF_OPEN_LIMIT).contains(&leaf.state) {
        errors.push(out_of_range(
            &door.id,
            "leaf.state",
            f64::from(leaf.state),
            "0 (closed) to 1.75 rad (open)",
        ));
    }
}

/// The category and the asset's generator, id and path are printable names.
fn check_object_names(object: &SceneObject, id: &str, errors: &mut Vec<ValidationError>) {
    for (field, value) in [("category", object.category.as_str())]
        .into_iter()
        .chain(match &object.asset {
            AssetRef::Procedural { generator, .. } => Some(("asset.generator", generator.as_str())),
            AssetRef::Imported { id, .. } => Some(("asset.id", id.as_str())),
        })
    {
        if !is_printable_id(value) {
            errors.push(ValidationError::UnprintableId {
                owner: format!("object `{id}`"),
                field,
                shown: shorten(value),
            });
        }
    }
    if let AssetRef::Imported { path, .. } = &object.asset {
        if path.is_empty() || path.chars().any(needs_escape) || path.len() > 4096 {
            errors.push(ValidationError::UnprintableId {
                owner: format!("object `{id}`"),
                field: "asset.path",
                shown: shorten(path),
            });
        }
    }
}

/// The pose's scale, yaw and translation are finite and within the limits.
fn check_pose(pose: &Pose, id: &str, errors: &mut Vec<ValidationError>) {
    if !pose.scale.is_finite() {
        errors.push(non_finite(id, "pose.scale"));
    } else if pose.scale <= 0.0 {
        errors.push(ValidationError::NonPositiveScale {
            id: id.to_owned(),
            scale: pose.scale,
        });
    } else if !(MIN_SCALE..=MAX_SCALE).contains(&pose.scale) {
        errors.push(out_of_range(
            id,
            "pose.scale",
            pose.scale,
            "a scale from 0.01 to 10 (limits::MIN_SCALE..=MAX_SCALE)",
        ));
    }
    if !pose.yaw.is_finite() {
        errors.push(non_finite(id, "pose.yaw"));
    } else if pose.yaw.abs() > MAX_YAW {
        errors.push(out_of_range(
            id,
            "pose.yaw",
            pose.yaw,
            "an angle within ±1000 rad (limits::MAX_YAW)",
        ));
    }
    if !pose.translation.iter().all(|v| v.is_finite()) {
        errors.push(non_finite(id, "pose.translation"));
    } else if let Some(v) = pose.translation.iter().find(|v| v.abs() > MAX_COORDINATE) {
        errors.push(out_of_range(
            id,
            "pose.translation",
            *v,
            "coordinates within ±1000 m (limits::MAX_COORDINATE)",
        ));
    }
}

/// The local bounds are finite, ordered, within ±[`MAX_OBJECT_SIZE`] of the origin and, scaled
/// by the pose, at most that large.
/// Every joint is well formed and in a state within its limits.
fn check_joints(object: &SceneObject, id: &str, errors: &mut Vec<ValidationError>) {
    for placed in &object.joints {
        if let Err(error) = placed.joint.check() {
            errors.push(ValidationError::BadJoint {
                id: id.to_owned(),
                error,
            });
        } else {
            let [lo, hi] = placed.joint.limits;
            if !(lo..=hi).contains(&placed.state) {
                errors.push(ValidationError::JointStateOutOfRange {
                    id: id.to_owned(),
                    joint: shorten(&placed.joint.name),
                    state: placed.state,
                    limits: placed.joint.limits,
                });
            }
        }
    }
}

fn check_local_bounds(object: &SceneObject, id: &str, errors: &mut Vec<ValidationError>) {
    let pose = &object.pose;
    if !bounds_finite(&object.local_bounds) {
        errors.push(non_finite(id, "local_bounds"));
    } else if !object.local_bounds.is_valid() {
        errors.push(out_of_range(
            id,
            "local_bounds",
            (object.local_bounds.max - object.local_bounds.min).min(),
            "min <= max on every axis",
        ));
    } else if let Some(v) = object
        .local_bounds
        .min
        .iter()
        .chain(object.local_bounds.max.iter())
        .find(|v| v.abs() > MAX_OBJECT_SIZE)
    {
        errors.push(out_of_range(
            id,
            "local_bounds",
            *v,
            "coordinates within ±50 m of the asset origin (limits::MAX_OBJECT_SIZE)",
        ));
    } else if (MIN_SCALE..=MAX_SCALE).contains(&pose.scale)
        && (object.local_bounds.max - object.local_bounds.min).max() * pose.scale > MAX_OBJECT_SIZE
    {
        errors.push(out_of_range(
            id,
            "pose.scale",
            pose.scale,
            "a scaled size of at most 50 m on every axis (limits::MAX_OBJECT_SIZE)",
        ));
    }
}

/// A floor, wall, door or window of an [`Architecture`] with a number that is not finite or lies beyond
/// ±[`MAX_COORDINATE`] m (see [`Architecture::out_of_bounds`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutOfBounds<'a> {
    /// What the element is: `floor`, `wall`, `door` or `window`.
    pub kind: &'static str,
    /// The element's id.
    pub id: &'a str,
    /// The fields checked together: `min/max` (floor), `start/end/height/thickness` (wall),
    /// `offset/width/height` (door) or `offset/width/height/sill` (window).
    pub fields: &'static str,
}

impl Architecture {
    /// The first element (the floor, then the walls, the doors, the windows) with a number that
    /// is not finite or lies beyond ±[`MAX_COORDINATE`] m, if any: the bounds that every reader of
    /// architecture (the exporter, whose GLB stores `f32`, and the evaluator, before parry and
    /// rapier see the room) checks through this one method. [`Scene::validate`] holds the
    /// architecture to these and the narrower wall and door limits, field by field.
    pub fn out_of_bounds(&self) -> Option<OutOfBounds<'_>> {
        let ok = |v: &f64| v.is_finite() && v.abs() <= MAX_COORDINATE;
        let floor = &self.floor;
        if !floor.min.iter().chain(floor.max.iter()).all(ok) {
            return Some(OutOfBounds {
                kind: "floor",
                id: &floor.id,
                fields: "min/max",
            });
        }
        let bad = |numbers: &[f64]| !numbers.iter().all(ok);
        let walls = (self.walls.iter())
            .filter(|w| {
                bad(&[
                    w.start.x,
                    w.start.y,
                    w.end.x,
                    w.end.y,
                    w.height,
                    w.thickness,
                ])
            })
            .map(|w| OutOfBounds {
                kind: "wall",
                id: w.id.as_str(),
                fields: "start/end/height/thickness",
            });
        let doors = (self.doors.iter())
            .filter(|d| bad(&[d.offset, d.width, d.height]))
            .map(|d| OutOfBounds {
                kind: "door",
                id: d.id.as_str(),
                fields: "offset/width/height",
            });
        let windows = (self.windows.iter())
            .filter(|w| bad(&[w.offset, w.width, w.height, w.sill]))
            .map(|w| OutOfBounds {
                kind: "window",
                id: w.id.as_str(),
                fields: "offset/width/height/sill",
            });
        walls.chain(doors).chain(windows).next()
    }
}

fn bounds_finite(b: &Aabb) -> bool {
    b.min.iter().chain(b.max.iter()).all(|v| v.is_finite())
}

/// A number as printed in messages: plain when moderate, in exponent form when huge or tiny
/// (so 1e308 does not print as 309 digits).
fn show_number(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e6 || v.abs() < 1e-6) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// `text` escaped for printing and cut to at most 80 characters.
fn shorten(text: &str) -> String {
    let p = printable(text);
    match p.char_indices().nth(80) {
        Some((cut, _)) => format!("{}…", &p[..cut]),
        None => p.into_owned(),
    }
}

fn non_finite(owner: &str, field: &'static str) -> ValidationError {
    ValidationError::NonFinite {
        owner: printable(owner).into_owned(),
        field,
    }
}

fn out_of_range(
    owner: &str,
    field: &'static str,
    value: f64,
    expected: &'static str,
) -> ValidationError {
    ValidationError::OutOfRange {
        owner: printable(owner).into_owned(),
        field,
        value,
        expected,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{object, scene_with, window};

    #[test]
    fn joints_are_checked_and_parent_links_must_name_one() {
        use crate::{Joint, JointKind, JointState, OpensTo};
        let drawer = |state: f32, limits: [f32; 2]| JointState {
            joint: Joint {
                name: "drawer_0".into(),
                kind: JointKind::Prismatic,
                axis: [0.0, 0.0, 1.0],
                anchor: [0.0, 0.3, 0.3],
                limits,
                opens_to: OpensTo::Out,
                parent: None,
            },
            state,
        };
        let mut dresser = object("dresser", ParentRef::Ground, RelationKind::OnFloor);
        dresser.joints = vec![drawer(0.1, [0.0, 0.4])];
        let mut sock = object(
            "sock",
            ParentRef::Object("dresser".into()),
            RelationKind::Inside,
        );
        sock.parent_link = Some("drawer_0".into());
        assert!(scene_with(vec![dresser.clone(), sock.clone()])
            .validate()
            .is_ok());

        sock.parent_link = Some("drawer_9".into());
        dresser.joints = vec![drawer(0.5, [0.0, 0.4])];
        let text = problems(&scene_with(vec![dresser.clone(), sock])).join("\n");
        assert!(text.contains("parent_link `drawer_9`"), "{text}");
        assert!(text.contains("joint `drawer_0` has state 0.5"), "{text}");
        dresser.joints = vec![drawer(0.0, [0.4, 0.0])];
        let text = problems(&scene_with(vec![dresser])).join("\n");
        assert!(text.contains("field `limits`"), "{text}");
    }

    fn problems(scene: &Scene) -> Vec<String> {
        scene
            .validate()
            .err()
            .unwrap_or_default()
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    #[test]
    fn huge_poses_and_scales_are_refused_with_their_field() {
        let mut far = object("sofa", ParentRef::Ground, RelationKind::OnFloor);
        far.pose.translation.x = 1e308;
        let p = problems(&scene_with(vec![far]));
        assert_eq!(p.len(), 1, "{p:?}");
        assert!(
            p[0].contains("sofa") && p[0].contains("pose.translation") && p[0].contains("1e308"),
            "{p:?}"
        );
        let mut big = object("sofa", ParentRef::Ground, RelationKind::OnFloor);
        big.pose.scale = 100.0;
        let p = problems(&scene_with(vec![big]));
        assert_eq!(p.len(), 1, "{p:?}");
        assert!(p[0].contains("pose.scale"), "{p:?}");
        let mut wide = object("rug", ParentRef::Ground, RelationKind::OnFloor);
        wide.local_bounds.max.x = 30.0;
        wide.pose.scale = 2.0;
        let p = problems(&scene_with(vec![wide]));
        assert!(p[0].contains("scaled size"), "{p:?}");
    }

    #[test]
    fn control_characters_in_ids_are_refused_and_escaped() {
        let evil = object(
            "chair\u{1b}]0;pwned\u{7}",
            ParentRef::Ground,
            RelationKind::OnFloor,
        );
        let mut spaced = object(" lamp", ParentRef::Ground, RelationKind::OnFloor);
        spaced.category = "lamp\nrm -rf".into();
        let p = problems(&scene_with(vec![evil, spaced]));
        assert_eq!(p.len(), 3, "{p:?}");
        assert!(
            p.iter().all(|m| !m.contains('\u{1b}') && !m.contains('\n')),
            "{p:?}"
        );
        assert!(p[0].contains("\\u{1b}"), "{p:?}");
        assert!(p.iter().any(|m| m.contains("field `category`")), "{p:?}");
        assert_eq!(printable("plain"), "plain");
        assert_eq!(printable("a\u{202e}b"), "a\\u{202e}b");
        assert!(is_printable_id("sofa_0") && !is_printable_id("") && !is_printable_id("a\tb"));
    }

    #[test]
    fn architecture_numbers_out_of_bounds_name_their_element() {
        let mut scene = scene_with(Vec::new());
        assert_eq!(scene.architecture.out_of_bounds(), None);
        scene.architecture.doors[0].width = f64::NAN;
        let door = scene.architecture.doors[0].id.clone();
        let bad = scene.architecture.out_of_bounds().unwrap();
        assert_eq!(
            (bad.kind, bad.id, bad.fields),
            ("door", door.as_str(), "offset/width/height")
        );
        scene.architecture.walls[1].height = 2.0 * MAX_COORDINATE;
        let bad = scene.architecture.out_of_bounds().unwrap();
        assert_eq!(
            (bad.kind, bad.fields),
            ("wall", "start/end/height/thickness")
        );
        scene.architecture.floor.min.x = -MAX_COORDINATE - 1.0;
        assert_eq!(scene.architecture.out_of_bounds().unwrap().kind, "floor");
    }

    #[test]
    fn windows_must_fit_their_wall_and_miss_the_other_openings() {
        let mut scene = scene_with(Vec::new());
        scene.architecture.windows = vec![window("window_0", "wall_0", 2.0)];
        assert!(scene.validate().is_ok(), "{:?}", problems(&scene));
        let door_offset = scene.architecture.doors[0].offset;
        let mut high = window("window_2", "wall_1", 2.0);
        high.sill = 2.0;
        let mut flat = window("window_6", "wall_1", 1.0);
        (flat.sill, flat.width) = (-0.1, 0.0);
        scene.architecture.windows = vec![
            window("window_0", "wall_9", 2.0),
            window("window_1", "wall_0", 0.3),
            high,
            window("window_3", "wall_2", door_offset + 0.5),
            window("window_4", "wall_3", 2.0),
            window("window_5", "wall_3", 2.8),
            flat,
        ];
        let text = problems(&scene).join("\n");
        for expected in [
            "window `window_0`: wall `wall_9` is not a wall",
            "window_1: field `offset` is 0.3, expected an opening that lies within its wall's length",
            "window_2: field `sill + height` is 3.2, expected at most its wall's height",
            "door `door_0` and window `window_3` overlap on wall `wall_2`",
            "window `window_4` and window `window_5` overlap on wall `wall_3`",
            "window_6: field `width` is 0, expected a positive size",
            "window_6: field `sill` is -0.1",
        ] {
            assert!(text.contains(expected), "missing {expected:?} in\n{text}");
        }
        scene.architecture.windows = vec![window("wall_0", "wall_0", 2.0)];
        let text = problems(&scene).join("\n");
        assert!(
            text.contains("id `wall_0` is used more than once (by wall and window)"),
            "{text}"
        );
        scene.architecture.windows[0].offset = f64::NAN;
        let bad = scene.architecture.out_of_bounds().unwrap();
        assert_eq!(
            (bad.kind, bad.fields),
            ("window", "offset/width/height/sill")
        );
    }

    #[test]
    fn rooms_doors_and_objects_name_known_rooms() {
        use crate::RoomArea;
        let rect =
            |id: &str, x0: f64, x1: f64| RoomArea::rectangle(id, "bedroom", [x0, -2.0], [x1, 2.0]);
        let mut sofa = object("sofa", ParentRef::Ground, RelationKind::OnFloor);
        sofa.room = Some("bedroom_1".into());
        let mut scene = scene_with(vec![sofa]);
        scene.architecture.rooms = vec![rect("bedroom_1", -3.0, 0.0), rect("hall", 0.0, 3.0)];
        scene.architecture.doors[0].joins = Some(["hall".into(), EXTERIOR.into()]);
        assert!(scene.validate().is_ok(), "{:?}", problems(&scene));

        scene.objects[0].room = Some("attic".into());
        scene.architecture.doors[0].joins = Some(["cellar".into(), EXTERIOR.into()]);
        let mut w = window("window_0", "wall_0", 2.0);
        w.room = Some("loft".into());
        scene.architecture.windows = vec![w];
        scene.architecture.rooms.push(rect("hall", 0.0, 0.0));
        let text = problems(&scene).join("\n");
        for expected in [
            "object `sofa`: field `room` names room `attic`, which is not in architecture.rooms",
            "door `door_0`: field `joins` names room `cellar`, which is not in architecture.rooms (nor `exterior`)",
            "window `window_0`: field `room` names room `loft`",
            "id `hall` is used more than once (by room and room)",
            "room `hall`: field `polygon` encloses no area",
        ] {
            assert!(text.contains(expected), "missing {expected:?} in\n{text}");
        }
        scene.architecture.doors[0].joins = Some(["hall".into(), "hall".into()]);
        let text = problems(&scene).join("\n");
        assert!(
            text.contains("door `door_0`: field `joins` names `hall` twice"),
            "{text}"
        );
    }

    #[test]
    fn counts_over_the_limits_are_one_problem() {
        let objects: Vec<_> = (0..=MAX_OBJECTS)
            .map(|k| object(&format!("o{k}"), ParentRef::Ground, RelationKind::OnFloor))
            .collect();
        let p = problems(&scene_with(objects));
        assert_eq!(p.len(), 1, "{p:?}");
        assert!(p[0].contains("limit of 2000"), "{p:?}");
    }

    #[test]
    fn unknown_generators_are_reported_by_the_caller_lookup() {
        let scene = scene_with(vec![object("a", ParentRef::Ground, RelationKind::OnFloor)]);
        assert!(scene.generator_errors(|g| g == "box").is_empty());
        let e = scene.generator_errors(|_| false);
        assert_eq!(e.len(), 1);
        assert!(e[0].to_string().contains("`box`"), "{}", e[0]);
    }
}
