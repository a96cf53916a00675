//! The evaluation input: objects with world-space meshes, their support links, and the room.

use scenethesis_assets::import::{AssetResolver, ResolveError};
use scenethesis_assets::{catalog, Placement};
use scenethesis_scene_graph::{
    Aabb, Architecture, Mesh, ParentRef, Relation, RelationKind, Scene, SceneObject,
};

use crate::EvalError;

/// Height (m) above which an object standing against a wall with no object beneath it counts as
/// wall-mounted.
pub const WALL_MOUNT_MIN_BOTTOM: f64 = 0.3;

/// One movable object to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct EvalObject {
    /// Stable id (glTF node name, key in `scene.json`).
    pub id: String,
    /// Semantic category, e.g. `bookshelf`; for foreign scenes the node name without a trailing
    /// `_<number>`.
    pub category: String,
    /// The object's triangle mesh in world coordinates, one part per closed piece.
    pub mesh: Mesh,
    /// Yaw (radians about +Y) of the object's own frame; its footprint is the box of the mesh
    /// in this frame, projected on the floor.
    pub yaw: f64,
    /// The object it rests on, or `None` for the ground.
    pub parent: Option<String>,
    /// How it rests on its parent (`on-floor`, `on`, `inside`, `under`, `against-wall`), when
    /// known.
    pub support: Option<RelationKind>,
    /// Further spatial relations the scene states for it.
    pub relations: Vec<Relation>,
    /// Wall- or ceiling-mounted: fixed in the simulation and excluded from the stability rates.
    pub welded: bool,
}

impl EvalObject {
    /// An object from a scene-graph object and its asset-frame mesh (posed here).
    ///
    /// It is welded when its category is a wall or ceiling category of the built-in library, or
    /// when it stands `against-wall` on the ground with its bottom above
    /// [`WALL_MOUNT_MIN_BOTTOM`].
    pub fn from_scene_object(object: &SceneObject, asset_mesh: &Mesh) -> Self {
        Self::from_scene_object_world(object, asset_mesh.transformed(&object.pose))
    }

    /// Like [`EvalObject::from_scene_object`] with a mesh that is already in world coordinates.
    pub fn from_scene_object_world(object: &SceneObject, world_mesh: Mesh) -> Self {
        let parent = object.parent.object_id().map(str::to_owned);
        let bottom = world_mesh
            .bounds()
            .map_or(object.world_aabb().min.y, |b| b.min.y);
        let welded = is_mounted_category(&object.category)
            || (object.parent == ParentRef::Ground
                && object.support == RelationKind::AgainstWall
                && bottom > WALL_MOUNT_MIN_BOTTOM);
        Self {
            id: object.id.clone(),
            category: object.category.clone(),
            mesh: world_mesh,
            yaw: object.pose.yaw,
            parent,
            support: Some(object.support),
            relations: object.relations.clone(),
            welded,
        }
    }

    /// The world box of the mesh (a degenerate box at the origin for an empty mesh).
    pub fn aabb(&self) -> Aabb {
        self.mesh.bounds().unwrap_or_else(|| {
            let o = nalgebra::Point3::origin();
            Aabb::new(o, o)
        })
    }

    /// Whether the object stands on the ground.
    pub fn on_ground(&self) -> bool {
        self.parent.is_none()
    }
}

/// Whether the built-in library places this category on a wall or a ceiling.
pub fn is_mounted_category(category: &str) -> bool {
    catalog::category(category)
        .map(|c| matches!(c.placement, Placement::Wall | Placement::Ceiling))
        .unwrap_or(matches!(
            category,
            "painting" | "whiteboard" | "mirror" | "wall_shelf" | "pendant_lamp"
        ))
}

/// A whole scene ready for evaluation: world-space objects and the room.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EvalScene {
    /// The movable objects, in a stable order.
    pub objects: Vec<EvalObject>,
    /// Floor, walls and door openings.
    pub architecture: Architecture,
}

impl EvalScene {
    /// A scene from a scene graph, with `mesh_of` giving each object's asset-frame mesh.
    pub fn from_scene(
        scene: &Scene,
        mut mesh_of: impl FnMut(&SceneObject) -> Result<Mesh, EvalError>,
    ) -> Result<Self, EvalError> {
        let objects = scene
            .objects
            .iter()
            .map(|o| Ok(EvalObject::from_scene_object(o, &mesh_of(o)?)))
            .collect::<Result<Vec<_>, EvalError>>()?;
        Ok(Self {
            objects,
            architecture: scene.architecture.clone(),
        })
    }

    /// A scene from a scene graph whose objects all use built-in procedural assets,
    /// regenerated from their generator and seed.
    pub fn from_scene_procedural(scene: &Scene) -> Result<Self, EvalError> {
        let mut resolver = AssetResolver::new();
        Self::from_scene(scene, |o| resolve(&mut resolver, o))
    }

    /// Checks the scene against [`crate::limits`]: object and wall counts, triangles per object,
    /// finite vertex coordinates within ±[`crate::limits::MAX_COORDINATE`] m and valid triangle
    /// indices, finite room numbers. Evaluating a scene that passes does bounded work and
    /// cannot panic in the geometry libraries.
    pub fn check_limits(&self) -> Result<(), EvalError> {
        use crate::limits::{MAX_COORDINATE, MAX_OBJECTS, MAX_TRIANGLES_PER_OBJECT, MAX_WALLS};
        let over = |what: &str, reason: String| EvalError::OverLimit {
            what: scenethesis_scene_graph::printable(what).into_owned(),
            reason,
        };
        if self.objects.len() > MAX_OBJECTS {
            return Err(over(
                "scene",
                format!(
                    "{} objects, more than the limit of {MAX_OBJECTS}",
                    self.objects.len()
                ),
            ));
        }
        let arch = &self.architecture;
        if arch.walls.len() > MAX_WALLS {
            return Err(over(
                "scene",
                format!(
                    "{} walls, more than the limit of {MAX_WALLS}",
                    arch.walls.len()
                ),
            ));
        }
        let ok = |v: f64| v.is_finite() && v.abs() <= MAX_COORDINATE;
        if !arch
            .floor
            .min
            .iter()
            .chain(arch.floor.max.iter())
            .all(|&v| ok(v))
        {
            return Err(over(
                "floor",
                format!("corners must be finite and within ±{MAX_COORDINATE} m"),
            ));
        }
        for w in &arch.walls {
            let numbers = [
                w.start.x,
                w.start.y,
                w.end.x,
                w.end.y,
                w.height,
                w.thickness,
            ];
            if !numbers.iter().all(|&v| ok(v)) {
                return Err(over(
                    &format!("wall {}", w.id),
                    format!("end points, height and thickness must be finite and within ±{MAX_COORDINATE} m"),
                ));
            }
        }
        for o in &self.objects {
            let what = format!("object {}", o.id);
            if o.mesh.triangle_count() > MAX_TRIANGLES_PER_OBJECT {
                return Err(over(
                    &what,
                    format!(
                        "{} triangles, more than the limit of {MAX_TRIANGLES_PER_OBJECT}",
                        o.mesh.triangle_count()
                    ),
                ));
            }
            if !o.yaw.is_finite() {
                return Err(over(&what, "the yaw is not a finite number".into()));
            }
            for part in &o.mesh.parts {
                if let Some(v) = part.positions.iter().flatten().find(|&&v| !ok(v as f64)) {
                    return Err(over(
                        &what,
                        format!("a vertex coordinate is {v}, expected a finite number within ±{MAX_COORDINATE} m"),
                    ));
                }
                let n = part.positions.len();
                if part.triangles.iter().flatten().any(|&i| i as usize >= n) {
                    return Err(over(
                        &what,
                        format!(
                            "part {} has a triangle index beyond its {n} vertices",
                            part.name
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The object with this id.
    pub fn object(&self, id: &str) -> Option<&EvalObject> {
        self.objects.iter().find(|o| o.id == id)
    }
}

/// The asset-frame mesh of an object, regenerated from its generator and seed (procedural) or
/// imported again from its asset folder (imported; see
/// [`scenethesis_assets::import::AssetResolver`]).
pub fn procedural_mesh(object: &SceneObject) -> Result<Mesh, EvalError> {
    resolve(&mut AssetResolver::new(), object)
}

fn resolve(resolver: &mut AssetResolver, object: &SceneObject) -> Result<Mesh, EvalError> {
    resolver.mesh(&object.asset).map_err(|e| match e {
        ResolveError::UnknownGenerator { generator } => EvalError::UnknownGenerator {
            object: scenethesis_scene_graph::printable(&object.id).into_owned(),
            generator,
        },
        other => EvalError::MissingMesh {
            object: scenethesis_scene_graph::printable(&object.id).into_owned(),
            reason: other.to_string(),
        },
    })
}
