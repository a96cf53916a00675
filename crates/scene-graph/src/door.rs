//! A room door's leaf: the panel hung in its opening on a vertical hinge, swinging into the
//! room. The leaf is architecture (fixed to the wall it sits in), with one revolute joint.
//!
//! `scene.json` records only what cannot be derived: the hinge side, the thickness and the
//! state ([`DoorLeaf`]). The leaf's joint and its closed box follow from the opening and its
//! wall ([`Architecture::door_leaf`]): the leaf fills the opening less [`LEAF_GAP`] at the
//! sides and top and [`LEAF_FLOOR_GAP`] at the floor, its room-side face flush with the wall's
//! room-side face, and it turns about the vertical line through the hinge edge of that face,
//! from closed (0) to [`LEAF_OPEN_LIMIT`] into the room. A double door ([`DoorLeaf::double`])
//! hangs two such leaves, each half the opening, mirrored on opposite jambs, each with its own
//! joint ([`LEAF_JOINT`], [`SECOND_LEAF_JOINT`]; [`Architecture::door_leaves`]).

use nalgebra::{Point3, Vector2};
use serde::{Deserialize, Serialize};

use crate::{
    Aabb, Architecture, DoorOpening, Joint, JointKind, JointState, Material, Mesh, MeshPart,
    OpensTo, Wall,
};

/// The name of a door leaf's joint (and of its moving link); writers name the link
/// `<door>_leaf`.
pub const LEAF_JOINT: &str = "leaf";

/// The name of the joint (and moving link) of a double door's second leaf, the mirror of the
/// first; writers name the link `<door>_leaf_2`.
pub const SECOND_LEAF_JOINT: &str = "leaf_2";

/// The thickness of the leaf a procedural room hangs in its door, in metres.
pub const LEAF_THICKNESS: f64 = 0.04;

/// How far a leaf opens into the room, radians (about 100°): past square, short of the wall.
pub const LEAF_OPEN_LIMIT: f32 = 1.75;

/// The gap between a leaf and its frame at the sides and top, in metres.
pub const LEAF_GAP: f64 = 0.005;

/// The gap between a leaf and the floor, in metres.
pub const LEAF_FLOOR_GAP: f64 = 0.01;

/// The leaf hung in a door opening (`scene.json`'s `doors[].leaf`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DoorLeaf {
    /// The hinge side, seen from inside the room facing the door: [`OpensTo::Left`] (hinged on
    /// the left edge) or [`OpensTo::Right`]. The leaf always swings into the room.
    pub opens_to: OpensTo,
    /// The leaf's thickness in metres: more than 0 and at most its wall's thickness.
    pub thickness: f64,
    /// The joint's state in radians: 0 closed, up to [`LEAF_OPEN_LIMIT`] open (both leaves of
    /// a double door).
    #[serde(default)]
    pub state: f32,
    /// A double door: two leaves, each half the opening, hinged on opposite jambs and meeting
    /// in the middle ([`Architecture::door_leaves`]); `false` (and absent from `scene.json`)
    /// for a single leaf.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub double: bool,
}

impl Default for DoorLeaf {
    fn default() -> Self {
        Self {
            opens_to: OpensTo::Left,
            thickness: LEAF_THICKNESS,
            state: 0.0,
            double: false,
        }
    }
}

/// A door leaf as the writers and the renderer need it, in world coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct LeafGeometry {
    /// The leaf's revolute joint ([`LEAF_JOINT`]) in world coordinates, with its state.
    pub joint: JointState,
    /// The closed leaf: one box part named [`LEAF_JOINT`] whose `joint` is [`LEAF_JOINT`].
    pub mesh: Mesh,
}

impl LeafGeometry {
    /// The leaf's box corners in world coordinates at its state.
    pub fn posed_mesh(&self) -> Mesh {
        let mut mesh = self.mesh.clone();
        for part in &mut mesh.parts {
            for p in &mut part.positions {
                *p = self.joint.joint.moved_point(self.joint.state, *p);
            }
        }
        mesh
    }
}

/// The material of door leaves.
pub fn leaf_material() -> Material {
    Material::new("door_leaf", [0.55, 0.38, 0.24], 0.6)
}

impl Architecture {
    /// The (first) leaf of `door` in world coordinates, or `None` when the door has no leaf
    /// or its wall is unknown: the whole leaf of a single door, the leaf hinged on its
    /// [`DoorLeaf::opens_to`] side of a double door ([`Architecture::door_leaves`]).
    ///
    /// ```
    /// use scenethesis_scene_graph::{Architecture, OpensTo};
    ///
    /// let room = Architecture::rectangular_room(4.0, 3.0, 2.5, 0.9);
    /// let door = &room.doors[0];
    /// let leaf = room.door_leaf(door).unwrap();
    /// assert_eq!(leaf.joint.joint.opens_to, OpensTo::Left);
    /// // Opened a quarter turn, the leaf stands in the room (z < 1.5, the front wall's face).
    /// let open = leaf.joint.joint.moved_point(std::f32::consts::FRAC_PI_2, [0.0, 1.0, 1.5]);
    /// assert!(open[2] < 1.5 - 0.3);
    /// ```
    pub fn door_leaf(&self, door: &DoorOpening) -> Option<LeafGeometry> {
        self.door_leaves(door).into_iter().next()
    }

    /// Every leaf hung in `door`, in world coordinates (empty when the door has no leaf or
    /// its wall is unknown): one for a single door; for a double door
    /// ([`DoorLeaf::double`]) two, each filling half the opening, the first ([`LEAF_JOINT`])
    /// hinged on the [`DoorLeaf::opens_to`] side, the second ([`SECOND_LEAF_JOINT`]) its
    /// mirror hinged on the other jamb, both at the door's state. Each joint turns about a
    /// vertical axis through the hinge edge of its leaf's room-side face, its sign chosen so
    /// that a positive state swings the leaf into the room.
    pub fn door_leaves(&self, door: &DoorOpening) -> Vec<LeafGeometry> {
        let (Some(leaf), Some(wall)) = (door.leaf.as_ref(), self.wall(&door.wall)) else {
            return Vec::new();
        };
        let a0 = door.offset - door.width / 2.0 + LEAF_GAP;
        let a1 = door.offset + door.width / 2.0 - LEAF_GAP;
        if !leaf.double {
            return vec![leaf_box(
                wall,
                door,
                leaf,
                leaf.opens_to,
                [a0, a1],
                LEAF_JOINT,
            )];
        }
        let mid = door.offset;
        // Hinged on the left seen from the room: on the wall's +u end (see `leaf_box`).
        let (own, other) = match leaf.opens_to {
            OpensTo::Right => ([a0, mid - LEAF_GAP / 2.0], [mid + LEAF_GAP / 2.0, a1]),
            _ => ([mid + LEAF_GAP / 2.0, a1], [a0, mid - LEAF_GAP / 2.0]),
        };
        let mirrored = match leaf.opens_to {
            OpensTo::Right => OpensTo::Left,
            _ => OpensTo::Right,
        };
        vec![
            leaf_box(wall, door, leaf, leaf.opens_to, own, LEAF_JOINT),
            leaf_box(wall, door, leaf, mirrored, other, SECOND_LEAF_JOINT),
        ]
    }

    /// The box the leaf of `door` sweeps through from closed to fully open, grown across the
    /// floor by the leaf's side gaps so that it holds the quarter disc of radius the opening's
    /// width about the hinge, in world coordinates (`None` without a leaf): what must stay
    /// free of furniture.
    pub fn door_swing(&self, door: &DoorOpening) -> Option<Aabb> {
        let steps = 32;
        let mut swept: Option<Aabb> = None;
        for geometry in self.door_leaves(door) {
            let joint = &geometry.joint.joint;
            for k in 0..=steps {
                let state = joint.limits[1] * k as f32 / steps as f32;
                for &p in geometry.mesh.parts.iter().flat_map(|p| &p.positions) {
                    let q = joint.moved_point(state, p).map(f64::from);
                    let q = Point3::new(q[0], q[1], q[2]);
                    swept = Some(swept.map_or(Aabb::new(q, q), |b| b.including(&q)));
                }
            }
        }
        let grow = nalgebra::Vector3::new(2.0 * LEAF_GAP, 0.0, 2.0 * LEAF_GAP);
        swept.map(|b| Aabb::new(b.min - grow, b.max + grow))
    }
}

/// The leaf of `door` in `wall` spanning `[a0, a1]` along the wall, hinged on `opens_to`'s
/// side seen from the room, its part and joint named `name`.
fn leaf_box(
    wall: &Wall,
    door: &DoorOpening,
    leaf: &DoorLeaf,
    opens_to: OpensTo,
    [a0, a1]: [f64; 2],
    name: &str,
) -> LeafGeometry {
    let u = wall.direction();
    let n = wall.inward_normal();
    let face = wall.thickness / 2.0;
    let (y0, y1) = (LEAF_FLOOR_GAP, door.height - LEAF_GAP);
    let at = |along: f64, across: f64, y: f64| -> [f32; 3] {
        let p = wall.start + u * along + n * across;
        [p.x as f32, y as f32, p.y as f32]
    };
    // Corner bits: along +u, up, toward the wall (−n): a right-handed numbering.
    let corners = std::array::from_fn(|i| {
        at(
            if i & 1 == 0 { a0 } else { a1 },
            if i & 4 == 0 {
                face
            } else {
                face - leaf.thickness
            },
            if i & 2 == 0 { y0 } else { y1 },
        )
    });
    let mut part = MeshPart::from_box_corners(name, 0, corners);
    part.joint = Some(name.to_owned());
    // Seen from the room facing the door, the viewer's right is the wall's −u.
    let (hinge, toward_free) = match opens_to {
        OpensTo::Right => (a0, u),
        _ => (a1, -u),
    };
    // A turn about +Y takes (dx, dz) to (dz, −dx).
    let turned = Vector2::new(toward_free.y, -toward_free.x);
    let up = if turned.dot(&n) > 0.0 { 1.0 } else { -1.0 };
    let joint = Joint {
        name: name.to_owned(),
        kind: JointKind::Revolute,
        axis: [0.0, up, 0.0],
        anchor: at(hinge, face, 0.0),
        limits: [0.0, LEAF_OPEN_LIMIT],
        opens_to,
        parent: None,
    };
    LeafGeometry {
        joint: JointState {
            joint,
            state: leaf.state,
        },
        mesh: Mesh {
            parts: vec![part],
            materials: vec![leaf_material()],
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;

    #[test]
    fn leaf_fills_its_opening_flush_with_the_room_face() {
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let leaf = room.door_leaf(&room.doors[0]).unwrap();
        let part = &leaf.mesh.parts[0];
        assert!(part.is_closed_and_oriented());
        assert!(part.signed_volume() > 0.0);
        let b = leaf.mesh.bounds().unwrap();
        // The front wall's centre line is z = 2.05, its room face z = 2.0: the leaf stands in
        // the opening behind that face.
        assert!(
            (b.min.z - 2.0).abs() < 1e-6 && (b.max.z - 2.04).abs() < 1e-6,
            "{b:?}"
        );
        assert!((b.min.x + 0.445).abs() < 1e-6 && (b.max.x - 0.445).abs() < 1e-6);
        assert!((b.min.y - 0.01).abs() < 1e-6 && (b.max.y - 2.095).abs() < 1e-6);
        // Hinged on the left seen from the room (facing +z): the +x edge, on the room face.
        let j = &leaf.joint.joint;
        assert_eq!(j.anchor, [0.445, 0.0, 2.0]);
        assert_eq!(
            (j.kind, j.limits),
            (JointKind::Revolute, [0.0, LEAF_OPEN_LIMIT])
        );
        assert!(j.check().is_ok());
    }

    #[test]
    fn both_hinge_sides_swing_into_the_room() {
        let mut room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        for side in [OpensTo::Left, OpensTo::Right] {
            room.doors[0].leaf.as_mut().unwrap().opens_to = side;
            let leaf = room.door_leaf(&room.doors[0]).unwrap();
            let j = &leaf.joint.joint;
            for k in 0..=35 {
                let state = LEAF_OPEN_LIMIT * k as f32 / 35.0;
                for &p in &leaf.mesh.parts[0].positions {
                    let q = j.moved_point(state, p);
                    // Never out of the room, never into the jambs (the opening is 0.9 wide).
                    assert!(
                        q[2] <= 2.04 + 1e-5,
                        "{side:?} at {state}: {q:?} leaves the room"
                    );
                    if q[2] > 2.0 + 1e-5 {
                        assert!(q[0].abs() <= 0.45, "{side:?} at {state}: {q:?} in the jamb");
                    }
                    if state >= std::f32::consts::FRAC_PI_2 {
                        assert!(q[2] <= 2.0 + 1e-5, "{side:?} at {state}: {q:?} not open");
                    }
                }
            }
            let quarter = j.moved_point(std::f32::consts::FRAC_PI_2, [-j.anchor[0], 1.0, 2.0]);
            assert!(
                (quarter[2] - (2.0 - 0.89)).abs() < 1e-5,
                "{side:?}: {quarter:?}"
            );
            let swing = room.door_swing(&room.doors[0]).unwrap();
            // The quarter disc of radius the opening's width, and no further out than the
            // leaf's outer face (plus the gap).
            assert!(
                swing.min.z <= 2.0 - 0.9 && swing.max.z <= 2.05 + 1e-6,
                "{swing:?}"
            );
        }
    }

    #[test]
    fn scene_json_keeps_the_leaf_and_reads_doors_without_one() {
        let mut scene = Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.5, 0.9));
        scene.architecture.doors[0].leaf.as_mut().unwrap().state = 0.5;
        let json = serde_json::to_string(&scene).unwrap();
        assert!(json.contains("\"leaf\":{\"opens_to\":\"left\",\"thickness\":0.04,\"state\":0.5}"));
        let back: Scene = serde_json::from_str(&json).unwrap();
        assert_eq!(back, scene);
        // An older file: the door without `leaf` is an empty opening.
        let old = json.replace(
            ",\"leaf\":{\"opens_to\":\"left\",\"thickness\":0.04,\"state\":0.5}",
            "",
        );
        let back: Scene = serde_json::from_str(&old).unwrap();
        assert_eq!(back.architecture.doors[0].leaf, None);
        assert!(back
            .architecture
            .door_leaf(&back.architecture.doors[0])
            .is_none());
        assert!(back.validate().is_ok());
    }

    #[test]
    fn bad_leaves_are_refused_naming_the_door_and_field() {
        let mut scene = Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.5, 0.9));
        assert!(scene.validate().is_ok());
        let message = |scene: &Scene| -> String {
            let errors = scene.validate().unwrap_err();
            errors
                .iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        };
        scene.architecture.doors[0].leaf.as_mut().unwrap().thickness = 0.2;
        let m = message(&scene);
        assert!(
            m.contains("door_0") && m.contains("`leaf.thickness`"),
            "{m}"
        );
        scene.architecture.doors[0].leaf.as_mut().unwrap().thickness = 0.0;
        assert!(message(&scene).contains("`leaf.thickness`"));
        scene.architecture.doors[0].leaf = Some(DoorLeaf {
            opens_to: OpensTo::Up,
            state: 2.0,
            ..DoorLeaf::default()
        });
        let m = message(&scene);
        assert!(
            m.contains("`leaf.opens_to`") && m.contains("`leaf.state`"),
            "{m}"
        );
        scene.architecture.doors[0].leaf = Some(DoorLeaf::default());
        scene.architecture.doors[0].width = 0.005;
        let m = message(&scene);
        assert!(m.contains("door_0") && m.contains("`width`"), "{m}");
    }
    #[test]
    fn a_double_door_hangs_two_mirrored_leaves_that_both_swing_in() {
        let mut room = Architecture::rectangular_room(6.0, 4.0, 2.8, 1.6);
        room.doors[0].leaf.as_mut().unwrap().double = true;
        let leaves = room.door_leaves(&room.doors[0]);
        assert_eq!(leaves.len(), 2);
        let names: Vec<&str> = leaves.iter().map(|l| l.joint.joint.name.as_str()).collect();
        assert_eq!(names, [LEAF_JOINT, SECOND_LEAF_JOINT]);
        let (a, b) = (&leaves[0].joint.joint, &leaves[1].joint.joint);
        // Hinged on opposite jambs (x = ±0.795), opening to opposite sides.
        assert!((a.anchor[0] + b.anchor[0]).abs() < 1e-6 && a.anchor[0].abs() > 0.79);
        assert_ne!(a.opens_to, b.opens_to);
        for leaf in &leaves {
            let bounds = leaf.mesh.bounds().unwrap();
            // Each fills half the opening, less the gaps.
            assert!(
                (bounds.max.x - bounds.min.x - 0.7925).abs() < 1e-5,
                "{bounds:?}"
            );
            let j = &leaf.joint.joint;
            for &p in &leaf.mesh.parts[0].positions {
                let q = j.moved_point(std::f32::consts::FRAC_PI_2, p);
                assert!(
                    q[2] <= 2.0 + 1e-5,
                    "{} opened leaves the room: {q:?}",
                    j.name
                );
            }
        }
        // The two halves do not overlap closed, and together sweep a half-width deep box.
        let (ba, bb) = (
            leaves[0].mesh.bounds().unwrap(),
            leaves[1].mesh.bounds().unwrap(),
        );
        assert!(ba.min.x >= bb.max.x || bb.min.x >= ba.max.x);
        let swing = room.door_swing(&room.doors[0]).unwrap();
        assert!(
            swing.min.z <= 2.0 - 0.79 && swing.min.z >= 2.0 - 0.85,
            "{swing:?}"
        );
        let json = serde_json::to_string(&room.doors[0]).unwrap();
        assert!(json.contains("\"double\":true"), "{json}");
    }
}
