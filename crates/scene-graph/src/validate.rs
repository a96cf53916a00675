use std::collections::HashMap;

use crate::{Aabb, ParentRef, Scene, FORMAT_VERSION, GROUND_ID};

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
    #[error("{owner}: field `{field}` is {value}, expected {expected}")]
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
    /// An object's parent is not an object of the scene.
    #[error("object `{id}`: parent `{parent}` is not an object of this scene (nor `ground`)")]
    UnknownParent {
        /// The object id.
        id: String,
        /// The missing parent id.
        parent: String,
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
}

impl Scene {
    /// Checks every rule of a well-formed scene and returns all problems found, each naming the
    /// object or element and field at fault. Never panics, whatever the contents.
    pub fn validate(&self) -> Result<(), Vec<ValidationError>> {
        let mut errors = Vec::new();
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

    fn check_ids(&self, errors: &mut Vec<ValidationError>) {
        let arch = &self.architecture;
        let mut seen: HashMap<&str, &'static str> = HashMap::new();
        let elements = std::iter::once(("floor", arch.floor.id.as_str()))
            .chain(arch.walls.iter().map(|w| ("wall", w.id.as_str())))
            .chain(arch.doors.iter().map(|d| ("door", d.id.as_str())))
            .chain(self.objects.iter().map(|o| ("object", o.id.as_str())));
        let mut counts: HashMap<&'static str, usize> = HashMap::new();
        for (kind, id) in elements {
            let n = counts.entry(kind).or_default();
            if id.is_empty() {
                errors.push(ValidationError::EmptyId {
                    owner: format!("{kind} #{n}"),
                });
            } else if id == GROUND_ID {
                errors.push(ValidationError::ReservedId { id: id.to_owned() });
            } else if let Some(first) = seen.insert(id, kind) {
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
        let floor = &arch.floor;
        if !(floor
            .min
            .iter()
            .chain(floor.max.iter())
            .all(|v| v.is_finite()))
        {
            errors.push(non_finite(&floor.id, "min/max"));
        } else {
            let e = floor.extent();
            for (v, field) in [(e.x, "max.x - min.x"), (e.y, "max.z - min.z")] {
                if v <= 0.0 {
                    errors.push(out_of_range(&floor.id, field, v, "a positive floor size"));
                }
            }
        }
        for wall in &arch.walls {
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
                continue;
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
        for door in &arch.doors {
            if ![door.offset, door.width, door.height]
                .iter()
                .all(|v| v.is_finite())
            {
                errors.push(non_finite(&door.id, "offset/width/height"));
                continue;
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
                }
            }
        }
    }

    fn check_objects(&self, errors: &mut Vec<ValidationError>) {
        for object in &self.objects {
            let id = &object.id;
            let pose = &object.pose;
            if !pose.scale.is_finite() {
                errors.push(non_finite(id, "pose.scale"));
            } else if pose.scale <= 0.0 {
                errors.push(ValidationError::NonPositiveScale {
                    id: id.clone(),
                    scale: pose.scale,
                });
            }
            if !pose.yaw.is_finite() {
                errors.push(non_finite(id, "pose.yaw"));
            }
            if !pose.translation.iter().all(|v| v.is_finite()) {
                errors.push(non_finite(id, "pose.translation"));
            }
            if !bounds_finite(&object.local_bounds) {
                errors.push(non_finite(id, "local_bounds"));
            } else if !object.local_bounds.is_valid() {
                errors.push(out_of_range(
                    id,
                    "local_bounds",
                    (object.local_bounds.max - object.local_bounds.min).min(),
                    "min <= max on every axis",
                ));
            }
            for relation in &object.relations {
                let t = relation.target.as_str();
                let exists = t == GROUND_ID
                    || self.object(t).is_some()
                    || self.architecture.ids().any(|a| a == t);
                if !exists {
                    errors.push(ValidationError::MissingRelationTarget {
                        id: id.clone(),
                        kind: relation.kind.to_string(),
                        target: t.to_owned(),
                    });
                }
            }
        }
    }
}

fn bounds_finite(b: &Aabb) -> bool {
    b.min.iter().chain(b.max.iter()).all(|v| v.is_finite())
}

fn non_finite(owner: &str, field: &'static str) -> ValidationError {
    ValidationError::NonFinite {
        owner: owner.to_owned(),
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
        owner: owner.to_owned(),
        field,
        value,
        expected,
    }
}
