//! What moving parts carry: when a joint's state changes, the objects resting in or on its
//! part (`parent_link`), and everything resting on those, move with it.

use std::collections::BTreeMap;

use nalgebra::{Point3, Rotation3, Vector3};

use crate::{Aabb, JointKind, JointState, Mesh, Scene, SceneObject};

/// A rigid motion a 5-DoF pose can follow: a turn about +Y by `yaw`, then a shift.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Motion {
    yaw: f64,
    shift: Vector3<f64>,
}

impl Motion {
    const NONE: Motion = Motion {
        yaw: 0.0,
        shift: Vector3::new(0.0, 0.0, 0.0),
    };

    fn rotation(&self) -> Rotation3<f64> {
        Rotation3::from_axis_angle(&Vector3::y_axis(), self.yaw)
    }

    fn point(&self, p: &Point3<f64>) -> Point3<f64> {
        self.rotation() * p + self.shift
    }

    /// `self` after `first`.
    fn after(&self, first: &Motion) -> Motion {
        Motion {
            yaw: first.yaw + self.yaw,
            shift: self.rotation() * first.shift + self.shift,
        }
    }

    /// The world motion of a joint's part going from `from` to `to`, for a joint already in
    /// world coordinates; `None` for a turn about a non-vertical axis, which a 5-DoF pose
    /// cannot follow.
    fn of_joint(world: &JointState, from: f32, to: f32) -> Option<Motion> {
        let j = &world.joint;
        let axis = Vector3::from(j.axis.map(f64::from)).try_normalize(1e-12)?;
        let delta = f64::from(to - from);
        match j.kind {
            JointKind::Prismatic => Some(Motion {
                yaw: 0.0,
                shift: axis * delta,
            }),
            JointKind::Revolute if axis.y.abs() > 0.999 => {
                let turn = Motion {
                    yaw: delta * axis.y.signum(),
                    shift: Vector3::zeros(),
                };
                let anchor = Point3::from(j.anchor.map(f64::from));
                Some(Motion {
                    shift: anchor.coords - turn.rotation() * anchor.coords,
                    ..turn
                })
            }
            JointKind::Revolute => None,
        }
    }
}

impl Scene {
    /// Sets each object's [`parent_link`](crate::SceneObject::parent_link) from where it
    /// rests: an object whose footprint centre lies inside a drawer of its parent (the parts of
    /// a prismatic joint, as `meshes` draws them closed) rests in that drawer and slides out
    /// with it; every other object rests on its parent's body. Objects behind a hinged door
    /// stand on the body's shelf, not on the door. Parents' joints must be closed.
    pub fn assign_parent_links(&mut self, meshes: &BTreeMap<String, Mesh>) {
        let links: Vec<Option<String>> = self
            .objects
            .iter()
            .map(|o| {
                let parent = self.object(o.parent.object_id()?)?;
                let mesh = meshes.get(&parent.id)?;
                let local = parent
                    .pose
                    .inverse_transform_point(&Point3::from(o.pose.translation));
                drawer_holding(parent, mesh, &local)
            })
            .collect();
        for (object, link) in self.objects.iter_mut().zip(links) {
            object.parent_link = link;
        }
    }
}

/// The prismatic joint of `parent` whose closed parts' box holds `local` (a point of the
/// parent's asset frame): within its footprint, from 1 cm below its bottom to its top.
fn drawer_holding(parent: &SceneObject, mesh: &Mesh, local: &Point3<f64>) -> Option<String> {
    parent
        .joints
        .iter()
        .filter(|j| j.joint.kind == JointKind::Prismatic)
        .find(|j| {
            let points = mesh
                .parts
                .iter()
                .filter(|p| p.joint.as_deref() == Some(j.joint.name.as_str()))
                .flat_map(|p| p.positions.iter())
                .map(|v| Point3::from(v.map(f64::from)))
                .collect::<Vec<_>>();
            Aabb::from_points(points.iter()).is_some_and(|b| {
                (b.min.x..=b.max.x).contains(&local.x)
                    && (b.min.z..=b.max.z).contains(&local.z)
                    && (b.min.y - 0.01..=b.max.y).contains(&local.y)
            })
        })
        .map(|j| j.joint.name.clone())
}

/// Every object's joint states, keyed by object id and joint name.
pub(crate) fn joint_states(scene: &Scene) -> BTreeMap<(String, String), f32> {
    scene
        .objects
        .iter()
        .flat_map(|o| {
            o.joints
                .iter()
                .map(|j| ((o.id.clone(), j.joint.name.clone()), j.state))
        })
        .collect()
}

/// Moves every object carried by a part whose state changed since `before`, parents first.
pub(crate) fn move_contents(scene: &mut Scene, before: &BTreeMap<(String, String), f32>) {
    let Ok(order) = scene.bfs_order() else {
        return;
    };
    let order: Vec<String> = order.iter().map(|o| o.id.clone()).collect();
    let mut moved: BTreeMap<String, Motion> = BTreeMap::new();
    for id in order {
        let Some(object) = scene.object(&id) else {
            continue;
        };
        let parent = object.parent.object_id().and_then(|p| scene.object(p));
        let inherited = parent
            .and_then(|p| moved.get(&p.id))
            .copied()
            .unwrap_or(Motion::NONE);
        let own = match (parent, object.parent_link.as_deref()) {
            (Some(p), Some(link)) => p
                .joints
                .iter()
                .find(|j| j.joint.name == link)
                .and_then(|j| {
                    let from = before.get(&(p.id.clone(), link.to_owned()))?;
                    Motion::of_joint(&j.posed(&p.pose), *from, j.state)
                })
                .unwrap_or(Motion::NONE),
            _ => Motion::NONE,
        };
        let total = inherited.after(&own);
        if total == Motion::NONE {
            continue;
        }
        let object = scene.object_mut(&id).expect("listed above");
        let t = total.point(&Point3::from(object.pose.translation));
        object.pose.translation = t.coords;
        object.pose.yaw = crate::wrap_yaw(object.pose.yaw + total.yaw);
        moved.insert(id, total);
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::{object, scene_with};
    use crate::{Joint, JointKind, JointState, OpenState, OpensTo, ParentRef, RelationKind};

    #[test]
    fn a_drawer_carries_its_contents_and_what_rests_on_them() {
        let mut dresser = object("dresser", ParentRef::Ground, RelationKind::OnFloor);
        dresser.pose.yaw = std::f64::consts::FRAC_PI_2; // front +Z turned to +X
        dresser.joints = vec![JointState {
            joint: Joint {
                name: "drawer".into(),
                kind: JointKind::Prismatic,
                axis: [0.0, 0.0, 1.0],
                anchor: [0.0, 0.5, 0.5],
                limits: [0.0, 0.4],
                opens_to: OpensTo::Out,
                parent: None,
            },
            state: 0.0,
        }];
        let mut tray = object(
            "tray",
            ParentRef::Object("dresser".into()),
            RelationKind::Inside,
        );
        tray.parent_link = Some("drawer".into());
        let pen = object("pen", ParentRef::Object("tray".into()), RelationKind::On);
        let still = object(
            "lamp",
            ParentRef::Object("dresser".into()),
            RelationKind::On,
        );
        let mut scene = scene_with(vec![dresser, tray, pen, still]);
        OpenState::Open.apply(&mut scene, 0);
        let x = |scene: &crate::Scene, id: &str| scene.object(id).unwrap().pose.translation.x;
        let slide = 0.9 * 0.4;
        assert!((x(&scene, "tray") - slide).abs() < 1e-6);
        assert!((x(&scene, "pen") - slide).abs() < 1e-6);
        assert_eq!(x(&scene, "lamp"), 0.0);
        // Closing again brings them back.
        OpenState::Closed.apply(&mut scene, 0);
        assert!(x(&scene, "tray").abs() < 1e-6 && x(&scene, "pen").abs() < 1e-6);
    }

    #[test]
    fn objects_in_a_drawer_get_it_as_parent_link_and_others_do_not() {
        use crate::{Material, Mesh, MeshPart};
        let mut mesh = Mesh::cuboid(
            "body",
            Material::new("oak", [0.5, 0.4, 0.3], 0.6),
            [-0.5, 0.0, -0.5],
            [0.5, 1.0, 0.5],
        );
        let mut drawer = MeshPart::cuboid("drawer", 0, [-0.4, 0.1, -0.4], [0.4, 0.4, 0.5]);
        drawer.joint = Some("drawer".into());
        mesh.parts.push(drawer);
        let mut dresser = object("dresser", ParentRef::Ground, RelationKind::OnFloor);
        dresser.joints = vec![JointState {
            joint: Joint {
                name: "drawer".into(),
                kind: JointKind::Prismatic,
                axis: [0.0, 0.0, 1.0],
                anchor: [0.0, 0.25, 0.5],
                limits: [0.0, 0.4],
                opens_to: OpensTo::Out,
                parent: None,
            },
            state: 0.0,
        }];
        dresser.pose.translation = nalgebra::Vector3::new(1.0, 0.0, 0.0);
        let mut sock = object(
            "sock",
            ParentRef::Object("dresser".into()),
            RelationKind::Inside,
        );
        sock.pose.translation = nalgebra::Vector3::new(1.1, 0.12, 0.0);
        let mut lamp = object(
            "lamp",
            ParentRef::Object("dresser".into()),
            RelationKind::On,
        );
        lamp.pose.translation = nalgebra::Vector3::new(1.0, 1.0, 0.0);
        let mut scene = scene_with(vec![dresser, sock, lamp]);
        let meshes = [("dresser".to_owned(), mesh)].into_iter().collect();
        scene.assign_parent_links(&meshes);
        assert_eq!(
            scene.object("sock").unwrap().parent_link.as_deref(),
            Some("drawer")
        );
        assert_eq!(scene.object("lamp").unwrap().parent_link, None);
        assert!(scene.validate().is_ok());
    }
}
