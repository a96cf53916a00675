//! Moving parts: the joints of an articulated asset (a cabinet door, a drawer, a lid) and the
//! state each one is in inside a scene.
//!
//! A joint joins a moving *link* (the mesh parts whose [`MeshPart::joint`](crate::MeshPart)
//! names it) to its parent link: the asset's body, or another joint's link. Every joint is
//! closed at state 0 and opens toward its upper limit.

use serde::{Deserialize, Serialize};

use crate::{fnv1a64_from, mix64, Aabb, Mesh, Pose, Scene};

/// The share of a joint's range that must open freely in a generated scene, and the state
/// [`OpenState::Open`] sets: every door, drawer and lid opens at least this far without hitting
/// another object or the architecture (the judge's opening clearance check).
pub const OPEN_SHARE: f32 = 0.9;

/// How a moving part moves relative to its parent link.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JointKind {
    /// Turns about an axis (a hinged door or lid); state and limits in radians.
    Revolute,
    /// Slides along an axis (a drawer); state and limits in metres.
    Prismatic,
}

/// Which way a part opens, seen from in front of its asset (the asset's +Z looking back at it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OpensTo {
    /// Swings to the viewer's left (a door hinged on its left edge).
    Left,
    /// Swings to the viewer's right (a door hinged on its right edge).
    Right,
    /// Swings up (a lid, a laptop screen, a toilet seat).
    Up,
    /// Swings down (an oven or dishwasher door hinged at its bottom).
    Down,
    /// Slides out toward the viewer (a drawer).
    Out,
}

/// One joint of an asset, in the asset's own frame (scale 1).
///
/// ```
/// use scenethesis_scene_graph::{Joint, JointKind, OpensTo};
///
/// // A 0.4 m wide door hinged on its left edge (x = -0.2, at the front z = 0.25).
/// let door = Joint {
///     name: "door_0".into(),
///     kind: JointKind::Revolute,
///     axis: [0.0, -1.0, 0.0],
///     anchor: [-0.2, 0.0, 0.25],
///     limits: [0.0, 1.9],
///     opens_to: OpensTo::Left,
///     parent: None,
/// };
/// assert!(door.check().is_ok());
/// assert_eq!(door.range(), 1.9);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    /// Name unique within the asset, e.g. `door_0`, `drawer_1`, `lid`: also the name of the
    /// moving link, which the mesh parts that move with it name.
    pub name: String,
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Unit axis in the asset frame. A revolute part turns about it by the right-hand rule and
    /// a prismatic part slides along it; a positive state opens the part either way.
    pub axis: [f32; 3],
    /// A point on the axis in the asset frame: the hinge line of a revolute joint, the closed
    /// position of a prismatic part's front centre.
    pub anchor: [f32; 3],
    /// `[lower, upper]` state range, radians or metres, with `lower ≤ 0 ≤ upper`: closed is 0.
    pub limits: [f32; 2],
    /// The side the part opens to.
    pub opens_to: OpensTo,
    /// The joint whose link carries this one (a toilet lid on its seat), or `None` for the
    /// asset's body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parent: Option<String>,
}

/// What is wrong with a joint description.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum JointError {
    /// The axis is zero or not finite.
    #[error("joint `{joint}`: field `axis` must be a finite, non-zero vector, got {axis:?}")]
    ZeroAxis {
        /// The joint's name.
        joint: String,
        /// The axis given.
        axis: [f32; 3],
    },
    /// The limits do not bracket the closed state 0, are reversed, or are not finite.
    #[error(
        "joint `{joint}`: field `limits` must be [lower, upper] with lower <= 0 <= upper and \
         lower < upper, got {limits:?}"
    )]
    BadLimits {
        /// The joint's name.
        joint: String,
        /// The limits given.
        limits: [f32; 2],
    },
    /// The anchor is not finite.
    #[error("joint `{joint}`: field `anchor` must be finite, got {anchor:?}")]
    BadAnchor {
        /// The joint's name.
        joint: String,
        /// The anchor given.
        anchor: [f32; 3],
    },
}

impl Joint {
    /// The length of the open range, `upper − lower`.
    pub fn range(&self) -> f32 {
        self.limits[1] - self.limits[0]
    }

    /// The state this joint is in when fully open: its upper limit.
    pub fn open_state(&self) -> f32 {
        self.limits[1]
    }

    /// Checks the axis (finite, non-zero), anchor (finite) and limits (finite, ordered, closed
    /// state inside).
    pub fn check(&self) -> Result<(), JointError> {
        let norm2: f32 = self.axis.iter().map(|a| a * a).sum();
        if !norm2.is_finite() || norm2 < 1e-12 {
            return Err(JointError::ZeroAxis {
                joint: self.name.clone(),
                axis: self.axis,
            });
        }
        if !self.anchor.iter().all(|a| a.is_finite()) {
            return Err(JointError::BadAnchor {
                joint: self.name.clone(),
                anchor: self.anchor,
            });
        }
        let [lo, hi] = self.limits;
        if !(lo.is_finite() && hi.is_finite() && lo <= 0.0 && 0.0 <= hi && lo < hi) {
            return Err(JointError::BadLimits {
                joint: self.name.clone(),
                limits: self.limits,
            });
        }
        Ok(())
    }

    /// The asset-frame transform of the moving link at `state` (clamped to the limits), as a
    /// map of asset-frame points: a rotation about the hinge line, or a slide along the axis.
    /// Only this joint's own motion: a nested joint's link moves by its parent's too.
    pub fn moved_point(&self, state: f32, p: [f32; 3]) -> [f32; 3] {
        let s = state.clamp(self.limits[0], self.limits[1]);
        let n: f32 = self.axis.iter().map(|a| a * a).sum::<f32>().sqrt();
        let u = self.axis.map(|a| a / n);
        match self.kind {
            JointKind::Prismatic => [p[0] + u[0] * s, p[1] + u[1] * s, p[2] + u[2] * s],
            JointKind::Revolute => {
                let v = [
                    p[0] - self.anchor[0],
                    p[1] - self.anchor[1],
                    p[2] - self.anchor[2],
                ];
                let (sin, cos) = s.sin_cos();
                let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
                let cross = [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ];
                std::array::from_fn(|k| {
                    self.anchor[k] + v[k] * cos + cross[k] * sin + u[k] * dot * (1.0 - cos)
                })
            }
        }
    }
}

/// A joint of a placed object and the state it is in (`scene.json`'s `joints`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointState {
    /// The asset's joint.
    #[serde(flatten)]
    pub joint: Joint,
    /// The current state: 0 closed, up to the upper limit open.
    pub state: f32,
}

/// The largest turn (radians) or slide (metres) between two sampled states of a sweep.
const SWEEP_STEP: f32 = 0.1;

/// The box, in the asset frame, that the moving parts of `mesh` pass through while each joint
/// opens on its own from closed to [`OPEN_SHARE`] of its upper limit (the others closed), or
/// `None` when nothing moves. The floor space in front of a cabinet that its doors and drawers
/// need: layouts keep other objects out of it.
///
/// ```
/// use scenethesis_scene_graph::{opening_sweep, Joint, JointKind, Material, Mesh, OpensTo};
///
/// let mut m = Mesh::cuboid("drawer", Material::new("oak", [0.6, 0.4, 0.2], 0.5),
///     [-0.2, 0.1, -0.2], [0.2, 0.3, 0.2]);
/// m.parts[0].joint = Some("drawer".into());
/// let slide = Joint { name: "drawer".into(), kind: JointKind::Prismatic, axis: [0.0, 0.0, 1.0],
///     anchor: [0.0, 0.2, 0.2], limits: [0.0, 0.3], opens_to: OpensTo::Out, parent: None };
/// let swept = opening_sweep(&m, &[slide]).unwrap();
/// assert!((swept.max.z - (0.2 + 0.9 * 0.3)).abs() < 1e-6);
/// ```
pub fn opening_sweep(mesh: &Mesh, joints: &[Joint]) -> Option<Aabb> {
    let mut swept: Option<Aabb> = None;
    for joint in joints {
        let target = OPEN_SHARE * joint.limits[1];
        let steps = (target / SWEEP_STEP).ceil().max(1.0) as usize;
        let states: Vec<JointState> = (0..=steps)
            .map(|k| JointState {
                joint: joint.clone(),
                state: target * k as f32 / steps as f32,
            })
            .collect();
        for part in &mesh.parts {
            if !carried_by(part.joint.as_deref(), &joint.name, joints) {
                continue;
            }
            for state in &states {
                for &p in &part.positions {
                    let q = state.joint.moved_point(state.state, p).map(f64::from);
                    let q = nalgebra::Point3::new(q[0], q[1], q[2]);
                    swept = Some(swept.map_or(Aabb::new(q, q), |b| b.including(&q)));
                }
            }
        }
    }
    swept
}

/// Whether a part on link `link` (a [`MeshPart::joint`](crate::MeshPart)) moves with joint
/// `name` of `joints`: it is that joint's link or nested under it (a cycle is cut off).
pub fn carried_by<'a, I>(link: Option<&str>, name: &str, joints: I) -> bool
where
    I: IntoIterator<Item = &'a Joint> + Clone,
{
    let mut next = link;
    for _ in 0..=joints.clone().into_iter().count() {
        match next {
            Some(n) if n == name => return true,
            Some(n) => {
                next = joints
                    .clone()
                    .into_iter()
                    .find(|j| j.name == n)
                    .and_then(|j| j.parent.as_deref())
            }
            None => return false,
        }
    }
    false
}

/// The initial states a generated scene gives its joints (`--open-state`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OpenState {
    /// Every joint closed (state 0).
    #[default]
    Closed,
    /// Each joint at a state drawn uniformly from closed to [`OPEN_SHARE`] of its upper limit,
    /// fixed by the scene's seed, the object's id and the joint's name.
    Random,
    /// Every joint open to [`OPEN_SHARE`] of its upper limit.
    Open,
}

impl OpenState {
    /// Whether this is the default, [`OpenState::Closed`].
    pub fn is_closed(&self) -> bool {
        *self == OpenState::Closed
    }

    /// Sets the state of every joint of every object of `scene` (`seed` fixes the random ones)
    /// and moves what the moving parts carry with them (a sock in a drawer slides out with it:
    /// [`SceneObject::parent_link`](crate::SceneObject::parent_link)). The room's door leaves
    /// are set too, by their door's id and [`crate::LEAF_JOINT`].
    ///
    /// ```
    /// use scenethesis_scene_graph::{OpenState, Scene, Architecture};
    /// let mut scene = Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.5, 0.9));
    /// OpenState::Open.apply(&mut scene, 7); // the room's door leaf opens
    /// assert!(scene.objects.is_empty());
    /// assert!(scene.architecture.doors[0].leaf.as_ref().unwrap().state > 1.5);
    /// ```
    pub fn apply(self, scene: &mut Scene, seed: u64) {
        let before = crate::carry::joint_states(scene);
        for object in &mut scene.objects {
            for placed in &mut object.joints {
                placed.state = self.state(seed, &object.id, &placed.joint);
            }
        }
        let arch = &scene.architecture;
        let states: Vec<Option<f32>> = arch
            .doors
            .iter()
            .map(|door| {
                let leaf = arch.door_leaf(door)?;
                Some(self.state(seed, &door.id, &leaf.joint.joint))
            })
            .collect();
        for (door, state) in scene.architecture.doors.iter_mut().zip(states) {
            if let (Some(leaf), Some(state)) = (door.leaf.as_mut(), state) {
                leaf.state = state;
            }
        }
        crate::carry::move_contents(scene, &before);
    }

    /// The state this setting gives joint `joint` of the element `owner`.
    fn state(self, seed: u64, owner: &str, joint: &Joint) -> f32 {
        let open = OPEN_SHARE * joint.limits[1];
        match self {
            OpenState::Closed => 0.0,
            OpenState::Open => open,
            OpenState::Random => {
                let h = fnv1a64_from(mix64(seed), owner.as_bytes());
                let h = mix64(fnv1a64_from(h, joint.name.as_bytes()));
                open * ((h >> 40) as f32 / (1u64 << 24) as f32)
            }
        }
    }
}

impl std::str::FromStr for OpenState {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "closed" => Ok(OpenState::Closed),
            "random" => Ok(OpenState::Random),
            "open" => Ok(OpenState::Open),
            _ => Err(format!("expected closed, random or open, found `{s}`")),
        }
    }
}

impl JointState {
    /// The same joint and state mapped through `pose` (asset frame → world): the anchor moves,
    /// the axis turns, and a prismatic joint's limits and state scale with the object.
    pub fn posed(&self, pose: &Pose) -> JointState {
        let a = self.joint.anchor.map(f64::from);
        let anchor = pose.transform_point(&nalgebra::Point3::new(a[0], a[1], a[2]));
        let v = self.joint.axis.map(f64::from);
        let axis = pose.rotation() * nalgebra::Vector3::new(v[0], v[1], v[2]);
        let k = match self.joint.kind {
            JointKind::Prismatic => pose.scale as f32,
            JointKind::Revolute => 1.0,
        };
        JointState {
            joint: Joint {
                anchor: [anchor.x as f32, anchor.y as f32, anchor.z as f32],
                axis: [axis.x as f32, axis.y as f32, axis.z as f32],
                limits: self.joint.limits.map(|l| l * k),
                ..self.joint.clone()
            },
            state: self.state * k,
        }
    }

    /// Every joint of an asset, closed (state 0): how a newly placed object starts.
    pub fn all_closed(joints: &[Joint]) -> Vec<JointState> {
        joints
            .iter()
            .map(|joint| JointState {
                joint: joint.clone(),
                state: 0.0,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn door() -> Joint {
        Joint {
            name: "door".into(),
            kind: JointKind::Revolute,
            axis: [0.0, 1.0, 0.0],
            anchor: [1.0, 0.0, 0.0],
            limits: [0.0, std::f32::consts::FRAC_PI_2],
            opens_to: OpensTo::Right,
            parent: None,
        }
    }

    #[test]
    fn revolute_turns_about_its_hinge_and_prismatic_slides() {
        let d = door();
        let p = d.moved_point(std::f32::consts::FRAC_PI_2, [0.0, 0.5, 0.0]);
        // (−1, 0, 0) from the hinge turned +90° about +Y is (0, 0, 1).
        assert!(
            (p[0] - 1.0).abs() < 1e-6 && (p[1] - 0.5).abs() < 1e-6 && (p[2] - 1.0).abs() < 1e-6
        );
        assert_eq!(
            d.moved_point(5.0, [0.0; 3]),
            d.moved_point(d.limits[1], [0.0; 3])
        );
        let drawer = Joint {
            kind: JointKind::Prismatic,
            axis: [0.0, 0.0, 2.0],
            limits: [0.0, 0.4],
            ..door()
        };
        assert_eq!(drawer.moved_point(0.3, [1.0, 1.0, 1.0]), [1.0, 1.0, 1.3]);
    }

    #[test]
    fn bad_descriptions_name_the_field() {
        let zero = Joint {
            axis: [0.0; 3],
            ..door()
        };
        assert!(zero.check().unwrap_err().to_string().contains("`axis`"));
        let reversed = Joint {
            limits: [1.0, 0.0],
            ..door()
        };
        assert!(reversed
            .check()
            .unwrap_err()
            .to_string()
            .contains("`limits`"));
        assert!(door().check().is_ok());
    }

    #[test]
    fn scene_state_flattens_the_joint() {
        let s = JointState {
            joint: door(),
            state: 0.25,
        };
        let json = serde_json::to_string(&s).unwrap();
        assert!(json.contains("\"name\":\"door\"") && json.contains("\"state\":0.25"));
        let back: JointState = serde_json::from_str(&json).unwrap();
        assert_eq!(back, s);
    }
}
