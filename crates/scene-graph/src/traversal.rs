use std::collections::{HashMap, VecDeque};

use crate::{ParentRef, Scene, SceneObject, ValidationError};

impl Scene {
    /// The objects in breadth-first order from the ground: the anchor first, then the other
    /// ground objects and the objects mounted on walls (walls stand on the ground) in stored
    /// order, then their children level by level, so that every parent comes before its
    /// children. Fails on an unknown parent or a parent cycle (objects that
    /// cannot be reached from the ground).
    pub fn bfs_order(&self) -> Result<Vec<&SceneObject>, ValidationError> {
        if let Some(err) = self.parent_link_errors().into_iter().next() {
            return Err(err);
        }
        let mut children: HashMap<&str, Vec<&SceneObject>> = HashMap::new();
        let mut roots: Vec<&SceneObject> = Vec::new();
        for object in &self.objects {
            match &object.parent {
                ParentRef::Ground | ParentRef::Wall(_) => roots.push(object),
                ParentRef::Object(p) => children.entry(p.as_str()).or_default().push(object),
            }
        }
        if let Some(anchor) = self.anchor.as_deref() {
            if let Some(pos) = roots.iter().position(|o| o.id == anchor) {
                let a = roots.remove(pos);
                roots.insert(0, a);
            }
        }
        let mut order = Vec::with_capacity(self.objects.len());
        let mut queue: VecDeque<&SceneObject> = roots.into();
        while let Some(object) = queue.pop_front() {
            order.push(object);
            if let Some(kids) = children.remove(object.id.as_str()) {
                queue.extend(kids);
            }
        }
        Ok(order)
    }

    /// Problems with parent links: parents that are not objects, and cycles of parents.
    pub(crate) fn parent_link_errors(&self) -> Vec<ValidationError> {
        let index: HashMap<&str, &SceneObject> =
            self.objects.iter().map(|o| (o.id.as_str(), o)).collect();
        let mut errors = Vec::new();
        let mut reported_cycles: Vec<Vec<String>> = Vec::new();
        for object in &self.objects {
            let mut path: Vec<&str> = vec![object.id.as_str()];
            let mut current = object;
            while let Some(parent_id) = current.parent.object_id() {
                let Some(parent) = index.get(parent_id) else {
                    if current.id == object.id {
                        errors.push(ValidationError::UnknownParent {
                            id: object.id.clone(),
                            parent: parent_id.to_owned(),
                        });
                    }
                    break;
                };
                if let Some(start) = path.iter().position(|p| *p == parent_id) {
                    let mut cycle: Vec<String> =
                        path[start..].iter().map(|s| s.to_string()).collect();
                    cycle.sort();
                    if !reported_cycles.contains(&cycle) {
                        reported_cycles.push(cycle.clone());
                        errors.push(ValidationError::ParentCycle { ids: cycle });
                    }
                    break;
                }
                path.push(parent_id);
                current = parent;
            }
        }
        errors
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::{object, scene_with};
    use crate::{ParentRef, RelationKind, ValidationError};

    #[test]
    fn anchor_first_then_parents_before_children() {
        let mut scene = scene_with(vec![
            object(
                "book",
                ParentRef::Object("shelf".into()),
                RelationKind::Inside,
            ),
            object("shelf", ParentRef::Ground, RelationKind::AgainstWall),
            object("mug", ParentRef::Object("table".into()), RelationKind::On),
            object("table", ParentRef::Ground, RelationKind::OnFloor),
            object("sofa", ParentRef::Ground, RelationKind::OnFloor),
        ]);
        scene.anchor = Some("sofa".into());
        let ids: Vec<&str> = scene
            .bfs_order()
            .unwrap()
            .iter()
            .map(|o| o.id.as_str())
            .collect();
        assert_eq!(ids, ["sofa", "shelf", "table", "book", "mug"]);
    }

    #[test]
    fn cycle_is_an_error_naming_its_members() {
        let scene = scene_with(vec![
            object("a", ParentRef::Object("b".into()), RelationKind::On),
            object("b", ParentRef::Object("a".into()), RelationKind::On),
        ]);
        assert_eq!(
            scene.bfs_order().unwrap_err(),
            ValidationError::ParentCycle {
                ids: vec!["a".into(), "b".into()]
            }
        );
    }
}
