//! Articulated objects, the one split every writer reads: an object's mesh as its fixed body
//! (the parts with no joint) and one link per joint of [`SceneObject::joints`] (the parts whose
//! [`MeshPart::joint`] names it), each link's geometry in its joint frame.
//!
//! A link's frame has its origin at the joint's anchor and the asset's axes when the part is
//! closed; the link's vertices are given relative to the anchor, so rotating or sliding the
//! frame moves the part. A link sits in its parent's frame (the body's is the asset frame, a
//! parent link's is its anchor frame) at [`Link::offset`], moved by the joint's state
//! ([`Link::local_pose`]). Everything is in asset units (scale 1); writers apply the pose.
//!
//! An object without joints has no articulation, and writers take their rigid path unchanged.
//! Parts naming a joint the object does not carry stay with the body, as drawn (closed).

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use scenethesis_scene_graph::{Joint, JointKind, JointState, Mesh, MeshPart, SceneObject};

use crate::{MassProperties, DENSITY};

/// Standard gravity, m/s², as the physics formats write it.
const GRAVITY: f64 = 9.81;

/// The least dry friction of a joint in the physics formats (N·m or N): a part nothing pulls
/// on (a door on an upright hinge) still does not drift when brushed.
pub const MIN_JOINT_FRICTION: f64 = 0.05;

/// Viscous damping of every joint in the physics formats (N·m·s/rad or N·s/m): a part swung
/// open comes to rest instead of bouncing off its limit.
pub const JOINT_DAMPING: f64 = 1.0;

/// One moving link: its joint, the state from the scene, its parent and its parts.
pub(crate) struct Link<'a> {
    /// The joint that moves this link (its name is the link's name).
    pub joint: &'a Joint,
    /// The joint's state in the scene, clamped to its limits.
    pub state: f64,
    /// The parent link's index in [`Articulation::links`]; `None` for the body.
    pub parent: Option<usize>,
    /// The link's parts, vertices relative to the anchor (asset axes, closed), with the
    /// object's materials.
    pub mesh: Mesh,
}

impl Link<'_> {
    /// The joint's unit axis in the asset frame (the same in the link's and its parent's frame
    /// when closed).
    pub fn axis(&self) -> Vector3<f64> {
        Vector3::from(self.joint.axis)
            .cast::<f64>()
            .try_normalize(1e-12)
            .unwrap_or_else(Vector3::y)
    }

    /// The anchor in the asset frame.
    pub fn anchor(&self) -> Vector3<f64> {
        Vector3::from(self.joint.anchor).cast()
    }

    /// The joint's limits as `f64`.
    pub fn limits(&self) -> [f64; 2] {
        self.joint.limits.map(f64::from)
    }

    /// Whether the link has triangles to draw or collide.
    pub fn has_geometry(&self) -> bool {
        self.mesh.parts.iter().any(|p| !p.triangles.is_empty())
    }

    /// The link's motion at `state`: a rotation about the axis through its origin, or a slide
    /// along it.
    pub fn motion(&self, state: f64) -> Isometry3<f64> {
        match self.joint.kind {
            JointKind::Revolute => Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_unchecked(self.axis()), state),
            ),
            JointKind::Prismatic => Isometry3::from_parts(
                Translation3::from(self.axis() * state),
                UnitQuaternion::identity(),
            ),
        }
    }
}

/// An object's body and links.
pub(crate) struct Articulation<'a> {
    /// The parts that do not move, in the asset frame, with the object's materials.
    pub body: Mesh,
    /// One link per joint, parents before children.
    pub links: Vec<Link<'a>>,
}

impl<'a> Articulation<'a> {
    /// The split of `object`'s `mesh`, or `None` when the object has no joints.
    pub fn of(object: &'a SceneObject, mesh: &Mesh) -> Option<Self> {
        Self::of_joints(&object.joints, mesh)
    }

    /// The split of a room door's leaves: no body, one link per leaf in world coordinates
    /// (the world is their asset frame, scale 1).
    pub fn of_leaf(leaf: &'a crate::architecture::Leaf) -> Self {
        Self::of_joints(&leaf.joints, &leaf.mesh).expect("a door's leaves have their joints")
    }

    /// The split of `mesh` by `joints`, or `None` when there are none.
    fn of_joints(joints: &'a [JointState], mesh: &Mesh) -> Option<Self> {
        if joints.is_empty() {
            return None;
        }
        // Parents before children; a joint whose parent is unknown (or in a cycle) hangs on
        // the body.
        let mut order: Vec<usize> = Vec::with_capacity(joints.len());
        let mut placed = vec![false; joints.len()];
        let position = |name: &str| joints.iter().position(|j| j.joint.name == name);
        loop {
            let before = order.len();
            for (i, js) in joints.iter().enumerate() {
                let ready = match js.joint.parent.as_deref().and_then(position) {
                    Some(p) => placed[p] || p == i,
                    None => true,
                };
                if !placed[i] && ready {
                    placed[i] = true;
                    order.push(i);
                }
            }
            if order.len() == before {
                break;
            }
        }
        order.extend((0..joints.len()).filter(|&i| !placed[i]));
        let mut links: Vec<Link<'a>> = Vec::with_capacity(order.len());
        for &i in &order {
            let js = &joints[i];
            let parent = js.joint.parent.as_deref().and_then(|p| {
                links
                    .iter()
                    .position(|l| l.joint.name == p)
                    .filter(|_| p != js.joint.name)
            });
            let [lo, hi] = js.joint.limits;
            links.push(Link {
                joint: &js.joint,
                state: f64::from(js.state.clamp(lo.min(hi), hi.max(lo))),
                parent,
                mesh: Mesh {
                    parts: Vec::new(),
                    materials: mesh.materials.clone(),
                },
            });
        }
        let mut body = Mesh {
            parts: Vec::new(),
            materials: mesh.materials.clone(),
        };
        for part in &mesh.parts {
            let link = part
                .joint
                .as_deref()
                .and_then(|name| links.iter_mut().find(|l| l.joint.name == name));
            match link {
                Some(link) => {
                    let anchor = link.joint.anchor;
                    link.mesh.parts.push(MeshPart {
                        positions: part
                            .positions
                            .iter()
                            .map(|p| std::array::from_fn(|k| p[k] - anchor[k]))
                            .collect(),
                        ..part.clone()
                    });
                }
                None => body.parts.push(part.clone()),
            }
        }
        Some(Self { body, links })
    }

    /// The origin of link `i`'s parent frame in the asset frame when closed: the parent's
    /// anchor, or the asset origin for the body.
    fn parent_anchor(&self, i: usize) -> Vector3<f64> {
        self.links[i]
            .parent
            .map_or_else(Vector3::zeros, |p| self.links[p].anchor())
    }

    /// Where link `i`'s frame sits in its parent's frame when closed: its anchor minus the
    /// parent's.
    pub fn offset(&self, i: usize) -> Vector3<f64> {
        self.links[i].anchor() - self.parent_anchor(i)
    }

    /// Link `i`'s frame in its parent's frame at the scene's state.
    pub fn local_pose(&self, i: usize) -> Isometry3<f64> {
        let link = &self.links[i];
        Isometry3::from_parts(
            Translation3::from(self.offset(i)),
            UnitQuaternion::identity(),
        ) * link.motion(link.state)
    }

    /// Link `i`'s frame in the asset frame at the scene's state (its parents' motions
    /// included).
    pub fn pose(&self, i: usize) -> Isometry3<f64> {
        let local = self.local_pose(i);
        match self.links[i].parent {
            Some(p) => self.pose(p) * local,
            None => local,
        }
    }

    /// The dry friction of joint `i` (N·m for a hinge, N for a slide) that holds its link, and
    /// every link it carries, against gravity in any state at the object's `scale`: twice the
    /// largest gravity moment (a closed oven door does not fall open, a lid stays where the
    /// scene put it), and at least [`MIN_JOINT_FRICTION`]. Gravity is −Y in the asset frame
    /// whatever the yaw.
    pub fn holding_friction(&self, i: usize, scale: f64) -> f64 {
        let link = &self.links[i];
        let axis = link.axis();
        let mut mass = 0.0;
        let mut lever: f64 = 0.0;
        for (j, other) in self.links.iter().enumerate() {
            if !self.carries(i, j) {
                continue;
            }
            if let Some(props) = MassProperties::of_mesh(&other.mesh, scale, DENSITY) {
                mass += props.mass;
            }
            let shift = other.anchor() - link.anchor();
            for p in other.mesh.parts.iter().flat_map(|p| &p.positions) {
                let w = Vector3::from(*p).cast::<f64>() + shift;
                lever = lever.max((w - axis * w.dot(&axis)).norm() * scale);
            }
        }
        let across = (1.0 - axis.y * axis.y).max(0.0).sqrt();
        let moment = match link.joint.kind {
            JointKind::Revolute => mass * GRAVITY * lever * across,
            JointKind::Prismatic => mass * GRAVITY * axis.y.abs(),
        };
        (2.0 * moment).max(MIN_JOINT_FRICTION)
    }

    /// Whether link `j` is link `i` or hangs below it.
    pub fn carries(&self, i: usize, j: usize) -> bool {
        let mut at = Some(j);
        while let Some(k) = at {
            if k == i {
                return true;
            }
            at = self.links[k].parent;
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::{
        Aabb, AssetRef, JointState, Material, OpensTo, ParentRef, Pose, RelationKind,
    };

    fn joint(name: &str, kind: JointKind, anchor: [f32; 3], parent: Option<&str>) -> JointState {
        JointState {
            joint: Joint {
                name: name.into(),
                kind,
                axis: [1.0, 0.0, 0.0],
                anchor,
                limits: [0.0, 1.5],
                opens_to: OpensTo::Up,
                parent: parent.map(Into::into),
            },
            state: 0.5,
        }
    }

    #[test]
    fn parts_split_by_joint_with_children_after_parents() {
        let mut seat = MeshPart::cuboid("seat", 0, [0.0, 1.0, 0.0], [1.0, 1.1, 1.0]);
        seat.joint = Some("seat".into());
        let mut lid = MeshPart::cuboid("lid", 0, [0.0, 1.1, 0.0], [1.0, 1.2, 1.0]);
        lid.joint = Some("lid".into());
        let mut stray = MeshPart::cuboid("stray", 0, [0.0; 3], [0.1; 3]);
        stray.joint = Some("nowhere".into());
        let mesh = Mesh {
            parts: vec![
                MeshPart::cuboid("bowl", 0, [0.0; 3], [1.0; 3]),
                seat,
                lid,
                stray,
            ],
            materials: vec![Material::new("m", [1.0; 3], 0.5)],
        };
        let object = SceneObject {
            id: "toilet".into(),
            category: "toilet".into(),
            asset: AssetRef::Procedural {
                generator: "toilet".into(),
                seed: 0,
                look: None,
            },
            pose: Pose::new(1.0, 0.0, Vector3::zeros()),
            parent: ParentRef::Ground,
            support: RelationKind::OnFloor,
            relations: Vec::new(),
            local_bounds: Aabb::new([0.0; 3].into(), [1.0; 3].into()),
            // The lid is listed before the seat it hangs on.
            joints: vec![
                joint("lid", JointKind::Revolute, [0.0, 1.1, 0.0], Some("seat")),
                joint("seat", JointKind::Prismatic, [0.0, 1.0, 0.0], None),
            ],
            parent_link: None,
            room: None,
        };
        let a = Articulation::of(&object, &mesh).unwrap();
        let names: Vec<&str> = a.links.iter().map(|l| l.joint.name.as_str()).collect();
        assert_eq!(names, ["seat", "lid"]);
        assert_eq!(a.links[1].parent, Some(0));
        assert_eq!(a.body.parts.len(), 2, "bowl and the stray part");
        // The lid's vertices are relative to its anchor.
        assert_eq!(a.links[1].mesh.parts[0].positions[0], [0.0, 0.0, 0.0]);
        assert!((a.offset(1) - Vector3::new(0.0, 0.1, 0.0)).norm() < 1e-6);
        // The seat slides 0.5 along x; the lid turns 0.5 rad on top of it.
        let lid = a.pose(1);
        assert!((lid.translation.vector - Vector3::new(0.5, 1.1, 0.0)).norm() < 1e-6);
        assert!((lid.rotation.angle() - 0.5).abs() < 1e-9);
        assert!(a.carries(0, 1) && !a.carries(1, 0));
        // A rigid object has no articulation.
        let rigid = SceneObject {
            joints: Vec::new(),
            ..object
        };
        assert!(Articulation::of(&rigid, &mesh).is_none());
    }
}
