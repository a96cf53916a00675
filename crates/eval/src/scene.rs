//! The evaluation input: objects with world-space meshes, their support links, and the room.

use scenethesis_import::{AssetResolver, ResolveError};
use scenethesis_scene_graph::{
    Aabb, Architecture, JointState, Mesh, Relation, RelationKind, Scene, SceneObject,
};

use crate::EvalError;

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
    /// The object it rests on, or `None` for the ground or the wall it hangs on (both are
    /// reached from the floor).
    pub parent: Option<String>,
    /// How it rests on its parent (`on-floor`, `on`, `inside`, `under`, `against-wall`,
    /// `mounted`), when known.
    pub support: Option<RelationKind>,
    /// Further spatial relations the scene states for it.
    pub relations: Vec<Relation>,
    /// Its joints and their states in world coordinates ([`JointState::posed`]); `mesh` shows
    /// the moving parts at these states. Empty for a rigid or foreign object.
    pub joints: Vec<JointState>,
    /// The parent's joint whose moving part carries it (a drawer it lies in), if any.
    pub parent_link: Option<String>,
}

impl EvalObject {
    /// An object from a scene-graph object and its asset-frame mesh (posed here, its moving
    /// parts at their joints' states: [`Mesh::with_joint_states`]). It is welded
    /// exactly when the scene says it is fixed to the world
    /// ([`SceneObject::fixed_to_world`]: mounted on a wall).
    pub fn from_scene_object(object: &SceneObject, asset_mesh: &Mesh) -> Self {
        let world = if object.joints.is_empty() {
            asset_mesh.transformed(&object.pose)
        } else {
            asset_mesh
                .with_joint_states(&object.joints)
                .transformed(&object.pose)
        };
        Self::from_scene_object_world(object, world)
    }

    /// Like [`EvalObject::from_scene_object`] with a mesh that is already in world coordinates.
    pub fn from_scene_object_world(object: &SceneObject, world_mesh: Mesh) -> Self {
        let parent = object.parent.object_id().map(str::to_owned);
        Self {
            id: object.id.clone(),
            category: object.category.clone(),
            mesh: world_mesh,
            yaw: object.pose.yaw,
            parent,
            support: Some(object.support),
            relations: object.relations.clone(),
            joints: object
                .joints
                .iter()
                .map(|j| j.posed(&object.pose))
                .collect(),
            parent_link: object.parent_link.clone(),
        }
    }

    /// The world box of the mesh (a degenerate box at the origin for an empty mesh).
    pub fn aabb(&self) -> Aabb {
        self.mesh.bounds().unwrap_or_else(|| {
            let o = nalgebra::Point3::origin();
            Aabb::new(o, o)
        })
    }

    /// Whether the object stands on the ground or hangs on a wall (no object holds it).
    pub fn on_ground(&self) -> bool {
        self.parent.is_none()
    }

    /// Whether the object is welded in the simulation and left out of the stability rates:
    /// exactly when its support is `mounted`, the shared rule of
    /// [`RelationKind::fixes_to_world`]. An object floating without that support is simulated
    /// like any other, and falls.
    pub fn welded(&self) -> bool {
        self.support.is_some_and(|s| s.fixes_to_world())
    }
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
    /// indices, room numbers within the scene graph's bounds
    /// ([`scenethesis_scene_graph::Architecture::out_of_bounds`]). Evaluating a scene that passes does bounded work and
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
        if let Some(bad) = arch.out_of_bounds() {
            let numbers = match bad.kind {
                "floor" => "corners",
                "wall" => "end points, height and thickness",
                _ => "offset, width and height",
            };
            let what = match bad.kind {
                "floor" => "floor".to_owned(),
                kind => format!("{kind} {}", bad.id),
            };
            return Err(over(
                &what,
                format!("{numbers} must be finite and within ±{MAX_COORDINATE} m"),
            ));
        }
        let ok = |v: f64| v.is_finite() && v.abs() <= MAX_COORDINATE;
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
/// [`scenethesis_import::AssetResolver`]).
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
